#!/usr/bin/env python3
# SPDX-License-Identifier: BSD-3-Clause
"""The tables of Documentation/performance.md that come from whole `msynth` commands rather than
from a Google Benchmark filter: each subcommand runs its commands under
`/usr/bin/time -f '%e %M %U %S %R'` (wall seconds, peak resident KB, user and system CPU seconds,
minor page faults), reads each run's statistics.json, and prints the Markdown table, preceded by
the load average before and after (the machine is shared: say the load next to the table).

  Testing/Benchmarks/perf-tables.py SUBCOMMAND [--msynth BIN] [--small] [--runs N] [--keep DIR]
                                    [--data DIR] [--castle FILE]

Subcommands (performance.md's section in brackets):
  whole-runs     tileset and voxel-tileset runs with the outputs users get ("Whole runs")
  startup        the fixed cost of a process: --version, 16² runs, the castle ("Whole runs")
  startup-cost   where a 16² run's instructions go, by callgrind: loading, initialisers, the
                 synthesis, each output, exit ("Whole runs"; needs valgrind)
  backtracks     Lines in 32² blocks: backtracking and the overlap ("Blocks, threads and
                 backtracking at scale")
  continuous     the TVCG examples and the house at 48 x 48 x 10, all outputs ("Continuous
                 synthesis", as the next three)
  threads        the house at 48 x 48 x 10 on 1 and 2 threads, stage seconds
  town           the gallery's town at 100 x 100 x 10
  exports        mesh.glb and model.vox of the README's houses and the town
  stream         a world in memory against a streamed one ("Worlds")
  regions        regions of a 10^12-site world, and pinned sites ("Worlds")
  connected      Circuits with --connected at 128² to 2048² ("Tilesets")
  failed-blocks  failed blocks with and without backtracking and repair, 20 seeds ("Tilesets")
  render-grids   model.vdb's render grids at 10^7 sites ("OpenVDB")
  all            every one of the above, in that order

--small runs every subcommand at small sizes (seconds each): to check the script, not to measure.
--runs N repeats each command N times and prints min–max (default 1; startup: 5).
--data is the published sets' folder (../shared/data beside the repository or
$MSYNTH_PUBLISHED_DATA; rows that need it are left out without it); --castle the original
program's castle.txt (merrell42/model-synthesis, samples/castle.txt; its rows are left out
without it). Only the standard library: the render grids' writes run the build's Python
package in a child process.
"""
import argparse
import json
import os
import re
import shutil
import statistics
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
DATA = os.path.join(ROOT, "Data")


def published_data(given=None):
    """The folder of the published sets: GIVEN, $MSYNTH_PUBLISHED_DATA or ../shared/data (as
    published-sweep.py finds it)."""
    for folder in (given, os.environ.get("MSYNTH_PUBLISHED_DATA"),
                   os.path.join(ROOT, "..", "shared", "data")):
        if folder and os.path.isdir(os.path.join(folder, "WaveFunctionCollapse")):
            return os.path.abspath(folder)
    return None


TOWN = ("Data/Continuous/town.obj --size {size} --seed 1 --grounded --thickness wall:z:4 "
        "--thickness shop:z:6 --thickness shoproof:z --thickness road:z --thickness tree:x "
        "--thickness tree:y --detail tree=Data/Continuous/tree.obj")
HOUSES = ("Data/Continuous/house.obj --size 24 24 10 --seed 3 --grounded --thickness wall:z "
          "--overhang roof --thickness wall:x:2+ --thickness wall:y:2+ --mirror x")


class Run:
    """One finished command: its /usr/bin/time figures, statistics.json and output folder."""

    def __init__(self, wall, peak_kb, user, system, faults, stats, out, code, text):
        self.wall, self.peak_mb, self.cpu = wall, peak_kb / 1024.0, user + system
        self.user, self.system, self.faults = user, system, faults
        self.stats, self.out, self.code, self.text = stats, out, code, text

    def stage(self, name):
        return self.stats.get("StageSeconds", {}).get(name)

    def size_mb(self, name):
        path = os.path.join(self.out, name)
        return os.path.getsize(path) / 1e6 if os.path.isfile(path) else None


class Tables:
    def __init__(self, args):
        self.args = args
        self.msynth = os.path.abspath(args.msynth)
        self.build = os.path.dirname(os.path.dirname(self.msynth))
        self.scratch = args.keep or tempfile.mkdtemp(prefix="perf-tables-")
        os.makedirs(self.scratch, exist_ok=True)
        self.data = published_data(args.data)
        self.count = 0

    # -- running ---------------------------------------------------------------------------------
    def timed(self, command, out=None, env=None):
        """Runs @p command (a list) under /usr/bin/time from the repository root."""
        timing = os.path.join(self.scratch, "time.txt")
        done = subprocess.run(["/usr/bin/time", "-f", "%e %M %U %S %R", "-o", timing] + command,
                              cwd=ROOT, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                              text=True, env=env)
        with open(timing) as f:
            last = f.read().strip().splitlines()[-1].split()
        wall, peak, user, system, faults = (float(v) for v in last)
        stats = {}
        if out and os.path.isfile(os.path.join(out, "statistics.json")):
            with open(os.path.join(out, "statistics.json")) as f:
                stats = json.load(f)
        return Run(wall, peak, user, system, faults, stats, out, done.returncode, done.stdout)

    def msynth_runs(self, arguments, runs=None, ok=True):
        """`msynth ARGUMENTS --out DIR` @p runs times (default --runs); the list of Runs."""
        result = []
        for _ in range(runs or self.args.runs):
            self.count += 1
            out = os.path.join(self.scratch, "run%d" % self.count)
            shutil.rmtree(out, ignore_errors=True)
            run = self.timed([self.msynth] + arguments.split() + ["--out", out], out)
            if ok and run.code != 0:
                sys.exit("perf-tables: msynth %s failed:\n%s" % (arguments, run.text[-3000:]))
            result.append(run)
        return result

    def check(self, run, *extra):
        """Whether `msynth check` passes the run's labels against its example (for tilesets)."""
        example = run.stats.get("example")
        labels = os.path.join(run.out, "labels.vti")
        done = subprocess.run([self.msynth, "check", os.path.join(ROOT, example), labels] +
                              list(extra), cwd=ROOT, capture_output=True, text=True)
        return done.returncode == 0, done.stdout + done.stderr

    # -- printing --------------------------------------------------------------------------------
    @staticmethod
    def load():
        with open("/proc/loadavg") as f:
            return " ".join(f.read().split()[:3])

    def table(self, title, header, rows_of):
        """Prints the table of @p rows_of (a generator of row lists), with the load around it."""
        print("\n<!-- perf-tables.py %s%s: load before %s -->" % (
            title, " --small" if self.args.small else "", self.load()))
        print("| " + " | ".join(header) + " |")
        print("|" + "---|" * len(header))
        sys.stdout.flush()
        for row in rows_of:
            print("| " + " | ".join(str(c) for c in row) + " |")
            sys.stdout.flush()
        print("<!-- load after %s -->" % self.load())
        if not self.args.keep:  # the outputs of the table's runs (GBs for some: town, stream)
            for name in os.listdir(self.scratch):
                if name.startswith("run"):
                    shutil.rmtree(os.path.join(self.scratch, name), ignore_errors=True)


def seconds(v):
    """A duration as the tables write it: three significant figures, at most."""
    if v is None:
        return "–"
    if v < 0.1:
        return "%.3f" % v
    if v < 10:
        return "%.2f" % v
    return "%.1f" % v if v < 100 else "%.0f" % v


def spread(values, show=seconds):
    """One figure, or min–max of several."""
    values = [v for v in values if v is not None]
    if not values:
        return "–"
    lo, hi = min(values), max(values)
    return show(lo) if show(lo) == show(hi) else "%s–%s" % (show(lo), show(hi))


def megabytes(v):
    if v is None:
        return "–"
    return "%.0f" % v if v >= 10 else ("%.1f" % v if v >= 1 else "%.2f" % v)


def count(v):
    return "{:,}".format(int(v))


# -- subcommands --------------------------------------------------------------------------------
def whole_runs(t):
    """Tileset runs with the outputs users get: wall, CPU, peak, synthesis, what was written."""
    small = t.args.small
    lines = "Data/Tilesets/Lines.xml --seed 1"
    rows = [
        ("%s --size 256 256 1 --block 32 32 1" % lines, 256 * 256, ["labels.vti", "picture.png"]),
        ("%s --size 256 256 1 --block 32 32 1 --outputs labels,picture,mesh,vdb" % lines,
         256 * 256, ["labels.vti", "picture.png", "mesh.vtp", "model.vdb"]),
    ]
    n, m, big = (300, 500, 500) if small else (1000, 2000, 3163)
    rows += [
        ("%s --size %d %d 1" % (lines, n, n), n * n, ["labels.vti", "picture.png"]),
        ("%s --size %d %d 1 --block 32 32 1" % (lines, n, n), n * n, ["labels.vti", "picture.png"]),
        ("%s --size %d %d 1" % (lines, m, m), m * m, ["picture.png"]),
        ("%s --size %d %d 1 --outputs labels" % (lines, big, big), big * big, ["labels.vti"]),
    ]
    p = "16 16 8" if small else "64 64 32"
    pipes = "Data/Tilesets/Pipes.xml --size %s --block 16 16 16 --seed 1" % p
    rows += [("%s --outputs labels" % pipes, None, ["labels.vti"]),
             ("%s --outputs labels,vox" % pipes, None, ["model.vox"]),
             (pipes, None, ["mesh.vtp", "model.vdb"])]
    header = ["`msynth synthesize` …", "sites", "wall s", "CPU s", "peak MB", "synthesis s",
              "files (MB)"]

    def gen():
        for command, sites, files in rows:
            runs = t.msynth_runs("synthesize " + command)
            if sites is None:
                size = runs[0].stats.get("size", [0, 0, 0])
                sites = size[0] * size[1] * size[2]
            written = ", ".join("%s %s" % (f, megabytes(runs[0].size_mb(f))) for f in files)
            yield ["`%s`" % command.replace("Data/Tilesets/", ""), count(sites),
                   spread(r.wall for r in runs), spread(r.cpu for r in runs),
                   spread((r.peak_mb for r in runs), megabytes),
                   spread(r.stats.get("Seconds") for r in runs), written]
    t.table("whole-runs", header, gen())


def startup(t):
    """The fixed cost of a process: CPU and minor page faults, median of --runs (default 5)."""
    runs = t.args.runs if t.args.runs > 1 else 5
    rows = [("`/bin/true`", ["/bin/true"], None), ("`msynth --version`", [t.msynth, "--version"],
                                                     None)]
    if t.data:
        wfc = os.path.join(t.data, "WaveFunctionCollapse")
        rows.append(("Knots Standard 16² (tiles)", "%s/tilesets/Knots.xml --subset Standard "
                     "--size 16 16 1 --seed 1" % wfc, True))
        rows.append(("Cat sample 16² (N 3)", "%s/samples/Cat.png --pattern 3 --symmetry 2 "
                     "--translate xy --size 16 16 1 --seed 1" % wfc, True))
    if t.args.castle:
        size = "20 20 10" if t.args.small else "40 40 10"
        rows.append(("castle %s, `--outputs txt`" % size, "%s --size %s --seed 1 --outputs txt" %
                     (os.path.abspath(t.args.castle), size), True))
        rows.append(("castle %s, default outputs" % size, "%s --size %s --seed 1" %
                     (os.path.abspath(t.args.castle), size), True))

    def gen():
        for name, command, is_synthesis in rows:
            if is_synthesis:
                done = t.msynth_runs("synthesize " + command, runs)
            else:
                done = [t.timed(command) for _ in range(runs)]
            yield [name, "%.0f" % (1000 * statistics.median(r.cpu for r in done)),
                   "%.0f" % (1000 * statistics.median(r.wall for r in done)),
                   count(statistics.median(r.faults for r in done))]
    t.table("startup", ["process", "CPU ms", "wall ms", "minor page faults"], gen())


# Where startup-cost puts a function's inclusive instructions (callgrind_annotate --inclusive):
# the parts in the table's order, each the first function matching its pattern.
COST_PARTS = [
    ("loading: mapping, relocation, symbol binding (`ld.so` before `main`)", r"rtld\.c:_dl_start "),
    ("libraries' initialisers (static constructors)", r"dl-init\.c:_dl_init "),
    ("`main`", r"\?\?\?:main "),
    ("  synthesis filter: example, rules, solve", r"vtkMSDiscreteSynthesis::RequestData\("),
    ("    of which the engine's solve", r"msynth::Synthesize\(msynth::AdjacencyRules"),
    ("  writing `labels.vti`", r"WriteXML<vtkXMLImageDataWriter"),
    ("  writing `picture.png`", r"msynth::cli::WritePicture\("),
    ("exit: destructors, unmapping", r"exit\.c:exit "),
    ("symbol binding on first calls (within the above)", r"_dl_runtime_resolve"),
]


def callgrind_parts(t, arguments):
    """Instructions of one `msynth ARGUMENTS` under callgrind: the total and COST_PARTS."""
    t.count += 1
    out = os.path.join(t.scratch, "run%d" % t.count)
    profile = os.path.join(t.scratch, "callgrind.%d" % t.count)
    done = subprocess.run(["valgrind", "--tool=callgrind", "--callgrind-out-file=" + profile,
                           t.msynth] + arguments.split() + ["--out", out], cwd=ROOT,
                          capture_output=True, text=True)
    if done.returncode != 0:
        sys.exit("perf-tables: callgrind of msynth %s failed:\n%s" % (arguments,
                                                                       done.stderr[-3000:]))
    text = subprocess.run(["callgrind_annotate", "--inclusive=yes", "--threshold=100", profile],
                          capture_output=True, text=True, check=True).stdout
    lines = [(int(m.group(1).replace(",", "")), m.group(2)) for m in
             re.finditer(r"^\s*([\d,]+) \([^)]*\)\s+(.*)$", text, re.M)]
    total = next(n for n, what in lines if what.startswith("PROGRAM TOTALS"))
    parts = []
    for _, pattern in COST_PARTS:
        found = [n for n, what in lines if re.search(pattern, what)]
        parts.append(found[0] if found else 0)
    return total, parts


def startup_cost(t):
    """What a 16² run costs and where: instructions by part (valgrind's callgrind, exact and
    independent of the load), CPU and wall milliseconds and minor page faults (the kernel's
    share: medians of 5 runs)."""
    if not shutil.which("valgrind") or not shutil.which("callgrind_annotate"):
        sys.exit("perf-tables: startup-cost needs valgrind (Debian package 'valgrind')")
    sample = (os.path.join(t.data, "WaveFunctionCollapse", "samples", "Flowers.png") if t.data
              else os.path.join(DATA, "Samples", "Maze.png"))
    name = os.path.splitext(os.path.basename(sample))[0]
    picture = ("%s --pattern 3 --symmetry 2 --ground --translate x --size 16 16 1 --seed 1" %
               sample)
    columns = [("%s 16²" % name, picture),
               ("%s 16², `--outputs picture`" % name, picture + " --outputs picture"),
               ("Lines 16² (tileset)", "Data/Tilesets/Lines.xml --size 16 16 1 --seed 1")]
    measured = [callgrind_parts(t, "synthesize " + command) for _, command in columns]
    timed = [t.msynth_runs("synthesize " + command, 1 if t.args.small else 5)
             for _, command in columns]

    def millions(n):
        return "%.1f M" % (n / 1e6) if n else "–"

    def gen():
        for i, (part, _) in enumerate(COST_PARTS):
            yield [part.replace("  ", "&nbsp;&nbsp;")] + [millions(parts[i])
                                                          for _, parts in measured]
        yield ["**instructions in all**"] + ["**%s**" % millions(total) for total, _ in measured]
        def median(runs, figure):
            return statistics.median(figure(r) for r in runs)
        yield ["CPU ms (median of runs)"] + ["%.0f" % (1000 * median(runs, lambda r: r.cpu))
                                             for runs in timed]
        yield ["wall ms (median of runs)"] + ["%.0f" % (1000 * median(runs, lambda r: r.wall))
                                              for runs in timed]
        yield ["minor page faults (median of runs)"] + [count(median(runs, lambda r: r.faults))
                                                        for runs in timed]
    t.table("startup-cost", ["part"] + [c for c, _ in columns], gen())


def continuous(t):
    """The TVCG examples as users run them, all outputs written (the defaults)."""
    c = "Data/Continuous/"
    small = t.args.small
    rows = [
        "house.obj --size 24 24 10 --seed 3",
        "house.obj --size 24 24 10 --seed 3 --grounded --thickness wall:z --mirror x",
        "cottage.obj --size %s --seed 5 --grounded --thickness wall:z:2 --overhang roof "
        "--thickness wall:x:2+ --thickness wall:y:2+ --blocks 8" % (
            "16 16 8" if small else "24 24 8"),
        "domed-building.obj --size 24 24 10 --seed 2 --grounded --detail dome=%sdome.obj" % c,
        "pyramid.obj --size 20 20 6 --seed 1 --grounded",
        "house.obj --size 100 56 6 --seed 1 --grounded --thickness wall:z --guide "
        "%sletters-guide.vti" % c,
        "oil-platform.obj --size 24 24 12 --seed 2 --grounded --blocks 0 --thickness platform:z "
        "--thickness platform:x:2+ --thickness platform:y:2+ --thickness beam:x --thickness beam:y "
        "--connected solid:3",
        "roads.obj --size 40 40 0 --seed 1 --blocks 0 --connected road:1 --thickness road:xy",
        "roads.obj --size %s 0 --seed 1 --blocks 0 --connected road:1 --thickness road:xy" % (
            "60 60" if small else "120 120"),
        "pipes.obj --size 24 24 12 --seed 1 --blocks 0 --connected pipe:1 --thickness pipe:xy "
        "--thickness pipe:yz --thickness pipe:xz",
        "house.obj --size %s --seed 5" % ("24 24 10" if small else "48 48 10"),
    ]
    if small:
        rows = rows[:2] + rows[4:5] + rows[7:8] + rows[-1:]

    def gen():
        for arguments in rows:
            runs = t.msynth_runs("synthesize " + c + arguments)
            shown = arguments.replace(" --detail dome=%sdome.obj" % c, " --detail dome=dome.obj")
            shown = shown.replace(c, "")
            yield ["`%s`" % shown, count(runs[0].stats.get("Polygons", 0)),
                   spread(r.wall for r in runs), spread(r.stage("synthesis") for r in runs),
                   spread(r.stage("model.vdb") for r in runs),
                   spread((r.peak_mb for r in runs), megabytes)]
    t.table("continuous", ["`msynth synthesize` …", "polygons", "whole run s", "synthesis s",
                           "`model.vdb` s", "peak MB"], gen())


STAGES = ["example and arrangement", "synthesis", "mesh", "vtp files", "model.vdb", "mesh.glb"]


def threads(t):
    """The house at 48 x 48 x 10 on one and two threads: the solver and every stage."""
    size = "24 24 10" if t.args.small else "48 48 10"
    header = ["`--threads`", "solver s", "whole run s"] + ["%s s" % s for s in STAGES] + [
        "polygons"]

    def gen():
        for grounded in ("", " --grounded"):
            for n in (1, 2):
                runs = t.msynth_runs("synthesize Data/Continuous/house.obj --size %s --seed 5%s "
                                     "--threads %d" % (size, grounded, n))
                yield (["%d%s" % (n, grounded), spread(r.stats.get("Seconds") for r in runs),
                        spread(r.wall for r in runs)] +
                       [spread(r.stage(s) for r in runs) for s in STAGES] +
                       [count(runs[0].stats.get("Polygons", 0))])
    t.table("threads (house.obj --size %s --seed 5)" % size, header, gen())


def town(t):
    """The gallery's town: wall, CPU, peak, the stages, and what it holds."""
    size = "24 24 6" if t.args.small else "100 100 10"
    header = ["town", "wall s", "CPU s (user + system)", "peak GB", "vertices", "polygons",
              "parts"] + ["%s s" % s for s in STAGES] + ["`arrangement.vtp` MB"]

    def gen():
        for run in t.msynth_runs("synthesize " + TOWN.format(size=size)):
            yield (["%s, 2 threads" % size.replace(" ", " × "), seconds(run.wall),
                    "%s (%s + %s)" % (seconds(run.cpu), seconds(run.user), seconds(run.system)),
                    "%.2f" % (run.peak_mb / 1024), count(run.stats.get("ArrangementVertices", 0)),
                    count(run.stats.get("Polygons", 0)), count(run.stats.get("Components", 0))] +
                   [seconds(run.stage(s)) for s in STAGES] +
                   [megabytes(run.size_mb("arrangement.vtp"))])
    t.table("town", header, gen())


def exports(t):
    """mesh.glb and model.vox beside model.vtp and model.vdb: stage seconds and file sizes."""
    size = "24 24 6" if t.args.small else "100 100 10"
    rows = [("houses (README)", HOUSES), ("town %s" % size.replace(" ", " × "),
                                          TOWN.format(size=size))]
    header = ["run", "polygons", "`mesh.glb` s, MB", "`model.vox` s, MB", "`model.vtp` MB",
              "`model.vdb` s, MB", "whole run s", "peak GB"]

    def gen():
        for name, arguments in rows:
            runs = t.msynth_runs("synthesize %s --outputs labels,mesh,vdb,glb,vox" % arguments)
            r = runs[0]
            yield [name, count(r.stats.get("Polygons", 0)),
                   "%s, %s" % (spread(x.stage("mesh.glb") for x in runs),
                               megabytes(r.size_mb("mesh.glb"))),
                   "%s, %s" % (spread(x.stage("model.vox") for x in runs),
                               megabytes(r.size_mb("model.vox"))),
                   megabytes(r.size_mb("model.vtp")),
                   "%s, %s" % (spread(x.stage("model.vdb") for x in runs),
                               megabytes(r.size_mb("model.vdb"))),
                   spread(x.wall for x in runs), "%.2f" % (max(x.peak_mb for x in runs) / 1024)]
    t.table("exports", header, gen())


def top_share(t, run):
    """The most frequent label's share of the run's labels.vti (from `msynth info`)."""
    done = subprocess.run([t.msynth, "info", os.path.join(run.out, "labels.vti")],
                          capture_output=True, text=True)
    counts = [int(c) for c in re.findall(r"^  label \S+: (\d+) sites", done.stdout, re.M)]
    return "%.3f" % (max(counts) / sum(counts)) if counts else "–"


def backtracks(t):
    """Lines in 32² blocks, one thread: what backtracking and the blocks' overlap cost."""
    n = 256 if t.args.small else 1000
    base = ("synthesize Data/Tilesets/Lines.xml --size %d %d 1 --seed 1 --threads 1 "
            "--outputs labels" % (n, n))
    rows = [("whole model", ""), ("32² blocks, overlap 16 (default)", " --block 32 32 1"),
            ("the same, `--backtracks 0`", " --block 32 32 1 --backtracks 0"),
            ("32² blocks, overlap 8", " --block 32 32 1 --overlap 8 8 0"),
            ("32² blocks, overlap 0", " --block 32 32 1 --overlap 0 0 0")]

    def gen():
        for name, extra in rows:
            runs = t.msynth_runs(base + extra)
            s = runs[0].stats
            yield [name, count(s.get("Blocks", 0)), "%s (%s)" % (
                count(s.get("Attempts", 0)), count(s.get("FailedAttempts", 0))),
                count(s.get("Backtracks", 0)), count(s.get("BlocksFailed", 0)),
                spread(r.user for r in runs), top_share(t, runs[0])]
    t.table("backtracks (Lines %d², seed 1, one thread)" % n,
            ["run", "blocks", "attempts (failed)", "backtracks", "failed blocks", "user CPU s",
             "most frequent label"], gen())


def stream(t):
    """Lines in 32² blocks: a world in memory against a streamed one, per site and peak."""
    whole, streamed = (300, 1000) if t.args.small else (1000, 8000)
    base = "synthesize Data/Tilesets/Lines.xml --block 32 32 1 --outputs labels --seed 3"
    rows = [("`--size %d %d 1` (in memory)" % (whole, whole), whole,
             "%s --size %d %d 1" % (base, whole, whole)),
            ("`--size %d %d 1 --stream`" % (streamed, streamed), streamed,
             "%s --size %d %d 1 --stream" % (base, streamed, streamed))]

    def gen():
        for name, n, command in rows:
            runs = t.msynth_runs(command)
            s = runs[0].stats
            yield [name, spread(r.wall for r in runs),
                   spread((1e6 * r.wall / (n * n) for r in runs), lambda v: "%.2f" % v),
                   spread((r.peak_mb for r in runs), megabytes),
                   "%s (%s repaired)" % (s.get("BlocksFailed", "–"),
                                         s.get("BlocksRepaired", "–"))]
    t.table("stream", ["run (Lines, 32² blocks, seed 3, `--outputs labels`)", "wall s",
                       "µs per site", "peak MB", "failed blocks"], gen())


def placed_pins(t, n):
    """Data/Tilesets/lines-drawn.vti (24 x 24 sites, ASCII) with its extent moved to the middle
    of an n x n world: a smaller .vti is placed by its extent."""
    with open(os.path.join(DATA, "Tilesets", "lines-drawn.vti")) as f:
        text = f.read()
    c = n // 2 - 12
    path = os.path.join(t.scratch, "lines-drawn-placed.vti")
    with open(path, "w") as f:
        f.write(text.replace('"0 23 0 23 0 0"', '"%d %d %d %d 0 0"' % (c, c + 23, c, c + 23)))
    return path


def regions(t):
    """Regions of a 10^6 x 10^6 Lines world and a 10^5 x 10^5 village; pinned sites."""
    lines = "synthesize Data/Tilesets/Lines.xml --size 1000000 1000000 1 --seed 3"
    big = 500 if t.args.small else 3000
    pins = 500 if t.args.small else 4000
    rows = [
        ("Lines, 256² region, 16² blocks", "%s --block 16 16 1 --region 500000 500000 0 500256 "
         "500256 1" % lines),
        ("the same, `--no-repair`", "%s --block 16 16 1 --region 500000 500000 0 500256 500256 1 "
         "--no-repair" % lines),
        ("Lines, %d² region, 32² blocks, `--outputs labels`" % big,
         "%s --block 32 32 1 --region 500000 500000 0 %d %d 1 --outputs labels" % (
             lines, 500000 + big, 500000 + big)),
        ("Village.txt, 48 × 48 × 5 region of 10⁵ × 10⁵ × 5, 12 × 12 × 5 blocks, "
         "`--no-repair`",
         "synthesize Data/Examples/Village.txt --size 100000 100000 5 --block 12 12 5 --seed 3 "
         "--region 50000 50000 0 50048 50048 5 --no-repair"),
        ("Lines %d², 32² blocks, `--outputs labels`" % pins,
         "synthesize Data/Tilesets/Lines.xml --size %d %d 1 --block 32 32 1 --seed 1 --outputs "
         "labels" % (pins, pins)),
        ("the same, `--fixed`: `lines-drawn.vti` (96 drawn tiles) placed in the middle",
         "synthesize Data/Tilesets/Lines.xml --size %d %d 1 --block 32 32 1 --seed 1 --outputs "
         "labels --fixed %s" % (pins, pins, placed_pins(t, pins))),
    ]

    def gen():
        for name, command in rows:
            runs = t.msynth_runs(command)
            yield [name, count(runs[0].stats.get("Blocks", 0)),
                   spread(r.stats.get("Seconds") for r in runs), spread(r.wall for r in runs),
                   spread((r.peak_mb for r in runs), megabytes)]
    t.table("regions", ["run", "blocks", "synthesis s", "wall s", "peak MB"], gen())


def connected(t):
    """Circuits as one track network: components before the repairs, time, memory."""
    sizes = [(64, False), (128, False), (64, True)] if t.args.small else [
        (128, False), (256, False), (512, False), (1024, False), (2048, False),
        (256, True), (512, True), (1024, True)]
    labels = "track,turn,t,bridge,connection,component"

    def gen():
        for n, blocks in sizes:
            command = ("synthesize Data/Tilesets/Circuits.xml --size %d %d 1 --seed 1 --threads 1 "
                       "--outputs labels --connected %s%s" % (
                           n, n, labels, " --block 16 16 1" if blocks else ""))
            runs = t.msynth_runs(command)
            c = runs[0].stats.get("Connected", {})
            valid, _ = t.check(runs[0], "--connected", labels)
            yield ["%d²%s" % (n, ", 16² blocks" if blocks else " whole"),
                   count(c.get("before", 0)), "%s%s" % (count(c.get("components", 0)),
                                                         "" if valid else " (check failed)"),
                   count(c.get("repairs", 0)), spread(r.wall for r in runs),
                   spread(r.cpu for r in runs), spread((r.peak_mb for r in runs), megabytes)]
    t.table("connected", ["Circuits", "components before", "after (`msynth check`)", "repairs",
                          "wall s", "CPU s", "peak MB"], gen())


def failed_blocks(t):
    """Failed blocks over seeds: `--backtracks 0 --no-repair` (Algorithm 3.4 as published)
    against the defaults (backtracking, repair rounds)."""
    seeds = 3 if t.args.small else 20
    n = 64 if t.args.small else 256
    rows = [("Lines %d², entropy" % n, "Data/Tilesets/Lines.xml --size %d %d 1 --block 32 32 1 "
             "--order entropy --choice frequency" % (n, n)),
            ("Lines %d², scan line" % n, "Data/Tilesets/Lines.xml --size %d %d 1 --block 32 32 1 "
             "--choice frequency" % (n, n))]
    if t.data:
        tiles = os.path.join(t.data, "WaveFunctionCollapse", "tilesets")
        for order, flag in (("entropy", " --order entropy"), ("scan line", "")):
            rows.append(("Castle %d², %s" % (n, order), "%s/Castle.xml --size %d %d 1 --block 32 "
                         "32 1 --choice frequency%s" % (tiles, n, n, flag)))
        k = 64 if t.args.small else 128
        for subset in ("Dense", "CE"):
            rows.append(("Knots %s %d², entropy" % (subset, k), "%s/Knots.xml --subset %s --size "
                         "%d %d 1 --block 32 32 1 --order entropy --choice frequency" % (
                             tiles, subset, k, k)))
    header = ["example (32² blocks, frequency-weighted)", "mode", "failed runs", "failed blocks",
              "repaired", "synthesis s (mean)", "wall s (mean)"]

    def gen():
        for name, arguments in rows:
            for mode, extra in (("`--backtracks 0 --no-repair`", " --backtracks 0 --no-repair"),
                                ("defaults", "")):
                runs = []
                for seed in range(1, seeds + 1):
                    runs += t.msynth_runs("synthesize %s --outputs labels --seed %d%s" % (
                        arguments, seed, extra), 1, ok=False)
                stats = [r.stats for r in runs if r.stats]
                yield [name, mode, "%d of %d" % (sum(r.code != 0 for r in runs), seeds),
                       "%d of %d" % (sum(s.get("BlocksFailed", 0) for s in stats),
                                     sum(s.get("Blocks", 0) for s in stats)),
                       count(sum(s.get("BlocksRepaired", 0) for s in stats)),
                       seconds(statistics.mean(s.get("Seconds", 0) for s in stats)
                               if stats else None),
                       seconds(statistics.mean(r.wall for r in runs))]
    t.table("failed-blocks (%d seeds)" % seeds, header, gen())


WRITE_VDB = r"""
import sys, time
import modelsynth
from vtkmodules.vtkIOXML import vtkXMLImageDataReader
labels, out, grids, budget = sys.argv[1], sys.argv[2], sys.argv[3] == "1", float(sys.argv[4])
reader = vtkXMLImageDataReader()
reader.SetFileName(labels)
reader.Update()
writer = modelsynth.vtkMSOpenVDBWriter()
writer.SetInputData(reader.GetOutput())
writer.SetFileName(out)
writer.WriteFloatLabelsOn()
writer.SetEmptyLabel(0)
writer.SetWriteRenderGrids(grids)
if budget > 0:
    writer.SetLabelSurfaceBudget(budget)
start = time.perf_counter()
if not writer.Write():
    sys.exit("the write failed")
print("%.3f" % (time.perf_counter() - start))
"""


def render_grids(t):
    """model.vdb of a village of 10^7 sites: written again from its labels.vti without the render
    grids, with them (the default) and with a surface per named label; the best of two writes."""
    size = "200 200 5" if t.args.small else "1414 1414 5"
    run = t.msynth_runs("synthesize Data/Examples/Village.txt --size %s --block 24 24 5 --seed 1 "
                        "--outputs labels,vdb" % size, 1)[0]
    script = os.path.join(t.scratch, "write_vdb.py")
    with open(script, "w") as f:
        f.write(WRITE_VDB)
    env = dict(os.environ)
    site = os.path.join(t.build, "lib", "python%d.%d" % sys.version_info[:2], "site-packages")
    env["PYTHONPATH"] = site + (os.pathsep + env["PYTHONPATH"] if env.get("PYTHONPATH") else "")
    labels = os.path.join(run.out, "labels.vti")
    rows = [("`Label`, `Label_float`, `LastBlock` (`WriteRenderGrids` off)", "0", "0"),
            ("+ `density`, `color`, `surface` (the default)", "1", "0"),
            ("+ `surface_NAME` per named label (`LabelSurfaceBudget` 1e8)", "1", "1e8")]

    def gen():
        yield ["the whole `msynth synthesize … --outputs labels,vdb` (wall s)", seconds(run.wall),
               megabytes(run.size_mb("model.vdb")), megabytes(run.peak_mb)]
        for name, grids, budget in rows:
            out = os.path.join(t.scratch, "again.vdb")
            writes = [t.timed([sys.executable, script, labels, out, grids, budget], env=env)
                      for _ in range(2)]
            for w in writes:
                if w.code != 0:
                    sys.exit("perf-tables: the write failed:\n" + w.text)
            best = min(float(w.text.split()[-1]) for w in writes)
            yield [name, seconds(best), megabytes(os.path.getsize(out) / 1e6),
                   megabytes(max(w.peak_mb for w in writes))]
    t.table("render-grids (Village.txt --size %s)" % size,
            ["`model.vdb`", "write s", "file MB", "peak MB"], gen())


SUBCOMMANDS = {"whole-runs": whole_runs, "startup": startup, "startup-cost": startup_cost,
               "backtracks": backtracks,
               "continuous": continuous,
               "threads": threads, "town": town, "exports": exports, "stream": stream,
               "regions": regions, "connected": connected, "failed-blocks": failed_blocks,
               "render-grids": render_grids}


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("subcommand", choices=list(SUBCOMMANDS) + ["all"])
    parser.add_argument("--msynth", default=os.path.join(ROOT, "build", "bin", "msynth"))
    parser.add_argument("--small", action="store_true", help="small sizes: checks the script")
    parser.add_argument("--runs", type=int, default=1, help="runs of each command (min–max)")
    parser.add_argument("--keep", help="folder for the outputs (default: a temporary one, removed)")
    parser.add_argument("--data", help="the published sets (default ../shared/data)")
    parser.add_argument("--castle", help="the original program's samples/castle.txt")
    args = parser.parse_args()
    if not os.path.isfile(args.msynth):
        sys.exit("perf-tables: no msynth at %s (build first, or --msynth)" % args.msynth)
    if not os.path.isfile("/usr/bin/time"):
        sys.exit("perf-tables: /usr/bin/time is missing (Debian package 'time')")
    t = Tables(args)
    try:
        for name in (SUBCOMMANDS if args.subcommand == "all" else [args.subcommand]):
            SUBCOMMANDS[name](t)
    finally:
        if not args.keep:
            shutil.rmtree(t.scratch, ignore_errors=True)


if __name__ == "__main__":
    main()
