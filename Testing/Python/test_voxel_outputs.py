"""A voxel tileset's mesh.glb and its --pieces, checked against model.vox (itself verified by
`msynth check`) with readers written here:
- mesh.glb (`--outputs glb`): the file's chunks, accessors and buffer views parsed here; its
  triangles, grouped by the plane they lie in and their material's colour, cover exactly the
  exposed faces of model.vox's voxels (counted here from the voxels and the palette), as
  mesh.vtp's merged rectangles do; VTK's own glTF reader loads it.
- a mesh.vtp past a million faces (written with LZ4, raw): its rectangles, by plane and colour,
  cover exactly the exposed voxel faces of model.vox, counted here with array operations.
- `--pieces`: each tile's piece drawn from the tile's voxels (a small triangle at each voxel's
  centre); the pieces placed in the model (but at label 0, the mesh's empty label), turned by the set's symmetry group (the square's 8
  about z for Tracks, the cube's 48 for Pipes), put a triangle at every voxel of model.vox and
  nowhere else."""
import json
import os
import struct
import unittest
from collections import Counter

import numpy as np
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkIOGeometry import vtkGLTFReader
from vtkmodules.vtkIOXML import vtkXMLPolyDataReader

from msynth_testing import data, fresh_folder, labels_zyx, read_label_grid
from msynth_testing import run_msynth as msynth
from test_voxel_tilesets import vox_models

PIPES, TRACKS = data("Tilesets/Pipes.xml"), data("Tilesets/Tracks.xml")


def glb_triangles(path):
    """[(colour as sRGB bytes, triangles (n, 3, 3) in the model's z-up frame)] of a .glb."""
    with open(path, "rb") as f:
        blob = f.read()
    magic, version, length = struct.unpack("<4sII", blob[:12])
    assert (magic, version, length) == (b"glTF", 2, len(blob))
    size, kind = struct.unpack("<II", blob[12:20])
    assert kind == 0x4E4F534A
    doc = json.loads(blob[20:20 + size])
    bsize, bkind = struct.unpack("<II", blob[20 + size:28 + size])
    assert bkind == 0x004E4942 and bsize >= doc["buffers"][0]["byteLength"]
    binary = blob[28 + size:28 + size + bsize]

    def accessor(i, dtype, width):
        a = doc["accessors"][i]
        view = doc["bufferViews"][a["bufferView"]]
        start = view.get("byteOffset", 0) + a.get("byteOffset", 0)
        count = a["count"] * width
        return np.frombuffer(binary, dtype=dtype, count=count, offset=start).reshape(-1, width)
    out = []
    for node in doc["scenes"][0]["nodes"]:
        for prim in doc["meshes"][doc["nodes"][node]["mesh"]]["primitives"]:
            assert prim.get("mode", 4) == 4
            xyz = accessor(prim["attributes"]["POSITION"], np.float32, 3).astype(float)
            xyz = np.stack([xyz[:, 0], -xyz[:, 2], xyz[:, 1]], axis=1)  # y up -> z up
            tri = accessor(prim["indices"], np.uint32, 1).reshape(-1, 3)
            linear = doc["materials"][prim["material"]]["pbrMetallicRoughness"]["baseColorFactor"]
            srgb = tuple(round(255 * (12.92 * c if c <= 0.0031308 else
                                      1.055 * c ** (1 / 2.4) - 0.055)) for c in linear[:3])
            out.append((srgb, xyz[tri]))
    return out


def exposed_faces(vox_path):
    """Counter of (axis, plane index in voxels, sRGB colour) over the faces of model.vox's voxels
    that do not touch a voxel of their colour (as a label surface has them), and the voxels."""
    sizes, voxels, palette = vox_models(vox_path)
    assert len(sizes) == 1
    filled = {(int(x), int(y), int(z)): int(c) for x, y, z, c in voxels[0]}
    faces = Counter()
    for (x, y, z), c in filled.items():
        for axis in range(3):
            for step in (-1, 1):
                n = [x, y, z]
                n[axis] += step
                if filled.get(tuple(n)) != c:  # empty or another colour: a face of c
                    plane = (x, y, z)[axis] + (1 if step > 0 else 0)
                    faces[(axis, plane, tuple(int(v) for v in palette[c - 1][:3]))] += 1
    return faces, filled


class VoxelOutputsTest(unittest.TestCase):
    def synthesize(self, xml, name, *extra):
        out = fresh_folder(name)
        size = ["6", "6", "4"] if xml == PIPES else ["10", "10", "1"]
        done = msynth("synthesize", xml, "--size", *size, "--seed", "5", "--out", out, *extra)
        self.assertEqual(done.returncode, 0, done.stderr)
        checked = msynth("check", xml, os.path.join(out, "model.vox"))
        self.assertEqual(checked.returncode, 0, checked.stdout + checked.stderr)
        return out

    def test_glb_covers_the_voxel_surface(self):
        for xml in (PIPES, TRACKS):
            out = self.synthesize(xml, "voxel-glb", "--outputs", "labels,vox,mesh,glb")
            faces, _ = exposed_faces(os.path.join(out, "model.vox"))
            # Voxels per site along each axis (a 2D set's voxel fills its site's height).
            per = np.array([5, 5, 5] if xml == PIPES else [6, 6, 1], float)
            # glb triangles: area per (axis, plane, colour), in voxel faces.
            area = Counter()
            for colour, tris in glb_triangles(os.path.join(out, "mesh.glb")):
                cross = np.cross(tris[:, 1] - tris[:, 0], tris[:, 2] - tris[:, 0])
                for t, c in zip(tris, cross):
                    axis = int(np.argmax(np.abs(c)))
                    self.assertAlmostEqual(np.abs(c).sum(), abs(c[axis]), places=5)
                    plane = int(round((t[0][axis] + 0.5) * per[axis]))
                    area[(axis, plane, colour)] += abs(c[axis]) / 2 * np.prod(per) / per[axis]
            self.assertEqual(set(area), set(faces))
            for key, count in faces.items():
                self.assertAlmostEqual(area[key], count, places=3, msg=str(key))
            # Fewer triangles than two per voxel face: the rectangles are merged, as in mesh.vtp.
            triangles = sum(len(t) for _, t in glb_triangles(os.path.join(out, "mesh.glb")))
            self.assertLess(triangles, 2 * sum(faces.values()))
            reader = vtkXMLPolyDataReader()
            reader.SetFileName(os.path.join(out, "mesh.vtp"))
            reader.Update()
            quads = reader.GetOutput().GetNumberOfCells()
            self.assertEqual(triangles, 2 * quads)  # each merged rectangle as two triangles
            gltf = vtkGLTFReader()
            gltf.SetFileName(os.path.join(out, "mesh.glb"))
            gltf.Update()
            self.assertGreater(gltf.GetOutput().GetNumberOfPoints(), 0)

    @unittest.skipIf(os.environ.get("MSYNTH_SANITIZED"), "a model of 7.5 M voxels: Release only")
    def test_a_mesh_of_millions_of_faces_is_fast_and_exact(self):
        out = fresh_folder("voxel-large-mesh")
        done = msynth("synthesize", PIPES, "--size", "48", "48", "26", "--block", "16", "16", "16",
                      "--seed", "2", "--outputs", "vox,mesh", "--out", out)
        self.assertEqual(done.returncode, 0, done.stderr)
        path = os.path.join(out, "mesh.vtp")
        with open(path, "rb") as f:
            head = f.read(4096)
        self.assertIn(b'compressor="vtkLZ4DataCompressor"', head)
        self.assertIn(b'<AppendedData encoding="raw">', head)
        # The voxels as a dense array of palette indices (one model: 240 x 240 x 130).
        sizes, voxels, palette = vox_models(os.path.join(out, "model.vox"))
        self.assertEqual(len(sizes), 1)
        grid = np.zeros(sizes[0], np.int16)
        v = voxels[0].astype(np.int64)
        grid[v[:, 0], v[:, 1], v[:, 2]] = v[:, 3]
        # Exposed faces per (axis, plane, palette index): a voxel face whose neighbour differs.
        want = Counter()
        for axis in range(3):
            padded = np.pad(grid, [(1, 1) if a == axis else (0, 0) for a in range(3)])
            lo = np.take(padded, range(0, padded.shape[axis] - 1), axis=axis)
            hi = np.take(padded, range(1, padded.shape[axis]), axis=axis)
            for side, other in ((lo, hi), (hi, lo)):
                exposed = (side != 0) & (side != other)
                planes = np.nonzero(exposed)[axis]
                colours = side[exposed]
                keys, counts = np.unique(planes * 256 + colours, return_counts=True)
                for k, c in zip(keys, counts):
                    want[(axis, int(k) // 256, int(k) % 256)] += int(c)
        reader = vtkXMLPolyDataReader()
        reader.SetFileName(path)
        reader.Update()
        mesh = reader.GetOutput()
        self.assertGreaterEqual(mesh.GetNumberOfCells(), 1 << 20)
        xyz = vtk_to_numpy(mesh.GetPoints().GetData()).astype(float)
        quads = vtk_to_numpy(mesh.GetPolys().GetConnectivityArray()).reshape(-1, 4)
        labels = vtk_to_numpy(mesh.GetCellData().GetArray("Label"))
        corners = xyz[quads] * 5 + 2.5  # in voxels, from the sites' cell corners
        extent = corners.max(axis=1) - corners.min(axis=1)
        axis = np.argmin(extent, axis=1)
        self.assertTrue(np.all(extent[np.arange(len(axis)), axis] < 1e-3))
        area = np.prod(extent, axis=1, where=np.arange(3)[None, :] != axis[:, None])
        plane = np.rint(corners[np.arange(len(axis)), 0, axis]).astype(np.int64)
        keys, where = np.unique((axis * 100000 + plane) * 256 + labels, return_inverse=True)
        sums = np.rint(np.bincount(where, weights=area)).astype(np.int64)
        got = Counter({(int(k) // 256 // 100000, int(k) // 256 % 100000, int(k) % 256): int(c)
                       for k, c in zip(keys, sums)})
        self.assertEqual(got, want)

    def test_pieces_turn_by_the_sets_symmetry_group(self):
        for xml, tile, n in ((PIPES, 5, 48), (TRACKS, 6, 8)):
            pieces = fresh_folder("voxel-pieces-" + str(n))
            tiles = os.path.splitext(xml)[0]
            for name in os.listdir(tiles):
                _, voxels, _ = vox_models(os.path.join(tiles, name))
                lines = []
                for i, (x, y, z, _) in enumerate(voxels[0]):
                    c = (np.array([x, y, z], float) + 0.5) / tile - 0.5
                    if tile == 6:
                        c[2] = 0.0  # a 2D tile's voxels fill its site's height
                    for d in ((0.01, 0, 0), (0, 0.01, 0), (-0.01, -0.01, 0)):
                        lines.append("v %r %r %r" % tuple(c + np.array(d)))
                    lines.append("f %d %d %d" % (3 * i + 1, 3 * i + 2, 3 * i + 3))
                if lines:
                    with open(os.path.join(pieces, name[:-4] + ".obj"), "w") as f:
                        f.write("\n".join(lines) + "\n")
            out = self.synthesize(xml, "voxel-pieces-out-" + str(n), "--outputs",
                                  "labels,vox,mesh", "--pieces", pieces)
            _, filled = exposed_faces(os.path.join(out, "model.vox"))
            sites = labels_zyx(read_label_grid(os.path.join(out, "labels.vti")))
            depth = 5 if tile == 5 else 1  # voxels per site along z
            filled = {v for v in filled  # label 0 is the mesh's empty label (Tracks' Grass)
                      if sites[v[2] // depth, v[1] // tile, v[0] // tile] != 0}
            reader = vtkXMLPolyDataReader()
            reader.SetFileName(os.path.join(out, "mesh.vtp"))
            reader.Update()
            mesh = reader.GetOutput()
            points = vtk_to_numpy(mesh.GetPoints().GetData()).astype(float)
            cells = vtk_to_numpy(mesh.GetPolys().GetConnectivityArray()).reshape(-1, 3)
            centres = points[cells].mean(axis=1)
            xyz = np.rint((centres + 0.5) * tile - 0.5).astype(int)
            if tile == 6:
                xyz[:, 2] = np.rint(centres[:, 2]).astype(int)
            placed = Counter(map(tuple, xyz))
            self.assertEqual(set(placed), set(filled), n)
            self.assertEqual(max(placed.values()), 1)


if __name__ == "__main__":
    unittest.main()
