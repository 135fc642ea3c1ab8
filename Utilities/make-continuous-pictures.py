"""Makes the continuous guide's composite of constrained models
(Documentation/images/continuous-constraints.png, 1800 x 800): six models synthesized with the
commands Documentation/guide-continuous.md lists, each rendered offscreen by render-model.py
(600 x 400, on a private Xvfb when there is no display) and tiled three to a row. Run from the
repository root after building:

    pvpython Utilities/make-continuous-pictures.py

Outputs go to output/continuous-pictures/NAME (the models) and the picture replaces the one in
Documentation/images."""
import os
import subprocess
import sys

M = "build/bin/msynth"
D = "Data/Continuous"
WALLS = "--thickness wall:x:2+ --thickness wall:y:2+"
# name, command (after "msynth"), top view; top row first, left to right.
PANELS = [
    ("houses", "synthesize %s/house.obj --size 24 24 10 --seed 3" % D, False),
    ("houses-constrained", "synthesize %s/house.obj --size 24 24 10 --seed 3 --grounded "
     "--thickness wall:z --overhang roof %s --mirror x" % (D, WALLS), False),
    ("cottages", "synthesize %s/cottage.obj --size 24 24 8 --seed 5 --grounded "
     "--thickness wall:z:2 --overhang roof %s --blocks 8" % (D, WALLS), False),
    ("domes", "synthesize %s/domed-building.obj --size 24 24 10 --seed 2 --grounded "
     "--detail dome=%s/dome.obj" % (D, D), False),
    ("pyramids", "synthesize %s/pyramid.obj --size 20 20 6 --seed 1 --grounded" % D, False),
    ("letters", "synthesize %s/house.obj --size 100 56 6 --seed 1 --grounded --thickness wall:z "
     "--guide %s/letters-guide.vti" % (D, D), True),
]
PANEL = (600, 400)
OUT = "Documentation/images/continuous-constraints.png"


def main():
    sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
    from xserver import ensure_display
    ensure_display()
    render = __import__("render-model").render
    from vtkmodules.vtkFiltersCore import vtkImageAppend
    from vtkmodules.vtkIOImage import vtkPNGReader, vtkPNGWriter

    rows = [vtkImageAppend(), vtkImageAppend()]
    for row in rows:
        row.SetAppendAxis(0)
    readers = []
    for k, (name, command, top) in enumerate(PANELS):
        folder = os.path.join("output", "continuous-pictures", name)
        subprocess.run([M, *command.split(), "--outputs", "mesh", "--out", folder], check=True,
                       stdout=subprocess.DEVNULL)
        png = folder + ".png"
        render(os.path.join(folder, "model.vtp"), png, top=top, size=PANEL)
        reader = vtkPNGReader()
        reader.SetFileName(png)
        readers.append(reader)
        rows[k // 3].AddInputConnection(reader.GetOutputPort())
        print("rendered", name)
    # Images grow upward: the second row goes first so the first row ends on top.
    whole = vtkImageAppend()
    whole.SetAppendAxis(1)
    whole.AddInputConnection(rows[1].GetOutputPort())
    whole.AddInputConnection(rows[0].GetOutputPort())
    writer = vtkPNGWriter()
    writer.SetFileName(OUT)
    writer.SetInputConnection(whole.GetOutputPort())
    writer.Write()
    print("made", OUT)


if __name__ == "__main__":
    main()
