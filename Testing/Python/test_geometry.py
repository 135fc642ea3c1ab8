"""Geometry of label grids: the voxel surface (face count recomputed here with numpy) and model
pieces placed at their sites; bad piece folders and files give errors."""
import os
import shutil
import unittest

import numpy as np
from vtkmodules.util.numpy_support import vtk_to_numpy

import modelsynth
from msynth_testing import data, labels_zyx, run_algorithm, tmp


def geometry(port, **options):
    return run_algorithm(modelsynth.vtkMSLabelGeometry(), port, **options)


def expected_faces(labels, empty=0):
    """Faces between a non-empty site and a different label or the outside, per label."""
    padded = np.pad(labels, 1, constant_values=empty)
    core = padded[1:-1, 1:-1, 1:-1]
    counts = {}
    for axis in range(3):
        for shift in (1, -1):
            neighbour = np.roll(padded, shift, axis=axis)[1:-1, 1:-1, 1:-1]
            mask = (core != empty) & (core != neighbour)
            for value, n in zip(*np.unique(core[mask], return_counts=True)):
                counts[int(value)] = counts.get(int(value), 0) + int(n)
    return counts


class GeometryTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.reader = modelsynth.vtkMSLabelGridReader()
        cls.reader.SetFileName(data("Examples/Village.vti"))
        cls.reader.Update()
        cls.labels = labels_zyx(cls.reader.GetOutput())

    def test_voxel_surface_faces(self):
        mesh, errors = geometry(self.reader.GetOutputPort())
        self.assertEqual(errors, "")
        cell_labels = vtk_to_numpy(mesh.GetCellData().GetArray("Label"))
        got = {int(v): int(n) for v, n in zip(*np.unique(cell_labels, return_counts=True))}
        self.assertEqual(got, expected_faces(self.labels))
        self.assertTrue(all(mesh.GetCell(i).GetNumberOfPoints() == 4 for i in range(mesh.GetNumberOfCells())))
        b = mesh.GetBounds()  # a 7 x 7 x 5 grid of unit voxels centred on the points
        self.assertEqual(b, (-0.5, 6.5, -0.5, 6.5, -0.5, 3.5))

    def test_pieces_are_placed_at_their_sites(self):
        folder = tmp("pieces")
        shutil.rmtree(folder, ignore_errors=True)
        os.makedirs(folder)
        # A roof piece: a pyramid in the unit cube (5 points, 4 triangles + a square base).
        with open(os.path.join(folder, "3.obj"), "w") as f:
            f.write("v -0.5 -0.5 -0.5\nv 0.5 -0.5 -0.5\nv 0.5 0.5 -0.5\nv -0.5 0.5 -0.5\nv 0 0 0.5\n"
                    "f 1 2 5\nf 2 3 5\nf 3 4 5\nf 4 1 5\nf 1 4 3 2\n")
        mesh, errors = geometry(self.reader.GetOutputPort(), PieceDirectory=folder)
        self.assertEqual(errors, "")
        cell_labels = vtk_to_numpy(mesh.GetCellData().GetArray("Label"))
        roofs = int((self.labels == 3).sum())
        self.assertEqual(int((cell_labels == 3).sum()), 5 * roofs)
        # Labels without a piece keep their voxel faces (roofs now count as empty for them).
        no_roof = np.where(self.labels == 3, 0, self.labels)
        expected = expected_faces(no_roof)
        for label in (1, 2):
            self.assertEqual(int((cell_labels == label).sum()), expected[label])
        # Apexes sit half a voxel above the roof sites (z = 3 in the village).
        points = vtk_to_numpy(mesh.GetPoints().GetData())
        self.assertAlmostEqual(points[:, 2].max(), 3.5)

    def test_bad_pieces(self):
        _, errors = geometry(self.reader.GetOutputPort(), PieceDirectory=tmp("no-such-folder"))
        self.assertIn("no such folder of pieces", errors)
        folder = tmp("bad-pieces")
        shutil.rmtree(folder, ignore_errors=True)
        os.makedirs(folder)
        with open(os.path.join(folder, "2.vtp"), "w") as f:
            f.write("<VTKFile garbage")
        _, errors = geometry(self.reader.GetOutputPort(), PieceDirectory=folder)
        self.assertIn("2.vtp", errors)
        self.assertIn("could not be read", errors)


if __name__ == "__main__":
    unittest.main()
