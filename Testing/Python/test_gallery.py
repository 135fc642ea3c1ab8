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


if __name__ == "__main__":
    unittest.main()
