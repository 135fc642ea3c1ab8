"""MarkovJunior voxel tilesets end to end: msynth synthesize (whole, blocks, threads, --tiles, a
2D set's picture, a model wider than 256 voxels), msynth check of every model.vox (the engine's
independent check) and info; the filter from Python with its field data and coloured geometry;
bad input as one line. model.vox files are also parsed here, chunk by chunk, to count the models
of the scene and compare the voxels with the picture."""
import os
import shutil
import struct
import subprocess
import unittest

import numpy as np
from vtkmodules.util.numpy_support import vtk_to_numpy

import modelsynth
from msynth_testing import BIN, data, fresh_folder, labels_zyx, run_algorithm, tmp

MSYNTH = os.path.join(BIN, "msynth")


def run(*args):
    return subprocess.run([MSYNTH] + [str(a) for a in args], capture_output=True, text=True, timeout=300)


def vox_models(path):
    """(sizes, voxels per model, palette) of a MagicaVoxel file, read here without the engine."""
    with open(path, "rb") as f:
        b = f.read()
    assert b[:4] == b"VOX " and b[8:12] == b"MAIN"
    pos, end = 20, len(b)
    sizes, voxels, palette = [], [], None
    while pos < end:
        name, content, children = b[pos:pos + 4], *struct.unpack("<II", b[pos + 4:pos + 12])
        body = b[pos + 12:pos + 12 + content]
        if name == b"SIZE":
            sizes.append(struct.unpack("<III", body[:12]))
        elif name == b"XYZI":
            n = struct.unpack("<I", body[:4])[0]
            voxels.append(np.frombuffer(body[4:4 + 4 * n], dtype=np.uint8).reshape(n, 4))
        elif name == b"RGBA":
            palette = np.frombuffer(body, dtype=np.uint8).reshape(256, 4)
        pos += 12 + content + children
    return sizes, voxels, palette


class VoxelTilesetTest(unittest.TestCase):
    def test_synthesize_and_check_3d_whole_and_in_blocks(self):
        folder = fresh_folder("voxel-pipes")
        for name, extra in (("whole", []), ("blocks", ["--block", 4, 4, 3, "--threads", 2]),
                            ("empty", ["--block", 4, 4, 3, "--empty", 0, "--choice", "frequency"])):
            out = os.path.join(folder, name)
            done = run("synthesize", data("Tilesets/Pipes.xml"), "--size", 8, 8, 6, "--seed", 4,
                       "--out", out, *extra)
            self.assertEqual(done.returncode, 0, done.stderr)
            self.assertIn("(0 failed)", done.stdout)
            for f in ("labels.vti", "model.vox", "mesh.vtp", "model.vdb", "statistics.json"):
                self.assertTrue(os.path.exists(os.path.join(out, f)), name + " " + f)
            checked = run("check", data("Tilesets/Pipes.xml"), os.path.join(out, "model.vox"))
            self.assertEqual(checked.returncode, 0, checked.stdout + checked.stderr)
            self.assertIn("all 384 tile cells", checked.stdout)
            sizes, _, _ = vox_models(os.path.join(out, "model.vox"))
            self.assertEqual(sizes, [(40, 40, 30)])
        # A voxel changed: the check names the cell and fails.
        path = os.path.join(folder, "whole", "model.vox")
        with open(path, "rb") as f:
            b = bytearray(f.read())
        at = b.find(b"XYZI") + 16  # the first voxel: x, y, z, colour index
        b[at + 3] = 255 if b[at + 3] != 255 else 254
        broken = os.path.join(folder, "broken.vox")
        with open(broken, "wb") as f:
            f.write(bytes(b))
        checked = run("check", data("Tilesets/Pipes.xml"), broken)
        self.assertEqual(checked.returncode, 1)
        self.assertIn("is no image of any tile", checked.stdout)

    def test_2d_set_picture_and_a_scene_of_several_models(self):
        folder = fresh_folder("voxel-tracks")
        out = os.path.join(folder, "wide")
        done = run("synthesize", data("Tilesets/Tracks.xml"), "--size", 50, 4, 1, "--block", 10, 4, 1,
                   "--seed", 2, "--out", out)
        self.assertEqual(done.returncode, 0, done.stderr)
        sizes, voxels, palette = vox_models(os.path.join(out, "model.vox"))
        self.assertEqual(sizes, [(256, 24, 1), (44, 24, 1)])  # 300 voxels wide: two models
        checked = run("check", data("Tilesets/Tracks.xml"), os.path.join(out, "model.vox"))
        self.assertEqual(checked.returncode, 0, checked.stdout)
        self.assertIn("2 models", checked.stdout)
        # The picture (y up, rows from the top) shows the voxels' colours.
        from vtkmodules.vtkIOImage import vtkPNGReader
        reader = vtkPNGReader()
        reader.SetFileName(os.path.join(out, "picture.png"))
        reader.Update()
        image = reader.GetOutput()
        self.assertEqual(image.GetDimensions(), (300, 24, 1))
        rgb = vtk_to_numpy(image.GetPointData().GetScalars()).reshape(24, 300, -1)  # VTK rows bottom first
        for (x, y, z, c) in voxels[0][:50]:
            self.assertEqual(tuple(rgb[y, x, :3]), tuple(palette[c - 1][:3]))

    def test_mirror_and_rotate_pair_each_image_with_its_own_image(self):
        """--mirror and --rotate of a voxel tileset need no --swap or --turn: each tile image is
        paired with its mirrored or turned image. The voxels, read here, are symmetric."""
        folder = fresh_folder("voxel-symmetry")
        for name, xml, size, option in (("mirror", "Pipes", (8, 8, 6), ["--mirror", "xyz"]),
                                        ("rotate", "Tracks", (10, 10, 1), ["--rotate"])):
            out = os.path.join(folder, name)
            done = run("synthesize", data("Tilesets/%s.xml" % xml), "--size", *size, "--seed", 3,
                       "--outputs", "vox", "--out", out, *option)
            self.assertEqual(done.returncode, 0, done.stderr)
            checked = run("check", data("Tilesets/%s.xml" % xml), os.path.join(out, "model.vox"))
            self.assertEqual(checked.returncode, 0, checked.stdout)
            sizes, voxels, palette = vox_models(os.path.join(out, "model.vox"))
            grid = np.zeros(sizes[0], dtype=np.uint8)
            grid[voxels[0][:, 0], voxels[0][:, 1], voxels[0][:, 2]] = voxels[0][:, 3]
            self.assertGreater(np.count_nonzero(grid), 0)
            if name == "mirror":
                for axis in range(3):
                    self.assertTrue((grid == np.flip(grid, axis)).all(), "mirror axis %d" % axis)
            else:  # a quarter turn about z maps the model onto itself
                self.assertTrue((grid == np.rot90(grid, 1, axes=(0, 1))).all())

    def test_tiles_folder_info_and_errors(self):
        folder = fresh_folder("voxel-tiles-folder")
        shutil.copy(data("Tilesets/Pipes.xml"), os.path.join(folder, "Mine.xml"))
        shutil.copytree(data("Tilesets/Pipes"), os.path.join(folder, "Drawn", "v1"))
        xml = os.path.join(folder, "Mine.xml")
        # Without --tiles the folder Mine/ is missing: one line naming the tile file.
        done = run("synthesize", xml, "--size", 4, 4, 4, "--out", os.path.join(folder, "no"))
        self.assertEqual(done.returncode, 1)
        self.assertEqual(len(done.stderr.strip().splitlines()), 1, done.stderr)
        self.assertIn("Empty.vox", done.stderr)
        # Tiles in subfolders of the tileset's own folder (as MarkovJunior's Knots3D keeps them
        # in Knots3D/3, Knots3D/4, ...): the line names the subfolders and how to choose one.
        shutil.copytree(data("Tilesets/Pipes"), os.path.join(folder, "Mine", "thin"))
        shutil.copytree(data("Tilesets/Pipes"), os.path.join(folder, "Mine", "thick"))
        done = run("synthesize", xml, "--size", 4, 4, 4, "--out", os.path.join(folder, "no"))
        self.assertEqual(done.returncode, 1)
        self.assertEqual(len(done.stderr.strip().splitlines()), 1, done.stderr)
        self.assertIn("Mine/Empty.vox': is missing; the tileset's folder holds its tiles in the "
                      "subfolders thick, thin: choose one as the tiles folder (msynth --tiles "
                      "Mine/thick", done.stderr)
        shutil.rmtree(os.path.join(folder, "Mine"))
        # --tiles relative to the XML's folder.
        done = run("synthesize", xml, "--tiles", "Drawn/v1", "--size", 4, 4, 4, "--out",
                   os.path.join(folder, "yes"))
        self.assertEqual(done.returncode, 0, done.stderr)
        checked = run("check", xml, os.path.join(folder, "yes", "model.vox"), "--tiles", "Drawn/v1")
        self.assertEqual(checked.returncode, 0, checked.stdout + checked.stderr)
        info = run("info", xml, "--tiles", "Drawn/v1")
        self.assertEqual(info.returncode, 0, info.stderr)
        self.assertIn("with the cube's 48 symmetries", info.stdout)
        self.assertIn("Bend: 48 distinct images", info.stdout)
        self.assertIn("transitions +z: 3285", info.stdout)
        # A tile of another size: one line.
        with open(os.path.join(folder, "Drawn", "v1", "Tee.vox"), "rb") as f:
            tee = bytearray(f.read())
        at = tee.find(b"SIZE") + 12
        tee[at:at + 12] = struct.pack("<III", 5, 5, 4)
        with open(os.path.join(folder, "Drawn", "v1", "Tee.vox"), "wb") as f:
            f.write(bytes(tee))
        done = run("info", xml, "--tiles", "Drawn/v1")
        self.assertEqual(done.returncode, 1)
        self.assertEqual(len(done.stderr.strip().splitlines()), 1, done.stderr)

    def test_filter_field_data_and_coloured_geometry(self):
        s = modelsynth.vtkMSDiscreteSynthesis()
        out, errors = run_algorithm(s, TilesetFile=data("Tilesets/Pipes.xml"), OutputSize=(4, 4, 3),
                                    GenerateGeometry=1, Seed=7, BlockSize=(2, 2, 3))
        self.assertEqual(errors, "")
        fd = out.GetFieldData()
        tiles = fd.GetAbstractArray("LabelTile")
        symmetry = fd.GetArray("LabelSymmetry")
        self.assertEqual(tiles.GetNumberOfValues(), 85)
        self.assertEqual(symmetry.GetNumberOfTuples(), 85)
        self.assertEqual([tiles.GetValue(i) for i in (0, 1, 25, 84)], ["Empty", "Pipe", "Bend", "Tee"])
        self.assertTrue(all(0 <= symmetry.GetTuple1(i) < 48 for i in range(85)))
        labels = labels_zyx(out)
        self.assertTrue(((labels >= 0) & (labels < 85)).all())
        geometry = s.GetOutputDataObject(1)
        colours = geometry.GetCellData().GetArray("PaletteColor")
        self.assertIsNotNone(colours)
        self.assertEqual(colours.GetNumberOfComponents(), 4)
        self.assertGreater(geometry.GetNumberOfCells(), 0)
        # The voxels fill the model's box: 4 x 4 x 3 sites of unit spacing, 5 voxels each.
        bounds = geometry.GetBounds()
        self.assertTrue(all(-0.5 - 1e-9 <= bounds[2 * a] and bounds[2 * a + 1] <= n - 0.5 + 1e-9
                            for a, n in enumerate((4, 4, 3))), bounds)
        # A missing tiles folder is one error, no crash.
        bad = modelsynth.vtkMSDiscreteSynthesis()
        _, errors = run_algorithm(bad, TilesetFile=data("Tilesets/Pipes.xml"), TilesFolder="/no/such",
                                  OutputSize=(2, 2, 2))
        self.assertIn("Empty.vox", errors)


if __name__ == "__main__":
    unittest.main()
