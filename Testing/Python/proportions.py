"""Object-type proportions of continuous models, measured without the solver's code (issue 29,
item 1): each type's share of the solid volume of a written model.vtp by the divergence theorem
over its polygons, against the same share of the example, computed from the OBJ text.

The matrix: every bundled multi-type example x {--grounded, --grounded + its documented
constraints} x seeds. A share passes when it is within TOLERANCE (relative) of the example's.

    /usr/bin/python3 Testing/Python/proportions.py [--size small|full|X Y Z] [--seeds 1-5]
        [--examples house,cottage] [--out DIR] [--threads N]

prints the table (one row per run) and exits 1 when a share falls outside the tolerance. It
needs MSYNTH_BIN (the msynth folder) and MSYNTH_DATA (Data/), as the tests set them; the full
sizes are the benchmark (Testing/Benchmarks/proportions.sh), the small ones the CI matrix
(test_proportions.py)."""
import argparse
import json
import os
import subprocess
import sys
import time

import numpy as np

TOLERANCE = 0.25
# name: (example, documented constraints (README, guide, gallery), small box, full box)
EXAMPLES = {
    "house": ("house.obj", ["--thickness", "wall:z", "--overhang", "roof", "--thickness", "wall:x:2+",
                            "--thickness", "wall:y:2+"], (16, 16, 8), (24, 24, 10)),
    "box-building": ("box-building.obj", ["--thickness", "building:z:6", "--thickness", "roof:z"],
                     (24, 24, 10), (48, 48, 10)),
    # Blocks of 8 spacings: the default 4 (4.2 units) holds no whole cottage (5.5 deep with its
    # porch), and with these constraints porches then stay one spacing deep.
    "cottage": ("cottage.obj", ["--thickness", "wall:z:2", "--overhang", "roof", "--thickness",
                                "wall:x:2+", "--thickness", "wall:y:2+", "--blocks", "8"],
                (12, 12, 8), (16, 16, 8)),
    "domed-building": ("domed-building.obj", ["--thickness", "wall:z:3"], (24, 24, 10),
                       (48, 48, 10)),
    "town": ("town.obj", ["--thickness", "wall:z:4", "--thickness", "shop:z:6", "--thickness",
                          "shoproof:z", "--thickness", "road:z", "--thickness", "tree:x",
                          "--thickness", "tree:y"], (24, 24, 6), (100, 100, 10)),
}


def read_obj(path):
    """Points and {type: [polygon]} of an OBJ example, types numbered as the reader numbers them
    (each distinct base name of 'o'/'g' lines, trailing digits and '._-' dropped, in order of
    appearance), with the names."""
    points, surfaces, current, names = [], {}, None, []
    with open(path) as f:
        for line in f:
            w = line.split()
            if not w or w[0].startswith("#"):
                continue
            if w[0] in ("o", "g"):
                base = w[1].rstrip("0123456789").rstrip("._-") or w[1]
                if base not in names:
                    names.append(base)
                current = names.index(base) + 1
            elif w[0] == "v":
                points.append([float(x) for x in w[1:4]])
            elif w[0] == "f":
                surfaces.setdefault(current or 1, []).append(
                    [int(x.split("/")[0]) - 1 for x in w[1:]])
    return np.array(points), surfaces, {i + 1: n for i, n in enumerate(names)}


def signed_volume(points, polygon):
    """The polygon's contribution to the enclosed volume (fan from its first point)."""
    c = points[polygon]
    return sum(float(np.dot(c[0], np.cross(c[k], c[k + 1]))) for k in range(1, len(c) - 1)) / 6


def shares(volumes):
    """{type: share of the solid volume} of {type: volume} (type 0, empty space, left out)."""
    solid = {t: v for t, v in volumes.items() if t > 0}
    total = sum(solid.values())
    return {t: (v / total if total > 0 else 0.0) for t, v in solid.items()}


def example_shares(path):
    """{type: share} of an OBJ example, and the type names."""
    points, surfaces, names = read_obj(path)
    volumes = {t: sum(signed_volume(points, p) for p in polys) for t, polys in surfaces.items()}
    return shares(volumes), names


def model_shares(vtp):
    """{type: share} of a continuous model.vtp: polygons are oriented from InsideType to
    OutsideType, so each adds its volume term to the inside type and takes it from the outside
    one. Read with VTK's own XML reader."""
    from vtkmodules.util.numpy_support import vtk_to_numpy
    from vtkmodules.vtkIOXML import vtkXMLPolyDataReader
    reader = vtkXMLPolyDataReader()
    reader.SetFileName(vtp)
    reader.Update()
    poly = reader.GetOutput()
    volumes = {}
    if poly.GetNumberOfCells() == 0:
        return {}
    points = vtk_to_numpy(poly.GetPoints().GetData()).astype(float)
    ids = vtk_to_numpy(poly.GetPolys().GetConnectivityArray())
    offsets = vtk_to_numpy(poly.GetPolys().GetOffsetsArray())
    inside = vtk_to_numpy(poly.GetCellData().GetArray("InsideType"))
    outside = vtk_to_numpy(poly.GetCellData().GetArray("OutsideType"))
    # Vectorized fan: triangles (p0, pk, pk+1) of every polygon.
    sizes = np.diff(offsets)
    first = np.repeat(offsets[:-1], sizes - 2)
    cell = np.repeat(np.arange(len(sizes)), sizes - 2)
    within = np.arange(len(first)) - np.repeat(np.cumsum(sizes - 2) - (sizes - 2), sizes - 2)
    a = points[ids[first]]
    b = points[ids[first + 1 + within]]
    c = points[ids[first + 2 + within]]
    v = np.einsum("ij,ij->i", a, np.cross(b, c)) / 6
    per_cell = np.bincount(cell, weights=v, minlength=len(sizes))
    for t in set(inside.tolist()) | set(outside.tolist()):
        volumes[int(t)] = float(per_cell[inside == t].sum() - per_cell[outside == t].sum())
    return shares(volumes)


def run(name, size, seed, constrained, out, threads=0, extra=()):
    """Synthesizes example `name` (grounded; with its constraints when `constrained`) into
    `out` and returns (example shares, model shares, statistics, seconds, names)."""
    example, constraints, _, _ = EXAMPLES[name]
    path = os.path.join(os.environ["MSYNTH_DATA"], "Continuous", example)
    command = [os.path.join(os.environ["MSYNTH_BIN"], "msynth"), "synthesize", path,
               "--size", *[str(s) for s in size], "--seed", str(seed), "--grounded",
               "--outputs", "mesh", "--threads", str(threads), "--out", out,
               *(constraints if constrained else []), *extra]
    start = time.monotonic()
    done = subprocess.run(command, capture_output=True, text=True)
    seconds = time.monotonic() - start
    if done.returncode != 0:
        raise RuntimeError(" ".join(command) + ": " + done.stderr.strip())
    with open(os.path.join(out, "statistics.json")) as f:
        stats = json.load(f)
    target, names = example_shares(path)
    return target, model_shares(os.path.join(out, "model.vtp")), stats, seconds, names


def failures(target, got):
    """The types whose share is not within TOLERANCE (relative) of the example's."""
    return [t for t, want in target.items()
            if want > 0 and abs(got.get(t, 0.0) - want) > TOLERANCE * want]


def parse_seeds(text):
    if "-" in text:
        low, high = text.split("-")
        return list(range(int(low), int(high) + 1))
    return [int(s) for s in text.split(",")]


def main(argv):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--size", nargs="+", default=["small"])
    parser.add_argument("--seeds", default="1-5")
    parser.add_argument("--examples", default=",".join(EXAMPLES))
    parser.add_argument("--out", default=os.path.join(os.environ.get("MSYNTH_TMP", "/tmp"),
                                                      "proportions"))
    parser.add_argument("--threads", type=int, default=0)
    parser.add_argument("--json", help="also write the rows as JSON here")
    args = parser.parse_args(argv)
    rows, bad = [], 0
    print("%-15s %-11s %4s %6s %7s %7s  %s" % ("example", "constraints", "seed", "sec", "emptied",
                                                "redrawn", "shares (example)"))
    for name in args.examples.split(","):
        _, _, small, full = EXAMPLES[name]
        size = small if args.size == ["small"] else full if args.size == ["full"] else \
            tuple(int(s) for s in args.size)
        for constrained in (False, True):
            if constrained and not EXAMPLES[name][1]:
                continue
            for seed in parse_seeds(args.seeds):
                out = os.path.join(args.out, "%s-%d-%d" % (name, int(constrained), seed))
                target, got, stats, seconds, names = run(name, size, seed, constrained, out,
                                                         args.threads)
                wrong = failures(target, got)
                bad += len(wrong)
                cells = ["%s %.2f (%.2f)%s" % (names.get(t, t), got.get(t, 0.0), want,
                                               " FAIL" if t in wrong else "")
                         for t, want in sorted(target.items())]
                emptied = stats.get("ProportionVolumeRemoved", 0.0)
                redrawn = stats.get("ProportionBlocksRedrawn", 0)
                print("%-15s %-11s %4d %6.2f %7.2f %7d  %s" % (
                    name, "documented" if constrained else "grounded", seed, seconds, emptied,
                    redrawn, ", ".join(cells)))
                rows.append({"example": name, "constrained": constrained, "seed": seed,
                             "size": list(size), "seconds": seconds,
                             "shares": {names.get(t, str(t)): got.get(t, 0.0) for t in target},
                             "targets": {names.get(t, str(t)): w for t, w in target.items()},
                             "failed": [names.get(t, str(t)) for t in wrong],
                             "emptied": emptied, "redrawn": redrawn,
                             "unsteered": stats.get("UnsteeredTypes", "")})
                sys.stdout.flush()
    print("%-15s %-11s %6s %8s %8s %8s" % ("example", "constraints", "within", "emptied",
                                           "redrawn", "sec/run"))
    for name in args.examples.split(","):
        for constrained in (False, True):
            cell = [r for r in rows if r["example"] == name and r["constrained"] == constrained]
            if cell:
                print("%-15s %-11s %3d/%-2d %8.2f %8.1f %8.2f" % (
                    name, "documented" if constrained else "grounded",
                    sum(1 for r in cell if not r["failed"]), len(cell),
                    sum(r["emptied"] for r in cell) / len(cell),
                    sum(r["redrawn"] for r in cell) / len(cell),
                    sum(r["seconds"] for r in cell) / len(cell)))
    print("%d of %d runs within %d %% on every type" %
          (sum(1 for r in rows if not r["failed"]), len(rows), round(TOLERANCE * 100)))
    if args.json:
        with open(args.json, "w") as f:
            json.dump(rows, f, indent=1)
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
