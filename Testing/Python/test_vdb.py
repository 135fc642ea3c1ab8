"""The VDB reader refuses what it cannot handle with clear errors: grids of other types, and
extents that would need an enormous dense allocation (files made with OpenVDB's own Python)."""
import os
import shutil
import subprocess
import unittest

import pyopenvdb

import modelsynth
from msynth_testing import BIN, ErrorObserver, data, fresh_folder, tmp


def read(path, **options):
    reader = modelsynth.vtkMSOpenVDBReader()
    errors = ErrorObserver(reader)
    reader.SetFileName(path)
    for k, v in options.items():
        getattr(reader, "Set" + k)(v)
    reader.Update()
    return reader.GetOutput(), errors.text()


class VDBReaderTest(unittest.TestCase):
    def test_unsupported_grid_type(self):
        grid = pyopenvdb.BoolGrid()
        grid.name = "flags"
        grid.getAccessor().setValueOn((1, 2, 3), True)
        path = tmp("bool.vdb")
        pyopenvdb.write(path, grids=[grid])
        out, errors = read(path)
        self.assertIn(path, errors)
        self.assertIn("value type 'bool'", errors)
        self.assertEqual(out.GetNumberOfPoints(), 0)

    def test_enormous_bounding_box_is_refused(self):
        grid = pyopenvdb.FloatGrid()
        grid.name = "far"
        acc = grid.getAccessor()
        acc.setValueOn((0, 0, 0), 1.0)
        acc.setValueOn((100000, 100000, 100000), 2.0)  # 10^15 voxels dense
        path = tmp("far.vdb")
        pyopenvdb.write(path, grids=[grid])
        out, errors = read(path)
        self.assertIn("more than the limit", errors)
        self.assertEqual(out.GetNumberOfPoints(), 0)

    def test_damaged_index_box_metadata_is_refused(self):
        # Our msynth_index_min/max metadata as a damaged file may hold it: the full 32-bit range
        # (once a division by zero), a box near the top of the range (once an overflow in
        # copyToDense), an empty box.
        for name, lo, hi in (("full-range", (-2147483648,) * 3, (2147483647,) * 3),
                             ("near-top", (2147483000,) * 3, (2147483647,) * 3),
                             ("empty", (5, 5, 5), (1, 1, 1))):
            grid = pyopenvdb.FloatGrid()
            grid.name = "Label"
            grid.getAccessor().setValueOn((1, 1, 1), 3.0)
            grid["msynth_index_min"] = lo
            grid["msynth_index_max"] = hi
            path = tmp(name + ".vdb")
            pyopenvdb.write(path, grids=[grid])
            out, errors = read(path)
            self.assertIn(path, errors, name)
            self.assertIn("which is empty or outside +-2^30", errors, name)
            self.assertEqual(out.GetNumberOfPoints(), 0, name)

    def test_a_stored_box_the_data_does_not_support_is_refused_at_once(self):
        # One voxel whose stored index box claims 2^28 voxels: once 60 s and 2 GB of dense
        # copies, now refused before any; a small box around few voxels is still read.
        import time
        for name, hi, refused in (("claims-2^28", (1023, 1023, 255), True),
                                  ("small-sparse", (63, 63, 63), False),
                                  ("outside", (0, 0, 0), True)):
            grid = pyopenvdb.FloatGrid()
            grid.name = "Label"
            grid.getAccessor().setValueOn((1, 1, 1), 3.0)
            grid["msynth_index_min"] = (0, 0, 0)
            grid["msynth_index_max"] = hi
            path = tmp(name + ".vdb")
            pyopenvdb.write(path, grids=[grid])
            start = time.monotonic()
            out, errors = read(path)
            # Refused before any dense copy: well under the seconds a 2^28-voxel copy takes
            # (more under the sanitizers, on a loaded machine).
            self.assertLess(time.monotonic() - start, 10.0 if os.environ.get("MSYNTH_SANITIZED") else 2.0, name)
            if refused:
                self.assertIn(path, errors, name)
                self.assertIn("(damaged metadata)", errors, name)
                self.assertEqual(out.GetNumberOfPoints(), 0, name)
            else:
                self.assertEqual(errors, "", name)
                self.assertEqual(out.GetNumberOfPoints(), 64 ** 3, name)

    def test_foreign_file_uses_active_bounding_box(self):
        grid = pyopenvdb.FloatGrid()
        grid.name = "density"
        acc = grid.getAccessor()
        acc.setValueOn((2, 3, 4), 1.5)
        acc.setValueOn((4, 3, 4), 2.5)
        path = tmp("foreign.vdb")
        pyopenvdb.write(path, grids=[grid])
        out, errors = read(path)
        self.assertEqual(errors, "")
        self.assertEqual(out.GetExtent(), (2, 4, 3, 3, 4, 4))
        a = out.GetPointData().GetArray("density")
        self.assertEqual([a.GetValue(i) for i in range(3)], [1.5, 0.0, 2.5])

    def test_not_a_vdb(self):
        path = tmp("text.vdb")
        with open(path, "w") as f:
            f.write("hello\n")
        _, errors = read(path)
        self.assertIn("not a readable OpenVDB file", errors)
        self.assertTrue(os.path.exists(path))


class OpenVDBModuleTest(unittest.TestCase):
    """OpenVDB is a module loaded on first use: runs that write no .vdb never load it (it was two
    thirds of every start-up), runs that do write a readable file, and a missing module is one
    line."""

    def synthesize(self, folder, *extra, env=None):
        out = fresh_folder(folder)
        r = subprocess.run([os.path.join(BIN, "msynth"), "synthesize",
                            data("Examples/Village.vti"), "--size", "10", "10", "5", "--seed",
                            "2", "--out", out, *extra], capture_output=True, text=True,
                           timeout=300, env=dict(os.environ, **(env or {})))
        return r, out

    def test_only_runs_that_write_vdb_load_openvdb(self):
        r, out = self.synthesize("vdb-module-none", "--outputs", "labels,txt",
                                 env={"LD_DEBUG": "files"})
        self.assertEqual(r.returncode, 0, r.stderr[-2000:])
        self.assertIn("libvtkCommonCore", r.stderr)  # LD_DEBUG did list what was loaded
        self.assertNotIn("libopenvdb", r.stderr)
        self.assertNotIn("libModelSynthOpenVDB", r.stderr)
        r, out = self.synthesize("vdb-module-used", env={"LD_DEBUG": "files"})
        self.assertEqual(r.returncode, 0, r.stderr[-2000:])
        self.assertIn("libModelSynthOpenVDB", r.stderr)
        self.assertIn("libopenvdb", r.stderr)
        image, errors = read(os.path.join(out, "model.vdb"))
        self.assertEqual(errors, "")
        self.assertEqual(image.GetDimensions()[:2], (10, 10))

    def test_a_missing_module_is_one_line_and_no_outputs(self):
        # A copy of the build's layout (bin/, lib/) without the module.
        root = fresh_folder("vdb-module-missing")
        os.makedirs(os.path.join(root, "bin"))
        os.makedirs(os.path.join(root, "lib"))
        shutil.copy(os.path.join(BIN, "msynth"), os.path.join(root, "bin"))
        lib = os.path.join(BIN, "..", "lib")
        for name in os.listdir(lib):
            if name.startswith("lib") and ".so" in name and "OpenVDB" not in name:
                os.symlink(os.path.realpath(os.path.join(lib, name)),
                           os.path.join(root, "lib", name))
        out = os.path.join(root, "out")
        r = subprocess.run([os.path.join(root, "bin", "msynth"), "synthesize",
                            data("Examples/Village.vti"), "--size", "10", "10", "5", "--out",
                            out], capture_output=True, text=True, timeout=300)
        self.assertNotEqual(r.returncode, 0)
        lines = r.stderr.strip().splitlines()
        self.assertEqual(len(lines), 1, r.stderr)
        self.assertIn("libModelSynthOpenVDB.so", lines[0])
        self.assertIn("does not load", lines[0])
        self.assertFalse(os.path.exists(out) and os.listdir(out), out)
        # Without a .vdb output the same tree runs.
        r = subprocess.run([os.path.join(root, "bin", "msynth"), "synthesize",
                            data("Examples/Village.vti"), "--size", "10", "10", "5", "--out",
                            out, "--outputs", "labels"], capture_output=True, text=True,
                           timeout=300)
        self.assertEqual(r.returncode, 0, r.stderr)


if __name__ == "__main__":
    unittest.main()
