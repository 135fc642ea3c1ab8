"""Renders a continuous model (model.vtp of `msynth synthesize`) to a PNG, coloured by object
type, offscreen: pvpython Utilities/render-model.py MODEL.vtp OUT.png [--top] [--size W H].
Run it under a display or Xvfb (xvfb-run -a pvpython ...). The README's picture of constrained
continuous models (Documentation/images/continuous-constraints.png) was made with it from the
commands the README lists."""
import argparse

from paraview.simple import (ColorBy, CreateView, GetColorTransferFunction, SaveScreenshot, Show,
                             XMLPolyDataReader)

COLOURS = [0.80, 0.70, 0.50,  # 1: walls, buildings
           0.65, 0.20, 0.12,  # 2: roofs, domes
           0.35, 0.50, 0.75,  # 3
           0.35, 0.65, 0.35,  # 4
           0.45, 0.45, 0.45]  # 5: chimneys

parser = argparse.ArgumentParser()
parser.add_argument("model")
parser.add_argument("out")
parser.add_argument("--top", action="store_true", help="look straight down")
parser.add_argument("--size", type=int, nargs=2, default=[1200, 800])
args = parser.parse_args()

reader = XMLPolyDataReader(FileName=[args.model])
view = CreateView("RenderView")
view.ViewSize = args.size
view.OrientationAxesVisibility = 0
view.UseColorPaletteForBackground = 0
view.Background = [1, 1, 1]
shown = Show(reader, view)
array = "InsideType" if "InsideType" in reader.CellData.keys() else "ObjectType"
ColorBy(shown, ("CELLS", array))
lut = GetColorTransferFunction(array)
lut.InterpretValuesAsCategories = 1
lut.AnnotationsInitialized = 1
lut.Annotations = [str(v) for t in range(1, 6) for v in (t, t)]
lut.IndexedColors = COLOURS
b = reader.GetDataInformation().GetBounds()
centre = [(b[0] + b[1]) / 2, (b[2] + b[3]) / 2, (b[4] + b[5]) / 2]
view.CameraFocalPoint = centre
if args.top:
    view.CameraViewUp = [0, 1, 0]
    view.CameraPosition = [centre[0], centre[1], centre[2] + 10 * max(b[1] - b[0], b[3] - b[2])]
    view.CameraParallelProjection = 1
else:
    view.CameraViewUp = [0, 0, 1]
    view.CameraPosition = [centre[0] + (b[1] - b[0]) * 0.9, centre[1] - (b[3] - b[2]) * 1.4,
                           centre[2] + (b[3] - b[2]) * 1.0]
view.ResetCamera()
SaveScreenshot(args.out, view)
