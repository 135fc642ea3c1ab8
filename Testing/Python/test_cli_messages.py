"""What msynth says to a new user: bad input gets one line that names the option (as typed on the
command line, not the filter's property) and the file, says what is wrong and what is expected;
summaries count in words that agree with their numbers (1 block, 2 blocks)."""
import json
import os
import re
import unittest
import xml.etree.ElementTree as ET

import numpy as np

from msynth_testing import data, expect_refused, fresh_folder, labels_zyx, read_label_grid, run_msynth


def one_line(test, r, code):
    """Exit @p code and one line on stderr; the line."""
    test.assertEqual(r.returncode, code, r.stdout + r.stderr)
    lines = r.stderr.strip().splitlines()
    test.assertEqual(len(lines), 1, r.stderr)
    return lines[0]


def tile_names(tileset):
    """The tile names of a simple-tiled tileset, read from its XML here."""
    return [t.get("name") for t in ET.parse(tileset).getroot().find("tiles").findall("tile")]


class ImpossibleOutputTest(unittest.TestCase):
    def test_a_failure_blocks_cannot_mend_is_not_blamed_on_blocks(self):
        """WaveFunctionCollapse's Chess (N=2, size 47, periodic): a checkerboard cannot repeat
        with an odd period, so the whole model fails; the fallback to blocks cannot start (no
        label is next to itself), and its error ("no usable trivial start ... use whole-model
        synthesis") was reported instead of the whole model's failure. Now the reason comes
        first, before any attempt: the example repeats every 2 sites (issue 44, item 5)."""
        from vtkmodules.util.numpy_support import numpy_to_vtk
        from vtkmodules.vtkCommonDataModel import vtkImageData
        from vtkmodules.vtkIOImage import vtkPNGWriter
        folder = fresh_folder("cli-chess")
        board = np.array([[[0, 0, 0], [255, 255, 255]], [[255, 255, 255], [0, 0, 0]]], np.uint8)
        image = vtkImageData()
        image.SetDimensions(2, 2, 1)
        image.GetPointData().SetScalars(numpy_to_vtk(board.reshape(4, 3), deep=True))
        writer = vtkPNGWriter()
        writer.SetFileName(os.path.join(folder, "Chess.png"))
        writer.SetInputData(image)
        writer.Write()
        r = run_msynth("synthesize", os.path.join(folder, "Chess.png"), "--pattern", "2",
                       "--translate", "xy", "--size", "47", "47", "1", "--out",
                       os.path.join(folder, "out"))
        one_line(self, r, 1)
        self.assertIn("the example repeats every 2 sites along x", r.stderr)
        self.assertIn("a model that repeats every 47 sites along x cannot exist: use a multiple "
                      "of 2 (48)", r.stderr)
        self.assertNotIn("trivial start", r.stderr)
        r = run_msynth("synthesize", os.path.join(folder, "Chess.png"), "--pattern", "2",
                       "--translate", "xy", "--size", "48", "48", "1", "--out",
                       os.path.join(folder, "out"))
        self.assertEqual(r.returncode, 0, r.stderr)


class SubsetTest(unittest.TestCase):
    def test_an_unknown_subset_lists_the_subsets(self):
        r = run_msynth("synthesize", data("Tilesets/Lines.xml"), "--subset", "Foo", "--size", "8",
                       "8", "1", "--out", fresh_folder("messages-subset"))
        self.assertIn("has no subset named 'Foo'; its subsets: straight", one_line(self, r, 1))


class FixedSizeTest(unittest.TestCase):
    def test_synthesize_names_the_fixed_file_and_sizes(self):
        lines, drawn = data("Tilesets/Lines.xml"), data("Tilesets/lines-drawn.vti")
        dims = read_label_grid(drawn).GetDimensions()  # the pins' size, read independently
        expect_refused(self, ["synthesize", lines], ["--size", "30", "30", "1", "--fixed", drawn],
                       "--fixed '%s': the pinned sites cover %d x %d x %d sites, the output 30 x 30 x 1: "
                       "expected a grid of the output's size (--size 30 30 1)" % ((drawn,) + dims))

    def test_a_fixed_file_that_does_not_fit_is_named(self):
        picture = data("Tilesets/lines-drawn.png")
        expect_refused(self, ["synthesize", data("Examples/Village.vti")],
                       ["--size", "30", "30", "5", "--fixed", picture],
                       "--fixed '%s': a picture pins the tiles of a 2D tileset or the patterns of an image "
                       "sample; this run's rules come from a label grid example" % picture)
        r = run_msynth("synthesize", data("Samples/Rooms.png"), "--size", "30", "30", "1", "--fixed", picture,
                       "--out", os.path.join(fresh_folder("messages-fixed-sample"), "out"))
        line = one_line(self, r, 1)
        self.assertRegex(line, r"^msynth: error: --fixed '%s': pixel \(\d+, \d+\) has a colour the sample does "
                         "not have" % re.escape(picture))

    def test_pattern_names_the_fixed_file_and_sizes(self):
        fixed = data("Patterns/city-crossroads-170.vti")
        dims = read_label_grid(fixed).GetDimensions()
        expect_refused(self, ["pattern", data("Patterns/city-urban.vti")],
                       ["--size", "100", "100", "--fixed", fixed],
                       "--fixed '%s': the grid has %d x %d x %d sites, the output 100 x 100 x 1: expected "
                       "a grid of the output's size (--size 100 100)" % ((fixed,) + dims))


class SizeOptionsTest(unittest.TestCase):
    def test_region_names_the_bound_that_is_out(self):
        village = data("Examples/Village.vti")
        size = ["--size", "100", "100", "5"]
        for region, what in ((["90", "90", "0", "120", "120", "1"], "x1 = 120 is past the world's 100 sites in x"),
                             (["10", "90", "0", "20", "101", "1"], "y1 = 101 is past the world's 100 sites in y"),
                             (["10", "10", "3", "20", "20", "3"], "z0 = 3 is not below z1 = 3")):
            out = os.path.join(fresh_folder("messages-region"), "out")
            r = run_msynth("synthesize", village, *size, "--region", *region, "--out", out)
            line = one_line(self, r, 2)
            self.assertIn("--region %s: %s" % (" ".join(region), what), line)
            self.assertIn("(--size 100 100 5)", line)
            self.assertNotIn("OutputSize", line)
            self.assertFalse(os.path.exists(out))

    def test_a_sample_names_its_minimum_size(self):
        rooms = data("Samples/Rooms.png")
        for size, pattern in ((["2", "2", "1"], []), (["3", "9", "1"], ["--pattern", "4"])):
            n = int(pattern[1]) if pattern else 3
            r = run_msynth("synthesize", rooms, "--size", *size, *pattern,
                           "--out", os.path.join(fresh_folder("messages-sample"), "out"))
            line = one_line(self, r, 2)
            self.assertIn("--size %s: a picture from '%s' is at least %d x %d pixels, its pattern size "
                          "(--pattern %d)" % (" ".join(size), rooms, n, n, n), line)
        # At the pattern size it runs: one window, one site.
        out = fresh_folder("messages-sample-smallest")
        r = run_msynth("synthesize", rooms, "--size", "3", "3", "1", "--out", out)
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertIn("1 x 1 x 1 pattern sites (a 3 x 3 picture), 1 distinct pattern, 1 block (0 failed)",
                      r.stdout)

    def test_the_filter_says_the_same_in_its_properties(self):
        """Python and ParaView name the filter's properties, as the command names its options."""
        import modelsynth
        from msynth_testing import run_algorithm
        synthesis = modelsynth.vtkMSDiscreteSynthesis()
        synthesis.SetSampleFile(data("Samples/Rooms.png"))
        _, errors = run_algorithm(synthesis, OutputSize=[2, 2, 1], PatternSize=3)
        self.assertIn("OutputSize must be at least 1 on every axis and, for an image sample, PatternSize (3) "
                      "in x and y, got 2 2 1.", errors)
        tracks = modelsynth.vtkMSDiscreteSynthesis()
        tracks.SetTilesetFile(data("Tilesets/Tracks.xml"))
        _, errors = run_algorithm(tracks, OutputSize=[8, 8, 1], Connected="track")
        self.assertIn("Connected: 'track' is neither a label value nor a tile or label name of the tileset; "
                      "its tiles: Grass, Rail, Curve, Switch", errors)

    def test_a_block_larger_than_the_model_says_it_runs_whole(self):
        village = data("Examples/Village.vti")
        common = ["--size", "12", "12", "5", "--seed", "4", "--outputs", "labels"]
        whole = fresh_folder("messages-block-whole")
        r = run_msynth("synthesize", village, *common, "--out", whole)
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertNotIn("note: --block", r.stdout)
        # The village stands on label 1: a run without --ground says how to put it under the
        # model (it floated: roofs and walls with no ground), and one with it says nothing.
        self.assertIn("note: the example stands on a layer of label 1; --ground 1 puts one under "
                      "the model (and --empty 0 air around it)", r.stdout)
        r = run_msynth("synthesize", village, *common, "--ground", "1", "--out",
                       fresh_folder("messages-grounded"))
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertNotIn("note:", r.stdout)
        out = fresh_folder("messages-block-large")
        r = run_msynth("synthesize", village, *common, "--block", "40", "40", "5", "--out", out)
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertEqual(r.stderr, "")
        notes = [line for line in r.stdout.splitlines() if line.startswith("note: --block")]
        self.assertEqual(notes, ["note: --block 40 40 5 is larger than the model (12 x 12 x 5): the model "
                                 "runs whole, in one block"])
        self.assertIn(", 1 block (0 failed)", r.stdout)
        with open(os.path.join(out, "statistics.json")) as f:
            self.assertEqual(json.load(f)["Blocks"], 1)
        np.testing.assert_array_equal(labels_zyx(read_label_grid(os.path.join(out, "labels.vti"))),
                                      labels_zyx(read_label_grid(os.path.join(whole, "labels.vti"))))
        # Larger on one axis only: the blocks span the model there.
        r = run_msynth("synthesize", village, *common, "--block", "6", "6", "9",
                       "--out", fresh_folder("messages-block-z"))
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertIn("note: --block 6 6 9 is larger than the model (12 x 12 x 5): the blocks span the "
                      "model on the axes where they are larger", r.stdout)


class LabelOptionsTest(unittest.TestCase):
    def test_ground_names_the_example_and_its_labels(self):
        village = data("Examples/Village.vti")
        labels = sorted(set(labels_zyx(read_label_grid(village)).ravel().tolist()))
        listed = ", ".join(str(v) for v in labels)
        for option in ("--ground", "--empty"):
            expect_refused(self, ["synthesize", village], ["--size", "20", "20", "5", option, "9"],
                           "%s 9: label 9 does not occur in '%s'; its labels are %s" % (option, village, listed))

    def test_ground_of_a_tileset_lists_its_labels(self):
        lines = data("Tilesets/Lines.xml")
        info = run_msynth("info", lines)  # the labels as msynth info lists them
        self.assertEqual(info.returncode, 0, info.stderr)
        count = int(re.search(r"^labels: (\d+)", info.stdout, re.M).group(1))
        expect_refused(self, ["synthesize", lines], ["--size", "20", "20", "1", "--ground", "99"],
                       "--ground 99: label 99 does not occur in '%s'; its labels are %s (msynth info '%s' "
                       "lists them)" % (lines, ", ".join(str(b) for b in range(count)), lines))

    def test_tile_names_are_listed(self):
        lines = data("Tilesets/Lines.xml")
        expect_refused(self, ["synthesize", lines], ["--size", "20", "20", "1", "--count", "corners:1:5"],
                       "--count: the tileset has no tile or label named 'corners'; its tiles: " +
                       ", ".join(tile_names(lines)))
        tracks = data("Tilesets/Tracks.xml")
        for option, value, name in (("--connected", "track,turns", "track"), ("--connected", "Rail,turns", "turns")):
            expect_refused(self, ["synthesize", tracks], ["--size", "20", "20", "1", option, value],
                           "%s: '%s' is neither a label value nor a tile or label name of the tileset; its "
                           "tiles: %s" % (option, name, ", ".join(tile_names(tracks))))
        # In a stream and in pattern synthesis too.
        expect_refused(self, ["synthesize", tracks], ["--size", "40", "40", "1", "--block", "10", "10", "1",
                                                      "--stream", "--connected", "track"],
                       "--connected: 'track' is neither")
        city = data("Patterns/City.xml")
        expect_refused(self, ["pattern", data("Patterns/city-urban.vti")],
                       ["--tileset", city, "--size", "20", "20", "--connected", "bridge"],
                       "--connected: 'bridge' is neither a label value nor a tile or label name of the "
                       "tileset; its tiles: " + ", ".join(tile_names(city)[:20]))
        expect_refused(self, ["synthesize", tracks],
                       ["--size", "20", "20", "1", "--connected", "Rail", "--path", "bridge"],
                       "--path: 'bridge' is neither a site x,y[,z] nor a label value or a tile or label name "
                       "of the tileset; its tiles: " + ", ".join(tile_names(tracks)))


class InfoOfOutputsTest(unittest.TestCase):
    def test_info_describes_the_meshes_msynth_writes(self):
        """Issue 49 item 4: `info output/mesh.vtp` failed ("non-manifold: edge shared by 4 faces")
        and `info model.vtp` of a continuous run said "non-manifold", while check called it valid:
        a mesh msynth wrote is described (polygons per label or object type) and the check named."""
        out = fresh_folder("info-outputs")
        village, house = data("Examples/Village.vti"), data("Continuous/house.obj")
        for example, size in ((village, ("16", "16", "5")), (house, ("12", "12", "8"))):
            done = run_msynth("synthesize", example, "--size", *size, "--seed", "3", "--out",
                              os.path.join(out, os.path.basename(example)))
            self.assertEqual(done.returncode, 0, done.stderr)
        mesh = os.path.join(out, "Village.vti", "mesh.vtp")
        r = run_msynth("info", mesh)
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertIn("model: %s (written by msynth from %s)" % (mesh, village), r.stdout)
        counted = re.findall(r"  label (\d+): (\d+) polygons?", r.stdout)
        self.assertTrue(counted, r.stdout)
        polygons = int(re.search(r"polygons: (\d+)", r.stdout).group(1))
        self.assertEqual(sum(int(n) for _, n in counted), polygons)
        self.assertIn("check its labels: msynth check %s %s" % (
            village, os.path.join(out, "Village.vti", "labels.vti")), r.stdout)
        model = os.path.join(out, "house.obj", "model.vtp")
        r = run_msynth("info", model)
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertRegex(r.stdout, r"type \d+ \((wall|roof)\): \d+ polygons")
        self.assertIn("check it: msynth check %s %s" % (house, model), r.stdout)
        self.assertEqual(run_msynth("check", house, model).returncode, 0)
        # The label grid a run wrote is a model too (it was called an "example").
        labels = os.path.join(out, "Village.vti", "labels.vti")
        r = run_msynth("info", labels)
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertIn("model: %s (written by msynth from %s)" % (labels, village), r.stdout)
        self.assertNotIn("example: ", r.stdout)
        self.assertIn("check it: msynth check %s %s" % (village, labels), r.stdout)
        self.assertIn("example: %s" % village, run_msynth("info", village).stdout)


class OtherKindTest(unittest.TestCase):
    def test_an_option_of_the_other_kind_names_its_counterpart(self):
        """The first hour (issue 49): --block on a polyhedral example (or --blocks, --grounded on
        a label grid) was refused without the option that does it there."""
        house, village = data("Continuous/house.obj"), data("Examples/Village.vti")
        for example, given, counterpart in (
                (house, ["--block", "8", "8", "5"], "continuous synthesis takes --blocks N"),
                (village, ["--blocks", "8"], "take --block NX NY NZ"),
                (village, ["--grounded"], "take --ground LABEL"),
                (house, ["--ground", "1"], "--grounded stands a continuous model on the ground")):
            expect_refused(self, ["synthesize", example], ["--size", "12", "12", "5", *given],
                           counterpart)


class SwappedArgumentsTest(unittest.TestCase):
    def test_check_and_quality_refuse_the_model_where_the_example_goes(self):
        """Issue 49: `msynth check MODEL EXAMPLE` said "consistent" for a label grid and a picture
        (the pairs of the example occur in the model) or failed on the example as a model; now
        the model given first (a file msynth wrote: field data naming its example, a picture's
        text chunk, a streamed model's pieces) or an example given second (a tileset, an .obj)
        is refused in one line naming both files and the order."""
        out = fresh_folder("swapped")
        village, lines, rooms = (data("Examples/Village.vti"), data("Tilesets/Lines.xml"),
                                 data("Samples/Rooms.png"))
        house, city = data("Continuous/house.obj"), data("Patterns/city-urban.vti")
        runs = {
            "village": ("synthesize", village, "--size", "16", "16", "5", "--block", "8", "8",
                        "5", "--ground", "1", "--empty", "0"),
            "tiles": ("synthesize", lines, "--size", "12", "12", "1"),
            "rooms": ("synthesize", rooms, "--size", "32", "32", "1"),
            "houses": ("synthesize", house, "--size", "12", "12", "8"),
            "stream": ("synthesize", lines, "--size", "64", "64", "1", "--block", "16", "16", "1",
                       "--stream", "--slab", "32", "--outputs", "labels"),
            "city": ("pattern", city, "--size", "12", "12"),
        }
        for name, command in runs.items():
            done = run_msynth(*command, "--seed", "2", "--out", os.path.join(out, name))
            self.assertEqual(done.returncode, 0, done.stderr)
        model = {name: os.path.join(out, name, file) for name, file in (
            ("village", "labels.vti"), ("mesh", "mesh.vtp"), ("tiles", "labels.vti"),
            ("rooms", "picture.png"), ("houses", "model.vtp"), ("stream", "labels.pvti"),
            ("city", "labels.vti"))}
        model["mesh"] = os.path.join(out, "village", "mesh.vtp")
        for example, name in ((village, "village"), (village, "mesh"), (lines, "tiles"),
                              (rooms, "rooms"), (house, "houses"), (lines, "stream")):
            r = run_msynth("check", model[name], example)
            line = one_line(self, r, 2)
            self.assertIn("'%s'" % model[name], line)
            self.assertIn("'%s'" % example, line)
            self.assertIn("the order is msynth check EXAMPLE MODEL (msynth check %s %s)"
                          % (example, model[name]), line)
            self.assertNotIn("consistent", r.stdout)
            if name != "mesh":  # (a label grid's surface is described by info, not checked)
                r = run_msynth("check", example, model[name])
                self.assertEqual(r.returncode, 0, r.stdout + r.stderr)
        line = one_line(self, run_msynth("check", model["village"], village), 2)
        self.assertIn("'%s' is a model msynth wrote from %s and '%s' is not" % (
            model["village"], village, village), line)
        line = one_line(self, run_msynth("check", model["houses"], house), 2)
        self.assertIn("'%s' is an example (a polyhedron) and '%s' is a model msynth wrote"
                      % (house, model["houses"]), line)
        # quality EXEMPLAR... MODEL, the same.
        suburban = data("Patterns/city-suburban.vti")
        line = one_line(self, run_msynth("quality", suburban, model["city"], city), 2)
        self.assertIn("the order is msynth quality EXEMPLAR... MODEL (msynth quality %s %s %s)"
                      % (suburban, city, model["city"]), line)
        r = run_msynth("quality", city, model["city"])
        self.assertIn("KL 4H:", r.stdout)
        self.assertEqual(r.stderr, "")
        # The model alone: the example it was made from is named, with the command to run.
        for name, example in (("village", village), ("houses", house)):
            line = one_line(self, run_msynth("check", model[name]), 2)
            self.assertIn("EXAMPLE is missing: '%s' is a model msynth wrote from %s (msynth check "
                          "%s %s)" % (model[name], example, example, model[name]), line)
        self.assertIn("MODEL is required", one_line(self, run_msynth("check", village), 2))
        # Two models msynth wrote may be compared, either way.
        other = os.path.join(out, "village-again")
        done = run_msynth(*runs["village"], "--seed", "3", "--out", other)
        self.assertEqual(done.returncode, 0, done.stderr)
        for a, b in ((model["village"], os.path.join(other, "labels.vti")),
                     (os.path.join(other, "labels.vti"), model["village"])):
            r = run_msynth("check", a, b)
            self.assertEqual(r.stderr, "")
            self.assertIn("adjacent pairs of", r.stdout)


class SummaryTest(unittest.TestCase):
    def test_an_image_sample_says_sites_and_picture(self):
        rooms = data("Samples/Rooms.png")
        out = fresh_folder("messages-rooms")
        r = run_msynth("synthesize", rooms, "--size", "64", "40", "1", "--out", out)
        self.assertEqual(r.returncode, 0, r.stderr)
        grid = read_label_grid(os.path.join(out, "labels.vti")).GetDimensions()
        patterns = len(np.unique(labels_zyx(read_label_grid(os.path.join(out, "labels.vti")))))
        from vtkmodules.vtkIOImage import vtkPNGReader
        png = vtkPNGReader()
        png.SetFileName(os.path.join(out, "picture.png"))
        png.Update()
        picture = png.GetOutput().GetDimensions()
        self.assertEqual(picture[:2], (64, 40))
        self.assertIn("%d x %d x 1 pattern sites (a 64 x 40 picture), %d distinct patterns, 1 block (0 failed)"
                      % (grid[0], grid[1], patterns), r.stdout)
        self.assertEqual((grid[0], grid[1]), (62, 38))  # a 3 x 3 window at every site
        with open(os.path.join(out, "statistics.json")) as f:
            self.assertEqual(json.load(f)["size"], [64, 40, 1])  # the picture, as the summary says

    def test_a_continuous_run_counts_its_vertices_once(self):
        """Issue 49: `synthesize house.obj` printed "21021 arrangement vertices" while
        statistics.json recorded "Vertices": 21021 and, mirrored, a message of "10725 vertices"
        (the half it synthesized). One figure, one name: the console's, statistics.json's
        ArrangementVertices and its message's are the written arrangement's points."""
        from vtkmodules.vtkIOXML import vtkXMLPolyDataReader
        house = data("Continuous/house.obj")
        for extra in ([], ["--mirror", "x"]):
            out = fresh_folder("vertices-%d" % len(extra))
            r = run_msynth("synthesize", house, "--size", "16", "16", "8", "--seed", "3",
                           "--grounded", *extra, "--outputs", "mesh,labels", "--out", out)
            self.assertEqual(r.returncode, 0, r.stderr)
            printed = int(re.search(r"^(\d+) arrangement vertices, ", r.stdout, re.M).group(1))
            with open(os.path.join(out, "statistics.json")) as f:
                stats = json.load(f)
            self.assertNotIn("Vertices", stats)
            self.assertEqual(stats["ArrangementVertices"], printed)
            self.assertTrue(stats["Message"].startswith("%d arrangement vertices, " % printed),
                            stats["Message"])
            self.assertEqual(len(re.findall(r"\d+ (arrangement )?vertices", stats["Message"])),
                             1, stats["Message"])
            reader = vtkXMLPolyDataReader()
            reader.SetFileName(os.path.join(out, "arrangement.vtp"))
            reader.Update()
            self.assertEqual(reader.GetOutput().GetNumberOfPoints(), printed)
            if extra:
                self.assertIn("mirrored across the plane at 7.5", stats["Message"])

    def test_counts_agree_with_their_numbers(self):
        out = fresh_folder("messages-blocks")
        r = run_msynth("synthesize", data("Examples/Village.vti"), "--size", "24", "12", "5",
                       "--block", "12", "12", "5", "--overlap", "0", "0", "0", "--outputs", "labels",
                       "--out", out)
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertRegex(r.stdout, r", 2 blocks \(")
        r = run_msynth("pattern", data("Patterns/city-urban.vti"), "--size", "12", "12", "--seed", "1",
                       "--out", fresh_folder("messages-pattern"))
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertTrue(r.stdout.startswith("1 sample of 12 x 12 by BLOCKSS"), r.stdout)
        self.assertNotIn("(s)", r.stdout)
        self.assertIsNone(re.search(r"\b1 [a-z]+s\b", r.stdout), r.stdout)


if __name__ == "__main__":
    unittest.main()
