#!/usr/bin/env python3
"""The published sets as the project's suite (issue 44, item 1): every entry of
WaveFunctionCollapse's samples.xml (overlapping and simple-tiled, at its own options, as `msynth
batch` runs them), every WaveFunctionCollapse tileset and every MarkovJunior voxel tileset (at
msynth's default options), each in three forms:

- whole: one run at the entry's size S (samples.xml's size; tilesets 24 x 24; MarkovJunior
  10 x 10 x 6, or 24 x 24 x 1 for a flat set);
- blocks: the same world in blocks of S/2 (at least 8 sites; 3D sets 5 x 5 x 3);
- region: the middle half of that world (x and y) computed alone with --region, which must
  equal the blocks run's sites there; it is measured against the whole run's same box.

Each output is checked by `msynth check` (independent of the solver) and measured against the
whole run: the form is varied when it has at least 80 % of the whole run's distinct labels and
its most frequent label's share is at most 1.25 times the whole run's. Prints a Markdown table
and exits 1 when a cell fails.

  Testing/Benchmarks/published-sweep.py [--data DIR] [--msynth BIN] [--small] [--only TEXT ...]
                                        [--seed N] [--threads N] [--keep DIR]

--data defaults to ../shared/data beside the repository (or $MSYNTH_PUBLISHED_DATA); without
the data the script prints "skipped: published data not found" and exits 0. --small caps the
sizes (CI): S at most 24 (an odd S stays odd), 3D sets 8 x 8 x 4.
"""
import argparse
import os
import shutil
import subprocess
import sys
import tempfile
import time
import xml.etree.ElementTree as ET

import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
DISTINCT, SHARE = 0.8, 1.25


def published_data(given=None):
    """The folder of the published sets: GIVEN, $MSYNTH_PUBLISHED_DATA or ../shared/data."""
    for folder in (given, os.environ.get("MSYNTH_PUBLISHED_DATA"),
                   os.path.join(ROOT, "..", "shared", "data")):
        if folder and os.path.isdir(os.path.join(folder, "WaveFunctionCollapse")):
            return os.path.abspath(folder)
    return None


class Entry:
    """One published entry: how to synthesize it and how to check it."""

    def __init__(self, name, example, size, options, check, kind):
        self.name, self.example, self.size = name, example, size
        self.options, self.check, self.kind = options, check, kind
        self.pattern = 0  # an image sample's N: sites = pixels - N + 1 where it does not repeat
        self.periodic = False


def wfc_entries(data, small):
    """samples.xml's entries with the options `msynth batch` gives them, then every tileset."""
    folder = os.path.join(data, "WaveFunctionCollapse")
    entries = []
    for element in ET.parse(os.path.join(folder, "samples.xml")).getroot():
        a = element.attrib
        periodic = a.get("periodic", "False") == "True"
        common = ["--order", "entropy", "--choice", "frequency"]
        translate = ["--translate", "xy"] if periodic else []
        if element.tag == "overlapping":
            size = int(a.get("size", 48))
            n, sym = a.get("N", "3"), a.get("symmetry", "8")
            sample = os.path.join(folder, "samples", a["name"] + ".png")
            image = ["--pattern", n, "--symmetry", sym]
            if a.get("periodicInput", "True") == "False":
                image.append("--no-periodic-input")
            ground = ["--ground"] if a.get("ground", "False") == "True" else []
            label = "%s N=%s sym=%s%s%s%s size=%d" % (
                a["name"], n, sym, " periodic" if periodic else "",
                " ground" if ground else "", " no-periodic-input" if "--no-periodic-input"
                in image else "", size)
            e = Entry(label, sample, size, common + image + ground + translate,
                      image + ground + translate, "overlapping")
            e.pattern = int(n)
        elif element.tag == "simpletiled":
            size = int(a.get("size", 24))
            xml = os.path.join(folder, "tilesets", a["name"] + ".xml")
            subset = ["--subset", a["subset"]] if "subset" in a else []
            label = "%s%s%s size=%d" % (a["name"], " (%s)" % a["subset"] if subset else "",
                                        " periodic" if periodic else "", size)
            e = Entry(label, xml, size, common + subset + translate, subset, "tileset")
        else:
            continue
        e.periodic = periodic
        if small:  # an odd size stays odd (Chess size=47)
            e.size = min(e.size, 24 - e.size % 2)
        entries.append(e)
    for xml in sorted(os.listdir(os.path.join(folder, "tilesets"))):
        if xml.endswith(".xml"):
            name = xml[:-4]
            entries.append(Entry("%s (all tiles, defaults)" % name,
                                 os.path.join(folder, "tilesets", xml), 24, [],
                                 [], "tileset"))
    return entries


def mj_entries(data, small, msynth):
    """MarkovJunior's voxel tilesets at the default options: 3D, or flat where the rules are
    (the run says so), tiles from the first subfolder where the set keeps them in several."""
    folder = os.path.join(data, "MarkovJunior", "tilesets")
    entries = []
    for xml in sorted(os.listdir(folder)):
        if not xml.endswith(".xml"):
            continue
        name, path = xml[:-4], os.path.join(folder, xml)
        tiles = []
        own = os.path.join(folder, name)
        subfolders = sorted(d for d in os.listdir(own) if os.path.isdir(os.path.join(own, d)))
        if subfolders and not any(f.endswith(".vox") for f in os.listdir(own)):
            tiles = ["--tiles", os.path.join(name, subfolders[0])]
        size = (8, 8, 4) if small else (10, 10, 6)
        probe = tempfile.mkdtemp()
        done = run(msynth, "synthesize", path, "--size", *map(str, size), *tiles, "--out",
                   os.path.join(probe, "out"), "--outputs", "labels", "--attempts", "1")
        shutil.rmtree(probe, ignore_errors=True)
        flat = "(size" in done.stderr and "1)" in done.stderr
        label = name + (" (%s)" % tiles[1] if tiles else "") + (" flat" if flat else "")
        e = Entry(label, path, (24, 24, 1) if flat else size,
                  tiles, tiles, "voxel")
        entries.append(e)
    return entries


def run(msynth, *args):
    return subprocess.run([msynth, *args], capture_output=True, text=True, timeout=1800)


def read_labels(path):
    from vtkmodules.util.numpy_support import vtk_to_numpy
    from vtkmodules.vtkIOXML import vtkXMLImageDataReader
    reader = vtkXMLImageDataReader()
    reader.SetFileName(path)
    reader.Update()
    image = reader.GetOutput()
    nx, ny, nz = image.GetDimensions()
    return vtk_to_numpy(image.GetPointData().GetArray("Label")).reshape(nz, ny, nx).copy()


def variety(labels):
    _, counts = np.unique(labels, return_counts=True)
    return len(counts), counts.max() / counts.sum()


class Sweep:
    def __init__(self, args):
        self.msynth, self.seed, self.threads = args.msynth, str(args.seed), args.threads
        self.keep = args.keep

    def sizes(self, e):
        """The size of the runs, their block and the region (sites, X0 Y0 Z0 X1 Y1 Z1)."""
        size = list(e.size) if isinstance(e.size, tuple) else [e.size, e.size, 1]
        if size[2] > 1:
            block = [max(3, size[0] // 2), max(3, size[1] // 2), max(2, size[2] // 2)]
        else:
            block = [max(8, size[0] // 2), max(8, size[1] // 2), 1]
        sites = [w - (0 if e.periodic or not e.pattern else e.pattern - 1) for w in size]
        region = [sites[0] // 4, sites[1] // 4, 0, sites[0] - sites[0] // 4,
                  sites[1] - sites[1] // 4, size[2]]
        return size, block, region

    def synthesize(self, e, folder, size, extra):
        outputs = {"overlapping": "labels,picture", "tileset": "labels",
                   "voxel": "labels,vox"}[e.kind]
        began = time.monotonic()
        done = run(self.msynth, "synthesize", e.example, "--size", *map(str, size), "--seed",
                   self.seed, *e.options, *extra, "--outputs", outputs, "--out", folder,
                   *(["--threads", str(self.threads)] if self.threads else []))
        seconds = time.monotonic() - began
        if done.returncode != 0:
            lines = done.stderr.strip().splitlines() or ["exit %d" % done.returncode]
            return None, lines[-1].replace("msynth: error: ", ""), seconds
        return read_labels(os.path.join(folder, "labels.vti")), None, seconds

    def check(self, e, folder, region):
        if e.kind == "overlapping":
            args = list(e.check)
            if region:  # the region's picture does not repeat, nor stand on the ground
                args = [a for a in args if a not in ("--translate", "xy", "--ground")]
            done = run(self.msynth, "check", e.example, os.path.join(folder, "picture.png"), *args)
        elif e.kind == "voxel":
            done = run(self.msynth, "check", e.example, os.path.join(folder, "model.vox"),
                       *e.check)
        else:
            done = run(self.msynth, "check", e.example, os.path.join(folder, "labels.vti"),
                       *e.check)
        if done.returncode == 0:
            return None
        text = (done.stdout + done.stderr).strip().splitlines()
        return "invalid: " + (text[-1] if text else "exit %d" % done.returncode)

    def entry(self, e, work):
        """The row of entry @p e: whole, blocks and region cells, and whether all are good."""
        size, block, region = self.sizes(e)
        cells, good = [], True
        labels, error, seconds = self.synthesize(e, os.path.join(work, "whole"), size, [])
        if labels is None:
            return ["error: " + error, "–", "–"], False, (size, block)
        problem = self.check(e, os.path.join(work, "whole"), False)
        reference = variety(labels)
        cells.append("%s%d, %.2f, %.1f s" % (problem + "; " if problem else "", reference[0],
                                             reference[1], seconds))
        good &= problem is None
        blocks, error, seconds = self.synthesize(e, os.path.join(work, "blocks"), size,
                                                 ["--block", *map(str, block)])
        cells.append(self.form(e, os.path.join(work, "blocks"), blocks, error, seconds,
                               reference, False))
        good &= cells[-1].startswith("ok")
        part, error, seconds = self.synthesize(e, os.path.join(work, "region"), size,
                                               ["--block", *map(str, block), "--region",
                                                *map(str, region)])
        box = (slice(region[2], region[5]), slice(region[1], region[4]),
               slice(region[0], region[3]))
        if part is not None and blocks is not None:
            if part.shape != blocks[box].shape or not np.array_equal(part, blocks[box]):
                error, part = "differs from the blocks run's sites", None
        # against the whole run's same box: as many sites
        cells.append(self.form(e, os.path.join(work, "region"), part, error, seconds,
                               variety(labels[box]), True))
        good &= cells[-1].startswith("ok") or cells[-1].startswith("n/a")
        return cells, good, (size, block)

    def form(self, e, folder, labels, error, seconds, reference, region):
        if labels is None:
            if region and "takes no symmetry" in (error or "") and e.periodic:
                return "n/a: periodic (a region of a repeating world needs all of it)"
            if region and "takes no symmetry" in (error or "") and "--ground" in e.options:
                return "n/a: --ground (a guide over the whole world)"
            return "error: " + (error or "")
        problem = self.check(e, folder, region)
        n, share = variety(labels)
        varied = n >= DISTINCT * reference[0] and share <= SHARE * reference[1]
        verdict = problem or ("ok" if varied else "not varied")
        return "%s: %d, %.2f, %.1f s" % (verdict, n, share, seconds)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--data")
    parser.add_argument("--msynth", default=os.path.join(ROOT, "build", "bin", "msynth"))
    parser.add_argument("--small", action="store_true")
    parser.add_argument("--only", nargs="*", default=[])
    parser.add_argument("--seed", type=int, default=1)
    parser.add_argument("--threads", type=int, default=0)
    parser.add_argument("--keep")
    args = parser.parse_args()
    data = published_data(args.data)
    if not data:
        print("skipped: published data not found")
        return 0
    entries = wfc_entries(data, args.small) + mj_entries(data, args.small, args.msynth)
    if args.only:
        entries = [e for e in entries if any(e.name.startswith(o) for o in args.only)]
    print("| entry | whole: labels, top share, time | blocks | region |")
    print("|---|---|---|---|")
    failed, tally = [], {"ok": 0, "n/a": 0, "cells": 0}
    work = args.keep or tempfile.mkdtemp(prefix="msynth-sweep-")
    sweep = Sweep(args)
    began = time.monotonic()
    for i, e in enumerate(entries):
        folder = os.path.join(work, "%02d" % (i + 1))
        shutil.rmtree(folder, ignore_errors=True)
        os.makedirs(folder)
        cells, good, sizes = sweep.entry(e, folder)
        where = " (%s in %s)" % ("x".join(map(str, sizes[0])), "x".join(map(str, sizes[1])))
        print("| %s%s | %s |" % (e.name, where, " | ".join(cells)), flush=True)
        for c in cells[1:]:
            tally["cells"] += 1
            tally["ok"] += c.startswith("ok")
            tally["n/a"] += c.startswith("n/a")
        if not good:
            failed.append(e.name)
        if not args.keep:
            shutil.rmtree(folder, ignore_errors=True)
    print("\n%d entries, %d block and region cells: %d valid and varied, %d n/a; %d entries "
          "failing%s; %.0f s" % (len(entries), tally["cells"], tally["ok"], tally["n/a"],
                                 len(failed), (": " + "; ".join(failed)) if failed else "",
                                 time.monotonic() - began))
    if not args.keep:
        shutil.rmtree(work, ignore_errors=True)
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
