"""Renders a model (model.vtp or mesh.vtp of `msynth synthesize`) to a PNG, coloured by object
type or label, offscreen: pvpython Utilities/render-model.py MODEL.vtp OUT.png [--top] [--size W H].
The camera is fitted to the model's bounds, so the model fills the picture. Labels 1-12 have the
gallery's colours; every further label a colour of its own (label_colour). Without a display (DISPLAY unset) it starts its own Xvfb (xserver.py). The picture of constrained
continuous models (Documentation/images/continuous-constraints.png) is made with it by
make-continuous-pictures.py, from the commands Documentation/guide-continuous.md lists."""
import argparse
import colorsys
import os
import sys

COLOURS = [0.80, 0.70, 0.50,  # 1: walls, buildings
           0.65, 0.20, 0.12,  # 2: roofs, domes
           0.35, 0.50, 0.75,  # 3
           0.35, 0.65, 0.35,  # 4
           0.45, 0.45, 0.45]  # 5: chimneys

# More colours for label meshes of discrete synthesis (Label cell data): labels 6-12.
MORE = [0.90, 0.60, 0.20, 0.55, 0.35, 0.70, 0.20, 0.60, 0.60, 0.85, 0.45, 0.55, 0.60, 0.55, 0.30,
        0.30, 0.30, 0.55, 0.75, 0.75, 0.40]

# Labels 13 and up: hues a golden-ratio turn apart (1/phi), saturation and value from the R2
# low-discrepancy sequence (steps 1/rho and 1/rho^2, rho the plastic number), so no two labels
# share a colour however many there are. The plugin's Label colour map
# (Plugins/ModelSynth/MSLabelColorMap.cxx) computes the same colours.
HUE_STEP = 0.6180339887498949
SATURATION_STEP = 0.7548776662466927
VALUE_STEP = 0.5698402909980532


def label_colour(label):
    """(r, g, b) in [0, 1] of label @p label: COLOURS + MORE for labels 1-12 (labels 0 and below
    take them in turn: label 0 has label 12's), then a colour of its own for every label from 13."""
    if label <= 12:
        i = 3 * ((label - 1) % 12)
        return tuple((COLOURS + MORE)[i:i + 3])
    n = label - 13
    hue = (0.07 + n * HUE_STEP) % 1.0
    saturation = 0.35 + 0.5 * ((0.5 + n * SATURATION_STEP) % 1.0)
    value = 0.55 + 0.4 * ((0.5 + n * VALUE_STEP) % 1.0)
    return colorsys.hsv_to_rgb(hue, saturation, value)


def fit_camera(camera, bounds, aspect, margin=0.96):
    """Moves @p camera (a vtkCamera, its direction kept) so that the box @p bounds fills the
    frame: its projected corners centred and spanning @p margin of the width or the height.
    (ResetCamera fits the bounding sphere, which leaves a flat model in a third of the frame.)"""
    corners = [(x, y, z) for x in bounds[0:2] for y in bounds[2:4] for z in bounds[4:6]]
    for _ in range(6):  # perspective: the corners' depths change as the camera moves
        matrix = camera.GetCompositeProjectionTransformMatrix(aspect, -1, 1)
        xs, ys = [], []
        for corner in corners:
            p = matrix.MultiplyPoint(corner + (1.0,))
            xs.append(p[0] / p[3])
            ys.append(p[1] / p[3])
        centre = ((min(xs) + max(xs)) / 2, (min(ys) + max(ys)) / 2)
        half = max((max(xs) - min(xs)) / 2, (max(ys) - min(ys)) / 2)
        if camera.GetParallelProjection():
            height = camera.GetParallelScale()
        else:
            import math
            height = camera.GetDistance() * math.tan(math.radians(camera.GetViewAngle()) / 2)
        # Pan by the projected centre's offset (in world units at the focal plane).
        up = camera.GetViewUp()
        forward = camera.GetDirectionOfProjection()
        right = (forward[1] * up[2] - forward[2] * up[1], forward[2] * up[0] - forward[0] * up[2],
                 forward[0] * up[1] - forward[1] * up[0])
        shift = [centre[0] * height * aspect * right[i] + centre[1] * height * up[i] for i in range(3)]
        camera.SetFocalPoint(*[f + d for f, d in zip(camera.GetFocalPoint(), shift)])
        camera.SetPosition(*[p + d for p, d in zip(camera.GetPosition(), shift)])
        if camera.GetParallelProjection():
            camera.SetParallelScale(height * half / margin)
        else:
            camera.Dolly(margin / half)
        if abs(half - margin) < 1e-3 and abs(centre[0]) + abs(centre[1]) < 1e-3:
            break


def render(model, out, top=False, size=(1200, 800)):
    """Renders the mesh file @p model to the PNG @p out, coloured by object type (InsideType,
    ObjectType), by the colours of a MagicaVoxel palette (PaletteColor: a .vox example's or a voxel
    tileset's mesh) or by label (Label), seen from the front corner or straight down, the model
    filling the frame."""
    from paraview.simple import (ColorBy, CreateView, Delete, GetColorTransferFunction, SaveScreenshot,
                                 Show, XMLPolyDataReader)
    reader = XMLPolyDataReader(FileName=[model])
    view = CreateView("RenderView")
    view.ViewSize = list(size)
    view.OrientationAxesVisibility = 0
    view.UseColorPaletteForBackground = 0
    view.Background = [1, 1, 1]
    shown = Show(reader, view)
    keys = reader.CellData.keys()
    array = next((a for a in ("InsideType", "ObjectType", "PaletteColor", "Label") if a in keys), keys[0])
    ColorBy(shown, ("CELLS", array))
    if array == "PaletteColor":  # RGBA as they are
        shown.MapScalars = 0
    lut = GetColorTransferFunction(array)
    lut.InterpretValuesAsCategories = 1
    lut.AnnotationsInitialized = 1
    low, high = (int(v) for v in reader.CellData[array].GetRange())
    labels = range(min(low, 1), max(min(high, 4095), 63) + 1)
    lut.Annotations = [str(v) for t in labels for v in (t, t)]
    lut.IndexedColors = [c for t in labels for c in label_colour(t)]
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
    camera = view.GetActiveCamera()
    fit_camera(camera, b, size[0] / size[1])
    view.CameraPosition = list(camera.GetPosition())
    view.CameraFocalPoint = list(camera.GetFocalPoint())
    view.CameraParallelScale = camera.GetParallelScale()
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
