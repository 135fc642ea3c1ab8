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
from vtkmodules.vtkCommonCore import vtkIntArray
from vtkmodules.vtkCommonDataModel import vtkImageData

from msynth_testing import (data, expect_refused, fresh_folder, labels_zyx, read_label_grid, read_pieces,
                            run_algorithm, run_msynth)

VILLAGE = data("Examples/Village.vti")
LINES = data("Tilesets/Lines.xml")
# (example, size, block, counts as label or tile -> (min, max))
CASES = [
    (VILLAGE, ["24", "24", "5"], ["12", "12", "5"], {"2": (150, 300), "3": (100, 180)}),
    (LINES, ["24", "24", "1"], ["12", "12", "1"], {"corner": (100, 150), "empty": (200, 400)}),
]

# A count of corners in a 96 x 80 Lines world (about 2300 unsteered): (min, max).
WORLD_CORNERS = (1200, 1800)

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
                (["--count", "roof:1:2"], "is not a label value")]:
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
    def test_counts_in_regions_and_streams_of_a_world(self):
        """A count of a world is shared over its blocks by position alone (LabelCounts.h): regions
        equal the whole run's window and a stream equals the whole run; the whole world's total,
        counted here from the written labels (whole and streamed), is in range."""
        common = ["--size", "96", "80", "1", "--block", "16", "16", "1", "--seed", "3", "--count",
                  "corner:%d:%d" % WORLD_CORNERS, "--outputs", "labels"]
        whole = fresh_folder("counts-world-whole")
        r = run_msynth("synthesize", LINES, *common, "--out", whole)
        self.assertEqual(r.returncode, 0, r.stderr)
        full = read_label_grid(os.path.join(whole, "labels.vti"))
        self.assertTrue(WORLD_CORNERS[0] <= counted(full, "corner") <= WORLD_CORNERS[1])
        labels = labels_zyx(full)[0]
        for x0, y0, x1, y1 in ((0, 0, 30, 24), (38, 36, 58, 52), (60, 50, 96, 80)):
            out = fresh_folder("counts-world-region")
            r = run_msynth("synthesize", LINES, *common, "--region", str(x0), str(y0), "0", str(x1),
                           str(y1), "1", "--out", out)
            self.assertEqual(r.returncode, 0, r.stderr)
            part = labels_zyx(read_label_grid(os.path.join(out, "labels.vti")))[0]
            np.testing.assert_array_equal(part, labels[y0:y1, x0:x1])
        out = fresh_folder("counts-world-stream")
        r = run_msynth("synthesize", LINES, *common, "--stream", "--slab", "20", "--out", out)
        self.assertEqual(r.returncode, 0, r.stderr)
        streamed = read_pieces(os.path.join(out, "labels.pvti"))
        np.testing.assert_array_equal(labels_zyx(streamed)[0], labels)
        self.assertTrue(WORLD_CORNERS[0] <= counted(streamed, "corner") <= WORLD_CORNERS[1])
        with open(os.path.join(out, "statistics.json")) as f:
            self.assertEqual(json.load(f)["Counts"][0]["achieved"], counted(streamed, "corner"))
        # The filter's Region with Counts: the same window.
        part, errors = run_algorithm(modelsynth.vtkMSDiscreteSynthesis(), TilesetFile=LINES,
                                     OutputSize=(96, 80, 1), BlockSize=(16, 16, 1), Seed=3,
                                     Counts="corner:%d:%d" % WORLD_CORNERS, Region=(28, 18, 0, 52, 40, 1))
        self.assertEqual(errors, "")
        np.testing.assert_array_equal(labels_zyx(part)[0], labels[18:40, 28:52])

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

    def test_counts_per_guide_region(self):
        """--count region=R:L:MIN:MAX with a guide whose Region array halves the output: in blocks,
        corners many on the left (about 90 unsteered) and few on the right; whole, few on the right
        (a whole model does not reliably reach a region's minimum far above its unsteered count);
        counted here by halves, and again by `msynth check --guide`."""
        guide = data("Tilesets/lines-halves.vti")
        runs = [(["--block", "12", "12", "1"], {("corner", 0): (100, 140), ("corner", 1): (0, 24)}),
                ([], {("corner", 1): (0, 24)})]
        for blocks, wanted in runs:
            args = ["--guide", guide]
            for (name, region), (lo, hi) in wanted.items():
                args += ["--count", "region=%d:%s:%d:%d" % (region, name, lo, hi)]
            for seed in ("1", "2"):
                out = fresh_folder("counts-region-%d-%s" % (len(blocks), seed))
                r = run_msynth("synthesize", LINES, "--size", "24", "24", "1", *blocks, "--seed", seed,
                               *args, "--outputs", "labels", "--out", out)
                self.assertEqual(r.returncode, 0, r.stderr)
                path = os.path.join(out, "labels.vti")
                labels = labels_zyx(read_label_grid(path))[0]
                with open(os.path.join(out, "statistics.json")) as f:
                    reported = {(c["label"], c.get("region")): c for c in json.load(f)["Counts"]}
                for (name, region), (lo, hi) in wanted.items():
                    half = labels[:, :12] if region == 0 else labels[:, 12:]
                    n = int(np.isin(half, LINES_TILES[name]).sum())
                    self.assertTrue(lo <= n <= hi, "%s in region %d: %d, not %d to %d (%s, seed %s)"
                                    % (name, region, n, lo, hi, blocks, seed))
                    self.assertEqual(reported[(name, region)]["achieved"], n)
                c = run_msynth("check", LINES, path, *args)
                self.assertEqual(c.returncode, 0, c.stdout + c.stderr)
                self.assertIn("count kept: corner in guide region 1", c.stdout)
        # The same through the check filter, without the command (GUI, Python): its CountGuideFile.
        reader = modelsynth.vtkMSLabelGridReader()
        reader.SetFileName(path)
        check, error = run_algorithm(modelsynth.vtkMSCheckModel(), port=reader.GetOutputPort(),
                                     TilesetFile=LINES, CountGuideFile=guide,
                                     Counts="region=1:corner:0:24,region=1:corner:50:60")
        self.assertEqual(error, "")
        fields = check.GetFieldData()
        achieved = [fields.GetArray("CountAchieved").GetValue(i) for i in range(2)]
        self.assertEqual(achieved, [int(np.isin(labels[:, 12:], LINES_TILES["corner"]).sum())] * 2)
        self.assertEqual(fields.GetArray("CountsKept").GetValue(0), 0)  # 50 to 60 is missed
        # The checker finds a region count the model does not keep.
        c = run_msynth("check", LINES, path, "--guide", guide, "--count", "region=1:corner:50:60")
        self.assertEqual(c.returncode, 1, c.stdout + c.stderr)
        self.assertIn("count missed: corner in guide region 1 holds", c.stdout)
        # A guide that is not a volume, and a region count without a guide: one line each.
        bad = os.path.join(fresh_folder("counts-bad-guide"), "guide.vti")
        with open(bad, "w") as f:
            f.write("garbage")
        for extra, message in [(["--guide", bad], "not a readable guide volume"),
                               ([], "give the guide with --guide")]:
            c = run_msynth("check", LINES, path, *extra, "--count", "region=1:corner:0:60")
            self.assertNotEqual(c.returncode, 0)
            self.assertIn(message, c.stderr)
            self.assertEqual(len(c.stderr.strip().splitlines()), 1, c.stderr)
        # Infeasible region counts are one line before any work.
        for extra, message in [
                (["--count", "region=0:corner:300:400"],
                 "asks for at least 300 sites, but the region has 288"),
                (["--count", "region=3:corner:0:4"], "the guide's region 3 holds no site of the output"),
                (["--count", "corner:0:400", "--count", "region=1:corner:0:4"],
                 "counted both in the whole output and in a guide region")]:
            expect_refused(self, ["synthesize"], [LINES, "--size", "24", "24", "1", "--guide", guide, *extra],
                           message, "counts-region-bad")
        r = run_msynth("synthesize", LINES, "--size", "24", "24", "1", "--count", "region=0:corner:0:4")
        self.assertNotEqual(r.returncode, 0)
        self.assertIn("needs a guide with regions", r.stderr)

    def test_the_filter_counts_per_guide_region(self):
        guide = vtkImageData()
        guide.SetDimensions(2, 1, 1)
        regions = vtkIntArray()
        regions.SetName("Region")
        for value in (0, 1):
            regions.InsertNextValue(value)
        guide.GetPointData().AddArray(regions)
        synthesis = modelsynth.vtkMSDiscreteSynthesis()
        synthesis.SetInputDataObject(1, guide)
        output, errors = run_algorithm(synthesis, TilesetFile=LINES, OutputSize=(20, 20, 1),
                                       BlockSize=(10, 10, 1), Seed=3,
                                       Counts="region=0:corner:0:20, region=1:corner:70:120")
        self.assertEqual(errors, "")
        fd = output.GetFieldData()
        labels = labels_zyx(output)[0]
        left = int(np.isin(labels[:, :10], LINES_TILES["corner"]).sum())
        right = int(np.isin(labels[:, 10:], LINES_TILES["corner"]).sum())
        self.assertTrue(left <= 20 and 70 <= right <= 120, (left, right))
        self.assertEqual([fd.GetArray("CountAchieved").GetValue(i) for i in range(2)], [left, right])
        self.assertEqual([fd.GetArray("CountRegion").GetValue(i) for i in range(2)], [0, 1])


if __name__ == "__main__":
    unittest.main()
