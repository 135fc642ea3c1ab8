"""Stand-ins for the twelve published MarkovJunior tilesets of issue 27 (Dungeon, Knots2D,
Escher, EscherSurface, Knots3D, MarchingHills, OrientedEscher, OrientedStairs, Partition,
PartitionedEdges, Paths, Surface), whose .vox tiles cannot be downloaded here: each set's tile
names, weights and neighbour rules in voxel_standins.txt, and tiles of our own drawing (a bar, a
turn, a plane, a wall... of 5 x 5 x 5 voxels, 5 x 5 x 1 in 2D), one colour per tile.
write_standins(folder) writes NAME.xml and NAME/TILE.vox for every set and returns
{name: is_2d}. voxel_standins.txt: "= NAME [full] [2d]", "tiles T[:W] ...", then rules separated
by ';': "A|B" (B may lie at +x of A) and "A^B" (A may lie at +z of B)."""
import importlib.util
import os

_SOURCE = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
_spec = importlib.util.spec_from_file_location(
    "make_voxel_tilesets", os.path.join(_SOURCE, "Utilities", "make-voxel-tilesets.py"))
_mvt = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(_mvt)

SIZE = 5
NAMES = ["Dungeon", "Knots2D", "Escher", "EscherSurface", "Knots3D", "MarchingHills",
         "OrientedEscher", "OrientedStairs", "Partition", "PartitionedEdges", "Paths", "Surface"]


def _region(s, sz, test):
    return {(x, y, z) for x in range(s) for y in range(s) for z in range(sz) if test(x, y, z)}


def _shape(name, s, sz):
    """The voxels of the stand-in tile @p name (a set of (x, y, z))."""
    c, cz = s // 2, sz // 2

    def arms(ds):
        return {(c + d[0] * t, c + d[1] * t, cz) for d in ds for t in range(c + 1)}
    shapes = {
        ("Empty", "Nothing"): lambda: set(),
        ("Stone", "Cube"): lambda: _region(s, sz, lambda x, y, z: True),
        ("o",): lambda: {(c, c, cz)},
        ("X", "Cross"): lambda: arms([(1, 0), (-1, 0), (0, 1), (0, -1)]),
        ("Line", "I", "00", "01", "10", "11"): lambda: arms([(1, 0), (-1, 0)]),
        ("Turn",): lambda: arms([(-1, 0), (0, 1)]),
        ("T",): lambda: arms([(-1, 0), (1, 0), (0, 1)]),
        ("ContactDown", "ContactUp", "Bridge", "Door"): lambda: arms([(1, 0)]),
        ("Wall",): lambda: _region(s, sz, lambda x, y, z: y <= c),
        ("In",): lambda: _region(s, sz, lambda x, y, z: not (x > c and y > c)),
        ("Out",): lambda: _region(s, sz, lambda x, y, z: x <= c and y <= c),
        ("Plane",): lambda: _region(s, sz, lambda x, y, z: z == c),
        ("Angle",): lambda: _region(
            s, sz, lambda x, y, z: (z == c and x <= c) or (x == c and z <= c)),
        ("Corner",): lambda: _region(s, sz, lambda x, y, z: (z == c and x <= c and y <= c) or (
            x == c and y <= c and z <= c) or (y == c and x <= c and z <= c)),
        ("Concave",): lambda: _region(
            s, sz, lambda x, y, z: (z == c and x <= c and y <= c) or (x == c and z >= c)),
    }
    for names, make in shapes.items():
        if name in names:
            return make()
    # Ramps: a diagonal bar up along x, with a mark on one side for the two T variants.
    v = {(x, c, round(x * (sz - 1) / (s - 1))) for x in range(s)}
    if name == "T1":
        v.add((c, 0, cz))
    if name == "T2":
        v.add((c, s - 1, cz))
    return v


def _sets():
    with open(os.path.join(os.path.dirname(os.path.abspath(__file__)), "voxel_standins.txt")) as f:
        text = f.read()
    for block in text.split("= ")[1:]:
        lines = block.strip().split("\n")
        head = lines[0].split()
        tiles = [t.split(":") for t in lines[1].split()[1:]]
        yield head[0], "full" in head, "2d" in head, tiles, lines[2:]


def write_standins(folder):
    palette = [((37 * i) % 256, (91 * i + 60) % 256, (53 * i + 120) % 256, 255)
               for i in range(1, 40)]
    flat = {}
    for name, full, is_2d, tiles, rules in _sets():
        sz = 1 if is_2d else SIZE
        flat[name] = is_2d
        os.makedirs(os.path.join(folder, name), exist_ok=True)
        for i, tile in enumerate(tiles):
            voxels = {p: i + 1 for p in _shape(tile[0], SIZE, sz)}
            _mvt.write_vox(os.path.join(folder, name, tile[0] + ".vox"), (SIZE, SIZE, sz),
                           voxels, palette)
        xml = ['<tileset%s>' % (' fullSymmetry="True"' if full else ''), '  <tiles>']
        xml += ['    <tile name="%s"%s/>' % (t[0], ' weight="%s"' % t[1] if len(t) > 1 else '')
                for t in tiles]
        xml += ['  </tiles>', '  <neighbors>']
        for line in rules:
            for rule in (r.strip() for r in line.split(";")):
                if "|" in rule:
                    xml.append('    <neighbor left="%s" right="%s"/>' % tuple(rule.split("|")))
                elif "^" in rule:
                    xml.append('    <neighbor top="%s" bottom="%s"/>' % tuple(rule.split("^")))
        xml += ['  </neighbors>', '</tileset>', '']
        with open(os.path.join(folder, name + ".xml"), "w") as f:
            f.write("\n".join(xml))
    assert sorted(flat) == sorted(NAMES), sorted(flat)
    return flat
