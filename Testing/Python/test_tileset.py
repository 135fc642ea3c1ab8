"""Tilesets end to end from Python: synthesis from a simple-tiled XML file, the picture composed
from the tile images, and errors for bad sets. Each site's pixels are checked against the tile
image turned and mirrored here with numpy, independently of the filter."""
import os
import shutil
import unittest

import numpy as np
from vtkmodules.util.numpy_support import numpy_to_vtk, vtk_to_numpy
from vtkmodules.vtkCommonDataModel import vtkImageData
from vtkmodules.vtkIOImage import vtkPNGWriter

import modelsynth
from msynth_testing import data, labels_zyx, run_algorithm, tmp

T = 5  # tile size in pixels

TILE_NAMES = ("empty", "line", "corner")  # the tiles of the bundled Data/Tilesets/Lines.xml


def tile_pixels(index):
    """An asymmetric T x T RGBA picture per tile (rows bottom first), so turns and mirrors show."""
    a = np.zeros((T, T, 4), dtype=np.uint8)
    for j in range(T):
        for i in range(T):
            a[j, i] = (40 * index + 7 * i, 13 * j, 30 * index + i * j, 255)
    return a


def write_png(path, pixels):
    image = vtkImageData()
    image.SetDimensions(T, T, 1)
    array = numpy_to_vtk(pixels.reshape(-1, 4), deep=True)
    array.SetName("RGBA")
    image.GetPointData().SetScalars(array)
    writer = vtkPNGWriter()
    writer.SetInputData(image)
    writer.SetFileName(path)
    writer.Write()


def oriented(pixels, k):
    """Orientation k: turned k % 4 quarter turns counter-clockwise, then mirrored if k >= 4."""
    out = np.rot90(pixels, -(k % 4), axes=(0, 1))  # rows bottom first: -1 is counter-clockwise
    return out[:, ::-1] if k >= 4 else out


class TilesetTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        folder = tmp("tiny-set")
        shutil.rmtree(folder, ignore_errors=True)
        os.makedirs(folder)
        cls.xml = folder + ".xml"
        # The bundled rules, with asymmetric images of our own so that turns and mirrors show.
        shutil.copy(data("Tilesets/Lines.xml"), cls.xml)
        for index, name in enumerate(TILE_NAMES):
            write_png(os.path.join(folder, name + ".png"), tile_pixels(index))

    def synthesize(self, **options):
        s = modelsynth.vtkMSDiscreteSynthesis()
        out, errors = run_algorithm(s, TilesetFile=self.xml, OutputSize=(12, 10, 1), **options)
        return s, out, errors

    def test_synthesis_and_picture(self):
        s, out, errors = self.synthesize(Seed=3, LabelChoice=1)
        self.assertEqual(errors, "")
        labels = labels_zyx(out)[0]
        names = out.GetFieldData().GetAbstractArray("TileNames")
        self.assertEqual([names.GetValue(i) for i in range(names.GetNumberOfValues())],
                         ["empty", "line 0", "line 1", "corner 0", "corner 1", "corner 2", "corner 3"])
        self.assertGreater(len(np.unique(labels)), 1)

        picture, errors = run_algorithm(modelsynth.vtkMSTileImage(), s.GetOutputPort(), TilesetFile=self.xml)
        self.assertEqual(errors, "")
        self.assertEqual(picture.GetDimensions(), (12 * T, 10 * T, 1))
        rgba = vtk_to_numpy(picture.GetPointData().GetArray("RGBA")).reshape(10 * T, 12 * T, 4)
        first = {0: 0, 1: 1, 2: 1, 3: 2, 4: 2, 5: 2, 6: 2}  # label -> tile index
        orientation = {0: 0, 1: 0, 2: 1, 3: 0, 4: 1, 5: 2, 6: 3}
        for y in range(10):
            for x in range(12):
                b = int(labels[y, x])
                expected = oriented(tile_pixels(first[b]), orientation[b])
                block = rgba[y * T:(y + 1) * T, x * T:(x + 1) * T]
                self.assertTrue(np.array_equal(block, expected), "site %s label %d" % ((x, y), b))

    def test_errors(self):
        _, errors = run_algorithm(modelsynth.vtkMSDiscreteSynthesis(), TilesetFile=tmp("none.xml"),
                                  OutputSize=(4, 4, 1))
        self.assertIn("none.xml", errors)
        bad = tmp("bad-set.xml")
        with open(bad, "w") as f:
            f.write("<set><tiles><tile name='a' symmetry='Q'/></tiles></set>")
        _, errors = run_algorithm(modelsynth.vtkMSDiscreteSynthesis(), TilesetFile=bad, OutputSize=(4, 4, 1))
        self.assertIn("symmetry 'Q'", errors)
        # A missing tile image is named.
        s, out, _ = self.synthesize(Seed=1)
        missing = tmp("tiny-set-missing")
        shutil.rmtree(missing, ignore_errors=True)
        os.makedirs(missing)
        shutil.copy(data("Tilesets/Lines.xml"), missing + ".xml")
        picture, errors = run_algorithm(modelsynth.vtkMSTileImage(), s.GetOutputPort(),
                                        TilesetFile=missing + ".xml")
        self.assertIn("no such tile image", errors)


if __name__ == "__main__":
    unittest.main()
