"""Time-varying (4D) synthesis, dissertation 3.5.4, from plain vtkmodules Python: frames are
fetched one time step at a time and checked against pairs (in space and in time) recomputed
here from the example with numpy."""
import unittest

import numpy as np
from vtkmodules.vtkCommonCore import vtkIntArray
from vtkmodules.vtkCommonDataModel import vtkImageData

import modelsynth
from msynth_testing import ErrorObserver, labels_zyx

EMPTY, IN, OUT = 0, 1, 2


def rolling_ball():
    """Fig. 3.27 along x, z slices as frames: a ball emerges in a cell (IN) and leaves it a
    frame later (OUT) while the next cell shows it emerging."""
    frames = np.zeros((8, 1, 6), dtype=np.int32)  # [t, y, x]
    for t in range(8):
        if t < 6:
            frames[t, 0, t] = IN
        if 1 <= t <= 6:
            frames[t, 0, t - 1] = OUT
    image = vtkImageData()
    image.SetDimensions(6, 1, 8)
    labels = vtkIntArray()
    labels.SetName("Label")
    for v in frames.ravel():
        labels.InsertNextValue(int(v))
    image.GetPointData().SetScalars(labels)
    return image, frames


def allowed_pairs(frames):
    """{(axis, a, b)}: axis 0-2 in space (x, y, z of [t, z, y, x] frames), 3 in time."""
    pairs = set()
    for axis, sl in ((0, np.s_[..., :-1]), (1, np.s_[..., :-1, :]), (2, np.s_[:, :-1, :, :])):
        nxt = {0: np.s_[..., 1:], 1: np.s_[..., 1:, :], 2: np.s_[:, 1:, :, :]}[axis]
        pairs |= {(axis, int(a), int(b)) for a, b in zip(frames[sl].ravel(), frames[nxt].ravel())}
    pairs |= {(3, int(a), int(b)) for a, b in zip(frames[:-1].ravel(), frames[1:].ravel())}
    return pairs


def fetch(filter_, frames):
    """All frames of the output, [t, z, y, x]."""
    out = []
    for t in range(frames):
        filter_.UpdateTimeStep(float(t))
        out.append(labels_zyx(filter_.GetOutput()).copy())
    return np.array(out)


class TimeVaryingTest(unittest.TestCase):
    def synthesize(self, **options):
        example, frames = rolling_ball()
        s = modelsynth.vtkMSTimeVaryingSynthesis()
        s.SetInputData(example)
        s.SetExampleTimeFromZ(1)
        for name, value in options.items():
            values = value if isinstance(value, (list, tuple)) else [value]
            getattr(s, "Set" + name)(*values)
        errors = ErrorObserver(s)
        return s, frames[:, np.newaxis], errors  # example frames as [t, z, y, x]

    def test_rolling_balls(self):
        balls = 0
        for block in ((0, 0, 0, 0), (6, 1, 1, 6)):
            s, example, errors = self.synthesize(OutputSize=(16, 1, 1), NumberOfFrames=20, Seed=3,
                                                 BlockSize=block)
            s.UpdateInformation()
            steps = s.GetOutputInformation(0).Get(s.GetExecutive().TIME_STEPS())
            self.assertEqual(len(steps), 20)
            model = fetch(s, 20)
            self.assertEqual(errors.text(), "")
            self.assertEqual(model.shape, (20, 1, 1, 16))
            bad = allowed_pairs(model) - allowed_pairs(example)
            self.assertEqual(bad, set(), "pairs the example never shows")
            m = model[:, 0, 0, :]  # [t, x]
            for t, x in zip(*np.nonzero(m == IN)):
                balls += 1
                if x > 0:
                    self.assertEqual(m[t, x - 1], OUT, "a ball came from nowhere")
                if t + 1 < 20:
                    self.assertEqual(m[t + 1, x], OUT, "a ball stopped")
            fd = s.GetOutput().GetFieldData()
            self.assertEqual(fd.GetArray("ExampleFrames").GetValue(0), 8)
        self.assertGreater(balls, 0)

    def test_loop_and_determinism(self):
        s, example, errors = self.synthesize(OutputSize=(12, 1, 1), NumberOfFrames=10, Seed=5, Loop=1)
        model = fetch(s, 10)
        self.assertEqual(errors.text(), "")
        self.assertGreater(int((model == IN).sum()), 0)
        looped = np.concatenate([model, model[:1]])
        self.assertEqual(allowed_pairs(looped) - allowed_pairs(example), set(), "the loop jumps")
        again, _, _ = self.synthesize(OutputSize=(12, 1, 1), NumberOfFrames=10, Seed=5, Loop=1)
        self.assertTrue(np.array_equal(fetch(again, 10), model))

    def test_errors(self):
        # One example frame has no pairs in time, so two output frames cannot be consistent.
        example, _ = rolling_ball()
        single = vtkImageData()
        single.SetDimensions(6, 1, 1)
        labels = vtkIntArray()
        labels.SetName("Label")
        for x in range(6):
            labels.InsertNextValue(0)
        single.GetPointData().SetScalars(labels)
        s = modelsynth.vtkMSTimeVaryingSynthesis()
        s.SetInputData(single)
        s.SetOutputSize(6, 1, 1)
        s.SetNumberOfFrames(3)
        errors = ErrorObserver(s)
        s.Update()
        self.assertIn("failed", errors.text())
        s.SetExampleTimeFromZ(1)
        s.SetBlockSize(3, 1, 1, 2)
        s.Update()
        self.assertIn("no usable trivial start", errors.text())


if __name__ == "__main__":
    unittest.main()
