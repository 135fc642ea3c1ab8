"""Writes Data/Continuous/town.obj, a town block of about 500 polygons for continuous synthesis
(issue 29 item 5): two roads crossing, and in the four quarters gabled houses (ridges along x
and along y), flat-roofed shops and trees as bounding volumes (unit boxes, tree.obj substituted
into them), every object on the ground. Object types: wall, roof, shop, tree, road, shoproof.

    /usr/bin/python3 Utilities/make-town.py [Data/Continuous]

Coordinates are whole units in x and y and half units in z (roads and flat roofs half a unit
thick), so the plane spacings are 1 across x and y and 0.5 across z, and the roofs' slopes are
45 degrees: seven plane families."""
import os
import sys

HEADER = """# A town block of {faces} polygons (issue 29): two roads crossing (type road, half a unit
# thick), and in the four quarters gabled houses (walls 2 high under 45-degree roofs, ridges
# along x and along y; types wall and roof), flat-roofed shops (shop, 3 high, under a roof slab
# half a unit thick: shoproof) and trees as bounding volumes (tree: 1 x 1 x 3 boxes; substitute
# Data/Continuous/tree.obj). Made by Utilities/make-town.py. Synthesize it with
# msynth synthesize Data/Continuous/town.obj --size 100 100 10 --grounded --thickness road:z
#   --thickness shoproof:z --thickness tree:x --thickness tree:y --detail tree=Data/Continuous/tree.obj
"""


class Obj:
    def __init__(self):
        self.points, self.index, self.objects = [], {}, []

    def at(self, p):
        if p not in self.index:
            self.index[p] = len(self.points) + 1
            self.points.append(p)
        return self.index[p]

    def add(self, name, faces):
        """An object of polygons given by their corner points (outward, counter-clockwise)."""
        self.objects.append((name, [[self.at(p) for p in face] for face in faces]))

    def write(self, path):
        # Types are numbered in order of first appearance; this order gives them the gallery's
        # colours: walls beige, roofs red, shops blue, trees green, roads grey, shop roofs orange.
        order = ["wall", "roof", "shop", "tree", "road", "shoproof"]
        self.objects.sort(key=lambda o: order.index(o[0].split(".")[0]))
        faces = sum(len(f) for _, f in self.objects)
        with open(path, "w") as out:
            out.write(HEADER.format(faces=faces))
            out.write("".join("v %g %g %g\n" % p for p in self.points))
            for name, polys in self.objects:
                out.write("o %s\n" % name)
                out.write("".join("f %s\n" % " ".join(map(str, f)) for f in polys))
        return faces


def box(x0, y0, z0, x1, y1, z1):
    """The six faces of an axis-aligned box, outward."""
    return [[(x0, y0, z0), (x0, y1, z0), (x1, y1, z0), (x1, y0, z0)],
            [(x0, y0, z1), (x1, y0, z1), (x1, y1, z1), (x0, y1, z1)],
            [(x0, y0, z0), (x1, y0, z0), (x1, y0, z1), (x0, y0, z1)],
            [(x1, y0, z0), (x1, y1, z0), (x1, y1, z1), (x1, y0, z1)],
            [(x1, y1, z0), (x0, y1, z0), (x0, y1, z1), (x1, y1, z1)],
            [(x0, y1, z0), (x0, y0, z0), (x0, y0, z1), (x0, y1, z1)]]


def gable(x0, y0, x1, y1, z, along_x):
    """A roof prism over [x0, x1] x [y0, y1] from height z, 45-degree slopes, its ridge along x
    (or y)."""
    if along_x:
        h = (y1 - y0) / 2
        ym = (y0 + y1) / 2
        return [[(x0, y0, z), (x0, y1, z), (x1, y1, z), (x1, y0, z)],
                [(x0, y0, z), (x1, y0, z), (x1, ym, z + h), (x0, ym, z + h)],
                [(x1, y1, z), (x0, y1, z), (x0, ym, z + h), (x1, ym, z + h)],
                [(x0, y1, z), (x0, y0, z), (x0, ym, z + h)],
                [(x1, y0, z), (x1, y1, z), (x1, ym, z + h)]]
    h = (x1 - x0) / 2
    xm = (x0 + x1) / 2
    return [[(x0, y0, z), (x0, y1, z), (x1, y1, z), (x1, y0, z)],
            [(x1, y0, z), (x1, y1, z), (xm, y1, z + h), (xm, y0, z + h)],
            [(x0, y1, z), (x0, y0, z), (xm, y0, z + h), (xm, y1, z + h)],
            [(x0, y0, z), (x1, y0, z), (xm, y0, z + h)],
            [(x1, y1, z), (x0, y1, z), (xm, y1, z + h)]]


def town():
    obj = Obj()
    # Roads: a cross of 2-unit roads over the 30 x 30 block, as tiles of 2 x 2 (the road's
    # surface in pieces, as a modeller's road kit would give it), half a unit thick.
    size, lane = 30, (14, 16)
    tiles = set()
    for k in range(0, size, 2):
        tiles.add((k, lane[0]))
        tiles.add((lane[0], k))
    for k, (x, y) in enumerate(sorted(tiles)):
        obj.add("road.%03d" % (k + 1), box(x, y, 0, x + 2, y + 2, 0.5))  # one object per tile
    # The quarters: [0, 14) and [16, 30) in x and y; one layout, turned for variety.
    houses_x = [(1, 1, 7, 5), (1, 8, 7, 12), (10, 1, 13, 6)]  # ridges along the longer side
    shops = [(10, 9, 13, 13)]
    trees = [(8, 3), (3, 6), (0, 6), (11, 7), (8, 10)]  # a unit apart from everything

    def place(dx, dy, flip):
        def xy(x, y):
            return (13 - x + dx, y + dy) if flip else (x + dx, y + dy)

        def rect(x0, y0, x1, y1):
            (a, b), (c, d) = xy(x0, y0), xy(x1, y1)
            return min(a, c), min(b, d), max(a, c), max(b, d)

        for i, (x0, y0, x1, y1) in enumerate(houses_x):
            rx0, ry0, rx1, ry1 = rect(x0, y0, x1, y1)
            obj.add("wall", box(rx0, ry0, 0, rx1, ry1, 2))
            along_x = (rx1 - rx0) >= (ry1 - ry0)
            obj.add("roof", gable(rx0, ry0, rx1, ry1, 2, along_x))
        for x0, y0, x1, y1 in shops:
            rx0, ry0, rx1, ry1 = rect(x0, y0, x1, y1)
            obj.add("shop", box(rx0, ry0, 0, rx1, ry1, 3))
            obj.add("shoproof", box(rx0, ry0, 3, rx1, ry1, 3.5))
        for x, y in trees:
            tx, ty, _, _ = rect(x, y, x + 1, y + 1)
            obj.add("tree", box(tx, ty, 0, tx + 1, ty + 1, 3))

    place(0, 0, False)
    place(16, 0, True)
    place(0, 16, True)
    place(16, 16, False)
    return obj


def tree_detail(path):
    """Data/Continuous/tree.obj: a trunk under a crown (an octagonal pyramid) inside the tree's
    bounding volume [0, 1] x [0, 1] x [0, 3]."""
    import math
    points, faces = [], []

    def ring(r, z, n=8):
        first = len(points) + 1
        for k in range(n):
            a = 2 * math.pi * (k + 0.5) / n
            points.append((0.5 + r * math.cos(a), 0.5 + r * math.sin(a), z))
        return list(range(first, first + n))

    low, high = ring(0.12, 0), ring(0.12, 0.75)
    faces.append(low[::-1])
    for k in range(8):
        faces.append([low[k], low[(k + 1) % 8], high[(k + 1) % 8], high[k]])
    crown = ring(0.5, 0.75)
    points.append((0.5, 0.5, 3))
    top = len(points)
    for k in range(8):  # the crown's underside, from the trunk out (facing down)
        faces.append([high[k], high[(k + 1) % 8], crown[(k + 1) % 8], crown[k]])
        faces.append([crown[k], crown[(k + 1) % 8], top])
    with open(path, "w") as out:
        out.write("# A tree for the town's bounding volumes (Data/Continuous/town.obj, type tree):\n"
                  "# a trunk under an octagonal crown, one closed surface, inside [0, 1] x [0, 1] x [0, 3]. Made by\n"
                  "# Utilities/make-town.py.\no tree\n")
        out.write("".join("v %.6f %.6f %g\n" % p for p in points))
        out.write("".join("f %s\n" % " ".join(map(str, f)) for f in faces))


if __name__ == "__main__":
    folder = sys.argv[1] if len(sys.argv) > 1 else os.path.join("Data", "Continuous")
    n = town().write(os.path.join(folder, "town.obj"))
    tree_detail(os.path.join(folder, "tree.obj"))
    print("town.obj: %d polygons" % n)
