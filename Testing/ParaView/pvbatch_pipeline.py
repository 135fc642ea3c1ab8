"""pvbatch: load the plugin, run reader -> transition tables -> VDB writer through proxies, read
the VDB back with the plugin's reader and check the values (also with OpenVDB's own Python
reader). Runs serially and under `mpirun -np 2 pvbatch --mpi`."""
import os

from paraview import servermanager
from paraview.simple import *  # noqa: F401,F403
from paraview.modules.vtkRemotingServerManager import vtkSMOrderedPropertyIterator

DATA = os.environ["MSYNTH_DATA"]
TMP = os.environ["MSYNTH_TMP"]

LoadPlugin(os.environ["MSYNTH_PLUGIN"], remote=False, ns=globals())

# Under `pvbatch --mpi` only rank 0 runs this script; the other ranks serve it (RMIs), so the
# script must not synchronise by itself (an explicit barrier would deadlock).
controller = servermanager.vtkProcessModule.GetProcessModule().GetGlobalController()
rank = controller.GetLocalProcessId() if controller else 0
ranks = controller.GetNumberOfProcesses() if controller else 1


def check(condition, message):
    if not condition:
        print("FAILED (rank %d): %s" % (rank, message), flush=True)
        os._exit(1)  # mpirun then stops every rank; sys.exit could leave others at a barrier


example = os.path.join(DATA, "Examples", "Village.vti")
reader = ModelSynthLabelGridReader(FileName=example)
tables = ModelSynthTransitionTables(Input=reader)
tables.UpdatePipeline()

# Fetch the tables to the client and recompute Eq. 3.2 from the fetched labels.
image = servermanager.Fetch(reader)
nx, ny, nz = image.GetDimensions()
labels = image.GetPointData().GetArray("Label")
check(labels is not None and labels.GetNumberOfTuples() == nx * ny * nz, "labels fetched")


def pair_counts(image):
    """{(axis, from, to): count} of Eq. 3.2 over a fetched label image (recomputed here)."""
    mx, my, mz = image.GetDimensions()
    a = image.GetPointData().GetArray("Label")
    at = lambda x, y, z: int(a.GetValue(x + mx * (y + my * z)))
    counts = {}
    for z in range(mz):
        for y in range(my):
            for x in range(mx):
                for axis, (dx, dy, dz) in enumerate(((1, 0, 0), (0, 1, 0), (0, 0, 1))):
                    if x + dx < mx and y + dy < my and z + dz < mz:
                        key = (axis, at(x, y, z), at(x + dx, y + dy, z + dz))
                        counts[key] = counts.get(key, 0) + 1
    return counts


value = lambda x, y, z: int(labels.GetValue(x + nx * (y + ny * z)))
expected = pair_counts(image)
transitions = servermanager.Fetch(tables, idx=0)
check(servermanager.Fetch(tables, idx=1).GetNumberOfRows() == 4, "four labels")
# Counts, not just pairs: under MPI a row computed on two ranks would show up twice.
got = {}
for r in range(transitions.GetNumberOfRows()):
    key = (transitions.GetValueByName(r, "Axis").ToInt(), transitions.GetValueByName(r, "From").ToInt(),
           transitions.GetValueByName(r, "To").ToInt())
    got[key] = got.get(key, 0) + transitions.GetValueByName(r, "Count").ToInt()
check(got == expected, "transition counts equal Eq. 3.2 (%d vs %d pairs)" % (len(got), len(expected)))

# Write through the writer proxy chosen by extension.
suffix = "mpi" if ranks > 1 else "serial"
path = os.path.join(TMP, "pvbatch-%s.vdb" % suffix)
if os.path.exists(path):
    os.remove(path)
writer = CreateWriter(path, reader)
check(writer.GetXMLName() == "MSOpenVDBWriter", "writer chosen for .vdb: " + writer.GetXMLName())
writer.WriteFloatLabels = 1
writer.UpdatePipeline()
del writer
check(os.path.exists(path), "VDB written")

# Read back through the plugin's VDB reader and compare every label.
back = ModelSynthOpenVDBReader(FileName=path)
back_image = servermanager.Fetch(back)
check(back_image.GetDimensions() == (nx, ny, nz), "dimensions round-trip")
back_labels = back_image.GetPointData().GetArray("Label")
check(back_labels is not None, "Label grid read back")
for i in range(nx * ny * nz):
    if back_labels.GetValue(i) != labels.GetValue(i):
        check(False, "label %d differs" % i)

# The render grids (WriteRenderGrids, on by default) are read back on the labels' extent;
# the plugin's property turns them off.
for name in ("density", "color", "surface"):
    check(back_image.GetPointData().GetArray(name) is not None, "render grid %s read back" % name)
bare_path = os.path.join(TMP, "pvbatch-%s-bare.vdb" % suffix)
writer = CreateWriter(bare_path, reader)
writer.WriteRenderGrids = 0
writer.LabelSurfaceBudget = 0
writer.UpdatePipeline()
del writer
bare = servermanager.Fetch(ModelSynthOpenVDBReader(FileName=bare_path))
check(bare.GetPointData().GetArray("density") is None, "WriteRenderGrids 0 writes no density")

# And with OpenVDB's own Python reader, from the float copy.
import pyopenvdb  # noqa: E402

grid = pyopenvdb.read(path, "Label_float")
accessor = grid.getConstAccessor()
for z in range(nz):
    for y in range(ny):
        for x in range(nx):
            check(accessor.getValue((x, y, z)) == float(value(x, y, z)),
                  "pyopenvdb value at %s" % ((x, y, z),))
leftovers = [n for n in os.listdir(TMP) if n.startswith("pvbatch-%s.vdb.tmp" % suffix)]
check(not leftovers, "no temporary files left: %s" % leftovers)

# Discrete synthesis through its proxy, checked against the example's pairs (Eq. 3.1) here.
synthesis = ModelSynthDiscreteSynthesis(Input=reader, OutputSize=[24, 20, 5], BlockSize=[8, 8, 5],
                                        Seed=2, UseBoundary=[1, 1, 1, 1, 1, 1],
                                        BoundaryLabels=[0, 0, 0, 0, 1, 0])
model = servermanager.Fetch(synthesis)
check(model.GetDimensions() == (24, 20, 5), "synthesized size")
unknown = set(pair_counts(model)) - set(expected)
check(not unknown, "every model pair occurs in the example (Eq. 3.1): %s" % sorted(unknown)[:3])
# The model in the original program's text format, through the plugin's writer proxy.
text_path = os.path.join(TMP, "pvbatch-%s-model.txt" % suffix)
text_writer = servermanager.writers.ModelSynthLabelGridWriter(Input=synthesis, FileName=text_path)
text_writer.UpdatePipeline()
del text_writer
with open(text_path) as f:
    words = f.read().split("\n", 3)[3].split()
mlabels = model.GetPointData().GetArray("Label")
check(words[:3] == ["24", "20", "5"], "text model dimensions")
check([int(w) for w in words[3:]] == [int(mlabels.GetValue(x + 24 * (y + 20 * z)))
                                      for z in range(5) for x in range(24) for y in range(20)],
      "text model values for z, for x, for y")
# The second port, Geometry: the model's voxel surface, which Apply shows in place of an outline
# (each rank holds a slab of it under MPI; fetched, they make one surface). Its faces are counted
# here from the labels: a non-empty site's side that meets another label or the outside.
mvalue = lambda x, y, z: int(mlabels.GetValue(x + 24 * (y + 20 * z)))
faces = 0
for z in range(5):
    for y in range(20):
        for x in range(24):
            here = mvalue(x, y, z)
            for dx, dy, dz in ((1, 0, 0), (-1, 0, 0), (0, 1, 0), (0, -1, 0), (0, 0, 1), (0, 0, -1)):
                qx, qy, qz = x + dx, y + dy, z + dz
                inside = 0 <= qx < 24 and 0 <= qy < 20 and 0 <= qz < 5
                faces += here != 0 and (not inside or mvalue(qx, qy, qz) != here)
surface = servermanager.Fetch(synthesis, None, None, 1)
check(surface.IsA("vtkPolyData") and surface.GetNumberOfCells() == faces,
      "the Geometry port has the model's %d voxel faces (got %d)" % (faces, surface.GetNumberOfCells()))
render_view = CreateRenderView()
shown = Show(OutputPort(synthesis, 1), render_view)
check(shown.Representation == "Surface" and list(shown.ColorArrayName) == ["CELLS", "Label"],
      "Apply shows the geometry coloured by Label: %s %s" % (shown.Representation, shown.ColorArrayName))
# ... through the plugin's categorical colour map: the legend lists the labels the model has
# (shown: non-empty), each in the colour the gallery's pictures give it (render-model.py).
label_map = GetColorTransferFunction("Label")
present = sorted({mvalue(x, y, z) for z in range(5) for y in range(20) for x in range(24)} - {0})
check(label_map.InterpretValuesAsCategories == 1 and
      sorted(int(v) for v in label_map.ActiveAnnotatedValues) == present,
      "Label is categorical, with the labels %s active (got %s)" % (present, list(label_map.ActiveAnnotatedValues)))
import importlib.util  # noqa: E402
spec = importlib.util.spec_from_file_location("render_model", os.path.join(
    os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__)))), "Utilities", "render-model.py"))
render_model = importlib.util.module_from_spec(spec)
spec.loader.exec_module(render_model)
colours = list(label_map.IndexedColors)
annotated = [int(v) for v in label_map.Annotations[::2]]
for label in list(range(0, 40)) + list(range(40, 1024, 37)) + [1023]:
    where = 3 * annotated.index(label)
    mine = render_model.label_colour(label)
    check(all(abs(colours[where + c] - mine[c]) < 1e-6 for c in range(3)),
          "label %d has the gallery's colour %s (got %s)" % (label, mine, colours[where:where + 3]))
check(len({tuple(round(255 * v) for v in colours[3 * annotated.index(t):3 * annotated.index(t) + 3])
           for t in range(1, 201)}) == 200, "labels 1-200 have 200 colours")
Hide(OutputPort(synthesis, 1), render_view)  # (a deleted view's representations live on, shown)
Delete(render_view)
del render_view

# Under MPI the blocks of each phase are spread over the ranks; the model is the one-process one.
processes = model.GetFieldData().GetArray("Processes").GetValue(0)
check(processes == ranks, "blocks spread over %d processes, expected %d" % (processes, ranks))
synthesis.DistributeBlocks = 0
alone = servermanager.Fetch(synthesis)
same = all(alone.GetPointData().GetArray("Label").GetValue(i) == model.GetPointData().GetArray("Label").GetValue(i)
           for i in range(24 * 20 * 5))
check(same, "the distributed model equals the one-process model")
synthesis.DistributeBlocks = 1

# The streaming pipeline's way: each process computes its own piece of the world from the blocks
# it depends on, with no exchange; fetched, the pieces make the one-process model.
synthesis.ComputeRequestedExtent = 1
# (Fetch brings rank 0's piece of image data; its extent says where it lies.)
piece = servermanager.Fetch(synthesis)
x0, x1, y0, y1, z0, z1 = piece.GetExtent()
# Pieces are slabs across x, the axis whose blocks' phase digit changes slowest (the most block
# origins: 5 along x's 24 sites in blocks of 8 every 4, 4 along y's 20), so cones reach least far.
check((x1 - x0 + 1) * ranks == 24 and y1 - y0 + 1 == 20, "piece extent %s" % (piece.GetExtent(),))
mine = piece.GetPointData().GetArray("Label")
whole = alone.GetPointData().GetArray("Label")
check(all(mine.GetValue((x - x0) + (x1 - x0 + 1) * ((y - y0) + (y1 - y0 + 1) * (z - z0))) ==
          whole.GetValue(x + 24 * (y + 20 * z))
          for z in range(z0, z1 + 1) for y in range(y0, y1 + 1) for x in range(x0, x1 + 1)),
      "the piece equals the one-process model's sites")
check(piece.GetFieldData().GetArray("Processes").GetValue(0) == 1, "no exchange between processes")
# A window far inside a world of 10^6 x 10^6 x 5 sites, asked for by Extract Subset.
synthesis.OutputSize = [1000000, 1000000, 5]
window = servermanager.Fetch(ExtractSubset(Input=synthesis, VOI=[400000, 400023, 700000, 700015, 0, 4]))
check(window.GetNumberOfPoints() == 24 * 16 * 5 // ranks, "far window: %d sites" % window.GetNumberOfPoints())
check(pair_counts(window).keys() <= pair_counts(image).keys(), "far window pairs occur in the example")
synthesis.OutputSize = [24, 20, 5]
synthesis.ComputeRequestedExtent = 0

# Geometry of the model through its proxy: closed voxel surfaces, one face per label change.
mesh = servermanager.Fetch(ModelSynthLabelGeometry(Input=synthesis))
check(mesh.GetNumberOfCells() > 0 and mesh.GetCellData().GetArray("Label") is not None, "mesh")

# Catalog evolution as time steps: the animation scene sees them.
synthesis.CatalogSnapshotsPerBlock = 2
synthesis.UpdatePipelineInformation()
steps = synthesis.TimestepValues
blocks = 5 * 4  # 24 and 20 sites in blocks of 8 (overlap 4): 5 and 4 starts
check(len(steps) == 1 + 2 * blocks, "time steps: %d" % len(steps))
scene = GetAnimationScene()
scene.UpdateAnimationUsingDataTimeSteps()
synthesis.UpdatePipeline(steps[len(steps) // 2])
mid = servermanager.Fetch(synthesis)
check(mid.GetPointData().GetArray("CatalogSize") is not None, "CatalogSize at a time step")
check(mid.GetPointData().GetArray("Entropy") is not None, "Entropy at a time step")
# Shown from the first snapshot (the ground decided), the labels get their colours as time
# reaches the steps that decide them: the categorical map's active labels grow. (What the
# animation scene does at each step, without its render, which would need a display.)
from paraview.modules.vtkRemotingViews import vtkSMTransferFunctionManager  # noqa: E402
label_map.ActiveAnnotatedValues = []
snapshot_view = CreateRenderView()
snapshot_view.ViewTime = steps[0]
Show(OutputPort(synthesis, 1), snapshot_view)
snapshot_view.Update()
first_active = list(label_map.ActiveAnnotatedValues)
snapshot_view.ViewTime = steps[-1]
snapshot_view.Update()
vtkSMTransferFunctionManager().ResetAllTransferFunctionRangesUsingCurrentData(
    servermanager.ActiveConnection.Session.GetSessionProxyManager(), True)
check(len(first_active) < len(present) and
      sorted(int(v) for v in label_map.ActiveAnnotatedValues) == present,
      "active labels %s at the first snapshot, %s at the last (expected %s)" % (
          first_active, list(label_map.ActiveAnnotatedValues), present))
Delete(snapshot_view)
del snapshot_view

# A tileset through its source proxy and the picture through the tile-image filter.
tileset = os.path.join(DATA, "Tilesets", "Lines.xml")
# Both synthesis proxies derive from MSDiscreteSynthesisBase: shared properties, own defaults.
fresh_tiles = ModelSynthTilesetSynthesis()
fresh_grid = ModelSynthDiscreteSynthesis(Input=reader)
check(list(fresh_tiles.OutputSize) == [32, 32, 1], "tileset default size %s" % list(fresh_tiles.OutputSize))
check(list(fresh_grid.OutputSize) == [32, 32, 8], "grid default size %s" % list(fresh_grid.OutputSize))
check((fresh_tiles.LabelChoice, fresh_tiles.SiteOrder) == ("Tile weights", "Minimum entropy"),
      "tileset defaults %s %s" % (fresh_tiles.LabelChoice, fresh_tiles.SiteOrder))
check(fresh_grid.SiteOrder == "Scan line", "grid site order %s" % fresh_grid.SiteOrder)
for name in ("BlockSize", "Seed", "Translate", "Rotate", "Mirror", "CatalogSnapshotsPerBlock",
             "BacktracksPerAttempt", "RepairFailedBlocks"):
    check(fresh_tiles.GetProperty(name) is not None and fresh_grid.GetProperty(name) is not None,
          "shared property " + name)
check(fresh_grid.GetProperty("ResemblanceWindow") is not None, "the grid's own property")
check(fresh_grid.LabelChoice == "Uniform", "grid label choice %s" % fresh_grid.LabelChoice)
for proxy in (fresh_grid, fresh_tiles):  # the panel shows the label choice beside the site order
    ordered = vtkSMOrderedPropertyIterator()
    ordered.SetProxy(proxy.SMProxy)
    ordered.Begin()
    names = []
    while not ordered.IsAtEnd():
        names.append(ordered.GetKey())
        ordered.Next()
    check(abs(names.index("LabelChoice") - names.index("SiteOrder")) == 1, "panel order %s" % names)
Delete(fresh_tiles)
Delete(fresh_grid)
tiled = ModelSynthTilesetSynthesis(TilesetFile=tileset, OutputSize=[12, 9, 1], Seed=4)
picture = servermanager.Fetch(ModelSynthTileImage(Input=tiled, TilesetFile=tileset))
check(picture.GetDimensions() == (96, 72, 1), "tile picture size %s" % (picture.GetDimensions(),))
check(picture.GetPointData().GetArray("RGBA") is not None, "tile picture colours")
# Without a TilesetFile of its own, the picture takes the synthesis's tileset.
upstream = servermanager.Fetch(ModelSynthTileImage(Input=tiled))
check(upstream.GetDimensions() == (96, 72, 1) and all(
    upstream.GetPointData().GetArray("RGBA").GetValue(i) == picture.GetPointData().GetArray("RGBA").GetValue(i)
    for i in range(0, 96 * 72 * 4, 97)), "the tile picture with the upstream tileset %s" % (upstream.GetDimensions(),))
# A map drawn as a picture with the tiles, pinned through the source proxy's Fixed File field.
drawn_reader = ModelSynthLabelGridReader(FileName=os.path.join(DATA, "Tilesets", "lines-drawn.vti"))
drawn_pins = servermanager.Fetch(drawn_reader).GetPointData().GetArray("Label")
completed = ModelSynthTilesetSynthesis(TilesetFile=tileset, OutputSize=[24, 24, 1], Seed=2,
                                       FixedFile=os.path.join(DATA, "Tilesets", "lines-drawn.png"))
completed_labels = servermanager.Fetch(completed).GetPointData().GetArray("Label")
pinned = [i for i in range(24 * 24) if drawn_pins.GetValue(i) >= 0]
check(len(pinned) > 50 and all(completed_labels.GetValue(i) == drawn_pins.GetValue(i) for i in pinned),
      "the drawn picture's %d tiles are kept" % len(pinned))

# An image sample (the overlapping model) through its source proxy and the pattern picture;
# every 3 x 3 window of the picture is checked against the sample's windows here.
sample = os.path.join(DATA, "Samples", "Rooms.png")
fresh_sample = ModelSynthImageSampleSynthesis()
check(list(fresh_sample.OutputSize) == [64, 64, 1], "sample default size %s" % list(fresh_sample.OutputSize))
check((fresh_sample.PatternSize, fresh_sample.PatternSymmetry, fresh_sample.PeriodicInput,
       fresh_sample.Ground) == (3, 8, 1, 0), "sample defaults")
Delete(fresh_sample)
rooms = ModelSynthImageSampleSynthesis(SampleFile=sample, OutputSize=[40, 30, 1], BlockSize=[16, 16, 1], Seed=3)
labels = servermanager.Fetch(rooms)
check(labels.GetDimensions() == (38, 28, 1), "pattern sites %s" % (labels.GetDimensions(),))
drawn = servermanager.Fetch(ModelSynthPatternPicture(Input=rooms))
check(drawn.GetDimensions() == (40, 30, 1), "pattern picture size %s" % (drawn.GetDimensions(),))
from vtkmodules.vtkIOImage import vtkPNGReader  # noqa: E402


def rows_of(image):
    """Pixels as rows from the top, each pixel a tuple of its components (RGB or RGBA)."""
    nx, ny, _ = image.GetDimensions()
    a = image.GetPointData().GetScalars()
    c = a.GetNumberOfComponents()
    px = [tuple(int(a.GetComponent(i, k)) for k in range(min(c, 3))) for i in range(nx * ny)]
    return [px[(ny - 1 - y) * nx:(ny - y) * nx] for y in range(ny)]


png = vtkPNGReader()
png.SetFileName(sample)
png.Update()
own = rows_of(png.GetOutput())
h, w = len(own), len(own[0])
allowed = set()
for y in range(h):
    for x in range(w):
        win = [[own[(y + j) % h][(x + i) % w] for i in range(3)] for j in range(3)]
        for _ in range(4):  # all eight symmetries: turns and their mirrors
            win = [list(r) for r in zip(*win)][::-1]
            allowed.add(str(win))
            allowed.add(str([r[::-1] for r in win]))
pic = rows_of(drawn)
bad = [(x, y) for y in range(28) for x in range(38)
       if str([pic[y + j][x:x + 3] for j in range(3)]) not in allowed]
check(not bad, "pattern picture windows not in the sample: %s" % bad[:3])
check(len({str([pic[y + j][x:x + 3] for j in range(3)]) for y in range(28) for x in range(38)}) >= 12,
      "the pattern picture is varied")
patterns_source = ModelSynthImagePatterns(SampleFile=sample)
check(servermanager.Fetch(patterns_source).GetDimensions() == (3, 3, 113), "the sample's 113 patterns")
check(servermanager.Fetch(patterns_source, idx=1).GetNumberOfRows() == 652, "pairs along x and y")

# Symmetry (§3.5.2) through the proxies: a tileable village, and a tile picture that looks the
# same turned a quarter (each tile turns to its next orientation).
synthesis.CatalogSnapshotsPerBlock = 0
synthesis.Translate = [1, 1, 0]
synthesis.UseBoundary = [0, 0, 0, 0, 1, 0]
periodic = servermanager.Fetch(synthesis).GetPointData().GetArray("Label")
at = lambda x, y, z: int(periodic.GetValue(x + 24 * (y + 20 * z)))
wrapped = set()
for z in range(5):
    for y in range(20):
        for x in range(24):
            wrapped.add((0, at(x, y, z), at((x + 1) % 24, y, z)))
            wrapped.add((1, at(x, y, z), at(x, (y + 1) % 20, z)))
check(not (wrapped - set(expected)), "the periodic village tiles: %s" % sorted(wrapped - set(expected))[:3])
synthesis.Translate = [0, 0, 0]
# The panel's face check box does what UseBoundary does: ground (1) on the -Z face.
synthesis.UseBoundary = [0, 0, 0, 0, 0, 0]
synthesis.BoundaryZMin = 1
grounded = servermanager.Fetch(synthesis).GetPointData().GetArray("Label")
check(all(grounded.GetValue(i) == 1 for i in range(24 * 20)), "Boundary Z Min puts ground below")
synthesis.BoundaryZMin = 0
synthesis.UseBoundary = [0, 0, 0, 0, 1, 0]
turned = ModelSynthTilesetSynthesis(TilesetFile=tileset, OutputSize=[10, 10, 1], Seed=4, Rotate=1)
tiles = servermanager.Fetch(turned).GetPointData().GetArray("Label")
tile = lambda x, y: int(tiles.GetValue(x + 10 * y))
turn = {0: 0, 1: 2, 2: 1, 3: 4, 4: 5, 5: 6, 6: 3}  # Lines.xml: empty, line 0-1, corner 0-3
check(all(tile(9 - y, x) == turn[tile(x, y)] for y in range(10) for x in range(10)),
      "the tile model turned a quarter is its own image")

# Time-varying synthesis (dissertation 3.5.4) from a file series: the rolling ball of Fig. 3.27,
# one .vti per frame, read as time steps; every output frame is fetched and checked here.
from vtkmodules.vtkCommonCore import vtkIntArray  # noqa: E402
from vtkmodules.vtkCommonDataModel import vtkImageData  # noqa: E402
from vtkmodules.vtkIOXML import vtkXMLImageDataWriter  # noqa: E402

series = []
ball = {}  # (t, x) -> label: 1 emerging, 2 leaving
for t in range(8):
    frame = vtkImageData()
    frame.SetDimensions(6, 1, 1)
    values = vtkIntArray()
    values.SetName("Label")
    for x in range(6):
        v = 1 if x == t else (2 if x == t - 1 else 0)
        ball[(t, x)] = v
        values.InsertNextValue(v)
    frame.GetPointData().SetScalars(values)
    path = os.path.join(TMP, "pvbatch-ball-%s_%d.vti" % (suffix, t))
    writer = vtkXMLImageDataWriter()
    writer.SetInputData(frame)
    writer.SetFileName(path)
    writer.Write()
    series.append(path)
frames_reader = XMLImageDataReader(FileName=series)
animated = ModelSynthTimeVaryingSynthesis(Input=frames_reader, OutputSize=[16, 1, 1], NumberOfFrames=12,
                                          Seed=2)
animated.UpdatePipelineInformation()
check(len(animated.TimestepValues) == 12, "12 output frames, got %s" % (animated.TimestepValues,))
allowed = set()
for t in range(8):
    for x in range(6):
        if x + 1 < 6:
            allowed.add((0, ball[(t, x)], ball[(t, x + 1)]))
        if t + 1 < 8:
            allowed.add((3, ball[(t, x)], ball[(t + 1, x)]))
movie = []
for t in range(12):
    animated.UpdatePipeline(float(t))
    frame = servermanager.Fetch(animated).GetPointData().GetArray("Label")
    movie.append([int(frame.GetValue(x)) for x in range(16)])
seen = {(0, row[x], row[x + 1]) for row in movie for x in range(15)}
seen |= {(3, movie[t][x], movie[t + 1][x]) for t in range(11) for x in range(16)}
check(seen <= allowed, "every pair in space and time occurs in the example: %s" % sorted(seen - allowed)[:3])
check(any(1 in row for row in movie), "some ball rolls")

# Continuous synthesis: the neighbourhood labels of a polyhedral example (dissertation 4.5.3).
tetra = ModelSynthPolyhedralExampleReader(FileName=os.path.join(DATA, "Continuous", "tetrahedron.obj"))
catalog = ModelSynthNeighbourhoodLabels(Input=tetra)
catalog.UpdatePipeline()
rows = servermanager.Fetch(catalog, idx=0)
check(rows.GetNumberOfRows() == 16, "tetrahedron: 16 labels, got %d" % rows.GetNumberOfRows())
kinds = sorted(rows.GetValueByName(r, "Kind").ToString() for r in range(rows.GetNumberOfRows()))
check(kinds.count("vertex") == 4 and kinds.count("edge") == 6 and kinds.count("face") == 4,
      "label kinds %s" % kinds)
marked = servermanager.Fetch(catalog, idx=1)
check(marked.GetNumberOfPolys() == 4 and marked.GetNumberOfVerts() == 4, "marked tetrahedron")

# Continuous synthesis end to end: plane arrangement -> label solver -> mesh (verified by the
# example analysis run on the output), and the catalog as time steps.
cube = ModelSynthPolyhedralExampleReader(FileName=os.path.join(DATA, "Continuous", "cube.obj"))
arrangement = ModelSynthPlaneArrangement(Input=cube, OutputSize=[5, 4, 3])
solver = ModelSynthContinuousSynthesis(Input=cube, Arrangement=arrangement, Seed=5, NumberOfSnapshots=4)
mesh = ModelSynthArrangementMesh(Input=cube, Arrangement=solver, CheckModel=1)
mesh.UpdatePipeline()
vertices = servermanager.Fetch(arrangement)
check(vertices.GetNumberOfPoints() == 6 * 5 * 4, "cube arrangement: a 6 x 5 x 4 grid, got %d"
      % vertices.GetNumberOfPoints())
model = servermanager.Fetch(mesh)
check(model.GetNumberOfPolys() > 0, "the cube model has polygons")
check(model.GetFieldData().GetAbstractArray("ModelCheck").GetValue(0) == "valid", "model check")
check(len(solver.TimestepValues) == 5, "catalog time steps: %s" % (solver.TimestepValues,))
solver.UpdatePipeline(0.0)
start = servermanager.Fetch(solver)
sizes = start.GetPointData().GetArray("CatalogSize")
check(sizes is not None and max(sizes.GetValue(i) for i in range(sizes.GetNumberOfTuples())) > 1,
      "the catalog at the start has several labels per vertex")

# The TVCG constraints through the proxy: grounded houses with walls one spacing high, eaves one
# spacing wide.
house = ModelSynthPolyhedralExampleReader(FileName=os.path.join(DATA, "Continuous", "house.obj"))
# The house as Blender exports it by default (y up), read with Up Axis Y: the same bounds.
blender = ModelSynthPolyhedralExampleReader(FileName=os.path.join(DATA, "Continuous", "house-blender.obj"),
                                            UpAxis="Y")
check(servermanager.Fetch(blender).GetBounds() == servermanager.Fetch(house).GetBounds(),
      "a y-up export read with Up Axis Y is the z-up house")
houses = ModelSynthContinuousSynthesis(Input=house, Seed=3, Grounded=1, Thickness="wall:z:1", Overhang="roof", ModelCandidates=2,
                                       KeepProportions=1, TargetFractions="", Connected="",
                                       Arrangement=ModelSynthPlaneArrangement(Input=house,
                                                                              OutputSize=[12, 12, 8]))
housemesh = ModelSynthArrangementMesh(Input=house, Arrangement=houses, CheckModel=1)
housemesh.UpdatePipeline()
fields = servermanager.Fetch(houses).GetFieldData()
check(fields.GetArray("ModelChosen") is not None and fields.GetArray("MatchError") is not None,
      "two model candidates, the best kept")
check(fields.GetArray("Components").GetValue(0) == fields.GetArray("GroundedComponents").GetValue(0)
      and fields.GetArray("Components").GetValue(0) > 0, "grounded houses all on the ground")
housemodel = servermanager.Fetch(housemesh)
check(housemodel.GetFieldData().GetAbstractArray("ModelCheck").GetValue(0) == "valid",
      "grounded model check")
zs = set()
for c in range(housemodel.GetNumberOfCells()):
    b = housemodel.GetCell(c).GetBounds()
    inside = housemodel.GetCellData().GetArray("InsideType").GetValue(c)
    outside = housemodel.GetCellData().GetArray("OutsideType").GetValue(c)
    if b[4] == b[5] and 1 in (inside, outside) and 0 in (inside, outside):
        zs.add(round(b[4], 6))
check(zs <= {0.0, 2.0} and zs, "wall floors and ceilings at z = 0 and 2 only: %s" % sorted(zs))

# Under MPI the continuous blocks of each phase are spread over the ranks as well (rank 0 sends
# the example and the arrangement's parameters); the model is the one-process one and valid.
spread = ModelSynthContinuousSynthesis(Input=house, Seed=5, BlockSize=4,
                                       Arrangement=ModelSynthPlaneArrangement(Input=house,
                                                                              OutputSize=[48, 48, 6]))
spreadmesh = ModelSynthArrangementMesh(Input=house, Arrangement=spread, CheckModel=1)
spreadmesh.UpdatePipeline()
shared = servermanager.Fetch(spread)
sf = shared.GetFieldData()
check(sf.GetArray("Processes").GetValue(0) == ranks, "continuous blocks over %d processes, expected %d"
      % (sf.GetArray("Processes").GetValue(0), ranks))
check(sf.GetArray("Phases").GetValue(0) < sf.GetArray("Blocks").GetValue(0), "blocks in phases")
check(servermanager.Fetch(spreadmesh).GetFieldData().GetAbstractArray("ModelCheck").GetValue(0) == "valid",
      "the distributed continuous model passes the check")
spread.DistributeBlocks = 0
alone = servermanager.Fetch(spread)
check(alone.GetFieldData().GetArray("Processes").GetValue(0) == 1, "one process without distribution")
la, lb = alone.GetPointData().GetArray("Label"), shared.GetPointData().GetArray("Label")
check(la.GetNumberOfTuples() == lb.GetNumberOfTuples() > 0
      and all(la.GetValue(i) == lb.GetValue(i) for i in range(la.GetNumberOfTuples())),
      "the distributed continuous model equals the one-process model")

# OpenVDB from the continuous chain: the mesh as level sets, the catalog as a sequence.
folder = os.path.join(TMP, "pvbatch-vdb-%s" % suffix)
os.makedirs(folder, exist_ok=True)
for name in os.listdir(folder):
    os.remove(os.path.join(folder, name))
SaveData(os.path.join(folder, "model.vdb"), proxy=mesh, VoxelSize=0.1)
SaveData(os.path.join(folder, "catalog.vdb"), proxy=solver, WriteTimeSteps=1, VoxelSize=0.5)
files = sorted(os.listdir(folder))
check(files == ["catalog_0001.vdb", "catalog_0002.vdb", "catalog_0003.vdb", "catalog_0004.vdb",
                "catalog_0005.vdb", "model.vdb"], "VDB files %s" % files)
surface = servermanager.Fetch(ModelSynthOpenVDBReader(FileName=os.path.join(folder, "model.vdb"),
                                                      GridName="surface"))
values = surface.GetPointData().GetArray("surface")
check(values is not None and values.GetRange()[0] < 0 < values.GetRange()[1], "a signed level set")

# Factor-graph pattern synthesis (Yeh et al. 2012): two facade exemplars through one multiple
# input, samples as time steps, each checked here against the exemplars' pairs; the picture.
patterns = os.path.join(DATA, "Patterns")
facades = [ModelSynthLabelGridReader(FileName=os.path.join(patterns, name))
           for name in ("facade-rectangular.vti", "facade-l-shaped.vti")]
allowed = set()
for f in facades:
    allowed |= set(pair_counts(servermanager.Fetch(f)))
pattern = ModelSynthPatternSynthesis(Exemplars=facades, OutputSize=[20, 13, 1], SoftFactors="4H,4V",
                                     Samples=3, BurnIn=1, Seed=5)
pattern.UpdatePipelineInformation()
check(len(pattern.TimestepValues) == 3, "3 samples as time steps, got %s" % (pattern.TimestepValues,))
for t in range(3):
    pattern.UpdatePipeline(float(t))
    sample = servermanager.Fetch(pattern)
    check(sample.GetFieldData().GetArray("Sample").GetValue(0) == t, "sample %d" % t)
    pairs = set(pair_counts(sample))
    check(pairs <= allowed, "sample %d: pairs no exemplar shows: %s" % (t, sorted(pairs - allowed)[:3]))
facade = servermanager.Fetch(ModelSynthTileImage(Input=pattern, TilesetFile=os.path.join(patterns, "Facade.xml")))
check(facade.GetDimensions()[:2] == (160, 104), "facade picture %s" % (facade.GetDimensions(),))

# A MarkovJunior voxel tileset through ModelSynth Tileset Synthesis: labels are (tile, symmetry),
# and the Geometry port shows the tiles' voxels with their colours.
voxels = ModelSynthTilesetSynthesis(TilesetFile=os.path.join(DATA, "Tilesets", "Pipes.xml"),
                                    OutputSize=[4, 4, 3], BlockSize=[2, 2, 3], GenerateGeometry=1, Seed=3)
model = servermanager.Fetch(voxels)
check(model.GetFieldData().GetAbstractArray("LabelTile").GetNumberOfValues() == 85, "85 tile images")
surface = servermanager.Fetch(voxels, idx=1)
colours = surface.GetCellData().GetArray("PaletteColor")
check(colours is not None and colours.GetNumberOfComponents() == 4 and surface.GetNumberOfCells() > 0,
      "the voxel tileset's geometry is coloured voxels")

print("pvbatch pipeline OK (rank %d of %d)" % (rank, ranks))
