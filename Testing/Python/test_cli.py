"""The msynth command line: outputs, exit codes and one-line errors."""
import csv
import os
import shutil
import subprocess
import unittest

from msynth_testing import BIN, data, tmp

MSYNTH = os.path.join(BIN, "msynth")


def run(*args):
    return subprocess.run([MSYNTH, *args], capture_output=True, text=True, timeout=120)


class CommandLineTest(unittest.TestCase):
    def test_analyze_writes_outputs(self):
        out = tmp("cli-out")
        shutil.rmtree(out, ignore_errors=True)
        r = run("analyze", data("Examples/Village.vti"), "--out", out)
        self.assertEqual(r.returncode, 0, r.stderr)
        for name in ("labels.csv", "transitions.csv", "example.vdb"):
            self.assertTrue(os.path.isfile(os.path.join(out, name)), name)
        with open(os.path.join(out, "labels.csv")) as f:
            rows = list(csv.DictReader(f))
        self.assertEqual([r["Label"] for r in rows], ["0", "1", "2", "3"])
        self.assertEqual(sum(int(r["Count"]) for r in rows), 7 * 7 * 5)
        listing = subprocess.run(["vdb_print", "-l", "-m", os.path.join(out, "example.vdb")],
                                 capture_output=True, text=True)
        self.assertEqual(listing.returncode, 0)
        self.assertIn("Name: Label", listing.stdout)
        self.assertIn("Tree_int32", listing.stdout)
        self.assertIn("generator: ModelSynth", listing.stdout)
        self.assertEqual([n for n in os.listdir(out) if ".tmp-" in n], [])

    def test_info(self):
        r = run("info", data("Examples/Checkerboard.vti"))
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertIn("labels: 2", r.stdout)
        self.assertIn("transitions +x: 2", r.stdout)

    def test_bad_input_exits_non_zero_with_one_line(self):
        path = data("Malformed/truncated.vti")
        r = run("info", path)
        self.assertEqual(r.returncode, 1)
        self.assertEqual(r.stderr.count("\n"), 1, r.stderr)
        self.assertIn(path, r.stderr)

    def test_unwritable_output(self):
        r = run("analyze", data("Examples/Village.vti"), "--out", "/proc/forbidden")
        self.assertEqual(r.returncode, 1)
        self.assertIn("/proc/forbidden", r.stderr)

    def test_usage_errors(self):
        self.assertEqual(run().returncode, 2)
        self.assertEqual(run("bogus").returncode, 2)
        self.assertEqual(run("info").returncode, 2)
        self.assertEqual(run("analyze", "x.vti", "--out").returncode, 2)
        self.assertEqual(run("--help").returncode, 0)


if __name__ == "__main__":
    unittest.main()
