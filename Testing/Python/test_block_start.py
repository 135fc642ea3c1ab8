"""Blocks must not flatten the model (issue: worlds, §0). Ramps.vti is a set whose structures
cannot close against the trivial label inside a 32-site block: each row climbs through a cycle of
34 labels (each may repeat) before it may return to label 0, so from Algorithm 3.4's trivial start
most blocks keep label 0. The automatic start (a probe run) chooses the undecided start there,
whose blocks continue structures across block borders: the block output is then as varied as a
whole-model run (distinct labels within 80 %, the most frequent label's share within 1.25 times),
valid by the independent check, the same for any thread count and for any region of the world.
On Lines, whose paths the trivial start keeps closed, the automatic start stays trivial. A
whole-model run that fails every attempt falls back to blocks (issue: first page, item 5)."""
import json
import os
import unittest

import numpy as np

from msynth_testing import data, fresh_folder, labels_and_start, labels_zyx, tmp, violations
from msynth_testing import read_label_grid as read
from msynth_testing import run_msynth as msynth

RAMPS = data("Examples/Ramps.vti")


def variety(labels):
    _, counts = np.unique(labels, return_counts=True)
    return len(counts), counts.max() / counts.sum()


def synthesize(example, name, *options):
    folder = fresh_folder(name)
    done = msynth("synthesize", example, "--outputs", "labels", "--out", folder, *options)
    return done, folder


class BlockStartTest(unittest.TestCase):
    def run_labels(self, example, name, *options):
        done, folder = synthesize(example, name, *options)
        self.assertEqual(done.returncode, 0, done.stderr)
        return labels_and_start(folder)

    def test_blocks_as_varied_as_a_whole_run(self):
        example = labels_zyx(read(RAMPS))
        for seed in ("1", "2", "3"):
            whole, _ = self.run_labels(RAMPS, "start-whole", "--size", "64", "64", "1",
                                       "--seed", seed)
            blocks = ["--size", "128", "128", "1", "--block", "32", "32", "1", "--seed", seed]
            auto, start = self.run_labels(RAMPS, "start-auto", *blocks)
            trivial, _ = self.run_labels(RAMPS, "start-trivial", *blocks, "--start", "trivial")
            self.assertEqual(start, "undecided")
            for labels in (whole, auto, trivial):
                self.assertEqual(violations(example, labels), [])
            (nw, sw), (na, sa), (nt, st) = variety(whole), variety(auto), variety(trivial)
            self.assertGreaterEqual(na, 0.8 * nw, seed)
            self.assertLessEqual(sa, 1.25 * sw, seed)
            # The trivial start flattens this set: the measure above would fail for it.
            self.assertGreater(st, 1.25 * sw, seed)

    def test_same_for_threads_and_regions(self):
        common = ["--size", "160", "96", "1", "--block", "32", "32", "1", "--seed", "7"]
        one, _ = self.run_labels(RAMPS, "start-one", *common, "--threads", "1")
        two, start = self.run_labels(RAMPS, "start-two", *common, "--threads", "2")
        self.assertEqual(start, "undecided")
        np.testing.assert_array_equal(one, two)
        part, _ = self.run_labels(RAMPS, "start-region", *common,
                                  "--region", "70", "40", "0", "110", "70", "1")
        np.testing.assert_array_equal(part, one[:, 40:70, 70:110])

    def test_lines_keep_the_trivial_start(self):
        lines = data("Tilesets/Lines.xml")
        _, start = self.run_labels(lines, "start-lines", "--size", "128", "128", "1",
                                   "--block", "32", "32", "1", "--seed", "1")
        self.assertEqual(start, "trivial")
        with open(os.path.join(tmp("start-lines"), "statistics.json")) as f:
            self.assertEqual(json.load(f)["StartFrom"], "trivial")

    def test_undecided_sites_fail_cleanly(self):
        # The village's blocks, ringed by decided sites, cannot always be completed from an
        # undecided start: the sites left undecided fail the run with one line.
        done, folder = synthesize(data("Examples/Village.vti"), "start-fails", "--size", "96",
                                  "96", "5", "--block", "24", "24", "5", "--seed", "1", "--start",
                                  "undecided")
        self.assertEqual(done.returncode, 1)
        lines = done.stderr.strip().splitlines()
        self.assertEqual(len(lines), 1, done.stderr)
        self.assertIn("left", lines[0])
        self.assertIn("undecided", lines[0])
        self.assertFalse(os.path.exists(os.path.join(folder, "labels.vti")))

    def test_blocks_when_the_whole_model_fails(self):
        # The README's old tileset recipe failed whole-model synthesis at larger sizes; the run
        # now falls back to blocks and says so (--no-fallback keeps the failure).
        lines = data("Tilesets/Lines.xml")
        recipe = ["--size", "128", "128", "1", "--order", "entropy", "--choice", "frequency",
                  "--backtracks", "0", "--attempts", "2", "--seed", "1"]
        done, folder = synthesize(lines, "start-fallback", *recipe)
        self.assertEqual(done.returncode, 0, done.stderr)
        self.assertIn("failed in all 2 attempts, so the model was synthesized in 32 x 32 x 1 "
                      "blocks instead", done.stdout)
        check = msynth("check", lines, os.path.join(folder, "labels.vti"))
        self.assertEqual(check.returncode, 0, check.stdout)
        done, folder = synthesize(lines, "start-no-fallback", *recipe, "--no-fallback")
        self.assertEqual(done.returncode, 1)
        self.assertEqual(len(done.stderr.strip().splitlines()), 1, done.stderr)
        self.assertIn("whole-model synthesis (Algorithm 3.1) failed", done.stderr)
        self.assertFalse(os.path.exists(os.path.join(folder, "labels.vti")))


if __name__ == "__main__":
    unittest.main()
