"""Run inside the ParaView GUI (paraview --script=...): load the plugin, build the pipeline,
report the result to the file named by MSYNTH_GUI_REPORT, and quit."""
import os

from paraview.simple import *  # noqa: F401,F403

report = os.environ["MSYNTH_GUI_REPORT"]


def tutorial_colours():
    """The tutorial's steps as a user clicks them (paraview-tutorial.md, "Synthesize a model"):
    applied first without the boundaries the model has no ground; applied again with them, the
    ground (label 1) must join the legend and be drawn in its colour. ParaView computes a
    categorical map's active labels when a representation is first shown; the plugin computes
    them again when the data shown changes (without it label 1 was drawn in the NaN colour and
    left off the legend). "ok", or what is wrong."""
    import importlib.util
    from vtkmodules.vtkIOImage import vtkPNGReader
    from vtkmodules.util.numpy_support import vtk_to_numpy
    spec = importlib.util.spec_from_file_location("render_model", os.path.join(
        os.path.dirname(os.environ["MSYNTH_DATA"]), "Utilities", "render-model.py"))
    render_model = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(render_model)
    view = GetActiveViewOrCreate("RenderView")
    for source in GetSources().values():
        Hide(source, view)
    village = ModelSynthLabelGridReader(FileName=os.path.join(os.environ["MSYNTH_DATA"], "Examples", "Village.vox"))
    model = ModelSynthDiscreteSynthesis(Input=village, OutputSize=[32, 32, 5], BlockSize=[16, 16, 5], Seed=2)
    drawn = Show(OutputPort(model, 1), view)
    Render(view)
    label_map = GetColorTransferFunction("Label")
    before = sorted(int(v) for v in label_map.ActiveAnnotatedValues)
    model.BoundaryLabels = [0, 0, 0, 0, 1, 0]
    for face in ("XMin", "XMax", "YMin", "YMax", "ZMin", "ZMax"):
        setattr(model, "Boundary" + face, 1)
    Render(view)
    surface = servermanager.Fetch(model, None, None, 1).GetCellData().GetArray("Label")
    present = sorted({int(surface.GetValue(i)) for i in range(surface.GetNumberOfTuples())})
    after = sorted(int(v) for v in label_map.ActiveAnnotatedValues)
    if 1 in before or 1 not in present:
        return "first-model-had-ground(%s,%s)" % (before, present)
    if after != present:
        return "legend-%s-for-labels-%s" % (after, present)
    # Flat colours and a NaN colour no label has: every label's colour is on the picture and the
    # NaN colour is not.
    drawn.Ambient, drawn.Diffuse = 1.0, 0.0
    label_map.NanColor = [1.0, 0.0, 1.0]
    view.ResetCamera()
    png_path = os.path.join(os.environ["MSYNTH_TMP"], "gui-tutorial.png")
    SaveScreenshot(png_path, view, ImageResolution=[320, 240])
    label_map.NanColor = [1.0, 1.0, 0.0]
    png = vtkPNGReader()
    png.SetFileName(png_path)
    png.Update()
    pixels = [tuple(int(c) for c in p[:3]) for p in vtk_to_numpy(png.GetOutput().GetPointData().GetScalars())]

    def near(p, q):
        return all(abs(a - b) <= 2 for a, b in zip(p, q))
    if any(near(p, (255, 0, 255)) for p in pixels):
        return "nan-colour-drawn"
    for label in present:
        colour = tuple(round(255 * c) for c in render_model.label_colour(label))
        if sum(near(p, colour) for p in pixels) < 100:
            return "label-%d-not-in-its-colour-%s" % (label, colour)
    Hide(OutputPort(model, 1), view)
    return "ok"


try:
    LoadPlugin(os.environ["MSYNTH_PLUGIN"], remote=False, ns=globals())
    reader = ModelSynthLabelGridReader(FileName=os.path.join(os.environ["MSYNTH_DATA"], "Examples", "Village.vti"))
    tables = ModelSynthTransitionTables(Input=reader)
    tables.UpdatePipeline()
    Show(reader)
    Render()
    rows = servermanager.Fetch(tables, idx=1).GetNumberOfRows()
    cube = ModelSynthPolyhedralExampleReader(FileName=os.path.join(os.environ["MSYNTH_DATA"], "Continuous", "cube.obj"))
    catalog = ModelSynthNeighbourhoodLabels(Input=cube)
    Show(OutputPort(catalog, 1))
    Render()
    continuous = servermanager.Fetch(catalog, idx=0).GetNumberOfRows()
    # The continuous chain as a user clicks it together: arrangement, solver, mesh.
    arrangement = ModelSynthPlaneArrangement(Input=cube, OutputSize=[4, 4, 3])
    solver = ModelSynthContinuousSynthesis(Input=cube, Arrangement=arrangement, Seed=2)
    mesh = ModelSynthArrangementMesh(Input=cube, Arrangement=solver, CheckModel=1)
    Show(mesh)
    Render()
    model = servermanager.Fetch(mesh)
    check = model.GetFieldData().GetAbstractArray("ModelCheck").GetValue(0)
    # The Seed as the panel sets it (the proxy property its widget edits): another seed gives
    # another model, and the picture of a fixed seed matches the baseline.
    polygons = model.GetNumberOfPolys()
    house = ModelSynthPolyhedralExampleReader(FileName=os.path.join(os.environ["MSYNTH_DATA"], "Continuous", "house.obj"))
    houses = ModelSynthContinuousSynthesis(Input=house, Arrangement=ModelSynthPlaneArrangement(
        Input=house, OutputSize=[12, 12, 6]), Grounded=1)
    houses.Seed = 5
    housemesh = ModelSynthArrangementMesh(Input=house, Arrangement=houses)
    housemesh.UpdatePipeline()
    first = servermanager.Fetch(housemesh).GetNumberOfPolys()
    houses.Seed = 6
    housemesh.UpdatePipeline()
    reseeded = servermanager.Fetch(housemesh).GetNumberOfPolys() != first
    houses.Seed = 5
    view = GetActiveViewOrCreate("RenderView")  # the one in the window's layout
    for source in GetSources().values():
        Hide(source, view)
    view.OrientationAxesVisibility = 0
    view.UseColorPaletteForBackground = 0
    view.Background = [1, 1, 1]
    shown = Show(housemesh, view)
    ColorBy(shown, ("CELLS", "InsideType"))
    view.CameraPosition = [30, -20, 25]
    view.CameraFocalPoint = [6, 6, 2]
    view.CameraViewUp = [0, 0, 1]
    view.ResetCamera()
    picture = os.path.join(os.environ["MSYNTH_TMP"], "gui-houses.png")
    SaveScreenshot(picture, view, ImageResolution=[400, 300])
    baseline = os.environ["MSYNTH_GUI_BASELINE"]
    from vtkmodules.vtkIOImage import vtkPNGReader
    from vtkmodules.vtkImagingCore import vtkImageDifference
    images = []
    for path in (picture, baseline):
        r = vtkPNGReader()
        r.SetFileName(path)
        r.Update()
        images.append(r.GetOutput())
    difference = vtkImageDifference()
    difference.SetInputData(images[0])
    difference.SetImageData(images[1])
    difference.Update()
    # VTK's regression-test measure: thresholded error per pixel, 0 for identical pictures.
    error = difference.GetThresholdedError() if images[1].GetNumberOfPoints() else 1e9
    matches = error < 10
    # A rotation-symmetric discrete model and an animation (the village's z layers as frames),
    # shown as a user would.
    turned = ModelSynthDiscreteSynthesis(Input=reader, OutputSize=[16, 16, 5], BlockSize=[8, 8, 5], Rotate=1)
    Show(turned)
    shown = Show(OutputPort(turned, 1))  # Geometry, coloured by Label with the plugin's map
    Render()
    label_map = GetColorTransferFunction("Label")
    labels_shown = sorted(int(v) for v in label_map.ActiveAnnotatedValues)
    categorical = (list(shown.ColorArrayName) == ["CELLS", "Label"] and
                   label_map.InterpretValuesAsCategories == 1 and labels_shown and labels_shown[0] >= 1)
    movie = ModelSynthTimeVaryingSynthesis(Input=reader, OutputSize=[12, 12, 1], NumberOfFrames=6,
                                          ExampleTimeFromZ=1, BlockSize=[6, 6, 1, 3])
    Show(movie)
    Render()  # (GetAnimationScene().UpdateAnimationUsingDataTimeSteps() from a --script never
    # returns in this GUI, even for ParaView's own TimeSource; pvbatch tests the scene instead)
    frames = len(movie.TimestepValues)
    tutorial = tutorial_colours()
    result = ("OK labels=%d continuous=%d model=%s frames=%d reseeded=%s categorical=%s picture=%s "
              "tutorial=%s") % (
        rows, continuous, check if polygons > 0 else "empty", frames, reseeded, bool(categorical),
        "matches" if matches else "differs (error %g; see %s)" % (error, picture), tutorial)
except Exception as e:  # report any failure instead of leaving the GUI open
    result = "ERROR %s" % e
with open(report, "w") as f:
    f.write(result)
os._exit(0)
