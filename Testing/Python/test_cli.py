"""The msynth command line: outputs, exit codes and one-line errors."""
import csv
import json
import os
import re
import resource
import shutil
import signal
import subprocess
import time
import unittest

import numpy as np

import modelsynth
from msynth_testing import BIN, data, fresh_folder, labels_zyx, tmp, violations

MSYNTH = os.path.join(BIN, "msynth")


# The sanitizer build runs several times slower, and beside other tests.
TIMEOUT = 300 if os.environ.get("MSYNTH_SANITIZED") else 120


def run(*args):
    return subprocess.run([MSYNTH, *args], capture_output=True, text=True, timeout=TIMEOUT)


def labels_of(path):
    """The Label array of a .vti as a [y, x] array (2D)."""
    reader = modelsynth.vtkMSLabelGridReader()
    reader.SetFileName(path)
    reader.Update()
    return labels_zyx(reader.GetOutput())[0]


def violations_free_pairs(path):
    """Every (axis, a, b) of neighbours along x and y in a 2D label grid."""
    g = labels_of(path)
    pairs = set(zip([0] * g[:, :-1].size, g[:, :-1].ravel().tolist(), g[:, 1:].ravel().tolist()))
    pairs |= set(zip([1] * g[:-1, :].size, g[:-1, :].ravel().tolist(), g[1:, :].ravel().tolist()))
    return pairs


class CommandLineTest(unittest.TestCase):
    def test_analyze_writes_outputs(self):
        out = tmp("cli-out")
        shutil.rmtree(out, ignore_errors=True)
        r = run("analyze", data("Examples/Village.vti"), "--out", out)
        self.assertEqual(r.returncode, 0, r.stderr)
        for name in ("labels.csv", "transitions.csv", "example.vdb"):
            self.assertTrue(os.path.isfile(os.path.join(out, name)), name)
        with open(os.path.join(out, "labels.csv")) as f:
            rows = list(csv.DictReader(f))
        self.assertEqual([r["Label"] for r in rows], ["0", "1", "2", "3"])
        self.assertEqual(sum(int(r["Count"]) for r in rows), 7 * 7 * 5)
        listing = subprocess.run(["vdb_print", "-l", "-m", os.path.join(out, "example.vdb")],
                                 capture_output=True, text=True)
        self.assertEqual(listing.returncode, 0)
        self.assertIn("Name: Label", listing.stdout)
        self.assertIn("Tree_int32", listing.stdout)
        self.assertIn("generator: ModelSynth", listing.stdout)
        self.assertEqual([n for n in os.listdir(out) if ".tmp-" in n], [])

    def test_info(self):
        r = run("info", data("Examples/Checkerboard.vti"))
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertIn("labels: 2", r.stdout)
        self.assertIn("transitions +x: 2", r.stdout)
        self.assertIn("infallibility: proved infallible", r.stdout)
        self.assertIn("infallibility: not proved", run("info", data("Examples/Village.vti")).stdout)

    def test_info_polyhedral(self):
        r = run("info", data("Continuous/tetrahedron.obj"))
        self.assertEqual(r.returncode, 0, r.stderr)
        lines = r.stdout.splitlines()
        self.assertEqual(lines[0], "labels: 16")
        self.assertEqual(lines[1].split(), ["0", "volume", "∅"])
        self.assertEqual(lines[2].split(), ["1", "volume", "ℝ³"])
        kinds = [line.split()[1] for line in lines[1:17]]
        self.assertEqual((kinds.count("face"), kinds.count("edge"), kinds.count("vertex")), (4, 6, 4))
        self.assertIn("plane families: 4", r.stdout)
        r = run("info", data("Continuous/two-objects2d.obj"), "--types", "roof=3")
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertIn("3·ℝ²", r.stdout)
        out = tmp("analyze-house")
        r = run("analyze", data("Continuous/house.obj"), "--out", out)
        self.assertEqual(r.returncode, 0, r.stderr)
        with open(os.path.join(out, "labels.csv"), encoding="utf-8") as f:
            rows = f.read().splitlines()
        self.assertEqual(rows[0].split(",")[:3], ["Id", "Kind", "Codimension"])
        self.assertEqual(len(rows), 1 + 49)
        self.assertTrue(os.path.getsize(os.path.join(out, "marked-example.vtp")) > 0)
        bad = tmp("open-cli.obj")
        with open(bad, "w") as f:
            f.write("v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\n")
        r = run("info", bad)
        self.assertEqual(r.returncode, 1)
        self.assertIn("open-cli.obj", r.stderr)
        self.assertIn("not closed", r.stderr)
        self.assertEqual(len(r.stderr.strip().splitlines()), 1, r.stderr)

    def test_discrete_catalog_sequence(self):
        out = tmp("cli-discrete-sequence")
        if os.path.isdir(out):
            for name in os.listdir(out):
                os.remove(os.path.join(out, name))
        r = run("synthesize", data("Examples/Village.vti"), "--size", "20", "20", "5", "--block", "10", "10", "5",
                "--snapshots", "1", "--seed", "2", "--out", out)
        self.assertEqual(r.returncode, 0, r.stderr)
        steps = sorted(n for n in os.listdir(out) if n.startswith("catalog_"))
        self.assertEqual(steps, ["catalog_%04d.vdb" % i for i in range(1, 11)])  # start + 9 blocks
        listing = subprocess.run(["vdb_print", "-l", "-m", os.path.join(out, steps[0])], capture_output=True,
                                 text=True).stdout
        for grid in ("Label", "CatalogSize", "Entropy"):
            self.assertIn("Name: " + grid + "\n", listing)
        self.assertIn("seed: 2", listing)
        # The text format's piece names travel to the .vdb as label_names.
        named = tmp("cli-discrete-named")
        r = run("synthesize", data("Examples/Village.txt"), "--size", "8", "8", "5", "--out", named)
        self.assertEqual(r.returncode, 0, r.stderr)
        listing = subprocess.run(["vdb_print", "-l", "-m", os.path.join(named, "model.vdb")], capture_output=True,
                                 text=True).stdout
        self.assertIn("label_names: 1:ground_tile;2:wall;2:window;3:roof", listing)
        # ... and the model in the original program's format, as it writes its outputs, with the
        # example's <Objects> trailer unchanged (its Blender and 3ds Max loaders read it).
        with open(os.path.join(named, "model.txt")) as f:
            text = f.read()
        with open(data("Examples/Village.txt")) as f:
            original = f.read()
        self.assertIn("\nx, y, and z extents\n8 8 5\n\n", text)
        self.assertTrue(text.endswith(original[original.index("<Objects>"):]))
        # Read independently as that program does (numbers after the header, for z, x, y).
        words = text.split("\n", 3)[3].split()
        values = np.array([int(w) for w in words[3:3 + 8 * 8 * 5]]).reshape(5, 8, 8)  # z, x, y
        reader = modelsynth.vtkMSLabelGridReader()
        reader.SetFileName(os.path.join(named, "labels.vti"))
        reader.Update()
        self.assertTrue(np.array_equal(values.transpose(0, 2, 1), labels_zyx(reader.GetOutput())))
        self.assertEqual(words[3 + 8 * 8 * 5], "<Objects>")
        # A .vox example gives model.vox with the example's palette, read back independently:
        # MagicaVoxel's chunks (SIZE, XYZI: x, y, z, index per voxel; RGBA) parsed here.
        vox = tmp("cli-discrete-vox")
        r = run("synthesize", data("Examples/Village.vox"), "--size", "9", "7", "5", "--seed", "5", "--out", vox)
        self.assertEqual(r.returncode, 0, r.stderr)
        with open(os.path.join(vox, "model.vox"), "rb") as f:
            raw = f.read()
        self.assertEqual(raw[:4], b"VOX ")
        at = raw.index(b"SIZE") + 12
        size = np.frombuffer(raw[at:at + 12], dtype="<u4").tolist()
        self.assertEqual(size, [9, 7, 5])
        at = raw.index(b"XYZI") + 12
        count = int(np.frombuffer(raw[at:at + 4], dtype="<u4")[0])
        voxels = np.frombuffer(raw[at + 4:at + 4 + 4 * count], dtype=np.uint8).reshape(-1, 4)
        dense = np.zeros((5, 7, 9), dtype=np.int32)
        dense[voxels[:, 2], voxels[:, 1], voxels[:, 0]] = voxels[:, 3]
        reader = modelsynth.vtkMSLabelGridReader()
        reader.SetFileName(os.path.join(vox, "labels.vti"))
        reader.Update()
        self.assertTrue(np.array_equal(dense, labels_zyx(reader.GetOutput())))
        with open(data("Examples/Village.vox"), "rb") as f:
            original = f.read()
        at = original.index(b"RGBA") + 12
        # Entries 1..255 (the chunk's 256th entry names no usable index).
        self.assertEqual(raw[raw.index(b"RGBA") + 12:][:1020], original[at:at + 1020])

    def test_synthesize_polyhedral_then_check(self):
        out = tmp("cli-continuous")
        r = run("synthesize", data("Continuous/l-prism.obj"), "--size", "8", "6", "3", "--seed", "4",
                "--snapshots", "2", "--out", out)
        self.assertEqual(r.returncode, 0, r.stderr)
        for name in ("model.vtp", "arrangement.vtp", "model.vdb", "statistics.json", "catalog_0001.vdb",
                     "catalog_0002.vdb", "catalog_0003.vdb"):
            self.assertTrue(os.path.getsize(os.path.join(out, name)) > 0, name)
        self.assertFalse(os.path.exists(os.path.join(out, "catalog_0004.vdb")))
        listing = subprocess.run(["vdb_print", "-l", "-m", os.path.join(out, "model.vdb")],
                                 capture_output=True, text=True).stdout
        for grid in ("surface", "surface_block", "density"):
            self.assertIn("Name: " + grid + "\n", listing)
        self.assertIn("class: level set", listing)
        self.assertIn("class: fog volume", listing)
        self.assertIn("seed: 4", listing)
        self.assertIn("object_type_names: 0:empty;1:block", listing)
        with open(os.path.join(out, "statistics.json")) as f:
            stats = json.load(f)
        self.assertGreater(stats["Polygons"], 0)
        self.assertEqual(stats["seed"], 4)
        r = run("check", data("Continuous/l-prism.obj"), os.path.join(out, "model.vtp"))
        self.assertEqual(r.returncode, 0, r.stdout + r.stderr)
        self.assertIn("valid", r.stdout)
        # Same seed, same files (timing is only in statistics.json).
        again = tmp("cli-continuous-again")
        run("synthesize", data("Continuous/l-prism.obj"), "--size", "8", "6", "3", "--seed", "4",
            "--snapshots", "2", "--out", again)
        for name in ("model.vtp", "arrangement.vtp"):
            with open(os.path.join(out, name), "rb") as a, open(os.path.join(again, name), "rb") as b:
                self.assertEqual(a.read(), b.read(), name)
        # OpenVDB stamps every file with a random UUID: compare the grids and metadata instead.
        for name in ("model.vdb", "catalog_0002.vdb"):
            listings = [subprocess.run(["vdb_print", "-l", "-m", os.path.join(folder, name)], capture_output=True,
                                       text=True).stdout.replace(folder, "") for folder in (out, again)]
            self.assertEqual(listings[0], listings[1], name)
        # A model with a polygon removed is not closed: check says so and exits 1.
        from vtkmodules.vtkIOXML import vtkXMLPolyDataReader, vtkXMLPolyDataWriter
        reader = vtkXMLPolyDataReader()
        reader.SetFileName(os.path.join(out, "model.vtp"))
        reader.Update()
        model = reader.GetOutput()
        model.BuildCells()
        model.DeleteCell(0)
        model.RemoveDeletedCells()
        broken = tmp("cli-continuous-broken.vtp")
        writer = vtkXMLPolyDataWriter()
        writer.SetInputData(model)
        writer.SetFileName(broken)
        writer.Write()
        r = run("check", data("Continuous/l-prism.obj"), broken)
        self.assertEqual(r.returncode, 1, r.stdout)
        self.assertIn("invalid", r.stdout)
        # 2D: SZ is ignored.
        r = run("synthesize", data("Continuous/triangle2d.obj"), "--size", "12", "9", "0", "--spacing", "1",
                "--out", tmp("cli-continuous-2d"))
        self.assertEqual(r.returncode, 0, r.stderr)
        # Usage errors exit 2; a box too small for any plane still works (an empty model).
        self.assertEqual(run("synthesize", data("Continuous/cube.obj"), "--size", "4", "x", "4").returncode, 2)
        self.assertEqual(run("synthesize", data("Continuous/cube.obj"), "--size", "4", "4", "4",
                             "--spacing", "-1").returncode, 2)
        r = run("synthesize", data("Continuous/cube.obj"), "--size", "0", "4", "4", "--out", tmp("cli-c0"))
        self.assertEqual(r.returncode, 1)
        self.assertIn("cube.obj", r.stderr)

    def test_bad_input_exits_non_zero_with_one_line(self):
        path = data("Malformed/truncated.vti")
        r = run("info", path)
        self.assertEqual(r.returncode, 1)
        self.assertEqual(r.stderr.count("\n"), 1, r.stderr)
        self.assertIn(path, r.stderr)
        # A folder, a pipe, an unknown extension; a file whose bad bytes are terminal escapes.
        folder = tmp("a-folder.vti")
        os.makedirs(folder, exist_ok=True)
        fifo = tmp("a-pipe.vti")
        if not os.path.exists(fifo):
            os.mkfifo(fifo)
        other = tmp("notes.abc")
        with open(other, "w") as f:
            f.write("x")
        escape = tmp("escape.txt")
        with open(escape, "w") as f:
            f.write("a\nb\nc\n1 1 1\n\x1b[31mred\x07\n")
        for path, problem in ((folder, "is a folder, not a file"),
                              (fifo, "is not a regular file (a pipe, socket or device)"),
                              (other, "has the unknown extension '.abc'; examples are label grids "
                                       "(.vti, .txt, .vox), tilesets (.xml), image samples (.png, .bmp) or "
                                       "polyhedra (.obj, .vtp, .ply, .stl)"),
                              (escape, "'?[31mred?' is not an integer")):
            for command in (("info", path), ("synthesize", path, "--size", "4", "4", "1")):
                r = run(*command)
                self.assertEqual(r.returncode, 1, command)
                self.assertEqual(r.stderr, "msynth: error: '%s'%s%s\n" % (
                    path, ", line 5: " if path == escape else ": ", problem), command)
                self.assertNotIn("\x1b", r.stderr)

    def test_moved_tetrahedron_vertex_does_not_hang(self):
        # The report: the bundled tetrahedron with one vertex moved to (255, 3, 0) made the plane
        # arrangement run for over 300 s. Each vertex moved in turn, in two boxes: every run
        # ends (a model, or one line refusing the arrangement) well within the limit.
        # The sanitizer build runs several times slower, beside other tests: a hang is still
        # minutes, so the limit grows with it.
        limit = 240 if os.environ.get("MSYNTH_SANITIZED") else 30
        with open(data("Continuous/tetrahedron.obj")) as f:
            lines = f.read().splitlines()
        vertices = [i for i, line in enumerate(lines) if line.startswith("v ")]
        for k, index in enumerate(vertices):
            moved = list(lines)
            moved[index] = "v 255 3 0"
            path = tmp("moved-tetrahedron-%d.obj" % k)
            with open(path, "w") as f:
                f.write("\n".join(moved) + "\n")
            for size in (("24", "24", "10"), ("300", "10", "10")):
                start = time.time()
                r = run("synthesize", path, "--size", *size, "--out", tmp("moved-tetrahedron-out"))
                self.assertLess(time.time() - start, limit, (k, size))
                self.assertIn(r.returncode, (0, 1), r.stderr)
                if r.returncode == 1:
                    self.assertEqual(r.stderr.count("\n"), 1, r.stderr)

    def test_unwritable_output(self):
        r = run("analyze", data("Examples/Village.vti"), "--out", "/proc/forbidden")
        self.assertEqual(r.returncode, 1)
        self.assertIn("/proc/forbidden", r.stderr)

    def test_outputs_appear_all_at_once_or_not_at_all(self):
        out = tmp("cli-all-or-nothing")
        shutil.rmtree(out, ignore_errors=True)
        args = ("synthesize", data("Examples/Village.vti"), "--block", "10", "10", "5", "--out", out)
        r = run(*args, "--size", "20", "20", "5", "--snapshots", "2", "--seed", "1")
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertIn("wrote %s/labels.vti" % out, r.stdout)  # the final names, not the staging
        self.assertIn("catalog_0019.vdb", os.listdir(out))
        self.assertNotIn("replaced", r.stderr)  # a new folder: nothing replaced

        def snapshot():
            files = {}
            for name in os.listdir(out):
                with open(os.path.join(out, name), "rb") as f:
                    files[name] = f.read()
            return files

        # A second run without snapshots replaces the whole set: no catalog of the first stays.
        r = run(*args, "--size", "20", "20", "5", "--seed", "2")
        self.assertEqual(r.returncode, 0, r.stderr)
        visible = sorted(n for n in os.listdir(out) if not n.startswith("."))
        self.assertEqual(visible, ["labels.vti", "mesh.vtp", "model.vdb", "statistics.json"])
        # ... and says so in one line (issue 49: earlier outputs were replaced silently).
        self.assertEqual(r.stderr.strip().splitlines()[-1],
                         "msynth: note: this run replaced the earlier outputs in '%s' (labels.vti, "
                         "mesh.vtp, model.vdb, statistics.json) and removed the earlier outputs it "
                         "did not write again (catalog_0001.vdb, catalog_0002.vdb, catalog_0003.vdb, "
                         "catalog_0004.vdb, catalog_0005.vdb, catalog_0006.vdb, catalog_0007.vdb, "
                         "catalog_0008.vdb and 11 more)" % out)
        before = snapshot()
        # Interrupted at any moment (synthesis, writing, publishing): exit 130/143 with one line
        # and the earlier set untouched, or exit 0 with a complete new set; never a mixture, and
        # no staging folder or temporary file left.
        # (About 2 s of synthesis and writing in the Release build: the signals land in
        # synthesis, in writing and after the end; a slower build is interrupted earlier.)
        for delay, sig in ((0.1, signal.SIGINT), (0.4, signal.SIGTERM), (0.8, signal.SIGINT),
                           (1.2, signal.SIGTERM), (1.6, signal.SIGINT), (3.0, signal.SIGTERM)):
            p = subprocess.Popen([MSYNTH, *args, "--size", "300", "300", "5", "--seed", "3"],
                                 stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
            time.sleep(delay)
            p.send_signal(sig)
            stdout, stderr = p.communicate(timeout=120)
            names = os.listdir(out)
            self.assertFalse([n for n in names if ".tmp-" in n or n.startswith(".msynth-stage")], names)
            if p.returncode == 0:
                before = snapshot()
                self.assertIn("statistics.json", before)
                with open(os.path.join(out, "statistics.json")) as f:
                    self.assertEqual(json.load(f)["seed"], 3)
            else:
                # (A signal before main() has set up its handling ends the process at once.)
                self.assertIn(p.returncode, (128 + sig, -sig), stderr)
                if p.returncode == 128 + sig:
                    self.assertEqual(stderr.strip().splitlines()[-1],
                                     "msynth: interrupted (%s); no outputs were written" % sig.name)
                self.assertEqual(snapshot(), before, "interrupted after %.1f s" % delay)

    def test_a_failed_write_leaves_nothing(self):
        # Files may not grow past 4 KB (as on a full disk, a write fails): exit 1 naming the file
        # and the problem, and no folder, file or temporary file is left.
        out = tmp("cli-full")
        shutil.rmtree(out, ignore_errors=True)

        def limit():
            signal.signal(signal.SIGXFSZ, signal.SIG_IGN)
            resource.setrlimit(resource.RLIMIT_FSIZE, (4096, 4096))

        for args in (("analyze", data("Examples/Village.vti")),
                     ("synthesize", data("Examples/Village.vti"), "--size", "30", "30", "5")):
            r = subprocess.run([MSYNTH, *args, "--out", out], capture_output=True, text=True,
                               timeout=120, preexec_fn=limit)
            self.assertEqual(r.returncode, 1, r.stdout + r.stderr)
            self.assertEqual(len(r.stderr.strip().splitlines()), 1, r.stderr)
            self.assertIn("could not be written: File too large", r.stderr)
            self.assertIn("'" + out + "/", r.stderr)
            self.assertNotIn(".msynth-stage", r.stderr)
            self.assertFalse(os.path.exists(out), os.listdir(out) if os.path.exists(out) else "")

    def test_synthesize_then_check(self):
        out = tmp("cli-synth")
        shutil.rmtree(out, ignore_errors=True)
        example = data("Examples/Village.vti")
        r = run("synthesize", example, "--size", "30", "24", "5", "--block", "10", "10", "5",
                "--seed", "9", "--ground", "1", "--empty", "0", "--order", "entropy", "--out", out)
        self.assertEqual(r.returncode, 0, r.stderr)
        # The end summary: size, labels, blocks and the time, of the whole run and of the synthesis
        # (statistics.json's Seconds).
        summary = [line for line in r.stdout.splitlines() if line.startswith("30 x 24 x 5 sites, ")]
        self.assertEqual(len(summary), 1, r.stdout)
        times = re.search(r"sites, \d+ distinct labels, \d+ blocks \(0 failed\), total ([0-9.]+) s, "
                          r"synthesis ([0-9.]+) s$", summary[0])
        self.assertTrue(times, summary[0])
        total, synthesis = float(times.group(1)), float(times.group(2))
        for name in ("labels.vti", "mesh.vtp", "model.vdb", "statistics.json"):
            self.assertTrue(os.path.isfile(os.path.join(out, name)), name)
        from vtkmodules.vtkIOXML import vtkXMLPolyDataReader
        mesh = vtkXMLPolyDataReader()
        mesh.SetFileName(os.path.join(out, "mesh.vtp"))
        mesh.Update()
        self.assertGreater(mesh.GetOutput().GetNumberOfCells(), 0)
        self.assertIsNotNone(mesh.GetOutput().GetCellData().GetArray("Label"))
        with open(os.path.join(out, "statistics.json")) as f:
            stats = json.load(f)
        self.assertEqual(stats["seed"], 9)
        self.assertEqual(stats["BlocksAccepted"] + stats["BlocksFailed"], stats["Blocks"])
        self.assertEqual(stats["size"], [30, 24, 5])
        self.assertAlmostEqual(synthesis, stats["Seconds"], delta=0.006)
        self.assertGreaterEqual(total, synthesis)

        # The model read back is consistent (independent numpy check) and so says `check`.
        reader = modelsynth.vtkMSLabelGridReader()
        reader.SetFileName(os.path.join(out, "labels.vti"))
        reader.Update()
        ex = modelsynth.vtkMSLabelGridReader()
        ex.SetFileName(example)
        ex.Update()
        self.assertEqual(violations(labels_zyx(ex.GetOutput()), labels_zyx(reader.GetOutput())), [])
        r = run("check", example, os.path.join(out, "labels.vti"))
        self.assertEqual(r.returncode, 0, r.stdout + r.stderr)
        self.assertIn("consistent", r.stdout)

        # Against another example it is not: exit 1 with the violations listed.
        r = run("check", data("Examples/Checkerboard.vti"), os.path.join(out, "labels.vti"))
        self.assertEqual(r.returncode, 1)
        self.assertIn("never occurs in the example", r.stdout)
        # Each printed violation names its pair as it is (a 2 x 2 model "0 0 / 0 1" in the
        # original text format, against the checkerboard).
        bad = tmp("cli-bad-model.txt")
        with open(bad, "w") as f:
            f.write("a\nb\nc\n2 2 1\n0 0\n0 1\n")
        r = run("check", data("Examples/Checkerboard.vti"), bad)
        self.assertEqual(r.returncode, 1)
        self.assertEqual(r.stdout.splitlines()[1:], [
            "  site (0, 0, 0): label 0 followed by 0 along +x is not allowed (never occurs in the example)",
            "  site (0, 0, 0): label 0 followed by 0 along +y is not allowed (never occurs in the example)",
        ])

        # Same seed, same file contents.
        again = tmp("cli-synth-again")
        shutil.rmtree(again, ignore_errors=True)
        run("synthesize", example, "--size", "30", "24", "5", "--block", "10", "10", "5",
            "--seed", "9", "--ground", "1", "--empty", "0", "--order", "entropy", "--out", again)
        with open(os.path.join(out, "labels.vti"), "rb") as a, open(os.path.join(again, "labels.vti"), "rb") as b:
            self.assertEqual(a.read(), b.read())

    def test_guide_option(self):
        from vtkmodules.vtkCommonCore import vtkFloatArray
        from vtkmodules.vtkCommonDataModel import vtkImageData
        from vtkmodules.vtkIOXML import vtkXMLImageDataWriter
        guide = vtkImageData()
        guide.SetDimensions(2, 1, 1)
        for label in (2, 3):
            w = vtkFloatArray()
            w.SetName("Weight_%d" % label)
            w.InsertNextValue(1.0)
            w.InsertNextValue(0.0)  # no buildings in the right half
            guide.GetPointData().AddArray(w)
        path = tmp("guide.vti")
        writer = vtkXMLImageDataWriter()
        writer.SetInputData(guide)
        writer.SetFileName(path)
        writer.Write()
        out = tmp("cli-guide")
        shutil.rmtree(out, ignore_errors=True)
        r = run("synthesize", data("Examples/Village.vti"), "--size", "20", "10", "5", "--block",
                "10", "10", "5", "--ground", "1", "--empty", "0", "--guide", path, "--out", out)
        self.assertEqual(r.returncode, 0, r.stderr)
        reader = modelsynth.vtkMSLabelGridReader()
        reader.SetFileName(os.path.join(out, "labels.vti"))
        reader.Update()
        model = labels_zyx(reader.GetOutput())
        self.assertFalse(((model[:, :, 10:] == 2) | (model[:, :, 10:] == 3)).any())
        r = run("synthesize", data("Examples/Village.vti"), "--size", "4", "4", "4", "--guide",
                tmp("no-guide.vti"), "--out", out)
        self.assertEqual(r.returncode, 1)
        self.assertIn("no such guide file", r.stderr)

    def test_image_sample(self):
        meadow = data("Samples/Meadow.png")
        out = tmp("cli-sample")
        shutil.rmtree(out, ignore_errors=True)
        r = run("synthesize", meadow, "--pattern", "3", "--symmetry", "2", "--ground", "--translate", "xy",
                "--size", "64", "40", "1", "--block", "16", "16", "1", "--seed", "3", "--choice", "frequency",
                "--out", out)
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertEqual(sorted(n for n in os.listdir(out) if not n.startswith(".")),
                         ["labels.vti", "picture.png", "statistics.json"])
        from vtkmodules.vtkIOImage import vtkPNGReader
        png = vtkPNGReader()
        png.SetFileName(os.path.join(out, "picture.png"))
        png.Update()
        self.assertEqual(png.GetOutput().GetDimensions(), (64, 40, 1))
        with open(os.path.join(out, "statistics.json")) as f:
            self.assertEqual(json.load(f)["BlocksFailed"], 0)
        r = run("info", meadow, "--symmetry", "2")
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertIn("16 x 10 pixels, 4 colours", r.stdout)
        self.assertIn("patterns: 33 (3 x 3 windows, 2 symmetries, wrapping)", r.stdout)
        picture = os.path.join(out, "picture.png")
        r = run("check", meadow, picture, "--symmetry", "2", "--translate", "xy", "--ground")
        self.assertEqual(r.returncode, 0, r.stdout + r.stderr)
        self.assertIn("consistent: every 3 x 3 window", r.stdout)
        # The check fails where the picture breaks the sample: not repeating, it wraps wrongly;
        # a sample without the earth has none of these windows.
        r = run("check", data("Samples/Rooms.png"), picture, "--symmetry", "2")
        self.assertEqual(r.returncode, 1)
        self.assertIn("is not in the sample", r.stdout)
        # Bounded, no ground, whole model; the same seed gives the same picture.
        for attempt in (1, 2):
            r = run("synthesize", data("Samples/Rooms.png"), "--size", "30", "20", "1", "--seed", "9",
                    "--out", tmp("cli-rooms%d" % attempt))
            self.assertEqual(r.returncode, 0, r.stderr)
        with open(tmp("cli-rooms1/picture.png"), "rb") as a, open(tmp("cli-rooms2/picture.png"), "rb") as b:
            self.assertEqual(a.read(), b.read())
        self.assertEqual(run("check", data("Samples/Rooms.png"), tmp("cli-rooms1/picture.png")).returncode, 0)
        # Usage: sample options elsewhere, grid options for a sample, --ground's two forms.
        for args, message in (
                ((data("Examples/Village.vti"), "--size", "5", "5", "5", "--pattern", "2"),
                 "--pattern applies to image samples"),
                ((meadow, "--size", "20", "20", "1", "--mirror", "x"), "--mirror applies to label grids"),
                ((meadow, "--size", "20", "20", "1", "--ground", "1"), "--ground takes no LABEL"),
                ((data("Examples/Village.vti"), "--size", "5", "5", "5", "--ground"), "--ground needs a LABEL")):
            r = run("synthesize", *args, "--out", tmp("cli-sample-usage"))
            self.assertEqual(r.returncode, 2, args)
            self.assertIn(message, r.stderr)
        # Bad samples and sizes: one line naming the problem, no output.
        bad = tmp("not-a-picture.png")
        shutil.rmtree(tmp("cli-sample-bad"), ignore_errors=True)
        with open(bad, "wb") as f:
            f.write(b"\x89PNG\r\n\x1a\n" + b"\0" * 20)
        for args in ((bad, "--size", "20", "20", "1"), (meadow, "--size", "2", "20", "1"),
                     (data("Samples/Bricks.png"), "--pattern", "8", "--size", "20", "20", "1")):
            r = run("synthesize", *args, "--out", tmp("cli-sample-bad"))
            # a picture narrower than the pattern is a usage error (exit 2) naming --size
            self.assertEqual(r.returncode, 2 if args[0] == meadow else 1, args)
            if args[0] == meadow:
                self.assertIn("--size 2 20 1: a picture from '%s' is at least 3 x 3 pixels" % meadow,
                              r.stderr)
            self.assertEqual(r.stderr.count("\n"), 1, r.stderr)
            self.assertFalse(os.path.exists(tmp("cli-sample-bad/picture.png")))

    def test_batch(self):
        # A sample list laid out as WaveFunctionCollapse and the original program lay theirs out:
        # samples/NAME.png, tilesets/NAME.xml with tilesets/NAME/, samples/NAME/data.xml with its
        # images beside it, samples/NAME.txt; an older ground index; one missing sample.
        root = tmp("cli-batch-list")
        shutil.rmtree(root, ignore_errors=True)
        os.makedirs(os.path.join(root, "samples"))
        os.makedirs(os.path.join(root, "tilesets"))
        shutil.copy(data("Samples/Meadow.png"), os.path.join(root, "samples", "Flowers.png"))
        shutil.copy(data("Tilesets/Lines.xml"), os.path.join(root, "tilesets", "Pipes.xml"))
        shutil.copytree(data("Tilesets/Lines"), os.path.join(root, "tilesets", "Pipes"))
        shutil.copytree(data("Tilesets/Lines"), os.path.join(root, "samples", "OldPipes"))
        shutil.copy(data("Tilesets/Lines.xml"), os.path.join(root, "samples", "OldPipes", "data.xml"))
        shutil.copy(data("Examples/Village.txt"), os.path.join(root, "samples", "village.txt"))
        with open(os.path.join(root, "samples.xml"), "w") as f:
            f.write("""<samples>
  <overlapping name="Flowers" N="3" symmetry="2" ground="-4" periodic="True" width="40" height="30"/>
  <simpletiled name="Pipes" width="12" height="10" periodic="True" screenshots="1"/>
  <simpletiled name="OldPipes" subset="straight" width="9" height="8" screenshots="1"/>
  <tiledmodel name="village.txt" width="14" length="12" height="5" blockWidth="7" blockLength="6"/>
  <overlapping name="Missing" N="2" screenshots="1"/>
</samples>""")
        out = tmp("cli-batch")
        shutil.rmtree(out, ignore_errors=True)
        r = run("batch", os.path.join(root, "samples.xml"), "--out", out, "--seed", "4")
        self.assertEqual(r.returncode, 1, r.stdout + r.stderr)  # the missing sample
        lines = r.stdout.splitlines()
        kinds = ("overlapping", "simpletiled", "tiledmodel")
        summary = {l.split()[0]: l for l in lines
                   if len(l.split()) > 1 and l.split()[0].isdigit() and l.split()[1] in kinds}
        self.assertEqual(len(summary), 5)
        for entry in ("1", "2", "3", "4"):
            self.assertTrue(summary[entry].endswith(" ok"), summary[entry])
        self.assertIn("2/2", summary["1"])  # two screenshots by default
        self.assertIn("error: '%s/samples/Missing.png': no such file" % root, summary["5"])
        self.assertIn("1 of 5 entries failed", r.stdout)
        for folder in ("1-Flowers/1", "1-Flowers/2", "2-Pipes/1", "3-OldPipes-straight/1", "4-village.txt/1"):
            self.assertTrue(os.path.exists(os.path.join(out, folder, "statistics.json")), folder)
        self.assertTrue(os.path.exists(os.path.join(out, "1-Flowers/1/picture.png")))
        self.assertTrue(os.path.exists(os.path.join(out, "4-village.txt/1/model.txt")))
        self.assertNotIn("replaced", r.stderr)
        # Again into the same folder: one note for the batch, not one per output.
        again = run("batch", os.path.join(root, "samples.xml"), "--out", out, "--seed", "4")
        notes = [l for l in again.stderr.splitlines() if "replaced" in l]
        self.assertEqual(notes, ["msynth: note: this run replaced the earlier outputs in '%s' "
                                 "(1-Flowers/1/, 1-Flowers/2/, 2-Pipes/1/, 3-OldPipes-straight/1/, "
                                 "4-village.txt/1/)" % out], again.stderr)
        # Each output is checked independently: the pictures against the sample's windows.
        r = run("check", os.path.join(root, "samples", "Flowers.png"), os.path.join(out, "1-Flowers/2/picture.png"),
                "--symmetry", "2", "--translate", "xy", "--ground")
        self.assertEqual(r.returncode, 0, r.stdout)
        # The bundled list runs as it is.
        r = run("batch", data("samples.xml"), "--out", tmp("cli-batch-bundled"))
        self.assertEqual(r.returncode, 0, r.stdout + r.stderr)
        self.assertIn("all 8 entries succeeded", r.stdout)
        # A malformed list: one line naming it and the line, exit 1.
        bad = os.path.join(root, "bad.xml")
        with open(bad, "w") as f:
            f.write("<samples>\n<overlapping name=\"a\" N=\"12\"/></samples>")
        r = run("batch", bad, "--out", tmp("cli-batch-bad"))
        self.assertEqual(r.returncode, 1)
        self.assertEqual(r.stderr.count("\n"), 1, r.stderr)
        self.assertIn("bad.xml', line 2: N=\"12\"", r.stderr)

    def test_tileset(self):
        tiles = data("Tilesets/Lines.xml")
        r = run("info", tiles)
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertIn("labels: 7", r.stdout)
        self.assertIn("label 6: corner 3", r.stdout)
        out = tmp("cli-tiles")
        shutil.rmtree(out, ignore_errors=True)
        r = run("synthesize", tiles, "--size", "20", "14", "1", "--seed", "5", "--order", "entropy",
                "--choice", "frequency", "--out", out)
        self.assertEqual(r.returncode, 0, r.stderr)
        from vtkmodules.vtkIOImage import vtkPNGReader
        png = vtkPNGReader()
        png.SetFileName(os.path.join(out, "picture.png"))
        png.Update()
        self.assertEqual(png.GetOutput().GetDimensions(), (160, 112, 1))  # 8-pixel tiles
        # A 2D tileset needs no voxel mesh or volume by default; --outputs chooses.
        self.assertEqual(sorted(n for n in os.listdir(out) if not n.startswith(".")),
                         ["labels.vti", "picture.png", "statistics.json"])
        r = run("synthesize", tiles, "--size", "6", "5", "1", "--outputs", "labels,mesh,vdb,vox", "--out", out)
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertEqual(sorted(n for n in os.listdir(out) if not n.startswith(".")),
                         ["labels.vti", "mesh.vtp", "model.vdb", "model.vox", "statistics.json"])
        self.assertIn("wrote %s/labels.vti, %s/model.vox, %s/mesh.vtp" % (out, out, out), r.stdout)
        r = run("synthesize", data("Examples/Village.vti"), "--size", "6", "5", "5", "--outputs", "picture",
                "--out", tmp("cli-no-picture"))
        self.assertEqual(r.returncode, 1)
        self.assertIn("pictures are made of a tileset's images or an image sample's pixels", r.stderr)
        r = run("synthesize", tiles, "--size", "6", "5", "1", "--outputs", "labels,gif", "--out", out)
        self.assertEqual(r.returncode, 2)
        self.assertIn("--outputs: unknown kind 'gif'", r.stderr)
        r = run("check", tiles, os.path.join(out, "labels.vti"))
        self.assertEqual(r.returncode, 0, r.stdout + r.stderr)
        # Subsets: only empty and straight lines (labels 0-2).
        r = run("synthesize", tiles, "--size", "12", "12", "1", "--subset", "straight", "--out", out)
        self.assertEqual(r.returncode, 0, r.stderr)
        reader = modelsynth.vtkMSLabelGridReader()
        reader.SetFileName(os.path.join(out, "labels.vti"))
        reader.Update()
        self.assertLessEqual(int(labels_zyx(reader.GetOutput()).max()), 2)
        self.assertEqual(run("check", tiles, os.path.join(out, "labels.vti"), "--subset", "straight").returncode, 0)

    def test_symmetry_options(self):
        example = data("Examples/Village.vti")
        ex = modelsynth.vtkMSLabelGridReader()
        ex.SetFileName(example)
        ex.Update()
        for name, options, check in (
                ("tile", ("--translate", "xy", "--ground", "1", "--empty", "0"),
                 lambda m: violations(labels_zyx(ex.GetOutput()), np.tile(m, (1, 2, 2))) == []),
                ("period", ("--translate", "x", "--period", "5", "0", "0"),
                 lambda m: (m[:, :, 5:] == m[:, :, :-5]).all()),
                ("rotate", ("--rotate", "--ground", "1", "--empty", "0"),
                 lambda m: (m.transpose(0, 2, 1)[:, ::-1, :] == m).all())):
            out = tmp("cli-sym-" + name)
            shutil.rmtree(out, ignore_errors=True)
            r = run("synthesize", example, "--size", "16", "16", "5", "--block", "8", "8", "5",
                    "--seed", "4", "--out", out, *options)
            self.assertEqual(r.returncode, 0, r.stderr)
            reader = modelsynth.vtkMSLabelGridReader()
            reader.SetFileName(os.path.join(out, "labels.vti"))
            reader.Update()
            model = labels_zyx(reader.GetOutput())
            self.assertEqual(violations(labels_zyx(ex.GetOutput()), model), [], name)
            self.assertTrue(check(model), name)
            self.assertEqual(run("check", example, os.path.join(out, "labels.vti")).returncode, 0)
        r = run("synthesize", example, "--size", "16", "12", "5", "--rotate", "--out", tmp("cli-sym-bad"))
        self.assertEqual(r.returncode, 1)
        self.assertIn("square", r.stderr)
        self.assertEqual(run("synthesize", example, "--size", "8", "8", "5", "--period", "1", "x", "0").returncode, 2)
        self.assertEqual(run("synthesize", example, "--size", "8", "8", "5", "--translate", "w").returncode, 2)

    def test_animate(self):
        # The rolling ball of Fig. 3.27: one image whose z slices are frames, or one file per frame.
        from vtkmodules.vtkCommonCore import vtkIntArray
        from vtkmodules.vtkCommonDataModel import vtkImageData
        from vtkmodules.vtkIOXML import vtkXMLImageDataWriter

        def write(path, frames):
            image = vtkImageData()
            image.SetDimensions(6, 1, len(frames))
            labels = vtkIntArray()
            labels.SetName("Label")
            for row in frames:
                for v in row:
                    labels.InsertNextValue(int(v))
            image.GetPointData().SetScalars(labels)
            writer = vtkXMLImageDataWriter()
            writer.SetInputData(image)
            writer.SetFileName(path)
            writer.Write()

        ball = [[1 if x == t else (2 if x == t - 1 else 0) for x in range(6)] for t in range(8)]
        allowed = {(0, r[x], r[x + 1]) for r in ball for x in range(5)}
        allowed |= {(1, ball[t][x], ball[t + 1][x]) for t in range(7) for x in range(6)}
        write(tmp("ball.vti"), ball)
        singles = []
        for t, row in enumerate(ball):
            singles.append(tmp("ball-frame-%d.vti" % t))
            write(singles[-1], [row])
        for name, examples, extra in (("z", [tmp("ball.vti")], ["--loop"]),
                                      ("files", singles, ["--block", "6", "1", "1", "--block-frames", "5"])):
            out = tmp("cli-animate-" + name)
            shutil.rmtree(out, ignore_errors=True)
            r = run("animate", *examples, "--size", "16", "1", "1", "--frames", "12", "--seed", "3",
                    "--out", out, *extra)
            self.assertEqual(r.returncode, 0, r.stderr)
            self.assertIn("consistent", r.stdout)
            # the summary names the first and last frames and volumes, with the same numbers
            self.assertIn("%s/frame_0001.vti ... frame_0012.vti, %s/model_0001.vdb ... model_0012.vdb"
                          % (out, out), r.stdout)
            movie = []
            for t in range(12):
                reader = modelsynth.vtkMSLabelGridReader()
                reader.SetFileName(os.path.join(out, "frame_%04d.vti" % (t + 1)))
                reader.Update()
                movie.append(labels_zyx(reader.GetOutput())[0, 0].tolist())
                self.assertTrue(os.path.isfile(os.path.join(out, "model_%04d.vdb" % (t + 1))))
            if name == "z":
                movie_wrapped = movie + movie[:1]
            else:
                movie_wrapped = movie
            seen = {(0, r[x], r[x + 1]) for r in movie for x in range(15)}
            seen |= {(1, movie_wrapped[t][x], movie_wrapped[t + 1][x])
                     for t in range(len(movie_wrapped) - 1) for x in range(16)}
            self.assertEqual(seen - allowed, set(), name)
            with open(os.path.join(out, "statistics.json")) as f:
                self.assertEqual(json.load(f)["exampleFrames"], 8)
        self.assertEqual(run("animate", tmp("ball.vti"), "--size", "4", "1", "1").returncode, 2)  # no --frames
        for bad in (data("Malformed/truncated.vti"), data("Continuous/cube.obj")):  # one line naming it
            r = run("animate", bad, "--size", "4", "1", "1", "--frames", "2", "--out", tmp("cli-animate-bad"))
            self.assertEqual(r.returncode, 1)
            self.assertEqual(r.stderr.count("\n"), 1, r.stderr)
            self.assertIn(bad, r.stderr)
        r = run("animate", tmp("ball.vti"), singles[0], "--size", "4", "1", "1", "--frames", "3")
        self.assertEqual(r.returncode, 1)  # frames of different sizes
        self.assertIn("frame 1", r.stderr)

    def test_animate_refuses_what_does_not_fit_before_allocating(self):
        # A million frames of 288 sites once ran 11 s to 3.4 GB before "out of memory" under a
        # 4 GB cap (and 160 s to 9 GB without one): the estimate comes first.
        cases = [(("16", "12", "6"), None)]  # 46 GB: more than any machine of ours
        if not os.environ.get("MSYNTH_SANITIZED"):  # the sanitizers reserve address space
            cases.append((("8", "6", "6"), 4 << 30))
        for size, cap in cases:
            out = tmp("cli-animate-huge")
            start = time.monotonic()
            r = subprocess.run([MSYNTH, "animate", data("Examples/Village.vox"), "--size", *size,
                                "--frames", "1000000", "--out", out], capture_output=True, text=True,
                               timeout=TIMEOUT, preexec_fn=(lambda: resource.setrlimit(
                                   resource.RLIMIT_AS, (cap, cap))) if cap else None)
            self.assertLess(time.monotonic() - start, 5, size)
            self.assertEqual(r.returncode, 1, r.stderr)
            self.assertIn("a %s x %s x %s model of 1000000 frames needs about" % size, r.stderr)
            self.assertEqual(r.stderr.count("\n"), 1, r.stderr)
            self.assertFalse(os.path.exists(out))

    def test_pattern_and_quality(self):
        """msynth pattern on the bundled city with fixed crossroads, then msynth quality; every
        sample's pairs are checked here against the exemplars with numpy."""
        out = tmp("cli-pattern")
        shutil.rmtree(out, ignore_errors=True)
        exemplars = [data("Patterns/city-suburban.vti"), data("Patterns/city-urban.vti")]
        r = run("pattern", *exemplars, "--size", "40", "30", "--factors", "2H,2V,3x3", "--samples", "2",
                "--burn-in", "1", "--seed", "4", "--tileset", data("Patterns/City.xml"), "--out", out)
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertIn("KL 3x3", r.stdout)
        for name in ("labels.vti", "labels_0001.vti", "labels_0002.vti", "picture.png", "statistics.json"):
            self.assertTrue(os.path.isfile(os.path.join(out, name)), name)
        with open(os.path.join(out, "statistics.json")) as f:
            stats = json.load(f)
        self.assertEqual(len(stats["samples"]), 2)
        self.assertGreaterEqual(stats["KL_3x3"], 0.0)
        allowed = set()
        for e in exemplars:
            allowed |= set(violations_free_pairs(e))
        for name in ("labels_0001.vti", "labels_0002.vti"):
            self.assertLessEqual(set(violations_free_pairs(os.path.join(out, name))), allowed, name)
        # The same inputs and seed give byte-identical labels (no timings in the file).
        again = tmp("cli-pattern-again")
        shutil.rmtree(again, ignore_errors=True)
        r = run("pattern", *exemplars, "--size", "40", "30", "--factors", "2H,2V,3x3", "--samples", "2",
                "--burn-in", "1", "--seed", "4", "--out", again)
        self.assertEqual(r.returncode, 0, r.stderr)
        for name in ("labels.vti", "labels_0001.vti"):
            with open(os.path.join(out, name), "rb") as a, open(os.path.join(again, name), "rb") as b:
                self.assertEqual(a.read(), b.read(), name)
        # The 170 x 170 city with crossroads fixed every 20 tiles (Yeh et al. §8.2).
        big = tmp("cli-pattern-170")
        shutil.rmtree(big, ignore_errors=True)
        r = run("pattern", *exemplars, "--size", "170", "170", "--fixed", data("Patterns/city-crossroads-170.vti"),
                "--burn-in", "0", "--seed", "1", "--out", big)
        self.assertEqual(r.returncode, 0, r.stderr)
        city = labels_of(os.path.join(big, "labels.vti"))
        self.assertTrue((city[10::20, 10::20] == 3).all(), "crossroads stay fixed")
        self.assertLessEqual(set(violations_free_pairs(os.path.join(big, "labels.vti"))), allowed)
        # quality: any model against the exemplars; a model with a seam exits 1.
        r = run("quality", *exemplars, os.path.join(out, "labels.vti"), "--factors", "3x3,4H")
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertIn("KL 3x3:", r.stdout)
        self.assertIn("every pair of neighbours occurs in an exemplar", r.stdout)
        r = run("quality", *exemplars, data("Patterns/facade-rectangular.vti"))
        self.assertEqual(r.returncode, 1)
        self.assertIn("seam:", r.stdout)
        # A tileset alone: its neighbor rules are the hard pairs; msynth check verifies them.
        lines = tmp("cli-pattern-lines")
        shutil.rmtree(lines, ignore_errors=True)
        r = run("pattern", data("Tilesets/Lines.xml"), "--size", "24", "16", "--seed", "2", "--out", lines)
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertIn("or the tileset's rules", r.stdout)
        self.assertTrue(os.path.isfile(os.path.join(lines, "picture.png")))
        r = run("check", data("Tilesets/Lines.xml"), os.path.join(lines, "labels.vti"))
        self.assertEqual(r.returncode, 0, r.stdout + r.stderr)
        # One-line errors.
        for args, message in ((("--size", "10", "10", "--factors", "2H,5Q"), "5Q"),
                              (("--size", "10", "10", "--zone-tiles", "1:99"), "99"),
                              (("--size", "10", "10", "10"), "3D"),
                              (("--size", "40000", "40000"), "memory available")):
            r = run("pattern", *exemplars, *args, "--out", tmp("cli-pattern-bad"))
            self.assertNotEqual(r.returncode, 0, args)
            self.assertIn(message, r.stderr)
            self.assertEqual(len(r.stderr.strip().splitlines()), 1, r.stderr)
        r = run("pattern", *exemplars, "--size", "10", "10", "--fixed", data("Patterns/city-crossroads-170.vti"),
                "--out", tmp("cli-pattern-bad"))
        self.assertNotEqual(r.returncode, 0)
        self.assertIn("the output 10 x 10 x 1", r.stderr)

    def test_up_axis_of_a_blender_export(self):
        # Blender's default OBJ export is y up: --up y reads it as the z-up house.obj, in every
        # command that reads a polyhedral example.
        blender, house = data("Continuous/house-blender.obj"), data("Continuous/house.obj")
        turned, original = run("info", blender, "--up", "y"), run("info", house)
        self.assertEqual(turned.returncode, 0, turned.stderr)
        self.assertEqual(turned.stdout, original.stdout)
        self.assertNotEqual(run("info", blender).stdout, original.stdout)
        out = os.path.join(tmp("cli"), "blender-house")
        shutil.rmtree(out, ignore_errors=True)
        r = run("synthesize", blender, "--up", "y", "--size", "12", "12", "6", "--grounded",
                "--thickness", "Wall:z", "--seed", "3", "--out", out)
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertIn("on the ground", r.stdout)
        model = os.path.join(out, "model.vtp")
        self.assertEqual(run("check", blender, model, "--up", "y").returncode, 0)
        self.assertEqual(run("check", blender, model).returncode, 1)  # read lying down: not its model
        bad = run("info", blender, "--up", "x")
        self.assertEqual(bad.returncode, 2)
        self.assertIn("--up", bad.stderr)

    def test_progress_names_each_stage_on_a_terminal(self):
        # stderr on a terminal (a pty): the bar names the stage it is in; piped, no bar.
        import pty
        out = os.path.join(tmp("cli"), "progress")
        shutil.rmtree(out, ignore_errors=True)
        controller, terminal = pty.openpty()
        proc = subprocess.Popen([MSYNTH, "synthesize", data("Examples/Village.vti"), "--size", "40", "40", "5",
                                 "--block", "10", "10", "5", "--seed", "3", "--out", out],
                                stdout=subprocess.DEVNULL, stderr=terminal)
        os.close(terminal)
        shown = b""
        while True:
            try:
                chunk = os.read(controller, 4096)
            except OSError:
                break
            if not chunk:
                break
            shown += chunk
        proc.wait(timeout=120)
        os.close(controller)
        self.assertEqual(proc.returncode, 0)
        text = shown.decode()
        for stage in ("synthesis [", "mesh [", "model.vdb ["):
            self.assertIn(stage, text)
        self.assertIn("100%", text)
        piped = run("synthesize", data("Examples/Village.vti"), "--size", "8", "8", "3", "--out", out + "-piped")
        self.assertEqual(piped.returncode, 0, piped.stderr)
        self.assertNotIn("[", piped.stderr)

    def test_synthesize_errors(self):
        # No label of a checkerboard tiles space: its blocks start undecided by default (issue
        # 44), and the trivial start, asked for, says why it cannot be.
        ok = run("synthesize", data("Examples/Checkerboard.vti"), "--size", "9", "9", "1",
                 "--block", "3", "3", "1", "--out", tmp("cli-undecided"))
        self.assertEqual(ok.returncode, 0, ok.stderr)
        failed = fresh_folder("cli-fail-trivial")
        r = run("synthesize", data("Examples/Checkerboard.vti"), "--size", "9", "9", "1",
                "--block", "3", "3", "1", "--start", "trivial", "--out", failed)
        self.assertEqual(r.returncode, 1)
        self.assertIn("no usable trivial start", r.stderr)
        self.assertFalse(os.path.exists(os.path.join(failed, "labels.vti")))
        self.assertEqual(run("synthesize", data("Examples/Village.vti")).returncode, 2)  # no --size
        self.assertEqual(run("synthesize", data("Examples/Village.vti"), "--size", "4", "x", "4").returncode, 2)
        self.assertEqual(run("synthesize", data("Examples/Village.vti"), "--size", "0", "4", "4").returncode, 2)
        self.assertEqual(run("synthesize", data("Examples/Village.vti"), "--size", "4", "4", "4",
                             "--order", "sideways").returncode, 2)
        self.assertEqual(run("check", data("Examples/Village.vti")).returncode, 2)

    def test_usage_errors(self):
        self.assertEqual(run().returncode, 2)
        self.assertEqual(run("bogus").returncode, 2)
        self.assertEqual(run("info").returncode, 2)
        self.assertEqual(run("analyze", "x.vti", "--out").returncode, 2)
        self.assertEqual(run("--help").returncode, 0)
        # Each command has its own options: one line ending with where to read them.
        village = data("Examples/Village.vti")
        for args, words in ((("check", village, village, "--mirror", "xy"), "--mirror"),
                            (("synthesize", village, "--size", "4", "4", "4", "--spacing", "2"),
                             "--spacing applies to polyhedral examples"),
                            (("synthesize", data("Continuous/cube.obj"), "--size", "4", "4", "4",
                              "--block", "2", "2", "2"), "--block applies to label grids"),
                            (("synthesize", village, "--size", "4.5", "4", "4"), "in sites"),
                            (("synthesize", village, "--size", "4", "4", "4", "--swap", "1-2"),
                             "is not LABEL:LABEL"),
                            (("animate", village, "--size", "4", "4", "1", "--frames", "2",
                              "--order", "entropy"), "--order"),
                            (("info",), "EXAMPLE is required")):
            r = run(*args)
            self.assertEqual(r.returncode, 2, args)
            self.assertEqual(r.stderr.count("\n"), 1, r.stderr)
            self.assertIn(words, r.stderr)
            self.assertTrue(r.stderr.rstrip().endswith("see msynth %s --help" % args[0]), r.stderr)
        r = run("synthesize", "--help")
        self.assertEqual(r.returncode, 0)
        self.assertIn("--mirror", r.stdout)
        self.assertIn("--spacing", r.stdout)
        self.assertNotIn("--frames", r.stdout)
        r = run("animate", "--help")
        self.assertIn("--frames", r.stdout)
        self.assertNotIn("--mirror", r.stdout)
        r = run("--version")
        self.assertEqual(r.returncode, 0)
        self.assertTrue(r.stdout.startswith("msynth "), r.stdout)


if __name__ == "__main__":
    unittest.main()
