"""Folders of model pieces (vtkMSLabelGeometry's PieceDirectory, `msynth synthesize --pieces`):
pieces found by label number and by the piece names of a `.txt` example's `<Objects>` section
(`roof.obj` for `$roof`); files that match nothing are named in one warning; an empty folder, or
one where nothing matches, is an error naming the folder."""
import os
import shutil
import subprocess
import unittest

import numpy as np
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkIOXML import vtkXMLPolyDataReader

import modelsynth
from msynth_testing import BIN, data, fresh_folder, labels_zyx, run_algorithm

MSYNTH = os.path.join(BIN, "msynth")
TIMEOUT = 300 if os.environ.get("MSYNTH_SANITIZED") else 120

# A pyramid in the unit cube: 5 points, 4 triangles and a square base (5 cells).
PYRAMID = ("v -0.5 -0.5 -0.5\nv 0.5 -0.5 -0.5\nv 0.5 0.5 -0.5\nv -0.5 0.5 -0.5\nv 0 0 0.5\n"
           "f 1 2 5\nf 2 3 5\nf 3 4 5\nf 4 1 5\nf 1 4 3 2\n")
# A single triangle (1 cell).
TRIANGLE = "v -0.5 -0.5 0\nv 0.5 -0.5 0\nv 0 0.5 0\nf 1 2 3\n"


def folder_with(name, files):
    folder = fresh_folder(name)
    for file, text in files.items():
        with open(os.path.join(folder, file), "w") as f:
            f.write(text)
    return folder


def read_example(name):
    reader = modelsynth.vtkMSLabelGridReader()
    reader.SetFileName(data(name))
    reader.Update()
    return reader


def cells_per_label(mesh):
    labels = vtk_to_numpy(mesh.GetCellData().GetArray("Label"))
    return {int(v): int(n) for v, n in zip(*np.unique(labels, return_counts=True))}


def warning_of(mesh):
    kept = mesh.GetFieldData().GetAbstractArray("PieceFolderWarning")
    return kept.GetValue(0) if kept else ""


class PieceFolderFilterTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.text = read_example("Examples/Village.txt")  # pieces: 1 ground_tile, 2 wall window, 3 roof
        cls.vti = read_example("Examples/Village.vti")
        cls.labels = labels_zyx(cls.text.GetOutput())

    def geometry(self, reader, folder):
        return run_algorithm(modelsynth.vtkMSLabelGeometry(), reader.GetOutputPort(), PieceDirectory=folder)

    def sites(self, label):
        return int((self.labels == label).sum())

    def test_pieces_by_the_example_names(self):
        folder = folder_with("pieces-names", {"roof.obj": PYRAMID, "wall.obj": TRIANGLE, "window.OBJ": TRIANGLE})
        mesh, errors = self.geometry(self.text, folder)
        self.assertEqual(errors, "")
        counts = cells_per_label(mesh)
        self.assertEqual(counts[3], 5 * self.sites(3))  # a pyramid per roof site
        self.assertEqual(counts[2], 2 * self.sites(2))  # wall and window at every wall site
        self.assertEqual(warning_of(mesh), "")

    def test_label_number_goes_first(self):
        folder = folder_with("pieces-number", {"3.obj": TRIANGLE, "roof.obj": PYRAMID})
        mesh, errors = self.geometry(self.text, folder)
        self.assertEqual(errors, "")
        self.assertEqual(cells_per_label(mesh)[3], self.sites(3))

    def test_unmatched_files_are_named_once(self):
        folder = folder_with("pieces-stray", {"roof.obj": PYRAMID, "round.obj": PYRAMID, "notes.txt": "x",
                                              "roof.mtl": "newmtl a\n"})
        mesh, errors = self.geometry(self.text, folder)
        self.assertEqual(errors, "")
        self.assertEqual(cells_per_label(mesh)[3], 5 * self.sites(3))
        warning = warning_of(mesh)
        self.assertIn("2 files match no label and no piece name", warning)
        self.assertIn("notes.txt, round.obj", warning)
        self.assertNotIn("roof.mtl", warning)  # an OBJ's material library goes with it
        self.assertIn("roof.obj", warning)  # the names expected are listed
        self.assertIn(folder, warning)

    def test_names_without_an_example_that_names_pieces(self):
        """A .vti example names no pieces: roof.obj matches nothing there."""
        folder = folder_with("pieces-vti", {"roof.obj": PYRAMID, "3.obj": PYRAMID})
        mesh, errors = self.geometry(self.vti, folder)
        self.assertEqual(errors, "")
        self.assertIn("1 file matches no label and no piece name and is not used: roof.obj", warning_of(mesh))

    def test_empty_folder_and_nothing_matching_are_errors(self):
        folder = fresh_folder("pieces-empty")
        _, errors = self.geometry(self.text, folder)
        self.assertIn("'%s': the folder of pieces is empty" % folder, errors)
        self.assertIn("<label>.vtp|.obj|.ply|.stl", errors)
        folder = folder_with("pieces-nothing", {"round.obj": PYRAMID, "readme.md": "x"})
        _, errors = self.geometry(self.text, folder)
        self.assertIn("'%s': no file is a piece (readme.md, round.obj)" % folder, errors)
        self.assertIn("ground_tile.obj, wall.obj, window.obj, roof.obj", errors)


def synthesize(example, folder, out):
    return subprocess.run([MSYNTH, "synthesize", data(example), "--size", "10", "10", "5", "--block", "10", "10", "5",
                           "--ground", "1", "--empty", "0", "--seed", "3", "--pieces", folder, "--out", out],
                          capture_output=True, text=True, timeout=TIMEOUT)


class PieceFolderCommandTest(unittest.TestCase):
    def test_pieces_named_by_the_example(self):
        folder = folder_with("cli-pieces", {"roof.obj": PYRAMID, "Roof.obj": PYRAMID})
        out = fresh_folder("cli-pieces-out")
        r = synthesize("Examples/Village.txt", folder, out)
        self.assertEqual(r.returncode, 0, r.stderr)
        warnings = [line for line in r.stderr.splitlines() if "warning" in line]
        self.assertEqual(len(warnings), 1, r.stderr)
        self.assertIn("msynth: warning: --pieces '%s': 1 file matches no label and no piece name and is not "
                      "used: Roof.obj" % folder, warnings[0])
        reader = vtkXMLPolyDataReader()
        reader.SetFileName(os.path.join(out, "mesh.vtp"))
        reader.Update()
        model = labels_zyx(read_example_vti(os.path.join(out, "labels.vti")))
        roofs = int((model == 3).sum())
        self.assertGreater(roofs, 0)
        self.assertEqual(cells_per_label(reader.GetOutput())[3], 5 * roofs)

    def test_empty_folder_fails_naming_it(self):
        folder = fresh_folder("cli-pieces-empty")
        out = os.path.join(os.path.dirname(folder), "cli-pieces-empty-out")
        shutil.rmtree(out, ignore_errors=True)
        r = synthesize("Examples/Village.txt", folder, out)
        self.assertEqual(r.returncode, 1)
        self.assertEqual(len(r.stderr.strip().splitlines()), 1, r.stderr)
        self.assertIn("'%s': the folder of pieces is empty" % folder, r.stderr)
        self.assertFalse(os.path.exists(out))


def read_example_vti(path):
    reader = modelsynth.vtkMSLabelGridReader()
    reader.SetFileName(path)
    reader.Update()
    return reader.GetOutput()


if __name__ == "__main__":
    unittest.main()
