"""Connected networks in pattern synthesis (`msynth pattern --connected`, the filter's
Connected): the bundled city's roads are one network, counted here by a flood over the sides
City.xml's `connects` give (test_connected's, no code shared with the solver), with every pair of
neighbours found in an exemplar (recomputed here), the fixed crossroads kept, and
`msynth check --tileset --connected` agreeing; without the flag the roads are many pieces;
requests it cannot keep are one line."""
import json
import os
import unittest

import numpy as np

import modelsynth
from msynth_testing import (data, expect_refused, fresh_folder, labels_zyx, read_label_grid,
                            run_algorithm, run_msynth, violations)
from test_connected import components, network_sides

CITY = data("Patterns/City.xml")
EXEMPLARS = [data("Patterns/city-suburban.vti"), data("Patterns/city-urban.vti")]
ROADS = ("road,road north,crossroad,junction south,junction north,corner east south,"
         "corner west south,corner east north,corner west north,junction east,junction west,"
         "dead end east,dead end west,dead end north,dead end south")


def pattern(name, *args):
    out = fresh_folder(name)
    r = run_msynth("pattern", *EXEMPLARS, "--tileset", CITY, *args, "--out", out)
    return r, out


class PatternConnectedTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.sides = network_sides(CITY, ROADS.split(","))
        cls.exemplars = [labels_zyx(read_label_grid(p)) for p in EXEMPLARS]

    def check_model(self, path, expected_components):
        labels = labels_zyx(read_label_grid(path))
        bad = set(violations(self.exemplars[0], labels)) & set(violations(self.exemplars[1], labels))
        self.assertEqual(bad, set(), "pairs no exemplar shows")
        n = components(labels[0], self.sides)
        if expected_components is not None:
            self.assertEqual(n, expected_components, path)
        return labels, n

    def test_the_city_is_one_road_network(self):
        fixed = data("Patterns/city-crossroads-170.vti")
        crossroads = labels_zyx(read_label_grid(fixed))
        for seed in ("1", "2"):
            r, plain = pattern("pconn-plain-" + seed, "--size", "170", "170", "--fixed", fixed,
                               "--seed", seed)
            self.assertEqual(r.returncode, 0, r.stderr)
            _, before = self.check_model(os.path.join(plain, "labels.vti"), None)
            self.assertGreater(before, 50, "without --connected the roads are many pieces")
            r, out = pattern("pconn-city-" + seed, "--size", "170", "170", "--fixed", fixed,
                             "--seed", seed, "--connected", ROADS)
            self.assertEqual(r.returncode, 0, r.stderr)
            self.assertIn("form 1 component", r.stdout)
            path = os.path.join(out, "labels.vti")
            labels, _ = self.check_model(path, 1)
            kept = crossroads >= 0
            self.assertTrue(np.array_equal(labels[kept], crossroads[kept]), "fixed sites moved")
            with open(os.path.join(out, "statistics.json")) as f:
                stats = json.load(f)["Connected"]
            self.assertEqual((stats["components"], stats["maximum"]), (1, 1))
            self.assertGreater(stats["before"], 1)
            self.assertTrue(os.path.exists(os.path.join(out, "picture.png")))
            c = run_msynth("check", EXEMPLARS[1], path, "--tileset", CITY, "--connected", ROADS)
            self.assertIn("connected: %s form 1 component" % ROADS, c.stdout)
            c = run_msynth("check", EXEMPLARS[1], os.path.join(plain, "labels.vti"), "--tileset",
                           CITY, "--connected", ROADS)
            self.assertIn("not connected: %s form %d components" % (ROADS, before), c.stdout)

    def test_every_sample_every_method_and_a_maximum(self):
        for args, most in ((["--samples", "3", "--factors", "2H,2V,3x3"], 1),
                           (["--method", "csp"], 1), (["--method", "mh", "--burn-in", "0"], 1),
                           ([], 3)):
            r, out = pattern("pconn-samples", "--size", "40", "30", "--seed", "4",
                             "--connected", "%s:%d" % (ROADS, most), *args)
            self.assertEqual(r.returncode, 0, r.stderr)
            files = ["labels_%04d.vti" % k for k in (1, 2, 3)] if "--samples" in args else ["labels.vti"]
            for name in files:
                _, n = self.check_model(os.path.join(out, name), None)
                self.assertGreaterEqual(n, 1, (args, name))
                self.assertLessEqual(n, most, (args, name))

    def test_requests_it_cannot_keep_are_one_line(self):
        for args, message in [
                (["--connected", "bridge"], "'bridge' is neither a label value nor a tile"),
                (["--connected", ROADS + ":0"], "is not a number of components"),
                (["--connected", "99"], "none of its labels occurs in the exemplars"),
                (["--connected", ROADS, "--mirror", "x"], "cannot be combined with mirroring")]:
            expect_refused(self, ["pattern", *EXEMPLARS, "--tileset", CITY, "--size", "20", "20"],
                           args, message)

    def test_the_filter_reports_the_network(self):
        readers = []
        synthesis = modelsynth.vtkMSPatternSynthesis()
        for path in EXEMPLARS:
            readers.append(modelsynth.vtkMSLabelGridReader())
            readers[-1].SetFileName(path)
            synthesis.AddInputConnection(0, readers[-1].GetOutputPort())
        output, errors = run_algorithm(synthesis, OutputSize=(48, 32, 1), Seed=2,
                                       Connected=ROADS, ConnectedTilesetFile=CITY)
        self.assertEqual(errors, "")
        fd = output.GetFieldData()
        self.assertEqual(fd.GetArray("ConnectedComponents").GetValue(0), 1)
        self.assertGreater(fd.GetArray("ConnectedBefore").GetValue(0), 1)
        self.assertEqual(components(labels_zyx(output)[0], self.sides), 1)

    def test_sides_of_tiles_that_are_never_turned(self):
        folder = fresh_folder("pconn-turned")
        bad = os.path.join(folder, "bad.xml")
        with open(bad, "w") as f:
            f.write('<set turned="false"><tiles><tile name="a" symmetry="L" connects="right"/>'
                    '</tiles></set>\n')

        def grid(name, row):
            path = os.path.join(folder, name)
            with open(path, "w") as f:
                f.write("ModelSynth test example.\n\nx, y, and z extents\n2 1 1\n\n%s\n" % row)
            return path

        r = run_msynth("check", grid("a.txt", "0 0"), grid("a.txt", "0 0"), "--tileset", bad,
                       "--connected", "a")
        self.assertNotEqual(r.returncode, 0)
        self.assertIn("never turned", r.stderr)
        # City.xml's sides as written: a dead end east (12) connects only to the right, so two
        # side by side are two components; facing a dead end west (13) they are one.
        for row, count in (("12 12", 2), ("12 13", 1)):
            path = grid("roads.txt", row)
            self.assertEqual(components(labels_zyx(read_label_grid(path))[0], self.sides), count)
            r = run_msynth("check", path, path, "--tileset", CITY, "--connected",
                           "dead end east,dead end west:5")
            self.assertIn("form %d component" % count, r.stdout, r.stderr)

if __name__ == "__main__":
    unittest.main()
