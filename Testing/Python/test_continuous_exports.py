"""Continuous models into Blender, game engines and MagicaVoxel (issue 47 item 2): mesh.glb and
model.vox of `msynth synthesize EXAMPLE.obj`, read back here by parsers of their own (the .glb's
JSON and binary chunks; MagicaVoxel's chunks and scene) and checked against model.vtp of the same
run, measured here: per object type the glTF mesh's name, colour, triangle count, bounding box,
area, enclosed volume (positive: the normals point out), closedness and normals; the voxels per
type against the type's volume, within the voxelization's error (half a voxel's diagonal times
the type's surface area)."""
import json
import math
import os
import struct
import sys
import unittest

import numpy as np
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkIOXML import vtkXMLPolyDataReader

import modelsynth
from msynth_testing import ErrorObserver, data, fresh_folder, linear, render_model, run_msynth

# The README's continuous example, as written there.
HOUSES = ["Continuous/house.obj", "--size", "24", "24", "10", "--seed", "3", "--grounded",
          "--thickness", "wall:z", "--overhang", "roof", "--thickness", "wall:x:2+",
          "--thickness", "wall:y:2+", "--mirror", "x"]

render_model = render_model()  # the palette every picture uses


# --- the .glb, parsed here --------------------------------------------------------------------

def read_glb(path):
    """(document, {mesh name: (positions (n, 3) in the model's z-up frame, normals likewise or
    None, triangles (m, 3), material)}) of a .glb: header, chunks and accessors read here."""
    with open(path, "rb") as f:
        blob = f.read()
    magic, version, length = struct.unpack("<4sII", blob[:12])
    assert (magic, version, length) == (b"glTF", 2, len(blob)), (magic, version, length)
    size, kind = struct.unpack("<II", blob[12:20])
    assert kind == 0x4E4F534A, kind  # JSON
    doc = json.loads(blob[20:20 + size])
    at = 20 + size
    binary_size, kind = struct.unpack("<II", blob[at:at + 8])
    assert kind == 0x004E4942, kind  # BIN
    binary = blob[at + 8:at + 8 + binary_size]

    def accessor(index):
        a = doc["accessors"][index]
        view = doc["bufferViews"][a["bufferView"]]
        assert "byteStride" not in view
        dtype = {5126: np.float32, 5125: np.uint32}[a["componentType"]]
        width = {"SCALAR": 1, "VEC3": 3}[a["type"]]
        start = view.get("byteOffset", 0) + a.get("byteOffset", 0)
        values = np.frombuffer(binary, dtype=dtype, count=a["count"] * width, offset=start)
        return values.reshape(-1, width) if width > 1 else values, a

    def to_z_up(v):  # glTF's (x, y, z) is the model's (x, z, -y)
        return np.column_stack([v[:, 0], -v[:, 2], v[:, 1]]).astype(float)

    meshes = {}
    for node in doc["scenes"][0]["nodes"]:
        mesh = doc["meshes"][doc["nodes"][node]["mesh"]]
        assert doc["nodes"][node]["name"] == mesh["name"]
        (primitive,) = mesh["primitives"]
        assert primitive.get("mode", 4) == 4
        positions, pa = accessor(primitive["attributes"]["POSITION"])
        # The accessor's bounds are the positions' (y up).
        np.testing.assert_allclose(pa["min"], positions.min(axis=0), rtol=0, atol=0)
        np.testing.assert_allclose(pa["max"], positions.max(axis=0), rtol=0, atol=0)
        normals = (to_z_up(accessor(primitive["attributes"]["NORMAL"])[0])
                   if "NORMAL" in primitive["attributes"] else None)
        triangles = accessor(primitive["indices"])[0].reshape(-1, 3)
        material = doc["materials"][primitive["material"]]
        meshes[mesh["name"]] = (to_z_up(positions), normals, triangles.astype(np.int64), material)
    return doc, meshes


# --- model.vtp, measured here -----------------------------------------------------------------

def read_model(path):
    """(points, polygons, inside types, outside types or None, {type id: name}) of model.vtp."""
    reader = vtkXMLPolyDataReader()
    reader.SetFileName(path)
    reader.Update()
    model = reader.GetOutput()
    points = vtk_to_numpy(model.GetPoints().GetData()).astype(float)
    offsets = vtk_to_numpy(model.GetPolys().GetOffsetsArray())
    connectivity = vtk_to_numpy(model.GetPolys().GetConnectivityArray())
    polygons = [connectivity[offsets[c]:offsets[c + 1]] for c in range(len(offsets) - 1)]
    cells = model.GetCellData()
    planar = cells.GetArray("ObjectType") is not None
    inside = vtk_to_numpy(cells.GetArray("ObjectType" if planar else "InsideType"))
    outside = None if planar else vtk_to_numpy(cells.GetArray("OutsideType"))
    names_array = model.GetFieldData().GetAbstractArray("TypeNames")
    names = {t: names_array.GetValue(t) for t in range(names_array.GetNumberOfValues())}
    spacing = model.GetFieldData().GetArray("SmallestSpacing").GetValue(0)
    return points, polygons, inside, outside, names, spacing


def type_surfaces(polygons, inside, outside):
    """{type: [corner index arrays]}: polygons with InsideType t as they are, with OutsideType t
    reversed (the closed surface of each type; empty space, 0, left out)."""
    surfaces = {}
    for c, polygon in enumerate(polygons):
        if inside[c] > 0:
            surfaces.setdefault(int(inside[c]), []).append(polygon)
        if outside is not None and outside[c] > 0:
            surfaces.setdefault(int(outside[c]), []).append(polygon[::-1])
    return surfaces


def newell(corners):
    """Twice the area vector of a planar polygon (its normal's direction by its winding)."""
    a, b = corners, np.roll(corners, -1, axis=0)
    return np.array([np.sum((a[:, 1] - b[:, 1]) * (a[:, 2] + b[:, 2])),
                     np.sum((a[:, 2] - b[:, 2]) * (a[:, 0] + b[:, 0])),
                     np.sum((a[:, 0] - b[:, 0]) * (a[:, 1] + b[:, 1]))])


def has_straight_corner(corners):
    incoming = corners - np.roll(corners, 1, axis=0)
    outgoing = np.roll(corners, -1, axis=0) - corners
    turn = np.linalg.norm(np.cross(incoming, outgoing), axis=1)
    return bool(np.any(turn <= 1e-9 * np.linalg.norm(incoming, axis=1) * np.linalg.norm(outgoing, axis=1)))


def polygon_measures(points, polygons):
    """(area, volume by the divergence theorem, triangles the documented triangulation makes:
    n - 2 for n corners, n when a corner is straight) of a closed oriented surface."""
    area = volume = 0.0
    triangles = 0
    for polygon in polygons:
        corners = points[polygon]
        n = newell(corners)
        area += np.linalg.norm(n) / 2
        volume += np.dot(n, corners[0]) / 6  # the cone from the origin over the polygon
        triangles += len(polygon) if has_straight_corner(corners) else len(polygon) - 2
    return area, volume, triangles


def triangle_measures(positions, triangles):
    """(area, signed volume, unit normals by winding) of a triangle mesh."""
    a, b, c = positions[triangles[:, 0]], positions[triangles[:, 1]], positions[triangles[:, 2]]
    cross = np.cross(b - a, c - a)
    length = np.linalg.norm(cross, axis=1)
    return length.sum() / 2, np.einsum("ij,ij->i", a, np.cross(b, c)).sum() / 6, cross / length[:, None]


# --- model.vox, parsed here -------------------------------------------------------------------

def read_vox(path):
    """(grid (x, y, z) of palette indices, palette RGBA (256, 4) by index, number of models):
    MagicaVoxel's chunks read here; a scene's models placed by their nTRN translations (the
    model's centre: lowest corner + size // 2)."""
    with open(path, "rb") as f:
        blob = f.read()
    assert blob[:4] == b"VOX " and struct.unpack("<I", blob[4:8])[0] == 150
    assert blob[8:12] == b"MAIN"
    at = 20 + struct.unpack("<I", blob[12:16])[0]
    models, sizes, translations, shapes, palette = [], [], {}, {}, None
    transform_child = {}

    def read_dict(body, k):
        pairs = {}
        (count,) = struct.unpack("<I", body[k:k + 4])
        k += 4
        for _ in range(count):
            words = []
            for _ in range(2):
                (n,) = struct.unpack("<I", body[k:k + 4])
                words.append(body[k + 4:k + 4 + n].decode())
                k += 4 + n
            pairs[words[0]] = words[1]
        return pairs, k

    while at < len(blob):
        tag, content, children = blob[at:at + 4], *struct.unpack("<II", blob[at + 4:at + 12])
        body = blob[at + 12:at + 12 + content]
        at += 12 + content + children
        if tag == b"SIZE":
            sizes.append(struct.unpack("<III", body[:12]))
        elif tag == b"XYZI":
            (count,) = struct.unpack("<I", body[:4])
            models.append(np.frombuffer(body[4:4 + 4 * count], dtype=np.uint8).reshape(-1, 4))
        elif tag == b"nTRN":
            (node,) = struct.unpack("<I", body[:4])
            _, k = read_dict(body, 4)
            child, _, _, frames = struct.unpack("<IiII", body[k:k + 16])
            frame, _ = read_dict(body, k + 16)
            transform_child[child] = node
            translations[node] = [int(v) for v in frame.get("_t", "0 0 0").split()]
        elif tag == b"nSHP":
            (node,) = struct.unpack("<I", body[:4])
            _, k = read_dict(body, 4)
            (count, model) = struct.unpack("<II", body[k:k + 8])
            shapes[node] = model
        elif tag == b"RGBA":
            rgba = np.frombuffer(body[:1024], dtype=np.uint8).reshape(256, 4)
            palette = np.zeros((256, 4), dtype=np.uint8)
            palette[1:] = rgba[:255]  # entry i of the chunk is palette index i + 1
    corners = [np.zeros(3, dtype=int)] * len(models)
    for node, model in shapes.items():
        centre = np.array(translations[transform_child[node]])
        corners[model] = centre - np.array(sizes[model]) // 2
    low = np.min(corners, axis=0) if corners else np.zeros(3, dtype=int)
    high = np.max([c + np.array(s) for c, s in zip(corners, sizes)], axis=0)
    grid = np.zeros(high - low, dtype=np.uint8)
    for corner, voxels in zip(corners, models):
        x, y, z = (voxels[:, :3].astype(int) + corner - low).T
        grid[x, y, z] = voxels[:, 3]
    return grid, palette, len(models)


class ContinuousExportsTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.out = os.path.join(fresh_folder("continuous-exports"), "houses")
        done = run_msynth("synthesize", data(HOUSES[0]), *HOUSES[1:], "--outputs",
                          "mesh,glb,vox", "--out", cls.out)
        assert done.returncode == 0, done.stderr
        cls.stdout = done.stdout
        with open(os.path.join(cls.out, "statistics.json")) as f:
            cls.stats = json.load(f)

    def check_glb(self, glb, vtp, flat=False):
        """mesh.glb against model.vtp, type by type; returns the meshes."""
        points, polygons, inside, outside, names, _ = read_model(vtp)
        surfaces = type_surfaces(polygons, inside, outside)
        doc, meshes = read_glb(glb)
        self.assertEqual(doc["asset"]["version"], "2.0")
        self.assertEqual(sorted(meshes), sorted(names[t] for t in surfaces))
        self.assertEqual([m["name"] for m in doc["materials"]],
                         [names[t] for t in sorted(surfaces)])
        for t, surface in sorted(surfaces.items()):
            name = names[t]
            positions, normals, triangles, material = meshes[name]
            area, volume, count = polygon_measures(points, surface)
            glb_area, glb_volume, winding = triangle_measures(positions, triangles)
            self.assertEqual(len(triangles), count, name)
            corners = points[np.concatenate(surface)]
            np.testing.assert_allclose(positions.min(axis=0), corners.min(axis=0), atol=1e-5)
            np.testing.assert_allclose(positions.max(axis=0), corners.max(axis=0), atol=1e-5)
            self.assertAlmostEqual(glb_area, area, delta=1e-5 * area)
            if not flat:
                self.assertGreater(volume, 0, name)
                self.assertAlmostEqual(glb_volume, volume, delta=1e-5 * volume)
                # Closed and consistently wound: every directed edge has its reverse.
                key = [tuple(p) for p in np.round(positions, 4)]
                edges = {}
                for a, b, c in triangles:
                    for u, v in ((a, b), (b, c), (c, a)):
                        edges[(key[u], key[v])] = edges.get((key[u], key[v]), 0) + 1
                self.assertTrue(all(edges.get((v, u), 0) == n for (u, v), n in edges.items()), name)
            else:
                np.testing.assert_allclose(winding, [[0, 0, 1]] * len(winding), atol=1e-6)
            # Each corner's normal is its triangle's, by the winding.
            self.assertIsNotNone(normals, name)
            for k in range(3):
                np.testing.assert_allclose(normals[triangles[:, k]], winding, atol=1e-5)
            factor = material["pbrMetallicRoughness"]["baseColorFactor"]
            np.testing.assert_allclose(factor, [linear(c) for c in render_model.label_colour(t)] + [1],
                                       atol=1e-6)
            self.assertEqual(material.get("doubleSided", False), flat, name)
        return meshes

    def check_vox(self, vox, vtp, voxel, flat=False):
        """model.vox against model.vtp: size, palette, voxels per type against volume (area)."""
        points, polygons, inside, outside, names, _ = read_model(vtp)
        grid, palette, models = read_vox(vox)
        axes = 2 if flat else 3
        extent = points.max(axis=0) - points.min(axis=0)
        want = [max(1, math.ceil(extent[a] / voxel - 1e-6)) if a < axes else 1 for a in range(3)]
        self.assertEqual(list(grid.shape), want)
        report = []
        for t, surface in sorted(type_surfaces(polygons, inside, outside).items()):
            area, volume, _ = polygon_measures(points, surface)
            count = int(np.count_nonzero(grid == t))
            if flat:  # one layer: voxels of voxel^2 against the type's area, error along its rim
                measure = area
                rim = sum(np.linalg.norm(points[np.roll(p, -1)] - points[p], axis=1).sum()
                          for p in surface)
                bound = math.sqrt(2) / 2 * voxel * rim
                got = count * voxel ** 2
            else:
                measure = volume
                bound = math.sqrt(3) / 2 * voxel * area
                got = count * voxel ** 3
            report.append("%s: %d voxels, %.3f against %.3f (bound %.3f)" % (
                names[t], count, got, measure, bound))
            self.assertLessEqual(abs(got - measure), bound, report[-1])
            if count >= 1000:  # sampled evenly (ties split), well inside the bound
                self.assertLessEqual(abs(got - measure), 0.05 * measure, report[-1])
            self.assertGreater(count, 0, report[-1])
            rgb = [255 * c for c in render_model.label_colour(t)] + [255]
            np.testing.assert_allclose(palette[t], rgb, atol=0.51, err_msg=names[t])  # rounded
        # No voxel holds an index that is not a solid type of the model.
        self.assertLessEqual(set(int(v) for v in np.unique(grid)) - {0},
                             set(type_surfaces(polygons, inside, outside)))
        print("\n".join(report))
        return grid, models

    def test_readme_houses_glb(self):
        meshes = self.check_glb(os.path.join(self.out, "mesh.glb"), os.path.join(self.out, "model.vtp"))
        self.assertEqual(sorted(meshes), ["roof", "wall"])
        self.assertIn("mesh.glb", self.stats["StageSeconds"])
        self.assertIn("/mesh.glb, ", self.stdout)

    def test_readme_houses_vox(self):
        vtp = os.path.join(self.out, "model.vtp")
        spacing = read_model(vtp)[5]
        voxel = self.stats["VoxVoxelSize"]
        # The default: half the smallest spacing, at least the extent / 256.
        points = read_model(vtp)[0]
        self.assertAlmostEqual(voxel, max(spacing / 2, (points.max(axis=0) - points.min(axis=0)).max() / 256))
        grid, models = self.check_vox(os.path.join(self.out, "model.vox"), vtp, voxel)
        self.assertEqual(models, 1)
        self.assertLessEqual(max(grid.shape), 256)

    def test_fine_voxels_are_a_scene_of_models(self):
        """Python's writer, a voxel fine enough for 288 voxels along x: MagicaVoxel's scene of
        two models, composed back into the same grid."""
        reader = vtkXMLPolyDataReader()
        reader.SetFileName(os.path.join(self.out, "model.vtp"))
        writer = modelsynth.vtkMSLabelGridWriter()
        writer.SetInputConnection(reader.GetOutputPort())
        path = os.path.join(fresh_folder("continuous-exports-scene"), "fine.vox")
        writer.SetFileName(path)
        writer.SetVoxelSize(23 / 288)
        errors = ErrorObserver(writer)
        self.assertEqual(writer.Write(), 1)
        self.assertEqual(errors.text(), "")
        self.assertAlmostEqual(writer.GetWrittenVoxelSize(), 23 / 288)
        grid, models = self.check_vox(path, os.path.join(self.out, "model.vtp"), 23 / 288)
        self.assertEqual(grid.shape[0], 288)
        self.assertEqual(models, 2)

    def test_refusals_name_the_file(self):
        reader = vtkXMLPolyDataReader()
        reader.SetFileName(os.path.join(self.out, "model.vtp"))
        folder = fresh_folder("continuous-exports-refused")
        for name, voxel, message in (("tiny.vox", 0.01, "more than 1000"),
                                     ("model.txt", 0, "written as .vox only")):
            writer = modelsynth.vtkMSLabelGridWriter()
            writer.SetInputConnection(reader.GetOutputPort())
            writer.SetFileName(os.path.join(folder, name))
            writer.SetVoxelSize(voxel)
            errors = ErrorObserver(writer)
            writer.Write()
            self.assertIn(name, errors.text())
            self.assertIn(message, errors.text())
            self.assertFalse(os.path.exists(os.path.join(folder, name)))
        r = run_msynth("synthesize", data("Continuous/house.obj"), "--size", "8", "8", "4",
                       "--outputs", "mesh,picture", "--out", os.path.join(folder, "x"))
        self.assertEqual(r.returncode, 1)
        self.assertIn("glb (mesh.glb) and vox (model.vox), not 'picture'", r.stderr)

    def test_large_label_grid_vox_is_a_scene(self):
        """A label grid past 256 sites a side (a discrete model) is MagicaVoxel's scene of models
        of at most 256 a side, composed back into the same labels."""
        from vtkmodules.util.numpy_support import numpy_to_vtk
        from vtkmodules.vtkCommonDataModel import vtkImageData
        labels = (np.arange(300 * 3 * 2) % 4).astype(np.int32).reshape(2, 3, 300)  # z, y, x
        image = vtkImageData()
        image.SetDimensions(300, 3, 2)
        array = numpy_to_vtk(labels.ravel(), deep=True)
        array.SetName("Label")
        image.GetPointData().AddArray(array)
        writer = modelsynth.vtkMSLabelGridWriter()
        writer.SetInputData(image)
        path = os.path.join(fresh_folder("continuous-exports-grid"), "wide.vox")
        writer.SetFileName(path)
        errors = ErrorObserver(writer)
        self.assertEqual(writer.Write(), 1)
        self.assertEqual(errors.text(), "")
        grid, _, models = read_vox(path)
        self.assertEqual(models, 2)
        self.assertTrue(np.array_equal(grid, labels.transpose(2, 1, 0)))

    def test_flat_model(self):
        """A 2D example: flat meshes facing up (glTF's +y), double-sided; one layer of voxels."""
        out = os.path.join(fresh_folder("continuous-exports-flat"), "flat")
        done = run_msynth("synthesize", data("Continuous/two-objects2d.obj"), "--size", "12", "12",
                          "0", "--seed", "1", "--outputs", "mesh,glb,vox", "--out", out)
        self.assertEqual(done.returncode, 0, done.stderr)
        vtp = os.path.join(out, "model.vtp")
        self.check_glb(os.path.join(out, "mesh.glb"), vtp, flat=True)
        with open(os.path.join(out, "statistics.json")) as f:
            voxel = json.load(f)["VoxVoxelSize"]
        self.check_vox(os.path.join(out, "model.vox"), vtp, voxel, flat=True)

    def test_default_outputs_include_glb(self):
        out = os.path.join(fresh_folder("continuous-exports-default"), "l")
        done = run_msynth("synthesize", data("Continuous/l-prism.obj"), "--size", "6", "6", "3",
                          "--seed", "1", "--out", out)
        self.assertEqual(done.returncode, 0, done.stderr)
        self.assertEqual(sorted(f for f in os.listdir(out) if not f.startswith(".")),
                         ["arrangement.vtp", "mesh.glb", "model.vdb", "model.vtp", "statistics.json"])
        self.check_glb(os.path.join(out, "mesh.glb"), os.path.join(out, "model.vtp"))


if __name__ == "__main__":
    unittest.main(argv=sys.argv[:1], verbosity=2)
