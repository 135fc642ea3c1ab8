"""Utilities/render-model.py: its palette (the first 12 colours as the gallery, the README and
the plugin's Label colour map have them; a colour of its own for every further label) and its
framing (the model fills the picture, seen from the corner or from above)."""
import importlib.util
import itertools
import math
import os
import shutil
import subprocess
import unittest

import numpy as np
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkIOImage import vtkPNGReader

from msynth_testing import BIN, data, fresh_folder

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
SCRIPT = os.path.join(ROOT, "Utilities", "render-model.py")
spec = importlib.util.spec_from_file_location("render_model", SCRIPT)
render_model = importlib.util.module_from_spec(spec)
spec.loader.exec_module(render_model)

FIRST_TWELVE = [(0.80, 0.70, 0.50), (0.65, 0.20, 0.12), (0.35, 0.50, 0.75), (0.35, 0.65, 0.35),
                (0.45, 0.45, 0.45), (0.90, 0.60, 0.20), (0.55, 0.35, 0.70), (0.20, 0.60, 0.60),
                (0.85, 0.45, 0.55), (0.60, 0.55, 0.30), (0.30, 0.30, 0.55), (0.75, 0.75, 0.40)]


def picture_coverage(path):
    """(fraction of pixels that are not the white background, the drawn part's width and height
    as fractions of the picture's)."""
    reader = vtkPNGReader()
    reader.SetFileName(path)
    reader.Update()
    image = reader.GetOutput()
    width, height, _ = image.GetDimensions()
    pixels = vtk_to_numpy(image.GetPointData().GetScalars()).reshape(height, width, -1)[..., :3]
    drawn = (pixels < 250).any(axis=2)
    ys, xs = np.nonzero(drawn)
    if not len(xs):
        return 0.0, 0.0, 0.0
    return float(drawn.mean()), (xs.max() - xs.min() + 1) / width, (ys.max() - ys.min() + 1) / height


class PaletteTest(unittest.TestCase):
    def test_first_twelve_unchanged(self):
        self.assertEqual(render_model.COLOURS + render_model.MORE, [c for rgb in FIRST_TWELVE for c in rgb])
        for label, rgb in enumerate(FIRST_TWELVE, start=1):
            self.assertEqual(tuple(render_model.label_colour(label)), rgb, label)
        self.assertEqual(tuple(render_model.label_colour(0)), FIRST_TWELVE[11])

    def test_many_labels_have_distinct_colours(self):
        colours = [tuple(255 * c for c in render_model.label_colour(t)) for t in range(1, 201)]
        self.assertEqual(len({tuple(round(c) for c in rgb) for rgb in colours}), 200)
        closest = min(math.dist(a, b) for a, b in itertools.combinations(colours, 2))
        self.assertGreater(closest, 8.0, "two of the first 200 labels look alike")
        for rgb in colours:
            self.assertTrue(all(0 <= c <= 255 for c in rgb), rgb)


class FramingTest(unittest.TestCase):
    def test_model_fills_the_picture(self):
        if os.environ.get("MSYNTH_SANITIZED"):
            self.skipTest("pictures are drawn in the Release build")
        pvpython = shutil.which("pvpython")
        if not pvpython:
            self.skipTest("no pvpython")
        out = fresh_folder("render-model")
        model = os.path.join(out, "village")
        done = subprocess.run([os.path.join(BIN, "msynth"), "synthesize", data("Examples/Village.vti"), "--size", "24",
                               "24", "5", "--block", "12", "12", "5", "--seed", "7", "--outputs", "mesh", "--out", model],
                              capture_output=True, text=True, timeout=120)
        self.assertEqual(done.returncode, 0, done.stderr)
        for view in ([], ["--top"]):
            png = os.path.join(out, "village%s.png" % "".join(view))
            done = subprocess.run([pvpython, SCRIPT, os.path.join(model, "mesh.vtp"), png, "--size", "360", "240"]
                                  + view, capture_output=True, text=True, timeout=200)
            self.assertEqual(done.returncode, 0, done.stderr)
            fraction, width, height = picture_coverage(png)
            # Before the fit, the view of the bounding sphere left the model 0.62 of the width
            # and 0.56 of the height (from above: 0.70 of the height), 17% of the pixels.
            self.assertGreater(max(width, height), 0.9, "%s: the model spans %.2f x %.2f of the picture" % (
                png, width, height))
            self.assertGreater(fraction, 0.25, "%s: the model covers %.2f of the picture" % (png, fraction))


if __name__ == "__main__":
    unittest.main()
