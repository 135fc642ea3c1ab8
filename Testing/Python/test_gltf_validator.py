"""The Khronos glTF validator (npm package gltf-validator, run by node) on the .glb files
ModelSynth writes: a voxel surface by label, a .vox example's palette colours, pieces, an empty
mesh, a voxel tileset's mesh.glb, and continuous models' (the README's houses, domes substituted
for bounding volumes, a flat model). Every file must have no errors and no warnings. Skipped (exit 77, shown by ctest as
"Not Run") when node or the package is missing: Utilities/install-dependencies.sh --tests
installs it into ~/.cache/modelsynth/npm (MSYNTH_NPM_PREFIX elsewhere)."""
import os
import re
import shutil
import subprocess
import sys

import modelsynth
from msynth_testing import data, fresh_folder, run_msynth

HERE = os.path.dirname(os.path.abspath(__file__))
PREFIX = os.environ.get("MSYNTH_NPM_PREFIX",
                        os.path.join(os.path.expanduser("~"), ".cache", "modelsynth", "npm"))
MODULES = os.path.join(PREFIX, "node_modules")


def write(example, path, pieces=""):
    reader = modelsynth.vtkMSLabelGridReader()
    reader.SetFileName(data(example))
    geometry = modelsynth.vtkMSLabelGeometry()
    geometry.SetInputConnection(reader.GetOutputPort())
    geometry.SetPieceDirectory(pieces)
    writer = modelsynth.vtkMSGLTFWriter()
    writer.SetInputConnection(geometry.GetOutputPort())
    writer.SetFileName(path)
    if writer.Write() != 1:
        sys.exit("could not write " + path)


def main():
    node = shutil.which("node")
    if not node or not os.path.isfile(os.path.join(MODULES, "gltf-validator", "package.json")):
        print("SKIPPED: the glTF validator needs node and the npm package gltf-validator in %s "
              "(Utilities/install-dependencies.sh --tests installs both)" % MODULES)
        return 77
    folder = fresh_folder("gltf-validator")
    pieces = fresh_folder("gltf-validator-pieces")
    with open(os.path.join(pieces, "2.obj"), "w") as f:
        f.write("v -0.5 -0.5 -0.5\nv 0.5 -0.5 -0.5\nv 0.5 0.5 -0.5\nv -0.5 0.5 -0.5\nv 0 0 0.5\n"
                "f 1 2 5\nf 2 3 5\nf 3 4 5\nf 4 1 5\nf 1 4 3 2\n")
    files = [os.path.join(folder, name) for name in ("voxels.glb", "palette.glb", "pieces.glb",
                                                     "empty.glb")]
    write("Examples/Village.vti", files[0])
    write("Examples/Village.vox", files[1])
    write("Examples/Village.vti", files[2], pieces)
    from vtkmodules.vtkCommonDataModel import vtkPolyData
    writer = modelsynth.vtkMSGLTFWriter()
    writer.SetInputData(vtkPolyData())
    writer.SetFileName(files[3])
    writer.Write()
    # A voxel tileset's mesh.glb: the merged rectangles of its voxels, a mesh per palette colour.
    tiles = os.path.join(folder, "pipes")
    done = run_msynth("synthesize", data("Tilesets/Pipes.xml"), "--size", "4", "4", "3", "--seed",
                      "3", "--outputs", "glb", "--out", tiles)
    if done.returncode != 0:
        sys.exit(done.stderr)
    files.append(os.path.join(tiles, "mesh.glb"))
    # Continuous models: the README's houses (a mesh per object type, with normals), a model
    # with a detail mesh substituted (domes), and a flat one (double-sided).
    for name, args in (
            ("houses", ["Continuous/house.obj", "--size", "24", "24", "10", "--seed", "3",
                        "--grounded", "--thickness", "wall:z", "--overhang", "roof", "--thickness",
                        "wall:x:2+", "--thickness", "wall:y:2+", "--mirror", "x"]),
            ("domes", ["Continuous/domed-building.obj", "--size", "12", "12", "8", "--seed", "2",
                       "--grounded", "--detail", "dome=" + data("Continuous/dome.obj")]),
            ("flat", ["Continuous/two-objects2d.obj", "--size", "12", "12", "0", "--seed", "1"])):
        out = os.path.join(folder, name)
        done = run_msynth("synthesize", data(args[0]), *args[1:], "--outputs", "glb", "--out", out)
        if done.returncode != 0:
            sys.exit(done.stderr)
        files.append(os.path.join(out, "mesh.glb"))
    r = subprocess.run([node, os.path.join(HERE, "validate_gltf.js"), MODULES, *files],
                       capture_output=True, text=True, timeout=120)
    print(r.stdout + r.stderr)
    if r.returncode != 0:
        return 1
    reports = re.findall(r": (\d+) errors, (\d+) warnings", r.stdout)
    if len(reports) != len(files) or any(report != ("0", "0") for report in reports):
        print("FAILED: expected no errors and no warnings in %d files" % len(files))
        return 1
    print("glTF validator: %d files valid" % len(files))
    return 0


if __name__ == "__main__":
    sys.exit(main())
