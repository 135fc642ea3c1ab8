"""Shared helpers of the Python tests: paths from ctest's environment, an error observer, and
an independent recomputation of Eq. 3.2 with numpy."""
import os

import numpy as np
from vtkmodules.util.misc import calldata_type
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.util.vtkConstants import VTK_STRING

DATA = os.environ["MSYNTH_DATA"]
TMP = os.environ["MSYNTH_TMP"]
BIN = os.environ.get("MSYNTH_BIN", "")


def data(relative):
    return os.path.join(DATA, relative)


def tmp(name):
    return os.path.join(TMP, name)


class ErrorObserver:
    """Collects ErrorEvent messages of a VTK object."""

    def __init__(self, obj):
        self.messages = []

        @calldata_type(VTK_STRING)
        def on_error(caller, event, calldata=None):
            self.messages.append(str(calldata) if calldata is not None else "")

        self._callback = on_error  # keep it alive as long as the observer
        obj.AddObserver("ErrorEvent", on_error)

    def text(self):
        return "\n".join(self.messages)


def render_model():
    """Utilities/render-model.py as a module: the palette every picture uses, taken from the
    script that draws them (not from the writers' code)."""
    import importlib.util
    source = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
    spec = importlib.util.spec_from_file_location(
        "render_model", os.path.join(source, "Utilities", "render-model.py"))
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def linear(c):
    """An sRGB component (0-1) as linear light, as glTF and OpenVDB colours are stored."""
    return c / 12.92 if c <= 0.04045 else ((c + 0.055) / 1.055) ** 2.4


def fresh_folder(name):
    """An empty folder of the test output area (made anew)."""
    import shutil
    folder = tmp(name)
    shutil.rmtree(folder, ignore_errors=True)
    os.makedirs(folder)
    return folder


def run_msynth(*args, timeout=None):
    """Runs the build's msynth with `args`; the completed process (text output captured)."""
    import subprocess
    limit = timeout or (300 if os.environ.get("MSYNTH_SANITIZED") else 120)
    return subprocess.run([os.path.join(BIN, "msynth"), *args], capture_output=True, text=True,
                          timeout=limit)


def expect_refused(test, command, args, message, name="refused"):
    """Runs `msynth *command *args --out DIR` and asserts that it fails with one line on stderr
    holding `message` and writes nothing. The folder is the process's own: test scripts that
    ctest runs side by side would otherwise empty and fill the same one."""
    out = os.path.join(fresh_folder("%s-%d" % (name, os.getpid())), "out")
    r = run_msynth(*command, *args, "--out", out)
    test.assertNotEqual(r.returncode, 0, args)
    lines = r.stderr.strip().splitlines()
    test.assertEqual(len(lines), 1, r.stderr)
    test.assertIn(message, lines[0])
    test.assertFalse(os.path.exists(out), "nothing is written")


def read_label_grid(path):
    """The image data of a label grid file (.vti, .txt, .vox) through the ModelSynth reader."""
    import modelsynth
    reader = modelsynth.vtkMSLabelGridReader()
    reader.SetFileName(path)
    reader.Update()
    return reader.GetOutput()


def read_pieces(path):
    """The image data of a streamed world's labels.pvti, through VTK's own pieces reader."""
    from vtkmodules.vtkIOXML import vtkXMLPImageDataReader
    reader = vtkXMLPImageDataReader()
    reader.SetFileName(path)
    reader.Update()
    return reader.GetOutput()


def write_label_image(labels_yx, path, origin=(0, 0)):
    """Writes a 2D label array ([y, x]) as a .vti whose extent starts at `origin` (x, y)."""
    from vtkmodules.util.numpy_support import numpy_to_vtk
    from vtkmodules.vtkCommonDataModel import vtkImageData
    from vtkmodules.vtkIOXML import vtkXMLImageDataWriter
    ny, nx = labels_yx.shape
    image = vtkImageData()
    image.SetExtent(origin[0], origin[0] + nx - 1, origin[1], origin[1] + ny - 1, 0, 0)
    array = numpy_to_vtk(np.ascontiguousarray(labels_yx, dtype=np.int32).ravel(), deep=True)
    array.SetName("Label")
    image.GetPointData().SetScalars(array)
    writer = vtkXMLImageDataWriter()
    writer.SetInputData(image)
    writer.SetFileName(path)
    if writer.Write() != 1:
        raise RuntimeError("could not write " + path)
    return path


def read_png(path):
    """A PNG's pixels as [row from the top, column, channel] (3 or 4 channels)."""
    from vtkmodules.vtkIOImage import vtkPNGReader
    reader = vtkPNGReader()
    reader.SetFileName(path)
    reader.Update()
    image = reader.GetOutput()
    width, height, _ = image.GetDimensions()
    return vtk_to_numpy(image.GetPointData().GetScalars()).reshape(height, width, -1)[::-1].copy()


def write_png(pixels_top_first, path):
    """Writes [row from the top, column, RGBA] pixels as a PNG."""
    from vtkmodules.util.numpy_support import numpy_to_vtk
    from vtkmodules.vtkCommonDataModel import vtkImageData
    from vtkmodules.vtkIOImage import vtkPNGWriter
    height, width, channels = pixels_top_first.shape
    image = vtkImageData()
    image.SetDimensions(width, height, 1)
    image.GetPointData().SetScalars(numpy_to_vtk(
        np.ascontiguousarray(pixels_top_first[::-1]).reshape(-1, channels), deep=True))
    writer = vtkPNGWriter()
    writer.SetInputData(image)
    writer.SetFileName(path)
    writer.Write()


def run_algorithm(algorithm, port=None, data=None, **options):
    """Connects `port` (or `data`), calls Set<Name>(value) for every option, updates, and
    returns (output, error text)."""
    if port is not None:
        algorithm.SetInputConnection(port)
    if data is not None:
        algorithm.SetInputData(data)
    for name, value in options.items():
        values = value if isinstance(value, (list, tuple)) else [value]
        getattr(algorithm, "Set" + name)(*values)
    errors = ErrorObserver(algorithm)
    algorithm.Update()
    return algorithm.GetOutput(), errors.text()


def labels_and_start(folder):
    """The labels of FOLDER/labels.vti ([z, y, x]) and the start its blocks took (its field
    StartFrom; None without one)."""
    from vtkmodules.vtkIOXML import vtkXMLImageDataReader
    reader = vtkXMLImageDataReader()
    reader.SetFileName(os.path.join(folder, "labels.vti"))
    reader.Update()
    start = reader.GetOutput().GetFieldData().GetAbstractArray("StartFrom")
    return labels_zyx(reader.GetOutput()), start.GetValue(0) if start else None


def labels_zyx(image, name="Label"):
    """The label array of a vtkImageData as a numpy array indexed [z, y, x]."""
    nx, ny, nz = image.GetDimensions()
    return vtk_to_numpy(image.GetPointData().GetArray(name)).reshape(nz, ny, nx)


def brute_force_transitions(labels):
    """{(axis, from, to): count} of Eq. 3.2, from a [z, y, x] numpy array (axis 0 = x)."""
    pairs = {}
    for axis, np_axis in ((0, 2), (1, 1), (2, 0)):
        n = labels.shape[np_axis]
        a = np.take(labels, range(0, n - 1), axis=np_axis).ravel()
        b = np.take(labels, range(1, n), axis=np_axis).ravel()
        for u, v in zip(a.tolist(), b.tolist()):
            pairs[(axis, u, v)] = pairs.get((axis, u, v), 0) + 1
    return pairs


def violations(example, model):
    """Adjacent pairs of `model` that never occur in `example` (Eq. 3.1), both [z, y, x] numpy
    arrays. Independent of the solver: recomputed here from the example."""
    allowed = set(brute_force_transitions(example))
    found = []
    for (axis, u, v), _ in brute_force_transitions(model).items():
        if (axis, u, v) not in allowed:
            found.append((axis, u, v))
    return found


def winding_numbers(points, polygons, queries):
    """Generalized winding number of closed polygon surfaces at many query points: the sum of
    the signed solid angles of fan triangles (Van Oosterom-Strackee) over 4 pi; about 1 inside
    and 0 outside, whatever the orientation of the input faces' triangulation."""
    total = np.zeros(len(queries))
    for poly in polygons:
        for k in range(1, len(poly) - 1):
            a, b, c = (points[poly[0]] - queries, points[poly[k]] - queries, points[poly[k + 1]] - queries)
            la, lb, lc = (np.linalg.norm(v, axis=1) for v in (a, b, c))
            det = np.einsum("ij,ij->i", a, np.cross(b, c))
            div = (la * lb * lc + np.einsum("ij,ij->i", a, b) * lc + np.einsum("ij,ij->i", a, c) * lb
                   + np.einsum("ij,ij->i", b, c) * la)
            total += 2 * np.arctan2(det, div)
    return total / (4 * np.pi)


def obj_objects(path):
    """Points and [(object name, [polygon as point indices])] of an OBJ in file order (each `o`
    or `g` statement starts an object), parsed here independently of the project's reader."""
    points, objects = [], []
    with open(path) as f:
        for line in f:
            w = line.split()
            if not w or w[0].startswith("#"):
                continue
            if w[0] == "v":
                points.append([float(c) for c in w[1:4]])
            elif w[0] in ("o", "g"):
                objects.append((" ".join(w[1:]), []))
            elif w[0] == "f":
                if not objects:
                    objects.append(("object", []))
                objects[-1][1].append([int(t.split("/")[0]) - 1 for t in w[1:]])
    return points, objects
