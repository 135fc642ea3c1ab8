"""Every check `msynth check` runs, through vtkMSCheckModel from Python without the command: a
picture against its image sample, a voxel model (.vox read whole) against a voxel tileset, a
label model's counts, network and path by tile names, and the soft shapes a pattern synthesis
records. Each output is corrupted here once and the filter must report exactly what the test
counts itself (numpy, from the labels or pixels)."""
import os
import unittest

import numpy as np
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkCommonDataModel import vtkImageData

import modelsynth
from msynth_testing import data, fresh_folder, labels_zyx, run_algorithm, run_msynth
from test_connected import NETWORKS, PATHS, components, network_sides


def field(image, name):
    a = image.GetFieldData().GetAbstractArray(name)
    return None if a is None else a.GetVariantValue(0).ToDouble() if a.IsNumeric() else a.GetValue(0)


def lines(image, name):
    a = image.GetFieldData().GetAbstractArray(name)
    return [a.GetValue(i) for i in range(a.GetNumberOfValues())] if a else []


def copy(image):
    c = vtkImageData()
    c.DeepCopy(image)
    return c


class CheckKindsTest(unittest.TestCase):
    def test_a_picture_against_its_sample(self):
        s = modelsynth.vtkMSDiscreteSynthesis()
        s.SetSampleFile(data("Samples/Rooms.png"))
        _, errors = run_algorithm(s, OutputSize=(24, 24, 1), Seed=3)
        self.assertEqual(errors, "")
        picture, errors = run_algorithm(modelsynth.vtkMSPatternImage(), s.GetOutputPort())
        self.assertEqual(errors, "")
        translate = s.GetTranslate()
        options = dict(SampleFile=data("Samples/Rooms.png"), PeriodicOutput=tuple(translate[:2]),
                       MaximumReported=50)
        out, errors = run_algorithm(modelsynth.vtkMSCheckModel(), data=copy(picture), **options)
        self.assertEqual(errors, "")
        self.assertEqual((field(out, "Valid"), field(out, "Violations")), (1, 0))
        # One pixel of a colour the sample does not hold: the 3 x 3 windows holding it, 9.
        broken = copy(picture)
        rgba = vtk_to_numpy(broken.GetPointData().GetScalars())
        nx = broken.GetDimensions()[0]
        rgba[5 + nx * 7] = (1, 2, 3, 255)
        out, errors = run_algorithm(modelsynth.vtkMSCheckModel(), data=broken, **options)
        self.assertEqual(errors, "")
        self.assertEqual((field(out, "Valid"), field(out, "Violations")), (0, 9))
        self.assertEqual(len(lines(out, "Problems")), 9)
        # Labels are not a picture: one error, no verdict.
        _, errors = run_algorithm(modelsynth.vtkMSCheckModel(), data=copy(s.GetOutput()), **options)
        self.assertIn("is a picture", errors)

    def test_a_voxel_model_against_its_tileset(self):
        out = os.path.join(fresh_folder("check-kinds-vox"), "pipes")
        done = run_msynth("synthesize", data("Tilesets/Pipes.xml"), "--size", "8", "8", "6",
                          "--seed", "4", "--out", out)
        self.assertEqual(done.returncode, 0, done.stderr)
        reader = modelsynth.vtkMSLabelGridReader()
        reader.SetFileName(os.path.join(out, "model.vox"))
        reader.VoxSceneOn()
        reader.GenerateGeometryOff()
        reader.Update()
        self.assertEqual(field(reader.GetOutput(), "VoxModels"), 1)
        options = dict(VoxelModel=1, TilesetFile=data("Tilesets/Pipes.xml"))
        verdict, errors = run_algorithm(modelsynth.vtkMSCheckModel(), data=copy(reader.GetOutput()),
                                        **options)
        self.assertEqual(errors, "")
        self.assertEqual((field(verdict, "Valid"), field(verdict, "Cells")), (1, 8 * 8 * 6))
        broken = copy(reader.GetOutput())
        labels = labels_zyx(broken)
        z, y, x = np.argwhere(labels > 0)[0]
        labels[z, y, x] = 255 if labels[z, y, x] != 255 else 254
        verdict, errors = run_algorithm(modelsynth.vtkMSCheckModel(), data=broken, **options)
        self.assertEqual(errors, "")
        self.assertEqual((field(verdict, "Valid"), field(verdict, "Violations")), (0, 1))
        self.assertIn("is no image of any tile", lines(verdict, "Problems")[0])

    def test_counts_network_and_path_by_tile_names(self):
        s = modelsynth.vtkMSDiscreteSynthesis()
        model, errors = run_algorithm(s, TilesetFile=PATHS, OutputSize=(24, 24, 1), Seed=1)
        self.assertEqual(errors, "")
        network = NETWORKS[PATHS]
        sides = network_sides(PATHS, network.split(","))
        corner = [i for i, side in enumerate(network_sides(PATHS, ["corner"])) if side is not None]
        check = dict(Counts="corner:0:0", Connected=network + ":1000", Path="0,0")

        def expect(image):
            labels = labels_zyx(image)[0]
            out, errors = run_algorithm(modelsynth.vtkMSCheckModel(), data=copy(image), **check)
            self.assertEqual(errors, "")
            self.assertEqual(field(out, "CountAchieved"), np.isin(labels, corner).sum())
            self.assertEqual(field(out, "CountsKept"), int(np.isin(labels, corner).sum() == 0))
            self.assertEqual(field(out, "ConnectedComponents"), components(labels, sides))
            self.assertEqual(field(out, "PathJoined"), int(sides[labels[0, 0]] is not None))
            findings = lines(out, "Findings")
            self.assertEqual(len(findings), 3)
            self.assertTrue(findings[1].startswith("connected: " + network + " form "))
            return out, labels

        out, labels = expect(model)
        self.assertEqual(field(out, "Valid"), int(not np.isin(labels, corner).any()))
        # One network site made a site of no network label: the components counted again.
        broken = copy(model)
        flat = labels_zyx(broken)[0]
        outside = next(i for i, side in enumerate(sides) if side is None)
        y, x = np.argwhere(np.array([[sides[v] is not None for v in row] for row in flat]))[0]
        flat[y, x] = outside
        out, _ = expect(broken)
        self.assertEqual(field(out, "Valid"), 0)
        _, errors = run_algorithm(modelsynth.vtkMSCheckModel(), data=copy(model),
                                  Connected="nothing")
        self.assertIn("'nothing' is neither a label value nor a name", errors)

    def test_the_soft_shapes_come_from_the_synthesis(self):
        reader = modelsynth.vtkMSLabelGridReader()
        reader.SetFileName(data("Patterns/border.vti"))
        reader.GenerateGeometryOff()
        s = modelsynth.vtkMSPatternSynthesis()
        s.AddInputConnection(0, reader.GetOutputPort())
        model, errors = run_algorithm(s, OutputSize=(16, 16, 1), SoftFactors="4H,4V", Seed=2)
        self.assertEqual(errors, "")
        self.assertEqual(field(model, "SoftShapes"), "4H,4V")
        c = modelsynth.vtkMSCheckModel()
        c.AddExampleConnection(reader.GetOutputPort())
        out, errors = run_algorithm(c, data=copy(model))
        self.assertEqual(errors, "")
        for shape in ("4H", "4V"):
            self.assertAlmostEqual(field(out, "KL_" + shape), field(model, "KL_" + shape))


if __name__ == "__main__":
    unittest.main()
