"""Geometry of label grids: the voxel surface (face count recomputed here with numpy) and model
pieces placed at their sites; bad piece folders and files give errors."""
import os
import shutil
import unittest

import numpy as np
from vtkmodules.vtkCommonDataModel import vtkDataObject
from vtkmodules.vtkCommonExecutionModel import vtkStreamingDemandDrivenPipeline
from vtkmodules.util.numpy_support import vtk_to_numpy

import modelsynth
from msynth_testing import ErrorObserver, data, labels_zyx, run_algorithm, tmp


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



def face_counts(mesh):
    cell_labels = vtk_to_numpy(mesh.GetCellData().GetArray("Label"))
    return {int(v): int(n) for v, n in zip(*np.unique(cell_labels, return_counts=True))}


def palette_colours(mesh, palette):
    """(the mesh's PaletteColor per cell, the palette's colour of each cell's Label)."""
    colours = vtk_to_numpy(mesh.GetCellData().GetArray("PaletteColor"))
    cell_labels = vtk_to_numpy(mesh.GetCellData().GetArray("Label"))
    return ([tuple(int(v) for v in c) for c in colours],
            [palette[int(label)] for label in cell_labels])


def update_port(algorithm, port, **request):
    """Updates output `port` alone with the given pipeline request keys; its data."""
    info = algorithm.GetOutputInformation(port)
    for key, value in request.items():
        info.Set(getattr(vtkStreamingDemandDrivenPipeline, key)(), value)
    algorithm.Update(port)
    return algorithm.GetOutputDataObject(port)


class GeometryPortTest(unittest.TestCase):
    """The solvers' second output: the model's voxel surface, so a viewer shows the model."""

    @classmethod
    def setUpClass(cls):
        cls.reader = modelsynth.vtkMSLabelGridReader()
        cls.reader.SetFileName(data("Examples/Village.vti"))

    def synthesis(self, **options):
        s = modelsynth.vtkMSDiscreteSynthesis()
        s.SetInputConnection(self.reader.GetOutputPort())
        s.SetOutputSize(14, 12, 5)
        s.SetBlockSize(7, 6, 5)
        s.SetSeed(4)
        for name, value in options.items():
            getattr(s, "Set" + name)(*(value if isinstance(value, (list, tuple)) else [value]))
        return s

    def test_model_surface(self):
        s = self.synthesis()
        errors = ErrorObserver(s)
        s.Update()
        self.assertEqual(errors.text(), "")
        mesh = s.GetGeometryOutput()
        self.assertEqual(mesh.GetCellData().GetScalars().GetName(), "Label")
        model = labels_zyx(s.GetOutput())
        self.assertEqual(face_counts(mesh), expected_faces(model))
        self.assertGreater(mesh.GetNumberOfCells(), 0)
        # Another empty label, and none at all.
        s.SetEmptyLabel(-1)
        s.Update()
        self.assertEqual(face_counts(s.GetGeometryOutput()), expected_faces(model, empty=-1))
        s.GenerateGeometryOff()
        s.Update()
        self.assertEqual(s.GetGeometryOutput().GetNumberOfCells(), 0)
        self.assertEqual(labels_zyx(s.GetOutput()).tolist(), model.tolist())

    def test_snapshots_show_decided_sites(self):
        s = self.synthesis(CatalogSnapshotsPerBlock=3)
        s.UpdateInformation()
        steps = s.GetOutputInformation(1).Get(vtkStreamingDemandDrivenPipeline.TIME_STEPS())
        self.assertGreater(len(steps), 4)
        undecided = -2**31
        for step in (1, len(steps) // 2, len(steps) - 1):
            # Asked for through the geometry port alone: it follows that port's time.
            mesh = update_port(s, 1, UPDATE_TIME_STEP=float(step))
            self.assertEqual(mesh.GetInformation().Get(vtkDataObject.DATA_TIME_STEP()), step)
            s.UpdateTimeStep(float(step))
            model = labels_zyx(s.GetOutput())
            if step < len(steps) - 1:
                self.assertIn(undecided, model)
            labels = np.where(model == undecided, 0, model)
            self.assertEqual(face_counts(mesh), expected_faces(labels), step)

    def test_pieces_put_together_are_the_whole_surface(self):
        s = self.synthesis()
        s.Update()
        whole = face_counts(s.GetGeometryOutput())
        for pieces in (2, 3, 16):
            joined = {}
            for piece in range(pieces):
                mesh = update_port(s, 1, UPDATE_PIECE_NUMBER=piece, UPDATE_NUMBER_OF_PIECES=pieces)
                for label, n in face_counts(mesh).items():
                    joined[label] = joined.get(label, 0) + n
            self.assertEqual(joined, whole, pieces)

    def test_reader_shows_the_example(self):
        for name in ("Village.vti", "Village.vox", "Village.txt"):
            reader = modelsynth.vtkMSLabelGridReader()
            reader.SetFileName(data("Examples/" + name))
            reader.Update()
            labels = labels_zyx(reader.GetOutput())
            self.assertEqual(face_counts(reader.GetGeometryOutput()), expected_faces(labels), name)
            whole = face_counts(reader.GetGeometryOutput())
            joined = {}
            for piece in range(3):
                mesh = update_port(reader, 1, UPDATE_PIECE_NUMBER=piece, UPDATE_NUMBER_OF_PIECES=3)
                for label, n in face_counts(mesh).items():
                    joined[label] = joined.get(label, 0) + n
            self.assertEqual(joined, whole, name)
        # A .vox example's palette colours its geometry (PaletteColor), read here from the file:
        # the RGBA chunk's entry i is the colour of palette index i + 1.
        with open(data("Examples/Village.vox"), "rb") as f:
            raw = f.read()
        at = raw.index(b"RGBA") + 12
        palette = {i + 1: tuple(raw[at + 4 * i:at + 4 * i + 4]) for i in range(255)}
        reader = modelsynth.vtkMSLabelGridReader()
        reader.SetFileName(data("Examples/Village.vox"))
        reader.Update()
        self.assertEqual(*palette_colours(reader.GetGeometryOutput(), palette))
        self.assertIsNone(update_port(self.reader, 1).GetCellData().GetArray("PaletteColor"))
        model = modelsynth.vtkMSDiscreteSynthesis()  # the model keeps the example's colours
        model.SetInputConnection(reader.GetOutputPort())
        model.SetOutputSize(12, 12, 5)
        model.SetBlockSize(6, 6, 5)
        model.Update()
        self.assertEqual(*palette_colours(model.GetGeometryOutput(), palette))
        # A bad file fails both outputs.
        reader = modelsynth.vtkMSLabelGridReader()
        reader.SetFileName(data("Malformed/truncated.vti"))
        errors = ErrorObserver(reader)
        reader.Update()
        self.assertIn("truncated.vti", errors.text())
        self.assertEqual(reader.GetGeometryOutput().GetNumberOfCells(), 0)
        self.assertEqual(reader.GetOutput().GetNumberOfPoints(), 0)

    def test_time_varying_frames(self):
        ball = modelsynth.vtkMSLabelGridReader()
        ball.SetFileName(data("Examples/Ball.vti"))
        s = modelsynth.vtkMSTimeVaryingSynthesis()
        s.SetInputConnection(ball.GetOutputPort())
        s.SetExampleTimeFromZ(1)
        s.SetOutputSize(24, 1, 1)
        s.SetNumberOfFrames(6)
        s.SetLoop(1)
        s.SetSeed(2)
        errors = ErrorObserver(s)
        for t in range(6):
            s.UpdateTimeStep(float(t))
            frame = labels_zyx(s.GetOutput())
            self.assertEqual(face_counts(s.GetGeometryOutput()), expected_faces(frame), t)
        self.assertEqual(errors.text(), "")


if __name__ == "__main__":
    unittest.main()
