"""Streamed worlds (issue: worlds, §2): `msynth synthesize --stream` computes the world slab by
slab in bounded memory. The slabs (labels.pvti over labels/, read by VTK's own pieces reader)
equal a whole run of the same world, pass the independent check (pairs recomputed from the
example here, `msynth check` piece by piece), and an interrupted stream resumes: finished slabs
are kept, a damaged one is computed again, and a stream of another world is refused."""
import json
import os
import signal
import subprocess
import time
import unittest

import numpy as np
from vtkmodules.vtkIOXML import vtkXMLImageDataReader, vtkXMLPImageDataReader

from msynth_testing import BIN, data, fresh_folder, labels_zyx, read_png, violations
from msynth_testing import read_label_grid as read
from msynth_testing import run_msynth as msynth


MSYNTH = os.path.join(BIN, "msynth")


def text(path):
    with open(path) as f:
        return f.read()


def write(path, content, mode="w"):
    with open(path, mode) as f:
        f.write(content)


def png_rgb(path):
    return read_png(path)[:, :, :3].astype(float)


def read_slab(path):
    reader = vtkXMLImageDataReader()
    reader.SetFileName(path)
    reader.Update()
    return reader.GetOutput()


def read_pieces(path):
    reader = vtkXMLPImageDataReader()
    reader.SetFileName(path)
    reader.Update()
    return reader.GetOutput()


class StreamTest(unittest.TestCase):
    def test_label_grid_stream_equals_the_whole_run(self):
        village = data("Examples/Village.vti")
        common = ["--size", "60", "140", "5", "--block", "12", "12", "5", "--seed", "5"]
        whole = fresh_folder("stream-whole")
        done = msynth("synthesize", village, *common, "--outputs", "labels", "--out", whole)
        self.assertEqual(done.returncode, 0, done.stderr)
        out = fresh_folder("stream-village")
        done = msynth("synthesize", village, *common, "--stream", "--slab", "30", "--out", out)
        self.assertEqual(done.returncode, 0, done.stderr)
        self.assertIn("streamed in 5 slabs along y", done.stdout)
        streamed = read_pieces(os.path.join(out, "labels.pvti"))
        self.assertEqual(streamed.GetDimensions(), (60, 140, 5))
        labels = labels_zyx(streamed)
        np.testing.assert_array_equal(labels, labels_zyx(read(os.path.join(whole, "labels.vti"))))
        self.assertEqual(violations(labels_zyx(read(village)), labels), [])
        self.assertGreaterEqual(len(np.unique(labels)), 3)  # not a blank world (4 labels in all)
        self.assertEqual(sorted(os.listdir(os.path.join(out, "vdb"))),
                         ["model_%05d.vdb" % j for j in range(5)])
        stats = json.loads(text(os.path.join(out, "statistics.json")))
        self.assertEqual(stats["Slabs"], 5)
        self.assertEqual(stats["SlabsResumed"], 0)
        self.assertFalse(os.path.exists(os.path.join(out, ".msynth-stream")))
        check = msynth("check", village, os.path.join(out, "labels.pvti"))
        self.assertEqual(check.returncode, 0, check.stdout + check.stderr)
        self.assertIn("5 pieces", check.stdout)

    def test_the_overview_picture_looks_like_the_whole_picture(self):
        lines = data("Tilesets/Lines.xml")
        common = ["--size", "600", "600", "1", "--block", "32", "32", "1", "--seed", "3"]
        whole = fresh_folder("stream-picture-whole")
        done = msynth("synthesize", lines, *common, "--out", whole)
        self.assertEqual(done.returncode, 0, done.stderr)
        out = fresh_folder("stream-picture")
        done = msynth("synthesize", lines, *common, "--stream", "--slab", "100", "--out", out)
        self.assertEqual(done.returncode, 0, done.stderr)
        self.assertEqual(len(os.listdir(os.path.join(out, "picture"))), 6)
        full, overview = (png_rgb(os.path.join(folder, "picture.png")) for folder in (whole, out))
        self.assertLessEqual(max(overview.shape), 2048)
        self.assertGreater(full.shape[0], overview.shape[0])  # downsampled
        # Each overview pixel is the mean of the pixels it stands for: the same mean colour, and
        # the lines still show (not one colour everywhere).
        np.testing.assert_allclose(overview.mean(axis=(0, 1)), full.mean(axis=(0, 1)), atol=2.0)
        self.assertGreater(overview.std(axis=(0, 1)).max(), 0.5 * full.std(axis=(0, 1)).max() / 4)
        self.assertGreater(len(np.unique(overview.reshape(-1, 3), axis=0)), 2)

    def test_check_finds_a_wrong_piece_and_a_broken_seam(self):
        lines = data("Tilesets/Lines.xml")
        out = fresh_folder("stream-check")
        done = msynth("synthesize", lines, "--size", "40", "90", "1", "--block", "16", "16", "1",
                      "--stream", "--slab", "30", "--seed", "2", "--outputs", "labels", "--out", out)
        self.assertEqual(done.returncode, 0, done.stderr)
        pvti = os.path.join(out, "labels.pvti")
        self.assertEqual(msynth("check", lines, pvti).returncode, 0)
        # Piece 1 replaced by piece 2 (same size, other labels): its seams no longer match.
        pieces = text(pvti)
        wrong = os.path.join(out, "wrong.pvti")
        write(wrong, pieces.replace('Source="labels/labels_00001.vti"',
                                            'Source="labels/labels_00002.vti"', 1))
        check = msynth("check", lines, wrong)
        self.assertEqual(check.returncode, 1, check.stdout + check.stderr)
        self.assertIn("does not share piece", check.stdout)
        # A gap between the pieces is refused in one line.
        gap = os.path.join(out, "gap.pvti")
        write(gap, pieces.replace('Extent="0 39 29 59', 'Extent="0 39 31 59', 1))
        check = msynth("check", lines, gap)
        self.assertNotEqual(check.returncode, 0)
        self.assertIn("does not continue the slabs", check.stderr)

    def test_an_interrupted_stream_resumes(self):
        lines = data("Tilesets/Lines.xml")
        common = ["--size", "400", "2400", "1", "--block", "32", "32", "1", "--seed", "8",
                  "--stream", "--slab", "100", "--threads", "1"]
        out = fresh_folder("stream-resume")
        stream = os.path.join(out, ".msynth-stream")
        run = subprocess.Popen([MSYNTH, "synthesize", lines, *common, "--out", out],
                               stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        listed = os.path.join(stream, "slabs.txt")
        deadline = time.monotonic() + 60
        while time.monotonic() < deadline and run.poll() is None:
            if os.path.exists(listed) and len(text(listed).splitlines()) >= 4:
                break
            time.sleep(0.02)
        self.assertIsNone(run.poll(), "the stream ended before it could be interrupted")
        run.send_signal(signal.SIGKILL)
        run.wait()
        kept = text(listed).splitlines()
        self.assertGreaterEqual(len(kept), 4)
        self.assertFalse(os.path.exists(os.path.join(out, "labels.pvti")))  # nothing published
        # Damage slab 2: it and the slabs after it are computed again.
        piece = os.path.join(stream, "labels", "labels_00002.vti")
        with open(piece, "rb") as f:
            raw = bytearray(f.read())
        raw[len(raw) // 2] ^= 0xFF
        write(piece, bytes(raw), "wb")
        done = msynth("synthesize", lines, *common, "--resume", "--out", out)
        self.assertEqual(done.returncode, 0, done.stderr)
        self.assertIn("slab 2 of the stream cannot be kept ('labels/labels_00002.vti' is missing "
                      "or damaged)", done.stderr)
        stats = json.loads(text(os.path.join(out, "statistics.json")))
        self.assertEqual(stats["SlabsResumed"], 2)
        slabs = len(os.listdir(os.path.join(out, "labels")))  # the world's slabs, counted here
        self.assertEqual(stats["Slabs"], slabs)
        self.assertIn("(streamed in %d slabs along y: 2 kept from the earlier run, %d computed now)"
                      % (slabs, slabs - 2), done.stdout)
        self.assertIn("sites in %d slabs, " % slabs, done.stdout)
        fresh = fresh_folder("stream-fresh")
        done = msynth("synthesize", lines, *common, "--out", fresh)
        self.assertEqual(done.returncode, 0, done.stderr)
        np.testing.assert_array_equal(
            labels_zyx(read_pieces(os.path.join(out, "labels.pvti"))),
            labels_zyx(read_pieces(os.path.join(fresh, "labels.pvti"))))
        self.assertEqual(msynth("check", lines, os.path.join(out, "labels.pvti")).returncode, 0)
        # A stream of another world is not resumed.
        again = fresh_folder("stream-other")
        run = subprocess.Popen([MSYNTH, "synthesize", lines, *common, "--out", again],
                               stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        listed = os.path.join(again, ".msynth-stream", "slabs.txt")
        while run.poll() is None and not (os.path.exists(listed) and text(listed)):
            time.sleep(0.02)
        run.send_signal(signal.SIGKILL)
        run.wait()
        other = [c if c != "8" else "9" for c in common]
        done = msynth("synthesize", lines, *other, "--resume", "--out", again)
        self.assertNotEqual(done.returncode, 0)
        self.assertIn("holds a stream of another world", done.stderr)
        self.assertEqual(len(done.stderr.strip().splitlines()), 1, done.stderr)

    def fresh_world(self, name, common):
        """An uninterrupted stream of Lines.xml: its folder and its labels."""
        fresh = fresh_folder(name)
        done = msynth("synthesize", data("Tilesets/Lines.xml"), *common, "--out", fresh)
        self.assertEqual(done.returncode, 0, done.stderr)
        return fresh, labels_zyx(read_pieces(os.path.join(fresh, "labels.pvti")))

    def interrupted(self, name, common, slabs=3):
        """A stream of Lines.xml killed after `slabs` slabs; its output folder."""
        out = fresh_folder(name)
        listed = os.path.join(out, ".msynth-stream", "slabs.txt")
        run = subprocess.Popen([MSYNTH, "synthesize", data("Tilesets/Lines.xml"), *common,
                                "--out", out], stdout=subprocess.DEVNULL,
                               stderr=subprocess.DEVNULL)
        deadline = time.monotonic() + 60
        while time.monotonic() < deadline and run.poll() is None:
            if os.path.exists(listed) and len(text(listed).splitlines()) >= slabs:
                break
            time.sleep(0.01)
        self.assertIsNone(run.poll(), "the stream ended before it could be interrupted")
        run.send_signal(signal.SIGKILL)
        run.wait()
        return out

    def test_a_resumed_stream_keeps_only_what_it_can_trust(self):
        """Issue 48, item 7: a slab whose listed extent was damaged, the temporary file of the
        slab being written, slabs written with other --outputs, and a stream killed after its
        last slab (before publishing)."""
        lines = data("Tilesets/Lines.xml")
        common = ["--size", "200", "1200", "1", "--block", "32", "32", "1", "--seed", "8",
                  "--stream", "--slab", "100", "--threads", "1", "--outputs", "labels"]
        fresh, expected = self.fresh_world("stream-trust-fresh", common)
        count = len(os.listdir(os.path.join(fresh, "labels")))

        # A damaged extent (the slab's file and checksum intact) and a stray temporary file.
        out = self.interrupted("stream-trust-extent", common)
        stream = os.path.join(out, ".msynth-stream")
        listed = text(os.path.join(stream, "slabs.txt")).splitlines()
        listed[1] = listed[1].replace("extent=0,199,", "extent=0,198,")
        write(os.path.join(stream, "slabs.txt"), "\n".join(listed) + "\n")
        write(os.path.join(stream, "labels", "labels_00003.vti.tmp-99999-7"), "partial")
        done = msynth("synthesize", lines, *common, "--resume", "--out", out)
        self.assertEqual(done.returncode, 0, done.stderr)
        self.assertIn("slab 1 of the stream cannot be kept (its extent is not its labels' extent)",
                      done.stderr)
        self.assertEqual(sorted(os.listdir(os.path.join(out, "labels"))),
                         sorted(os.listdir(os.path.join(fresh, "labels"))))
        np.testing.assert_array_equal(
            labels_zyx(read_pieces(os.path.join(out, "labels.pvti"))), expected)
        self.assertEqual(msynth("check", lines, os.path.join(out, "labels.pvti")).returncode, 0)

        # More --outputs on --resume: the slabs without pictures are computed again.
        out = self.interrupted("stream-trust-outputs", common)
        more = common[:-1] + ["labels,picture"]
        done = msynth("synthesize", lines, *more, "--resume", "--out", out)
        self.assertEqual(done.returncode, 0, done.stderr)
        self.assertIn("slab 0 of the stream cannot be kept (it was written with other --outputs)",
                      done.stderr)
        self.assertEqual(len(os.listdir(os.path.join(out, "picture"))), count)
        self.assertTrue(os.path.exists(os.path.join(out, "picture.png")))

        # Killed after the last slab, before publishing: every slab is listed; resuming publishes.
        out = self.interrupted("stream-trust-all", common)
        stream = os.path.join(out, ".msynth-stream")
        rows = []
        for j in range(count):
            name = "labels/labels_%05d.vti" % j
            with open(os.path.join(fresh, name), "rb") as f:
                raw = f.read()
            write(os.path.join(stream, name), raw, "wb")
            digest = 1469598103934665603
            for byte in raw:
                digest = ((digest ^ byte) * 1099511628211) & 0xFFFFFFFFFFFFFFFF
            low, high = 0 if j == 0 else 100 * j - 1, min(100 * j + 99, 1199)
            rows.append("%d extent=0,199,%d,%d,0,0 %s=%d:%016x"
                        % (j, low, high, name, len(raw), digest))
        write(os.path.join(stream, "slabs.txt"), "\n".join(rows) + "\n")
        done = msynth("synthesize", lines, *common, "--resume", "--out", out)
        self.assertEqual(done.returncode, 0, done.stderr)
        self.assertIn("all kept from the earlier run", done.stdout)
        np.testing.assert_array_equal(
            labels_zyx(read_pieces(os.path.join(out, "labels.pvti"))), expected)

    def test_a_resumed_stream_reports_the_worlds_failures(self):
        """Issue 48, item 7: a resumed stream reported blocks failed that the uninterrupted run
        repaired (it reruns first passes below its first slab, not their repairs). Each slab's
        field data lists the failed blocks that start in it, slabs.txt keeps them, and the
        resumed run reports the world's failures, as the uninterrupted run does."""
        lines = data("Tilesets/Lines.xml")
        # (a quarter of the world under the sanitizers: 8 failed blocks, and minutes, not ten)
        size = ["200", "2400"] if os.environ.get("MSYNTH_SANITIZED") else ["400", "4800"]
        common = ["--size", *size, "1", "--block", "6", "6", "1", "--attempts", "1",
                  "--backtracks", "0", "--seed", "11", "--stream", "--slab", "100",
                  "--threads", "1", "--outputs", "labels"]
        fresh, expected = self.fresh_world("stream-failures-fresh", common)
        out = self.interrupted("stream-failures", common, slabs=5)
        done = msynth("synthesize", lines, *common, "--resume", "--out", out)
        self.assertEqual(done.returncode, 0, done.stderr)
        np.testing.assert_array_equal(
            labels_zyx(read_pieces(os.path.join(out, "labels.pvti"))), expected)

        def failed(folder):
            """The failed blocks the slabs of `folder` list, each (origin, emptied site)."""
            listed = []
            for name in sorted(os.listdir(os.path.join(folder, "labels"))):
                fields = read_slab(os.path.join(folder, "labels", name)).GetFieldData()
                origins, sites = (fields.GetArray(n) for n in
                                  ("FailedBlockOrigins", "FailedBlockSites"))
                for i in range(origins.GetNumberOfTuples()):
                    listed.append(origins.GetTuple3(i) + sites.GetTuple3(i))
            return sorted(listed)

        stats = json.loads(text(os.path.join(fresh, "statistics.json")))
        resumed = json.loads(text(os.path.join(out, "statistics.json")))
        self.assertGreater(stats["BlocksFailed"], 0, "the world checks too little")
        self.assertGreater(resumed["SlabsResumed"], 0)
        self.assertEqual(resumed["BlocksFailed"], stats["BlocksFailed"])
        self.assertEqual(failed(out), failed(fresh))
        self.assertEqual(len(failed(fresh)), stats["BlocksFailed"])
        for origin in failed(fresh):  # in world coordinates (they were a window's once)
            self.assertTrue(0 <= origin[0] < int(size[0]) and 0 <= origin[1] < int(size[1]), origin)

    def test_an_interrupted_stream_says_how_to_go_on(self):
        """Ctrl-C during a stream: the one line names the kept slabs and --resume (issue 49)."""
        common = ["--size", "400", "2400", "1", "--block", "32", "32", "1", "--seed", "8",
                  "--stream", "--slab", "100", "--threads", "1", "--outputs", "labels"]
        out = fresh_folder("stream-sigint")
        listed = os.path.join(out, ".msynth-stream", "slabs.txt")
        run = subprocess.Popen([MSYNTH, "synthesize", data("Tilesets/Lines.xml"), *common,
                                "--out", out], stdout=subprocess.DEVNULL, stderr=subprocess.PIPE,
                               text=True)
        deadline = time.monotonic() + 60
        while time.monotonic() < deadline and run.poll() is None:
            if os.path.exists(listed) and text(listed):
                break
            time.sleep(0.01)
        run.send_signal(signal.SIGINT)
        _, stderr = run.communicate(timeout=60)
        self.assertEqual(run.returncode, 128 + signal.SIGINT, stderr)
        finished = len(text(listed).splitlines())  # what is on disk, as the line says
        self.assertGreater(finished, 0)
        self.assertRegex(stderr, r"no outputs were written; %d finished slabs? of \d+ (is|are) "
                         r"kept in '" % finished)
        self.assertIn("': the same command with --resume goes on from ", stderr)
        done = msynth("synthesize", data("Tilesets/Lines.xml"), *common, "--resume", "--out", out)
        self.assertEqual(done.returncode, 0, done.stderr)
        self.assertIn("%d kept from the earlier run" % finished, done.stdout)

    def test_an_early_interrupt_promises_nothing_to_resume(self):
        """Issue 49: Ctrl-C before the first slab was finished promised kept slabs and --resume,
        and left an empty stream behind. Now it says there is nothing to resume, and the stream's
        folder is gone with the output folder the run made."""
        common = ["--size", "400", "2400", "1", "--block", "32", "32", "1", "--seed", "8",
                  "--stream", "--slab", "2400", "--threads", "1", "--outputs", "labels"]
        out = os.path.join(fresh_folder("stream-sigint-early"), "out")
        stream = os.path.join(out, ".msynth-stream")
        run = subprocess.Popen([MSYNTH, "synthesize", data("Tilesets/Lines.xml"), *common,
                                "--out", out], stdout=subprocess.DEVNULL, stderr=subprocess.PIPE,
                               text=True)
        deadline = time.monotonic() + 60
        while time.monotonic() < deadline and run.poll() is None:
            if os.path.exists(os.path.join(stream, "definition.txt")):
                break
            time.sleep(0.005)
        self.assertEqual(text(os.path.join(stream, "slabs.txt")), "", "the one slab was finished")
        run.send_signal(signal.SIGINT)
        _, stderr = run.communicate(timeout=60)
        self.assertEqual(run.returncode, 128 + signal.SIGINT, stderr)
        self.assertEqual(stderr.strip(), "msynth: interrupted (SIGINT); no outputs were written; "
                         "no slab was finished, so there is nothing to --resume: the same "
                         "command starts again")
        self.assertFalse(os.path.exists(out), os.listdir(out) if os.path.exists(out) else "")

    def test_damaged_stream_states_resume_or_fail_cleanly(self):
        """Seeded damage of an interrupted stream's state (a byte of slabs.txt, definition.txt
        or a slab changed, a NUL written, a line repeated, a file cut short): --resume either
        publishes the world a fresh run makes or fails in one line publishing nothing."""
        import random
        import shutil
        lines = data("Tilesets/Lines.xml")
        common = ["--size", "160", "800", "1", "--block", "32", "32", "1", "--seed", "5",
                  "--stream", "--slab", "100", "--threads", "1", "--outputs", "labels"]
        _, expected = self.fresh_world("stream-damage-fresh", common)
        state = self.interrupted("stream-damage-state", common, slabs=4)
        seeds = 3 if os.environ.get("MSYNTH_SANITIZED") else 10
        for seed in range(int(os.environ.get("MSYNTH_STREAM_DAMAGE_SEEDS", seeds))):
            rng = random.Random(seed)
            out = fresh_folder("stream-damage")
            shutil.rmtree(out)
            shutil.copytree(state, out)
            stream = os.path.join(out, ".msynth-stream")
            victim = rng.choice(["slabs.txt", "slabs.txt", "definition.txt",
                                 os.path.join("labels", "labels_00001.vti")])
            path = os.path.join(stream, victim)
            with open(path, "rb") as f:
                raw = bytearray(f.read())
            kind = rng.choice(["flip", "nul", "repeat", "cut"])
            at = rng.randrange(len(raw))
            if kind == "flip":
                raw[at] ^= 1 << rng.randrange(8)
            elif kind == "nul":
                raw[at] = 0
            elif kind == "repeat":
                first = raw.split(b"\n")[0] + b"\n"
                raw = first + raw
            else:
                raw = raw[:at]
            write(path, bytes(raw), "wb")
            done = msynth("synthesize", lines, *common, "--resume", "--out", out)
            what = "seed %d: %s of %s at %d" % (seed, kind, victim, at)
            if done.returncode == 0:
                np.testing.assert_array_equal(
                    labels_zyx(read_pieces(os.path.join(out, "labels.pvti"))), expected, what)
            else:
                self.assertEqual(len(done.stderr.strip().splitlines()), 1, what + done.stderr)
                self.assertFalse(os.path.exists(os.path.join(out, "labels.pvti")), what)

    def test_the_filter_streams_slabs_to_a_python_observer(self):
        import modelsynth
        synthesis = modelsynth.vtkMSDiscreteSynthesis()
        synthesis.SetTilesetFile(data("Tilesets/Lines.xml"))
        synthesis.SetOutputSize(48, 100, 1)
        synthesis.SetBlockSize(16, 16, 1)
        synthesis.SetSeed(6)
        synthesis.GenerateGeometryOff()
        synthesis.Update()
        whole = labels_zyx(synthesis.GetOutput())
        world = np.full(whole.shape, -2, dtype=whole.dtype)
        seen = []

        def on_slab(caller, event):
            slab = caller.GetCurrentSlab()
            x0, x1, y0, y1, z0, z1 = slab.GetExtent()
            world[z0:z1 + 1, y0:y1 + 1, x0:x1 + 1] = labels_zyx(slab)
            seen.append((caller.GetCurrentSlabIndex(), caller.GetNumberOfSlabs()))

        synthesis.AddObserver(modelsynth.vtkMSDiscreteSynthesis.SlabEvent, on_slab)
        synthesis.StreamNextUpdate(25, 0)
        synthesis.Update()
        self.assertEqual(seen, [(j, 4) for j in range(4)])
        np.testing.assert_array_equal(world, whole)
        self.assertEqual(synthesis.GetOutput().GetNumberOfPoints(), 0)  # the slabs were the output
        # The next update after a change computes the whole output again.
        synthesis.Modified()
        synthesis.Update()
        np.testing.assert_array_equal(labels_zyx(synthesis.GetOutput()), whole)

    def test_a_world_too_large_for_memory_streams(self):
        lines = data("Tilesets/Lines.xml")
        out = fresh_folder("stream-auto")
        env = dict(os.environ, MSYNTH_AVAILABLE_MEMORY=str(60 * 2 ** 20))  # a 60 MB machine
        done = subprocess.run([MSYNTH, "synthesize", lines, "--size", "1400", "1400", "1",
                               "--block", "32", "32", "1", "--slab", "400", "--seed", "4",
                               "--outputs", "labels", "--out", out],
                              capture_output=True, text=True, env=env, timeout=300)
        self.assertEqual(done.returncode, 0, done.stderr)
        self.assertIn("is streamed slab by slab instead", done.stderr)
        self.assertTrue(os.path.exists(os.path.join(out, "labels.pvti")))
        self.assertEqual(msynth("check", lines, os.path.join(out, "labels.pvti")).returncode, 0)
        # Without blocks a world cannot be streamed: the memory check refuses it in one line.
        done = subprocess.run([MSYNTH, "synthesize", lines, "--size", "1400", "1400", "1",
                               "--out", out], capture_output=True, text=True, env=env, timeout=300)
        self.assertNotEqual(done.returncode, 0)
        self.assertIn("more than the", done.stderr)

    def test_streams_refuse_what_needs_the_whole_world(self):
        lines = data("Tilesets/Lines.xml")
        out = fresh_folder("stream-refused")
        for extra, words in ((["--mirror", "x"], "symmetry"),
                             (["--snapshots", "1"], "--snapshots"),
                             (["--outputs", "labels,mesh"], "not 'mesh'")):
            done = msynth("synthesize", lines, "--size", "40", "40", "1", "--block", "16", "16",
                          "1", "--stream", *extra, "--out", out)
            self.assertNotEqual(done.returncode, 0, extra)
            self.assertIn(words, done.stderr)
            self.assertEqual(len(done.stderr.strip().splitlines()), 1, done.stderr)
        for block in ([], ["--block", "40", "50", "1"]):
            done = msynth("synthesize", lines, "--size", "40", "40", "1", *block, "--stream", "--out", out)
            self.assertEqual(done.returncode, 2)
            self.assertEqual(len(done.stderr.strip().splitlines()), 1, done.stderr)
            self.assertIn("--stream computes the world block by block: give a --block smaller than --size "
                          "40 40 1 on at least one axis (--block %s)" % (" ".join(block[1:]) or "0 0 0"),
                          done.stderr)


if __name__ == "__main__":
    unittest.main()
