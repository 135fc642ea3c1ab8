"""Every check `msynth check` runs, through vtkMSCheckModel from Python without the command: a
picture against its image sample, a voxel model (.vox read whole) against a voxel tileset, a
label model's counts, network and path by tile names, and the soft shapes a pattern synthesis
records. Each output is corrupted here once and the filter must report exactly what the test
counts itself (numpy, from the labels or pixels)."""
import os
import unittest

import numpy as np
from vtkmodules.util.numpy_support import numpy_to_vtk, vtk_to_numpy
from vtkmodules.util.vtkAlgorithm import VTKPythonAlgorithmBase
from vtkmodules.vtkCommonDataModel import vtkImageData
from vtkmodules.vtkCommonExecutionModel import vtkStreamingDemandDrivenPipeline as SDDP
from vtkmodules.vtkIOXML import vtkXMLImageDataWriter

import modelsynth
from msynth_testing import data, fresh_folder, labels_zyx, read_label_grid, run_algorithm, run_msynth
from test_connected import NETWORKS, PATHS, components, network_sides
from test_time_varying import allowed_pairs, fetch, rolling_ball


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


class Frames(VTKPythonAlgorithmBase):
    """Frames [t, z, y, x] of labels as time steps 0, 1, ... (what a file series is)."""
    def __init__(self, frames):
        VTKPythonAlgorithmBase.__init__(self, nInputPorts=0, nOutputPorts=1, outputType="vtkImageData")
        self.frames = frames

    def RequestInformation(self, request, inInfo, outInfo):
        info = outInfo.GetInformationObject(0)
        nt, nz, ny, nx = self.frames.shape
        info.Set(SDDP.WHOLE_EXTENT(), (0, nx - 1, 0, ny - 1, 0, nz - 1), 6)
        info.Set(SDDP.TIME_STEPS(), [float(t) for t in range(nt)], nt)
        info.Set(SDDP.TIME_RANGE(), [0.0, float(nt - 1)], 2)
        return 1

    def RequestData(self, request, inInfo, outInfo):
        info = outInfo.GetInformationObject(0)
        t = int(round(info.Get(SDDP.UPDATE_TIME_STEP()))) if info.Has(SDDP.UPDATE_TIME_STEP()) else 0
        nt, nz, ny, nx = self.frames.shape
        out = vtkImageData.GetData(outInfo)
        out.SetDimensions(nx, ny, nz)
        labels = numpy_to_vtk(np.ascontiguousarray(self.frames[t].ravel()), deep=1)
        labels.SetName("Label")
        out.GetPointData().SetScalars(labels)
        return 1


def time_violations(example, model, loop=False):
    """The pairs of `model` [t, z, y, x] (space and time) that `example` never shows."""
    allowed = allowed_pairs(example)
    bad = []
    nt = model.shape[0]
    for t in range(nt):
        for axis, step in ((0, (0, 0, 1)), (1, (0, 1, 0)), (2, (1, 0, 0))):
            f = model[t]
            src = f[:f.shape[0] - step[0], :f.shape[1] - step[1], :f.shape[2] - step[2]]
            dst = f[step[0]:, step[1]:, step[2]:]
            bad += [(axis, a, b) for a, b in zip(src.ravel(), dst.ravel()) if (axis, a, b) not in allowed]
        if t + 1 < nt or loop:
            bad += [(3, a, b) for a, b in zip(model[t].ravel(), model[(t + 1) % nt].ravel())
                    if (3, a, b) not in allowed]
    return bad


class CheckKindsTest(unittest.TestCase):
    def test_a_time_varying_model_every_frame(self):
        example, frames = rolling_ball()
        s = modelsynth.vtkMSTimeVaryingSynthesis()
        s.SetInputData(example)
        s.SetExampleTimeFromZ(1)
        s.SetOutputSize(6, 1, 1)
        s.SetNumberOfFrames(8)
        s.SetSeed(2)
        c = modelsynth.vtkMSCheckModel()
        c.SetInputConnection(s.GetOutputPort())
        c.AddExampleData(example)
        out, errors = run_algorithm(c, TimeVarying=1, ExampleTimeFromZ=1)
        self.assertEqual(errors, "")
        model = fetch(s, 8)
        self.assertEqual((field(out, "Valid"), field(out, "Frames"), field(out, "ExampleFrames")), (1, 8, 8))
        self.assertEqual(field(out, "PairsChecked"), 8 * 5 + 7 * 6)
        self.assertEqual(time_violations(frames[:, np.newaxis], model), [])
        # One site of one frame changed: exactly the pairs it breaks, in space and in time.
        broken = model.copy()
        broken[3, 0, 0, 2] = 2 if broken[3, 0, 0, 2] != 2 else 1
        expected = time_violations(frames[:, np.newaxis], broken)
        self.assertGreater(len(expected), 0)
        c = modelsynth.vtkMSCheckModel()
        series = Frames(broken)
        c.SetInputConnection(series.GetOutputPort())
        c.AddExampleData(example)
        out, errors = run_algorithm(c, TimeVarying=1, ExampleTimeFromZ=1, MaximumReported=50)
        self.assertEqual(errors, "")
        self.assertEqual((field(out, "Valid"), field(out, "Violations")), (0, len(expected)))
        times = out.GetFieldData().GetArray("ViolationTimes")
        self.assertTrue(set(int(times.GetValue(i)) for i in range(times.GetNumberOfTuples())) <= {2, 3})
        # The example as a series of time steps of its own gives the same verdict; with Loop the
        # last frame is followed by the first.
        c = modelsynth.vtkMSCheckModel()
        sources = [Frames(model), Frames(frames[:, np.newaxis].astype(np.int32))]  # kept alive
        c.SetInputConnection(sources[0].GetOutputPort())
        c.AddExampleConnection(sources[1].GetOutputPort())
        for loop in (0, 1):
            out, errors = run_algorithm(c, TimeVarying=1, Loop=loop)
            self.assertEqual(errors, "")
            wrong = time_violations(frames[:, np.newaxis], model, loop=bool(loop))
            self.assertEqual(field(out, "Violations"), len(wrong), loop)
        # One series feeding both the synthesis and the check (as a file series in ParaView):
        # the check asks again for the example's step the synthesis moved.
        shared = Frames(frames[:, np.newaxis].astype(np.int32))
        s = modelsynth.vtkMSTimeVaryingSynthesis()
        s.SetInputConnection(shared.GetOutputPort())
        s.SetOutputSize(16, 1, 1)
        s.SetNumberOfFrames(12)
        s.SetSeed(3)
        c = modelsynth.vtkMSCheckModel()
        c.SetInputConnection(s.GetOutputPort())
        c.AddExampleConnection(shared.GetOutputPort())
        out, errors = run_algorithm(c, TimeVarying=1)
        self.assertEqual(errors, "")
        self.assertEqual((field(out, "Valid"), field(out, "ExampleFrames")), (1, 8))
        self.assertEqual(time_violations(frames[:, np.newaxis], fetch(s, 12)), [])

    def test_msynth_check_an_animation(self):
        out = os.path.join(fresh_folder("check-kinds-animation"), "anim")
        village = data("Examples/Village.vti")
        r = run_msynth("animate", village, "--size", "8", "8", "1", "--frames", "3", "--seed", "1",
                       "--out", out)
        self.assertEqual(r.returncode, 0, r.stderr)
        first = os.path.join(out, "frame_0001.vti")
        c = run_msynth("check", village, first, "--animation")
        self.assertEqual(c.returncode, 0, c.stdout + c.stderr)
        self.assertIn("of the 3 frames", c.stdout)
        example = labels_zyx(read_label_grid(village))[:, np.newaxis]  # z slices as frames
        model = np.array([labels_zyx(read_label_grid(os.path.join(out, "frame_%04d.vti" % (t + 1))))
                          for t in range(3)])
        # A site of the middle frame changed: exactly the pairs it breaks are counted.
        image = read_label_grid(os.path.join(out, "frame_0002.vti"))
        labels = labels_zyx(image)
        labels[0, 3, 3] = 1 if labels[0, 3, 3] != 1 else 2
        model[1, 0, 3, 3] = labels[0, 3, 3]
        writer = vtkXMLImageDataWriter()
        writer.SetInputData(image)
        writer.SetFileName(os.path.join(out, "frame_0002.vti"))
        writer.Write()
        expected = len(time_violations(example, model))
        self.assertGreater(expected, 0)
        c = run_msynth("check", village, first, "--animation")
        self.assertEqual(c.returncode, 1, c.stdout + c.stderr)
        self.assertIn("inconsistent: %d of" % expected, c.stdout)
        looping = len(time_violations(example, model, loop=True))
        c = run_msynth("check", village, first, "--animation", "--loop")
        self.assertIn("inconsistent: %d of" % looping, c.stdout)
        # Frame N is frame_N.vti and model_N.vdb, from 1; a file that is no numbered frame is
        # refused in one line that names the first frame's name.
        self.assertTrue(os.path.isfile(os.path.join(out, "model_0003.vdb")))
        self.assertFalse(os.path.exists(os.path.join(out, "frame_0000.vti")))
        c = run_msynth("check", village, village, "--animation")
        self.assertEqual(c.returncode, 2, c.stdout + c.stderr)
        self.assertIn("first frame (frame_0001.vti)", c.stderr)

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
