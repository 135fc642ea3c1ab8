"""Files that could crash a run or be damaged by one (issue 48): a guide whose WholeExtent its
pieces do not hold, or that is reversed; outputs named after a device, a FIFO or a folder; an
output folder whose manifest is damaged; a model read by `check` from a broken file. Each ends in
one line naming the file and the problem, within seconds, and leaves nothing behind."""
import os
import stat
import struct
import time
import unittest

from msynth_testing import data, fresh_folder, run_msynth

GUIDE = """<?xml version="1.0"?>
<VTKFile type="ImageData" version="0.1" byte_order="LittleEndian">
  <ImageData WholeExtent="{whole}" Origin="0 0 0" Spacing="1 1 1">
    <Piece Extent="0 1 0 1 0 0">
      <PointData>
        <DataArray type="Float32" Name="Weight_1" format="ascii">1 1 1 1</DataArray>
        <DataArray type="Int32" Name="Region" format="ascii">0 0 1 1</DataArray>
      </PointData>
    </Piece>
  </ImageData>
</VTKFile>
"""


def chunk(name, content, children=b""):
    return name + struct.pack("<ii", len(content), len(children)) + content + children


def vox(body):
    return b"VOX " + struct.pack("<i", 150) + chunk(b"MAIN", b"", body)


def far_scene(offset):
    """A .vox scene of two 5 x 5 x 5 models, the second translated by `offset` (text "x y z")."""
    def text(t):
        return struct.pack("<i", len(t)) + t.encode()

    def attributes(pairs):
        return struct.pack("<i", len(pairs)) + b"".join(text(k) + text(v) for k, v in pairs)

    def transform(node, child, at):
        return chunk(b"nTRN", struct.pack("<i", node) + attributes([]) +
                     struct.pack("<iiii", child, -1, 0, 1) + attributes([("_t", at)] if at else []))

    def shape(node, model):
        return chunk(b"nSHP", struct.pack("<i", node) + attributes([]) +
                     struct.pack("<ii", 1, model) + attributes([]))

    models = b"".join(chunk(b"SIZE", struct.pack("<iii", 5, 5, 5)) +
                      chunk(b"XYZI", struct.pack("<i", 1) + bytes([0, 0, 0, 1])) for _ in range(2))
    group = chunk(b"nGRP", struct.pack("<i", 1) + attributes([]) + struct.pack("<iii", 2, 2, 4))
    return vox(models + transform(0, 1, None) + group + transform(2, 3, "0 0 0") + shape(3, 0) +
               transform(4, 5, offset) + shape(5, 1))


def write(path, content, mode="w"):
    with open(path, mode) as f:
        f.write(content)


class HostileFilesTest(unittest.TestCase):
    def one_line(self, done, *needles):
        self.assertNotEqual(done.returncode, 0, done.stdout)
        self.assertLess(done.returncode, 128, "a signal, not an error: " + done.stderr)
        lines = done.stderr.strip().splitlines()
        self.assertEqual(len(lines), 1, done.stderr)
        for needle in needles:
            self.assertIn(needle, lines[0])

    def test_guides_whose_extent_their_pieces_do_not_hold(self):
        folder = fresh_folder("hostile-guides")
        village = data("Examples/Village.vti")
        model = os.path.join(folder, "model")
        done = run_msynth("synthesize", village, "--size", "16", "16", "5", "--out", model)
        self.assertEqual(done.returncode, 0, done.stderr)
        large = os.path.join(folder, "large.vti")  # 10^10 points over a piece of four
        write(large, GUIDE.format(whole="0 100000 0 100000 0 0"))
        reversed_ = os.path.join(folder, "reversed.vti")
        write(reversed_, GUIDE.format(whole="0 1 0 1 5 0"))
        for guide, problem in ((large, "its pieces hold 4"), (reversed_, "reversed WholeExtent")):
            out = os.path.join(folder, "out")
            done = run_msynth("synthesize", village, "--size", "16", "16", "5", "--guide", guide,
                              "--out", out, timeout=60)
            self.one_line(done, os.path.basename(guide), problem)
            self.assertFalse(os.path.exists(out))
            done = run_msynth("synthesize", data("Continuous/house.obj"), "--size", "12", "12",
                              "8", "--guide", guide, "--out", out, timeout=60)
            self.one_line(done, os.path.basename(guide), problem)
            self.assertFalse(os.path.exists(out))
            done = run_msynth("check", village, os.path.join(model, "labels.vti"), "--count",
                              "region=0:1:0:1000", "--guide", guide, timeout=60)
            self.one_line(done, os.path.basename(guide), problem)

    def test_a_device_a_fifo_or_another_format_is_not_written_over(self):
        folder = fresh_folder("hostile-targets")
        village = data("Examples/Village.vti")
        fifo = os.path.join(folder, "pipe.vti")
        os.mkfifo(fifo)
        for target, problem in ((fifo, "not a regular file"), ("/dev/null", "name a .vti file"),
                                (os.path.join(folder, "x.vox"), "name a .vti file")):
            done = run_msynth("analyze", village, "--infallible", "--write-infallible", target)
            self.one_line(done, target, problem)
        self.assertTrue(stat.S_ISFIFO(os.stat(fifo).st_mode))
        self.assertTrue(stat.S_ISCHR(os.stat("/dev/null").st_mode))
        self.assertFalse(os.path.exists(os.path.join(folder, "x.vox")))
        self.assertEqual(sorted(os.listdir(folder)), ["pipe.vti"])  # no temporary file left

    def test_a_damaged_manifest_stops_the_run_before_it_publishes(self):
        out = fresh_folder("hostile-manifest")
        village = data("Examples/Village.vti")
        write(os.path.join(out, "notes.txt"), "the user's")
        write(os.path.join(out, ".msynth-outputs"), b"labels.vti\n\x00\nmesh.vtp\n", "wb")
        done = run_msynth("synthesize", village, "--size", "16", "16", "5", "--out", out,
                          timeout=60)
        self.one_line(done, ".msynth-outputs", "is damaged (line 2 is not a file name)")
        self.assertEqual(sorted(os.listdir(out)), [".msynth-outputs", "notes.txt"])

    def test_memory_is_estimated_before_a_small_file_asks_for_much(self):
        """A scene's second model translated far away (a 362-byte file spanning 10^9 voxels), an
        empty .vox declaring 512 x 512 x 256: refused at once when the memory available (here
        set by MSYNTH_AVAILABLE_MEMORY) cannot hold what the command takes per site."""
        folder = fresh_folder("hostile-memory")
        scene = os.path.join(folder, "far.vox")
        write(scene, far_scene("1000 1000 1000"), "wb")
        empty = os.path.join(folder, "empty.vox")
        write(empty, vox(chunk(b"SIZE", struct.pack("<iii", 512, 512, 256)) +
                         chunk(b"XYZI", struct.pack("<i", 0))), "wb")
        env = dict(os.environ, MSYNTH_AVAILABLE_MEMORY=str(10**9))
        import subprocess
        from msynth_testing import BIN
        for args, needle in ((["check", data("Tilesets/Pipes.xml"), scene],
                              "places its models over 1005 x 1005 x 1005 voxels"),
                             (["info", empty], "declares a model of 512 x 512 x 256 voxels")):
            start = time.monotonic()
            done = subprocess.run([os.path.join(BIN, "msynth"), *args], capture_output=True,
                                  text=True, timeout=60, env=env)
            self.one_line(done, needle, "the memory available allows no more")
            self.assertLess(time.monotonic() - start, 10)

    def test_a_scene_of_models_far_apart_is_refused_at_once(self):
        """Two 5^3 models 400 x 400 x 300 voxels apart span 5 * 10^7 sites that fit in memory, but
        composing and checking them took 5 s and 650 MB (6 * 10^8 sites 1000 apart: 7 GB and a
        minute): a scene past 2^24 sites whose models' boxes fill under 1/64 of it is refused in
        one line; models 100 apart (10^6 sites) are still read and checked."""
        folder = fresh_folder("hostile-far-apart")
        far = os.path.join(folder, "far.vox")
        write(far, far_scene("400 400 300"), "wb")
        start = time.monotonic()
        done = run_msynth("check", data("Tilesets/Pipes.xml"), far, timeout=60)
        self.one_line(done, "far.vox", "places its 2 models far apart", "405 x 405 x 305")
        self.assertLess(time.monotonic() - start, 3)
        near = os.path.join(folder, "near.vox")
        write(near, far_scene("100 100 100"), "wb")
        done = run_msynth("check", data("Tilesets/Pipes.xml"), near, timeout=60)
        self.assertNotIn("far apart", done.stderr)
        self.assertIn("tile cells", done.stdout + done.stderr)

    def test_check_names_the_broken_file(self):
        folder = fresh_folder("hostile-check")
        broken = os.path.join(folder, "broken.vox")
        write(broken, "garbage")
        done = run_msynth("check", data("Tilesets/Lines.xml"), broken)
        self.one_line(done, "broken.vox", "does not start with 'VOX '")
        self.assertNotIn("vtkMSCheckModel failed", done.stderr)


if __name__ == "__main__":
    unittest.main()
