"""Every example in the README and the guides (Documentation/guide-*.md, scripting.md,
authoring.md) runs as written from the repository root: each ```sh block as a
bash script and each ```python block with the interpreter it names (plain vtkmodules Python, or
pvbatch for paraview.simple), in a scratch folder laid out like a checkout (Data, Utilities and
build/ linked), so the outputs do not land in the sources. A block passes when it exits 0, prints no
error (VTK's "ERR|", "Error", "error:") on either stream, and prints every number that a print's
comment states (`print(n, "sites")  # 16384`). The two commands of a fresh machine
(run-example.sh, run-tests.sh) and the placeholder my_script.py are left out: CI runs the first
two itself. The main job's own output is measured against its example and against the measures
recorded with the README's first picture (test_main_job_makes_the_picture)."""
import hashlib
import json
import os
import re
import shutil
import subprocess
import sys
import unittest

from msynth_testing import run_msynth, tmp
import village_measures

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
BUILD = os.path.dirname(os.environ["MSYNTH_BIN"])


GUIDES = ["README.md", os.path.join("Documentation", "scripting.md"),
          os.path.join("Documentation", "authoring.md")] + sorted(
    os.path.join("Documentation", name) for name in os.listdir(os.path.join(ROOT, "Documentation"))
    if name.startswith("guide-") and name.endswith(".md"))


def blocks():
    """(language, text, "file:line") of every fenced block of the README and the guides."""
    for name in GUIDES:
        with open(os.path.join(ROOT, name)) as f:
            text = f.read()
        for m in re.finditer(r"^```(\w+)\n(.*?)^```", text, re.S | re.M):
            yield m.group(1), m.group(2), "%s:%d" % (name, text[:m.start()].count("\n") + 1)


# An error that does not end the run: VTK's log ("ERR|"), a filter's "Error" or msynth's "error:"
ERROR_LINE = re.compile(r"\bERR\||\bError\b|\berror:")
# A print whose comment states what it prints: print(...)  # 16384  (or "# prints 16384 ...")
STATED = re.compile(r"^\s*print\(.*#\s*(?:prints\s+)?(-?\d[\d.,]*)\b")


def printed_problems(text, stdout, stderr):
    """What a block's output says against it: error lines on either stream, and every number that
    a print's comment states and no printed line holds as a word."""
    plain = re.sub(r"\x1b\[[0-9;]*m", "", stdout + stderr)  # without VTK's terminal colours
    problems = ["error printed: " + l.strip() for l in plain.splitlines() if ERROR_LINE.search(l)]
    for source in text.splitlines():
        m = STATED.match(source)
        if m and not any(re.search(r"(?<![\w.])%s(?![\w.])" % re.escape(m.group(1)), l)
                         for l in stdout.splitlines()):
            problems.append("the comment says %s, none printed: %s" % (m.group(1), source.strip()))
    return problems


class ReadmeExamplesTest(unittest.TestCase):
    def test_every_example_runs(self):
        if os.environ.get("MSYNTH_SANITIZED"):
            self.skipTest("the README's examples run in the Release build")
        scratch = self.scratch_checkout("readme")
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
            problems = printed_problems(text, done.stdout, done.stderr)
            self.assertFalse(problems, "%s:\n%s\n%s" % (line, "\n".join(problems), text))
            ran += 1
        self.assertGreaterEqual(ran, 11)

    def test_each_example_writes_a_folder_of_its_own(self):
        """Issue 49: outputs landed in output/ (the main job), output/NAME/ and beside them
        (output/houses.vtp next to output/houses/), and one folder served different commands
        (output/pipes: a voxel tileset in one guide, continuous pipes in another), each run
        replacing the other's files. Every example of the README and the guides writes into
        output/NAME/ (no file directly in output/), and a folder is one command's."""
        commands = {}
        loose = []
        for language, text, line in blocks():
            joined = re.sub(r"\\\n\s*", " ", text)
            for command in joined.splitlines():
                command = re.sub(r"#.*", "", command).strip()
                loose += ["%s: %s" % (line, m) for m in
                          re.findall(r"""(?<![\w/.-])output/[^/\s"']+\.\w+(?=[\s"']|$)""", command)]
                out = re.search(r"--out (output/[^\s]+)", command)
                if language == "sh" and out:
                    same = re.sub(r"^(\$M|build/bin/msynth) ", "msynth ", re.sub(r"\s+", " ", command))
                    commands.setdefault(out.group(1).rstrip("/"), {}).setdefault(same, line)
        self.assertFalse(loose, "files written directly in output/")
        shared = {folder: sorted(uses.values()) for folder, uses in commands.items()
                  if len(uses) > 1}
        self.assertFalse(shared, "folders written by different commands")
        self.assertGreater(len(commands), 40)

    def scratch_checkout(self, name):
        """A scratch folder laid out like a checkout (Data, Utilities and build/ linked)."""
        scratch = tmp(name)
        shutil.rmtree(scratch, ignore_errors=True)
        os.makedirs(scratch)
        for entry in ("Data", "Utilities"):
            os.symlink(os.path.join(ROOT, entry), os.path.join(scratch, entry))
        os.symlink(BUILD, os.path.join(scratch, "build"))
        return scratch

    def test_main_job_makes_the_picture(self):
        """The README's main job (its first command block) is run-example.sh; its model looks like
        its example (village_measures: label shares, buildings per column, roof cover, footprint)
        and is the model of the README's first picture (the measures and the picture's hash that
        Utilities/make-readme-picture.sh recorded with it)."""
        if os.environ.get("MSYNTH_SANITIZED"):
            self.skipTest("the main job runs in the Release build")
        with open(os.path.join(ROOT, "README.md")) as f:
            readme = f.read()
        with open(os.path.join(ROOT, "Documentation", "images", "village.json")) as f:
            record = json.load(f)
        picture = re.search(r"!\[[^]]*\]\(([^)]+)\)", readme).group(1)
        self.assertEqual(picture, record["picture"], "the README's first picture")
        first_block = re.search(r"^```sh\n(.*?)^```", readme, re.S | re.M).group(1)
        commands = [line for line in first_block.splitlines() if line and not line.startswith("#")]
        self.assertEqual(commands[0], record["command"], "the README's main job")
        with open(os.path.join(ROOT, picture), "rb") as f:
            self.assertEqual(hashlib.sha256(f.read()).hexdigest(), record["picture_sha256"],
                             "%s is not the picture Utilities/make-readme-picture.sh made" % picture)

        scratch = self.scratch_checkout("main-job")
        # (its default --out, output/main, as the README says: each run in a folder of its own)
        done = subprocess.run(["bash", os.path.join(scratch, "Utilities", "run-example.sh"),
                               "--no-build"], cwd=scratch, capture_output=True, text=True,
                              timeout=200)
        self.assertEqual(done.returncode, 0, done.stdout + done.stderr)
        self.assertIn("consistent", done.stdout)
        main = os.path.join(scratch, "output", "main")
        self.assertIn("outputs are in %s" % main, done.stdout)
        self.assertIn("`%s/labels.vti`" % os.path.relpath(main, scratch), readme)
        for name in ("labels.vti", "mesh.vtp", "mesh.glb", "model.vox", "model.vdb",
                     "statistics.json"):  # what the README says the main job writes
            self.assertTrue(os.path.isfile(os.path.join(main, name)), name)
        model = village_measures.measures(
            village_measures.read_labels(os.path.join(main, "labels.vti")))
        example = village_measures.measures(
            village_measures.read_labels(os.path.join(ROOT, "Data", "Examples", "Houses.vox")))
        self.assertEqual(village_measures.compare(model, example), [])
        for name, value in record["measures"].items():
            self.assertAlmostEqual(model[name], value, 9, "%s: the main job's model is not the "
                                   "picture's; rerun Utilities/make-readme-picture.sh" % name)

    def test_measures_tell_a_maze_from_the_example(self):
        """village_measures.compare rejects the main job's former model, a maze of roofs (the
        7 x 7 x 5 village, labels drawn uniformly) and the resemblance village of one-site huts."""
        if os.environ.get("MSYNTH_SANITIZED"):
            self.skipTest("the main job runs in the Release build")
        village = os.path.join(ROOT, "Data", "Examples", "Village.vti")
        example = village_measures.measures(village_measures.read_labels(village))
        for choice, unlike in (("uniform", "roof_cover"), ("resemblance", "mean_footprint")):
            out = tmp("maze-" + choice)
            done = run_msynth("synthesize", village, "--size", "48", "48", "5", "--block", "12", "12",
                              "5", "--ground", "1", "--empty", "0", "--choice", choice, "--seed", "1",
                              "--outputs", "labels", "--out", out)
            self.assertEqual(done.returncode, 0, done.stderr)
            model = village_measures.measures(
                village_measures.read_labels(os.path.join(out, "labels.vti")))
            problems = village_measures.compare(model, example)
            self.assertTrue(any(p.startswith(unlike) for p in problems), (choice, problems))


if __name__ == "__main__":
    unittest.main()
