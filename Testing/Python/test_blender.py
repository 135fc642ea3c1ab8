"""Issue 47 item 3: the exports as a renderer takes them. Debian's Blender (`blender -b`, Cycles on
the CPU) imports mesh.glb of a discrete run (the main job's example), a voxel-tileset run and a
continuous run (the README's houses) and renders it from above (Utilities/blender-render.py
--flat: each face in the colour the file gives it), and the label grid's model.vdb as a volume
(density and color). Each picture is compared with the project's
own rendering of the same model (render-model.py of mesh.vtp / model.vtp): the silhouettes agree
(intersection over union at least 0.9), and with the example's palette: the colours are the
palette's, and for the label grid in the shares of the labels at the top of the columns
(recomputed from labels.vti)."""
import os
import shutil
import subprocess
import unittest
from collections import Counter

import numpy as np
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkIOXML import vtkXMLImageDataReader, vtkXMLPolyDataReader

from msynth_testing import data, fresh_folder, read_png, render_model, run_msynth

SOURCE = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
SIZE = 200
render_model = render_model()


def read_rgba(path):
    """(height, width, 4) RGBA as int, top row first (opaque when the PNG has no alpha)."""
    pixels = read_png(path).astype(int)
    if pixels.shape[2] == 3:
        pixels = np.concatenate([pixels, np.full(pixels.shape[:2] + (1,), 255)], axis=2)
    return pixels


def mesh_cells(path):
    """The cell data of a mesh file (.vtp)."""
    mesh = vtkXMLPolyDataReader()
    mesh.SetFileName(path)
    mesh.Update()
    return mesh.GetOutput().GetCellData()


def framed(mask, n=100):
    """@p mask cropped to its bounding box and sampled on n x n points (so two pictures of one
    silhouette at different scales and margins compare)."""
    rows, cols = np.nonzero(mask)
    box = mask[rows.min():rows.max() + 1, cols.min():cols.max() + 1]
    r = (np.arange(n) + 0.5) * box.shape[0] / n
    c = (np.arange(n) + 0.5) * box.shape[1] / n
    return box[r.astype(int)][:, c.astype(int)]


def iou(a, b):
    a, b = framed(a), framed(b)
    return (a & b).sum() / (a | b).sum()


def near_shares(pixels, palette, tolerance=6):
    """The share of @p pixels within @p tolerance of some colour of @p palette ({key: rgb}), and
    the shares of the keys (each pixel to its nearest colour)."""
    keys = list(palette)
    colours = np.array([palette[k] for k in keys])
    distance = np.abs(pixels[:, None, :] - colours[None, :, :]).max(axis=2)
    nearest = distance.argmin(axis=1)
    close = distance.min(axis=1) <= tolerance
    counts = Counter(nearest[close].tolist())
    return close.mean(), {keys[k]: v / len(pixels) for k, v in counts.items()}


@unittest.skipIf(os.environ.get("MSYNTH_SANITIZED"), "the renders are the Release build's")
class BlenderTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.blender = shutil.which("blender")
        cls.pvpython = shutil.which("pvpython")
        cls.folder = fresh_folder("blender")

    def render_both(self, glb, mesh, name):
        """Blender's flat picture of @p glb and the project's top view of @p mesh: (pixels,
        silhouette IoU)."""
        self.assertIsNotNone(self.blender, "blender not found (Utilities/install-dependencies.sh "
                             "--tests installs Debian's)")
        mine = os.path.join(self.folder, name + "-blender.png")
        done = subprocess.run([self.blender, "-b", "--factory-startup", "-P",
                               os.path.join(SOURCE, "Utilities", "blender-render.py"), "--", glb,
                               mine, "--size", str(SIZE), "--flat"],
                              capture_output=True, text=True, timeout=300)
        self.assertEqual(done.returncode, 0, done.stdout[-2000:] + done.stderr[-2000:])
        self.assertIn("blender-render:", done.stdout)
        theirs = os.path.join(self.folder, name + "-paraview.png")
        done = subprocess.run([self.pvpython, os.path.join(SOURCE, "Utilities", "render-model.py"),
                               mesh, theirs, "--top", "--size", str(SIZE), str(SIZE)],
                              capture_output=True, text=True, timeout=300)
        self.assertEqual(done.returncode, 0, done.stderr[-2000:])
        blender, paraview = read_rgba(mine), read_rgba(theirs)
        silhouette = blender[..., 3] > 128
        drawn = (paraview[..., :3] < 250).any(axis=2)  # render-model.py draws on white
        self.assertGreater(silhouette.sum(), SIZE * SIZE // 20, "%s: Blender drew nothing" % name)
        return blender[silhouette][:, :3], iou(silhouette, drawn)

    def test_a_label_grid_from_magicavoxel(self):
        out = os.path.join(self.folder, "village")
        done = run_msynth("synthesize", data("Examples/Houses.vox"), "--size", "24", "24", "5",
                          "--block", "12", "12", "5", "--ground", "1", "--empty", "0", "--choice",
                          "resemblance", "--seed", "1", "--outputs", "labels,mesh,glb,vdb", "--out",
                          out)
        self.assertEqual(done.returncode, 0, done.stderr)
        pixels, overlap = self.render_both(os.path.join(out, "mesh.glb"),
                                           os.path.join(out, "mesh.vtp"), "village")
        self.assertGreaterEqual(overlap, 0.9)
        # The example's palette: the colour of each label on mesh.vtp's cells (PaletteColor).
        cells = mesh_cells(os.path.join(out, "mesh.vtp"))
        palette = {int(label): tuple(int(v) for v in rgba[:3]) for label, rgba in zip(
            vtk_to_numpy(cells.GetArray("Label")), vtk_to_numpy(cells.GetArray("PaletteColor")))}
        # Seen from above: the label at the top of each column, recomputed from the label grid.
        grid = vtkXMLImageDataReader()
        grid.SetFileName(os.path.join(out, "labels.vti"))
        grid.Update()
        nx, ny, nz = grid.GetOutput().GetDimensions()
        labels = vtk_to_numpy(grid.GetOutput().GetPointData().GetArray("Label")).reshape(nz, ny, nx)
        top = np.zeros((ny, nx), int)
        for z in range(nz):
            top = np.where(labels[z] != 0, labels[z], top)
        expected = Counter()
        for label, count in Counter(top.ravel().tolist()).items():
            expected[palette[label]] += count / top.size
        close, shares = near_shares(pixels, {c: c for c in expected})
        self.assertGreater(close, 0.97, "pixels in the palette's colours of the top labels")
        for colour, share in expected.items():
            self.assertAlmostEqual(shares.get(colour, 0.0), share, delta=0.03, msg=str(colour))
        # model.vdb as a volume: `density` absorbs and `color` is emitted (blender-render.py): the
        # same silhouette as the mesh, and the palette's colours where the ray is absorbed within
        # one voxel (at edges, where it crosses several, the colours blend).
        volume = os.path.join(self.folder, "village-vdb.png")
        done = subprocess.run([self.blender, "-b", "--factory-startup", "-P",
                               os.path.join(SOURCE, "Utilities", "blender-render.py"), "--",
                               os.path.join(out, "model.vdb"), volume, "--size", str(SIZE),
                               "--flat"], capture_output=True, text=True, timeout=300)
        self.assertEqual(done.returncode, 0, done.stdout[-2000:] + done.stderr[-2000:])
        fog = read_rgba(volume)
        mesh_silhouette = read_rgba(os.path.join(self.folder, "village-blender.png"))[..., 3] > 128
        self.assertGreaterEqual(iou(fog[..., 3] > 128, mesh_silhouette), 0.9)
        close, shares = near_shares(fog[fog[..., 3] > 128][:, :3], {c: c for c in expected}, 12)
        self.assertGreater(close, 0.7, "volume pixels in the palette's colours")
        for colour, share in expected.items():
            self.assertGreater(shares.get(colour, 0.0), 0.5 * share, msg=str(colour))

    def test_a_voxel_tileset(self):
        out = os.path.join(self.folder, "pipes")
        done = run_msynth("synthesize", data("Tilesets/Pipes.xml"), "--size", "6", "6", "4",
                          "--seed", "4", "--outputs", "labels,mesh,glb", "--out", out)
        self.assertEqual(done.returncode, 0, done.stderr)
        pixels, overlap = self.render_both(os.path.join(out, "mesh.glb"),
                                           os.path.join(out, "mesh.vtp"), "pipes")
        self.assertGreaterEqual(overlap, 0.9)
        colours = {tuple(int(v) for v in rgba[:3]) for rgba in vtk_to_numpy(
            mesh_cells(os.path.join(out, "mesh.vtp")).GetArray("PaletteColor"))}
        close, _ = near_shares(pixels, {c: c for c in colours})
        self.assertGreater(close, 0.97, "pixels in the tiles' palette colours")

    def test_a_continuous_model(self):
        out = os.path.join(self.folder, "houses")
        done = run_msynth("synthesize", data("Continuous/house.obj"), "--size", "24", "24", "10",
                          "--seed", "3", "--grounded", "--thickness", "wall:z", "--overhang",
                          "roof", "--thickness", "wall:x:2+", "--thickness", "wall:y:2+",
                          "--mirror", "x", "--out", out)
        self.assertEqual(done.returncode, 0, done.stderr)
        pixels, overlap = self.render_both(os.path.join(out, "mesh.glb"),
                                           os.path.join(out, "model.vtp"), "houses")
        self.assertGreaterEqual(overlap, 0.9)
        # The object types' colours (the pictures' palette: type 1 walls, 2 roofs).
        palette = {t: tuple(round(255 * c) for c in render_model.label_colour(t)) for t in (1, 2)}
        close, shares = near_shares(pixels, palette)
        self.assertGreater(close, 0.97, "pixels in the types' colours")
        self.assertGreater(shares.get(2, 0.0), 0.5, "seen from above, the houses are roofs")


if __name__ == "__main__":
    unittest.main()
