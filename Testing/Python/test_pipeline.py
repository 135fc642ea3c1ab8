"""reader -> transition tables -> VDB writer from plain vtkmodules Python, every result checked
against an independent numpy recomputation."""
import unittest

import numpy as np
import pyopenvdb
from vtkmodules.util.numpy_support import vtk_to_numpy

import modelsynth
from msynth_testing import ErrorObserver, brute_force_transitions, data, labels_zyx, tmp


class PipelineTest(unittest.TestCase):
    def run_pipeline(self, example):
        reader = modelsynth.vtkMSLabelGridReader()
        reader.SetFileName(data(example))
        tables = modelsynth.vtkMSTransitionTables()
        tables.SetInputConnection(reader.GetOutputPort())
        tables.Update()
        return reader, tables

    def test_transitions_match_eq_3_2(self):
        for example in ("Examples/Village.vti", "Examples/Checkerboard.vti",
                        "Examples/CheckerboardCells.vti"):
            reader, tables = self.run_pipeline(example)
            labels = labels_zyx(reader.GetOutput())
            expected = brute_force_transitions(labels)
            t = tables.GetOutput(0)
            got = {}
            for r in range(t.GetNumberOfRows()):
                key = (t.GetValueByName(r, "Axis").ToInt(), t.GetValueByName(r, "From").ToInt(),
                       t.GetValueByName(r, "To").ToInt())
                got[key] = t.GetValueByName(r, "Count").ToLongLong()
            self.assertEqual(got, expected, example)
            lab = tables.GetOutput(1)
            values, counts = np.unique(labels, return_counts=True)
            self.assertEqual([lab.GetValueByName(r, "Label").ToInt() for r in range(lab.GetNumberOfRows())],
                             values.tolist())
            self.assertEqual([lab.GetValueByName(r, "Count").ToLongLong() for r in range(lab.GetNumberOfRows())],
                             counts.tolist())

    def test_infallibility_verdict(self):
        _, board = self.run_pipeline("Examples/Checkerboard.vti")
        fd = board.GetOutput(0).GetFieldData()
        self.assertEqual(fd.GetArray("Infallible").GetValue(0), 1)
        self.assertIn("Algorithm 3.1", fd.GetAbstractArray("Recommendation").GetValue(0))
        _, village = self.run_pipeline("Examples/Village.vti")
        fd = village.GetOutput(0).GetFieldData()
        self.assertEqual(fd.GetArray("Infallible").GetValue(0), 0)
        self.assertIn("no label fits", fd.GetAbstractArray("InfallibilityExplanation").GetValue(0))
        self.assertIn("block synthesis", fd.GetAbstractArray("Recommendation").GetValue(0))

    def test_infallibility_with_a_wider_region(self):
        # A 2D example the 2x2 condition cannot prove but 3x2 regions of Algorithm 3.6 can.
        from vtkmodules.vtkCommonCore import vtkIntArray
        from vtkmodules.vtkCommonDataModel import vtkImageData
        rows = [[0, 0, 0, 0, 0], [0, 0, 3, 2, 0], [0, 3, 2, 2, 0], [0, 1, 2, 3, 0], [0, 0, 0, 0, 0]]
        image = vtkImageData()
        image.SetDimensions(5, 5, 1)
        labels = vtkIntArray()
        labels.SetName("Label")
        for row in reversed(rows):  # y up: the last row written is the bottom one
            for v in row:
                labels.InsertNextValue(v)
        image.GetPointData().SetScalars(labels)
        tables = modelsynth.vtkMSTransitionTables()
        tables.SetInputData(image)
        tables.Update()
        fd = tables.GetOutput(0).GetFieldData()
        self.assertEqual(fd.GetArray("Infallible").GetValue(0), 1, fd.GetAbstractArray("InfallibilityExplanation").GetValue(0))
        self.assertEqual(fd.GetArray("InfallibilityRegion").GetTuple3(0), (3.0, 2.0, 2.0))
        self.assertIn("3x2", fd.GetAbstractArray("InfallibilityExplanation").GetValue(0))

    def test_checkerboard_alternates(self):
        _, tables = self.run_pipeline("Examples/Checkerboard.vti")
        t = tables.GetOutput(0)
        pairs = {(t.GetValueByName(r, "Axis").ToInt(), t.GetValueByName(r, "From").ToInt(),
                  t.GetValueByName(r, "To").ToInt()) for r in range(t.GetNumberOfRows())}
        self.assertEqual(pairs, {(a, b, 1 - b) for a in (0, 1) for b in (0, 1)})

    def test_vdb_round_trip_and_independent_reader(self):
        reader, _ = self.run_pipeline("Examples/Village.vti")
        path = tmp("python-village.vdb")
        writer = modelsynth.vtkMSOpenVDBWriter()
        writer.SetInputConnection(reader.GetOutputPort())
        writer.SetFileName(path)
        writer.WriteFloatLabelsOn()
        writer.AddMetadata("seed", "3")
        self.assertEqual(writer.Write(), 1)
        original = labels_zyx(reader.GetOutput())

        back = modelsynth.vtkMSOpenVDBReader()
        back.SetFileName(path)
        back.Update()
        self.assertTrue(np.array_equal(labels_zyx(back.GetOutput()), original))
        self.assertEqual(back.GetOutput().GetFieldData().GetAbstractArray("seed").GetValue(0), "3")

        # OpenVDB's own Python reader (no ModelSynth code) sees the same values in the float copy.
        grid = pyopenvdb.read(path, "Label_float")
        nx, ny, nz = reader.GetOutput().GetDimensions()
        dense = np.zeros((nx, ny, nz), dtype=np.float32)
        grid.copyToArray(dense, ijk=(0, 0, 0))
        self.assertTrue(np.array_equal(dense.transpose(2, 1, 0), original.astype(np.float32)))
        self.assertEqual(grid.activeVoxelCount(), int((original != 0).sum()))  # empty is background

    def test_text_format_reads_like_vti(self):
        # Both files were written from the same village by Utilities/make-test-data.py.
        vti, _ = self.run_pipeline("Examples/Village.vti")
        txt, tables = self.run_pipeline("Examples/Village.txt")
        self.assertTrue(np.array_equal(labels_zyx(vti.GetOutput()), labels_zyx(txt.GetOutput())))
        fd = txt.GetOutput().GetFieldData()
        names = fd.GetAbstractArray("PieceNames")
        labels = fd.GetArray("PieceLabels")
        pieces = [(labels.GetValue(i), names.GetValue(i)) for i in range(names.GetNumberOfValues())]
        self.assertEqual(pieces, [(1, "ground_tile"), (2, "wall"), (2, "window"), (3, "roof")])
        self.assertEqual(tables.GetOutput(0).GetNumberOfRows(), 22)

    def test_text_model_writer_keeps_the_objects_trailer(self):
        # reader (.txt) -> synthesis -> text writer: the original program's layout, the example's
        # <Objects> section unchanged, and the values of the model read independently here.
        reader = modelsynth.vtkMSLabelGridReader()
        reader.SetFileName(data("Examples/Village.txt"))
        synthesis = modelsynth.vtkMSDiscreteSynthesis()
        synthesis.SetInputConnection(reader.GetOutputPort())
        synthesis.SetOutputSize(9, 8, 5)
        synthesis.SetSeed(4)
        writer = modelsynth.vtkMSLabelGridWriter()
        writer.SetInputConnection(synthesis.GetOutputPort())
        path = tmp("village-model.txt")
        writer.SetFileName(path)
        errors = ErrorObserver(writer)
        self.assertEqual(writer.Write(), 1)
        self.assertEqual(errors.text(), "")
        with open(path) as f:
            text = f.read()
        with open(data("Examples/Village.txt")) as f:
            original = f.read()
        lines = text.split("\n")
        self.assertEqual(lines[2], "x, y, and z extents")
        self.assertEqual(lines[3], "9 8 5")
        self.assertEqual(lines[4], "")
        self.assertEqual(lines[5], "".join("%2d " % v for v in labels_zyx(synthesis.GetOutput())[0, :, 0]))
        self.assertTrue(text.endswith(original[original.index("<Objects>"):]))
        values = np.array([int(w) for w in "\n".join(lines[4:]).split()[:9 * 8 * 5]]).reshape(5, 9, 8)
        self.assertTrue(np.array_equal(values.transpose(0, 2, 1), labels_zyx(synthesis.GetOutput())))
        # A failed write names the file and leaves nothing.
        writer.SetFileName(tmp("no-such-folder") + "/x/model.txt")
        errors = ErrorObserver(writer)
        writer.Write()
        self.assertIn("no-such-folder/x/model.txt", errors.text())

    def test_magicavoxel_reads_like_vti(self):
        vti, _ = self.run_pipeline("Examples/Village.vti")
        vox, _ = self.run_pipeline("Examples/Village.vox")
        self.assertTrue(np.array_equal(labels_zyx(vti.GetOutput()), labels_zyx(vox.GetOutput())))
        palette = vox.GetOutput().GetFieldData().GetArray("PaletteRGBA")
        self.assertEqual((palette.GetNumberOfTuples(), palette.GetNumberOfComponents()), (256, 4))
        # Written by make-test-data.py: chunk entry i (palette index i + 1) is (37i, 91i, 53i, 255) mod 256.
        self.assertEqual(palette.GetTuple4(3), ((37 * 3) % 256, (91 * 3) % 256, (53 * 3) % 256, 255))

    def test_malformed_examples_report_errors(self):
        cases = {
            "Malformed/no-label-array.vti": "has no label array 'Label'",
            "Malformed/float-labels.vti": "labels must be integers",
            "Malformed/not-xml.vti": "not a readable VTK image data",
            "Malformed/huge-extent.vti": "too large to read",
        }
        for relative, problem in cases.items():
            reader = modelsynth.vtkMSLabelGridReader()
            errors = ErrorObserver(reader)
            reader.SetFileName(data(relative))
            reader.Update()
            self.assertIn(data(relative), errors.text(), relative)
            self.assertIn(problem, errors.text(), relative)
            self.assertEqual(reader.GetOutput().GetNumberOfPoints(), 0)


if __name__ == "__main__":
    unittest.main()
