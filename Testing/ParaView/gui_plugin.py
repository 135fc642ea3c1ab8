"""Run inside the ParaView GUI (paraview --script=...): load the plugin, build the pipeline,
report the result to the file named by MSYNTH_GUI_REPORT, and quit."""
import os

from paraview.simple import *  # noqa: F401,F403

report = os.environ["MSYNTH_GUI_REPORT"]
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
    result = "OK labels=%d continuous=%d model=%s frames=%d reseeded=%s categorical=%s picture=%s" % (
        rows, continuous, check if polygons > 0 else "empty", frames, reseeded, bool(categorical),
        "matches" if matches else "differs (error %g; see %s)" % (error, picture))
except Exception as e:  # report any failure instead of leaving the GUI open
    result = "ERROR %s" % e
with open(report, "w") as f:
    f.write(result)
os._exit(0)
