"""Connected networks (--connected, the filter's Connected): on the bundled path tilesets (Paths
behaves like WaveFunctionCollapse's Knots, Circuits like its Circuit), whole and in blocks, the
network is one component, counted here by a flood over the tiles' connecting sides read from
the XML (no code shared with the solver) and by `msynth check --connected`; the model is the
same for 1 and 2 threads; requests it cannot keep are one line before any work."""
import json
import os
import unittest
import xml.etree.ElementTree as ET
from collections import deque

import numpy as np

import modelsynth
from msynth_testing import (data, expect_refused, fresh_folder, labels_zyx, read_label_grid,
                            run_algorithm, run_msynth)

PATHS = data("Tilesets/Paths.xml")
CIRCUITS = data("Tilesets/Circuits.xml")
NETWORKS = {PATHS: "line,corner,t,cross", CIRCUITS: "track,turn,t,bridge,connection,component"}
ORIENTATIONS = {"X": 1, "I": 2, "\\": 2, "L": 4, "T": 4}
SIDE = {"right": (1, 0), "top": (0, 1), "left": (-1, 0), "bottom": (0, -1)}


def network_sides(path, names):
    """Per label of the tileset, the steps (dx, dy) its path leaves through, or None outside
    the network: a tile's `connects` sides turned a quarter counter-clockwise per orientation."""
    sides = []
    for tile in ET.parse(path).getroot().find("tiles"):
        steps = [SIDE[s] for s in tile.get("connects", "").split()]
        for k in range(ORIENTATIONS[tile.get("symmetry", "X")]):
            turned = set(steps)
            for _ in range(k):
                turned = {(-y, x) for x, y in turned}
            sides.append(turned if tile.get("name") in names else None)
    return sides


def components(labels, sides):
    """Components of the network in a 2D label array [y, x], joined where both sides connect."""
    ny, nx = labels.shape
    seen = np.zeros(labels.shape, bool)
    count = 0
    for y0 in range(ny):
        for x0 in range(nx):
            if seen[y0, x0] or sides[labels[y0, x0]] is None:
                continue
            count += 1
            seen[y0, x0] = True
            queue = deque([(x0, y0)])
            while queue:
                x, y = queue.popleft()
                for dx, dy in sides[labels[y, x]]:
                    qx, qy = x + dx, y + dy
                    if not (0 <= qx < nx and 0 <= qy < ny) or seen[qy, qx]:
                        continue
                    other = sides[labels[qy, qx]]
                    if other is not None and (-dx, -dy) in other:
                        seen[qy, qx] = True
                        queue.append((qx, qy))
    return count


class ConnectedTest(unittest.TestCase):
    def test_one_network_whole_and_in_blocks(self):
        for tileset, network in NETWORKS.items():
            sides = network_sides(tileset, network.split(","))
            before = []
            for blocks in ([], ["--block", "16", "16", "1"]):
                for seed in ("1", "2"):
                    models = []
                    for threads in ("1", "2"):
                        out = fresh_folder("connected-%s-%d-%s-%s" % (
                            os.path.basename(tileset), len(blocks), seed, threads))
                        r = run_msynth("synthesize", tileset, "--size", "40", "40", "1", *blocks,
                                       "--seed", seed, "--threads", threads, "--connected", network,
                                       "--outputs", "labels", "--out", out)
                        self.assertEqual(r.returncode, 0, r.stderr)
                        path = os.path.join(out, "labels.vti")
                        labels = labels_zyx(read_label_grid(path))[0]
                        self.assertEqual(components(labels, sides), 1, (tileset, blocks, seed))
                        with open(os.path.join(out, "statistics.json")) as f:
                            stats = json.load(f)["Connected"]
                        self.assertEqual((stats["components"], stats["maximum"]), (1, 1))
                        before.append(stats["before"])
                        c = run_msynth("check", tileset, path, "--connected", network)
                        self.assertEqual(c.returncode, 0, c.stdout + c.stderr)
                        self.assertIn("form 1 component", c.stdout)
                        self.assertIn("consistent", c.stdout)
                        models.append(labels)
                    self.assertTrue(np.array_equal(models[0], models[1]), "threads change the model")
            self.assertGreater(max(before), 1, "the runs should start from several components")

    def test_check_counts_the_components_of_a_plain_model(self):
        out = fresh_folder("connected-plain")
        r = run_msynth("synthesize", CIRCUITS, "--size", "32", "32", "1", "--seed", "1",
                       "--outputs", "labels", "--out", out)
        self.assertEqual(r.returncode, 0, r.stderr)
        path = os.path.join(out, "labels.vti")
        network = NETWORKS[CIRCUITS]
        expected = components(labels_zyx(read_label_grid(path))[0], network_sides(CIRCUITS, network.split(",")))
        self.assertGreater(expected, 1)
        c = run_msynth("check", CIRCUITS, path, "--connected", network)
        self.assertEqual(c.returncode, 1, c.stdout + c.stderr)
        self.assertIn("not connected: %s form %d components" % (network, expected), c.stdout)
        c = run_msynth("check", CIRCUITS, path, "--connected", "%s:%d" % (network, expected))
        self.assertEqual(c.returncode, 0, c.stdout + c.stderr)

    def test_requests_it_cannot_keep_are_one_line_before_any_work(self):
        village = data("Examples/Village.vti")
        for example, args, message in [
                (PATHS, ["--connected", "bridge"], "'bridge' is neither a label value nor a tile"),
                (PATHS, ["--connected", "line:0"], "is not a number of components"),
                (PATHS, ["--connected", "line:1,corner:2"], "names more than one network"),
                (village, ["--connected", "9"], "label 9 does not occur in the example"),
                (village, ["--connected", "2,3", "--mirror", "x"], "cannot be combined with symmetry"),
                (village, ["--connected", "2,3", "--block", "12", "12", "5", "--region", "0", "0", "0",
                           "12", "12", "5"], "connected network")]:
            size = ["24", "24", "5"] if example == village else ["16", "16", "1"]
            expect_refused(self, ["synthesize", example, "--size", *size], args, message)

    def test_the_filter_reports_the_network(self):
        synthesis = modelsynth.vtkMSDiscreteSynthesis()
        output, errors = run_algorithm(synthesis, TilesetFile=PATHS, OutputSize=(24, 24, 1),
                                       BlockSize=(12, 12, 1), Seed=3, Connected=NETWORKS[PATHS])
        self.assertEqual(errors, "")
        fd = output.GetFieldData()
        self.assertEqual(fd.GetAbstractArray("ConnectedLabels").GetValue(0), NETWORKS[PATHS])
        self.assertEqual(fd.GetArray("ConnectedComponents").GetValue(0), 1)
        sides = network_sides(PATHS, NETWORKS[PATHS].split(","))
        self.assertEqual(components(labels_zyx(output)[0], sides), 1)
        _, errors = run_algorithm(modelsynth.vtkMSDiscreteSynthesis(), TilesetFile=PATHS,
                                  OutputSize=(8, 8, 1), Connected="nothing")
        self.assertIn("'nothing' is neither a label value nor a tile", errors)


if __name__ == "__main__":
    unittest.main()


def path_components(labels, sides, sites):
    """The components (as sets of sites) of the network holding `sites` [(x, y)], or None when a
    site holds no network label: the same flood as `components`, from each site."""
    ny, nx = labels.shape
    found = []
    for x0, y0 in sites:
        if sides[labels[y0, x0]] is None:
            return None
        if any((x0, y0) in c for c in found):
            continue
        part, queue = {(x0, y0)}, deque([(x0, y0)])
        while queue:
            x, y = queue.popleft()
            for dx, dy in sides[labels[y, x]]:
                q = (x + dx, y + dy)
                if 0 <= q[0] < nx and 0 <= q[1] < ny and q not in part:
                    other = sides[labels[q[1], q[0]]]
                    if other is not None and (-dx, -dy) in other:
                        part.add(q)
                        queue.append(q)
        found.append(part)
    return found


class PathTest(unittest.TestCase):
    def test_sites_and_labels_are_joined_whole_and_in_blocks(self):
        network = NETWORKS[PATHS]
        sides = network_sides(PATHS, network.split(","))
        plain = fresh_folder("path-plain")
        r = run_msynth("synthesize", PATHS, "--size", "40", "40", "1", "--seed", "1",
                       "--outputs", "labels", "--out", plain)
        self.assertEqual(r.returncode, 0, r.stderr)
        labels = labels_zyx(read_label_grid(os.path.join(plain, "labels.vti")))[0]
        empty = [(x, y) for y in range(40) for x in range(40) if sides[labels[y, x]] is None]
        sites = [empty[0], empty[len(empty) // 2], empty[-1]]  # outside the plain network
        self.assertIsNone(path_components(labels, sides, sites))
        args = ["%d,%d" % s for s in sites]
        c = run_msynth("check", PATHS, os.path.join(plain, "labels.vti"), "--connected",
                       network + ":100", "--path", *args)
        self.assertEqual(c.returncode, 1, c.stdout + c.stderr)
        self.assertIn("path not joined", c.stdout)
        for blocks in ([], ["--block", "16", "16", "1"]):
            out = fresh_folder("path-sites-%d" % len(blocks))
            r = run_msynth("synthesize", PATHS, "--size", "40", "40", "1", *blocks, "--seed", "1",
                           "--connected", network + ":100", "--path", *args,
                           "--outputs", "labels", "--out", out)
            self.assertEqual(r.returncode, 0, r.stderr)
            path = os.path.join(out, "labels.vti")
            labels = labels_zyx(read_label_grid(path))[0]
            parts = path_components(labels, sides, sites)
            self.assertIsNotNone(parts, "a path site holds no network label")
            self.assertEqual(len(parts), 1, blocks)
            c = run_msynth("check", PATHS, path, "--connected", network + ":100", "--path", *args)
            self.assertEqual(c.returncode, 0, c.stdout + c.stderr)
            self.assertIn("path joined: 3 sites in 1 component", c.stdout)
            with open(os.path.join(out, "statistics.json")) as f:
                self.assertEqual(json.load(f)["Connected"]["pathSites"], 3)
        # Every site of a label: the circuit's connections, many components apart without it.
        circuit = NETWORKS[CIRCUITS]
        csides = network_sides(CIRCUITS, circuit.split(","))
        for blocks in ([], ["--block", "16", "16", "1"]):
            out = fresh_folder("path-label-%d" % len(blocks))
            r = run_msynth("synthesize", CIRCUITS, "--size", "48", "48", "1", *blocks, "--seed", "1",
                           "--connected", circuit + ":10000", "--path", "connection",
                           "--outputs", "labels", "--out", out)
            self.assertEqual(r.returncode, 0, r.stderr)
            labels = labels_zyx(read_label_grid(os.path.join(out, "labels.vti")))[0]
            connection = [i for i, s in enumerate(network_sides(CIRCUITS, ["connection"]))
                          if s is not None]
            sites = [(x, y) for y in range(48) for x in range(48) if labels[y, x] in connection]
            self.assertGreater(len(sites), 10)
            self.assertEqual(len(path_components(labels, csides, sites)), 1, blocks)
            with open(os.path.join(out, "statistics.json")) as f:
                stats = json.load(f)["Connected"]
            self.assertEqual(stats["pathSites"], len(sites))
            self.assertGreater(stats["repairs"], 0)

    def test_the_filter_joins_its_path(self):
        network = NETWORKS[CIRCUITS]
        output, errors = run_algorithm(modelsynth.vtkMSDiscreteSynthesis(), TilesetFile=CIRCUITS,
                                       OutputSize=(32, 32, 1), Seed=2, Connected=network + ":1000",
                                       Path="0,0;31,31;connection")
        self.assertEqual(errors, "")
        labels = labels_zyx(output)[0]
        sides = network_sides(CIRCUITS, network.split(","))
        connection = [i for i, s in enumerate(network_sides(CIRCUITS, ["connection"])) if s]
        sites = [(0, 0), (31, 31)] + [(x, y) for y in range(32) for x in range(32)
                                      if labels[y, x] in connection]
        self.assertEqual(len(path_components(labels, sides, sites)), 1)
        self.assertEqual(output.GetFieldData().GetArray("ConnectedPathSites").GetValue(0),
                         len(sites))

    def test_paths_it_cannot_keep_are_one_line(self):
        for args, message in [
                (["--connected", "line", "--path", "40,3"], "the path's site (40, 3, 0) is outside"),
                (["--connected", "line", "--path", "1,1,9"], "is outside the model"),
                (["--connected", "line", "--path", "empty"], "cannot carry the network of line"),
                (["--path", "1,1"], "needs a network of labels to carry it"),
                (["--connected", "line", "--path", "nothing"], "'nothing' is neither a site")]:
            expect_refused(self, ["synthesize", PATHS, "--size", "40", "40", "1"], args, message)
        c = run_msynth("check", PATHS, PATHS, "--path", "1,1")
        self.assertNotEqual(c.returncode, 0)
        self.assertIn("--path needs --connected", c.stderr)
