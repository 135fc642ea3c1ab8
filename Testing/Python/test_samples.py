"""Image samples (the overlapping model) from Python: synthesis from a PNG sample through
vtkMSDiscreteSynthesis, the picture through vtkMSPatternImage, checked here with numpy and
independently of the engine: every N x N window of the picture must be a window of the sample
(or one of its first S dihedral images, in WaveFunctionCollapse's order)."""
import os
import unittest

import numpy as np
from vtkmodules.util.numpy_support import numpy_to_vtk, vtk_to_numpy
from vtkmodules.vtkCommonDataModel import vtkImageData
from vtkmodules.vtkCommonExecutionModel import vtkStreamingDemandDrivenPipeline
from vtkmodules.vtkIOImage import vtkPNGReader
from vtkmodules.vtkIOXML import vtkXMLImageDataReader, vtkXMLImageDataWriter

import modelsynth
from msynth_testing import ErrorObserver, data, run_algorithm, tmp


def picture_rows(image):
    """RGBA pixels of a VTK image as a [row from the top, x] array of 32-bit values."""
    nx, ny, _ = image.GetDimensions()
    rgba = vtk_to_numpy(image.GetPointData().GetScalars()).reshape(ny, nx, -1)
    if rgba.shape[2] == 3:
        rgba = np.concatenate([rgba, np.full((ny, nx, 1), 255, np.uint8)], axis=2)
    rgba = rgba[::-1].astype(np.uint32)  # VTK rows are bottom first
    return rgba[:, :, 0] | (rgba[:, :, 1] << 8) | (rgba[:, :, 2] << 16) | (rgba[:, :, 3] << 24)


def read_png(path):
    reader = vtkPNGReader()
    reader.SetFileName(path)
    reader.Update()
    return picture_rows(reader.GetOutput())


def dihedral(window, k):
    """Image k of a window: even k are k/2 quarter turns counter-clockwise, odd k those mirrored."""
    w = np.rot90(window, k // 2)  # numpy turns counter-clockwise, rows from the top
    return w[:, ::-1] if k % 2 else w


def windows(pixels, n, wrap):
    h, w = pixels.shape
    ys = range(h) if wrap[1] else range(h - n + 1)
    xs = range(w) if wrap[0] else range(w - n + 1)
    tiled = np.tile(pixels, (2, 2))
    for y in ys:
        for x in xs:
            yield x, y, tiled[y:y + n, x:x + n]


def check_picture(test, sample, picture, n, symmetry, periodic_input=True, periodic=(0, 0),
                  ground=False):
    allowed = set()
    for _, _, w in windows(sample, n, (periodic_input, periodic_input)):
        for k in range(symmetry):
            allowed.add(dihedral(w, k).tobytes())
    bad = [(x, y) for x, y, w in windows(picture, n, periodic) if w.tobytes() not in allowed]
    test.assertEqual(bad, [], "windows not in the sample")
    if ground:
        # Repeating along y: the window at the bottom middle, wrapping (WaveFunctionCollapse);
        # bounded: any window of the sample's last n rows.
        sh, sw = sample.shape
        tiled = np.tile(sample, (2, 2))
        if periodic[1]:
            g = {tiled[sh - 1:sh - 1 + n, sw // 2:sw // 2 + n].tobytes()}
        else:
            g = {tiled[sh - n:sh, x:x + n].tobytes()
                 for x in range(sw if periodic_input else sw - n + 1)}
        row = picture.shape[0] - (1 if periodic[1] else n)
        for x, y, w in windows(picture, n, periodic):
            test.assertEqual(w.tobytes() in g, y == row, "ground at (%d, %d)" % (x, y))


def assert_varied(test, sample, picture, n):
    """Valid is not enough: the picture must use a good part of the sample's windows (a picture
    of one pattern everywhere passes the window check)."""
    used = {w.tobytes() for _, _, w in windows(picture, n, (0, 0))}
    own = {w.tobytes() for _, _, w in windows(sample, n, (1, 1))}
    test.assertGreaterEqual(len(used), min(12, len(own) // 2), "too few different windows")


def labels_of(image):
    """The Label array of a 2D image as [y, x]."""
    nx, ny, _ = image.GetDimensions()
    return vtk_to_numpy(image.GetPointData().GetArray("Label")).reshape(ny, nx)


def synthesize(sample, **options):
    s = modelsynth.vtkMSDiscreteSynthesis()
    s.SetSampleFile(data("Samples/" + sample))
    out, errors = run_algorithm(s, **options)
    return s, out, errors


def picture_of(port):
    image = modelsynth.vtkMSPatternImage()
    out, errors = run_algorithm(image, port)
    return out, errors


class TestSamples(unittest.TestCase):
    def test_meadow_with_ground_repeating(self):
        sample = read_png(data("Samples/Meadow.png"))
        for seed in (1, 2, 3):
            s, labels, errors = synthesize("Meadow.png", OutputSize=(48, 30, 1), BlockSize=(16, 16, 1),
                                           PatternSymmetry=2, Ground=1, Translate=(1, 1, 0),
                                           Seed=seed, LabelChoice=1)
            self.assertEqual(errors, "")
            self.assertEqual(labels.GetDimensions(), (48, 30, 1))  # repeating: a site per pixel
            fd = labels.GetFieldData()
            self.assertEqual(fd.GetArray("BlocksFailed").GetValue(0), 0)
            picture, errors = picture_of(s.GetOutputPort())
            self.assertEqual(errors, "")
            self.assertEqual(picture.GetDimensions(), (48, 30, 1))
            pixels = picture_rows(picture)
            check_picture(self, sample, pixels, 3, 2, periodic=(1, 1), ground=True)
            assert_varied(self, sample, pixels, 3)
            self.assertTrue((pixels[-1] == sample[-1, 0]).all())  # earth along the bottom

    def test_meadow_with_ground_bounded(self):
        sample = read_png(data("Samples/Meadow.png"))
        for translate in ((1, 0, 0), (0, 0, 0)):
            s, labels, errors = synthesize("Meadow.png", OutputSize=(60, 24, 1),
                                           BlockSize=(12, 12, 1), PatternSymmetry=2, Ground=1,
                                           Translate=translate, Seed=5, LabelChoice=1)
            self.assertEqual(errors, "")
            self.assertEqual(labels.GetFieldData().GetArray("BlocksFailed").GetValue(0), 0)
            picture, errors = picture_of(s.GetOutputPort())
            pixels = picture_rows(picture)
            check_picture(self, sample, pixels, 3, 2, periodic=translate[:2], ground=True)
            assert_varied(self, sample, pixels, 3)
            self.assertTrue((pixels[-2:] == sample[-1, 0]).all())  # the sample's two earth rows

    def test_rooms_bounded_whole_and_blocks(self):
        sample = read_png(data("Samples/Rooms.png"))
        for block in ((0, 0, 0), (12, 12, 1)):
            s, labels, errors = synthesize("Rooms.png", OutputSize=(40, 36, 1), BlockSize=block,
                                           Seed=7, SiteOrder=2, LabelChoice=1)
            self.assertEqual(errors, "")
            self.assertEqual(labels.GetDimensions(), (38, 34, 1))  # W - N + 1 sites
            picture, errors = picture_of(s.GetOutputPort())
            self.assertEqual(errors, "")
            self.assertEqual(picture.GetDimensions(), (40, 36, 1))
            check_picture(self, sample, picture_rows(picture), 3, 8)
            assert_varied(self, sample, picture_rows(picture), 3)

    def test_bricks_blocks_start_from_layers(self):
        sample = read_png(data("Samples/Bricks.png"))
        s, labels, errors = synthesize("Bricks.png", OutputSize=(30, 30, 1), BlockSize=(10, 10, 1),
                                       PatternSymmetry=2, Seed=3)
        self.assertEqual(errors, "")
        self.assertEqual(labels.GetFieldData().GetArray("BlocksFailed").GetValue(0), 0)
        picture, errors = picture_of(s.GetOutputPort())
        check_picture(self, sample, picture_rows(picture), 3, 2)
        assert_varied(self, sample, picture_rows(picture), 3)

    def test_maze_and_city_in_blocks(self):
        # A maze (one attempt of the whole model fails most seeds at 256²) and city blocks.
        for name in ("Maze.png", "City.png"):
            sample = read_png(data("Samples/" + name))
            for seed in (1, 2):
                s, labels, errors = synthesize(name, OutputSize=(64, 64, 1), BlockSize=(20, 20, 1),
                                               Seed=seed, SiteOrder=2, LabelChoice=1)
                self.assertEqual(errors, "")
                self.assertEqual(labels.GetFieldData().GetArray("BlocksFailed").GetValue(0), 0)
                picture, errors = picture_of(s.GetOutputPort())
                check_picture(self, sample, picture_rows(picture), 3, 8)
                assert_varied(self, sample, picture_rows(picture), 3)

    def test_snapshots_and_guide(self):
        # Catalog snapshots as time steps, as for any example.
        s, labels, errors = synthesize("Rooms.png", OutputSize=(34, 26, 1), BlockSize=(16, 16, 1),
                                       Seed=4, CatalogSnapshotsPerBlock=2)
        self.assertEqual(errors, "")
        blocks = labels.GetFieldData().GetArray("Blocks").GetValue(0)
        steps = s.GetOutputInformation(0).Get(vtkStreamingDemandDrivenPipeline.TIME_STEPS())
        self.assertEqual(len(steps), 1 + 2 * blocks)
        s.UpdateTimeStep(steps[len(steps) // 2])
        middle = s.GetOutput()
        self.assertIsNotNone(middle.GetPointData().GetArray("CatalogSize"))
        # A guide over the pattern grid: the most common pattern (all floor) may not appear in
        # the left half, and does not; every window is still the sample's.
        plain = labels_of(synthesize("Rooms.png", OutputSize=(34, 26, 1), Seed=4)[1])
        floor = int(np.bincount(plain.ravel()).argmax())
        guide = vtkImageData()
        guide.SetDimensions(2, 1, 1)
        weight = numpy_to_vtk(np.array([0.0, 1.0]), deep=True)
        weight.SetName("Weight_%d" % floor)
        guide.GetPointData().AddArray(weight)
        s = modelsynth.vtkMSDiscreteSynthesis()
        s.SetSampleFile(data("Samples/Rooms.png"))
        s.SetGuideData(guide)
        out, errors = run_algorithm(s, OutputSize=(34, 26, 1), Seed=4)
        self.assertEqual(errors, "")
        guided = labels_of(out)
        self.assertFalse((guided[:, :16] == floor).any())
        self.assertTrue((guided[:, 16:] == floor).any())
        picture, errors = picture_of(s.GetOutputPort())
        check_picture(self, read_png(data("Samples/Rooms.png")), picture_rows(picture), 3, 8)

    def test_patterns_and_pairs_as_data(self):
        # vtkMSImagePatterns: each slice is a window of the sample (or an image of one), each
        # pair agrees where the two windows overlap, the counts add up to every window read.
        reader = modelsynth.vtkMSImagePatterns()
        reader.SetSampleFile(data("Samples/Rooms.png"))
        reader.Update()
        patterns = reader.GetOutputDataObject(0)
        self.assertEqual(patterns.GetDimensions(), (3, 3, 113))
        rgba = vtk_to_numpy(patterns.GetPointData().GetArray("RGBA")).reshape(113, 3, 3, 4)
        rgba = rgba[:, ::-1].astype(np.uint32)  # rows from the top
        cells = rgba[..., 0] | (rgba[..., 1] << 8) | (rgba[..., 2] << 16) | (rgba[..., 3] << 24)
        sample = read_png(data("Samples/Rooms.png"))
        allowed = {dihedral(w, k).tobytes() for _, _, w in windows(sample, 3, (1, 1)) for k in range(8)}
        self.assertTrue(all(c.tobytes() in allowed for c in cells))
        self.assertEqual(len({c.tobytes() for c in cells}), 113)
        pairs = reader.GetOutputDataObject(1)
        rows = pairs.GetNumberOfRows()
        self.assertEqual(rows, 2 * 326)
        for r in range(rows):
            a, b = int(pairs.GetValueByName(r, "From").ToInt()), int(pairs.GetValueByName(r, "To").ToInt())
            if int(pairs.GetValueByName(r, "Axis").ToInt()) == 0:
                self.assertTrue((cells[a][:, 1:] == cells[b][:, :2]).all())
            else:  # +y is up: b lies above a
                self.assertTrue((cells[a][:2, :] == cells[b][1:, :]).all())
        counts = vtk_to_numpy(reader.GetOutputDataObject(2).GetColumnByName("Count"))
        self.assertEqual(int(counts.sum()), 16 * 16 * 8)
        bad = modelsynth.vtkMSImagePatterns()
        observer = ErrorObserver(bad)
        bad.Update()
        self.assertIn("No SampleFile", observer.text())
        bad.SetSampleFile(data("Samples/Bricks.png"))
        bad.SetPatternSize(7)  # larger than the 8 x 6 sample
        bad.Update()
        self.assertIn("smaller than a 7 x 7 pattern", observer.text())

    def test_labels_saved_and_composed_later(self):
        s, labels, errors = synthesize("Rooms.png", OutputSize=(20, 20, 1), PatternSize=2,
                                       PatternSymmetry=4, Seed=2)
        self.assertEqual(errors, "")
        path = tmp("sample-labels.vti")
        writer = vtkXMLImageDataWriter()
        writer.SetInputData(labels)
        writer.SetFileName(path)
        self.assertTrue(writer.Write())
        reader = vtkXMLImageDataReader()
        reader.SetFileName(path)
        # The reader announces no pattern size: the properties say it, the field data checks it.
        image = modelsynth.vtkMSPatternImage()
        picture, errors = run_algorithm(image, reader.GetOutputPort(), PatternSize=2)
        self.assertEqual(errors, "")
        direct, _ = picture_of(s.GetOutputPort())
        self.assertTrue((picture_rows(picture) == picture_rows(direct)).all())
        check_picture(self, read_png(data("Samples/Rooms.png")), picture_rows(picture), 2, 4)
        image = modelsynth.vtkMSPatternImage()
        _, errors = run_algorithm(image, reader.GetOutputPort(), PatternSize=3)
        self.assertIn("set PatternSize and PeriodicOutput", errors)

    def test_errors(self):
        _, out, errors = synthesize("Missing.png", OutputSize=(10, 10, 1))
        self.assertIn("Missing.png", errors)
        self.assertEqual(out.GetNumberOfPoints(), 0)
        _, out, errors = synthesize("Bricks.png", OutputSize=(10, 10, 1), PatternSize=7)
        self.assertIn("smaller than a 7 x 7 pattern", errors)
        _, out, errors = synthesize("Bricks.png", OutputSize=(10, 10, 3))
        self.assertIn("OutputSize must be 1 in z", errors)
        _, out, errors = synthesize("Bricks.png", OutputSize=(10, 10, 1),
                                    TilesetFile=data("Tilesets/Lines.xml"))
        self.assertIn("not both", errors)
        image = modelsynth.vtkMSPatternImage()
        labels = modelsynth.vtkMSLabelGridReader()
        labels.SetFileName(data("Examples/Checkerboard.vti"))
        _, errors = run_algorithm(image, labels.GetOutputPort())
        self.assertIn("No SampleFile", errors)


if __name__ == "__main__":
    unittest.main()
