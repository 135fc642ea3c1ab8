"""The default start of block synthesis (issue 44, item 2). A large world's automatic start is
probed by one block ringed by the trivial label, not by a world of blocks and a whole-model run:
on a castle-like text example the default run is the trivial run and costs about as much. On the
published sets (../shared/data): a region of WaveFunctionCollapse's Castle tileset with default
options is accepted and equals the whole run's sites (the weight-based probe chose a whole-model
start on some seeds and refused it), and the City sample in blocks with translation is as varied
as a whole run (it was one pattern everywhere)."""
import os
import time
import unittest

import numpy as np

from msynth_testing import data, fresh_folder, labels_and_start
from msynth_testing import run_msynth as msynth

SHARED = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "..", "shared",
                      "data", "WaveFunctionCollapse")


def variety(labels):
    _, counts = np.unique(labels, return_counts=True)
    return len(counts), counts.max() / counts.sum()


class BlockStartDefaultsTest(unittest.TestCase):
    def run_labels(self, name, *args):
        folder = fresh_folder(name)
        began = time.monotonic()
        done = msynth("synthesize", *args, "--out", folder)
        seconds = time.monotonic() - began
        self.assertEqual(done.returncode, 0, done.stderr)
        return labels_and_start(folder) + (seconds,)

    def test_text_example_probe_is_cheap(self):
        if os.environ.get("MSYNTH_SANITIZED"):
            self.skipTest("timed in the Release build")
        common = [data("Examples/Village.txt"), "--size", "140", "140", "5", "--block", "20",
                  "20", "5", "--seed", "1", "--outputs", "labels"]
        trivial = min((self.run_labels("defaults-trivial", *common, "--start", "trivial")
                       for _ in range(2)), key=lambda r: r[2])
        auto = min((self.run_labels("defaults-auto", *common) for _ in range(2)),
                   key=lambda r: r[2])
        self.assertEqual(auto[1], "trivial")
        np.testing.assert_array_equal(auto[0], trivial[0])
        self.assertLess(auto[2], 1.3 * trivial[2] + 0.3, (auto[2], trivial[2]))

    def published(self, *path):
        name = os.path.join(SHARED, *path)
        if not os.path.exists(name):
            self.skipTest("skipped: published data not found")
        return name

    def test_castle_tileset_region_with_defaults(self):
        castle = self.published("tilesets", "Castle.xml")
        for seed in ("1", "3"):
            common = [castle, "--size", "256", "256", "1", "--block", "32", "32", "1", "--seed",
                      seed, "--outputs", "labels"]
            whole, start, _ = self.run_labels("defaults-castle", *common)
            self.assertEqual(start, "trivial")
            self.assertEqual(variety(whole)[0], 29)
            part, _, _ = self.run_labels("defaults-castle-region", *common, "--region", "64",
                                         "64", "0", "160", "128", "1")
            np.testing.assert_array_equal(part, whole[:, 64:128, 64:160])

    def test_city_varied_in_blocks(self):
        city = [self.published("samples", "City.png"), "--pattern", "3", "--symmetry", "8",
                "--translate", "xy", "--seed", "1", "--outputs", "labels"]
        whole, _, _ = self.run_labels("defaults-city-whole", *city, "--size", "64", "64", "1")
        blocks, _, _ = self.run_labels("defaults-city-blocks", *city, "--size", "128", "128",
                                       "1", "--block", "32", "32", "1")
        (nw, sw), (nb, sb) = variety(whole), variety(blocks)
        self.assertGreaterEqual(nb, 0.8 * nw)
        self.assertLessEqual(sb, 1.25 * sw)


if __name__ == "__main__":
    unittest.main()
