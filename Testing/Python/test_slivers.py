"""Continuous synthesis without slivers (issue 29 item 2) and the rotated prism's model used as an
example (issue 30 item 5), through the command line: statistics.json reports the narrowest face,
edge or gap, and `msynth check` measures it again on the written polygons (not through the
solver) and fails under a tenth of the smallest plane spacing."""
import json
import math
import os
import subprocess
import time
import unittest

from msynth_testing import data, tmp

MSYNTH = os.path.join(os.environ["MSYNTH_BIN"], "msynth")


def msynth(*args, timeout=120):
    return subprocess.run([MSYNTH, *args], capture_output=True, text=True, timeout=timeout)


def rotated_prism(angle):
    """The bundled pentagonal prism turned about z by angle (radians), as an OBJ file."""
    path = tmp("prism-rotated-%g.obj" % angle)
    c, s = math.cos(angle), math.sin(angle)
    with open(data("Continuous/pentagonal-prism.obj")) as src, open(path, "w") as out:
        for line in src:
            if line.startswith("v "):
                x, y, z = map(float, line.split()[1:])
                line = "v %.9f %.9f %.9f\n" % (c * x - s * y, s * x + c * y, z)
            out.write(line)
    return path


class SliverTest(unittest.TestCase):
    def synthesize(self, example, out, *options):
        done = msynth("synthesize", example, "--out", out, *options)
        self.assertEqual(done.returncode, 0, done.stderr)
        with open(os.path.join(out, "statistics.json")) as f:
            return json.load(f)

    def assert_checked(self, example, out, stats):
        """The check passes and measures the same narrowest feature, at least a tenth."""
        check = msynth("check", example, os.path.join(out, "model.vtp"))
        self.assertEqual(check.returncode, 0, check.stdout + check.stderr)
        self.assertIn("narrowest face, edge or gap: ", check.stdout)
        line = next(l for l in check.stdout.splitlines() if l.startswith("narrowest face"))
        fraction = float(line.split("(")[-1].split()[0])
        self.assertGreaterEqual(fraction, 0.1)
        self.assertAlmostEqual(fraction, stats["SmallestFeatureFraction"], places=4)

    def test_rotated_prisms_have_no_slivers(self):
        # Before: features down to 10^-6 of a spacing and zero-area polygons (the check failed).
        for angle in (0.3, 0.7, 1.1):
            example = rotated_prism(angle)
            out = tmp("slivers-%g" % angle)
            stats = self.synthesize(example, out, "--size", "8", "8", "3", "--spacing", "0.3",
                                    "--seed", "2")
            self.assertGreater(stats["Polygons"], 100)
            self.assertGreaterEqual(stats["SmallestFeatureFraction"], 0.1, angle)
            self.assertAlmostEqual(stats["SmallestFeature"] / stats["SmallestFeatureFraction"], 0.3,
                                   places=4)
            self.assert_checked(example, out, stats)

    def test_bundled_rotated_pentagon(self):
        # Before: a gap 0.00066 wide (0.0002 of the spacing 3) at seed 3.
        example = data("Continuous/pentagon-rotated.obj")
        out = tmp("slivers-pentagon")
        stats = self.synthesize(example, out, "--size", "20", "20", "6", "--seed", "3")
        self.assertGreaterEqual(stats["SmallestFeatureFraction"], 0.1)
        self.assert_checked(example, out, stats)
        # Its model as an example: before, 134,040 arrangement vertices at 8 x 8 x 4 (7 s) and
        # 804,204 at 16 x 16 x 6 (over 100 s, three of four blocks failing).
        model = os.path.join(out, "model.vtp")
        for size in (("8", "8", "4"), ("16", "16", "6")):
            again = tmp("slivers-model-" + "x".join(size))
            start = time.monotonic()
            stats = self.synthesize(model, again, "--size", *size, "--seed", "1")
            self.assertLess(time.monotonic() - start, 20)
            self.assertLess(stats["ArrangementVertices"], 5000)
            self.assertEqual(stats["BlocksFailed"], 0)
            self.assertGreaterEqual(stats["SmallestFeatureFraction"], 0.1)
            check = msynth("check", model, os.path.join(again, "model.vtp"))
            self.assertEqual(check.returncode, 0, check.stdout + check.stderr)

    def test_check_fails_under_a_tenth_of_the_spacing(self):
        """A model whose recorded smallest spacing is 100 times its own: every feature is then
        under a tenth of it, and the check says so in one line."""
        from vtkmodules.vtkIOXML import vtkXMLPolyDataReader, vtkXMLPolyDataWriter
        example = data("Continuous/l-prism.obj")
        out = tmp("slivers-l-prism")
        stats = self.synthesize(example, out, "--size", "8", "6", "3", "--seed", "4")
        self.assertGreater(stats["SmallestFeature"], 0)
        reader = vtkXMLPolyDataReader()
        reader.SetFileName(os.path.join(out, "model.vtp"))
        reader.Update()
        model = reader.GetOutput()
        spacing = model.GetFieldData().GetArray("SmallestSpacing")
        spacing.SetValue(0, 100 * spacing.GetValue(0))
        broken = os.path.join(out, "coarse.vtp")
        writer = vtkXMLPolyDataWriter()
        writer.SetFileName(broken)
        writer.SetInputData(model)
        writer.Write()
        check = msynth("check", example, broken)
        self.assertEqual(check.returncode, 1, check.stdout + check.stderr)
        self.assertIn("under 10 % of the smallest plane spacing", check.stdout)
        self.assertEqual(len(check.stdout.strip().splitlines()), 1, check.stdout)


if __name__ == "__main__":
    unittest.main()
