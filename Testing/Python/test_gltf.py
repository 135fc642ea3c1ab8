"""mesh.glb (vtkMSGLTFWriter, `msynth synthesize --outputs glb`): read back by VTK's glTF reader
and by parsing the file's JSON here; each material's colour and each mesh's triangles checked
against the mesh written (its labels, palette colours and pieces), colours against
Utilities/render-model.py's palette; errors are one line naming the file."""
import json
import os
import shutil
import struct
import subprocess
import unittest

import numpy as np
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkIOGeometry import vtkGLTFReader
from vtkmodules.vtkIOXML import vtkXMLPolyDataReader

import modelsynth
from msynth_testing import BIN, ErrorObserver, data, fresh_folder, linear, render_model, tmp

MSYNTH = os.path.join(BIN, "msynth")
TIMEOUT = 300 if os.environ.get("MSYNTH_SANITIZED") else 120

render_model = render_model()  # the palette every picture uses


def glb_json(path):
    """The JSON chunk of a .glb file, parsed here (header, chunk lengths and types checked)."""
    with open(path, "rb") as f:
        blob = f.read()
    magic, version, length = struct.unpack("<4sII", blob[:12])
    assert (magic, version, length) == (b"glTF", 2, len(blob)), (magic, version, length)
    size, kind = struct.unpack("<II", blob[12:20])
    assert kind == 0x4E4F534A, kind  # "JSON"
    return json.loads(blob[20:20 + size])


def read_back(path):
    """VTK's glTF reader: [(points (n, 3) in the model's z-up frame, triangle count)] per mesh,
    in node order."""
    reader = vtkGLTFReader()
    reader.SetFileName(path)
    reader.Update()
    blocks = []
    iterator = reader.GetOutput().NewIterator()
    iterator.InitTraversal()
    while not iterator.IsDoneWithTraversal():
        mesh = iterator.GetCurrentDataObject()
        xyz = vtk_to_numpy(mesh.GetPoints().GetData()).astype(float)
        polys = vtk_to_numpy(mesh.GetPolys().GetConnectivityArray())
        assert mesh.GetPolys().GetMaxCellSize() == 3
        # glTF's y up back to z up: (x, y, z)_gltf = (x, z, -y)_model
        blocks.append((np.column_stack([xyz[:, 0], -xyz[:, 2], xyz[:, 1]]), len(polys) // 3))
        iterator.GoToNextItem()
    return blocks


def expected_groups(mesh, color_array=None):
    """{key: (point set, triangle count)} of a vtkPolyData by Label (and colour), counted
    here: a polygon of n corners is n - 2 triangles."""
    labels = vtk_to_numpy(mesh.GetCellData().GetArray("Label"))
    colors = (vtk_to_numpy(mesh.GetCellData().GetArray(color_array))
              if color_array and mesh.GetCellData().GetArray(color_array) else None)
    points = vtk_to_numpy(mesh.GetPoints().GetData()).astype(float)
    offsets = vtk_to_numpy(mesh.GetPolys().GetOffsetsArray())
    connectivity = vtk_to_numpy(mesh.GetPolys().GetConnectivityArray())
    first = mesh.GetNumberOfVerts() + mesh.GetNumberOfLines()
    groups = {}
    for c in range(mesh.GetNumberOfPolys()):
        key = (int(labels[first + c]),) + (tuple(int(v) for v in colors[first + c][:3])
                                           if colors is not None else ())
        corners = connectivity[offsets[c]:offsets[c + 1]]
        ids, count = groups.get(key, (set(), 0))
        ids.update(int(i) for i in corners)
        groups[key] = (ids, count + len(corners) - 2)
    return {k: ({tuple(np.round(points[i], 4)) for i in ids}, n) for k, (ids, n) in groups.items()}


def geometry(example, pieces=""):
    reader = modelsynth.vtkMSLabelGridReader()
    reader.SetFileName(data(example))
    g = modelsynth.vtkMSLabelGeometry()
    g.SetInputConnection(reader.GetOutputPort())
    g.SetPieceDirectory(pieces)
    g.Update()
    return g


def write(port_or_data, path):
    w = modelsynth.vtkMSGLTFWriter()
    if hasattr(port_or_data, "GetNumberOfPoints"):
        w.SetInputData(port_or_data)
    else:
        w.SetInputConnection(port_or_data)
    w.SetFileName(path)
    errors = ErrorObserver(w)
    ok = w.Write()
    return ok, errors.text()


class GltfTest(unittest.TestCase):
    def check_file(self, path, mesh, color_array=None):
        """Every mesh of @p path matches one group of @p mesh: name, material, points and
        triangle count; returns the document."""
        doc = glb_json(path)
        self.assertEqual(doc["asset"]["version"], "2.0")
        expected = expected_groups(mesh, color_array)
        blocks = read_back(path)
        self.assertEqual(len(blocks), len(expected))
        self.assertEqual(len(doc["meshes"]), len(expected))
        for (points, triangles), node in zip(blocks, doc["scenes"][0]["nodes"]):
            gltf_mesh = doc["meshes"][doc["nodes"][node]["mesh"]]
            material = doc["materials"][gltf_mesh["primitives"][0]["material"]]
            words = material["name"].split()
            key = (int(words[1]),)
            if color_array:
                key += tuple(int(words[2][i:i + 2], 16) for i in (1, 3, 5))
                rgb = [v / 255 for v in key[1:]]
            else:
                rgb = render_model.label_colour(key[0])
            self.assertIn(key, expected)
            want_points, want_triangles = expected[key]
            self.assertEqual(triangles, want_triangles, material["name"])
            self.assertEqual({tuple(p) for p in np.round(points, 4)}, want_points)
            factor = material["pbrMetallicRoughness"]["baseColorFactor"]
            np.testing.assert_allclose(factor[:3], [linear(c) for c in rgb], atol=1e-6)
            self.assertEqual(factor[3], 1.0)
        self.assertEqual(sum(n for _, n in blocks), sum(n for _, n in expected.values()))
        return doc

    def test_voxel_surface_by_label(self):
        g = geometry("Examples/Village.vti")
        path = tmp("village.glb")
        ok, errors = write(g.GetOutputPort(), path)
        self.assertEqual((ok, errors), (1, ""))
        doc = self.check_file(path, g.GetOutput())
        self.assertEqual([m["name"] for m in doc["materials"]], ["label 1", "label 2", "label 3"])

    def test_palette_colours_of_a_vox_example(self):
        g = geometry("Examples/Village.vox")
        self.assertIsNotNone(g.GetOutput().GetCellData().GetArray("PaletteColor"))
        path = tmp("village-vox.glb")
        self.assertEqual(write(g.GetOutputPort(), path), (1, ""))
        self.check_file(path, g.GetOutput(), "PaletteColor")

    def test_concave_pieces_are_triangulated(self):
        # An L-shaped hexagon (concave) as every label's piece.
        folder = fresh_folder("gltf-pieces")
        for label in (1, 2, 3):
            with open(os.path.join(folder, "%d.obj" % label), "w") as f:
                f.write("v -0.5 -0.5 0\nv 0.5 -0.5 0\nv 0.5 0 0\nv 0 0 0\nv 0 0.5 0\nv -0.5 0.5 0\n"
                        "f 1 2 3 4 5 6\n")
        g = geometry("Examples/Village.vti", folder)
        path = tmp("village-pieces.glb")
        self.assertEqual(write(g.GetOutputPort(), path), (1, ""))
        self.check_file(path, g.GetOutput())
        # Ear clipping keeps every triangle inside the L: total area 3/4 per piece.
        reader = vtkGLTFReader()
        reader.SetFileName(path)
        reader.Update()
        area = 0.0
        it = reader.GetOutput().NewIterator()
        it.InitTraversal()
        while not it.IsDoneWithTraversal():
            m = it.GetCurrentDataObject()
            xyz = vtk_to_numpy(m.GetPoints().GetData()).astype(float)
            tri = vtk_to_numpy(m.GetPolys().GetConnectivityArray()).reshape(-1, 3)
            a, b, c = xyz[tri[:, 0]], xyz[tri[:, 1]], xyz[tri[:, 2]]
            area += 0.5 * np.linalg.norm(np.cross(b - a, c - a), axis=1).sum()
            it.GoToNextItem()
        sites = int(np.count_nonzero(vtk_to_numpy(
            g.GetInputDataObject(0, 0).GetPointData().GetArray("Label"))))
        self.assertAlmostEqual(area, 0.75 * sites, places=3)

    def test_vertices_and_lines_are_left_out(self):
        """Cell data of polygons follows the vertices' and lines': each triangle keeps its label."""
        from vtkmodules.vtkCommonCore import vtkIntArray, vtkPoints
        from vtkmodules.vtkCommonDataModel import vtkCellArray, vtkPolyData
        mesh = vtkPolyData()
        points = vtkPoints()
        for p in [(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0), (2, 0, 0), (2, 1, 1)]:
            points.InsertNextPoint(*p)
        mesh.SetPoints(points)
        verts, lines, polys = vtkCellArray(), vtkCellArray(), vtkCellArray()
        verts.InsertNextCell(1, [5])
        lines.InsertNextCell(2, [4, 5])
        polys.InsertNextCell(4, [0, 1, 2, 3])
        polys.InsertNextCell(3, [1, 4, 5])
        mesh.SetVerts(verts)
        mesh.SetLines(lines)
        mesh.SetPolys(polys)
        labels = vtkIntArray()
        labels.SetName("Label")
        for value in (9, 8, 1, 2):  # vertex, line, quad, triangle
            labels.InsertNextValue(value)
        mesh.GetCellData().AddArray(labels)
        path = tmp("verts-lines.glb")
        self.assertEqual(write(mesh, path), (1, ""))
        doc = self.check_file(path, mesh)
        self.assertEqual([m["name"] for m in doc["materials"]], ["label 1", "label 2"])
        self.assertEqual([n for _, n in read_back(path)], [2, 1])

    def test_empty_mesh_and_errors(self):
        from vtkmodules.vtkCommonDataModel import vtkPolyData
        path = tmp("empty.glb")
        self.assertEqual(write(vtkPolyData(), path), (1, ""))
        self.assertEqual(glb_json(path).get("meshes", []), [])
        bad = os.path.join(tmp("gltf-not-a-folder"))
        with open(bad, "w") as f:
            f.write("a file, not a folder")
        target = os.path.join(bad, "mesh.glb")
        g = geometry("Examples/Village.vti")
        ok, errors = write(g.GetOutputPort(), target)
        self.assertEqual(ok, 0)
        self.assertIn(target, errors)
        # One error event, one line of message (after VTK's "ERROR: In file, line" header).
        lines = [l for l in errors.splitlines() if l.strip() and not l.startswith("ERROR: In ")]
        self.assertEqual(len(lines), 1, errors)


class CommandLineGltfTest(unittest.TestCase):
    def run_msynth(self, *args):
        return subprocess.run([MSYNTH, *args], capture_output=True, text=True, timeout=TIMEOUT)

    def test_outputs_glb_with_pieces(self):
        out = tmp("gltf-cli")
        shutil.rmtree(out, ignore_errors=True)
        folder = fresh_folder("gltf-cli-pieces")
        with open(os.path.join(folder, "2.obj"), "w") as f:  # label 2 (roofs) as a pyramid
            f.write("v -0.5 -0.5 -0.5\nv 0.5 -0.5 -0.5\nv 0.5 0.5 -0.5\nv -0.5 0.5 -0.5\n"
                    "v 0 0 0.5\nf 1 2 5\nf 2 3 5\nf 3 4 5\nf 4 1 5\nf 1 4 3 2\n")
        r = self.run_msynth("synthesize", data("Examples/Village.vti"), "--size", "12", "12", "5",
                            "--seed", "4", "--out", out, "--outputs", "mesh,glb",
                            "--pieces", folder)
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertTrue(os.path.isfile(os.path.join(out, "mesh.glb")))
        reader = vtkXMLPolyDataReader()
        reader.SetFileName(os.path.join(out, "mesh.vtp"))
        reader.Update()
        GltfTest.check_file(self, os.path.join(out, "mesh.glb"), reader.GetOutput())
        # Only what was asked for (and statistics.json).
        self.assertEqual(sorted(n for n in os.listdir(out) if not n.startswith(".")),
                         ["mesh.glb", "mesh.vtp", "statistics.json"])

    def test_unwritable_output_is_one_line(self):
        blocker = tmp("gltf-blocker")
        with open(blocker, "w") as f:
            f.write("a file")
        r = self.run_msynth("synthesize", data("Examples/Village.vti"), "--size", "8", "8", "5",
                            "--out", os.path.join(blocker, "out"), "--outputs", "glb")
        self.assertNotEqual(r.returncode, 0)
        self.assertEqual(len(r.stderr.strip().splitlines()), 1, r.stderr)
        self.assertIn(blocker, r.stderr)

    def test_unknown_kind_lists_glb(self):
        r = self.run_msynth("synthesize", data("Examples/Village.vti"), "--size", "8", "8", "5",
                            "--outputs", "gltf")
        self.assertNotEqual(r.returncode, 0)
        self.assertIn("glb", r.stderr)


if __name__ == "__main__":
    unittest.main()
