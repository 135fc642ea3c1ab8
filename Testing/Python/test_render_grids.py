"""model.vdb of discrete runs holds what a renderer shades (issue 47): `density` (fog volume of
the solid sites), `color` (the palette in linear RGB), `surface` (level set, negative exactly at
the solid sites) and `surface_NAME` per named label, on the label grid's transform; read back with
OpenVDB's own Python (pyopenvdb) and the project's reader, and checked against labels.vti, the
palette of Utilities/render-model.py and a .vox example's palette; also a voxel tileset's (at its
voxels), each slab of a stream, and every frame of an animation."""
import glob
import importlib.util
import os
import unittest

import numpy as np
import pyopenvdb
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkIOXML import vtkXMLImageDataReader, vtkXMLPolyDataReader

import modelsynth
from msynth_testing import ErrorObserver, data, fresh_folder, run_msynth

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
spec = importlib.util.spec_from_file_location(
    "render_model", os.path.join(ROOT, "Utilities", "render-model.py"))
render_model = importlib.util.module_from_spec(spec)
spec.loader.exec_module(render_model)


def linear(c):
    """A display (sRGB) component as linear, as renderers take colours."""
    return c / 12.92 if c <= 0.04045 else ((c + 0.055) / 1.055) ** 2.4


def read_labels(path, name="Label"):
    """The labels of a .vti as an (x, y, z) array, and the image."""
    r = vtkXMLImageDataReader()
    r.SetFileName(path)
    r.Update()
    image = r.GetOutput()
    nx, ny, nz = image.GetDimensions()
    values = vtk_to_numpy(image.GetPointData().GetArray(name)).reshape(nz, ny, nx)
    return values.transpose(2, 1, 0), image


def grid(path, name):
    return pyopenvdb.read(path, name)


def dense(g, lo, shape, components=1):
    """Grid @p g over the index box starting at @p lo with @p shape, (x, y, z) indexed."""
    out = np.zeros(tuple(shape) + ((components,) if components > 1 else ()), dtype=np.float32)
    g.copyToArray(out, ijk=tuple(int(v) for v in lo))
    return out


def grid_names(path):
    """The names of the grids of @p path (pyopenvdb cannot read int32 grids: the project's
    reader, whose arrays are the grids)."""
    image, _ = read_vdb(path)
    data_ = image.GetPointData()
    return {data_.GetArrayName(i) for i in range(data_.GetNumberOfArrays())}


def read_vdb(path):
    reader = modelsynth.vtkMSOpenVDBReader()
    errors = ErrorObserver(reader)
    reader.SetFileName(path)
    reader.Update()
    return reader.GetOutput(), errors.text()


class RenderGridsTest(unittest.TestCase):
    def check_render_grids(self, vdb, labels, lo, image, empty=0):
        """The render grids of @p vdb against the labels (x, y, z) whose first site is index @p lo
        (of @p image, whose origin and spacing place them): classes, transform, density on
        exactly the solid sites, surface negative exactly inside them. Returns the solid mask and
        the colour grid over the labels."""
        solid = labels != empty
        density = grid(vdb, "density")
        surface = grid(vdb, "surface")
        self.assertEqual(density.gridClass, "fog volume")
        self.assertEqual(surface.gridClass, "level set")
        self.assertEqual(density.activeVoxelCount(), int(solid.sum()))
        np.testing.assert_array_equal(dense(density, lo, labels.shape), solid.astype(np.float32))
        inside = dense(surface, lo, labels.shape) < 0
        np.testing.assert_array_equal(inside, solid)
        # Outside the labels the level set is positive: the box grown by the band.
        grown = [v - 3 for v in lo]
        shape = [n + 6 for n in labels.shape]
        self.assertEqual(int((dense(surface, grown, shape) < 0).sum()), int(solid.sum()))
        self.assertAlmostEqual(surface.background, 3 * surface.transform.voxelSize()[0], places=5)
        origin, spacing = np.array(image.GetOrigin()), np.array(image.GetSpacing())
        for name in ("density", "color", "surface"):
            placed = grid(vdb, name).transform.indexToWorld((1, 2, 3))
            np.testing.assert_allclose(placed, origin + np.array([1, 2, 3]) * spacing, atol=1e-9)
        color = dense(grid(vdb, "color"), lo, labels.shape, 3)
        return solid, color

    def test_label_grid_run(self):
        out = fresh_folder("render-village")
        done = run_msynth("synthesize", data("Examples/Village.txt"), "--size", "20", "16", "5",
                          "--block", "10", "8", "5", "--seed", "4", "--out", out)
        self.assertEqual(done.returncode, 0, done.stderr)
        vdb = os.path.join(out, "model.vdb")
        labels, image = read_labels(os.path.join(out, "labels.vti"))
        solid, color = self.check_render_grids(vdb, labels, (0, 0, 0), image)
        for label in np.unique(labels[solid]):
            expected = [linear(c) for c in render_model.label_colour(int(label))]
            got = color[labels == label]
            np.testing.assert_allclose(got, np.tile(expected, (len(got), 1)), atol=1e-6)
        self.assertTrue((color[~solid] == 0).all())
        # surface_NAME per named label present (Village.txt names its pieces).
        names = grid_names(vdb)
        self.assertIn("surface_roof", names)
        roof = grid(vdb, "surface_roof")
        np.testing.assert_array_equal(dense(roof, (0, 0, 0), labels.shape) < 0, labels == 3)
        # The project's reader reads them all onto the labels' extent.
        image, errors = read_vdb(vdb)
        self.assertEqual(errors, "")
        self.assertEqual(image.GetDimensions(), labels.shape)
        arrays = {image.GetPointData().GetArrayName(i)
                  for i in range(image.GetPointData().GetNumberOfArrays())}
        self.assertTrue({"Label", "density", "color", "surface", "surface_roof"} <= arrays, arrays)
        density = vtk_to_numpy(image.GetPointData().GetArray("density"))
        self.assertEqual(int(density.sum()), int(solid.sum()))
        # msynth info describes it.
        info = run_msynth("info", vdb)
        self.assertEqual(info.returncode, 0, info.stderr)
        self.assertIn("density", info.stdout)
        self.assertIn("fog volume", info.stdout)
        self.assertIn("level set", info.stdout)

    def test_vox_example_takes_its_palette(self):
        out = fresh_folder("render-houses")
        done = run_msynth("synthesize", data("Examples/Houses.vox"), "--size", "24", "24", "8",
                          "--seed", "2", "--out", out)
        self.assertEqual(done.returncode, 0, done.stderr)
        reader = modelsynth.vtkMSLabelGridReader()
        reader.SetFileName(data("Examples/Houses.vox"))
        reader.Update()
        palette = vtk_to_numpy(reader.GetOutput().GetFieldData().GetArray("PaletteRGBA"))
        labels, image = read_labels(os.path.join(out, "labels.vti"))
        solid, color = self.check_render_grids(os.path.join(out, "model.vdb"), labels, (0, 0, 0),
                                               image)
        for label in np.unique(labels[solid]):
            expected = [linear(c / 255.0) for c in palette[label][:3]]
            np.testing.assert_allclose(color[labels == label][0], expected, atol=1e-6)

    def test_voxel_tileset_at_its_voxels(self):
        out = fresh_folder("render-pipes")
        done = run_msynth("synthesize", data("Tilesets/Pipes.xml"), "--size", "4", "4", "3",
                          "--seed", "1", "--out", out)
        self.assertEqual(done.returncode, 0, done.stderr)
        vdb = os.path.join(out, "model.vdb")
        image, errors = read_vdb(vdb)
        self.assertEqual(errors, "")  # no grid skipped for another transform
        voxels = vtk_to_numpy(image.GetPointData().GetArray("Label"))
        nx, ny, nz = image.GetDimensions()
        labels = voxels.reshape(nz, ny, nx).transpose(2, 1, 0)
        self.check_render_grids(vdb, labels, (0, 0, 0), image)
        # The voxels' boxes are where mesh.vtp's faces are.
        mesh = vtkXMLPolyDataReader()
        mesh.SetFileName(os.path.join(out, "mesh.vtp"))
        mesh.Update()
        solid = np.argwhere(labels != 0)
        origin, spacing = np.array(image.GetOrigin()), np.array(image.GetSpacing())
        lo = origin + solid.min(axis=0) * spacing - spacing / 2
        hi = origin + solid.max(axis=0) * spacing + spacing / 2
        bounds = mesh.GetOutput().GetBounds()
        np.testing.assert_allclose(lo, bounds[0::2], atol=1e-5)
        np.testing.assert_allclose(hi, bounds[1::2], atol=1e-5)
        names = grid_names(vdb)
        self.assertTrue(any(n.startswith("surface_") for n in names), names)

    def test_each_slab_of_a_stream(self):
        out = fresh_folder("render-stream")
        done = run_msynth("synthesize", data("Examples/Village.vti"), "--size", "20", "40", "5",
                          "--block", "10", "10", "5", "--seed", "3", "--stream", "--slab", "20",
                          "--empty", "0", "--out", out)
        self.assertEqual(done.returncode, 0, done.stderr)
        slabs = sorted(glob.glob(os.path.join(out, "labels", "labels_*.vti")))
        self.assertGreater(len(slabs), 1)
        for slab in slabs:
            labels, image = read_labels(slab)
            e = image.GetExtent()
            vdb = os.path.join(out, "vdb", "model_" + os.path.basename(slab)[7:-4] + ".vdb")
            self.check_render_grids(vdb, labels, (e[0], e[2], e[4]), image)

    def test_every_frame_of_an_animation(self):
        out = fresh_folder("render-animate")
        done = run_msynth("animate", data("Examples/Ball.vti"), "--size", "16", "1", "1",
                          "--frames", "3", "--loop", "--seed", "3", "--out", out)
        self.assertEqual(done.returncode, 0, done.stderr)
        for t in range(1, 4):  # frame N is frame_N.vti and model_N.vdb
            labels, image = read_labels(os.path.join(out, "frame_%04d.vti" % t))
            self.check_render_grids(os.path.join(out, "model_%04d.vdb" % t), labels,
                                    (0, 0, 0), image)

    def test_writer_properties_from_python(self):
        w = modelsynth.vtkMSOpenVDBWriter()
        self.assertTrue(w.GetWriteRenderGrids())
        self.assertEqual(w.GetLabelSurfaceBudget(), 2e7)
        labels, image = read_labels(os.path.join(ROOT, "Data", "Examples", "Village.vti"))
        folder = fresh_folder("render-writer")
        for render, expected in ((False, set()), (True, {"density", "color", "surface"})):
            w = modelsynth.vtkMSOpenVDBWriter()
            w.SetInputData(image)
            w.SetWriteRenderGrids(render)
            w.SetLabelSurfaceBudget(0)  # no surface_NAME
            path = os.path.join(folder, "w%d.vdb" % render)
            w.SetFileName(path)
            self.assertEqual(w.Write(), 1)
            names = grid_names(path)
            self.assertEqual(names & {"density", "color", "surface"}, expected)
            self.assertFalse(any(n.startswith("surface_") for n in names))


if __name__ == "__main__":
    unittest.main()
