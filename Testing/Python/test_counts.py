"""Label counts (--count, the filter's Counts): the number of sites of a label or tile stays in
[MIN, MAX] on every run of a matrix (a label grid and a tileset, whole model and blocks, seeds,
1 and 2 threads), verified here by counting the written labels and by `msynth check`
(which counts them again, sharing no code with the solver); impossible counts are one line
before any work, with nothing written."""
import json
import os
import unittest

import numpy as np

import modelsynth
from msynth_testing import data, fresh_folder, labels_zyx, read_label_grid, run_algorithm, run_msynth

VILLAGE = data("Examples/Village.vti")
LINES = data("Tilesets/Lines.xml")
# (example, size, block, counts as label or tile -> (min, max))
CASES = [
    (VILLAGE, ["24", "24", "5"], ["12", "12", "5"], {"2": (150, 300), "3": (100, 180)}),
    (LINES, ["24", "24", "1"], ["12", "12", "1"], {"corner": (100, 150), "empty": (200, 400)}),
]


# Lines.xml's labels by tile, in the format's order: empty (X, one orientation), line (I, two),
# corner (L, four).
LINES_TILES = {"empty": [0], "line": [1, 2], "corner": [3, 4, 5, 6]}


def counted(model, name):
    """Sites of `model` (image data) holding label `name`, or any label of Lines' tile `name`."""
    labels = labels_zyx(model).ravel()
    if name.lstrip("-").isdigit():
        return int(np.count_nonzero(labels == int(name)))
    return int(np.isin(labels, LINES_TILES[name]).sum())


class CountsTest(unittest.TestCase):
    def test_counts_hold_on_every_run_of_the_matrix(self):
        for example, size, block, counts in CASES:
            args = [a for name, (lo, hi) in counts.items() for a in ("--count", "%s:%d:%d" % (name, lo, hi))]
            for blocks in ([], ["--block", *block]):
                for seed in ("1", "2", "3"):
                    models = []
                    for threads in ("1", "2"):
                        out = fresh_folder("counts-%s-%d-%s-%s" % (
                            os.path.basename(example), len(blocks), seed, threads))
                        r = run_msynth("synthesize", example, "--size", *size, *blocks, "--seed", seed,
                                       "--threads", threads, *args, "--outputs", "labels",
                                       "--out", out)
                        self.assertEqual(r.returncode, 0, r.stderr)
                        path = os.path.join(out, "labels.vti")
                        model = read_label_grid(path)
                        with open(os.path.join(out, "statistics.json")) as f:
                            stats = json.load(f)
                        reported = {c["label"]: c for c in stats["Counts"]}
                        for name, (lo, hi) in counts.items():
                            n = counted(model, name)
                            self.assertTrue(lo <= n <= hi, "%s: %s holds %d sites, not %d to %d (%s, seed %s)"
                                            % (example, name, n, lo, hi, blocks, seed))
                            self.assertEqual(reported[name]["achieved"], n)
                            self.assertEqual((reported[name]["minimum"], reported[name]["maximum"]), (lo, hi))
                        c = run_msynth("check", example, path, *args)
                        self.assertEqual(c.returncode, 0, c.stdout + c.stderr)
                        self.assertIn("count kept", c.stdout)
                        models.append(labels_zyx(model))
                    self.assertTrue(np.array_equal(models[0], models[1]), "threads change the model")

    def test_check_finds_a_missed_count(self):
        out = fresh_folder("counts-plain")
        r = run_msynth("synthesize", LINES, "--size", "16", "16", "1", "--seed", "1", "--outputs", "labels",
                       "--out", out)
        self.assertEqual(r.returncode, 0, r.stderr)
        c = run_msynth("check", LINES, os.path.join(out, "labels.vti"), "--count", "corner:0:0")
        self.assertEqual(c.returncode, 1, c.stdout + c.stderr)
        self.assertIn("count missed: corner holds", c.stdout)

    def test_impossible_counts_are_one_line_before_any_work(self):
        for args, message in [
                (["--count", "2:3000:3000"], "asks for at least 3000 sites, but the output has 2880"),
                (["--count", "9:1:2"], "label 9 does not occur in the example"),
                (["--count", "2:1:2", "--mirror", "x"], "cannot be combined with symmetry"),
                (["--count", "2:5:3"], "is not 'label:min:max'"),
                (["--count", "roof:1:2"], "is not a label value"),
                (["--count", "3:1:5", "--block", "12", "12", "5", "--region", "0", "0", "0", "12", "12", "5"],
                 "label counts")]:
            out = os.path.join(fresh_folder("counts-bad"), "out")
            r = run_msynth("synthesize", VILLAGE, "--size", "24", "24", "5", *args, "--out", out)
            self.assertNotEqual(r.returncode, 0, args)
            lines = r.stderr.strip().splitlines()
            self.assertEqual(len(lines), 1, r.stderr)
            self.assertIn(message, lines[0])
            self.assertFalse(os.path.exists(out), "nothing is written")
        r = run_msynth("synthesize", LINES, "--size", "8", "8", "1", "--count", "bridge:1:2")
        self.assertNotEqual(r.returncode, 0)
        self.assertIn("no tile or label named 'bridge'", r.stderr)

    def test_the_filter_reports_the_counts(self):
        synthesis = modelsynth.vtkMSDiscreteSynthesis()
        output, errors = run_algorithm(synthesis, TilesetFile=LINES, OutputSize=(20, 20, 1),
                                       BlockSize=(10, 10, 1), Seed=5, Counts="corner:60:100, 0:100:250")
        self.assertEqual(errors, "")
        fd = output.GetFieldData()
        names = fd.GetAbstractArray("CountNames")
        self.assertEqual([names.GetValue(i) for i in range(2)], ["corner", "0"])
        achieved = fd.GetArray("CountAchieved")
        self.assertEqual(achieved.GetValue(0), counted(output, "corner"))
        self.assertEqual(achieved.GetValue(1), counted(output, "0"))
        self.assertTrue(60 <= achieved.GetValue(0) <= 100 and 100 <= achieved.GetValue(1) <= 250)
        _, errors = run_algorithm(modelsynth.vtkMSDiscreteSynthesis(), TilesetFile=LINES,
                                  OutputSize=(20, 20, 1), Counts="corner:500:600")
        self.assertIn("asks for at least 500 sites, but the output has 400", errors)


if __name__ == "__main__":
    unittest.main()
