"""Continuous model synthesis, example analysis from plain vtkmodules Python: the
polyhedral example reader and the neighbourhood-label filter, checked against the
dissertation's counts and, for 2D examples, against an independent brute-force recomputation
of every vertex figure (Eq. 4.22) by sampling directions around each point."""
import math
import os
import unittest

import numpy as np

from vtkmodules.vtkCommonDataModel import vtkPolyData
from vtkmodules.vtkIOGeometry import vtkSTLWriter
from vtkmodules.vtkIOPLY import vtkPLYWriter
from vtkmodules.vtkIOXML import vtkXMLPolyDataWriter
from vtkmodules.vtkFiltersCore import vtkTriangleFilter

import modelsynth
from msynth_testing import ErrorObserver, data, obj_objects, tmp, winding_numbers


def analyze(path, **options):
    reader = modelsynth.vtkMSPolyhedralExampleReader()
    reader.SetFileName(path)
    for name, value in options.items():
        getattr(reader, "Set" + name)(value)
    labels = modelsynth.vtkMSNeighbourhoodLabels()
    labels.SetInputConnection(reader.GetOutputPort())
    errors = ErrorObserver(labels)
    reader_errors = ErrorObserver(reader)
    labels.Update()
    return reader, labels, reader_errors.text() + errors.text()


def read_obj(path):
    """Points and {object: [polygon as point indices]} of an OBJ, parsed here independently
    (objects of one name together)."""
    points, listed = obj_objects(path)
    objects = {}
    for name, polygons in listed:
        objects.setdefault(name, []).extend(polygons)
    return points, objects


def read_obj_2d(path):
    """Polygons per object of a 2D OBJ (as (x, y) corners): {object: [polygon]}."""
    points, objects = read_obj(path)
    return {name: [[(points[i][0], points[i][1]) for i in poly] for poly in polys]
            for name, polys in objects.items()}


def inside(polygon, x, y):
    result = False
    for (ax, ay), (bx, by) in zip(polygon, polygon[1:] + polygon[:1]):
        if (ay > y) != (by > y) and ax + (y - ay) * (bx - ax) / (by - ay) > x:
            result = not result
    return result


def brute_force_labels(objects):
    """Distinct vertex figures of a 2D example: the object index met in each of N directions
    around every vertex and every piece of every edge (split where other vertices lie on it),
    plus the exterior and each object's interior."""
    names = sorted(objects)
    polygons = [(names.index(n), poly) for n in names for poly in objects[n]]
    vertices = sorted({p for _, poly in polygons for p in poly})
    samples = list(vertices)
    for _, poly in polygons:
        for a, b in zip(poly, poly[1:] + poly[:1]):
            ts = [0.0, 1.0]
            for v in vertices:
                cross = (b[0] - a[0]) * (v[1] - a[1]) - (b[1] - a[1]) * (v[0] - a[0])
                if abs(cross) < 1e-12:
                    t = ((v[0] - a[0]) * (b[0] - a[0]) + (v[1] - a[1]) * (b[1] - a[1])) / (
                        (b[0] - a[0]) ** 2 + (b[1] - a[1]) ** 2)
                    if 0 < t < 1:
                        ts.append(t)
            ts.sort()
            for t0, t1 in zip(ts, ts[1:]):
                t = (t0 + t1) / 2
                samples.append((a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1])))
    n, eps = 720, 1e-6
    figures = set()
    for (x, y) in samples:
        pattern = []
        for k in range(n):
            angle = 2 * math.pi * (k + 0.5) / n
            px, py = x + eps * math.cos(angle), y + eps * math.sin(angle)
            which = [obj for obj, poly in polygons if inside(poly, px, py)]
            pattern.append(which[0] + 1 if which else 0)
        figures.add(tuple(pattern))
    figures.add(tuple([0] * n))
    for obj in range(len(names)):
        figures.add(tuple([obj + 1] * n))
    return figures, samples


def brute_force_labels_3d(path, directions=1500, eps=1e-4):
    """Distinct vertex figures of a 3D example, sampled at every vertex, every edge midpoint and
    beside every edge inside every face, in the same fixed set of directions (a Fibonacci
    sphere), plus the exterior and each object's interior (one object type per OBJ object)."""
    points, objects = read_obj(path)
    points = np.array(points)
    names = sorted(objects)
    samples = [p for p in points]
    for polygons in objects.values():
        for poly in polygons:
            a0, a1, a2 = (points[poly[i]] for i in range(3))
            normal = np.cross(a1 - a0, a2 - a0)
            normal /= np.linalg.norm(normal)
            for i in range(len(poly)):
                a, b = points[poly[i]], points[poly[(i + 1) % len(poly)]]
                mid = (a + b) / 2
                samples.append(mid)
                inward = np.cross(normal, b - a)
                inward /= np.linalg.norm(inward)
                samples.append(mid + 1e-3 * inward)
                samples.append(mid - 1e-3 * inward)
    k = np.arange(directions) + 0.5
    phi = np.arccos(1 - 2 * k / directions)
    theta = np.pi * (1 + 5 ** 0.5) * k
    dirs = np.stack([np.cos(theta) * np.sin(phi), np.sin(theta) * np.sin(phi), np.cos(phi)], axis=1)
    figures = set()
    for p in samples:
        queries = p + eps * dirs
        pattern = np.zeros(directions, dtype=int)
        for index, name in enumerate(names):
            inside = winding_numbers(points, objects[name], queries) > 0.5
            pattern[inside] = index + 1
        figures.add(tuple(pattern.tolist()))
    figures.add(tuple([0] * directions))
    for index in range(len(names)):
        figures.add(tuple([index + 1] * directions))
    return figures


class ContinuousAnalysisTest(unittest.TestCase):
    def test_dissertation_counts(self):
        for name, count in (("triangle2d.obj", 8), ("tetrahedron.obj", 16), ("cube.obj", 28)):
            _, labels, errors = analyze(data(os.path.join("Continuous", name)))
            self.assertEqual(errors, "")
            self.assertEqual(labels.GetLabelTable().GetNumberOfRows(), count, name)

    def test_2d_labels_match_brute_force(self):
        for name in ("triangle2d.obj", "concave2d.obj", "two-objects2d.obj"):
            path = data(os.path.join("Continuous", name))
            figures, _ = brute_force_labels(read_obj_2d(path))
            _, labels, errors = analyze(path)
            self.assertEqual(errors, "")
            self.assertEqual(labels.GetLabelTable().GetNumberOfRows(), len(figures), name)

    def test_3d_labels_match_brute_force(self):
        # Every OBJ object here is its own object type, as in the bundled examples.
        for name in ("cube.obj", "tetrahedron.obj", "l-prism.obj", "house.obj"):
            path = data(os.path.join("Continuous", name))
            _, labels, errors = analyze(path)
            self.assertEqual(errors, "")
            self.assertEqual(labels.GetLabelTable().GetNumberOfRows(), len(brute_force_labels_3d(path)), name)

    def test_table_and_marked_example(self):
        _, labels, _ = analyze(data("Continuous/l-prism.obj"))
        table = labels.GetLabelTable()
        rows = [{table.GetColumnName(c): table.GetValue(r, c).ToString()
                 for c in range(table.GetNumberOfColumns())} for r in range(table.GetNumberOfRows())]
        self.assertEqual(rows[0]["Expression"], "∅")
        self.assertEqual(rows[1]["Expression"], "ℝ³")
        reflex = [r for r in rows if r["Kind"] == "edge" and "∪" in r["Expression"]]
        self.assertEqual(len(reflex), 1)
        self.assertEqual(reflex[0]["HalfSpaces"], "2")
        normals = table.GetFieldData().GetArray("FamilyNormals")
        self.assertEqual(normals.GetNumberOfTuples(), 3)
        marked = labels.GetMarkedExample()
        self.assertEqual(marked.GetNumberOfPolys(), 8)
        self.assertEqual(marked.GetNumberOfVerts(), 12)
        self.assertEqual(marked.GetNumberOfLines(), 18)
        ids = marked.GetCellData().GetArray("LabelId")
        codim = marked.GetCellData().GetArray("Codimension")
        for c in range(marked.GetNumberOfCells()):
            label = int(ids.GetValue(c))
            self.assertGreaterEqual(label, 0)
            # A cell's label has the cell's own codimension (a face is a face, ...).
            self.assertEqual(int(rows[label]["Codimension"]), int(codim.GetValue(c)))

    def test_same_example_through_stl_ply_and_vtp(self):
        def write(writer, path, polydata):
            writer.SetFileName(path)
            writer.SetInputData(polydata)
            writer.Write()
            return path

        reader, labels, _ = analyze(data("Continuous/cube.obj"))
        tri = vtkTriangleFilter()
        tri.SetInputData(reader.GetOutput())
        tri.Update()
        for path in (write(vtkSTLWriter(), tmp("cube.stl"), tri.GetOutput()),
                     write(vtkPLYWriter(), tmp("cube.ply"), reader.GetOutput())):
            _, again, errors = analyze(path)
            self.assertEqual(errors, "", path)
            self.assertEqual(again.GetLabelTable().GetNumberOfRows(), 28, path)
        two, _, _ = analyze(data("Continuous/two-objects2d.obj"))
        vtp = write(vtkXMLPolyDataWriter(), tmp("two-objects.vtp"), two.GetOutput())
        _, from_vtp, errors = analyze(vtp)
        self.assertEqual(errors, "")
        self.assertEqual(from_vtp.GetLabelTable().GetNumberOfRows(), 17)

    def test_object_types_option(self):
        # One type for both objects: the roof merges with the base, no two-type labels remain.
        _, labels, errors = analyze(data("Continuous/two-objects2d.obj"), ObjectTypes="roof=1;base=1")
        self.assertEqual(errors, "")
        table = labels.GetLabelTable()
        for r in range(table.GetNumberOfRows()):
            self.assertNotIn("2", table.GetValueByName(r, "ObjectTypes").ToString().split())
        _, labels, errors = analyze(data("Continuous/two-objects2d.obj"), ObjectTypes="roof")
        self.assertIn("not name=type", errors)

    def test_blender_export_with_y_up(self):
        # house-blender.obj is house.obj as Blender exports it by default (y up, normals, UVs,
        # materials, v/vt/vn faces): with UpAxis Y it is the same example, point for point.
        def polygons(reader):
            mesh = reader.GetOutput()
            points = mesh.GetPoints()
            out = set()
            for c in range(mesh.GetNumberOfCells()):
                ids = mesh.GetCell(c).GetPointIds()
                corners = [tuple(round(v, 6) + 0.0 for v in points.GetPoint(ids.GetId(i)))
                           for i in range(ids.GetNumberOfIds())]
                first = corners.index(min(corners))  # the same polygon from any start
                out.add((tuple(corners[first:] + corners[:first]),
                         mesh.GetCellData().GetArray("ObjectType").GetValue(c)))
            return out
        original, labels, errors = analyze(data("Continuous/house.obj"))
        self.assertEqual(errors, "")
        turned, turned_labels, errors = analyze(data("Continuous/house-blender.obj"), UpAxis=1)
        self.assertEqual(errors, "")
        self.assertEqual(polygons(turned), polygons(original))
        self.assertEqual(turned_labels.GetLabelTable().GetNumberOfRows(),
                         labels.GetLabelTable().GetNumberOfRows())
        names = turned.GetOutput().GetFieldData().GetAbstractArray("TypeNames")
        self.assertEqual([names.GetValue(i) for i in range(names.GetNumberOfValues())], ["Wall", "Roof"])
        # As the file is, the house lies on its side: its roof points along +y.
        lying, _, errors = analyze(data("Continuous/house-blender.obj"))
        self.assertEqual(errors, "")
        self.assertEqual(lying.GetOutput().GetBounds()[2:], (0.0, 4.0, -3.5, 0.5))

    def test_malformed_examples(self):
        cases = {
            "open.obj": ("v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\n", "not closed"),
            "flipped.obj": ("v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 4 3\n",
                            "inconsistent orientation"),
            "badindex.obj": ("v 0 0 0\nf 1 2 3\n", "out of range"),
            "garbage.obj": ("v a b c\n", "not a finite number"),
            "empty.obj": ("", "contains no faces"),
            "bowtie.obj": ("v 0 0 0\nv 3 2 0\nv 3 0 0\nv 0 1 0\nf 1 2 3 4\n", "intersects itself"),
            "touching.obj": ("v 0 0 0\nv 4 0 0\nv 4 3 0\nv 2 0 0\nv 0 3 0\nf 1 2 3 4 5\n",
                             "intersects itself"),
        }
        for name, (text, problem) in cases.items():
            path = tmp(name)
            with open(path, "w") as f:
                f.write(text)
            reader, labels, errors = analyze(path)
            self.assertIn(problem, errors, name)
            self.assertIn(name, errors)
            self.assertEqual(labels.GetLabelTable().GetNumberOfRows(), 0)
        # A plus shape: edges on one line but apart (x = 3 from y 0 to 2 and from 3 to 5) do
        # not meet, so it is a simple polygon and loads.
        path = tmp("plus.obj")
        with open(path, "w") as f:
            f.write("o road\n" + "".join("v %d %d 0\n" % p for p in (
                (2, 0), (3, 0), (3, 2), (5, 2), (5, 3), (3, 3), (3, 5), (2, 5), (2, 3), (0, 3),
                (0, 2), (2, 2))) + "f 1 2 3 4 5 6 7 8 9 10 11 12\n")
        reader, labels, errors = analyze(path)
        self.assertEqual(errors, "")
        self.assertGreater(labels.GetLabelTable().GetNumberOfRows(), 0)
        _, _, errors = analyze(tmp("does-not-exist.obj"))
        self.assertIn("no such file", errors)
        with open(tmp("bad.stl"), "w") as f:
            f.write("solid x\n facet normal 0 0 1\n")
        _, _, errors = analyze(tmp("bad.stl"))
        self.assertIn("bad.stl", errors)


if __name__ == "__main__":
    unittest.main()
