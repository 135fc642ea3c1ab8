"""Pinned sites (--fixed, the filter's Fixed input): a partly drawn map is completed. Every pin
is kept, every model passes the independent check (`msynth check`, or pairs recomputed from the
example here), and pins that cannot hold are one line before any work, with nothing written."""
import os
import subprocess
import unittest

import numpy as np
from vtkmodules.util.numpy_support import numpy_to_vtk, vtk_to_numpy
from vtkmodules.vtkCommonDataModel import vtkImageData
from vtkmodules.vtkIOImage import vtkPNGReader
from vtkmodules.vtkIOXML import vtkXMLImageDataWriter

import modelsynth
from msynth_testing import (BIN, data, fresh_folder, labels_zyx, read_png, run_algorithm, tmp,
                            violations, write_png)

MSYNTH = os.path.join(BIN, "msynth")
TIMEOUT = 300 if os.environ.get("MSYNTH_SANITIZED") else 120


def msynth(*args):
    return subprocess.run([MSYNTH, *args], capture_output=True, text=True, timeout=TIMEOUT)


def read_labels(path):
    reader = modelsynth.vtkMSLabelGridReader()
    reader.SetFileName(path)
    reader.Update()
    return labels_zyx(reader.GetOutput())


def image_of(labels_zyx_array):
    nz, ny, nx = labels_zyx_array.shape
    image = vtkImageData()
    image.SetDimensions(nx, ny, nz)
    a = numpy_to_vtk(np.ascontiguousarray(labels_zyx_array).ravel().astype(np.int32), deep=True)
    a.SetName("Label")
    image.GetPointData().SetScalars(a)
    return image


def write_pins(path, labels_zyx_array):
    w = vtkXMLImageDataWriter()
    w.SetInputData(image_of(labels_zyx_array))
    w.SetFileName(path)
    assert w.Write() == 1
    return path


def drawn_map_picture(pins_yx, path):
    """The picture a user draws of the Lines map `pins_yx` ([y, x], -1 free): each pinned site's
    tile image, composed by vtkMSTileImage, and fully transparent cells where sites are free.
    Returns the tile size."""
    grid = image_of(np.where(pins_yx < 0, 0, pins_yx)[None, :, :])
    tiles = modelsynth.vtkMSTileImage()
    tiles.SetInputData(grid)
    tiles.SetTilesetFile(data("Tilesets/Lines.xml"))
    tiles.Update()
    out = tiles.GetOutput()
    w, h, _ = out.GetDimensions()
    t = w // pins_yx.shape[1]
    rgba = vtk_to_numpy(out.GetPointData().GetScalars()).reshape(h, w, 4).copy()
    for y, x in zip(*np.nonzero(pins_yx < 0)):
        rgba[y * t:(y + 1) * t, x * t:(x + 1) * t, :] = 0
    write_png(rgba[::-1], path)  # composed rows from the bottom
    return t


class PinsTest(unittest.TestCase):
    def complete(self, example, size, block, patches, checked):
        """Pins `patches` (index tuples into a [z, y, x] grid) of a model of `example`, completes
        them whole and in blocks of `block`, and checks every run's `checked` output (the file
        `msynth check` reads) and that every pin is kept."""
        name = os.path.splitext(os.path.basename(example))[0]
        source = fresh_folder("pins-%s-source" % name)
        r = msynth("synthesize", data(example), "--size", *size, "--seed", "4", "--out", source)
        self.assertEqual(r.returncode, 0, r.stderr)
        drawn = read_labels(os.path.join(source, "labels.vti"))
        pins = np.full(drawn.shape, -1, dtype=np.int32)
        for patch in patches:
            pins[patch] = drawn[patch]
        path = write_pins(tmp("%s-pins.vti" % name), pins)
        for extra in ([], ["--block", *block]):
            out = fresh_folder("pins-" + name)
            r = msynth("synthesize", data(example), "--size", *size, "--seed", "9", "--fixed", path,
                       "--out", out, *extra)
            self.assertEqual(r.returncode, 0, r.stderr)
            model = read_labels(os.path.join(out, "labels.vti"))
            kept = pins >= 0
            self.assertTrue(np.array_equal(model[kept], pins[kept]), extra)
            self.assertGreater(len(np.unique(model[~kept])), 1, "the rest is synthesized")
            check = msynth("check", data(example), os.path.join(out, checked))
            self.assertEqual(check.returncode, 0, check.stdout + check.stderr)

    def test_a_drawn_patch_of_a_tileset_map_is_completed(self):
        # A map of the Lines tileset; a patch of it (a hand-drawn part) and a lone tile pinned.
        self.complete("Tilesets/Lines.xml", ("24", "24", "1"), ("12", "12", "1"),
                      [np.s_[0, 8:14, 9:15], np.s_[0, 20, 2]], "labels.vti")

    def test_a_map_drawn_as_a_picture_is_completed(self):
        # The bundled drawn map as a picture: its tiles' images, transparent where free.
        pins = read_labels(data("Tilesets/lines-drawn.vti"))[0]
        path = tmp("lines-drawn.png")
        t = drawn_map_picture(pins, path)
        kept = pins >= 0
        for extra in ([], ["--block", "12", "12", "1"]):
            out = fresh_folder("pins-picture")
            r = msynth("synthesize", data("Tilesets/Lines.xml"), "--size", "24", "24", "1",
                       "--seed", "3", "--fixed", path, "--out", out, *extra)
            self.assertEqual(r.returncode, 0, r.stderr)
            model = read_labels(os.path.join(out, "labels.vti"))[0]
            self.assertTrue(np.array_equal(model[kept], pins[kept]), extra)
            self.assertGreater(len(np.unique(model[~kept])), 1, "the rest is synthesized")
            check = msynth("check", data("Tilesets/Lines.xml"), os.path.join(out, "labels.vti"))
            self.assertEqual(check.returncode, 0, check.stdout + check.stderr)
        # The bundled picture (README) is that same map.
        r = msynth("synthesize", data("Tilesets/Lines.xml"), "--size", "24", "24", "1", "--seed",
                   "3", "--fixed", data("Tilesets/lines-drawn.png"), "--out", out)
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertTrue(np.array_equal(read_labels(os.path.join(out, "labels.vti"))[0][kept],
                                       pins[kept]))
        # The filter: a PNG reader on the Fixed input of a tileset run.
        png = vtkPNGReader()
        png.SetFileName(path)
        synthesis = modelsynth.vtkMSDiscreteSynthesis()
        synthesis.SetTilesetFile(data("Tilesets/Lines.xml"))
        synthesis.SetFixedConnection(png.GetOutputPort())
        result, errors = run_algorithm(synthesis, OutputSize=(24, 24, 1), Seed=5)
        self.assertEqual(errors, "")
        self.assertTrue(np.array_equal(labels_zyx(result)[0][kept], pins[kept]))
        # FixedFile (the GUI's file field of the tileset proxy, which has no inputs).
        synthesis = modelsynth.vtkMSDiscreteSynthesis()
        synthesis.SetTilesetFile(data("Tilesets/Lines.xml"))
        synthesis.SetFixedFile(path)
        result, errors = run_algorithm(synthesis, OutputSize=(24, 24, 1), Seed=6)
        self.assertEqual(errors, "")
        self.assertTrue(np.array_equal(labels_zyx(result)[0][kept], pins[kept]))
        # A cell that is no tile: one line naming the file and the site; nothing written.
        spoiled = pins.copy()
        drawn_map_picture(spoiled, path)
        rgba = read_png(path)
        y, x = [int(v[0]) for v in np.nonzero(kept)]
        rgba[(23 - y) * t + 1, x * t + 1, :3] = (255, 0, 255)  # rows from the top in the file
        write_png(rgba, path)
        bad = tmp("pins-picture-bad")
        subprocess.run(["rm", "-rf", bad])
        r = msynth("synthesize", data("Tilesets/Lines.xml"), "--size", "24", "24", "1",
                   "--fixed", path, "--out", bad)
        self.assertEqual(r.returncode, 1, r.stderr)
        self.assertEqual(r.stderr.count("\n"), 1, r.stderr)
        self.assertIn(path, r.stderr)
        self.assertIn("site (%d, %d)" % (x, y), r.stderr)
        self.assertFalse(os.path.exists(bad))
        write_png(rgba[:-1], path)  # not a whole number of tiles
        r = msynth("synthesize", data("Tilesets/Lines.xml"), "--size", "24", "24", "1",
                   "--fixed", path, "--out", bad)
        self.assertEqual(r.returncode, 1, r.stderr)
        self.assertIn("not a whole number of", r.stderr)
        r = msynth("synthesize", data("Examples/Village.vti"), "--size", "24", "24", "5",
                   "--fixed", path, "--out", bad)
        self.assertEqual(r.returncode, 1, r.stderr)
        self.assertIn("a picture pins the tiles of a 2D tileset or the patterns of an image sample",
                      r.stderr)

    def test_an_image_sample_keeps_a_pinned_patch(self):
        # The patterns of a City picture, a patch pinned; the picture passes the window check.
        self.complete("Samples/City.png", ("40", "40", "1"), ("20", "20", "1"), [np.s_[0, 10:16, 10:16]],
                      "picture.png")

    def test_a_sample_picture_partly_drawn_is_completed(self):
        # A Rooms picture of 24 x 24 pixels (22 x 22 sites of 3 x 3 patterns) with everything but
        # a 10 x 10 patch made transparent: the sites whose windows lie in the patch are pinned
        # to the patterns drawn there, the rest completed, and the picture passes the check.
        source = fresh_folder("pins-sample-source")
        args = ["--size", "24", "24", "1", "--pattern", "3"]
        r = msynth("synthesize", data("Samples/Rooms.png"), *args, "--seed", "4", "--out", source)
        self.assertEqual(r.returncode, 0, r.stderr)
        drawn = read_png(os.path.join(source, "picture.png"))
        if drawn.shape[2] == 3:
            drawn = np.concatenate([drawn, np.full(drawn.shape[:2] + (1,), 255, np.uint8)], axis=2)
        patch = np.zeros(drawn.shape[:2], bool)
        patch[5:15, 5:15] = True
        drawn[~patch] = 0
        path = tmp("rooms-drawn.png")
        write_png(drawn, path)
        out = fresh_folder("pins-sample")
        r = msynth("synthesize", data("Samples/Rooms.png"), *args, "--seed", "9", "--fixed", path,
                   "--out", out)
        self.assertEqual(r.returncode, 0, r.stderr)
        before = read_labels(os.path.join(source, "labels.vti"))[0]
        after = read_labels(os.path.join(out, "labels.vti"))[0]
        self.assertEqual(before.shape, (22, 22))
        rows = [21 - row for row in range(5, 13)]  # windows starting at pixel rows 5..12
        self.assertTrue(np.array_equal(after[rows, 5:13], before[rows, 5:13]))
        picture = read_png(os.path.join(out, "picture.png"))
        self.assertTrue(np.array_equal(picture[5:15, 5:15, :3], drawn[5:15, 5:15, :3]))
        self.assertFalse(np.array_equal(after, before), "the rest is synthesized anew")
        check = msynth("check", data("Samples/Rooms.png"), os.path.join(out, "picture.png"),
                       "--pattern", "3")
        self.assertEqual(check.returncode, 0, check.stdout + check.stderr)
        # A colour the sample lacks: one line naming the file and the pixel.
        drawn[7, 9] = (255, 0, 255, 255)
        write_png(drawn, path)
        bad = tmp("pins-sample-bad")
        subprocess.run(["rm", "-rf", bad])
        r = msynth("synthesize", data("Samples/Rooms.png"), *args, "--fixed", path, "--out", bad)
        self.assertEqual(r.returncode, 1, r.stderr)
        self.assertEqual(r.stderr.count("\n"), 1, r.stderr)
        self.assertIn(path, r.stderr)
        self.assertIn("pixel (9, 7)", r.stderr)
        self.assertFalse(os.path.exists(bad))

    def test_contradictory_pins_are_one_line_and_nothing_is_written(self):
        pins = np.full((5, 16, 16), -1, dtype=np.int32)
        pins[1, 5, 5] = 1  # ground over ground: never in the village
        pins[2, 5, 5] = 1
        path = write_pins(tmp("village-bad-pins.vti"), pins)
        out = tmp("pins-bad")
        subprocess.run(["rm", "-rf", out])
        r = msynth("synthesize", data("Examples/Village.vti"), "--size", "16", "16", "5", "--fixed", path,
                   "--out", out)
        self.assertEqual(r.returncode, 1, r.stderr)
        self.assertEqual(r.stderr.count("\n"), 1, r.stderr)
        self.assertIn("cannot meet", r.stderr)
        self.assertIn("(5, 5, 1)", r.stderr)
        self.assertFalse(os.path.exists(out))
        small = write_pins(tmp("village-small-pins.vti"), np.full((5, 4, 4), -1, dtype=np.int32))
        r = msynth("synthesize", data("Examples/Village.vti"), "--size", "16", "16", "5", "--fixed", small,
                   "--out", out)
        self.assertEqual(r.returncode, 1)
        self.assertEqual(r.stderr.count("\n"), 1, r.stderr)
        self.assertIn("--fixed '%s': the pinned sites cover 4 x 4 x 5 sites, the output 16 x 16 x 5: "
                      "expected a grid of the output's size (--size 16 16 5)" % small, r.stderr)
        r = msynth("synthesize", data("Examples/Village.vti"), "--size", "16", "16", "5",
                   "--fixed-empty-free", "--out", out)
        self.assertEqual(r.returncode, 2, r.stderr)  # needs --fixed

    def test_the_filter_keeps_pins_and_empty_is_free_with_the_flag(self):
        reader = modelsynth.vtkMSLabelGridReader()
        reader.SetFileName(data("Examples/Village.vti"))
        reader.Update()
        example = labels_zyx(reader.GetOutput())
        roof = int(example.max())
        pins = np.zeros((5, 20, 20), dtype=np.int32)  # 0: empty, free with --fixed-empty-free
        pins[3, 6, 6] = roof
        pins[3, 14, 12] = roof
        synthesis = modelsynth.vtkMSDiscreteSynthesis()
        synthesis.SetInputConnection(reader.GetOutputPort())
        free = np.where(pins == 0, -1, pins)
        synthesis.SetFixedData(image_of(free))
        out, errors = run_algorithm(synthesis, OutputSize=(20, 20, 5), BlockSize=(10, 10, 5), Seed=3,
                                    UseBoundary=(0, 0, 0, 0, 1, 0), BoundaryLabels=(0, 0, 0, 0, 1, 0))
        self.assertEqual(errors, "")
        model = labels_zyx(out)
        self.assertEqual(model[3, 6, 6], roof)
        self.assertEqual(model[3, 14, 12], roof)
        self.assertEqual(violations(example, model), [])
        # Through the command line, the same pins with 0 as free.
        path = write_pins(tmp("village-roof-pins.vti"), pins)
        folder = fresh_folder("pins-village")
        r = msynth("synthesize", data("Examples/Village.vti"), "--size", "20", "20", "5", "--block", "10",
                   "10", "5", "--ground", "1", "--seed", "3", "--fixed", path, "--fixed-empty-free",
                   "--out", folder)
        self.assertEqual(r.returncode, 0, r.stderr)
        model = read_labels(os.path.join(folder, "labels.vti"))
        self.assertEqual(model[3, 6, 6], roof)
        self.assertEqual(model[3, 14, 12], roof)
        check = msynth("check", data("Examples/Village.vti"), os.path.join(folder, "labels.vti"))
        self.assertEqual(check.returncode, 0, check.stdout + check.stderr)


if __name__ == "__main__":
    unittest.main()
