"""Worlds as functions of their inputs (issue: worlds, §1): `msynth synthesize --region` and the
filter's Region compute one box of a world from the blocks it depends on alone. The region equals
the same sites of a whole run (label grid and tileset; repair passes included), sits where it lies in the
world, passes the independent check (pairs recomputed from the example here, `msynth check` for
tilesets), and a far region of a 10^6 x 10^6 world takes well under a few seconds."""
import json
import os
import time
import unittest

import numpy as np

import modelsynth
from msynth_testing import (data, fresh_folder, labels_zyx, read_pieces, run_algorithm, violations,
                            write_label_image)
from msynth_testing import read_label_grid as read
from msynth_testing import run_msynth as msynth


class WorldsTest(unittest.TestCase):
    def test_label_grid_region_equals_the_whole_run(self):
        village = data("Examples/Village.vti")
        whole = fresh_folder("worlds-whole")
        common = ["--size", "150", "120", "5", "--block", "12", "12", "5", "--seed", "4"]
        done = msynth("synthesize", village, *common, "--out", whole)
        self.assertEqual(done.returncode, 0, done.stderr)
        region = fresh_folder("worlds-region")
        done = msynth("synthesize", village, *common, "--region", "17", "9", "0", "41", "30", "5",
                      "--out", region)
        self.assertEqual(done.returncode, 0, done.stderr)
        self.assertIn("the region's cone of", done.stdout + done.stderr)
        full = read(os.path.join(whole, "labels.vti"))
        part = read(os.path.join(region, "labels.vti"))
        self.assertEqual(part.GetDimensions(), (24, 21, 5))
        spacing = full.GetSpacing()
        expected = [full.GetOrigin()[a] + spacing[a] * (17, 9, 0)[a] for a in range(3)]
        np.testing.assert_allclose(part.GetOrigin(), expected)
        np.testing.assert_array_equal(labels_zyx(part), labels_zyx(full)[0:5, 9:30, 17:41])
        example = labels_zyx(read(village))
        self.assertEqual(violations(example, labels_zyx(part)), [])
        # Without repair passes the cone is narrower than this world: fewer blocks than a whole run.
        narrow = fresh_folder("worlds-narrow")
        done = msynth("synthesize", village, *common, "--no-repair", "--region", "17", "9", "0", "41",
                      "30", "5", "--out", narrow)
        self.assertEqual(done.returncode, 0, done.stderr)
        stats = json.load(open(os.path.join(narrow, "statistics.json")))
        self.assertLess(stats["Blocks"], json.load(open(os.path.join(whole, "statistics.json")))["Blocks"])

    def test_far_region_of_a_huge_tileset_world(self):
        out = fresh_folder("worlds-far")
        start = time.monotonic()
        done = msynth("synthesize", data("Tilesets/Lines.xml"), "--size", "1000000", "1000000", "1",
                      "--block", "16", "16", "1", "--region", "700000", "300000", "0", "700128",
                      "300096", "1", "--seed", "9", "--out", out)
        seconds = time.monotonic() - start
        self.assertEqual(done.returncode, 0, done.stderr)
        self.assertLess(seconds, 20)
        model = read(os.path.join(out, "labels.vti"))
        # Where it lies in the world (a tileset's region was once placed at twice its corner).
        np.testing.assert_allclose(model.GetOrigin(), (700000, 300000, 0))
        labels = labels_zyx(model)
        self.assertEqual(labels.shape, (1, 96, 128))
        self.assertGreater(len(np.unique(labels)), 2)  # not a blank model
        check = msynth("check", data("Tilesets/Lines.xml"), os.path.join(out, "labels.vti"))
        self.assertEqual(check.returncode, 0, check.stdout + check.stderr)

    def test_filter_region_and_refusals(self):
        reader = modelsynth.vtkMSLabelGridReader()
        reader.SetFileName(data("Examples/Village.vti"))
        synthesis = modelsynth.vtkMSDiscreteSynthesis()
        whole, errors = run_algorithm(synthesis, port=reader.GetOutputPort(), OutputSize=[40, 40, 5],
                                      BlockSize=[10, 10, 5], Seed=2)
        self.assertEqual(errors, "")
        full = labels_zyx(whole).copy()
        part, errors = run_algorithm(synthesis, Region=[5, 20, 0, 25, 40, 5])
        self.assertEqual(errors, "")
        np.testing.assert_array_equal(labels_zyx(part), full[:, 20:40, 5:25])
        _, errors = run_algorithm(synthesis, Region=[5, 20, 0, 25, 41, 5])
        self.assertIn("is not a non-empty box inside OutputSize (x0 y0 z0 x1 y1 z1): y1 is past "
                      "OutputSize's 40.", errors)
        _, errors = run_algorithm(synthesis, Region=[0, 0, 0, 8, 8, 5], Mirror=[1, 0, 0])
        self.assertIn("a region of a world takes no symmetry", errors)
        done = msynth("synthesize", data("Examples/Village.vti"), "--size", "20", "20", "5",
                      "--region", "0", "0", "0", "30", "5", "5", "--out", fresh_folder("worlds-bad"))
        self.assertEqual(done.returncode, 2)
        self.assertEqual(len(done.stderr.strip().splitlines()), 1, done.stderr)
        self.assertIn("--region 0 0 0 30 5 5: x1 = 30 is past the world's 20 sites in x", done.stderr)

    def test_requested_extents_compute_only_their_cone(self):
        # The streaming pipeline's way (issue: worlds, section 3): the whole extent is the world,
        # and an Extract Subset downstream computes just its extent from its cone.
        from vtkmodules.vtkImagingCore import vtkExtractVOI
        lines = data("Tilesets/Lines.xml")

        def synthesis(size):
            s = modelsynth.vtkMSDiscreteSynthesis()
            s.SetTilesetFile(lines)
            s.SetOutputSize(*size)
            s.SetBlockSize(32, 32, 1)
            s.SetSeed(3)
            return s

        streamed = synthesis((200, 150, 1))
        streamed.SetComputeRequestedExtent(True)
        voi = vtkExtractVOI()
        voi.SetInputConnection(streamed.GetOutputPort())
        voi.SetVOI(50, 120, 40, 99, 0, 0)
        voi.Update()
        self.assertEqual(voi.GetOutput().GetExtent(), (50, 120, 40, 99, 0, 0))
        whole = synthesis((200, 150, 1))
        whole.Update()
        np.testing.assert_array_equal(labels_zyx(voi.GetOutput()),
                                      labels_zyx(whole.GetOutput())[:, 40:100, 50:121])
        # A far window of a 10^6 x 10^6 world: seconds, and only the blocks of its cone.
        streamed.SetOutputSize(1000000, 1000000, 1)
        voi.SetVOI(500000, 500063, 700000, 700047, 0, 0)
        start = time.perf_counter()
        voi.Update()
        seconds = time.perf_counter() - start
        out = voi.GetOutput()
        self.assertEqual(out.GetDimensions(), (64, 48, 1))
        blocks = out.GetFieldData().GetArray("Blocks").GetValue(0)
        self.assertLess(blocks, 10000)
        self.assertLess(seconds, 60 if os.environ.get("MSYNTH_SANITIZED") else 20)
        check = fresh_folder("worlds-extent")
        from vtkmodules.vtkIOXML import vtkXMLImageDataWriter
        writer = vtkXMLImageDataWriter()
        writer.SetInputData(out)
        writer.SetFileName(os.path.join(check, "window.vti"))
        writer.Write()
        done = msynth("check", lines, os.path.join(check, "window.vti"))
        self.assertEqual(done.returncode, 0, done.stdout + done.stderr)

    def test_regions_take_the_pins_that_fall_in_them(self):
        """A pin grid placed by its extent (a 16 x 12 grid from site 30, 20 of the world): regions
        equal the whole run's window with the same pins, keep every pin inside them, and pass
        `msynth check`; the filter's Region agrees."""
        lines = data("Tilesets/Lines.xml")
        common = ["--size", "96", "80", "1", "--block", "16", "16", "1", "--seed", "3"]
        source = fresh_folder("worlds-pins-source")
        done = msynth("synthesize", lines, "--size", "32", "32", "1", "--seed", "9", "--outputs", "labels",
                      "--out", source)
        self.assertEqual(done.returncode, 0, done.stderr)
        drawn = labels_zyx(read(os.path.join(source, "labels.vti")))[0]
        pins = np.full((12, 16), -1, dtype=np.int32)  # [y, x]
        pins[2:8, 3:9] = drawn[10:16, 10:16]  # a drawn patch
        pins[11, 15] = drawn[4, 4]  # a lone tile
        placed = write_label_image(pins, os.path.join(fresh_folder("worlds-pins-grid"), "placed.vti"), (30, 20))

        whole = fresh_folder("worlds-pins-whole")
        done = msynth("synthesize", lines, *common, "--fixed", placed, "--outputs", "labels", "--out", whole)
        self.assertEqual(done.returncode, 0, done.stderr)
        full = labels_zyx(read(os.path.join(whole, "labels.vti")))[0]
        kept = pins >= 0
        np.testing.assert_array_equal(full[20:32, 30:46][kept], pins[kept])
        for x0, y0, x1, y1 in ((25, 15, 60, 45), (40, 28, 50, 34), (0, 0, 20, 20)):
            out = fresh_folder("worlds-pins-region")
            done = msynth("synthesize", lines, *common, "--fixed", placed, "--region", str(x0), str(y0), "0",
                          str(x1), str(y1), "1", "--outputs", "labels", "--out", out)
            self.assertEqual(done.returncode, 0, done.stderr)
            part = labels_zyx(read(os.path.join(out, "labels.vti")))[0]
            np.testing.assert_array_equal(part, full[y0:y1, x0:x1])
            inside = np.zeros((80, 96), dtype=bool)
            inside[20:32, 30:46] = kept
            window = inside[y0:y1, x0:x1]
            world_pins = np.full((80, 96), -1, dtype=np.int32)
            world_pins[20:32, 30:46] = pins
            np.testing.assert_array_equal(part[window], world_pins[y0:y1, x0:x1][window])
            check = msynth("check", lines, os.path.join(out, "labels.vti"))
            self.assertEqual(check.returncode, 0, check.stdout + check.stderr)
        synthesis = modelsynth.vtkMSDiscreteSynthesis()
        part, errors = run_algorithm(synthesis, TilesetFile=lines, OutputSize=[96, 80, 1],
                                     BlockSize=[16, 16, 1], Seed=3, FixedFile=placed,
                                     Region=[28, 18, 0, 52, 40, 1])
        self.assertEqual(errors, "")
        np.testing.assert_array_equal(labels_zyx(part)[0], full[18:40, 28:52])
        # The bundled drawn map: its large patch's placement block has to grow (its first size
        # cannot be solved), so the region's window grows with it and the region runs again.
        drawn_map = data("Tilesets/lines-drawn.vti")
        small = ["--size", "24", "24", "1", "--block", "12", "12", "1", "--seed", "2", "--fixed", drawn_map]
        whole = fresh_folder("worlds-pins-drawn-whole")
        self.assertEqual(msynth("synthesize", lines, *small, "--outputs", "labels", "--out", whole).returncode, 0)
        full = labels_zyx(read(os.path.join(whole, "labels.vti")))[0]
        out = fresh_folder("worlds-pins-drawn-region")
        done = msynth("synthesize", lines, *small, "--region", "4", "4", "0", "16", "20", "1", "--outputs",
                      "labels", "--out", out)
        self.assertEqual(done.returncode, 0, done.stderr)
        np.testing.assert_array_equal(labels_zyx(read(os.path.join(out, "labels.vti")))[0], full[4:20, 4:16])
        drawn_whole = full
        # A stream with the same pins equals the whole run, slab by slab, and `msynth check` passes
        # piece by piece; --resume keeps slabs made with the same pins only.
        whole = fresh_folder("worlds-pins-whole")
        self.assertEqual(msynth("synthesize", lines, *common, "--fixed", placed, "--outputs", "labels",
                                "--out", whole).returncode, 0)
        full = labels_zyx(read(os.path.join(whole, "labels.vti")))[0]
        out = fresh_folder("worlds-pins-stream")
        done = msynth("synthesize", lines, *common, "--fixed", placed, "--stream", "--slab", "20",
                      "--out", out)
        self.assertEqual(done.returncode, 0, done.stderr)
        streamed = labels_zyx(read_pieces(os.path.join(out, "labels.pvti")))[0]
        np.testing.assert_array_equal(streamed, full)
        np.testing.assert_array_equal(streamed[20:32, 30:46][kept], pins[kept])
        check = msynth("check", lines, os.path.join(out, "labels.pvti"))
        self.assertEqual(check.returncode, 0, check.stdout + check.stderr)
        # The drawn map streamed: the window grows with the placement there too.
        out = fresh_folder("worlds-pins-drawn-stream")
        done = msynth("synthesize", lines, *small, "--stream", "--slab", "5", "--out", out)
        self.assertEqual(done.returncode, 0, done.stderr)
        np.testing.assert_array_equal(labels_zyx(read_pieces(os.path.join(out, "labels.pvti")))[0], drawn_whole)
    def test_open_networks_in_regions_and_streams(self):
        """`--connected LABELS:open` (what connected means in a world without bounds: no component
        closed off) is kept block by block on what each block reads, so a region and a stream equal
        the whole run; `msynth check --connected LABELS:open` counts the components that reach no
        border of the file (a region's border counts as reaching out)."""
        lines = data("Tilesets/Lines.xml")
        common = ["--size", "96", "80", "1", "--block", "16", "16", "1", "--seed", "1",
                  "--connected", "line,corner:open", "--outputs", "labels"]
        whole = fresh_folder("worlds-open-whole")
        done = msynth("synthesize", lines, *common, "--out", whole)
        self.assertEqual(done.returncode, 0, done.stderr)
        full = labels_zyx(read(os.path.join(whole, "labels.vti")))[0]
        with open(os.path.join(whole, "statistics.json")) as f:
            self.assertGreater(json.load(f)["Connected"]["redone"], 0)
        region = fresh_folder("worlds-open-region")
        done = msynth("synthesize", lines, *common, "--region", "30", "20", "0", "70", "60", "1", "--out", region)
        self.assertEqual(done.returncode, 0, done.stderr)
        np.testing.assert_array_equal(labels_zyx(read(os.path.join(region, "labels.vti")))[0], full[20:60, 30:70])
        stream = fresh_folder("worlds-open-stream")
        done = msynth("synthesize", lines, *common, "--stream", "--slab", "20", "--out", stream)
        self.assertEqual(done.returncode, 0, done.stderr)
        np.testing.assert_array_equal(labels_zyx(read_pieces(os.path.join(stream, "labels.pvti")))[0], full)
        done = msynth("check", lines, os.path.join(region, "labels.vti"), "--connected", "line,corner:open")
        self.assertIn("closed off", done.stdout)
        # The check's meaning on grids made here: a lone wall site inside a field of air is closed
        # off; one on the border reaches out.
        for where, closed in (((3, 3), 1), ((0, 3), 0)):
            grid = np.zeros((6, 6), dtype=np.int32)
            grid[where[1], where[0]] = 2
            path = write_label_image(grid, os.path.join(fresh_folder("worlds-open-grid"), "grid.vti"))
            done = msynth("check", data("Examples/Village.vti"), path, "--connected", "2:open")
            self.assertIn("%d of them closed off" % closed, done.stdout, done.stdout + done.stderr)


if __name__ == "__main__":
    unittest.main()
