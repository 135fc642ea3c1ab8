"""Discrete synthesis from plain vtkmodules Python: every model is checked against the example
by an independent numpy recomputation of Eq. 3.1; failures are errors, never models."""
import unittest

import numpy as np
from vtkmodules.vtkCommonCore import vtkFloatArray, vtkIntArray
from vtkmodules.vtkCommonDataModel import vtkImageData

import modelsynth
from msynth_testing import ErrorObserver, data, labels_zyx, run_algorithm, violations


def synthesize(example_port=None, example_data=None, **options):
    return run_algorithm(modelsynth.vtkMSDiscreteSynthesis(), example_port, example_data, **options)


class SynthesisTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.reader = modelsynth.vtkMSLabelGridReader()
        cls.reader.SetFileName(data("Examples/Village.vti"))
        cls.reader.Update()
        cls.example = labels_zyx(cls.reader.GetOutput())

    def test_blocks_with_boundaries(self):
        for order in (0, 1, 2):
            out, errors = synthesize(self.reader.GetOutputPort(), OutputSize=(36, 28, 5),
                                     BlockSize=(12, 12, 5), Seed=7, SiteOrder=order,
                                     UseBoundary=(1, 1, 1, 1, 1, 1), BoundaryLabels=(0, 0, 0, 0, 1, 0))
            self.assertEqual(errors, "")
            self.assertEqual(out.GetDimensions(), (36, 28, 5))
            model = labels_zyx(out)
            self.assertEqual(violations(self.example, model), [])
            self.assertTrue((model[0] == 1).all(), "ground along the bottom")
            self.assertTrue((model[-1] == 0).all() and (model[:, :, 0] == 0)[1:].all(), "empty around")
            self.assertGreater(int((model == 2).sum()), 0, "some walls were built")
            fd = out.GetFieldData()
            self.assertEqual(fd.GetArray("BlocksAccepted").GetValue(0) + fd.GetArray("BlocksFailed").GetValue(0),
                             fd.GetArray("Blocks").GetValue(0))
            self.assertEqual(fd.GetArray("TrivialLabel").GetValue(0), 0)
            last = labels_zyx(out, "LastBlock")
            self.assertGreaterEqual(int(last.max()), 0)

    def test_enums_and_statistics_have_one_naming(self):
        # VTK's SetXToY convention on every synthesis filter, with the same values.
        for cls in (modelsynth.vtkMSDiscreteSynthesis, modelsynth.vtkMSTimeVaryingSynthesis,
                    modelsynth.vtkMSContinuousSynthesis):
            f = cls()
            f.SetSiteOrderToRandom()
            self.assertEqual(f.GetSiteOrder(), cls.RANDOM)
            f.SetSiteOrderToScanLine()
            self.assertEqual(f.GetSiteOrder(), modelsynth.vtkMSDiscreteSynthesis.SCAN_LINE)
            f.SetLabelChoiceToFrequency()
            self.assertEqual(f.GetLabelChoice(), modelsynth.vtkMSDiscreteSynthesis.FREQUENCY)
        s = modelsynth.vtkMSDiscreteSynthesis()
        s.SetSiteOrderToMinimumEntropy()
        s.SetLabelChoiceToResemblance()
        self.assertEqual((s.GetSiteOrder(), s.GetLabelChoice()), (2, 2))
        # The statistics under the names every solver uses, with the run's status.
        out, errors = synthesize(self.reader.GetOutputPort(), OutputSize=(20, 20, 5),
                                 BlockSize=(8, 8, 5), Seed=3)
        self.assertEqual(errors, "")
        fd = out.GetFieldData()
        for name in ("Blocks", "BlocksAccepted", "BlocksFailed", "BlocksRejected", "Attempts",
                     "FailedAttempts", "Assignments", "Backtracks", "Phases", "Threads",
                     "Processes", "Seconds"):
            self.assertIsNotNone(fd.GetArray(name), name)
        self.assertEqual(fd.GetAbstractArray("Status").GetValue(0), "succeeded")
        self.assertEqual(fd.GetArray("FailedAttempts").GetValue(0),
                         fd.GetArray("Attempts").GetValue(0) - fd.GetArray("BlocksAccepted").GetValue(0))

    def test_same_seed_same_model(self):
        a, _ = synthesize(self.reader.GetOutputPort(), OutputSize=(20, 20, 5), BlockSize=(8, 8, 5), Seed=3)
        b, _ = synthesize(self.reader.GetOutputPort(), OutputSize=(20, 20, 5), BlockSize=(8, 8, 5), Seed=3)
        c, _ = synthesize(self.reader.GetOutputPort(), OutputSize=(20, 20, 5), BlockSize=(8, 8, 5), Seed=4)
        self.assertTrue(np.array_equal(labels_zyx(a), labels_zyx(b)))
        self.assertFalse(np.array_equal(labels_zyx(a), labels_zyx(c)))

    def test_catalog_snapshots_as_time_steps(self):
        from vtkmodules.vtkCommonExecutionModel import vtkStreamingDemandDrivenPipeline as SDDP

        plain, _ = synthesize(self.reader.GetOutputPort(), OutputSize=(16, 14, 5), BlockSize=(8, 8, 5), Seed=21)
        s = modelsynth.vtkMSDiscreteSynthesis()
        s.SetInputConnection(self.reader.GetOutputPort())
        s.SetOutputSize(16, 14, 5)
        s.SetBlockSize(8, 8, 5)
        s.SetSeed(21)
        s.SetCatalogSnapshotsPerBlock(3)
        s.UpdateInformation()
        info = s.GetOutputInformation(0)
        steps = info.Get(SDDP.TIME_STEPS())
        blocks = 3 * 3  # 16 and 14 sites in blocks of 8 with overlap 4: 3 starts per axis
        self.assertEqual(len(steps), 1 + 3 * blocks)

        def at(t):
            s.UpdateTimeStep(t)
            out = s.GetOutput()
            return (labels_zyx(out), labels_zyx(out, "CatalogSize"), labels_zyx(out, "Entropy"),
                    out.GetFieldData().GetArray("Step").GetValue(0))

        first = at(0)
        last = at(steps[-1])
        middle = at(steps[len(steps) // 2])
        self.assertEqual(first[3], 0)
        self.assertEqual(last[3], len(steps) - 1)
        # Block mode starts from the trivial model: everything decided, empty.
        self.assertTrue((first[1] == 1).all() and (first[0] == 0).all())
        # The last step is the model, identical to a run without snapshots.
        self.assertTrue((last[1] == 1).all())
        self.assertTrue(np.array_equal(last[0], labels_zyx(plain)))
        self.assertEqual(violations(self.example, last[0]), [])
        # Some step in between shows undecided sites with their catalog size and entropy.
        undecided = None
        for t in steps:
            labels, size, entropy, _ = at(t)
            if (size > 1).any():
                undecided = (labels, size, entropy)
                break
        self.assertIsNotNone(undecided)
        labels, size, entropy = undecided
        self.assertTrue((labels[size > 1] == np.iinfo(np.int32).min).all())
        self.assertTrue((entropy[size > 1] > 0).all() and (entropy[size == 1] == 0).all())
        self.assertTrue(middle[1].min() >= 1)

    def test_guide_volume_shapes_the_city(self):
        # A guide (6 x 6 x 1 over the output) forbids walls and roofs outside an L shape.
        guide = vtkImageData()
        guide.SetDimensions(6, 6, 1)
        inside = lambda i, j: i < 2 or j < 2
        for label in (2, 3):
            w = vtkFloatArray()
            w.SetName("Weight_%d" % label)
            for j in range(6):
                for i in range(6):
                    w.InsertNextValue(4.0 if inside(i, j) else 0.0)
            guide.GetPointData().AddArray(w)
        s = modelsynth.vtkMSDiscreteSynthesis()
        s.SetInputConnection(self.reader.GetOutputPort())
        s.SetGuideData(guide)
        s.SetOutputSize(30, 30, 5)
        s.SetBlockSize(10, 10, 5)
        s.SetSeed(4)
        s.SetUseBoundary(1, 1, 1, 1, 1, 1)
        s.SetBoundaryLabels(0, 0, 0, 0, 1, 0)
        errors = ErrorObserver(s)
        s.Update()
        self.assertEqual(errors.text(), "")
        model = labels_zyx(s.GetOutput())
        self.assertEqual(violations(self.example, model), [])
        z, y, x = np.nonzero((model == 2) | (model == 3))
        self.assertGreater(len(x), 0)
        # Site x reads guide cell floor((x + 1/2) * 6 / 30) = x // 5.
        self.assertTrue(all(inside(i // 5, j // 5) for i, j in zip(x, y)))

        bad = vtkImageData()
        bad.SetDimensions(2, 2, 1)
        w = vtkFloatArray()
        w.SetName("Weight_0")
        for _ in range(4):
            w.InsertNextValue(0.0)
        bad.GetPointData().AddArray(w)
        s.SetGuideData(bad)
        errors = ErrorObserver(s)
        s.Update()
        self.assertIn("the boundary label 0 has guide weight 0", errors.text())
        s.SetUseBoundary(0, 0, 0, 0, 0, 0)
        errors = ErrorObserver(s)
        s.Update()  # the start avoids label 0: another label, or layers of labels
        self.assertEqual(errors.text(), "")
        model = labels_zyx(s.GetOutput())
        self.assertEqual(violations(self.example, model), [])
        self.assertFalse((model == 0).any())
        s.SetUseTrivialLabel(1)
        s.SetTrivialLabel(0)
        errors = ErrorObserver(s)
        s.Update()
        self.assertIn("trivial label 0 weight 0", errors.text())

    def test_resemblance_choice(self):
        # Through the VTK layer (the engine test measures the resemblance itself): consistent,
        # not an empty model, and deterministic.
        options = dict(OutputSize=(24, 24, 5), BlockSize=(12, 12, 5), Seed=1, LabelChoice=2,
                       UseBoundary=(1, 1, 1, 1, 1, 1), BoundaryLabels=(0, 0, 0, 0, 1, 0))
        a, errors = synthesize(self.reader.GetOutputPort(), **options)
        b, _ = synthesize(self.reader.GetOutputPort(), **options)
        self.assertEqual(errors, "")
        model = labels_zyx(a)
        self.assertEqual(violations(self.example, model), [])
        self.assertGreater(int((model == 2).sum()), 0)
        self.assertTrue(np.array_equal(model, labels_zyx(b)))

    def test_soft_constraints(self):
        base = dict(OutputSize=(32, 32, 5), BlockSize=(8, 8, 5), Seed=5,
                    UseBoundary=(1, 1, 1, 1, 1, 1), BoundaryLabels=(0, 0, 0, 0, 1, 0))
        free, errors = synthesize(self.reader.GetOutputPort(), **base)
        self.assertEqual(errors, "")
        steered, errors = synthesize(self.reader.GetOutputPort(), TargetFractions="2:0.3",
                                     SoftTemperature=0.05, **base)
        self.assertEqual(errors, "")
        walls = lambda image: float((labels_zyx(image) == 2).mean())
        self.assertGreater(walls(steered), walls(free))
        self.assertEqual(violations(self.example, labels_zyx(steered)), [])
        self.assertGreater(steered.GetFieldData().GetArray("BlocksRejected").GetValue(0), 0)
        _, errors = synthesize(self.reader.GetOutputPort(), TargetFractions="2=0.3", **base)
        self.assertIn("is not 'label:fraction'", errors)
        whole = dict(base, BlockSize=(0, 0, 0))
        _, errors = synthesize(self.reader.GetOutputPort(), TargetFractions="2:0.3", **whole)
        self.assertIn("need block synthesis", errors)

    def test_mirror_symmetry(self):
        for size in ((21, 16, 5), (20, 17, 5)):
            out, errors = synthesize(self.reader.GetOutputPort(), OutputSize=size, BlockSize=(8, 8, 5),
                                     Seed=6, Mirror=(1, 1, 0), UseBoundary=(1, 1, 1, 1, 1, 1),
                                     BoundaryLabels=(0, 0, 0, 0, 1, 0))
            self.assertEqual(errors, "")
            model = labels_zyx(out)
            self.assertEqual(violations(self.example, model), [])
            self.assertTrue(np.array_equal(model, model[:, :, ::-1]), "symmetric in x")
            self.assertTrue(np.array_equal(model, model[:, ::-1, :]), "symmetric in y")
        _, errors = synthesize(self.reader.GetOutputPort(), OutputSize=(10, 10, 5), Mirror=(1, 0, 0),
                               MirrorSwaps="2:3")
        self.assertIn("not symmetric under the mirror map along x", errors)
        _, errors = synthesize(self.reader.GetOutputPort(), OutputSize=(10, 10, 5), Mirror=(1, 0, 0),
                               MirrorSwaps="2-3")
        self.assertIn("is not a pair 'a:b'", errors)

    def test_translation_symmetry(self):
        # Tileable in x and y: the output repeated 2 x 2 is still consistent (numpy check).
        out, errors = synthesize(self.reader.GetOutputPort(), OutputSize=(24, 20, 5), BlockSize=(8, 8, 5),
                                 Seed=2, Translate=(1, 1, 0), UseBoundary=(0, 0, 0, 0, 1, 0),
                                 BoundaryLabels=(0, 0, 0, 0, 1, 0))
        self.assertEqual(errors, "")
        model = labels_zyx(out)
        self.assertEqual(violations(self.example, model), [])
        self.assertEqual(violations(self.example, np.tile(model, (1, 2, 2))), [], "tiles seamlessly")
        self.assertTrue((model[0] == 1).all())
        self.assertGreater(int((model == 2).sum()), 0)
        # A period of 7 along x: M(x + 7) = M(x).
        out, errors = synthesize(self.reader.GetOutputPort(), OutputSize=(24, 20, 5), BlockSize=(8, 8, 5),
                                 Seed=3, Translate=(1, 0, 0), TranslationPeriod=(7, 0, 0))
        self.assertEqual(errors, "")
        model = labels_zyx(out)
        self.assertEqual(violations(self.example, model), [])
        self.assertTrue(np.array_equal(model[:, :, 7:], model[:, :, :-7]))
        _, errors = synthesize(self.reader.GetOutputPort(), OutputSize=(10, 10, 5), Translate=(1, 0, 0),
                               TranslationMap="2-3")
        self.assertIn("TranslationMap: '2-3' is not a pair", errors)
        _, errors = synthesize(self.reader.GetOutputPort(), OutputSize=(10, 10, 5), Translate=(1, 0, 0),
                               Mirror=(0, 1, 0))
        self.assertIn("cannot be combined", errors)

    def test_rotation_symmetry(self):
        # The village's rules look the same turned a quarter, so every label is its own image.
        for n in (20, 21):
            out, errors = synthesize(self.reader.GetOutputPort(), OutputSize=(n, n, 5), BlockSize=(6, 6, 5),
                                     Seed=5, Rotate=1, UseBoundary=(0, 0, 0, 0, 1, 0),
                                     BoundaryLabels=(0, 0, 0, 0, 1, 0))
            self.assertEqual(errors, "")
            model = labels_zyx(out)
            self.assertEqual(violations(self.example, model), [])
            y, x = np.indices((n, n))
            # M(n - 1 - y, x) = M(x, y): the site turned a quarter counter-clockwise holds the same.
            self.assertTrue(np.array_equal(model[:, x, n - 1 - y], model), "turned copy differs")
            self.assertGreater(int((model == 2).sum()), 0)
        _, errors = synthesize(self.reader.GetOutputPort(), OutputSize=(20, 16, 5), Rotate=1)
        self.assertIn("square in x and y", errors)

    def test_whole_model_failure_is_an_error_not_a_model(self):
        # A 1D example 0 1 2 cannot fill a 2D output: nothing may follow anything along y, which
        # is said before any attempt (it was a catalog emptied in every attempt).
        example = vtkImageData()
        example.SetDimensions(3, 1, 1)
        labels = vtkIntArray()
        labels.SetName("Label")
        for v in (0, 1, 2):
            labels.InsertNextValue(v)
        example.GetPointData().SetScalars(labels)
        out, errors = synthesize(example_data=example, OutputSize=(4, 4, 1))
        self.assertIn("no two labels may be neighbours along y", errors)
        self.assertIn("(size 4 1 1)", errors)
        self.assertEqual(out.GetNumberOfPoints(), 0)

    def test_explicit_source(self):
        # The source chosen explicitly uses its own file only, and names what is missing.
        lines = data("Tilesets/Lines.xml")
        out, errors = synthesize(OutputSize=(8, 8, 1), Source=3, TilesetFile=lines)
        self.assertIn("The source is an image sample but no SampleFile is set", errors)
        self.assertEqual(out.GetNumberOfPoints(), 0)
        out, errors = synthesize(self.reader.GetOutputPort(), OutputSize=(8, 8, 5),
                                 BlockSize=(4, 4, 5), Source=1, TilesetFile=lines)
        self.assertEqual(errors, "")
        self.assertIsNone(out.GetFieldData().GetAbstractArray("TilesetFile"))
        self.assertEqual(violations(self.example, labels_zyx(out)), [])
        tiles, errors = synthesize(OutputSize=(8, 8, 1), Source=2, TilesetFile=lines,
                                   SampleFile=data("Samples/City.png"))
        self.assertEqual(errors, "")
        self.assertEqual(tiles.GetFieldData().GetAbstractArray("TilesetFile").GetValue(0), lines)
        _, errors = synthesize(OutputSize=(8, 8, 1), TilesetFile=lines,
                               SampleFile=data("Samples/City.png"))
        self.assertIn("not both", errors)

    def test_no_trivial_start(self):
        board = modelsynth.vtkMSLabelGridReader()
        board.SetFileName(data("Examples/Checkerboard.vti"))
        out, errors = synthesize(board.GetOutputPort(), OutputSize=(20, 20, 1), BlockSize=(5, 5, 1))
        self.assertIn("no usable trivial start", errors)
        self.assertEqual(out.GetNumberOfPoints(), 0)
        out, errors = synthesize(board.GetOutputPort(), OutputSize=(9, 7, 1))  # whole model works
        self.assertEqual(errors, "")
        model = labels_zyx(out)
        self.assertTrue(((model[0, 1:, :] != model[0, :-1, :]).all()))


if __name__ == "__main__":
    unittest.main()
