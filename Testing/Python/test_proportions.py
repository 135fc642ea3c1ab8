"""The grounded-proportions matrix (issue 29 item 1) on small boxes: every bundled multi-type
example x {--grounded, --grounded + its documented constraints} x seeds 1-5, each object type's
share of the solid volume of the written model.vtp measured here (proportions.py: the divergence
theorem over the polygons, read by VTK's XML reader; the example's from the OBJ text), not by
the solver.

- Where the matrix holds, every share is within 25 % (relative) of the example's.
- Everywhere, a type outside 25 % is named in statistics.json's ProportionsOutside with why, and
  a type named there is outside (the report is true).
The full sizes are the benchmark (Testing/Benchmarks/proportions.sh)."""
import os
import re
import subprocess
import unittest

import proportions as p
from msynth_testing import tmp

# Seeds 1-5; under the sanitizers (several times slower, run for memory errors, not the matrix)
# seeds 1-2, which keeps the test within its time there.
SEEDS = range(1, 3) if os.environ.get("MSYNTH_SANITIZED") else range(1, 6)
# (example, with its documented constraints) whose every run keeps every share within 25 %.
# Every cell: where emptying whole parts cannot keep the shares (one building whose dome
# outgrew its storey walls; a town whose roads join every building into one part) or would
# leave most of the box bare, blocks are synthesized again (statistics.json's
# ProportionBlocksRedrawn; each such model checked against Eq. 4.1 by `msynth check`).
HOLDS = {("house", False), ("house", True), ("box-building", False), ("box-building", True),
         ("domed-building", False), ("domed-building", True), ("cottage", False),
         ("cottage", True), ("town", False), ("town", True)}
# Runs of a cell that may miss: with parts at the example's sizes (the default, RunEnds.h),
# emptying a whole part moves a share further, and a cottage's roof follows its walls' width.
# Seeds 1-5 measured: the cottage grounded misses in 2 (walls 0.60-0.64 against 0.50, roofs
# 0.23 against 0.34), with its constraints in 1 (porch and chimney 0.05 and 0.04 against 0.08),
# the town grounded in 1 (shop 0.09 against 0.14).
MISSES = {("cottage", False): 2, ("cottage", True): 1, ("town", False): 1}


class ProportionsMatrix(unittest.TestCase):
    def check(self, name, constrained, seeds=SEEDS):
        """Returns how many runs redrew blocks."""
        size = p.EXAMPLES[name][2]
        redrawn = 0
        missed = []
        for seed in seeds:
            out = tmp("proportions-%s-%d-%d" % (name, int(constrained), seed))
            target, got, stats, _, names = p.run(name, size, seed, constrained, out, threads=1)
            wrong = p.failures(target, got)
            where = "%s %s seed %d: %s against %s" % (
                name, "constrained" if constrained else "grounded", seed,
                {names[t]: round(got.get(t, 0), 3) for t in target},
                {names[t]: round(v, 3) for t, v in target.items()})
            if (name, constrained) in HOLDS and wrong:
                missed.append(where)
                self.assertLessEqual(len(missed), MISSES.get((name, constrained), 0),
                                     "; ".join(missed))
            reported = {int(t) for t in re.findall(r"type (\d+):", stats["ProportionsOutside"])}
            # The solver measures its own mesh; allow a type at the border either way.
            clear = {t for t in wrong if abs(got.get(t, 0) / target[t] - 1) > p.TOLERANCE + 0.02}
            self.assertTrue(clear <= reported, where + "; reported: " + stats["ProportionsOutside"])
            inside = {t for t in target if abs(got.get(t, 0) / target[t] - 1) < p.TOLERANCE - 0.02}
            self.assertFalse(inside & reported, where + "; reported: " + stats["ProportionsOutside"])
            self.assertGreaterEqual(stats["ProportionPartsRemoved"], 0)
            self.assertGreaterEqual(stats["ProportionBlocksRedrawn"], 0)
            if stats["ProportionBlocksRedrawn"] > 0:
                # Redrawn blocks keep the model consistent: Eq. 4.1 checked on the mesh alone.
                done = subprocess.run(
                    [os.path.join(os.environ["MSYNTH_BIN"], "msynth"), "check",
                     os.path.join(os.environ["MSYNTH_DATA"], "Continuous", p.EXAMPLES[name][0]),
                     os.path.join(out, "model.vtp")], capture_output=True, text=True)
                self.assertEqual(done.returncode, 0, where + ": " + done.stdout + done.stderr)
                redrawn += 1
        return redrawn

    def test_house(self):
        self.check("house", False)
        self.check("house", True)

    def test_box_building(self):
        self.check("box-building", False)
        self.check("box-building", True)

    def test_domed_building(self):
        self.check("domed-building", False)
        # Seed 3 holds one building whose dome outgrew its storey walls: no part can be emptied.
        self.assertGreaterEqual(self.check("domed-building", True), int(3 in SEEDS))

    def test_cottage(self):
        """Both hold in every seed. The documented run has blocks of 8 spacings: in the default
        4 (4.2 units) no whole cottage fits (5.5 deep with its porch), and its porches stayed one
        spacing deep, 0 of 5 (the example itself is a valid output under the constraints)."""
        self.check("cottage", False)
        self.check("cottage", True)

    def test_town(self):
        """Seeds 1-5 (about 5 s a run): both hold; grounded, seeds 2 and 4 carried too much shop,
        or road and shop roof, until blocks were redrawn (a part holds several types: roads join
        the buildings)."""
        self.assertGreaterEqual(self.check("town", False), int(4 in SEEDS))  # seeds 2 and 4
        self.check("town", True)

    def test_a_guide_keeps_every_part(self):
        """A guide that spells letters with 0/1 masks asks for houses in places: no part is
        emptied for the proportions (they emptied 72 of 74 parts once, a blank picture)."""
        import json
        out = tmp("proportions-guide")
        done = subprocess.run([os.path.join(os.environ["MSYNTH_BIN"], "msynth"), "synthesize",
                               os.path.join(os.environ["MSYNTH_DATA"], "Continuous", "house.obj"),
                               "--size", "100", "56", "6", "--seed", "1", "--grounded",
                               "--thickness", "wall:z", "--guide",
                               os.path.join(os.environ["MSYNTH_DATA"], "Continuous", "letters-guide.vti"),
                               "--outputs", "mesh", "--out", out], capture_output=True, text=True)
        self.assertEqual(done.returncode, 0, done.stderr)
        stats = json.load(open(os.path.join(out, "statistics.json")))
        self.assertEqual(stats["ProportionPartsRemoved"], 0)
        # Houses at the example's sizes: about 20 of them (86 small ones without --sizes).
        self.assertGreater(stats["Components"], 15)

    def test_an_emptied_model_is_said_on_the_console(self):
        """The house grounded with storey walls alone keeps one house of 34 parts (the rest are
        out of proportion): the command says so in a note; with the guide's constraints it keeps
        seven and says nothing."""
        import json
        for extra, noted in (([], True), (["--overhang", "roof", "--thickness", "wall:x:2+",
                                           "--thickness", "wall:y:2+", "--mirror", "x"], False)):
            out = tmp("proportions-note-%d" % len(extra))
            done = subprocess.run(
                [os.path.join(os.environ["MSYNTH_BIN"], "msynth"), "synthesize",
                 os.path.join(os.environ["MSYNTH_DATA"], "Continuous", "house.obj"),
                 "--size", "24", "24", "10", "--seed", "3", "--grounded", "--thickness", "wall:z",
                 *extra, "--outputs", "mesh", "--out", out], capture_output=True, text=True)
            self.assertEqual(done.returncode, 0, done.stderr)
            stats = json.load(open(os.path.join(out, "statistics.json")))
            self.assertEqual(stats["ProportionVolumeRemoved"] > 0.5, noted)
            note = re.search(r"note: (\d+) parts? \((\d+) % of the solid\) were emptied",
                             done.stdout)
            self.assertEqual(note is not None, noted, done.stdout)
            if note:
                self.assertEqual(int(note.group(1)), stats["ProportionPartsRemoved"])
                self.assertEqual(int(note.group(2)), round(100 * stats["ProportionVolumeRemoved"]))

    def test_measure_is_independent(self):
        """The example's shares from the OBJ text: the house's walls 4 x 3 x 2 = 24 against a
        roof prism 5 x 4 x 2 / 2 = 20."""
        target, names = p.example_shares(os.path.join(os.environ["MSYNTH_DATA"], "Continuous",
                                                      "house.obj"))
        self.assertEqual(names, {1: "wall", 2: "roof"})
        self.assertAlmostEqual(target[1], 24 / 44)
        self.assertAlmostEqual(target[2], 20 / 44)


if __name__ == "__main__":
    unittest.main()
