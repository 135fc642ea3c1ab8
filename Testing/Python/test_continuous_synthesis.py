"""Continuous model synthesis II from plain vtkmodules Python: the chain example reader
-> plane arrangement -> label solver -> mesh extraction, and every synthesized model checked
here without the C++ code: the vertex figure (the object type met in many directions) at every
vertex, edge and face of the output is recomputed by point-in-polygon tests (2D) or generalized
winding numbers (3D) and must be a figure of the example computed the same way (Eq. 4.1); each
object type's surface must be closed and consistently oriented."""
import json
import math
import os
import subprocess
import unittest

import numpy as np
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkCommonDataModel import vtkPolyData
from vtkmodules.vtkCommonExecutionModel import vtkStreamingDemandDrivenPipeline

import modelsynth
from msynth_testing import ErrorObserver, data, tmp, winding_numbers
from proportions import read_obj

N2D, EPS2D = 720, 1e-6
K = np.arange(500) + 0.5
PHI = np.arccos(1 - 2 * K / len(K))
THETA = np.pi * (1 + 5 ** 0.5) * K
DIRS3D = np.stack([np.cos(THETA) * np.sin(PHI), np.sin(THETA) * np.sin(PHI), np.cos(PHI)], axis=1)
ANGLES = 2 * np.pi * (np.arange(N2D) + 0.5) / N2D
DIRS2D = np.stack([np.cos(ANGLES), np.sin(ANGLES)], axis=1)


def regions_of(polydata):
    """The mesh's connected parts, as vtkPolyDataConnectivityFilter finds them (RegionId per
    point)."""
    from vtkmodules.vtkFiltersCore import vtkPolyDataConnectivityFilter
    parts = vtkPolyDataConnectivityFilter()
    parts.SetInputData(polydata)
    parts.SetExtractionModeToAllRegions()
    parts.ColorRegionsOn()
    parts.Update()
    return parts


def chain(example, size, seed=1, spacing=0.0, snapshots=0, block=4.0, threads=0):
    reader = modelsynth.vtkMSPolyhedralExampleReader()
    reader.SetFileName(data("Continuous/" + example))
    arrangement = modelsynth.vtkMSPlaneArrangement()
    arrangement.SetInputConnection(reader.GetOutputPort())
    arrangement.SetOutputSize(*size)
    arrangement.SetSpacing(spacing)
    solver = modelsynth.vtkMSContinuousSynthesis()
    solver.SetInputConnection(0, reader.GetOutputPort())
    solver.SetArrangementConnection(arrangement.GetOutputPort())
    solver.SetSeed(seed)
    solver.SetBlockSize(block)
    solver.SetNumberOfSnapshots(snapshots)
    solver.SetNumberOfThreads(threads)
    mesh = modelsynth.vtkMSArrangementMesh()
    mesh.SetInputConnection(0, reader.GetOutputPort())
    mesh.SetArrangementConnection(solver.GetOutputPort())
    errors = [ErrorObserver(a) for a in (reader, arrangement, solver, mesh)]
    mesh.Update()
    return reader, arrangement, solver, mesh, "\n".join(e.text() for e in errors if e.text())


def polygons_of(poly):
    """Points (n x 3) and polygons (lists of point ids) of a vtkPolyData's polys."""
    points = vtk_to_numpy(poly.GetPoints().GetData()).astype(float)
    ids = vtk_to_numpy(poly.GetPolys().GetConnectivityArray())
    offsets = vtk_to_numpy(poly.GetPolys().GetOffsetsArray())
    return points, [ids[offsets[i]:offsets[i + 1]].tolist() for i in range(len(offsets) - 1)]


def typed_surfaces(poly):
    """{type: [polygon]} with polygons oriented outward from that type (3D) or the filled
    faces of each type (2D)."""
    points, polys = polygons_of(poly)
    cells = poly.GetCellData()
    out = {}
    if cells.GetArray("ObjectType") is not None:
        types = vtk_to_numpy(cells.GetArray("ObjectType"))
        for p, t in zip(polys, types):
            out.setdefault(int(t), []).append(p)
        return points, out
    inside = vtk_to_numpy(cells.GetArray("InsideType"))
    outside = vtk_to_numpy(cells.GetArray("OutsideType"))
    for p, a, b in zip(polys, inside, outside):
        if a > 0:
            out.setdefault(int(a), []).append(p)
        if b > 0:
            out.setdefault(int(b), []).append(p[::-1])
    return points, out


def read_example(name):
    """The example's points and {type: [polygon]}, types as the reader numbers them, from the
    OBJ text (proportions.read_obj)."""
    points, surfaces, _ = read_obj(data("Continuous/" + name))
    return points, surfaces


def inside_2d(polygon, q):
    """Crossing test of many query points q (n x 2) against one polygon (m x 2)."""
    result = np.zeros(len(q), dtype=bool)
    for a, b in zip(polygon, np.roll(polygon, -1, axis=0)):
        crosses = (a[1] > q[:, 1]) != (b[1] > q[:, 1])
        with np.errstate(divide="ignore", invalid="ignore"):
            x = a[0] + (q[:, 1] - a[1]) * (b[0] - a[0]) / (b[1] - a[1])
        result ^= crosses & (x > q[:, 0])
    return result


def samples(points, surfaces, planar):
    """Every vertex, every piece of every edge (split where other vertices lie on it: another
    object may touch part of it) at its midpoint and, in 3D, beside it inside each face."""
    out = [p for p in points]
    for polys in surfaces.values():
        for poly in polys:
            corners = points[poly]
            normal = np.cross(corners[1] - corners[0], corners[2] - corners[0]) if not planar else None
            for a, b in zip(corners, np.roll(corners, -1, axis=0)):
                ab = b - a
                t = (points - a) @ ab / (ab @ ab)
                off = np.linalg.norm(points - (a + np.outer(t, ab)), axis=1)
                cuts = sorted({0.0, 1.0} | {float(x) for x in t[(off < 1e-9) & (t > 1e-9) & (t < 1 - 1e-9)]})
                for t0, t1 in zip(cuts, cuts[1:]):
                    mid = a + (t0 + t1) / 2 * ab
                    out.append(mid)
                    if not planar:
                        inward = np.cross(normal, ab)
                        inward /= np.linalg.norm(inward)
                        out.extend([mid + 1e-3 * inward, mid - 1e-3 * inward])
    return out


def figures(points, surfaces, planar, at):
    """The set of vertex figures (type per direction) at the sample points `at`."""
    found = set()
    for p in at:
        if planar:
            q = p[:2] + EPS2D * DIRS2D
            pattern = np.zeros(len(q), dtype=int)
            for t, polys in surfaces.items():
                for poly in polys:
                    pattern[inside_2d(points[poly][:, :2], q)] = t
        else:
            q = p + 1e-4 * DIRS3D
            pattern = np.zeros(len(q), dtype=int)
            for t, polys in surfaces.items():
                pattern[winding_numbers(points, polys, q) > 0.5] = t
        found.add(tuple(pattern.tolist()))
    return found


def closed_and_oriented(surfaces):
    """Every directed edge of a type's surface is matched by exactly one reversed edge."""
    for polys in surfaces.values():
        directed = {}
        for poly in polys:
            for a, b in zip(poly, poly[1:] + poly[:1]):
                directed[(a, b)] = directed.get((a, b), 0) + 1
        for (a, b), n in directed.items():
            if n != 1 or directed.get((b, a), 0) != 1:
                return False
    return True


class ContinuousSynthesisTest(unittest.TestCase):
    def check_model(self, example, size, planar, **options):
        _, arrangement, solver, mesh, errors = chain(example, size, **options)
        self.assertEqual(errors, "")
        model = mesh.GetOutput()
        self.assertGreater(model.GetNumberOfPolys(), 0, example)
        points, surfaces = typed_surfaces(model)
        if not planar:
            self.assertTrue(closed_and_oriented(surfaces), example + ": closed and oriented")
        ex_points, ex_surfaces = read_example(example)
        allowed = figures(ex_points, ex_surfaces, planar, samples(ex_points, ex_surfaces, planar))
        # The exterior and each type's interior are figures too.
        n = N2D if planar else len(DIRS3D)
        allowed |= {tuple([t] * n) for t in [0] + list(ex_surfaces)}
        found = figures(points, surfaces, planar, samples(points, surfaces, planar))
        self.assertTrue(found <= allowed, "%s: %d of %d output figures are not the example's"
                        % (example, len(found - allowed), len(found)))
        self.assertGreater(len(found), 3)
        return arrangement, solver, model

    def test_2d_triangle(self):
        self.check_model("triangle2d.obj", (10, 8, 0), True, spacing=1.0)

    def test_2d_two_objects(self):
        self.check_model("two-objects2d.obj", (12, 8, 0), True)

    def test_3d_cube(self):
        arrangement, solver, model = self.check_model("cube.obj", (4, 3, 3), False, seed=2)
        grid = arrangement.GetOutput()
        self.assertEqual(grid.GetNumberOfPoints(), 5 * 4 * 4)
        self.assertEqual(grid.GetNumberOfLines(), 4 * 4 * 4 + 5 * 3 * 4 + 5 * 4 * 3)
        for name in ("Families", "NumberOfFamilies", "CatalogSize"):
            self.assertIsNotNone(grid.GetPointData().GetArray(name), name)
        labelled = solver.GetOutput()
        for name in ("Label", "CatalogSize", "Entropy"):
            self.assertIsNotNone(labelled.GetPointData().GetArray(name), name)
        self.assertEqual(labelled.GetFieldData().GetArray("Success").GetValue(0), 1)
        # The checker itself can fail: a hole, or a box where the example has none.
        points, surfaces = typed_surfaces(model)
        holed = {t: polys[1:] for t, polys in surfaces.items()}
        self.assertFalse(closed_and_oriented(holed))
        ex_points, ex_surfaces = read_example("cube.obj")
        allowed = figures(ex_points, ex_surfaces, False, samples(ex_points, ex_surfaces, False))
        stairs_points, stairs = read_example("stairs.obj")
        self.assertFalse(figures(stairs_points, stairs, False, samples(stairs_points, stairs, False)) <= allowed)

    def test_3d_stairs(self):
        self.check_model("stairs.obj", (6, 4, 4), False, seed=4)

    def test_same_seed_same_model(self):
        labels = []
        for seed in (3, 3, 4):
            _, _, solver, _, errors = chain("l-prism.obj", (6, 6, 2), seed=seed)
            self.assertEqual(errors, "")
            labels.append(vtk_to_numpy(solver.GetOutput().GetPointData().GetArray("Label")).copy())
        self.assertTrue(np.array_equal(labels[0], labels[1]))
        self.assertFalse(np.array_equal(labels[0], labels[2]))

    def test_threads_give_the_same_model(self):
        """Non-touching blocks of a phase on one thread and on two (16 blocks in 9 phases): the
        same labels through the filter and the command line, each model checked by msynth check
        (re-analysis of the output; this file's figures take minutes at this size)."""
        labels = []
        for threads in (1, 2):
            _, _, solver, mesh, errors = chain("house.obj", (32, 32, 8), seed=5, threads=threads)
            self.assertEqual(errors, "")
            fields = solver.GetOutput().GetFieldData()
            if os.cpu_count() >= 2:
                self.assertEqual(fields.GetArray("Threads").GetValue(0), threads)
            self.assertLess(fields.GetArray("Phases").GetValue(0), fields.GetArray("Blocks").GetValue(0))
            labels.append(vtk_to_numpy(solver.GetOutput().GetPointData().GetArray("Label")).copy())
        self.assertTrue(np.array_equal(labels[0], labels[1]))
        from vtkmodules.vtkIOXML import vtkXMLPolyDataReader
        msynth = os.path.join(os.environ["MSYNTH_BIN"], "msynth")
        runs = []
        for threads in ("1", "2"):
            out = tmp("threads-" + threads)
            done = subprocess.run([msynth, "synthesize", data("Continuous/house.obj"), "--size", "32",
                                   "32", "8", "--seed", "5", "--grounded", "--threads", threads,
                                   "--out", out], capture_output=True, text=True)
            self.assertEqual(done.returncode, 0, done.stderr)
            stats = json.load(open(os.path.join(out, "statistics.json")))
            if os.cpu_count() >= 2:  # --threads reaches the solver
                self.assertEqual(stats["Threads"], int(threads))
            self.assertIn("model.vdb", stats["StageSeconds"])
            self.assertGreater(stats["VoxelSize"], 0)
            reader = vtkXMLPolyDataReader()
            reader.SetFileName(os.path.join(out, "arrangement.vtp"))
            reader.Update()
            runs.append(vtk_to_numpy(reader.GetOutput().GetPointData().GetArray("Label")).copy())
            check = subprocess.run([msynth, "check", data("Continuous/house.obj"),
                                    os.path.join(out, "model.vtp")], capture_output=True, text=True)
            self.assertEqual(check.returncode, 0, check.stdout + check.stderr)
        self.assertTrue(np.array_equal(runs[0], runs[1]), "the labels differ between 1 and 2 threads")
        # Only the files asked for: the mesh without its level sets; kinds of label grids refused.
        out = tmp("threads-mesh-only")
        done = subprocess.run([msynth, "synthesize", data("Continuous/house.obj"), "--size", "16",
                               "16", "8", "--outputs", "mesh", "--out", out],
                              capture_output=True, text=True)
        self.assertEqual(done.returncode, 0, done.stderr)
        self.assertEqual(sorted(f for f in os.listdir(out) if not f.startswith(".")),
                         ["model.vtp", "statistics.json"])
        self.assertNotIn("model.vdb", json.load(open(os.path.join(out, "statistics.json")))["StageSeconds"])
        done = subprocess.run([msynth, "synthesize", data("Continuous/house.obj"), "--size", "16",
                               "16", "8", "--outputs", "mesh,picture", "--out", out + "-x"],
                              capture_output=True, text=True)
        self.assertEqual(done.returncode, 1)
        self.assertIn("not 'picture'", done.stderr)
        self.assertEqual(len(done.stderr.strip().splitlines()), 1, done.stderr)

    @unittest.skipIf(os.environ.get("MSYNTH_SANITIZED"), "a 280,000-vertex run: Release only")
    def test_a_large_arrangement_is_written_with_lz4(self):
        """An arrangement of 2^18 vertices or more is written with LZ4 and raw bytes (zlib took
        most of a large run's writing); VTK's reader reads it back: every vertex, labelled."""
        from vtkmodules.vtkIOXML import vtkXMLPolyDataReader
        msynth = os.path.join(os.environ["MSYNTH_BIN"], "msynth")
        out = tmp("large-arrangement")
        done = subprocess.run([msynth, "synthesize", data("Continuous/house.obj"), "--size", "36",
                               "36", "8", "--spacing", "0.25", "--seed", "1", "--outputs",
                               "labels,mesh", "--out", out], capture_output=True, text=True)
        self.assertEqual(done.returncode, 0, done.stderr)
        stats = json.load(open(os.path.join(out, "statistics.json")))
        self.assertGreaterEqual(stats["ArrangementVertices"], 2**18)
        with open(os.path.join(out, "arrangement.vtp"), "rb") as f:
            head = f.read(400)
        self.assertIn(b'compressor="vtkLZ4DataCompressor"', head)
        reader = vtkXMLPolyDataReader()
        reader.SetFileName(os.path.join(out, "arrangement.vtp"))
        reader.Update()
        got = reader.GetOutput()
        self.assertEqual(got.GetNumberOfPoints(), stats["ArrangementVertices"])
        labels = vtk_to_numpy(got.GetPointData().GetArray("Label"))
        self.assertTrue((labels >= 0).all())
        check = subprocess.run([msynth, "check", data("Continuous/house.obj"),
                                os.path.join(out, "model.vtp")], capture_output=True, text=True)
        self.assertEqual(check.returncode, 0, check.stdout + check.stderr)

    def test_catalog_time_steps(self):
        _, _, solver, _, errors = chain("cube.obj", (4, 4, 3), snapshots=3)
        self.assertEqual(errors, "")
        info = solver.GetOutputInformation(0)
        steps = info.Get(vtkStreamingDemandDrivenPipeline.TIME_STEPS())
        self.assertEqual(list(steps), [0.0, 1.0, 2.0, 3.0])
        solver.UpdateTimeStep(0.0)
        start = vtk_to_numpy(solver.GetOutput().GetPointData().GetArray("CatalogSize"))
        self.assertGreater(start.max(), 1)
        # Undecided vertices hold the one undecided value of every filter (VTK_INT_MIN).
        labels = vtk_to_numpy(solver.GetOutput().GetPointData().GetArray("Label"))
        np.testing.assert_array_equal(labels == -2**31, start > 1)
        solver.UpdateTimeStep(3.0)
        end = vtk_to_numpy(solver.GetOutput().GetPointData().GetArray("CatalogSize"))
        self.assertEqual(end.max(), 1)

    def test_model_to_openvdb_level_sets(self):
        # The mesh goes straight to the VDB writer: level sets per type and a fog volume, signs
        # checked against winding numbers of the mesh at sampled voxels.
        _, _, _, mesh, errors = chain("box-building.obj", (12, 9, 8), seed=6, spacing=1.0)
        self.assertEqual(errors, "")
        path = tmp("continuous-model.vdb")
        writer = modelsynth.vtkMSOpenVDBWriter()
        writer.SetInputConnection(mesh.GetOutputPort())
        writer.SetFileName(path)
        writer.SetVoxelSize(0.25)
        writer_errors = ErrorObserver(writer)
        writer.Write()
        self.assertEqual(writer_errors.text(), "")
        listing = subprocess.run(["vdb_print", "-l", "-m", path], capture_output=True, text=True).stdout
        for grid, kind in (("surface", "level set"), ("surface_building", "level set"),
                           ("surface_roof", "level set"), ("density", "fog volume")):
            block = listing.split("Name: " + grid + "\n")[1].split("Name: ")[0]
            self.assertIn("class: " + kind, block, grid)
        reader = modelsynth.vtkMSOpenVDBReader()
        reader.SetFileName(path)
        reader.Update()
        volume = reader.GetOutput()
        points, surfaces = typed_surfaces(mesh.GetOutput())
        union = [p for p in polygons_of(mesh.GetOutput())[1]]
        outside = vtk_to_numpy(mesh.GetOutput().GetCellData().GetArray("OutsideType"))
        union = [p for p, o in zip(union, outside) if o == 0]
        sdf = vtk_to_numpy(volume.GetPointData().GetArray("surface"))
        fog = vtk_to_numpy(volume.GetPointData().GetArray("density"))
        rng = np.random.default_rng(1)
        ids = rng.choice(volume.GetNumberOfPoints(), 400, replace=False)
        where = np.array([volume.GetPoint(int(i)) for i in ids])
        inside = winding_numbers(points, union, where) > 0.5
        far = np.abs(sdf[ids]) > 0.3  # more than a voxel from the surface
        self.assertGreater(far.sum(), 100)
        self.assertTrue(np.all((sdf[ids] < 0)[far] == inside[far]), "level-set signs")
        self.assertTrue(np.all((fog[ids] > 0.5)[far] == inside[far]), "fog inside, none outside")
        # A flat 2D model has no level set: a clear error, no file.
        _, _, _, flat, errors = chain("triangle2d.obj", (8, 6, 0), spacing=1.0)
        writer.SetInputConnection(flat.GetOutputPort())
        writer.SetFileName(tmp("flat.vdb"))
        writer_errors = ErrorObserver(writer)
        writer.Write()
        self.assertIn("flat", writer_errors.text())
        self.assertFalse(os.path.exists(tmp("flat.vdb")))

    def test_catalog_sequence_and_arrangement_fields_to_openvdb(self):
        # The labelled arrangement's point fields resampled to voxels (nearest vertex), one
        # numbered file per catalog time step.
        _, _, solver, _, errors = chain("cube.obj", (4, 3, 3), snapshots=3)
        self.assertEqual(errors, "")
        folder = tmp("catalog-sequence")
        os.makedirs(folder, exist_ok=True)
        for name in os.listdir(folder):
            os.remove(os.path.join(folder, name))
        writer = modelsynth.vtkMSOpenVDBWriter()
        writer.SetInputConnection(solver.GetOutputPort())
        writer.SetFileName(os.path.join(folder, "catalog.vdb"))
        writer.SetVoxelSize(0.5)
        writer.WriteTimeStepsOn()
        self.assertEqual(writer.Write(), 1)
        self.assertEqual(sorted(os.listdir(folder)), ["catalog_%04d.vdb" % i for i in (1, 2, 3, 4)])
        sizes = []
        for i in (1, 4):
            reader = modelsynth.vtkMSOpenVDBReader()
            reader.SetFileName(os.path.join(folder, "catalog_%04d.vdb" % i))
            reader.Update()
            image = reader.GetOutput()
            sizes.append(vtk_to_numpy(image.GetPointData().GetArray("CatalogSize")))
            self.assertEqual(image.GetPointData().GetArray("Label").GetDataType(), 6)  # VTK_INT
        solver.UpdateTimeStep(0.0)
        start = vtk_to_numpy(solver.GetOutput().GetPointData().GetArray("CatalogSize"))
        self.assertEqual(sizes[0].max(), start.max())   # the start: many labels per vertex
        self.assertEqual(sizes[1].max(), 1)             # the end: decided everywhere
        # Every step: the voxel centred on each arrangement vertex (integer coordinates, voxels
        # of 0.5 from the lowest vertex) holds that vertex's catalog size at that step.
        for step in range(4):
            solver.UpdateTimeStep(float(step))
            labelled = solver.GetOutput()
            expected = vtk_to_numpy(labelled.GetPointData().GetArray("CatalogSize"))
            reader = modelsynth.vtkMSOpenVDBReader()
            reader.SetFileName(os.path.join(folder, "catalog_%04d.vdb" % (step + 1)))
            reader.Update()
            image = reader.GetOutput()
            got = vtk_to_numpy(image.GetPointData().GetArray("CatalogSize"))
            for v in range(labelled.GetNumberOfPoints()):
                voxel = image.FindPoint(labelled.GetPoint(v))
                self.assertEqual(got[voxel], expected[v], "step %d vertex %d" % (step, v))
        # The voxel at a vertex holds that vertex's value (nearest-vertex resampling).
        listing = subprocess.run(["vdb_print", "-l", "-m", os.path.join(folder, "catalog_0004.vdb")],
                                 capture_output=True, text=True).stdout
        self.assertIn("Name: Label", listing)
        self.assertIn("Tree_int32", listing)

    def test_bad_inputs(self):
        # An arrangement input that is not one (no parameters in its field data).
        reader = modelsynth.vtkMSPolyhedralExampleReader()
        reader.SetFileName(data("Continuous/cube.obj"))
        solver = modelsynth.vtkMSContinuousSynthesis()
        solver.SetInputConnection(0, reader.GetOutputPort())
        solver.SetInputData(1, vtkPolyData())
        errors = ErrorObserver(solver)
        solver.Update()
        self.assertIn("ArrangementOrigin", errors.text())
        # An arrangement of another example.
        other = modelsynth.vtkMSPolyhedralExampleReader()
        other.SetFileName(data("Continuous/tetrahedron.obj"))
        arrangement = modelsynth.vtkMSPlaneArrangement()
        arrangement.SetInputConnection(other.GetOutputPort())
        solver.SetArrangementConnection(arrangement.GetOutputPort())
        errors = ErrorObserver(solver)
        solver.Update()
        self.assertIn("another example", errors.text())
        # A mesh from an arrangement without labels.
        arrangement.SetInputConnection(reader.GetOutputPort())
        mesh = modelsynth.vtkMSArrangementMesh()
        mesh.SetInputConnection(0, reader.GetOutputPort())
        mesh.SetArrangementConnection(arrangement.GetOutputPort())
        errors = ErrorObserver(mesh)
        mesh.Update()
        self.assertIn("'Label'", errors.text())
        # A box too large for the vertex limit.
        arrangement.SetOutputSize(100, 100, 100)
        arrangement.SetMaximumVertices(1000)
        errors = ErrorObserver(arrangement)
        arrangement.Update()
        self.assertIn("vertices", errors.text())

    def test_constraints_through_the_filter_and_the_command_line(self):
        """Grounded houses with walls one plane spacing (2 units) high and no roofs in the left
        half (a guide), checked on the mesh: every connected part reaches the ground, wall floors
        and ceilings lie only at z = 0 and 2, no roof polygon in the left half of the box."""
        from vtkmodules.vtkCommonDataModel import vtkImageData
        from vtkmodules.util.numpy_support import numpy_to_vtk
        guide = vtkImageData()
        guide.SetDimensions(2, 1, 1)
        weights = numpy_to_vtk(np.array([0.0, 1.0]), deep=True)
        weights.SetName("Weight_roof")
        guide.GetPointData().AddArray(weights)
        reader, arrangement, solver, mesh, _ = chain("house.obj", (16, 16, 8), seed=2)
        solver.SetGrounded(True)
        solver.SetThickness("wall:z:1")
        solver.SetInputData(2, guide)
        # The constraints read against the example alone, before any arrangement is built.
        reader.Update()
        self.assertEqual(solver.CheckConstraints(reader.GetOutput(), 0.01, 12), "")
        solver.SetThickness("wall:xy:2")
        self.assertIn("a width across several axes",
                      solver.CheckConstraints(reader.GetOutput(), 0.01, 12))
        solver.SetThickness("wall:z:1")
        errors = ErrorObserver(solver)
        mesh.Update()
        self.assertEqual(errors.text(), "")
        fields = solver.GetOutput().GetFieldData()
        self.assertEqual(fields.GetArray("Components").GetValue(0),
                         fields.GetArray("GroundedComponents").GetValue(0))
        self.assertIsNotNone(fields.GetArray("TypeShare_2"))
        model = mesh.GetOutput()
        middle = arrangement.GetOutput().GetBounds()[0] + 8  # the box starts at the eaves, x = -0.5
        points, polys = polygons_of(model)
        inside = vtk_to_numpy(model.GetCellData().GetArray("InsideType"))
        outside = vtk_to_numpy(model.GetCellData().GetArray("OutsideType"))
        self.assertGreater(len(polys), 0)
        for poly, a, b in zip(polys, inside, outside):
            corners = points[poly]
            flat = np.ptp(corners[:, 2]) < 1e-9
            if 1 in (a, b) and flat and 0 in (a, b):
                self.assertIn(round(corners[0, 2], 6), (0.0, 2.0), "a wall floor or ceiling")
            if 2 in (a, b):
                self.assertGreaterEqual(corners[:, 0].mean(), middle, "a roof in the left half")
        parts = regions_of(model)
        region = vtk_to_numpy(parts.GetOutput().GetPointData().GetArray("RegionId"))
        z = vtk_to_numpy(parts.GetOutput().GetPoints().GetData())[:, 2]
        for r in np.unique(region):
            self.assertAlmostEqual(z[region == r].min(), 0.0, msg="part %d floats" % r)
        # Walls in whole slabs of two spacings (1 unit) across x and y: every wall side facing x
        # (or y) lies on one grid of 1-unit steps, so no wall is half a unit thin.
        solver.SetInputData(2, None)
        solver.SetThickness("wall:z,wall:x:2+,wall:y:2+")
        solver.SetOverhang("roof")
        mesh.Update()
        self.assertEqual(errors.text(), "")
        points, polys = polygons_of(mesh.GetOutput())
        inside = vtk_to_numpy(mesh.GetOutput().GetCellData().GetArray("InsideType"))
        outside = vtk_to_numpy(mesh.GetOutput().GetCellData().GetArray("OutsideType"))
        sides = {0: set(), 1: set()}
        for poly, a, b in zip(polys, inside, outside):
            corners = points[poly]
            for axis in (0, 1):
                if (a == 1) != (b == 1) and np.ptp(corners[:, axis]) < 1e-9:
                    sides[axis].add(round(corners[0, axis] % 1.0, 6) % 1.0)
        self.assertTrue(sides[0] and sides[1], "walls have sides facing x and y")
        self.assertEqual(len(sides[0]), 1, "wall sides facing x at %s (mod 1)" % sides[0])
        self.assertEqual(len(sides[1]), 1, "wall sides facing y at %s (mod 1)" % sides[1])
        # The same from the command line, and its one-line errors.
        from vtkmodules.vtkIOXML import vtkXMLImageDataWriter
        folder = tmp("constraints-cli")
        os.makedirs(folder, exist_ok=True)
        writer = vtkXMLImageDataWriter()
        writer.SetInputData(guide)
        writer.SetFileName(os.path.join(folder, "guide.vti"))
        writer.Write()
        msynth = os.path.join(os.environ["MSYNTH_BIN"], "msynth")
        out = os.path.join(folder, "out")
        done = subprocess.run([msynth, "synthesize", data("Continuous/house.obj"), "--size", "16", "16",
                               "8", "--seed", "2", "--grounded", "--thickness", "wall:z",
                               "--guide", os.path.join(folder, "guide.vti"), "--out", out],
                              capture_output=True, text=True)
        self.assertEqual(done.returncode, 0, done.stderr)
        self.assertIn("on the ground", done.stdout)
        stats = open(os.path.join(out, "statistics.json")).read()
        self.assertIn('"FloatingPartsRemoved"', stats)
        self.assertIn('"TypeShares"', stats)
        for args, message in (
                (["--thickness", "wall:q"], "the axis must be x, y, z or h1"),
                (["--thickness", "wall:x:0+"], "N+ for multiples of N"),
                (["--thickness", "wall:x:2+", "--thickness", "wall:y:2+"], None),
                (["--connected", "tower:2"], "'tower' is not an object type"),
                (["--overhang", "tower"], "'tower' is not an object type"),
                (["--overhang", "roof", "--grounded"], None),
                (["--target", "roof:2"], "LABEL:FRACTION"),
                (["--thickness", "wall:z", "--no-proportions"], None)):
            done = subprocess.run([msynth, "synthesize", data("Continuous/house.obj"), "--size", "8",
                                   "8", "6", "--out", out + "-x"] + args, capture_output=True,
                                  text=True)
            if message is None:
                self.assertEqual(done.returncode, 0, done.stderr)
                continue
            self.assertNotEqual(done.returncode, 0, args)
            self.assertIn(message, done.stderr)
            self.assertEqual(len(done.stderr.strip().splitlines()), 1, done.stderr)
        # A mistyped constraint is read before the plane arrangement is built: at a size whose
        # arrangement is refused for its vertices, the constraint's problem is what is said.
        for args, message in ((["--thickness", "wall:xy:2"], "a width across several axes"),
                              (["--connected", "tower"], "'tower' is not an object type"),
                              (["--overhang", "tower"], "'tower' is not an object type")):
            done = subprocess.run([msynth, "synthesize", data("Continuous/house.obj"), "--size",
                                   "3000", "3000", "30", "--out", out + "-z"] + args,
                                  capture_output=True, text=True)
            self.assertNotEqual(done.returncode, 0, args)
            self.assertIn(message, done.stderr)
            self.assertNotIn("more than the limit", done.stderr)
            self.assertFalse(os.path.exists(out + "-z"))
        done = subprocess.run([msynth, "synthesize", data("Examples/Village.vti"), "--size", "8", "8",
                               "4", "--grounded", "--out", out + "-y"], capture_output=True, text=True)
        self.assertNotEqual(done.returncode, 0)
        self.assertIn("--grounded applies to polyhedral examples", done.stderr)

    def test_rotated_example_snaps_its_directions(self):
        """A regular pentagonal prism turned by an arbitrary angle: its plane directions are
        snapped to integers that keep exact coordinates within 128 bits; the change is reported
        and tiny, the model is checked against the example, and the run takes well under a
        second."""
        import time
        start = time.monotonic()
        reader, arrangement, solver, mesh, errors = chain("pentagon-rotated.obj", (20, 20, 6), seed=2)
        self.assertEqual(errors, "")
        fields = arrangement.GetOutput().GetFieldData()
        self.assertEqual(fields.GetArray("MaximumSmallInteger").GetValue(0), 4096)
        change = fields.GetArray("DirectionChangeDegrees").GetValue(0)
        self.assertGreater(change, 0)
        self.assertLess(change, 0.012)
        self.assertGreater(mesh.GetOutput().GetNumberOfPolys(), 0)
        self.assertLess(time.monotonic() - start, 10)
        folder = tmp("pentagon-rotated")
        msynth = os.path.join(os.environ["MSYNTH_BIN"], "msynth")
        done = subprocess.run([msynth, "synthesize", data("Continuous/pentagon-rotated.obj"), "--size",
                               "20", "20", "6", "--seed", "3", "--out", folder],
                              capture_output=True, text=True, timeout=60)
        self.assertEqual(done.returncode, 0, done.stderr)
        check = subprocess.run([msynth, "check", data("Continuous/pentagon-rotated.obj"),
                                os.path.join(folder, "model.vtp")], capture_output=True, text=True)
        self.assertEqual(check.returncode, 0, check.stdout + check.stderr)
        self.assertIn("valid", check.stdout)

    def test_non_trihedral_vertices(self):
        """Pyramids and octahedra: four planes meet at their apexes (TVCG 4.4). The output has
        such vertices, found on the mesh (points where faces of four or more directions meet),
        and so does a pentagonal pyramid's five-plane apex."""
        for name, size in (("pyramid.obj", (16, 16, 6)), ("octahedron.obj", (16, 16, 8))):
            reader, arrangement, solver, mesh, errors = chain(name, size, seed=1)
            self.assertEqual(errors, "")
            fields = arrangement.GetOutput().GetFieldData()
            self.assertGreater(fields.GetArray("NonTrihedralLabels").GetValue(0), 0)
            self.assertEqual(fields.GetArray("NonTrihedralLabelsWithoutSites").GetValue(0), 0)
            points, polys = polygons_of(mesh.GetOutput())
            directions = {}
            for poly in polys:
                c = points[poly]
                n = np.cross(c[1] - c[0], c[2] - c[0])
                n = n / np.linalg.norm(n)
                for i in poly:
                    directions.setdefault(i, set()).add(tuple(np.round(n, 6)))
            apexes = [i for i, d in directions.items() if len(d) >= 4]
            self.assertGreater(len(apexes), 0, name + ": no vertex where four planes meet")
        # A regular pentagon's directions are no small integers: with them the five planes would
        # only nearly meet, so they are snapped to small integers (the paper's "modify the
        # normals"), the change is reported, and the output holds the five-plane apex.
        msynth = os.path.join(os.environ["MSYNTH_BIN"], "msynth")
        out = tmp("pyramid-pentagonal")
        done = subprocess.run([msynth, "synthesize", data("Continuous/pyramid-pentagonal.obj"), "--size",
                               "12", "12", "4", "--seed", "1", "--out", out],
                              capture_output=True, text=True, timeout=60)
        self.assertEqual(done.returncode, 0, done.stderr)
        self.assertIn("directions were snapped to small integers; faces turn by up to", done.stderr)
        change = float(done.stderr.split("faces turn by up to ")[1].split()[0])
        self.assertGreater(change, 0.01)
        self.assertLess(change, 3)
        check = subprocess.run([msynth, "check", data("Continuous/pyramid-pentagonal.obj"),
                                os.path.join(out, "model.vtp")], capture_output=True, text=True)
        self.assertEqual(check.returncode, 0, check.stdout + check.stderr)
        from vtkmodules.vtkIOXML import vtkXMLPolyDataReader
        model = vtkXMLPolyDataReader()
        model.SetFileName(os.path.join(out, "model.vtp"))
        model.Update()
        points, polys = polygons_of(model.GetOutput())
        directions = {}
        for poly in polys:
            c = points[poly]
            n = np.cross(c[1] - c[0], c[2] - c[0])
            for i in poly:
                directions.setdefault(tuple(np.round(points[i], 6)), set()).add(
                    tuple(np.round(n / np.linalg.norm(n), 6)))
        self.assertTrue(any(len(d) == 5 for d in directions.values()), "no five-plane apex")

    def test_mirrored_models(self):
        """Reflection symmetry (TVCG 7): the model's polygons, reflected across the middle of
        their bounding box, are the model's polygons (same points and object types), checked on
        the mesh, for x, y and both at once; an axis with no symmetric planes is a clear error."""
        for axes in ((0,), (1,), (0, 1)):
            reader, arrangement, solver, mesh, _ = chain("house.obj", (20, 20, 8), seed=4)
            solver.SetMirror(*[int(a in axes) for a in range(3)])
            solver.SetGrounded(True)
            errors = ErrorObserver(solver)
            mesh.Update()
            self.assertEqual(errors.text(), "")
            model = mesh.GetOutput()
            points, polys = polygons_of(model)
            self.assertGreater(len(polys), 0)
            inside = vtk_to_numpy(model.GetCellData().GetArray("InsideType"))
            outside = vtk_to_numpy(model.GetCellData().GetArray("OutsideType"))
            for axis in axes:
                middle = (points[:, axis].min() + points[:, axis].max()) / 2
                def key(poly, flip):
                    c = points[poly].copy()
                    if flip:
                        c[:, axis] = 2 * middle - c[:, axis]
                    return tuple(sorted(tuple(np.round(p, 5)) for p in c))
                faces = {(key(p, False), int(a), int(b)) for p, a, b in zip(polys, inside, outside)}
                mirrored = {(key(p, True), int(a), int(b)) for p, a, b in zip(polys, inside, outside)}
                self.assertEqual(faces, mirrored, "axes %s, axis %d" % (axes, axis))
        reader, arrangement, solver, mesh, _ = chain("tetrahedron.obj", (12, 12, 6), seed=1)
        solver.SetMirror(1, 0, 0)  # the slanted face (1, 1, 1) has no image (-1, 1, 1)
        errors = ErrorObserver(solver)
        solver.Update()
        self.assertIn("mirror", errors.text())

    def test_bounding_volume_substitution(self):
        """Bounding volumes (TVCG 4.8): domes synthesized as a box cut through three corners come
        out as scaled copies, and the hemisphere substituted into each is scaled the same in x,
        y and z; measured on the output polygons of the dome type."""
        reader, arrangement, solver, mesh, _ = chain("domed-building.obj", (24, 24, 10), seed=2)
        solver.SetGrounded(True)
        detail = modelsynth.vtkMSPolyhedralExampleReader()
        detail.SetFileName(data("Continuous/dome.obj"))
        mesh.SetDetailConnection(detail.GetOutputPort())
        mesh.SetDetailType("dome")
        mesh.CheckModelOn()
        errors = ErrorObserver(mesh)
        mesh.Update()
        self.assertEqual(errors.text(), "")
        model = mesh.GetOutput()
        fields = model.GetFieldData()
        self.assertEqual(fields.GetAbstractArray("ModelCheck").GetValue(0), "valid")
        scales = vtk_to_numpy(fields.GetArray("DetailScales"))
        self.assertGreater(len(scales), 0)
        points, polys = polygons_of(model)
        inside = vtk_to_numpy(model.GetCellData().GetArray("InsideType"))
        dome = [p for p, t in zip(polys, inside) if t == 2]
        detail.Update()
        self.assertEqual(len(dome), len(scales) * detail.GetOutput().GetNumberOfPolys())
        # Each copy (its polygons are consecutive) has a hemisphere's extents, 2 : 2 : 1.
        per = detail.GetOutput().GetNumberOfPolys()
        for k in range(len(scales)):
            corners = points[np.concatenate([np.array(p) for p in dome[k * per:(k + 1) * per]])]
            extent = corners.max(axis=0) - corners.min(axis=0)
            self.assertAlmostEqual(extent[0], extent[1], places=6)
            self.assertAlmostEqual(extent[0], 2 * extent[2], places=6)
        for s in scales:
            self.assertAlmostEqual(s[0], s[1], places=9)
            self.assertAlmostEqual(s[0], s[2], places=9)
        self.assertEqual(fields.GetArray("DetailAnisotropy").GetValue(0), 0.0)
        mesh.SetDetailType("tower")
        errors = ErrorObserver(mesh)
        mesh.Update()
        self.assertIn("'tower' is not an object type", errors.text())

    def test_prism_bounding_volume_keeps_cylinders_round(self):
        """Bounding volumes (TVCG 4.8) cut into triangular prisms: silos synthesized as a box
        cut along its vertical diagonal into two prisms of two types scale the same in x and y
        but freely in z, so each cylinder substituted for a pair is round (equal x and y extents)
        while heights vary; the boxes do not overlap, so neither do the cylinders."""
        reader, arrangement, solver, mesh, _ = chain("silo.obj", (16, 16, 8), seed=3)
        solver.SetGrounded(True)
        detail = modelsynth.vtkMSPolyhedralExampleReader()
        detail.SetFileName(data("Continuous/cylinder.obj"))
        mesh.SetDetailConnection(detail.GetOutputPort())
        mesh.SetDetailType("silo+silo2")
        errors = ErrorObserver(mesh)
        mesh.Update()
        self.assertEqual(errors.text(), "")
        model = mesh.GetOutput()
        scales = vtk_to_numpy(model.GetFieldData().GetArray("DetailScales"))
        self.assertGreater(len(scales), 2)
        for s in scales:
            self.assertAlmostEqual(s[0], s[1], places=9)
        self.assertTrue(any(abs(s[2] - s[0]) > 1e-6 for s in scales), "heights scale freely")
        points, polys = polygons_of(model)
        detail.Update()
        per = detail.GetOutput().GetNumberOfPolys()
        self.assertEqual(len(polys), len(scales) * per)
        for k in range(len(scales)):
            corners = points[np.concatenate([np.array(p) for p in polys[k * per:(k + 1) * per]])]
            extent = corners.max(axis=0) - corners.min(axis=0)
            self.assertAlmostEqual(extent[0], extent[1], places=6)
            self.assertAlmostEqual(extent[0], 2 * scales[k][0], places=6)
            self.assertAlmostEqual(extent[2], 4 * scales[k][2], places=6)
        boxes = [(points[np.concatenate([np.array(p) for p in polys[k * per:(k + 1) * per]])])
                 for k in range(len(scales))]
        boxes = [(b.min(axis=0), b.max(axis=0)) for b in boxes]
        for i in range(len(boxes)):
            for j in range(i):
                overlap = np.minimum(boxes[i][1], boxes[j][1]) - np.maximum(boxes[i][0], boxes[j][0])
                self.assertFalse((overlap[:2] > 1e-6).all(), "cylinders %d and %d overlap" % (i, j))

    def test_several_models_and_volume_shares(self):
        """--models N keeps the best of N whole models (statistics name which and its match
        error); TypeShares in statistics.json are the model's volume fractions, recomputed here
        from model.vtp by the divergence theorem."""
        msynth = os.path.join(os.environ["MSYNTH_BIN"], "msynth")
        out = tmp("models-cli")
        done = subprocess.run([msynth, "synthesize", data("Continuous/house.obj"), "--size", "12", "12",
                               "8", "--seed", "4", "--grounded", "--models", "3", "--out", out],
                              capture_output=True, text=True)
        self.assertEqual(done.returncode, 0, done.stderr)
        with open(os.path.join(out, "statistics.json")) as f:
            stats = json.load(f)
        self.assertEqual(stats["ModelCandidates"], 3)
        self.assertIn(stats["ModelChosen"], (0, 1, 2))
        self.assertGreater(stats["MatchError"], 0)
        self.assertIn("of 3 kept (match error", stats["Message"])
        from vtkmodules.vtkIOXML import vtkXMLPolyDataReader
        reader = vtkXMLPolyDataReader()
        reader.SetFileName(os.path.join(out, "model.vtp"))
        reader.Update()
        points, polys = polygons_of(reader.GetOutput())
        inside = vtk_to_numpy(reader.GetOutput().GetCellData().GetArray("InsideType"))
        outside = vtk_to_numpy(reader.GetOutput().GetCellData().GetArray("OutsideType"))
        volume = {}
        for poly, a, b in zip(polys, inside, outside):
            c = points[poly]
            v = sum(np.dot(c[0], np.cross(c[k], c[k + 1])) for k in range(1, len(c) - 1)) / 6
            volume[int(a)] = volume.get(int(a), 0) + v
            volume[int(b)] = volume.get(int(b), 0) - v
        volume.pop(0, None)
        total = sum(volume.values())
        for t, v in volume.items():
            self.assertAlmostEqual(stats["TypeShares"][str(t)], v / total, places=4)
        done = subprocess.run([msynth, "synthesize", data("Continuous/house.obj"), "--size", "8", "8", "6",
                               "--models", "2", "--snapshots", "2", "--out", out + "-x"],
                              capture_output=True, text=True)
        self.assertNotEqual(done.returncode, 0)
        self.assertIn("snapshots are of one model", done.stderr)

    def test_road_and_pipe_networks(self):
        """The bundled roads (2D) and pipes (3D), each grown from one seed with a width, through
        the filter and the command line: one connected part on the mesh that spans most of the
        box, and a model msynth check accepts."""
        for name, size, width in (("roads.obj", (24, 24, 0), "road:xy"),
                                  ("pipes.obj", (12, 12, 6), "pipe:xy pipe:yz pipe:xz")):
            reader, arrangement, solver, mesh, _ = chain(name, size, seed=2, block=0)
            solver.SetThickness(width)
            solver.SetConnected(width.split(":")[0] + ":1")
            errors = ErrorObserver(solver)
            mesh.Update()
            self.assertEqual(errors.text(), "")
            self.assertEqual(regions_of(mesh.GetOutput()).GetNumberOfExtractedRegions(), 1, name)
            bounds = mesh.GetOutput().GetBounds()
            for axis, extent in enumerate(size):
                if extent:
                    self.assertGreater(bounds[2 * axis + 1] - bounds[2 * axis], 0.6 * extent, name)
        msynth = os.path.join(os.environ["MSYNTH_BIN"], "msynth")
        out = tmp("pipes-cli")
        done = subprocess.run([msynth, "synthesize", data("Continuous/pipes.obj"), "--size", "12", "12",
                               "6", "--blocks", "0", "--connected", "pipe:1", "--thickness", "pipe:xy",
                               "--thickness", "pipe:yz", "--thickness", "pipe:xz", "--out", out],
                              capture_output=True, text=True)
        self.assertEqual(done.returncode, 0, done.stderr)
        with open(os.path.join(out, "statistics.json")) as f:
            self.assertEqual(json.load(f)["Components"], 1)
        done = subprocess.run([msynth, "check", data("Continuous/pipes.obj"),
                               os.path.join(out, "model.vtp")], capture_output=True, text=True)
        self.assertEqual(done.returncode, 0, done.stdout + done.stderr)
        done = subprocess.run([msynth, "synthesize", data("Continuous/pipes.obj"), "--size", "8", "8",
                               "4", "--thickness", "pipe:xy:2", "--out", out + "-x"],
                              capture_output=True, text=True)
        self.assertNotEqual(done.returncode, 0)
        self.assertIn("a width across several axes is one spacing", done.stderr)

    def test_oil_platform_grows_from_a_few_seeds(self):
        """The oil platform with dimensional constraints (decks one spacing thick, beams one across
        x and y) grown from three seeds on the ground, the whole model at once: at most three
        connected parts on the mesh, each on the ground, decks one unit thick at height 4."""
        for seed in (1, 2):
            reader, arrangement, solver, mesh, _ = chain("oil-platform.obj", (24, 24, 12), seed=seed,
                                                         block=0)
            solver.SetGrounded(True)
            solver.SetThickness("platform:z beam:x beam:y")
            solver.SetConnected("solid:3")
            errors = ErrorObserver(solver)
            mesh.Update()
            self.assertEqual(errors.text(), "")
            parts = regions_of(mesh.GetOutput())
            region = vtk_to_numpy(parts.GetOutput().GetPointData().GetArray("RegionId"))
            z = vtk_to_numpy(parts.GetOutput().GetPoints().GetData())[:, 2]
            self.assertGreaterEqual(len(np.unique(region)), 1)
            self.assertLessEqual(len(np.unique(region)), 3, "seed %d" % seed)
            for r in np.unique(region):
                self.assertAlmostEqual(z[region == r].min(), 0.0)
            points, polys = polygons_of(mesh.GetOutput())
            inside = vtk_to_numpy(mesh.GetOutput().GetCellData().GetArray("InsideType"))
            outside = vtk_to_numpy(mesh.GetOutput().GetCellData().GetArray("OutsideType"))
            bottoms, tops = set(), set()
            for poly, a, b in zip(polys, inside, outside):
                c = points[poly]
                if 2 not in (a, b) or np.ptp(c[:, 2]) > 1e-9:
                    continue
                up = np.cross(c[1] - c[0], c[2] - c[0])[2] * (1 if a == 2 else -1) > 0
                (tops if up else bottoms).add(round(c[0, 2], 6))
            self.assertTrue(bottoms)
            self.assertEqual({z + 1 for z in bottoms}, tops, "decks one unit thick")


class ModelVoxelsTest(unittest.TestCase):
    """The OpenVDB writer voxelizes continuous models itself (what msynth synthesize passes it):
    with the arrangement on its port 1, voxels of max(s / 4, E / 256) and a flat model as the
    label grid ObjectType; the voxel count is capped."""

    def write(self, model, arrangement, path, **options):
        writer = modelsynth.vtkMSOpenVDBWriter()
        writer.SetInputData(model)
        if arrangement is not None:
            writer.SetArrangementData(arrangement)
        writer.SetFileName(path)
        for name, value in options.items():
            getattr(writer, "Set" + name)(value)
        errors = ErrorObserver(writer)
        if os.path.exists(path):
            os.remove(path)
        writer.Write()
        return errors.text()

    def test_flat_model_as_object_types(self):
        import pyopenvdb
        _, _, solver, mesh, errors = chain("triangle2d.obj", (12, 9, 0), spacing=1.0)
        self.assertEqual(errors, "")
        model, labelled = mesh.GetOutput(), solver.GetOutput()
        path = tmp("voxels-2d.vdb")
        self.assertIn("flat", self.write(model, None, path))  # no arrangement: no volume to write
        self.assertEqual(self.write(model, labelled, path), "")
        types = pyopenvdb.read(path, "ObjectType_float")  # beside the int grid, for this module
        # Spacing 1 makes the smallest plane spacing 1: voxels of 1/4 (12/256 is smaller).
        self.assertAlmostEqual(types.transform.voxelSize()[0], 0.25)
        # The filled area, recomputed here from the model's polygons (shoelace), is what the
        # non-empty voxels cover.
        points, polys = polygons_of(model)
        filled = vtk_to_numpy(model.GetCellData().GetArray("ObjectType"))
        area = sum(0.5 * abs(np.dot(points[p, 0], np.roll(points[p, 1], -1)) -
                             np.dot(points[p, 1], np.roll(points[p, 0], -1)))
                   for p, t in zip(polys, filled) if t != 0)
        self.assertGreater(area, 0)
        self.assertAlmostEqual(types.activeVoxelCount() * 0.25 ** 2 / area, 1.0, delta=0.1)
        # More voxels than allowed: refused, no file.
        errors = self.write(model, labelled, path, MaximumVoxels=100)
        self.assertIn("MaximumVoxels", errors)
        self.assertFalse(os.path.exists(path))


if __name__ == "__main__":
    unittest.main()
