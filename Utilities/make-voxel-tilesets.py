"""Writes the bundled voxel tilesets in MarkovJunior's format (Data/Tilesets/NAME.xml with one
MagicaVoxel tile per name in Data/Tilesets/NAME/), drawn here:

- Pipes (3D, fullSymmetry, 5 x 5 x 5 voxels): Empty, Pipe (open at -x and +x), Bend (-x, +y),
  Tee (-x, +x, +y), each with a coloured band so that turned images differ;
- Tracks (2D, 6 x 6 x 1 voxels): Grass, Rail (-x, +x), Curve (-x, +y), Switch (-x, +x, +y).

The rules say where the openings meet: for every pair of the tiles' images (named by turn
prefixes such as "zx Bend"), "left" may touch "right" along +x when both or neither are open
there; one rule per orbit of such pairs under the turns (the others are the rules' images).
python3 Utilities/make-voxel-tilesets.py [OUTPUT_DIR] (default Data/Tilesets)."""
import os
import struct
import sys

DIRECTIONS = [(1, 0, 0), (-1, 0, 0), (0, 1, 0), (0, -1, 0), (0, 0, 1), (0, 0, -1)]


def write_vox(path, size, voxels, palette):
    """A one-model MagicaVoxel file: @p voxels maps (x, y, z) to palette indices 1..255;
    @p palette lists RGBA tuples for indices 1.. (the rest grey)."""
    sx, sy, sz = size
    xyzi = struct.pack("<I", len(voxels)) + b"".join(
        struct.pack("<BBBB", x, y, z, c) for (x, y, z), c in sorted(voxels.items()))
    colours = list(palette) + [(128, 128, 128, 255)] * (256 - len(palette))
    rgba = b"".join(struct.pack("<BBBB", *c) for c in colours[:256])

    def chunk(name, content):
        return name + struct.pack("<II", len(content), 0) + content

    body = chunk(b"SIZE", struct.pack("<III", sx, sy, sz)) + chunk(b"XYZI", xyzi) + chunk(
        b"RGBA", rgba)
    with open(path, "wb") as f:
        f.write(b"VOX " + struct.pack("<I", 150) + b"MAIN" + struct.pack("<II", 0, len(body)) + body)


def turn(voxels, s, sz, op):
    """The format's quarter turns as source lookups: the image's voxel (x, y, z) is the tile's
    voxel at z: (y, s-1-x, z), y: (z, y, s-1-x), x: (x, z, s-1-y)."""
    out = {}
    for x in range(s):
        for y in range(s):
            for z in range(sz):
                src = {"z": (y, s - 1 - x, z), "y": (z, y, s - 1 - x), "x": (x, z, s - 1 - y)}[op]
                if src in voxels:
                    out[(x, y, z)] = voxels[src]
    return out


def move(d, op):
    """Where a direction goes when the tile turns (the geometric map of the source lookup)."""
    x, y, z = d
    return {"z": (-y, x, z), "y": (-z, y, x), "x": (x, -z, y)}[op]


def images(voxels, openings, s, sz, letters):
    """Every distinct image of a tile under turns about @p letters: (prefix, voxels, openings),
    the prefix applied right to left as the format reads it."""
    found = [("", voxels, frozenset(openings))]
    seen = {frozenset(voxels.items())}
    i = 0
    while i < len(found):
        prefix, v, o = found[i]
        for op in letters:
            w = turn(v, s, sz, op)
            key = frozenset(w.items())
            if key not in seen:
                seen.add(key)
                found.append((op + prefix, w, frozenset(move(d, op) for d in o)))
        i += 1
    return found


def arm(s, d, lo, hi, colour):
    """Voxels of a square bar from the tile's centre to its face in direction @p d."""
    c = s // 2
    out = {}
    for x in range(s):
        for y in range(s):
            for z in range(s):
                p = (x, y, z)
                along = [i for i in range(3) if d[i] != 0][0]
                inside = all(lo <= p[i] <= hi for i in range(3) if i != along)
                reach = p[along] >= c - 1 if d[along] > 0 else p[along] <= c + 1
                if inside and reach:
                    out[p] = colour
    return out


def pipes():
    s = 5
    palette = [(120, 130, 140, 255), (200, 120, 60, 255), (60, 150, 200, 255),
               (230, 200, 70, 255), (90, 170, 90, 255)]
    tiles = {"Empty": ({}, set(), 3.0)}
    pipe = {**arm(s, (1, 0, 0), 1, 3, 1), **arm(s, (-1, 0, 0), 1, 3, 1)}
    for y in (1, 2, 3):
        pipe[(1, y, 3)] = 4  # a yellow band on top, off centre
    tiles["Pipe"] = (pipe, {(1, 0, 0), (-1, 0, 0)}, 1.0)
    bend = {**arm(s, (-1, 0, 0), 1, 3, 2), **arm(s, (0, 1, 0), 1, 3, 2)}
    bend[(0, 2, 3)] = 3  # a blue mark on the -x arm's top
    tiles["Bend"] = (bend, {(-1, 0, 0), (0, 1, 0)}, 1.0)
    tee = {**arm(s, (-1, 0, 0), 1, 3, 5), **arm(s, (1, 0, 0), 1, 3, 5), **arm(s, (0, 1, 0), 1, 3, 3)}
    tiles["Tee"] = (tee, {(-1, 0, 0), (1, 0, 0), (0, 1, 0)}, 0.3)
    return "Pipes", s, s, True, tiles, palette


def tracks():
    s = 6
    palette = [(80, 160, 70, 255), (110, 80, 50, 255), (170, 170, 180, 255), (200, 60, 50, 255)]
    grass = {(x, y, 0): 1 for x in range(s) for y in range(s)}
    tiles = {"Grass": (grass, set(), 2.0)}
    rail = dict(grass)
    for x in range(s):
        rail[(x, 2, 0)] = rail[(x, 3, 0)] = 3
        rail[(x, 1, 0)] = 2
    tiles["Rail"] = (rail, {(1, 0, 0), (-1, 0, 0)}, 1.0)
    curve = dict(grass)
    for i in range(4):
        curve[(i, 2, 0)] = curve[(2, 2 + i, 0)] = curve[(i, 3, 0)] = curve[(3, 2 + i, 0)] = 3
    curve[(0, 1, 0)] = 4  # a red signal on one side
    tiles["Curve"] = (curve, {(-1, 0, 0), (0, 1, 0)}, 1.0)
    switch = dict(rail)
    for y in range(2, s):
        switch[(2, y, 0)] = switch[(3, y, 0)] = 3
    switch[(5, 5, 0)] = 4
    tiles["Switch"] = (switch, {(-1, 0, 0), (1, 0, 0), (0, 1, 0)}, 0.4)
    return "Tracks", s, 1, False, tiles, palette


def write_set(out_dir, name, s, sz, full, tiles, palette):
    os.makedirs(os.path.join(out_dir, name), exist_ok=True)
    for tile, (voxels, _, _) in tiles.items():
        write_vox(os.path.join(out_dir, name, tile + ".vox"), (s, s, sz), voxels, palette)
    letters = "xyz" if full else "z"
    every, voxels = [], []
    for tile, (v, op, _) in tiles.items():
        for prefix, w, o in images(v, op, s, sz, letters):
            every.append((tile, prefix, o))
            voxels.append(frozenset(w.items()))
    index = {key: i for i, key in enumerate(voxels)}
    turned = [{op: index[frozenset(turn(dict(key), s, sz, op).items())] for op in letters}
              for key in voxels]
    seen = set()

    def first_of_orbit(i, j, d):
        """True once per orbit of the configuration (image i at 0, image j at d) under the
        turns: the other configurations of the orbit are the rule's images."""
        if (i, j, d) in seen:
            return False
        queue = [(i, j, d)]
        seen.add(queue[0])
        while queue:
            a, b, e = queue.pop()
            for op in letters:
                f = move(e, op)
                state = (turned[a][op], turned[b][op], f) if max(f) > 0 else (
                    turned[b][op], turned[a][op], tuple(-c for c in f))
                if state not in seen:
                    seen.add(state)
                    queue.append(state)
        return True
    lines = ['<tileset%s>' % (' fullSymmetry="True"' if full else ""),
             "  <!-- generated by Utilities/make-voxel-tilesets.py -->", "  <tiles>"]
    lines += ['    <tile name="%s" weight="%g"/>' % (t, w) for t, (_, _, w) in tiles.items()]
    lines += ["  </tiles>", "  <neighbors>"]
    ref = lambda tile, prefix: (prefix + " " if prefix else "") + tile
    for i, (a, pa, oa) in enumerate(every):
        for j, (b, pb, ob) in enumerate(every):
            if ((1, 0, 0) in oa) == ((-1, 0, 0) in ob) and first_of_orbit(i, j, (1, 0, 0)):
                lines.append('    <neighbor left="%s" right="%s"/>' % (ref(a, pa), ref(b, pb)))
    if sz > 1 and not full:
        for i, (a, pa, oa) in enumerate(every):
            for j, (b, pb, ob) in enumerate(every):
                if ((0, 0, 1) in ob) == ((0, 0, -1) in oa) and first_of_orbit(j, i, (0, 0, 1)):
                    lines.append('    <neighbor top="%s" bottom="%s"/>' % (ref(a, pa), ref(b, pb)))
    lines += ["  </neighbors>", "</tileset>", ""]
    with open(os.path.join(out_dir, name + ".xml"), "w") as f:
        f.write("\n".join(lines))


def main():
    out_dir = sys.argv[1] if len(sys.argv) > 1 else os.path.join(
        os.path.dirname(os.path.abspath(__file__)), "..", "Data", "Tilesets")
    for make in (pipes, tracks):
        write_set(out_dir, *make())


if __name__ == "__main__":
    main()
