"""VTK XML files (.vti) before VTK's reader: every encoding VTK writes is accepted, and the
damaged files that crashed VTK's reader (an unknown array type in field data, a string array
holding more strings than it declares, a compressed header with a zero block size) are errors
naming the file. Random byte flips of a compressed file are read or refused, never a crash."""
import os
import random
import re
import unittest

import numpy as np
from vtkmodules.util.numpy_support import numpy_to_vtk
from vtkmodules.vtkCommonCore import vtkStringArray
from vtkmodules.vtkCommonDataModel import vtkImageData
from vtkmodules.vtkIOXML import vtkXMLImageDataWriter

import modelsynth
from msynth_testing import labels_zyx, run_algorithm, tmp

LABELS = (np.arange(4 * 3 * 2, dtype=np.int32) * 7) % 5


def example():
    image = vtkImageData()
    image.SetDimensions(4, 3, 2)
    a = numpy_to_vtk(LABELS, deep=True)
    a.SetName("Label")
    image.GetPointData().SetScalars(a)
    names = vtkStringArray()
    names.SetName("Notes")
    for s in ("a", "bc", ""):
        names.InsertNextValue(s)
    image.GetFieldData().AddArray(names)
    return image


def write(path, mode, compressor, header64):
    w = vtkXMLImageDataWriter()
    w.SetInputData(example())
    w.SetFileName(path)
    {"ascii": w.SetDataModeToAscii, "binary": w.SetDataModeToBinary,
     "appended": w.SetDataModeToAppended, "base64": w.SetDataModeToAppended}[mode]()
    w.SetEncodeAppendedData(mode == "base64")
    {"none": w.SetCompressorTypeToNone, "zlib": w.SetCompressorTypeToZLib,
     "lz4": w.SetCompressorTypeToLZ4, "lzma": w.SetCompressorTypeToLZMA}[compressor]()
    w.SetHeaderTypeToUInt64() if header64 else w.SetHeaderTypeToUInt32()
    w.SetBlockSize(16)  # several blocks for 96 bytes of labels
    assert w.Write() == 1
    return path


def read(path):
    return run_algorithm(modelsynth.vtkMSLabelGridReader(), FileName=path)


class VTKXMLCheckTest(unittest.TestCase):
    def test_every_encoding_vtk_writes_is_read(self):
        for mode in ("ascii", "binary", "appended", "base64"):
            for compressor in ("none", "zlib", "lz4", "lzma"):
                for header64 in (False, True):
                    path = write(tmp("enc.vti"), mode, compressor, header64)
                    out, errors = read(path)
                    case = (mode, compressor, header64)
                    self.assertEqual(errors, "", case)
                    self.assertTrue(np.array_equal(labels_zyx(out).ravel(), LABELS), case)

    def damaged(self, name, text_or_bytes, problem):
        path = tmp(name)
        with open(path, "wb") as f:
            f.write(text_or_bytes if isinstance(text_or_bytes, bytes) else text_or_bytes.encode())
        out, errors = read(path)
        self.assertIn("'%s'" % path, errors, name)
        self.assertIn(problem, errors, name)
        self.assertEqual(out.GetNumberOfPoints(), 0, name)

    def test_the_files_that_crashed_vtk_are_errors(self):
        with open(write(tmp("plain.vti"), "ascii", "none", False)) as f:
            text = f.read()
        # An unknown array type in field data.
        unknown = re.sub(r'type="String"', 'type="Quux"', text, count=1)
        self.damaged("unknown-type.vti", unknown, "array 'Notes' has type 'Quux', which VTK does not know")
        # A string array holding more strings than it declares.
        more = re.sub(r'(Name="Notes" NumberOfTuples=")3"', r'\g<1>1"', text)
        self.damaged("more-strings.vti", more, "array 'Notes' holds 3 strings but declares 1")
        # A compressed header whose block size is 0 (VTK divided by it).
        path = write(tmp("zlib.vti"), "appended", "zlib", True)
        with open(path, "rb") as f:
            data = bytearray(f.read())
        start = data.index(b"<AppendedData")
        start = data.index(b"_", start) + 1
        offset = int(re.search(rb'Name="Label"[^>]*offset="(\d+)"', data).group(1))
        data[start + offset + 8:start + offset + 16] = bytes(8)  # UInt64 words: blocks, size, last
        self.damaged("zero-block.vti", bytes(data), "compression header of")
        # More strings in compressed data, too (decompressed and counted).
        with open(write(tmp("zlib-strings.vti"), "appended", "zlib", False), "rb") as f:
            data = f.read()
        self.damaged("zlib-more-strings.vti",
                     re.sub(rb'(Name="Notes" NumberOfTuples=")3"', rb'\g<1>2"', data), "holds 3 strings but declares 2")

    def test_a_last_block_size_without_blocks_is_an_error(self):
        # A compression header of no blocks whose last block claims bytes: VTK took the data's
        # size as 0 * size - size + last and divided by the block size (SIGFPE, from
        # ReadXMLInformation for the TimeValue field array it reads first). Every array kind
        # our size check leaves alone: field data without a count, bits, and a TimeValue array.
        image = example()
        times = numpy_to_vtk(np.array([0.5]), deep=True)
        times.SetName("TimeValue")
        image.GetFieldData().AddArray(times)
        w = vtkXMLImageDataWriter()
        w.SetInputData(image)
        w.SetFileName(tmp("time.vti"))
        w.SetDataModeToAppended()
        w.SetEncodeAppendedData(False)
        w.SetCompressorTypeToZLib()
        w.SetHeaderTypeToUInt32()
        self.assertEqual(w.Write(), 1)
        with open(tmp("time.vti"), "rb") as f:
            original = f.read()
        start = original.index(b"_", original.index(b"<AppendedData")) + 1
        for name in (b"TimeValue", b"Label"):
            offset = int(re.search(rb'Name="' + name + rb'"[^>]*offset="(\d+)"', original).group(1))
            for drop_count in (False, True):
                data = bytearray(original)
                # UInt32 words: blocks 0, block size 0, last block 8 bytes.
                data[start + offset:start + offset + 12] = bytes(8) + (8).to_bytes(4, "little")
                if drop_count:
                    data = bytearray(re.sub(rb'(Name="' + name + rb'")( NumberOfTuples="\d+")?',
                                            rb"\1", bytes(data)))
                self.damaged("last-block-%s-%d.vti" % (name.decode(), drop_count), bytes(data),
                             "has a compression header of 0 blocks of 0 bytes (the last 8)")

    def test_regression_inputs_through_the_real_readers(self):
        # The inputs kept from fuzzing and from the crash reports, through VTK's readers behind
        # our checks (the harnesses only reach our side).
        regressions = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "Fuzz", "Regressions")
        folder = os.path.join(regressions, "FuzzVTKXML")
        names = sorted(os.listdir(folder))
        self.assertGreaterEqual(len(names), 5)
        for name in names:
            path = os.path.join(folder, name)
            out, errors = read(path)
            self.assertIn("'%s'" % path, errors, name)
            self.assertEqual(out.GetNumberOfPoints(), 0, name)
        vdb = os.path.join(regressions, "FuzzVDB", "four-bytes-ff.vdb")
        out, errors = run_algorithm(modelsynth.vtkMSOpenVDBReader(), FileName=vdb)
        if errors:
            self.assertIn(vdb, errors)

    def test_random_damage_is_read_or_refused(self):
        rng = random.Random(5)
        for compressor in ("zlib", "lz4", "none"):
            with open(write(tmp("fuzz-src.vti"), "appended", compressor, True), "rb") as f:
                original = f.read()
            start = original.index(b"<AppendedData")
            for trial in range(150):
                data = bytearray(original)
                for _ in range(rng.randint(1, 4)):
                    i = rng.randrange(start, len(data)) if rng.random() < 0.8 else rng.randrange(len(data))
                    data[i] = rng.randrange(256)
                path = tmp("fuzz.vti")
                with open(path, "wb") as f:
                    f.write(bytes(data))
                out, errors = read(path)  # a crash here ends the test process
                if errors:
                    self.assertIn(path, errors)


if __name__ == "__main__":
    unittest.main()
