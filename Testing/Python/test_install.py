"""The installed tree: `cmake --install` into a scratch root (DESTDIR, prefix /usr: the Debian
package's layout), then the installed msynth, the package from /usr/bin/python3 and pvpython,
and the plugin in pvbatch, each run with an environment that knows nothing of the build tree.

Usage (ctest): python3 test_install.py CMAKE_COMMAND BUILD_DIR"""
import os
import re
import shutil
import subprocess
import sys
import unittest

from vtkmodules.vtkIOXML import vtkXMLImageDataReader

from msynth_testing import data, labels_zyx, tmp, violations

CMAKE, BUILD = sys.argv[1], sys.argv[2]
ROOT = tmp("install-root")
USR = os.path.join(ROOT, "usr")
PYTHON_DIR = os.path.join(USR, "lib", "python3.11", "dist-packages")
PLUGIN_DIR = os.path.join(USR, "lib", "x86_64-linux-gnu", "paraview-5.11", "plugins",
                          "ModelSynthPlugin")
TIMEOUT = 300 if os.environ.get("MSYNTH_SANITIZED") else 120


def clean_env(**extra):
    """The environment minus everything that points into the build tree."""
    env = {k: v for k, v in os.environ.items()
           if not k.startswith("MSYNTH_") and k not in ("PYTHONPATH", "LD_LIBRARY_PATH",
                                                       "PV_PLUGIN_PATH")}
    if os.environ.get("MSYNTH_SANITIZED"):  # the interpreters need the preloaded runtime
        env["MSYNTH_SANITIZED"] = "1"
    env.update(extra)
    return env


def run(args, **extra):
    return subprocess.run(args, capture_output=True, text=True, timeout=TIMEOUT, cwd=tmp(""),
                          env=clean_env(**extra))


def setUpModule():
    shutil.rmtree(ROOT, ignore_errors=True)
    r = subprocess.run([CMAKE, "--install", BUILD, "--prefix", "/usr"], capture_output=True,
                       text=True, env=dict(os.environ, DESTDIR=ROOT), timeout=TIMEOUT)
    if r.returncode != 0:
        raise RuntimeError("cmake --install failed:\n" + r.stdout + r.stderr)


class InstalledTreeTest(unittest.TestCase):
    def test_layout(self):
        for relative in ("bin/msynth", "lib/python3.11/dist-packages/modelsynth/__init__.py",
                         "lib/x86_64-linux-gnu/paraview-5.11/plugins/ModelSynthPlugin/"
                         "ModelSynthPlugin.so",
                         "share/modelsynth/README.md",
                         "share/modelsynth/Documentation/architecture.md",
                         "share/modelsynth/Data/Examples/Village.vti",
                         "share/modelsynth/Data/Tilesets/Lines.xml"):
            self.assertTrue(os.path.isfile(os.path.join(USR, relative)), relative)
        self.assertFalse(os.path.exists(os.path.join(USR, "share/modelsynth/Data/Malformed")))
        self.assertFalse(os.path.exists(os.path.join(USR, "include")))

    def test_no_build_paths_in_binaries(self):
        """Every installed ELF file finds its libraries $ORIGIN-relative, never in the build."""
        found = 0
        for folder, _, files in os.walk(USR):
            for name in files:
                path = os.path.join(folder, name)
                with open(path, "rb") as f:
                    if f.read(4) != b"\x7fELF" or os.path.islink(path):
                        continue
                found += 1
                r = subprocess.run(["readelf", "-d", path], capture_output=True, text=True)
                for line in r.stdout.splitlines():
                    if "RUNPATH" in line or "RPATH" in line:
                        self.assertNotIn(BUILD, line, path)
                        self.assertNotIn(os.path.dirname(BUILD), line, path)
        self.assertGreaterEqual(found, 8)  # msynth, 4 libraries, 2 Python modules, the plugin

    def test_debian_package_holds_the_installed_tree(self):
        """`cpack -G DEB` makes a package of exactly the installed files, with dependencies."""
        if os.environ.get("MSYNTH_SANITIZED"):
            self.skipTest("the package is made from the Release tree (CPack under the sanitizers "
                          "does not finish in the test's time)")
        cpack = os.path.join(os.path.dirname(CMAKE), "cpack")
        out = tmp("install-deb")
        shutil.rmtree(out, ignore_errors=True)
        r = subprocess.run([cpack, "-G", "DEB", "-B", out], cwd=BUILD, capture_output=True,
                           text=True, timeout=3 * TIMEOUT)
        self.assertEqual(r.returncode, 0, r.stdout + r.stderr)
        debs = [n for n in os.listdir(out) if n.endswith(".deb")]
        self.assertEqual(len(debs), 1, debs)
        deb = os.path.join(out, debs[0])
        listing = subprocess.run(["dpkg-deb", "-c", deb], capture_output=True, text=True).stdout
        # "perms owner size date time ./path[ -> target]"; paths may hold spaces.
        packaged = {line.split(None, 5)[5].split(" -> ")[0].lstrip(".")
                    for line in listing.splitlines() if not line.startswith("d")}
        installed = set()
        for folder, _, files in os.walk(ROOT):
            for name in files:
                installed.add("/" + os.path.relpath(os.path.join(folder, name), ROOT))
        self.assertIn("/usr/bin/msynth", packaged)
        # The package is the runtime: it leaves out the development pieces (static wrapping
        # libraries, link names) that a full install also writes.
        development = {p for p in installed
                       if p.endswith(".a") or re.fullmatch(r"/usr/lib/lib\w+\.so", p)}
        self.assertEqual(installed - packaged - development, set())
        # Unpacked anywhere, its msynth runs (libraries found $ORIGIN-relative).
        unpacked = tmp("install-deb-root")
        shutil.rmtree(unpacked, ignore_errors=True)
        subprocess.run(["dpkg-deb", "-x", deb, unpacked], check=True)
        folder = tmp("install-deb-run")
        shutil.rmtree(folder, ignore_errors=True)
        done = run([os.path.join(unpacked, "usr", "bin", "msynth"), "synthesize",
                    data("Examples/Village.vti"), "--size", "12", "10", "5", "--outputs", "labels",
                    "--out", folder])
        self.assertEqual(done.returncode, 0, done.stderr)
        self.assertTrue(os.path.isfile(os.path.join(folder, "labels.vti")))
        depends = subprocess.run(["dpkg-deb", "-f", deb, "Depends"], capture_output=True,
                                 text=True).stdout
        self.assertIn("paraview", depends)

    def test_msynth_runs_and_synthesizes(self):
        msynth = os.path.join(USR, "bin", "msynth")
        r = run([msynth, "--version"])
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertRegex(r.stdout, r"\d+\.\d+\.\d+")
        example = os.path.join(USR, "share/modelsynth/Data/Examples/Village.vti")
        out = tmp("install-synthesis")
        shutil.rmtree(out, ignore_errors=True)
        r = run([msynth, "synthesize", example, "--size", "10", "10", "5", "--seed", "3",
                 "--out", out, "--outputs", "labels"])
        self.assertEqual(r.returncode, 0, r.stderr)
        r = run([msynth, "check", example, os.path.join(out, "labels.vti")])
        self.assertEqual(r.returncode, 0, r.stdout + r.stderr)
        # Checked here too, by the tests' own recomputation of Eq. 3.1.
        grids = []
        for path in (data("Examples/Village.vti"), os.path.join(out, "labels.vti")):
            reader = vtkXMLImageDataReader()
            reader.SetFileName(path)
            reader.Update()
            grids.append(labels_zyx(reader.GetOutput()))
        self.assertEqual(violations(*grids), [])

    def test_python_imports_installed_package(self):
        script = ("import modelsynth, sys; r = modelsynth.vtkMSLabelGridReader(); "
                  "r.SetFileName(sys.argv[1]); r.Update(); "
                  "print(modelsynth.__file__); print(r.GetOutput().GetNumberOfPoints()); "
                  "print(modelsynth.plugin_path())")
        example = os.path.join(USR, "share/modelsynth/Data/Examples/Village.vti")
        for interpreter in ("/usr/bin/python3", shutil.which("pvpython")):
            r = run([interpreter, "-c", script, example], PYTHONPATH=PYTHON_DIR)
            self.assertEqual(r.returncode, 0, interpreter + ": " + r.stderr)
            lines = r.stdout.split()
            self.assertTrue(lines[0].startswith(PYTHON_DIR), lines[0])
            self.assertEqual(lines[1], str(7 * 7 * 5))
            self.assertEqual(lines[2], os.path.join(PLUGIN_DIR, "ModelSynthPlugin.so"))

    def test_pvbatch_auto_loads_plugin(self):
        """Debian's ParaView 5.11 auto-loads plugins from PV_PLUGIN_PATH (which the package's
        /etc/profile.d/modelsynth.sh sets) and /usr/bin/plugins only: the script names no path."""
        script = tmp("install-pvbatch.py")
        example = os.path.join(USR, "share/modelsynth/Data/Examples/Village.vti")
        with open(script, "w") as f:
            f.write(
                "import sys\n"
                "from paraview.simple import *\n"
                "from paraview import servermanager\n"
                "reader = ModelSynthLabelGridReader(FileName=[sys.argv[1]])\n"
                "reader.UpdatePipeline()\n"
                "print('points', reader.GetDataInformation().GetNumberOfPoints())\n"
                "plm = servermanager.vtkSMProxyManager.GetProxyManager().GetPluginManager()\n"
                "info = plm.GetLocalInformation()\n"
                "print('files', *[info.GetPluginFileName(i) for i in "
                "range(info.GetNumberOfPlugins()) if info.GetPluginLoaded(i)])\n")
        r = run(["pvbatch", script, example], PV_PLUGIN_PATH=PLUGIN_DIR)
        self.assertEqual(r.returncode, 0, r.stdout + r.stderr)
        self.assertIn("points %d" % (7 * 7 * 5), r.stdout)
        self.assertIn(os.path.join(PLUGIN_DIR, "ModelSynthPlugin.so"), r.stdout)


if __name__ == "__main__":
    unittest.main(argv=sys.argv[:1])
