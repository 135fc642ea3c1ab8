"""Every example in the README, the guides and the gallery runs as written from the repository root: each ```sh block as a
bash script and each ```python block with the interpreter it names (plain vtkmodules Python, or
pvbatch for paraview.simple), in a scratch folder laid out like a checkout (Data, Utilities and
build/ linked), so the outputs do not land in the sources. The two commands of a fresh machine
(run-example.sh, run-tests.sh) and the placeholder my_script.py are left out: CI runs the first
two itself."""
import os
import re
import shutil
import subprocess
import sys
import unittest

from msynth_testing import tmp

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
BUILD = os.path.dirname(os.environ["MSYNTH_BIN"])


GUIDES = ("README.md", os.path.join("Documentation", "scripting.md"),
          os.path.join("Documentation", "authoring.md"))


def blocks():
    """(language, text, "file:line") of every fenced block of the README and the guides."""
    for name in GUIDES:
        with open(os.path.join(ROOT, name)) as f:
            text = f.read()
        for m in re.finditer(r"^```(\w+)\n(.*?)^```", text, re.S | re.M):
            yield m.group(1), m.group(2), "%s:%d" % (name, text[:m.start()].count("\n") + 1)


class ReadmeExamplesTest(unittest.TestCase):
    def test_every_example_runs(self):
        if os.environ.get("MSYNTH_SANITIZED"):
            self.skipTest("the README's examples run in the Release build")
        scratch = tmp("readme")
        shutil.rmtree(scratch, ignore_errors=True)
        os.makedirs(scratch)
        for name in ("Data", "Utilities"):
            os.symlink(os.path.join(ROOT, name), os.path.join(scratch, name))
        os.symlink(BUILD, os.path.join(scratch, "build"))
        ran = 0
        for language, text, line in blocks():
            if "Utilities/run-" in text or "my_script.py" in text:
                continue
            if language == "sh":
                command = ["bash", "-e", "-o", "pipefail", "-c", text]
            elif language == "python":
                script = os.path.join(scratch, "block_%d.py" % ran)
                with open(script, "w") as f:
                    f.write(text)
                command = ["pvbatch", script] if "paraview.simple" in text else [sys.executable, script]
            else:
                continue
            try:  # within the test's own limit, so that a hang names its block
                done = subprocess.run(command, cwd=scratch, capture_output=True, text=True, timeout=200)
            except subprocess.TimeoutExpired:
                self.fail("%s did not finish within 200 s:\n%s" % (line, text))
            self.assertEqual(done.returncode, 0, "%s:\n%s\n%s\n%s\n...\n%s" % (
                line, text, done.stdout[-2000:], done.stderr[:2000], done.stderr[-2000:]))
            ran += 1
        self.assertGreaterEqual(ran, 11)

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
            done = subprocess.run([os.path.join(os.environ["MSYNTH_BIN"], "msynth")] + command.split()
                                  + ["--out", os.path.join(scratch, name)], cwd=ROOT,
                                  capture_output=True, text=True, timeout=300)
            self.assertEqual(done.returncode, 0, "%s: %s" % (name, done.stderr))
            self.assertTrue(os.listdir(os.path.join(scratch, name)), name)


if __name__ == "__main__":
    unittest.main()
