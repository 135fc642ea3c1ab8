"""What a user sees of a village (a label grid with ground below and empty space above), measured
with numpy only, sharing no code with the solver: each label's share of the sites above the
ground, the buildings (6-connected parts of non-ground, non-empty sites) per ground column, the
share of columns a roof covers seen from above, and the mean footprint of a building.

Usable as a module (measures(), compare()) and as a script:
  python3 village_measures.py EXAMPLE MODEL.vti [--json OUT.json]
prints both measures side by side (EXAMPLE .vti or .vox), with --json also writes the model's."""
import sys

import numpy as np

EMPTY, GROUND, ROOF = 0, 1, 3  # every other label is a wall


def label_array(image):
    """The Label array of vtkImageData @p image as a numpy array indexed [z, y, x]."""
    from vtkmodules.util.numpy_support import vtk_to_numpy
    array = image.GetPointData().GetArray("Label")
    nx, ny, nz = image.GetDimensions()
    if array is None:  # labels on cells: one fewer site per axis of more than one point
        array = image.GetCellData().GetArray("Label")
        nx, ny, nz = (max(n - 1, 1) for n in (nx, ny, nz))
    return vtk_to_numpy(array).reshape(nz, ny, nx)


def read_vox(path):
    """[z, y, x] labels of a MagicaVoxel file's first model (palette index = label, 0 = empty),
    parsed here from the format's chunks (SIZE, XYZI), not by the ModelSynth reader."""
    import struct
    with open(path, "rb") as f:
        data = f.read()
    assert data[:4] == b"VOX ", path
    position, labels = 20, None  # past "VOX ", the version and MAIN's 12-byte header
    while position + 12 <= len(data):
        cid = data[position:position + 4]
        content, children = struct.unpack_from("<II", data, position + 4)
        body = position + 12
        if cid == b"SIZE" and labels is None:
            nx, ny, nz = struct.unpack_from("<III", data, body)
            labels = np.zeros((nz, ny, nx), np.int32)
        elif cid == b"XYZI":
            count = struct.unpack_from("<I", data, body)[0]
            voxels = np.frombuffer(data, np.uint8, 4 * count, body + 4).reshape(count, 4)
            labels[voxels[:, 2], voxels[:, 1], voxels[:, 0]] = voxels[:, 3]
            return labels
        position = body + content + children
    raise ValueError("%s: no XYZI chunk" % path)


def read_labels(path):
    """[z, y, x] labels of a .vti label grid (VTK's own XML reader, not the ModelSynth one) or a
    .vox model (read_vox)."""
    if path.endswith(".vox"):
        return read_vox(path)
    from vtkmodules.vtkIOXML import vtkXMLImageDataReader
    reader = vtkXMLImageDataReader()
    reader.SetFileName(path)
    reader.Update()
    return label_array(reader.GetOutput())


def components(solid):
    """Number of 6-connected components of the boolean array @p solid, and their footprints
    (the number of distinct (y, x) columns of each), by an explicit flood fill."""
    seen = np.zeros(solid.shape, bool)
    footprints = []
    shape = solid.shape
    for start in zip(*np.nonzero(solid)):
        if seen[start]:
            continue
        seen[start] = True
        stack, columns = [start], set()
        while stack:
            z, y, x = stack.pop()
            columns.add((y, x))
            for dz, dy, dx in ((1, 0, 0), (-1, 0, 0), (0, 1, 0), (0, -1, 0), (0, 0, 1), (0, 0, -1)):
                n = (z + dz, y + dy, x + dx)
                if all(0 <= n[i] < shape[i] for i in range(3)) and solid[n] and not seen[n]:
                    seen[n] = True
                    stack.append(n)
        footprints.append(len(columns))
    return len(footprints), footprints


def measures(labels):
    """Measures of a village, [z, y, x] labels with the ground in layer 0."""
    above = labels[1:]
    sites = above.size
    columns = labels.shape[1] * labels.shape[2]
    count, footprints = components((above != EMPTY) & (above != GROUND))
    return {
        "ground_layer": float(np.mean(labels[0] == GROUND)),
        "empty": float(np.mean(above == EMPTY)),
        "wall": float(np.mean(~np.isin(above, (EMPTY, GROUND, ROOF)))),
        "roof": float(np.mean(above == ROOF)),
        "ground_above": float(np.mean(above == GROUND)),
        "buildings": count,
        "buildings_per_column": count / columns,
        "roof_cover": float(np.mean(np.any(above == ROOF, axis=0))),
        "mean_footprint": float(np.mean(footprints)) if footprints else 0.0,
    }


# (low, high): a model's measure must lie within low..high times the example's. Walls may fall
# lower than the rest: houses of one storey are as right as the example's two.
TOLERANCES = {"wall": (0.45, 1.6), "roof": (0.6, 1.6), "buildings_per_column": (0.5, 2.0),
              "roof_cover": (0.6, 1.6), "mean_footprint": (0.5, 1.6)}


def compare(model, example):
    """The ways @p model's measures are unlike @p example's (an empty list when alike): each
    measure of TOLERANCES within its bounds, the ground layer all ground and no ground above it."""
    problems = []
    for name, (low, high) in TOLERANCES.items():
        if not low * example[name] <= model[name] <= high * example[name]:
            problems.append("%s %.4f not within %.2f-%.2f x the example's %.4f" % (
                name, model[name], low, high, example[name]))
    if model["ground_layer"] != 1.0 or model["ground_above"] != 0.0:
        problems.append("ground layer %.3f ground, %.3f ground above it" % (
            model["ground_layer"], model["ground_above"]))
    return problems


if __name__ == "__main__":
    example, model = (measures(read_labels(p)) for p in sys.argv[1:3])
    if "--json" in sys.argv:
        import json
        with open(sys.argv[sys.argv.index("--json") + 1], "w") as f:
            json.dump(model, f, indent=1, sort_keys=True)
            f.write("\n")
    for name in example:
        print("%-22s example %9.4f   model %9.4f" % (name, example[name], model[name]))
    for problem in compare(model, example):
        print("unlike the example:", problem)
