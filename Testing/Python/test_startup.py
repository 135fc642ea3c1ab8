"""A run loads only what it uses (issue 45, "fixed costs paid only when needed"): the VTK
algorithms a few outputs and inputs need (vtkOBJReader, vtkPNGReader, vtkPointInterpolator,
vtkTriangleFilter: about 30 shared libraries) are in the module libModelSynthVTKOnDemand, and
OpenVDB in libModelSynthOpenVDB, each loaded on first use. Small runs that use neither load
neither, and stay within a budget of shared objects; the runs that use them still work. The
loader's own list (LD_DEBUG=files) is the measure: wall-clock budgets are noise on a loaded
machine."""
import os
import re
import shutil
import subprocess
import unittest

from msynth_testing import BIN, data, fresh_folder

# What a run that reads a picture or a tileset and writes labels.vti, picture.png and
# statistics.json must not load.
HEAVY = ("libModelSynthVTKOnDemand", "libModelSynthOpenVDB", "libopenvdb", "libvtkIOGeometry",
         "libvtkFiltersPoints", "libvtkFiltersCore", "libvtkFiltersGeneral",
         "libvtkRenderingCore", "libvtkIOImage", "libvtkImagingCore", "libtiff", "libjpeg")
# Shared objects such a run loads (msynth's own libraries, VTK's Common, ExecutionModel, IOXML
# and ParallelCore with their dependencies, libstdc++, libc...): 40 on Debian 12; the 30 heavy
# ones above would take it to about 60.
BUDGET = 45


def loaded(stderr):
    """The shared objects the dynamic loader opened, by file name, in order."""
    names = []
    for line in stderr.splitlines():
        m = re.search(r"file=(\S+) \[\d+\];\s+generating link map", line)
        if m:
            names.append(os.path.basename(m.group(1)))
    return names


def synthesize(folder, *args, env=None):
    out = fresh_folder(folder)
    r = subprocess.run([os.path.join(BIN, "msynth"), "synthesize", *args, "--out", out],
                       capture_output=True, text=True, timeout=300,
                       env=dict(os.environ, LD_DEBUG="files", **(env or {})))
    return r, out


class StartupTest(unittest.TestCase):
    def check_light(self, r, out, files):
        self.assertEqual(r.returncode, 0, r.stderr[-3000:])
        names = loaded(r.stderr)
        self.assertIn("libvtkCommonCore-pv5.11.so.1", names)  # LD_DEBUG did list them
        for heavy in HEAVY:
            self.assertFalse([n for n in names if n.startswith(heavy)],
                             "%s loaded: %s" % (heavy, names))
        self.assertLessEqual(len(names), BUDGET, names)
        written = [f for f in os.listdir(out) if not f.startswith(".")]
        self.assertEqual(sorted(written), sorted(files + ["statistics.json"]))

    def test_a_picture_sample_loads_only_what_it_uses(self):
        r, out = synthesize("startup-sample", data("Samples/Maze.png"), "--pattern", "3",
                            "--translate", "xy", "--size", "16", "16", "1", "--seed", "1")
        self.check_light(r, out, ["labels.vti", "picture.png"])
        r, out = synthesize("startup-sample-picture", data("Samples/Maze.png"), "--pattern",
                            "3", "--size", "16", "16", "1", "--seed", "1", "--outputs",
                            "picture")
        self.check_light(r, out, ["picture.png"])

    def test_a_tileset_loads_only_what_it_uses(self):
        r, out = synthesize("startup-tileset", data("Tilesets/Lines.xml"), "--size", "16",
                            "16", "1", "--seed", "1")
        self.check_light(r, out, ["labels.vti", "picture.png"])

    def test_the_outputs_that_need_the_module_load_it(self):
        # mesh.glb triangulates with vtkTriangleFilter: the module loads and the file is there.
        r, out = synthesize("startup-glb", data("Tilesets/Lines.xml"), "--size", "8", "8", "1",
                            "--seed", "1", "--outputs", "glb")
        self.assertEqual(r.returncode, 0, r.stderr[-3000:])
        names = loaded(r.stderr)
        self.assertTrue([n for n in names if n.startswith("libModelSynthVTKOnDemand")], names)
        self.assertTrue([n for n in names if n.startswith("libvtkFiltersCore")], names)
        self.assertGreater(os.path.getsize(os.path.join(out, "mesh.glb")), 0)

    def test_a_missing_module_is_one_line_and_no_outputs(self):
        # A copy of the build's layout (bin/, lib/) without the module: runs that need it fail
        # in one line naming it; the others run.
        root = fresh_folder("startup-module-missing")
        os.makedirs(os.path.join(root, "bin"))
        os.makedirs(os.path.join(root, "lib"))
        shutil.copy(os.path.join(BIN, "msynth"), os.path.join(root, "bin"))
        lib = os.path.join(BIN, "..", "lib")
        for name in os.listdir(lib):
            if name.startswith("lib") and ".so" in name and "VTKOnDemand" not in name:
                os.symlink(os.path.realpath(os.path.join(lib, name)),
                           os.path.join(root, "lib", name))
        msynth = os.path.join(root, "bin", "msynth")
        out = os.path.join(root, "out")
        r = subprocess.run([msynth, "synthesize", data("Tilesets/Lines.xml"), "--size", "8", "8",
                            "1", "--out", out, "--outputs", "glb"], capture_output=True,
                           text=True, timeout=300)
        self.assertNotEqual(r.returncode, 0)
        lines = r.stderr.strip().splitlines()
        self.assertEqual(len(lines), 1, r.stderr)
        self.assertIn("libModelSynthVTKOnDemand.so", lines[0])
        self.assertIn("does not load", lines[0])
        self.assertFalse(os.path.exists(out) and os.listdir(out), out)
        r = subprocess.run([msynth, "synthesize", data("Tilesets/Lines.xml"), "--size", "8", "8",
                            "1", "--out", out], capture_output=True, text=True, timeout=300)
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertTrue(os.path.exists(os.path.join(out, "picture.png")))


if __name__ == "__main__":
    unittest.main()
