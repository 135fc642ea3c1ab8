"""Every gallery command (Utilities/make-gallery.py's ENTRIES) runs as Documentation/gallery.md
shows it, and writes something (apart from test_readme, so that each stays well within its time
limit)."""
import os
import shutil
import subprocess
import unittest

from msynth_testing import tmp

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))


class GalleryTest(unittest.TestCase):
    def test_every_gallery_command_runs(self):
        """The gallery's commands (Utilities/make-gallery.py) as the page shows them."""
        if os.environ.get("MSYNTH_SANITIZED"):
            self.skipTest("the gallery's examples run in the Release build")
        import importlib.util
        spec = importlib.util.spec_from_file_location(
            "gallery", os.path.join(ROOT, "Utilities", "make-gallery.py"))
        gallery = importlib.util.module_from_spec(spec)
        spec.loader.exec_module(gallery)
        scratch = tmp("gallery")
        shutil.rmtree(scratch, ignore_errors=True)
        os.makedirs(scratch)
        for name, kind, what, command, preview in gallery.ENTRIES:
            if name in gallery.QUICK_SIZES:  # minutes at the gallery's size: the same, smaller
                words = command.split()
                at = words.index("--size")
                words[at + 1:at + 4] = gallery.QUICK_SIZES[name].split()
                command = " ".join(words)
            done = subprocess.run([os.path.join(os.environ["MSYNTH_BIN"], "msynth")] + command.split()
                                  + ["--out", os.path.join(scratch, name)], cwd=ROOT,
                                  capture_output=True, text=True, timeout=300)
            self.assertEqual(done.returncode, 0, "%s: %s" % (name, done.stderr))
            self.assertTrue(os.listdir(os.path.join(scratch, name)), name)
            self.check_structure(name, command, os.path.join(scratch, name, "statistics.json"))

    def check_structure(self, name, command, statistics):
        """A 3D continuous model records its structure against its example: a median footprint
        (or, for a network, its share in network-sized parts) for every object type of the
        example, named as its OBJ names them."""
        words = command.split()
        example = words[1]
        if not example.endswith(".obj") or "--size" not in words or \
                float(words[words.index("--size") + 3]) == 0:
            return
        import json
        with open(statistics) as f:
            measures = {m["measure"]: m for m in json.load(f)["Resemblance"]}
        types = set()
        with open(os.path.join(ROOT, example)) as f:
            for line in f:
                if line.startswith("o "):
                    types.add(line.split()[1].split(".")[0])
        for t in types:
            if "--types" in words:
                break  # types renamed on the command line
            key = "%s: median footprint (square units)" % t
            if key not in measures:  # a network: how much of it is in network-sized parts
                key = "%s: volume share in networks (parts spanning half the example's)" % t
            self.assertIn(key, measures, name)
            self.assertGreater(measures[key]["example"], 0, (name, key))


if __name__ == "__main__":
    unittest.main()
