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
from msynth_testing import ErrorObserver, data, fresh_folder, labels_zyx, run_algorithm, tmp

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
        folder = fresh_folder("tiny-set")
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

    def test_rotation_symmetry_turns_the_picture(self):
        # With Rotate and no RotationMap each tile turns to its next orientation, so the picture
        # composed from the tile images, turned a quarter, is the same picture. The images are
        # as symmetric as their tiles' classes say (empty X: any turn; line I: a half turn) and
        # otherwise asymmetric (corner L), so a wrong turn direction shows.
        folder = fresh_folder("turn-set")
        xml = folder + ".xml"
        shutil.copy(data("Tilesets/Lines.xml"), xml)
        empty, line, corner = (tile_pixels(i) for i in range(3))
        turns = [np.rot90(empty, k) for k in range(4)]
        write_png(os.path.join(folder, "empty.png"), np.maximum.reduce(turns))
        write_png(os.path.join(folder, "line.png"), np.maximum(line, np.rot90(line, 2)))
        write_png(os.path.join(folder, "corner.png"), corner)
        for n, block in ((8, (0, 0, 0)), (9, (4, 4, 1))):
            s = modelsynth.vtkMSDiscreteSynthesis()
            out, errors = run_algorithm(s, TilesetFile=xml, OutputSize=(n, n, 1), Seed=4, Rotate=1,
                                        BlockSize=block)
            self.assertEqual(errors, "")
            self.assertGreater(len(np.unique(labels_zyx(out))), 2)
            picture, errors = run_algorithm(modelsynth.vtkMSTileImage(), s.GetOutputPort(), TilesetFile=xml)
            self.assertEqual(errors, "")
            rgba = vtk_to_numpy(picture.GetPointData().GetArray("RGBA")).reshape(n * T, n * T, 4)
            self.assertTrue(np.array_equal(np.rot90(rgba), rgba), "the picture is not turn-symmetric")
        # An explicit map that is not a quarter turn of the rules is refused.
        _, errors = run_algorithm(modelsynth.vtkMSDiscreteSynthesis(), TilesetFile=xml, OutputSize=(8, 8, 1),
                                  Rotate=1, RotationMap="3:3,4:4,5:6,6:5")
        self.assertIn("not preserved by a quarter turn", errors)

    def test_pieces_turned_by_orientation(self):
        # A tileset of one F tile (8 orientations) and a model holding labels 0..7 in a row; the
        # piece f.obj is an off-centre box, so each orientation's turn and mirror shows in where
        # its box lands, recomputed here; mirrored boxes must stay outward (positive volume).
        folder = fresh_folder("f-pieces")
        xml = os.path.join(folder, "fset.xml")
        with open(xml, "w") as f:
            f.write('<set><tiles><tile name="f" symmetry="F"/></tiles>'
                    '<neighbors><neighbor left="f" right="f"/></neighbors></set>')
        lo, hi = (0.1, 0.0, -0.1), (0.4, 0.1, 0.1)
        corners = [(x, y, z) for z in (lo[2], hi[2]) for y in (lo[1], hi[1]) for x in (lo[0], hi[0])]
        with open(os.path.join(folder, "f.obj"), "w") as f:
            for c in corners:
                f.write("v %g %g %g\n" % c)
            for face in ((1, 3, 4, 2), (5, 6, 8, 7), (1, 2, 6, 5), (2, 4, 8, 6), (4, 3, 7, 8), (3, 1, 5, 7)):
                f.write("f %d %d %d %d\n" % face)
        model = vtkImageData()
        model.SetDimensions(8, 1, 1)
        labels = numpy_to_vtk(np.arange(8, dtype=np.int32), deep=True)
        labels.SetName("Label")
        model.GetPointData().SetScalars(labels)
        geometry = modelsynth.vtkMSLabelGeometry()
        out, errors = run_algorithm(geometry, data=model, PieceDirectory=folder, TilesetFile=xml,
                                    EmptyLabel=-1)
        self.assertEqual(errors, "")
        points = vtk_to_numpy(out.GetPoints().GetData())
        ids = vtk_to_numpy(out.GetPolys().GetConnectivityArray())
        offsets = vtk_to_numpy(out.GetPolys().GetOffsetsArray())
        cell_labels = vtk_to_numpy(out.GetCellData().GetArray("Label"))
        for k in range(8):
            polys = [ids[offsets[c]:offsets[c + 1]] for c in range(len(offsets) - 1) if cell_labels[c] == k]
            self.assertEqual(len(polys), 6, "orientation %d" % k)
            used = np.unique(np.concatenate(polys))
            centre = points[used].mean(axis=0) - (k, 0, 0)
            x, y = 0.25, 0.05
            for _ in range(k % 4):
                x, y = -y, x
            if k >= 4:
                x = -x
            self.assertTrue(np.allclose(centre[:2], (x, y)), "orientation %d: %s" % (k, centre))
            volume = sum(np.dot(points[p[0]], np.cross(points[p[i]], points[p[i + 1]]))
                         for p in polys for i in range(1, len(p) - 1)) / 6
            self.assertGreater(volume, 0, "orientation %d stays outward" % k)

    def test_older_layout_unique_images_bmp_and_dihedral_numbers(self):
        # The older published layout: NAME/data.xml with the images beside it, a unique set (one
        # image per orientation, "tile k.png"), <set size>, a .bmp image, and rule numbers that
        # are dihedral elements 0-7 rather than orientations ("b_i 3" of an I tile).
        from vtkmodules.vtkIOImage import vtkBMPWriter
        folder = fresh_folder("old-layout-set")
        xml = os.path.join(folder, "data.xml")
        with open(xml, "w") as f:
            f.write('<set size="%d" unique="True"><tiles><tile name="b" symmetry="X"/>'
                    '<tile name="b_i" symmetry="I"/></tiles><neighbors>'
                    '<neighbor left="b" right="b"/><neighbor left="b_i 3" right="b"/>'
                    '<neighbor left="b_i 2" right="b_i 6"/></neighbors></set>' % T)
        images = {"b 0": tile_pixels(0), "b_i 0": tile_pixels(1), "b_i 1": tile_pixels(2)}
        for name, pixels in images.items():
            if name == "b_i 1":  # as a BMP (RGB: opaque)
                image = vtkImageData()
                image.SetDimensions(T, T, 1)
                array = numpy_to_vtk(pixels[:, :, :3].reshape(-1, 3), deep=True)
                image.GetPointData().SetScalars(array)
                writer = vtkBMPWriter()
                writer.SetInputData(image)
                writer.SetFileName(os.path.join(folder, name + ".bmp"))
                writer.Write()
            else:
                write_png(os.path.join(folder, name + ".png"), pixels)
        # WaveFunctionCollapse's rules by hand: b_i 3 = b_i 2 turned = orientation 1 (vertical)
        # beside b; b_i 2 = orientation 0 left of b_i 6 = orientation 0 (mirrored: the same).
        # A horizontal and a vertical line cannot cross, so seeds differ in which appears.
        allowed_x = {(0, 0), (2, 0), (0, 2), (1, 1)}
        allowed_y = {(0, 0), (1, 0), (0, 1), (2, 2)}
        by_label = [images["b 0"], images["b_i 0"], images["b_i 1"].copy()]
        by_label[2][:, :, 3] = 255
        used = set()
        for seed in range(8):
            s = modelsynth.vtkMSDiscreteSynthesis()
            out, errors = run_algorithm(s, TilesetFile=xml, OutputSize=(9, 7, 1), Seed=seed)
            self.assertEqual(errors, "")
            labels = labels_zyx(out)[0]
            used |= set(int(b) for b in np.unique(labels))
            for y in range(7):
                for x in range(9):
                    if x + 1 < 9:
                        self.assertIn((labels[y, x], labels[y, x + 1]), allowed_x)
                    if y + 1 < 7:
                        self.assertIn((labels[y, x], labels[y + 1, x]), allowed_y)
            picture, errors = run_algorithm(modelsynth.vtkMSTileImage(), s.GetOutputPort(), TilesetFile=xml)
            self.assertEqual(errors, "")
            rgba = vtk_to_numpy(picture.GetPointData().GetArray("RGBA")).reshape(7 * T, 9 * T, 4)
            for y in range(7):
                for x in range(9):
                    block = rgba[y * T:(y + 1) * T, x * T:(x + 1) * T]
                    self.assertTrue(np.array_equal(block, by_label[labels[y, x]]), (seed, x, y))
        self.assertEqual(used, {0, 1, 2})
        # <set size> must match the images.
        with open(xml) as f:
            text = f.read()
        with open(xml, "w") as f:
            f.write(text.replace('size="%d"' % T, 'size="%d"' % (T + 1)))
        _, errors = run_algorithm(modelsynth.vtkMSTileImage(), s.GetOutputPort(), TilesetFile=xml)
        self.assertIn("<set size> says %d" % (T + 1), errors)

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
        self.assertIn("empty.png': no such image file", errors)

    def test_picture_takes_the_inputs_tileset(self):
        """Without a TilesetFile of its own, Tile Image takes the synthesis's (its pipeline
        information), or a saved model's (its field data); with neither, one error."""
        s, out, _ = self.synthesize(Seed=3, TilesetSubset="")
        self.assertEqual(out.GetFieldData().GetAbstractArray("TilesetFile").GetValue(0), self.xml)
        self.assertEqual(out.GetFieldData().GetAbstractArray("TilesetSubset").GetValue(0), "")
        own, errors = run_algorithm(modelsynth.vtkMSTileImage(), s.GetOutputPort(), TilesetFile=self.xml)
        self.assertEqual(errors, "")
        expected = vtk_to_numpy(own.GetPointData().GetArray("RGBA")).copy()
        upstream, errors = run_algorithm(modelsynth.vtkMSTileImage(), s.GetOutputPort())
        self.assertEqual(errors, "")
        self.assertEqual(upstream.GetDimensions(), own.GetDimensions())
        self.assertTrue((vtk_to_numpy(upstream.GetPointData().GetArray("RGBA")) == expected).all())
        # A saved model names its tileset in its field data.
        from vtkmodules.vtkIOXML import vtkXMLImageDataReader, vtkXMLImageDataWriter
        saved = tmp("tiny-set-model.vti")
        writer = vtkXMLImageDataWriter()
        writer.SetInputData(out)
        writer.SetFileName(saved)
        writer.Write()
        reader = vtkXMLImageDataReader()
        reader.SetFileName(saved)
        from_file, errors = run_algorithm(modelsynth.vtkMSTileImage(), reader.GetOutputPort())
        self.assertEqual(errors, "")
        self.assertTrue((vtk_to_numpy(from_file.GetPointData().GetArray("RGBA")) == expected).all())
        # Neither: one error of the filter's own, no failure (and dump) of the executive.
        example = modelsynth.vtkMSLabelGridReader()
        example.SetFileName(data("Examples/Village.vti"))
        picture = modelsynth.vtkMSTileImage()
        picture.SetInputConnection(example.GetOutputPort())
        mine, executive = ErrorObserver(picture), ErrorObserver(picture.GetExecutive())
        picture.Update()
        self.assertEqual(len(mine.messages), 1, mine.text())
        self.assertIn("No tileset: set TilesetFile", mine.text())
        self.assertEqual(executive.messages, [])
        self.assertEqual(picture.GetOutput().GetNumberOfPoints(), 0)


if __name__ == "__main__":
    unittest.main()
