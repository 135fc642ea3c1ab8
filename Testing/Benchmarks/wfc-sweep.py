#!/usr/bin/env python3
# SPDX-License-Identifier: BSD-3-Clause
"""Whole-process times of every overlapping and simple-tiled entry of WaveFunctionCollapse's
samples.xml at its own options and size (issue 45 item 3), msynth against fast-wfc's example
program (math-fehr/fast-wfc) when given, same run. Prints a Markdown table: per entry the
seconds of each (median of the seeds: wall, and CPU = user + system, which a loaded machine
inflates less), whether `msynth check` finds each picture valid, and the ratios fast-wfc /
msynth of both; then the totals.

Options map as WaveFunctionCollapse reads them: N -> --pattern, symmetry (8) -> --symmetry,
periodic -> --translate xy, periodicInput="False" -> --no-periodic-input, ground -> --ground,
size (48; width/height) -> --size, heuristic Scanline -> --order scanline (Entropy and MRV:
--order entropy), subset -> --subset. One picture per entry (screenshots is ignored). fast-wfc
gets the same entry in its own format (one samples.xml per entry, width/height, ground="-1"),
tries up to 10 times as its example does, and draws its own seed; its overlapping pictures are
checked with `msynth check` too (its tiled ones are not: it writes no labels).

  Testing/Benchmarks/wfc-sweep.py [--msynth BIN] [--fast-wfc BIN] [--data DIR] [--seeds S]
                                  [--only NAME] [--timeout SECONDS]
"""
import argparse
import os
import resource
import shutil
import statistics
import struct
import subprocess
import sys
import tempfile
import time
import xml.etree.ElementTree as ET

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))


def cpu_of_children():
    usage = resource.getrusage(resource.RUSAGE_CHILDREN)
    return usage.ru_utime + usage.ru_stime


def run(cmd, cwd=None, timeout=None, cpu=None):
    """Seconds of a whole process and whether it exited 0 (None seconds on timeout); its CPU
    seconds (user + system) are appended to the list @p cpu when given."""
    start, start_cpu = time.perf_counter(), cpu_of_children()
    try:
        p = subprocess.run(cmd, cwd=cwd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                           timeout=timeout)
    except subprocess.TimeoutExpired:
        return None, False, ""
    if cpu is not None:
        cpu.append(cpu_of_children() - start_cpu)
    return time.perf_counter() - start, p.returncode == 0, p.stdout.decode(errors="replace")


def png_width(path):
    with open(path, "rb") as f:
        head = f.read(24)
    return struct.unpack(">I", head[16:20])[0]


def entries(samples_xml):
    for e in ET.parse(samples_xml).getroot():
        if e.tag not in ("overlapping", "simpletiled"):
            continue
        a = dict(e.attrib)
        if a.get("textOutput") == "True":
            continue  # the same set again, as text: not a picture
        size = int(a.get("size", a.get("width", "48")))
        yield e.tag, a, size


def msynth_args(kind, a, size, data):
    true = lambda k, d="False": a.get(k, d) == "True"
    order = "scanline" if a.get("heuristic") == "Scanline" else "entropy"
    if kind == "overlapping":
        example = os.path.join(data, "samples", a["name"] + ".png")
        pattern = ["--pattern", a.get("N", "3"), "--symmetry", a.get("symmetry", "8")]
        if not true("periodicInput", "True"):
            pattern.append("--no-periodic-input")
        extra = ["--ground"] if true("ground") else []
    else:
        example = os.path.join(data, "tilesets", a["name"] + ".xml")
        pattern = ["--subset", a["subset"]] if "subset" in a else []
        extra = []
    translate = ["--translate", "xy"] if true("periodic") else []
    synth = [example, "--size", str(size), str(size), "1", "--order", order] + pattern + \
        translate + extra
    check = [example] + pattern + (["--translate", "xy"] if translate else []) + \
        (["--ground"] if extra else [])
    return synth, check


def fastwfc_dir(kind, a, size, data, tmp):
    """A folder with fast-wfc's samples.xml for this entry and its sample or tileset."""
    d = tempfile.mkdtemp(dir=tmp)
    os.makedirs(os.path.join(d, "samples"))
    os.makedirs(os.path.join(d, "results"))
    attrs = {k: v for k, v in a.items() if k in ("name", "N", "symmetry", "periodic",
                                                 "periodicInput", "subset")}
    attrs.update(width=str(size), height=str(size), screenshots="1")
    if kind == "overlapping":
        if a.get("ground") == "True":
            attrs["ground"] = "-1"
        shutil.copy(os.path.join(data, "samples", a["name"] + ".png"), os.path.join(d, "samples"))
    else:
        src = os.path.join(data, "tilesets", a["name"])
        dst = os.path.join(d, "samples", a["name"])
        shutil.copytree(src, dst)
        tree = ET.parse(os.path.join(data, "tilesets", a["name"] + ".xml"))
        first = sorted(f for f in os.listdir(src) if f.endswith(".png"))[0]
        tree.getroot().set("size", str(png_width(os.path.join(src, first))))
        tree.write(os.path.join(dst, "data.xml"))
    root = ET.Element("samples")
    ET.SubElement(root, kind, attrs)
    ET.ElementTree(root).write(os.path.join(d, "samples.xml"))
    return d


def label(kind, a, size):
    opts = []
    if kind == "overlapping":
        opts.append("N " + a.get("N", "3"))
        if a.get("symmetry", "8") != "8":
            opts.append("symmetry " + a["symmetry"])
        if a.get("periodicInput") == "False":
            opts.append("bounded input")
        if a.get("ground") == "True":
            opts.append("ground")
    else:
        opts.append("tiled" + (" " + a["subset"] if "subset" in a else ""))
    if a.get("periodic") == "True":
        opts.append("periodic")
    if a.get("heuristic") == "Scanline":
        opts.append("scan line")
    return "%s (%s, %d²)" % (a["name"], ", ".join(opts), size)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--msynth", default=os.path.join(ROOT, "build", "bin", "msynth"))
    ap.add_argument("--fast-wfc", default="")
    ap.add_argument("--data", default=os.path.join(ROOT, "..", "shared", "data",
                                                   "WaveFunctionCollapse"))
    ap.add_argument("--seeds", type=int, default=1)
    ap.add_argument("--only", default="")
    ap.add_argument("--timeout", type=float, default=600)
    o = ap.parse_args()
    tmp = tempfile.mkdtemp()
    total_ms = total_fw = total_ms_cpu = total_fw_cpu = 0.0
    slower = []
    print("| entry | msynth s | msynth CPU s | valid | fast-wfc s | fast-wfc CPU s | valid | "
          "fast-wfc / msynth | CPU ratio |")
    print("|---|---|---|---|---|---|---|---|---|")
    seen = set()
    try:
        for kind, a, size in entries(os.path.join(o.data, "samples.xml")):
            key = (kind, tuple(sorted(a.items())), size)
            if key in seen or (o.only and a["name"] != o.only):
                continue
            seen.add(key)
            synth, check = msynth_args(kind, a, size, o.data)
            times, cpus, valid = [], [], True
            for seed in range(1, o.seeds + 1):
                out = os.path.join(tmp, "ms")
                shutil.rmtree(out, ignore_errors=True)
                t, ok, _ = run([o.msynth, "synthesize"] + synth +
                               ["--seed", str(seed), "--out", out], timeout=o.timeout,
                               cpu=cpus)
                times.append(t if t is not None else o.timeout)
                model = os.path.join(out, "picture.png" if kind == "overlapping"
                                     else "labels.vti")
                valid = valid and ok and run([o.msynth, "check", check[0], model] +
                                             check[1:])[1]
            ms = statistics.median(times)
            ms_cpu = statistics.median(cpus) if cpus else o.timeout
            fw_cell, fw_cpu_cell, fw_valid, ratio, cpu_ratio = "–", "–", "–", "–", "–"
            if o.fast_wfc:
                d = fastwfc_dir(kind, a, size, o.data, tmp)
                fws, fw_cpus, fw_ok = [], [], True
                for _ in range(o.seeds):
                    t, ok, text = run([o.fast_wfc], cwd=d, timeout=o.timeout, cpu=fw_cpus)
                    fws.append(t if t is not None else o.timeout)
                    fw_ok = fw_ok and ok and "finished!" in text
                    if kind == "overlapping" and fw_ok:
                        pic = os.path.join(d, "results", a["name"] + "0.png")
                        fw_ok = run([o.msynth, "check", check[0], pic] + check[1:])[1]
                fw = statistics.median(fws)
                fw_cpu = statistics.median(fw_cpus) if fw_cpus else o.timeout
                fw_cell, fw_cpu_cell = "%.3f" % fw, "%.3f" % fw_cpu
                fw_valid = ("yes" if fw_ok else "no") if kind == "overlapping" else \
                    ("finished" if fw_ok else "failed")
                ratio = "%.1f×" % (fw / ms)
                cpu_ratio = "%.1f×" % (fw_cpu / max(ms_cpu, 1e-3))
                total_fw += fw
                total_fw_cpu += fw_cpu
                if fw < ms:
                    slower.append(a["name"])
            total_ms += ms
            total_ms_cpu += ms_cpu
            print("| %s | %.3f | %.3f | %s | %s | %s | %s | %s | %s |" % (
                label(kind, a, size), ms, ms_cpu, "yes" if valid else "no", fw_cell,
                fw_cpu_cell, fw_valid, ratio, cpu_ratio), flush=True)
        if o.fast_wfc:
            print("| **total** | **%.2f** | **%.2f** | | **%.2f** | **%.2f** | | **%.1f×** | "
                  "**%.1f×** |" % (total_ms, total_ms_cpu, total_fw, total_fw_cpu,
                                   total_fw / total_ms, total_fw_cpu / total_ms_cpu))
            print("\nmsynth slower (wall) on: %s" % (", ".join(slower) if slower else "none"))
        else:
            print("| **total** | **%.2f** | **%.2f** | | | | | | |" % (total_ms, total_ms_cpu))
    finally:
        shutil.rmtree(tmp, ignore_errors=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
