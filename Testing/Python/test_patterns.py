"""Factor-graph pattern synthesis (Yeh et al. 2012) from Python: vtkMSPatternSynthesis with the
bundled facade exemplars, zones, fixed sites, samples as time steps, mirroring and the tile
picture. Every pattern is checked here with numpy, independently of the engine: its pairs along
x and y must occur in an exemplar, zones and fixed sites must hold, and SatisfiedSoft must count
the soft windows that occur in an exemplar."""
import unittest

import numpy as np
from vtkmodules.util.numpy_support import numpy_to_vtk, vtk_to_numpy
from vtkmodules.vtkCommonDataModel import vtkImageData
from vtkmodules.vtkCommonExecutionModel import vtkStreamingDemandDrivenPipeline
from vtkmodules.vtkIOXML import vtkXMLImageDataReader

import modelsynth
from msynth_testing import ErrorObserver, brute_force_transitions, data, labels_zyx

SKY, CORNICE, WALL, TOP, MIDDLE, SILL, DOOR_TOP, DOOR, PLINTH, COURSE = range(10)


def read(name):
    r = vtkXMLImageDataReader()
    r.SetFileName(data(name))
    r.Update()
    return r.GetOutput()


def int_image(values_yx, name):
    """A 2D vtkImageData from a [y, x] numpy array."""
    ny, nx = values_yx.shape
    image = vtkImageData()
    image.SetDimensions(nx, ny, 1)
    a = numpy_to_vtk(np.ascontiguousarray(values_yx.ravel()).astype(np.int32), deep=1)
    a.SetName(name)
    image.GetPointData().SetScalars(a)
    return image


def windows(labels_yx, h, w):
    """Every h x w window of a [y, x] array, as tuples."""
    ny, nx = labels_yx.shape
    return [tuple(labels_yx[y:y + h, x:x + w].ravel()) for y in range(ny - h + 1) for x in range(nx - w + 1)]


class PatternSynthesisTest(unittest.TestCase):
    def setUp(self):
        self.exemplars = [read("Patterns/facade-rectangular.vti"), read("Patterns/facade-l-shaped.vti")]
        self.pairs = {}
        for e in self.exemplars:
            self.pairs.update(brute_force_transitions(labels_zyx(e)))

    def synthesis(self, **options):
        s = modelsynth.vtkMSPatternSynthesis()
        for e in self.exemplars:
            s.AddExemplarData(e)
        for name, value in options.items():
            values = value if isinstance(value, (list, tuple)) else [value]
            getattr(s, "Set" + name)(*values)
        return s

    def check_pairs(self, labels):
        z = labels.reshape(1, *labels.shape)
        for (axis, a, b) in brute_force_transitions(z):
            self.assertIn((axis, a, b), self.pairs, "pair %d after %d along %s occurs in no exemplar" % (b, a, "xyz"[axis]))

    def test_samples_zones_and_fixed_sites(self):
        nx, ny = 24, 16
        zones = np.zeros((ny, nx), np.int32)
        zones[0, :] = 2                  # the plinth row
        zones[10:, 12:] = 1              # sky over the right part: an L-shaped facade
        zones[5, :] = 3                  # a string course
        fixed = np.full((ny, nx), -1, np.int32)
        fixed[1, 4] = DOOR
        s = self.synthesis(OutputSize=(nx, ny, 1), SoftFactors="4H,4V", Samples=3, BurnIn=2, Seed=3,
                           ZoneTiles="1:%d;2:%d;3:%d" % (SKY, PLINTH, COURSE))
        s.SetZonesData(int_image(zones, "Zone"))
        s.SetFixedData(int_image(fixed, "Label"))
        errors = ErrorObserver(s)
        s.UpdateInformation()
        info = s.GetOutputInformation(0)
        self.assertEqual(info.Length(vtkStreamingDemandDrivenPipeline.TIME_STEPS()), 3)
        samples = []
        for step in range(3):
            s.UpdateTimeStep(step)
            self.assertEqual(errors.text(), "")
            out = s.GetOutput()
            fd = out.GetFieldData()
            self.assertEqual(fd.GetArray("Sample").GetValue(0), step)
            labels = labels_zyx(out)[0]
            self.check_pairs(labels)
            self.assertTrue((labels[0, :] == PLINTH).all())
            self.assertTrue((labels[10:, 12:] == SKY).all())
            self.assertEqual(labels[1, 4], DOOR)
            self.assertTrue((labels[5, :] == COURSE).all())
            # SatisfiedSoft counts, per anchor, the 4H and 4V windows an exemplar shows.
            seen_h = set(w for e in self.exemplars for w in windows(labels_zyx(e)[0], 1, 4))
            seen_v = set(w for e in self.exemplars for w in windows(labels_zyx(e)[0], 4, 1))
            expected = np.zeros((ny, nx), np.int32)
            for y in range(ny):
                for x in range(nx):
                    if x + 4 <= nx and tuple(labels[y, x:x + 4]) in seen_h:
                        expected[y, x] += 1
                    if y + 4 <= ny and tuple(labels[y:y + 4, x]) in seen_v:
                        expected[y, x] += 1
            satisfied = vtk_to_numpy(out.GetPointData().GetArray("SatisfiedSoft")).reshape(ny, nx)
            np.testing.assert_array_equal(satisfied, expected)
            self.assertAlmostEqual(fd.GetArray("LogProbability").GetValue(0), expected.sum() * np.log1p(0.1))
            self.assertGreaterEqual(fd.GetArray("KL_4H").GetValue(0), 0.0)
            samples.append(labels.copy())
        self.assertFalse((samples[0] == samples[2]).all(), "samples should move on")
        moves = fd.GetArray("Moves").GetValue(0)
        self.assertGreater(moves, 0)
        # Asking for a step again does not sample again.
        s.UpdateTimeStep(0)
        self.assertEqual(s.GetOutput().GetFieldData().GetArray("Moves").GetValue(0), moves)

    def test_baselines_and_picture(self):
        # Single-site MH rarely finds a facade (§8.2); the city's dead ends make it easy.
        city = [read("Patterns/city-suburban.vti"), read("Patterns/city-urban.vti")]
        pairs = {}
        for e in city:
            pairs.update(brute_force_transitions(labels_zyx(e)))
        s = modelsynth.vtkMSPatternSynthesis()
        for e in city:
            s.AddExemplarData(e)
        s.SetOutputSize(8, 8, 1)
        s.SetMethod(modelsynth.vtkMSPatternSynthesis.METROPOLIS_HASTINGS)
        s.SetBurnIn(0)
        errors = ErrorObserver(s)
        s.Update()
        self.assertEqual(errors.text(), "")
        for key in brute_force_transitions(labels_zyx(s.GetOutput())):
            self.assertIn(key, pairs)
        s = self.synthesis(OutputSize=(10, 10, 1), Method=modelsynth.vtkMSPatternSynthesis.CONSTRAINT_SOLVER)
        errors = ErrorObserver(s)
        s.Update()
        self.assertEqual(errors.text(), "")
        self.check_pairs(labels_zyx(s.GetOutput())[0])
        picture = modelsynth.vtkMSTileImage()
        picture.SetInputConnection(s.GetOutputPort())
        picture.SetTilesetFile(data("Patterns/Facade.xml"))
        errors = ErrorObserver(picture)
        picture.Update()
        self.assertEqual(errors.text(), "")
        self.assertEqual(picture.GetOutput().GetDimensions(), (80, 80, 1))

    def test_mirror(self):
        border = read("Patterns/border.vti")
        s = modelsynth.vtkMSPatternSynthesis()
        s.AddExemplarData(border)
        s.SetOutputSize(17, 12, 1)
        s.SetSoftFactors("3x3")
        s.SetMirror(1, 0, 0)
        s.SetMirrorSwaps("3:4,5:6,7:8,10:11")
        errors = ErrorObserver(s)
        s.Update()
        self.assertEqual(errors.text(), "")
        labels = labels_zyx(s.GetOutput())[0]
        swap = {3: 4, 4: 3, 5: 6, 6: 5, 7: 8, 8: 7, 10: 11, 11: 10}
        mirrored = np.vectorize(lambda v: swap.get(v, v))(labels[:, ::-1])
        np.testing.assert_array_equal(labels, mirrored)

    def test_errors(self):
        s = modelsynth.vtkMSPatternSynthesis()
        errors = ErrorObserver(s)
        s.Update()
        self.assertIn("at least one exemplar", errors.text())
        for options, message in (({"SoftFactors": "4Q"}, "4Q"),
                                 ({"ZoneTiles": "1-2"}, "ZoneTiles"),
                                 ({"MirrorSwaps": "a:b"}, "mirror swaps"),
                                 ({"OutputSize": (8, 8, 3)}, "3D")):
            s = self.synthesis(**options)
            errors = ErrorObserver(s)
            s.Update()
            self.assertIn(message, errors.text())
        s = self.synthesis(OutputSize=(8, 8, 1))
        s.SetFixedData(int_image(np.full((4, 4), -1, np.int32), "Label"))
        errors = ErrorObserver(s)
        s.Update()
        self.assertIn("the output 8 x 8 x 1", errors.text())


if __name__ == "__main__":
    unittest.main()
