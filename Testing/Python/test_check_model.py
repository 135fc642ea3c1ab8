"""The independent checks as a filter (vtkMSCheckModel) from Python: synthesis -> check gives
the verdict as field data; a model corrupted here gives verdict 0 with the violations this test
counts itself (numpy, from the example); a pattern's KL divergence per shape equals the one this
test computes from the histograms (Yeh et al. 2012 §7, Laplace smoothing); bad input is an
error, not a verdict."""
import math
import unittest

from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkCommonDataModel import vtkImageData

import modelsynth
from msynth_testing import ErrorObserver, data, labels_zyx, read_label_grid, violations


def field(image, name):
    a = image.GetFieldData().GetAbstractArray(name)
    return None if a is None else a.GetVariantValue(0).ToDouble() if a.IsNumeric() else a.GetValue(0)


def check(model, examples=(), **options):
    """(output, errors) of vtkMSCheckModel on `model` (data) against `examples` (data)."""
    c = modelsynth.vtkMSCheckModel()
    c.SetInputData(model)
    for e in examples:
        c.AddExampleData(e)
    for name, value in options.items():
        getattr(c, "Set" + name)(value)
    errors = ErrorObserver(c)
    c.Update()
    return c.GetOutput(), errors.text()


def kl(exemplars, model, length):
    """D(f_model || f^_exemplars) for `length` tiles in a row along x, from [z, y, x] arrays."""
    def counts(grids):
        h = {}
        for g in grids:
            nz, ny, nx = g.shape
            for z in range(nz):
                for y in range(ny):
                    for x in range(nx - length + 1):
                        key = tuple(int(v) for v in g[z, y, x:x + length])
                        h[key] = h.get(key, 0) + 1
        return h
    f, e = counts([model]), counts(exemplars)
    union = set(f) | set(e)
    total_f, total_e = sum(f.values()), sum(e.values())
    return sum(n / total_f * math.log((n / total_f) / ((e.get(c, 0) + 1) / (total_e + len(union))))
               for c, n in f.items())


class CheckModelTest(unittest.TestCase):
    def setUp(self):
        self.reader = modelsynth.vtkMSLabelGridReader()
        self.reader.SetFileName(data("Examples/Village.vti"))
        self.reader.GenerateGeometryOff()
        self.reader.Update()

    def synthesized(self):
        s = modelsynth.vtkMSDiscreteSynthesis()
        s.SetInputConnection(self.reader.GetOutputPort())
        s.SetOutputSize(16, 16, 5)
        s.SetBlockSize(8, 8, 5)
        s.SetSeed(7)
        s.GenerateGeometryOff()
        return s

    def test_synthesis_then_check(self):
        s = self.synthesized()
        c = modelsynth.vtkMSCheckModel()
        c.SetInputConnection(s.GetOutputPort())
        c.AddExampleConnection(self.reader.GetOutputPort())
        errors = ErrorObserver(c)
        c.Update()
        self.assertEqual(errors.text(), "")
        out = c.GetOutput()
        self.assertEqual(field(out, "Valid"), 1)
        self.assertEqual(field(out, "Violations"), 0)
        self.assertEqual(field(out, "PairsChecked"), 15 * 16 * 5 * 2 + 16 * 16 * 4)
        self.assertEqual(out.GetFieldData().GetAbstractArray("Problems").GetNumberOfValues(), 0)
        # The model passes through with the solver's own field data.
        self.assertEqual(out.GetDimensions(), (16, 16, 5))
        self.assertIsNotNone(out.GetFieldData().GetArray("Blocks"))
        self.assertEqual(violations(labels_zyx(self.reader.GetOutput()), labels_zyx(out)), [])

    def test_corrupted_model(self):
        example = read_label_grid(data("Examples/Checkerboard.vti"))
        model = vtkImageData()
        model.DeepCopy(example)
        labels = model.GetPointData().GetArray("Label")
        nx, ny, nz = model.GetDimensions()
        self.assertGreaterEqual(min(nx, ny), 4)
        # An interior site given its +x neighbour's label: the four pairs through it now join
        # equal labels, which a checkerboard never shows.
        x, y = 2, 2
        i = x + nx * y
        labels.SetValue(i, labels.GetValue(i + 1))
        expected = violations(labels_zyx(example), labels_zyx(model))
        out, errors = check(model, [example])
        self.assertEqual(errors, "")
        self.assertEqual(field(out, "Valid"), 0)
        self.assertEqual(field(out, "Violations"), 4)
        self.assertEqual(len(expected), 2)  # distinct (axis, from, to): one per axis here
        sites = vtk_to_numpy(out.GetFieldData().GetArray("ViolationSites")).tolist()
        axes = vtk_to_numpy(out.GetFieldData().GetArray("ViolationAxes")).tolist()
        pairs = vtk_to_numpy(out.GetFieldData().GetArray("ViolationLabels")).tolist()
        self.assertEqual(sorted(zip(map(tuple, sites), axes)),
                         sorted([((x - 1, y, 0), 0), ((x, y, 0), 0), ((x, y - 1, 0), 1), ((x, y, 0), 1)]))
        self.assertTrue(all(a == b for a, b in pairs))
        self.assertEqual(sorted({(ax, a, b) for ax, (a, b) in zip(axes, pairs)}), sorted(expected))
        problems = out.GetFieldData().GetAbstractArray("Problems")
        self.assertEqual(problems.GetNumberOfValues(), 4)
        self.assertIn("is not allowed", problems.GetValue(0))
        # At most MaximumReported listed; all counted.
        out, _ = check(model, [example], MaximumReported=1)
        self.assertEqual((field(out, "Violations"), out.GetFieldData().GetArray("ViolationSites").GetNumberOfTuples()),
                         (4, 1))

    def test_tileset_recorded_by_the_synthesis(self):
        s = modelsynth.vtkMSDiscreteSynthesis()
        s.SetTilesetFile(data("Tilesets/Lines.xml"))
        s.SetOutputSize(12, 12, 1)
        s.SetSeed(2)
        s.GenerateGeometryOff()
        c = modelsynth.vtkMSCheckModel()  # no example: the tileset the model names
        c.SetInputConnection(s.GetOutputPort())
        errors = ErrorObserver(c)
        c.Update()
        self.assertEqual(errors.text(), "")
        self.assertEqual(field(c.GetOutput(), "Valid"), 1)
        self.assertEqual(field(c.GetOutput(), "PairsChecked"), 2 * 11 * 12)

    def test_pattern_kl_per_shape(self):
        exemplars = [read_label_grid(data("Patterns/facade-rectangular.vti")),
                     read_label_grid(data("Patterns/facade-l-shaped.vti"))]
        p = modelsynth.vtkMSPatternSynthesis()
        for e in exemplars:
            p.AddExemplarData(e)
        p.SetOutputSize(20, 14, 1)
        p.SetSoftFactors("4H")
        p.SetSeed(3)
        c = modelsynth.vtkMSCheckModel()
        c.SetInputConnection(p.GetOutputPort())
        for e in exemplars:
            c.AddExampleData(e)
        c.SetShapes("3H,4H")
        errors = ErrorObserver(c)
        c.Update()
        self.assertEqual(errors.text(), "")
        out = c.GetOutput()
        self.assertEqual(field(out, "Valid"), 1)
        grids = [labels_zyx(e) for e in exemplars]
        for length in (3, 4):
            self.assertAlmostEqual(field(out, "KL_%dH" % length), kl(grids, labels_zyx(out), length), places=9)
        self.assertGreater(field(out, "PatternLogProbability"), 0)

    def test_bad_input_is_an_error(self):
        model = read_label_grid(data("Examples/Checkerboard.vti"))
        out, errors = check(model)
        self.assertIn("Nothing to check the model against", errors)
        self.assertIsNone(out.GetFieldData().GetArray("Valid"))
        out, errors = check(model, [model], TilesetFile=data("Tilesets/NoSuchSet.xml"))
        self.assertIn("NoSuchSet.xml", errors)
        out, errors = check(model, [model], Shapes="4Q")
        self.assertNotEqual(errors, "")


if __name__ == "__main__":
    unittest.main()
