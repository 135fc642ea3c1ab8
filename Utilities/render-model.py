"""Renders a model (model.vtp or mesh.vtp of `msynth synthesize`) to a PNG, coloured by object
type or label, offscreen: pvpython Utilities/render-model.py MODEL.vtp OUT.png [--top] [--size W H].
Without a display (DISPLAY unset) it starts its own Xvfb (xserver.py). The README's picture of constrained
continuous models (Documentation/images/continuous-constraints.png) was made with it from the
commands the README lists."""
import argparse
import os
import sys

from paraview.simple import (ColorBy, CreateView, Delete, GetColorTransferFunction, SaveScreenshot,
                             Show, XMLPolyDataReader)

COLOURS = [0.80, 0.70, 0.50,  # 1: walls, buildings
           0.65, 0.20, 0.12,  # 2: roofs, domes
           0.35, 0.50, 0.75,  # 3
           0.35, 0.65, 0.35,  # 4
           0.45, 0.45, 0.45]  # 5: chimneys

# More colours for label meshes of discrete synthesis (Label cell data), repeated as needed.
MORE = [0.90, 0.60, 0.20, 0.55, 0.35, 0.70, 0.20, 0.60, 0.60, 0.85, 0.45, 0.55, 0.60, 0.55, 0.30,
        0.30, 0.30, 0.55, 0.75, 0.75, 0.40]


def render(model, out, top=False, size=(1200, 800)):
    """Renders the mesh file @p model to the PNG @p out, coloured by object type (InsideType,
    ObjectType) or by label (Label), seen from the front corner or straight down."""
    reader = XMLPolyDataReader(FileName=[model])
    view = CreateView("RenderView")
    view.ViewSize = list(size)
    view.OrientationAxesVisibility = 0
    view.UseColorPaletteForBackground = 0
    view.Background = [1, 1, 1]
    shown = Show(reader, view)
    keys = reader.CellData.keys()
    array = next((a for a in ("InsideType", "ObjectType", "Label") if a in keys), keys[0])
    ColorBy(shown, ("CELLS", array))
    lut = GetColorTransferFunction(array)
    lut.InterpretValuesAsCategories = 1
    lut.AnnotationsInitialized = 1
    colours = COLOURS + MORE
    count = len(colours) // 3
    lut.Annotations = [str(v) for t in range(1, 64) for v in (t, t)]
    lut.IndexedColors = [colours[3 * ((t - 1) % count) + c] for t in range(1, 64) for c in range(3)]
    b = reader.GetDataInformation().GetBounds()
    centre = [(b[0] + b[1]) / 2, (b[2] + b[3]) / 2, (b[4] + b[5]) / 2]
    view.CameraFocalPoint = centre
    if top:
        view.CameraViewUp = [0, 1, 0]
        view.CameraPosition = [centre[0], centre[1], centre[2] + 10 * max(b[1] - b[0], b[3] - b[2])]
        view.CameraParallelProjection = 1
    else:
        view.CameraViewUp = [0, 0, 1]
        view.CameraPosition = [centre[0] + (b[1] - b[0]) * 0.9, centre[1] - (b[3] - b[2]) * 1.4,
                               centre[2] + (b[3] - b[2]) * 1.0]
    view.ResetCamera()
    SaveScreenshot(out, view)
    Delete(view)
    Delete(reader)


if __name__ == "__main__":
    parser = argparse.ArgumentParser()
    parser.add_argument("model")
    parser.add_argument("out")
    parser.add_argument("--top", action="store_true", help="look straight down")
    parser.add_argument("--size", type=int, nargs=2, default=[1200, 800])
    args = parser.parse_args()
    sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
    from xserver import ensure_display
    ensure_display()
    render(args.model, args.out, args.top, args.size)
