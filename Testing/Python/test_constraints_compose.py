"""Constraints together (issue 44's done-when): a road network with a number of houses and
pinned sites in one run, on the bundled suburban city exemplar, whole and in blocks, passes
`msynth check --fixed --count --connected`; the components, the houses and the pins are also
counted here with numpy and a flood of the test's own. The same run through the filter and
vtkMSCheckModel in Python. An open network with counts and pins gives a region equal to the
whole run; what cannot work is one line."""
import json
import os
import unittest
from collections import deque

import numpy as np

import modelsynth
from msynth_testing import (data, expect_refused, fresh_folder, labels_zyx, read_label_grid,
                            run_algorithm, run_msynth)

CITY = data("Patterns/city-suburban.vti")
PINS = data("Patterns/city-pins-48.vti")
# The road tiles the suburban exemplar holds (Data/Patterns/City.xml: tiles 1 to 15).
ROADS = "1,2,3,4,5,7,8,9,10,13,15"
HOUSE = 16
HOUSES = (40, 60)  # unsteered, a 48 x 48 town holds about 90 to 120 houses


def components(labels, values):
    """Components of the sites of `labels` ([y, x]) holding any of `values`, face neighbours."""
    on = np.isin(labels, values)
    seen = np.zeros(labels.shape, bool)
    count = 0
    ny, nx = labels.shape
    for y0, x0 in zip(*np.nonzero(on)):
        if seen[y0, x0]:
            continue
        count += 1
        seen[y0, x0] = True
        queue = deque([(y0, x0)])
        while queue:
            y, x = queue.popleft()
            for qy, qx in ((y + 1, x), (y - 1, x), (y, x + 1), (y, x - 1)):
                if 0 <= qy < ny and 0 <= qx < nx and on[qy, qx] and not seen[qy, qx]:
                    seen[qy, qx] = True
                    queue.append((qy, qx))
    return count


def pins_yx():
    return labels_zyx(read_label_grid(PINS))[0]


class ConstraintsComposeTest(unittest.TestCase):
    def verify(self, labels, what):
        roads = [int(v) for v in ROADS.split(",")]
        self.assertEqual(components(labels, roads), 1, what)
        houses = int(np.count_nonzero(labels == HOUSE))
        self.assertGreaterEqual(houses, HOUSES[0], what)
        self.assertLessEqual(houses, HOUSES[1], what)
        pins = pins_yx()
        pinned = pins >= 0
        self.assertGreater(np.count_nonzero(pinned), 0)
        self.assertTrue(np.array_equal(labels[pinned], pins[pinned]), what)
        return houses

    def test_network_houses_and_pins_in_one_run_pass_check(self):
        count = "%d:%d:%d" % (HOUSE, *HOUSES)
        for blocks in ([], ["--block", "16", "16", "1"]):
            for seed in ("1", "2", "3"):
                what = "blocks %s seed %s" % (blocks, seed)
                out = fresh_folder("compose-%d-%s" % (len(blocks), seed))
                r = run_msynth("synthesize", CITY, "--size", "48", "48", "1", *blocks,
                               "--seed", seed, "--connected", ROADS, "--fixed", PINS,
                               "--count", count, "--outputs", "labels", "--out", out)
                self.assertEqual(r.returncode, 0, what + ": " + r.stderr)
                path = os.path.join(out, "labels.vti")
                houses = self.verify(labels_zyx(read_label_grid(path))[0], what)
                c = run_msynth("check", CITY, path, "--fixed", PINS, "--count", count,
                               "--connected", ROADS)
                self.assertEqual(c.returncode, 0, what + ": " + c.stdout + c.stderr)
                self.assertIn("pins kept: 7 pinned sites hold their labels", c.stdout)
                self.assertIn("count kept: %d holds %d sites" % (HOUSE, houses), c.stdout)
                self.assertIn("connected: %s form 1 component" % ROADS, c.stdout)
                with open(os.path.join(out, "statistics.json")) as f:
                    stats = json.load(f)
                self.assertEqual(stats["Connected"]["components"], 1, what)
                self.assertEqual(stats["Counts"][0]["achieved"], houses, what)

    def test_path_and_counts_per_guide_region_compose_too(self):
        guide = data("Tilesets/lines-halves.vti")  # Region 0 the left half, 1 the right one
        for blocks in ([], ["--block", "16", "16", "1"]):
            what = "blocks %s" % blocks
            out = fresh_folder("compose-path-%d" % len(blocks))
            both = ["--fixed", PINS, "--guide", guide, "--count", "region=0:16:10:25",
                    "--count", "region=1:16:50:80", "--connected", ROADS + ":4",
                    "--path", "6,5", "42,42", "24,30"]
            r = run_msynth("synthesize", CITY, "--size", "48", "48", "1", *blocks, "--seed", "2",
                           *both, "--outputs", "labels", "--out", out)
            self.assertEqual(r.returncode, 0, what + ": " + r.stderr)
            c = run_msynth("check", CITY, os.path.join(out, "labels.vti"), *both)
            self.assertEqual(c.returncode, 0, what + ": " + c.stdout + c.stderr)
            self.assertIn("path joined: 3 sites in 1 component", c.stdout)
            labels = labels_zyx(read_label_grid(os.path.join(out, "labels.vti")))[0]
            self.assertTrue(10 <= np.count_nonzero(labels[:, :24] == HOUSE) <= 25, what)
            self.assertTrue(50 <= np.count_nonzero(labels[:, 24:] == HOUSE) <= 80, what)

    def test_check_finds_a_missed_pin(self):
        out = fresh_folder("compose-plain")
        r = run_msynth("synthesize", CITY, "--size", "48", "48", "1", "--seed", "4",
                       "--outputs", "labels", "--out", out)
        self.assertEqual(r.returncode, 0, r.stderr)
        c = run_msynth("check", CITY, os.path.join(out, "labels.vti"), "--fixed", PINS)
        self.assertEqual(c.returncode, 1, c.stdout + c.stderr)
        self.assertIn("pins missed: ", c.stdout)
        self.assertIn(" of 7 pinned sites hold another label (the first: (", c.stdout)

    def test_the_filter_and_the_check_filter_compose_them(self):
        reader = modelsynth.vtkMSLabelGridReader()
        reader.SetFileName(CITY)
        synthesis = modelsynth.vtkMSDiscreteSynthesis()
        output, errors = run_algorithm(synthesis, port=reader.GetOutputPort(),
                                       OutputSize=(48, 48, 1), BlockSize=(16, 16, 1), Seed=5,
                                       Connected=ROADS, FixedFile=PINS,
                                       Counts="%d:%d:%d" % (HOUSE, *HOUSES))
        self.assertEqual(errors, "")
        fd = output.GetFieldData()
        self.assertEqual(fd.GetArray("ConnectedComponents").GetValue(0), 1)
        houses = self.verify(labels_zyx(output)[0], "filter")
        self.assertEqual(fd.GetArray("CountAchieved").GetValue(0), houses)
        check = modelsynth.vtkMSCheckModel()
        check.AddExampleConnection(reader.GetOutputPort())
        checked, errors = run_algorithm(check, port=synthesis.GetOutputPort(), PinsFile=PINS,
                                        Counts="%d:%d:%d" % (HOUSE, *HOUSES), Connected=ROADS)
        self.assertEqual(errors, "")
        cfd = checked.GetFieldData()
        self.assertEqual(cfd.GetArray("Valid").GetValue(0), 1)
        self.assertEqual(cfd.GetArray("PinsKept").GetValue(0), 1)
        self.assertEqual(cfd.GetArray("PinsChecked").GetValue(0), 7)
        self.assertEqual(cfd.GetArray("CountsKept").GetValue(0), 1)
        self.assertEqual(cfd.GetArray("ConnectedKept").GetValue(0), 1)

    def test_open_network_counts_and_pins_in_a_region_equal_the_whole_run(self):
        common = ["--size", "48", "48", "1", "--block", "16", "16", "1", "--seed", "2",
                  "--connected", ROADS + ":open", "--fixed", PINS, "--count", "16:80:140",
                  "--outputs", "labels"]
        whole = fresh_folder("compose-open-whole")
        r = run_msynth("synthesize", CITY, *common, "--out", whole)
        self.assertEqual(r.returncode, 0, r.stderr)
        part = fresh_folder("compose-open-region")
        r = run_msynth("synthesize", CITY, *common, "--region", "8", "12", "0", "40", "36", "1",
                       "--out", part)
        self.assertEqual(r.returncode, 0, r.stderr)
        w = labels_zyx(read_label_grid(os.path.join(whole, "labels.vti")))[0]
        p = labels_zyx(read_label_grid(os.path.join(part, "labels.vti")))[0]
        self.assertTrue(np.array_equal(p, w[12:36, 8:40]))
        # Pins and counts hold in the world; LABELS:open's guarantee is per block (a component
        # closed off across blocks can remain, as without them: architecture.md), not checked.
        c = run_msynth("check", CITY, os.path.join(whole, "labels.vti"), "--fixed", PINS,
                       "--count", "16:80:140")
        self.assertEqual(c.returncode, 0, c.stdout + c.stderr)

    def test_combinations_that_cannot_work_are_one_line(self):
        size = ["--size", "48", "48", "1", "--block", "16", "16", "1"]
        expect_refused(self, ["synthesize", CITY, *size],
                       ["--connected", ROADS, "--fixed", PINS, "--count", "16:40:60",
                        "--region", "0", "0", "0", "16", "16", "1"],
                       "connected network but an open one", name="compose-refused")
        expect_refused(self, ["synthesize", CITY, *size],
                       ["--connected", ROADS, "--count", "16:40:60", "--mirror", "x"],
                       "cannot be combined with symmetry", name="compose-refused")


if __name__ == "__main__":
    unittest.main()
