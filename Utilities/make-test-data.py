#!/usr/bin/env python3
"""Regenerates the bundled examples (Data/Examples) and malformed fixtures (Data/Malformed).

Run with /usr/bin/python3 (ParaView's vtkmodules). The files are committed; rerun after changing
this script. All files are ASCII VTK XML so that reviews can read them.
"""
import math
import os
import sys

from vtkmodules.vtkCommonCore import vtkDoubleArray, vtkFloatArray, vtkIntArray
from vtkmodules.vtkCommonDataModel import vtkImageData
from vtkmodules.vtkIOXML import vtkXMLImageDataWriter

DATA = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "Data")

EMPTY, GROUND, WALL, ROOF = 0, 1, 2, 3


def write(image, path):
    w = vtkXMLImageDataWriter()
    w.SetInputData(image)
    w.SetDataModeToAscii()
    w.SetFileName(path)
    if not w.Write():
        sys.exit("could not write " + path)


def label_image(dims, fn, name="Label", array_type=vtkIntArray, components=1, spacing=(1, 1, 1)):
    image = vtkImageData()
    image.SetDimensions(*dims)
    image.SetSpacing(*spacing)
    a = array_type()
    a.SetName(name)
    a.SetNumberOfComponents(components)
    a.SetNumberOfTuples(dims[0] * dims[1] * dims[2])
    i = 0
    for z in range(dims[2]):
        for y in range(dims[1]):
            for x in range(dims[0]):
                for c in range(components):
                    a.SetComponent(i, c, fn(x, y, z))
                i += 1
    image.GetPointData().AddArray(a)
    return image


def village(x, y, z):
    """A 3D block: ground at z = 0, a 3x3 house of walls two storeys high, a roof over it."""
    if z == 0:
        return GROUND
    inside = 2 <= x <= 4 and 2 <= y <= 4
    if inside and z in (1, 2):
        return WALL
    if inside and z == 3:
        return ROOF
    return EMPTY


HOUSE_INSIDE = 2  # the houses' labels: 0 empty, 1 ground, 2 inside, 3 roof, then the outer walls
SW, SE, NW, NE, SOUTH, NORTH, WEST, EAST = range(4, 12)
HOUSE_COLOURS = {GROUND: (96, 150, 70), HOUSE_INSIDE: (205, 180, 130), ROOF: (170, 55, 40),
                 SOUTH: (215, 195, 150), NORTH: (215, 195, 150), WEST: (215, 195, 150),
                 EAST: (215, 195, 150), SW: (120, 85, 55), SE: (120, 85, 55), NW: (120, 85, 55),
                 NE: (120, 85, 55)}


def houses(x, y, z):
    """The main job's example (9 x 8 x 5): ground at z = 0 and one 5 x 4 house two storeys high
    under a flat roof. Each wall site's label says which side of the house it is on (corner posts
    SW..NE, walls SOUTH..EAST, HOUSE_INSIDE inside), so every pair of neighbours the example
    allows keeps houses rectangular, one empty site apart, each under one roof."""
    if z == 0:
        return GROUND
    if not (2 <= x <= 6 and 2 <= y <= 5) or z > 3:
        return EMPTY
    if z == 3:
        return ROOF
    west, east = x == 2, x == 6
    if y in (2, 5):
        row = (SW, SE, SOUTH) if y == 2 else (NW, NE, NORTH)
        return row[0] if west else row[1] if east else row[2]
    return WEST if west else EAST if east else HOUSE_INSIDE


def ball(x, y, z):
    """The rolling ball of dissertation Fig. 3.27 for time-varying synthesis: z is time; the
    ball (1) moves one site to the right per frame, leaving a trail (2) behind it."""
    return 1 if x == z else (2 if x == z - 1 else 0)


# The dissertation's two fallible examples (D§3.3.4, Figs. 3.5(a) and 3.6(a); their pictures are
# not in the text we have, so these follow what the text says of them). Rows top first, y up.
FIG_3_5A = """
0 0 0 0 0 0 0 0 0 0
0 3 4 5 0 0 7 4 5 0
0 2 0 6 0 0 2 1 6 0
8 8 8 8 8 8 8 8 8 8"""
# Fig. 3.5(a): every 2 has a 6 two sites to its right, joined through either of two paths (a 0 or
# a 1 between them), and the labels above (3 or 7, then 4, 5) are what ties the 2 to its 6. E_I
# of Fig. 3.15 is this with the 0 between 2 and 6 made a 9 (Eq. 3.12).
FIG_3_6A = """
0 0 0 0 0 0 0
0 0 4 1 5 0 0
0 0 2 3 2 0 0
6 6 6 6 6 6 6"""
# Fig. 3.6(a): a pair of 2s two sites apart joined by a path (4 1 5) over them; 2s must come in
# pairs, but a row 2 3 2 3 2 is consistent locally, so Algorithm 3.1 may go on after its model
# can no longer be completed.


def picture_image(text):
    rows = [[int(v) for v in line.split()] for line in text.strip().splitlines()]
    height = len(rows)
    return label_image((len(rows[0]), height, 1), lambda x, y, z: rows[height - 1 - y][x])


def main():
    examples = os.path.join(DATA, "Examples")
    malformed = os.path.join(DATA, "Malformed")
    os.makedirs(examples, exist_ok=True)
    os.makedirs(malformed, exist_ok=True)

    write(label_image((7, 7, 5), village), os.path.join(examples, "Village.vti"))
    text_examples(examples, malformed)
    vox_examples(examples, malformed)
    tileset_example(DATA)
    sample_images(DATA)
    write(label_image((4, 4, 1), lambda x, y, z: (x + y) % 2), os.path.join(examples, "Checkerboard.vti"))
    write(label_image((6, 1, 8), ball), os.path.join(examples, "Ball.vti"))
    write(picture_image(FIG_3_5A), os.path.join(examples, "Fallible-Fig3.5a.vti"))
    write(picture_image(FIG_3_6A), os.path.join(examples, "Fallible-Fig3.6a.vti"))

    # Labels as cell data (one label per voxel) must read the same as point data.
    cells = vtkImageData()
    cells.SetDimensions(4, 4, 2)
    a = vtkIntArray()
    a.SetName("Label")
    for z in range(1):
        for y in range(3):
            for x in range(3):
                a.InsertNextValue((x + y) % 2)
    cells.GetCellData().AddArray(a)
    write(cells, os.path.join(examples, "CheckerboardCells.vti"))

    write(label_image((3, 3, 1), lambda x, y, z: 1.0, name="Density", array_type=vtkFloatArray),
          os.path.join(malformed, "no-label-array.vti"))
    write(label_image((3, 3, 1), lambda x, y, z: 0.5 * x, array_type=vtkDoubleArray),
          os.path.join(malformed, "float-labels.vti"))
    write(label_image((3, 3, 1), lambda x, y, z: x, components=2),
          os.path.join(malformed, "two-component-labels.vti"))

    good = open(os.path.join(examples, "Checkerboard.vti")).read()
    with open(os.path.join(malformed, "truncated.vti"), "w") as f:
        f.write(good[: len(good) // 2])
    with open(os.path.join(malformed, "not-xml.vti"), "w") as f:
        f.write("this is not a VTK file\n\x01\x02 binary junk\n")
    with open(os.path.join(malformed, "huge-extent.vti"), "w") as f:
        f.write(good.replace('WholeExtent="0 3 0 3 0 0"', 'WholeExtent="0 99999 0 99999 0 99999"')
                    .replace('Extent="0 3 0 3 0 0"', 'Extent="0 99999 0 99999 0 99999"'))
    with open(os.path.join(malformed, "too-few-values.vti"), "w") as f:
        f.write(good.replace('WholeExtent="0 3 0 3 0 0"', 'WholeExtent="0 3 0 4 0 0"')
                    .replace('Piece Extent="0 3 0 3 0 0"', 'Piece Extent="0 3 0 4 0 0"'))


def write_text_model(path, dims, fn, objects=None, scene="Blender Scenes/village.blend"):
    """The original model-synthesis text format as that program writes it: 3 header lines,
    X Y Z, a blank line, each slice as X rows of Y values ("%2d ") and a blank line, then the
    <Objects> trailer: the scene line, then one entry per label 1, 2, ... (a free-text line,
    '$'-prefixed piece names, '#')."""
    nx, ny, nz = dims
    text = ("ModelSynth test example.  Do not insert or delete lines from this file.\n\n"
            "x, y, and z extents\n%d %d %d\n\n" % dims)
    for z in range(nz):
        for x in range(nx):
            text += "".join("%2d " % fn(x, y, z) for y in range(ny)) + "\n"
        text += "\n"
    if objects:
        text += "<Objects>\n" + scene + "\n"
        for label, names in objects:
            text += "".join(l + "\n" for l in [str(label)] + ["$" + n for n in names] + ["#"])
    with open(path, "w") as f:
        f.write(text)


def text_examples(examples, malformed):
    write_text_model(os.path.join(examples, "Village.txt"), (7, 7, 5), village,
                     [(1, ["ground_tile"]), (2, ["wall", "window"]), (3, ["roof"])])
    header = "a\nb\nc\n"
    bad = {
        "text-short-row.txt": header + "2 3 1\n1 1 1\n1 1\n<Objects>\nscene\n",
        "text-bad-dimensions.txt": header + "2 three 1\n",
        "text-huge.txt": header + "100000 100000 100000\n0\n",
        "text-missing-slice.txt": header + "1 2 2\n1 1\n",
        "text-bad-objects.txt": header + "1 1 1\n4\n<Objects>\nscene\n4\nwall\n#\n",
    }
    for name, text in bad.items():
        with open(os.path.join(malformed, name), "w") as f:
            f.write(text)


def vox_bytes(dims, fn, palette=True, chunks=None, colours=None):
    """A MagicaVoxel file: MAIN { SIZE, XYZI, RGBA } (or the given child chunks); @p colours maps
    palette indices to (r, g, b), the others grey (by default, a colour ramp)."""
    import struct

    def chunk(cid, content, children=b""):
        return cid + struct.pack("<II", len(content), len(children)) + content + children

    nx, ny, nz = dims
    if chunks is None:
        voxels = [(x, y, z, fn(x, y, z)) for z in range(nz) for y in range(ny) for x in range(nx)
                  if fn(x, y, z) != 0]
        chunks = chunk(b"SIZE", struct.pack("<III", nx, ny, nz))
        chunks += chunk(b"XYZI", struct.pack("<I", len(voxels)) + b"".join(struct.pack("<BBBB", *v) for v in voxels))
        if colours is not None:
            chunks += chunk(b"RGBA", b"".join(struct.pack("<BBBB", *colours.get(i, (128, 128, 128)), 255)
                                              for i in range(1, 257)))
        elif palette:
            colours = b"".join(struct.pack("<BBBB", (37 * i) % 256, (91 * i) % 256, (53 * i) % 256, 255)
                               for i in range(1, 257))
            chunks += chunk(b"RGBA", colours)
    return b"VOX " + struct.pack("<I", 150) + chunk(b"MAIN", b"", chunks)


def vox_examples(examples, malformed):
    import struct

    with open(os.path.join(examples, "Village.vox"), "wb") as f:
        f.write(vox_bytes((7, 7, 5), village))
    with open(os.path.join(examples, "Houses.vox"), "wb") as f:
        f.write(vox_bytes((9, 8, 5), houses, colours=HOUSE_COLOURS))
    good = vox_bytes((7, 7, 5), village)
    bad = {
        "vox-bad-magic.vox": b"VOXX" + good[4:],
        "vox-truncated.vox": good[: len(good) // 2],
        "vox-no-model.vox": b"VOX " + struct.pack("<I", 150) + b"MAIN" + struct.pack("<II", 0, 0),
        "vox-voxel-outside.vox": vox_bytes((2, 2, 2), None, chunks=(
            b"SIZE" + struct.pack("<IIIII", 12, 0, 2, 2, 2)
            + b"XYZI" + struct.pack("<III", 8, 0, 1) + struct.pack("<BBBB", 5, 0, 0, 1))),
        "vox-count-too-large.vox": vox_bytes((2, 2, 2), None, chunks=(
            b"SIZE" + struct.pack("<IIIII", 12, 0, 2, 2, 2)
            + b"XYZI" + struct.pack("<III", 8, 0, 1000000) + struct.pack("<BBBB", 0, 0, 0, 1))),
        "vox-huge-size.vox": vox_bytes((2, 2, 2), None, chunks=(
            b"SIZE" + struct.pack("<IIIII", 12, 0, 4000, 4000, 4000))),
    }
    for name, data in bad.items():
        with open(os.path.join(malformed, name), "wb") as f:
            f.write(data)


LINES_XML = """<?xml version="1.0"?>
<!-- Pipes: empty space, a straight line (I: orientation 0 is horizontal) and a corner
     (L: orientation 0 joins the top and the right edge). Every rule joins matching edges;
     ModelSynth expands each to all rotations and reflections. -->
<set unique="False">
  <tiles>
    <tile name="empty" symmetry="X" weight="2.0"/>
    <tile name="line" symmetry="I"/>
    <tile name="corner" symmetry="L" weight="0.5"/>
  </tiles>
  <neighbors>
    <neighbor left="empty" right="empty"/>
    <neighbor left="line" right="line"/>
    <neighbor left="line 1" right="line 1"/>
    <neighbor left="line 1" right="empty"/>
    <neighbor left="line" right="corner 1"/>
    <neighbor left="corner" right="line"/>
    <neighbor left="corner" right="corner 1"/>
    <neighbor left="empty" right="corner"/>
    <neighbor left="line 1" right="corner"/>
  </neighbors>
  <subsets>
    <subset name="straight"><tile name="empty"/><tile name="line"/></subset>
  </subsets>
</set>
"""


def tileset_example(data):
    """Data/Tilesets/Lines.xml and its 8 x 8 tile images in Data/Tilesets/Lines/."""
    from vtkmodules.vtkIOImage import vtkPNGWriter
    from vtkmodules.vtkCommonCore import vtkUnsignedCharArray

    folder = os.path.join(data, "Tilesets", "Lines")
    os.makedirs(folder, exist_ok=True)
    with open(os.path.join(data, "Tilesets", "Lines.xml"), "w") as f:
        f.write(LINES_XML)
    n = 8
    background, pipe = (30, 30, 40, 255), (230, 200, 60, 255)
    shapes = {
        "empty": lambda i, j: False,
        "line": lambda i, j: j in (3, 4),                                  # left to right
        "corner": lambda i, j: (i in (3, 4) and j >= 3) or (j in (3, 4) and i >= 3),  # top, right
    }
    for name, inside in shapes.items():
        image = vtkImageData()
        image.SetDimensions(n, n, 1)
        rgba = vtkUnsignedCharArray()
        rgba.SetNumberOfComponents(4)
        for j in range(n):          # rows bottom first
            for i in range(n):
                rgba.InsertNextTuple4(*(pipe if inside(i, j) else background))
        image.GetPointData().SetScalars(rgba)
        writer = vtkPNGWriter()
        writer.SetInputData(image)
        writer.SetFileName(os.path.join(folder, name + ".png"))
        writer.Write()


# Image samples for the overlapping model, as text art (top row first), one character a colour.
SAMPLE_COLOURS = {
    ".": (150, 200, 255, 255),  # sky
    "#": (110, 75, 40, 255),    # earth
    "|": (40, 150, 50, 255),    # stem
    "o": (230, 60, 90, 255),    # flower
    "W": (20, 20, 20, 255),     # wall
    " ": (235, 235, 225, 255),  # floor
    "r": (170, 60, 40, 255),    # brick
    "m": (200, 200, 190, 255),  # mortar
    "=": (90, 90, 95, 255),     # road
    "B": (150, 70, 50, 255),    # building wall
    "R": (200, 120, 80, 255),   # roof
    "g": (70, 160, 60, 255),    # park
}
SAMPLES = {
    # Flowers on stems between sky and earth: for --ground (the earth stays at the bottom).
    "Meadow": [
        "................",
        "................",
        "................",
        "..o.........o...",
        "..|....o....|...",
        "..|....|....|...",
        "..|....|..o.|...",
        "..|....|..|.|...",
        "################",
        "################",
    ],
    # Rooms with doors, walls one pixel thick: all eight symmetries.
    "Rooms": [
        "WWWWWWWWWWWWWWWW",
        "W    W         W",
        "W    W         W",
        "W              W",
        "W    W         W",
        "WWWWWW WWWWWWWWW",
        "W       W      W",
        "W       W      W",
        "W              W",
        "W       W      W",
        "W       W      W",
        "WWWW WWWWWWW WWW",
        "W         W    W",
        "W              W",
        "W         W    W",
        "WWWWWWWWWWWWWWWW",
    ],
    # A brick wall: no 3 x 3 window of one colour, so blocks start from layers of rows.
    "Bricks": [
        "mmmmmmmm",
        "rrrmrrrr",
        "rrrmrrrr",
        "mmmmmmmm",
        "rrrrrrmr",
        "rrrrrrmr",
    ],
    # A maze with corridors one pixel wide (WaveFunctionCollapse's mazes are hard for it).
    "Maze": [
        "WWWWWWWWWWWWWWW",
        "W   W         W",
        "WWW W WWWWWWW W",
        "W   W   W   W W",
        "W WWWWW W W W W",
        "W   W W W W   W",
        "WWW W W W WWW W",
        "W W W W W   W W",
        "W W W W WWW W W",
        "W   W   W   W W",
        "W WWWWW W WWW W",
        "W W   W W W   W",
        "W W W WWW W WWW",
        "W   W     W   W",
        "WWWWWWWWWWWWWWW",
    ],
    # City blocks between roads: buildings (walls around roofs) and parks.
    "City": [
        "================",
        "=BBBB=BBBBB=gggg",
        "=BRRB=BRRRB=gggg",
        "=BRRB=BRRRB=gggg",
        "=BRRB=BRRRB=gggg",
        "=BBBB=BBBBB=gggg",
        "================",
        "=BBBB=ggggg=BBBB",
        "=BRRB=ggggg=BRRB",
        "=BRRB=ggggg=BRRB",
        "=BBBB=ggggg=BBBB",
        "================",
        "=BBBB=BBBBB=BBBB",
        "=BRRB=BRRRB=BRRB",
        "=BRRB=BRRRB=BRRB",
        "=BBBB=BBBBB=BBBB",
    ],
}


def sample_images(data):
    """Data/Samples/<name>.png from SAMPLES."""
    from vtkmodules.vtkIOImage import vtkPNGWriter
    from vtkmodules.vtkCommonCore import vtkUnsignedCharArray

    folder = os.path.join(data, "Samples")
    os.makedirs(folder, exist_ok=True)
    for name, rows in SAMPLES.items():
        image = vtkImageData()
        image.SetDimensions(len(rows[0]), len(rows), 1)
        rgba = vtkUnsignedCharArray()
        rgba.SetNumberOfComponents(4)
        for row in reversed(rows):  # VTK's rows are bottom first
            for c in row:
                rgba.InsertNextTuple4(*SAMPLE_COLOURS[c])
        image.GetPointData().SetScalars(rgba)
        writer = vtkPNGWriter()
        writer.SetInputData(image)
        writer.SetFileName(os.path.join(folder, name + ".png"))
        writer.Write()


# Pattern exemplars (factor-graph synthesis): tilesets whose tiles are drawn as 8 x 8 text art,
# exemplars as text art over the tiles (top row first; one character a tile). Every tile has
# symmetry X, so label k is tile k; the pairs come from the exemplars, not from the XML.
PATTERN_PALETTE = {
    ".": (160, 205, 250, 255),  # sky / grass / paper
    "#": (205, 180, 140, 255),  # stone
    "d": (120, 100, 80, 255),   # dark stone, lines
    "w": (60, 90, 130, 255),    # glass
    "f": (240, 240, 235, 255),  # frame
    "b": (110, 60, 40, 255),    # door wood
    "r": (150, 50, 40, 255),    # roof
    "g": (90, 170, 80, 255),    # grass
    "t": (40, 110, 50, 255),    # tree
    "a": (70, 70, 75, 255),     # asphalt
    "y": (235, 210, 80, 255),   # road marking
    "h": (200, 90, 70, 255),    # house roof
    "B": (120, 125, 140, 255),  # tall building
    "k": (30, 30, 30, 255),     # ink
    "p": (250, 248, 235, 255),  # paper
}
WALL_PIXELS = ["########"] * 8
PATTERN_SETS = {
    "Facade": {
        "tiles": [
            (".", "sky", ["........"] * 8),
            ("-", "cornice", ["rrrrrrrr", "rrrrrrrr", "dddddddd", "########", "dddddddd",
                              "########", "########", "########"]),
            ("#", "wall", WALL_PIXELS),
            ("T", "window top", ["########", "#dddddd#", "#ffffff#", "#fwwwwf#", "#fwwwwf#",
                                 "#fwwwwf#", "#fwwwwf#", "#fwwwwf#"]),
            ("W", "window middle", ["#fwwwwf#", "#fwwwwf#", "#ffffff#", "#fwwwwf#", "#fwwwwf#",
                                    "#fwwwwf#", "#fwwwwf#", "#fwwwwf#"]),
            ("_", "window sill", ["#fwwwwf#", "#fwwwwf#", "#ffffff#", "dddddddd", "########",
                                  "########", "########", "########"]),
            ("D", "door top", ["##dddd##", "#dffffd#", "#fbbbbf#", "#fbbbbf#", "#fbbbbf#",
                               "#fbbbbf#", "#fbbbbf#", "#fbbbbf#"]),
            ("d", "door", ["#fbbbbf#", "#fbbbbf#", "#fbbbbf#", "#fbbyyf#", "#fbbbbf#",
                           "#fbbbbf#", "#fbbbbf#", "#fbbbbf#"]),
            ("=", "plinth", ["dddddddd", "########", "dddddddd", "dddddddd", "dddddddd",
                             "dddddddd", "dddddddd", "dddddddd"]),
            ("~", "string course", ["########", "dddddddd", "ffffffff", "ffffffff", "dddddddd",
                                    "########", "########", "########"]),
        ],
        "exemplars": {
            # Rectangular: windows four tiles high (top, two middles, sill), three tiles apart,
            # under a cornice; a string course between the floors; a door four tiles high on the
            # plinth. Plain wall never spans four tiles in a row.
            "facade-rectangular": [
                "............",
                "............",
                "------------",
                "#T##T##T##T#",
                "#W##W##W##W#",
                "#W##W##W##W#",
                "#_##_##_##_#",
                "~~~~~~~~~~~~",
                "#T##D##T##T#",
                "#W##d##W##W#",
                "#W##d##W##W#",
                "#_##d##_##_#",
                "============",
            ],
            # L-shaped: a tower on the left of a wider ground block.
            "facade-l-shaped": [
                "...............",
                "-------........",
                "#T##T##........",
                "#W##W##........",
                "#W##W##........",
                "#_##_##........",
                "~~~~~~~--------",
                "#T##T##T##T##T#",
                "#W##W##W##W##W#",
                "#W##W##W##W##W#",
                "#_##_##_##_##_#",
                "~~~~~~~~~~~~~~~",
                "#T##D##T##T##D#",
                "#W##d##W##W##d#",
                "#W##d##W##W##d#",
                "#_##d##_##_##d#",
                "===============",
            ],
        },
    },
    "City": {
        "tiles": [
            (".", "grass", ["gggggggg"] * 8),
            ("-", "road", ["gggggggg", "aaaaaaaa", "aaaaaaaa", "ayyaayya", "aaaaaaaa",
                           "aaaaaaaa", "gggggggg", "gggggggg"]),
            ("|", "road north", ["gaaaaaag", "gaaaaaag", "gaayaaag", "gaayaaag", "gaaaaaag",
                                 "gaayaaag", "gaayaaag", "gaaaaaag"]),
            ("+", "crossroad", ["gaaaaaag", "aaaaaaaa", "aaaaaaaa", "aaaaaaaa", "aaaaaaaa",
                                "aaaaaaaa", "aaaaaaaa", "gaaaaaag"]),
            ("v", "junction south", ["gggggggg", "aaaaaaaa", "aaaaaaaa", "aaaaaaaa",
                                     "aaaaaaaa", "aaaaaaaa", "aaaaaaaa", "gaaaaaag"]),
            ("^", "junction north", ["gaaaaaag", "aaaaaaaa", "aaaaaaaa", "aaaaaaaa",
                                     "aaaaaaaa", "aaaaaaaa", "gggggggg", "gggggggg"]),
            ("a", "corner east south", ["gggggggg", "gaaaaaaa", "gaaaaaaa", "gaaaaaaa",
                                        "gaaaaaaa", "gaaaaaaa", "gaaaaaaa", "gaaaaaag"]),
            ("b", "corner west south", ["gggggggg", "aaaaaaag", "aaaaaaag", "aaaaaaag",
                                        "aaaaaaag", "aaaaaaag", "aaaaaaag", "gaaaaaag"]),
            ("c", "corner east north", ["gaaaaaag", "gaaaaaaa", "gaaaaaaa", "gaaaaaaa",
                                        "gaaaaaaa", "gaaaaaaa", "gggggggg", "gggggggg"]),
            ("e", "corner west north", ["gaaaaaag", "aaaaaaag", "aaaaaaag", "aaaaaaag",
                                        "aaaaaaag", "aaaaaaag", "gggggggg", "gggggggg"]),
            (">", "junction east", ["gaaaaaag", "gaaaaaaa", "gaaaaaaa", "gaaaaaaa",
                                    "gaaaaaaa", "gaaaaaaa", "gaaaaaaa", "gaaaaaag"]),
            ("<", "junction west", ["gaaaaaag", "aaaaaaag", "aaaaaaag", "aaaaaaag",
                                    "aaaaaaag", "aaaaaaag", "aaaaaaag", "gaaaaaag"]),
            ("1", "dead end east", ["gggggggg", "ggggaaaa", "gggaaaaa", "ggaaaaaa", "ggaaaaaa",
                                    "gggaaaaa", "ggggaaaa", "gggggggg"]),
            ("2", "dead end west", ["gggggggg", "aaaagggg", "aaaaaggg", "aaaaaagg", "aaaaaagg",
                                    "aaaaaggg", "aaaagggg", "gggggggg"]),
            ("3", "dead end north", ["gaaaaaag", "gaaaaaag", "gaaaaaag", "ggaaaagg", "gggaaggg",
                                     "gggggggg", "gggggggg", "gggggggg"]),
            ("4", "dead end south", ["gggggggg", "gggggggg", "gggggggg", "gggaaggg", "ggaaaagg",
                                     "gaaaaaag", "gaaaaaag", "gaaaaaag"]),
            ("h", "house", ["gggggggg", "gghhhhgg", "ghhhhhhg", "hhhhhhhh", "g######g",
                            "g##dd##g", "g##dd##g", "gggggggg"]),
            ("B", "tower", ["BBBBBBBB", "BkBkBkBB", "BBBBBBBB", "BkBkBkBB", "BBBBBBBB",
                            "BkBkBkBB", "BBBBBBBB", "BkBkBkBB"]),
            ("t", "trees", ["gggggggg", "ggttgggg", "gttttggg", "ggttgttg", "gggggttt",
                            "gttggttg", "ttttgggg", "gttggggg"]),
        ],
        "exemplars": {
            # Urban: a grid of roads every four tiles, blocks of towers.
            "city-urban": [
                "BBB|BBB|BBB|",
                "BBB|BBB|BBB|",
                "BBB|B.B|BBB|",
                "---+---+---+",
                "BBB|BBB|BBB|",
                "B.B|BBB|.t.|",
                "BBB|BBB|BBB|",
                "---+---+---+",
                "BBB|BBB|BBB|",
                "BBB|.B.|BBB|",
                "BBB|BBB|BBB|",
                "---+---+---+",
            ],
            # Suburban: winding roads with junctions and dead ends, houses and trees.
            "city-suburban": [
                "h.t.|.h..4.t.h",
                ".h..|.t..|.h..",
                "----+----e...t",
                "..h.|..h...h..",
                "t...|.t...t...",
                ".h..c---v--2.h",
                "..t.....|..t..",
                "---b.h..|.h...",
                ".h.|..t.>-----",
                "t..|.h..|.t.h.",
                "...c---2|..4..",
                ".h.t.h..|..|.t",
                "--------^--^--",
                "h.t.h.t.h..t.h",
            ],
        },
    },
    "Border": {
        "tiles": [
            (".", "blank", ["pppppppp"] * 8),
            ("=", "edge top", ["pppppppp", "kkkkkkkk", "pppppppp", "kkkkkkkk", "pppppppp",
                               "pppppppp", "pppppppp", "pppppppp"]),
            ("_", "edge bottom", ["pppppppp", "pppppppp", "pppppppp", "pppppppp", "kkkkkkkk",
                                  "pppppppp", "kkkkkkkk", "pppppppp"]),
            ("[", "edge left", ["pkpkpppp"] * 8),
            ("]", "edge right", ["ppppkpkp"] * 8),
            ("1", "corner top left", ["pppppppp", "pkkkkkkk", "pkpppppp", "pkpkkkkk", "pkpkpppp",
                                      "pkpkpppp", "pkpkpppp", "pkpkpppp"]),
            ("2", "corner top right", ["pppppppp", "kkkkkkkp", "ppppppkp", "kkkkpkkp",
                                       "ppppkpkp", "ppppkpkp", "ppppkpkp", "ppppkpkp"]),
            ("3", "corner bottom left", ["pkpkpppp", "pkpkpppp", "pkpkpppp", "pkpkpppp",
                                         "pkpkkkkk", "pkpppppp", "pkkkkkkk", "pppppppp"]),
            ("4", "corner bottom right", ["ppppkpkp", "ppppkpkp", "ppppkpkp", "ppppkpkp",
                                          "kkkkkpkp", "ppppppkp", "kkkkkkkp", "pppppppp"]),
            ("o", "rosette", ["pppppppp", "pppkkppp", "ppkppkpp", "pkpkkpkp", "pkpkkpkp",
                              "ppkppkpp", "pppkkppp", "pppppppp"]),
            ("(", "curl left", ["pppppppp", "ppkkkppp", "pkpppppp", "pkppkkkk", "pkppkppp",
                                "ppkkpppp", "pppppppp", "pppppppp"]),
            (")", "curl right", ["pppppppp", "pppkkkpp", "ppppppkp", "kkkkppkp", "pppkppkp",
                                 "ppppkkpp", "pppppppp", "pppppppp"]),
        ],
        "mirror": "[],12,34,()",
        "exemplars": {
            # A frame: corners, edges, curls in mirrored pairs around rosettes, blank inside.
            "border": [
                "1==========2",
                "[(o)....(o)]",
                "[..........]",
                "[o........o]",
                "[..........]",
                "[..........]",
                "[o........o]",
                "[..........]",
                "[(o)....(o)]",
                "3__________4",
            ],
        },
    },
}


# Zonings (zone ids as digits, top row first). An L-shaped facade as Fig. 9(b) zones one: 0 the
# facade, 1 sky, 2 the plinth, 3 string courses (the floors' heights). A frame: 1 its ring, 2 a
# band that may hold ornaments, 0 blank paper inside.
PATTERN_ZONES = {
    "facade-l-zones": ["1" * 28] * 2 + ["0" * 14 + "1" * 14] * 5 + ["0" * 28] * 5 + ["3" * 28]
    + ["0" * 28] * 4 + ["2" * 28],
    # Style mixing (Fig. 15): the left half takes its soft factors from exemplar 1, the right half
    # from exemplar 2 (stretched over the output).
    "city-halves-zones": ["12"],
    "border-zones": ["1" * 24] + ["1" + "2" * 22 + "1"] * 2 + ["1" + "22" + "0" * 18 + "22" + "1"] * 10
    + ["1" + "2" * 22 + "1"] * 2 + ["1" * 24],
}


def pattern_data(data):
    """Data/Patterns: NAME.xml with NAME/<tile>.png for each set, and the exemplars as .vti."""
    from vtkmodules.vtkIOImage import vtkPNGWriter
    from vtkmodules.vtkCommonCore import vtkUnsignedCharArray

    folder = os.path.join(data, "Patterns")
    for set_name, spec in PATTERN_SETS.items():
        os.makedirs(os.path.join(folder, set_name), exist_ok=True)
        chars = [c for c, _, _ in spec["tiles"]]
        lines = ['<?xml version="1.0"?>',
                 "<!-- Tiles of the bundled %s pattern exemplars (label k is tile k)." % set_name,
                 "     Pattern synthesis learns the pairs from the exemplars; no neighbor rules. -->",
                 '<set size="8">', "  <tiles>"]
        for c, name, art in spec["tiles"]:
            lines.append('    <tile name="%s" symmetry="X"/>' % name)
            image = vtkImageData()
            image.SetDimensions(8, 8, 1)
            rgba = vtkUnsignedCharArray()
            rgba.SetNumberOfComponents(4)
            for row in reversed(art):
                assert len(row) == 8, (name, row)
                for p in row:
                    rgba.InsertNextTuple4(*PATTERN_PALETTE[p])
            image.GetPointData().SetScalars(rgba)
            writer = vtkPNGWriter()
            writer.SetInputData(image)
            writer.SetFileName(os.path.join(folder, set_name, name + ".png"))
            writer.Write()
        lines += ["  </tiles>", "</set>", ""]
        with open(os.path.join(folder, set_name + ".xml"), "w") as f:
            f.write("\n".join(lines))
        for name, rows in spec["exemplars"].items():
            assert all(len(r) == len(rows[0]) for r in rows), name
            h = len(rows)
            write(label_image((len(rows[0]), h, 1),
                              lambda x, y, z: chars.index(rows[h - 1 - y][x])),
                  os.path.join(folder, name + ".vti"))
    for name, rows in PATTERN_ZONES.items():
        assert all(len(r) == len(rows[0]) for r in rows), name
        h = len(rows)
        write(label_image((len(rows[0]), h, 1), lambda x, y, z: int(rows[h - 1 - y][x]), name="Zone"),
              os.path.join(folder, name + ".vti"))
    # Crossroads every 20 tiles over a 170 x 170 city (-1: free), as Yeh et al. fix them.
    write(label_image((170, 170, 1), lambda x, y, z: 3 if x % 20 == 10 and y % 20 == 10 else -1),
          os.path.join(folder, "city-crossroads-170.vti"))
    # A 48 x 48 suburban town's pinned sites (-1: free): four road sites near the corners, which
    # one road network must join, and three houses (taken from a model of city-suburban.vti, so
    # they can hold together); the constraints-together example of guide-command-line.md.
    town_pins = {(6, 5): 2, (41, 5): 2, (5, 42): 1, (42, 42): 2, (23, 24): 16, (14, 40): 16,
                 (31, 11): 16}
    write(label_image((48, 48, 1), lambda x, y, z: town_pins.get((x, y), -1)),
          os.path.join(folder, "city-pins-48.vti"))


# "MS" in a 5-row bitmap font, one character per 5 columns with a gap column.
LETTERS = [
    "X...X.XXXXX",
    "XX.XX.X....",
    "X.X.X.XXXXX",
    "X...X.....X",
    "X...X.XXXXX",
]


def continuous_data(data):
    """Data/Continuous/letters-guide.vti: a large-scale guide (TVCG 4.7) spelling "MS" over the
    output box of a continuous run: Weight_1 and Weight_2 (the first two object types) are 1 on
    the letters and 0
    elsewhere (one layer in z: the guide is stretched over the box)."""
    rows, cols = len(LETTERS), len(LETTERS[0])
    border = 1
    dims = (cols + 2 * border, rows + 2 * border, 1)

    def on(x, y, z):
        r, c = dims[1] - 1 - y - border, x - border  # row 0 at the top (+y)
        return 1.0 if 0 <= r < rows and 0 <= c < cols and LETTERS[r][c] == "X" else 0.0

    image = label_image(dims, on, name="Weight_1", array_type=vtkFloatArray)
    roof = label_image(dims, on, name="Weight_2", array_type=vtkFloatArray)
    image.GetPointData().AddArray(roof.GetPointData().GetArray("Weight_2"))
    write(image, os.path.join(data, "Continuous", "letters-guide.vti"))
    network_examples(os.path.join(data, "Continuous"))
    silo_example(os.path.join(data, "Continuous"))
    blender_example(os.path.join(data, "Continuous"))


def blender_example(folder):
    """Data/Continuous/house-blender.obj (and .mtl): house.obj as Blender 4.1's OBJ exporter
    writes it with its default settings: Forward -Z, Up Y (Blender's (x, y, z) is the file's
    (x, z, -y)), each object's vertices, then its normals and UVs, smoothing off, a material per
    object, faces as v/vt/vn, objects named as a Blender user names them. Read with --up y (the
    reader's UpAxis Y) it is house.obj."""
    objects, points = [], []
    with open(os.path.join(folder, "house.obj")) as f:
        for line in f:
            words = line.split()
            if words and words[0] == "o":
                objects.append((words[1].capitalize(), []))
            elif words and words[0] == "v":
                points.append(tuple(float(w) for w in words[1:4]))
            elif words and words[0] == "f":
                objects[-1][1].append([int(w) for w in words[1:]])
    lines = ["# Blender 4.1.1", "# www.blender.org", "mtllib house-blender.mtl"]
    normals, uvs, written = [], 0, 0
    for name, faces in objects:
        used = sorted({i for face in faces for i in face})
        index = {i: written + k + 1 for k, i in enumerate(used)}
        written += len(used)
        lines.append("o " + name)
        lines += ["v %.6f %.6f %.6f" % (points[i - 1][0], points[i - 1][2], -points[i - 1][1] + 0.0)
                  for i in used]
        corners = []
        for face in faces:
            p = [points[i - 1] for i in face]
            a = [p[1][c] - p[0][c] for c in range(3)]
            b = [p[2][c] - p[0][c] for c in range(3)]
            n = [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]
            length = math.sqrt(sum(c * c for c in n))
            n = (n[0] / length, n[2] / length, -n[1] / length)
            text = "vn %.4f %.4f %.4f" % n
            if text not in normals:
                normals.append(text)
                lines.append(text)
            corners.append(normals.index(text) + 1)
        for face in faces:
            for k in range(len(face)):
                lines.append("vt %.6f %.6f" % (0.125 * ((uvs + k) % 8), 0.25 * ((uvs + k) % 4)))
            uvs += len(face)
        lines += ["s 0", "usemtl " + ("Brick" if name == "Wall" else "Tiles")]
        first_uv = uvs - sum(len(face) for face in faces) + 1
        for face, n in zip(faces, corners):
            lines.append("f " + " ".join("%d/%d/%d" % (index[i], first_uv + k, n)
                                         for k, i in enumerate(face)))
            first_uv += len(face)
    with open(os.path.join(folder, "house-blender.obj"), "w") as f:
        f.write("\n".join(lines) + "\n")
    with open(os.path.join(folder, "house-blender.mtl"), "w") as f:
        f.write("# Blender 4.1.1 MTL File: 'house.blend'\n# www.blender.org\n")
        for name, colour in (("Brick", "0.600000 0.250000 0.150000"), ("Tiles", "0.300000 0.300000 0.350000")):
            f.write("\nnewmtl %s\nNs 250.000000\nKa 1.000000 1.000000 1.000000\nKd %s\n"
                    "Ks 0.500000 0.500000 0.500000\nKe 0.000000 0.000000 0.000000\nNi 1.450000\n"
                    "d 1.000000\nillum 2\n" % (name, colour))


def silo_example(folder):
    """Data/Continuous/silo.obj, the box [0, 2] x [0, 2] x [0, 4] cut along its vertical diagonal
    into two triangular prisms of types "silo" and "silo2" (the cut is a face synthesis keeps),
    as the bounding volume of a cylinder, and cylinder.obj, the detail in that box (TVCG 4.8):
    the diagonal makes synthesis scale the box uniformly in x and y, freely in z, so every
    substituted cylinder stays round."""
    with open(os.path.join(folder, "silo.obj"), "w") as f:
        f.write("# Silos for bounding volumes (TVCG 4.8): the box [0, 2] x [0, 2] x [0, 4] cut along\n"
                "# its vertical diagonal into two triangular prisms of types silo and silo2, which\n"
                "# model synthesis can only scale uniformly in x and y. Substitute a cylinder:\n"
                "# msynth synthesize Data/Continuous/silo.obj --size 16 16 8 --grounded\n"
                "#   --detail silo+silo2=Data/Continuous/cylinder.obj\n")
        for name, corners, first in (("silo", ((0, 0), (2, 0), (0, 2)), 0),
                                     ("silo2", ((2, 0), (2, 2), (0, 2)), 6)):
            f.write("o %s\n" % name)
            for z in (0, 4):
                f.write("".join("v %d %d %d\n" % (x, y, z) for x, y in corners))
            f.write("".join("f %s\n" % " ".join(str(first + i) for i in face) for face in
                            ((1, 3, 2), (4, 5, 6), (1, 2, 5, 4), (2, 3, 6, 5), (3, 1, 4, 6))))
    n = 32
    with open(os.path.join(folder, "cylinder.obj"), "w") as f:
        f.write("# A cylinder of radius 1 and height 4 in the box of silo.obj's bounding volume\n"
                "# ([0, 2] x [0, 2] x [0, 4]), %d sides.\no silo\n" % n)
        for z in (0, 4):
            for k in range(n):
                a = 2 * math.pi * k / n
                f.write("v %.9f %.9f %d\n" % (1 + math.cos(a), 1 + math.sin(a), z))
        f.write("f %s\n" % " ".join(str(n - k) for k in range(n)))
        f.write("f %s\n" % " ".join(str(n + 1 + k) for k in range(n)))
        for k in range(n):
            j = (k + 1) % n
            f.write("f %d %d %d %d\n" % (1 + k, 1 + j, n + 1 + j, n + 1 + k))


def network_examples(folder):
    """Data/Continuous/roads.obj (2D) and pipes.obj (3D): networks one unit wide on a lattice of
    period 4 (roads) and 6 (pipes), for connectivity from one seed with a width (TVCG 4.5, 4.6,
    Figs. 10 and 11)."""
    def write_obj(path, comment, name, points, faces):
        with open(path, "w") as f:
            f.write("".join("# %s\n" % line for line in comment))
            f.write("o %s\n" % name)
            f.write("".join("v %d %d %d\n" % p for p in points))
            f.write("".join("f %s\n" % " ".join(str(i + 1) for i in face) for face in faces))

    def grid(cells, axes):
        """Boundary faces of unit cells (a set of integer tuples, 2 or 3 axes), outward."""
        index, points, faces = {}, [], []

        def at(p):
            p = tuple(p) + (0,) * (3 - len(p))
            if p not in index:
                index[p] = len(points)
                points.append(p)
            return index[p]

        if axes == 2:  # each cell is a square polygon, counter-clockwise
            for x, y in sorted(cells):
                faces.append([at((x, y)), at((x + 1, y)), at((x + 1, y + 1)), at((x, y + 1))])
            return points, faces
        for c in sorted(cells):
            for axis in range(3):
                for d in (-1, 1):
                    n = list(c)
                    n[axis] += d
                    if tuple(n) in cells:
                        continue
                    o = list(c)
                    o[axis] += d == 1
                    a, b = (axis + 1) % 3, (axis + 2) % 3
                    quad = []
                    for u, v in ((0, 0), (1, 0), (1, 1), (0, 1)):
                        p = list(o)
                        p[a] += u
                        p[b] += v
                        quad.append(at(p))
                    faces.append(quad if d == 1 else quad[::-1])
        return points, faces

    roads = {(x, y) for x in range(9) for y in range(9) if x % 4 == 0 or y % 4 == 0}
    write_obj(os.path.join(folder, "roads.obj"), [
        "A road network (TVCG Fig. 10, in spirit): roads one unit wide on a 9 x 9 lattice of",
        "period 4, with corners, T junctions and a crossing, as unit squares of one object. Grow",
        "one network from a single seed, one plane spacing wide (never two across x and y):",
        "msynth synthesize Data/Continuous/roads.obj --size 40 40 0 --blocks 0",
        "  --connected road:1 --thickness road:xy"], "road", *grid(roads, 2))
    pipes = {(x, y, z) for x in range(13) for y in range(7) for z in range(7)
             if (x % 6 == 0) + (y % 6 == 0) + (z % 6 == 0) >= 2}
    write_obj(os.path.join(folder, "pipes.obj"), [
        "Pipes (TVCG Fig. 11, in spirit): square pipes one unit across along the edges of two",
        "cubes of side 7 sharing a face (corners and junctions). Grow one network from a single",
        "seed, one spacing across in every direction but the pipe's own:",
        "msynth synthesize Data/Continuous/pipes.obj --size 24 24 12 --blocks 0",
        "  --connected pipe:1 --thickness pipe:xy --thickness pipe:yz --thickness pipe:xz"],
        "pipe", *grid(pipes, 3))


if __name__ == "__main__":
    if sys.argv[1:] == ["samples"]:
        sample_images(DATA)
    elif sys.argv[1:] == ["patterns"]:
        pattern_data(DATA)
    elif sys.argv[1:] == ["continuous"]:
        continuous_data(DATA)
    else:
        main()
