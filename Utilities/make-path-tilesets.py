#!/usr/bin/env python3
"""Writes the bundled path tilesets Data/Tilesets/Paths.xml and Circuits.xml with their tile images.

They behave like WaveFunctionCollapse's Knots and Circuit sets (paths of lines, corners, T
junctions and crossings over empty space; tracks between components on a substrate) but are
written here from edge types: every side of a tile has a type, and two tiles may meet where the
types of the sides they turn to each other agree. Each tile's `connects` attribute lists the
sides a path leaves it through, which `--connected` follows. The files are committed; rerun after
changing this script (plain Python, no modules beyond the standard library).
"""
import os
import struct
import zlib

DATA = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "Data", "Tilesets")
SIDES = ("right", "top", "left", "bottom")  # +x, +y, -x, -y; a quarter turn moves each to the next
SIZE = 12


def turn(types, k):
    """Side types (right, top, left, bottom) after k quarter turns counter-clockwise."""
    return tuple(types[(i - k) % 4] for i in range(4))


def orientations(symmetry):
    return {"X": 1, "I": 2, "\\": 2, "L": 4, "T": 4}[symmetry]


def rules(tiles, meets):
    """Neighbor pairs (left, right) of every tile orientation whose facing sides meet."""
    out = []
    for a in tiles:
        for ka in range(orientations(a[1])):
            for b in tiles:
                for kb in range(orientations(b[1])):
                    if meets(turn(a[2], ka)[0], turn(b[2], kb)[2]):
                        out.append((f"{a[0]} {ka}", f"{b[0]} {kb}"))
    return out


def png(path, pixels):
    rows = b"".join(b"\x00" + bytes(c for p in row for c in p) for row in pixels)

    def chunk(kind, data):
        body = kind + data
        return struct.pack(">I", len(data)) + body + struct.pack(">I", zlib.crc32(body))

    with open(path, "wb") as f:
        f.write(b"\x89PNG\r\n\x1a\n")
        f.write(chunk(b"IHDR", struct.pack(">IIBBBBB", SIZE, SIZE, 8, 2, 0, 0, 0)))
        f.write(chunk(b"IDAT", zlib.compress(rows, 9)))
        f.write(chunk(b"IEND", b""))


def draw(types, colours, background):
    """A tile: its background, a stroke from the centre to every side whose type has a colour."""
    pixels = [[background for _ in range(SIZE)] for _ in range(SIZE)]
    mid, half = SIZE // 2, 2
    centre = None
    for side, kind in zip(SIDES, types):
        colour = colours.get(kind)
        if colour is None:
            continue
        centre = colour
        for t in range(mid + half):
            for w in range(mid - half, mid + half):
                x, y = {"right": (mid + t - half, w), "left": (mid - t + half - 1, w),
                        "top": (w, mid - t + half - 1), "bottom": (w, mid + t - half)}[side]
                if 0 <= x < SIZE and 0 <= y < SIZE:
                    pixels[y][x] = colour
    return pixels, centre


def write(name, comment, tiles, meets, colours, backgrounds):
    folder = os.path.join(DATA, name)
    os.makedirs(folder, exist_ok=True)
    lines = ['<?xml version="1.0"?>', f"<!-- {comment} -->", '<set unique="False">', "  <tiles>"]
    for tile, symmetry, types, weight in tiles:
        connects = " ".join(s for s, t in zip(SIDES, types) if t in colours)
        lines.append(f'    <tile name="{tile}" symmetry="{symmetry}" weight="{weight}"'
                     f' connects="{connects}"/>')
        pixels, _ = draw(types, colours, backgrounds.get(tile, (235, 230, 220)))
        png(os.path.join(folder, tile + ".png"), pixels)
    lines += ["  </tiles>", "  <neighbors>"]
    for left, right in rules(tiles, meets):
        lines.append(f'    <neighbor left="{left}" right="{right}"/>')
    lines += ["  </neighbors>", "</set>", ""]
    with open(os.path.join(DATA, name + ".xml"), "w") as f:
        f.write("\n".join(lines))


# Paths: Knots' tiles (empty, line, corner, T junction, crossing), P a path side, E empty.
write("Paths",
      "Paths of lines, corners, T junctions and crossings over empty space, as "
      "WaveFunctionCollapse's Knots set; written by Utilities/make-path-tilesets.py",
      [("empty", "X", ("E", "E", "E", "E"), 3.0), ("line", "I", ("P", "E", "P", "E"), 1.0),
       ("corner", "L", ("P", "P", "E", "E"), 1.0), ("t", "T", ("P", "P", "P", "E"), 0.1),
       ("cross", "I", ("P", "P", "P", "P"), 0.2)],
      lambda a, b: a == b, {"P": (40, 40, 60)}, {})
# Circuits: Circuit's substrate, components and their connections, tracks, turns, T junctions
# and bridges; S substrate, T track, C a component's side (which may face substrate too).
write("Circuits",
      "Tracks joining components on a substrate, as WaveFunctionCollapse's Circuit set; written "
      "by Utilities/make-path-tilesets.py",
      [("substrate", "X", ("S", "S", "S", "S"), 2.0), ("component", "X", ("C", "C", "C", "C"), 8.0),
       ("connection", "T", ("S", "T", "S", "C"), 4.0), ("track", "I", ("T", "S", "T", "S"), 2.0),
       ("turn", "L", ("T", "T", "S", "S"), 1.0), ("t", "T", ("T", "T", "T", "S"), 0.2),
       ("bridge", "I", ("T", "T", "T", "T"), 0.5)],
      lambda a, b: a == b or {a, b} == {"C", "S"}, {"T": (230, 190, 60), "C": (50, 50, 50)},
      {"substrate": (40, 110, 60), "component": (50, 50, 50), "connection": (40, 110, 60),
       "track": (40, 110, 60), "turn": (40, 110, 60), "t": (40, 110, 60),
       "bridge": (40, 110, 60)})
