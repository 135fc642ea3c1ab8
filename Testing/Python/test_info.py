"""`msynth info` on every file msynth writes (issue 47 item 4): a real run's model.vdb, mesh.glb,
model.vox and a stream's labels.pvti are described (grids with their classes, meshes and
materials, models and palette, pieces); damaged and hostile files of each format give one line
naming the file, quickly, whatever sizes they claim."""
import json
import os
import resource
import struct
import subprocess
import time
import unittest

from msynth_testing import BIN, data, fresh_folder, run_msynth


def glb(document, binary=b""):
    """A binary glTF of the JSON @p document (a dict or bytes) and the BIN chunk @p binary."""
    text = document if isinstance(document, bytes) else json.dumps(document).encode()
    text += b" " * (-len(text) % 4)
    body = struct.pack("<II", len(text), 0x4E4F534A) + text
    if binary:
        binary += b"\0" * (-len(binary) % 4)
        body += struct.pack("<II", len(binary), 0x004E4942) + binary
    return struct.pack("<III", 0x46546C67, 2, 12 + len(body)) + body


def triangle_document(count=3, extra=None):
    doc = {"asset": {"version": "2.0"},
           "buffers": [{"byteLength": 36}],
           "bufferViews": [{"buffer": 0, "byteLength": 36}],
           "accessors": [{"bufferView": 0, "componentType": 5126, "count": count, "type": "VEC3"}],
           "meshes": [{"name": "tri", "primitives": [{"attributes": {"POSITION": 0}, "material": 0}]}],
           "materials": [{"name": "red", "pbrMetallicRoughness": {"baseColorFactor": [1, 0, 0, 1]}}],
           "nodes": [{"mesh": 0}], "scenes": [{"nodes": [0]}]}
    doc.update(extra or {})
    return doc


def chunk(name, content, children=b""):
    return name + struct.pack("<ii", len(content), len(children)) + content + children


def vox(*chunks):
    main = b"".join(chunks)
    return b"VOX " + struct.pack("<i", 150) + chunk(b"MAIN", b"", main)


def limited():
    # 4 GB of address space: a file that made info allocate what it claims would fail here.
    # (Not under the sanitizers: AddressSanitizer reserves terabytes of address space for its
    # shadow memory and cannot start within the limit; it reports a huge allocation itself.)
    if not os.environ.get("MSYNTH_SANITIZED"):
        resource.setrlimit(resource.RLIMIT_AS, (4 << 30, resource.RLIM_INFINITY))


class InfoTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.out = fresh_folder("info-run")
        done = run_msynth("synthesize", data("Examples/Village.vox"), "--size", "24", "20", "5",
                          "--seed", "3", "--outputs", "labels,mesh,glb,vdb,vox", "--out", cls.out)
        assert done.returncode == 0, done.stderr
        cls.stream = fresh_folder("info-stream")
        done = run_msynth("synthesize", data("Examples/Village.vti"), "--size", "20", "40", "5",
                          "--block", "10", "10", "5", "--stream", "--slab", "20", "--outputs",
                          "labels", "--out", cls.stream)
        assert done.returncode == 0, done.stderr

    def info(self, path):
        start = time.monotonic()
        done = subprocess.run([os.path.join(BIN, "msynth"), "info", path], capture_output=True,
                              text=True, timeout=60, preexec_fn=limited)
        self.assertLess(time.monotonic() - start, 20, path)
        return done

    def refused(self, path, *needles):
        done = self.info(path)
        self.assertEqual(done.returncode, 1, (path, done.stdout))
        self.assertEqual(done.stderr.count("\n"), 1, done.stderr)
        self.assertTrue(done.stderr.startswith("msynth: error: '%s'" % path), done.stderr)
        for needle in needles:
            self.assertIn(needle, done.stderr)
        self.assertNotIn("Traceback", done.stderr)

    def test_model_vdb(self):
        done = self.info(os.path.join(self.out, "model.vdb"))
        self.assertEqual(done.returncode, 0, done.stderr)
        lines = done.stdout.splitlines()
        self.assertIn("(OpenVDB, ", lines[0])
        grids = {l.split(":")[0][5:]: l for l in lines if l.startswith("grid ")}
        self.assertIn("fog volume class", grids["density"])
        self.assertIn("vec3s", grids["color"])
        self.assertIn("level set class", grids["surface"])
        self.assertIn("int32, unknown class", grids["Label"])
        self.assertIn("index box (0, 0, 0) - (", grids["density"])
        self.assertIn("index box (-3, -3, -3) - (", grids["surface"])
        self.assertIn("voxel size 1", grids["surface"])

    def test_mesh_glb(self):
        done = self.info(os.path.join(self.out, "mesh.glb"))
        self.assertEqual(done.returncode, 0, done.stderr)
        self.assertIn("(glTF 2.0, binary)", done.stdout)
        self.assertIn("triangles", done.stdout)
        self.assertRegex(done.stdout, r"materials: [1-9]")
        self.assertRegex(done.stdout, r"base colour #[0-9a-f]{6}")

    def test_model_vox(self):
        done = self.info(os.path.join(self.out, "model.vox"))
        self.assertEqual(done.returncode, 0, done.stderr)
        self.assertIn("model 0: 24 x 20 x 5", done.stdout)
        self.assertIn("palette: the file's", done.stdout)
        self.assertRegex(done.stdout, r"\n  [0-9]+: [0-9]+ voxels?, #[0-9a-f]{6}")
        self.assertIn("labels:", done.stdout)  # then analysed as an example

    def test_labels_pvti(self):
        done = self.info(os.path.join(self.stream, "labels.pvti"))
        self.assertEqual(done.returncode, 0, done.stderr)
        self.assertIn("whole extent: 0-19 x 0-39 x 0-4 (4000 sites)", done.stdout)
        self.assertIn("pieces: 2", done.stdout)
        self.assertIn("labels/labels_00001.vti", done.stdout)
        self.assertIn("Label: Int32", done.stdout)

    def test_damaged_vdb(self):
        folder = fresh_folder("info-bad-vdb")
        with open(os.path.join(self.out, "model.vdb"), "rb") as f:
            good = f.read()
        for name, content, needle in (("half.vdb", good[:len(good) // 2], "corrupt"),
                                      ("empty.vdb", b"", ""),
                                      ("garbage.vdb", b"\x20BDV" + b"\xff" * 400, "")):
            path = os.path.join(folder, name)
            with open(path, "wb") as f:
                f.write(content)
            self.refused(path, needle)

    def test_damaged_and_hostile_gltf(self):
        folder = fresh_folder("info-bad-gltf")
        good = glb(triangle_document(), b"\0" * 36)
        cases = (
            ("good-but-lying-count.glb", glb(triangle_document(count=10**12), b"\0" * 36),
             "accessor 0"),
            ("truncated.glb", good[:-8], "truncated or damaged"),
            ("json-past-end.glb", good[:12] + struct.pack("<I", 2**31) + good[16:], "damaged"),
            ("bin-past-end.glb", good[:-44] + struct.pack("<II", 2**31, 0x004E4942) + good[-36:],
             "damaged"),
            ("nested.glb", glb(b"[" * 200000 + b"]" * 200000), "nested deeper"),
            ("not-json.glb", glb(b"{\"asset\": {"), "not a glTF file"),
            ("view-outside.glb", glb(triangle_document(extra={"bufferViews": [
                {"buffer": 0, "byteOffset": 2**40, "byteLength": 36}]}), b"\0" * 36), "outside"),
            ("missing-material.glb", glb(triangle_document(extra={"materials": []}), b"\0" * 36),
             "material"),
            ("garbage.glb", b"glTF" + b"\xff" * 100, "glTF"),
            ("missing-buffer.gltf", json.dumps(triangle_document(extra={
                "buffers": [{"byteLength": 36, "uri": "nowhere.bin"}]})).encode(), "nowhere.bin"),
        )
        for name, content, needle in cases:
            path = os.path.join(folder, name)
            with open(path, "wb") as f:
                f.write(content)
            self.refused(path, needle)
        # The good one is described.
        path = os.path.join(folder, "good.glb")
        with open(path, "wb") as f:
            f.write(good)
        done = self.info(path)
        self.assertEqual(done.returncode, 0, done.stderr)
        self.assertIn("tri: triangles, 3 vertices, 1 triangle, material 0", done.stdout)
        self.assertIn("0 red: base colour #ff0000", done.stdout)

    def test_damaged_and_hostile_vox(self):
        folder = fresh_folder("info-bad-vox")
        size = chunk(b"SIZE", struct.pack("<iii", 2, 2, 2))
        cases = (
            ("huge-count.vox", vox(size, chunk(b"XYZI", struct.pack("<i", 2**30))), "XYZI declares"),
            ("loop.vox", vox(size, chunk(b"XYZI", struct.pack("<i", 0)),
                             chunk(b"nTRN", struct.pack("<ii", 0, 0) + struct.pack("<iiii", 0, -1, 0, 0))),
             "loop"),
            ("long-chunk.vox", vox(size) + b"XYZI" + struct.pack("<ii", 2**30, 0), "past the end"),
            ("not-vox.vox", b"hello world, not voxels", "VOX"),
        )
        for name, content, needle in cases:
            path = os.path.join(folder, name)
            with open(path, "wb") as f:
                f.write(content)
            self.refused(path, needle)

    def test_damaged_pvti(self):
        folder = fresh_folder("info-bad-pvti")
        with open(os.path.join(self.stream, "labels.pvti")) as f:
            good = f.read()
        cases = (
            ("not-xml.pvti", "<VTKFile type=\"PImageData\"><PImageData", ""),
            ("other-type.pvti", good.replace("PImageData", "PPolyData"), "PImageData"),
            ("bad-extent.pvti", good.replace('WholeExtent="0 19 0 39 0 4"', 'WholeExtent="0 19 x"'),
             "WholeExtent"),
            ("outside.pvti", good.replace('Extent="0 19 19 39 0 4"', 'Extent="0 19 19 99 0 4"'),
             "outside the whole extent"),
            ("deep.pvti", "<a>" * 100000, "nested"),
        )
        for name, content, needle in cases:
            path = os.path.join(folder, name)
            with open(path, "w") as f:
                f.write(content)
            self.refused(path, needle)
        # Pieces that are missing: listed, then one line.
        path = os.path.join(folder, "missing.pvti")
        with open(path, "w") as f:
            f.write(good)
        self.refused(path, "2 piece files named in it are missing")


if __name__ == "__main__":
    unittest.main()
