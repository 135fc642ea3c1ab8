"""pvbatch: every check `msynth check` runs, through the plugin's ModelSynth Check Model without
the command: a picture (ParaView's PNG reader) against its image sample, a .vox read whole
against its voxel tileset, counts, a network and a path by tile names, and an animation in
space and time. Each verdict is compared with what this script counts itself, and one output is
corrupted per kind."""
import os
import subprocess
import xml.etree.ElementTree as ET

from paraview import servermanager
from paraview.simple import *  # noqa: F401,F403
from vtkmodules.vtkIOImage import vtkPNGWriter

from pvbatch_testing import DATA, TMP, check, load_plugin

load_plugin(globals())


def value(data, name):
    a = data.GetFieldData().GetAbstractArray(name)
    check(a is not None, "field data " + name)
    return a.GetVariantValue(0).ToDouble() if a.IsNumeric() else a.GetValue(0)


# A picture written as PNG and read back by ParaView's reader; one pixel changed: 9 windows.
sample = os.path.join(DATA, "Samples", "Rooms.png")
rooms = ModelSynthImageSampleSynthesis(SampleFile=sample, OutputSize=[24, 24, 1], Seed=3)
picture = servermanager.Fetch(ModelSynthPatternPicture(Input=rooms))
paths = []
for name, broken in (("good", False), ("broken", True)):
    if broken:
        rgba = picture.GetPointData().GetScalars()
        rgba.SetTuple4(5 + 24 * 7, 1, 2, 3, 255)
    paths.append(os.path.join(TMP, "pvbatch-check-%s.png" % name))
    writer = vtkPNGWriter()
    writer.SetInputData(picture)
    writer.SetFileName(paths[-1])
    writer.Write()
for path, valid, violations in ((paths[0], 1, 0), (paths[1], 0, 9)):
    png = PNGSeriesReader(FileNames=[path])
    verdict = servermanager.Fetch(ModelSynthCheckModel(
        Input=png, SampleFile=sample, PeriodicOutput=list(rooms.Translate)[:2], MaximumReported=20))
    check((value(verdict, "Valid"), value(verdict, "Violations")) == (valid, violations),
          "picture %s: %s %s" % (path, value(verdict, "Valid"), value(verdict, "Violations")))

# A voxel tileset's model.vox, read whole (VoxScene), against the tileset.
out = os.path.join(TMP, "pvbatch-check-pipes")
pipes = os.path.join(DATA, "Tilesets", "Pipes.xml")
done = subprocess.run([os.path.join(os.environ["MSYNTH_BIN"], "msynth"), "synthesize", pipes,
                       "--size", "8", "8", "6", "--seed", "4", "--out", out], capture_output=True)
check(done.returncode == 0, done.stderr.decode())
vox = ModelSynthLabelGridReader(FileName=os.path.join(out, "model.vox"), VoxScene=1, GenerateGeometry=0)
verdict = servermanager.Fetch(ModelSynthCheckModel(Input=vox, VoxelModel=1, TilesetFile=pipes))
check((value(verdict, "Valid"), value(verdict, "Cells")) == (1, 384), "voxel model valid, 384 cells")

# Counts, a network and a path by tile names, counted here from the labels.
paths_xml = os.path.join(DATA, "Tilesets", "Paths.xml")
turns = {"X": 1, "I": 2, "\\": 2, "L": 4, "T": 4}
names = [tile.get("name") for tile in ET.parse(paths_xml).getroot().find("tiles")
         for _ in range(turns[tile.get("symmetry", "X")])]
tiled = ModelSynthTilesetSynthesis(TilesetFile=paths_xml, OutputSize=[24, 24, 1], Seed=1)
checked = ModelSynthCheckModel(Input=tiled, Counts="corner:0:1000", Connected="line,corner,t,cross:1000",
                               Path="0,0")
verdict = servermanager.Fetch(checked)
labels = verdict.GetPointData().GetArray("Label")
corners = sum(1 for i in range(labels.GetNumberOfTuples()) if names[int(labels.GetValue(i))] == "corner")
check(value(verdict, "CountAchieved") == corners, "corners %g, counted %d" % (value(verdict, "CountAchieved"), corners))
check(value(verdict, "CountsKept") == 1, "the count is kept")
check(value(verdict, "ConnectedComponents") >= 1, "components counted")
check(verdict.GetFieldData().GetAbstractArray("Findings").GetNumberOfValues() == 3, "three findings")
check(value(verdict, "PathJoined") == int(names[int(labels.GetValue(0))] in ("line", "corner", "t", "cross")),
      "path of one site joined when it is a network site")

# An animation: every time step checked in space and in time against the ball's z slices.
ball = ModelSynthLabelGridReader(FileName=os.path.join(DATA, "Examples", "Ball.vti"), GenerateGeometry=0)
animated = ModelSynthTimeVaryingSynthesis(Input=ball, ExampleTimeFromZ=1, OutputSize=[16, 1, 1],
                                          NumberOfFrames=12, Seed=2)
timed = ModelSynthCheckModel(Input=animated, Examples=[ball], TimeVarying=1, ExampleTimeFromZ=1)
verdict = servermanager.Fetch(timed)
check((value(verdict, "Valid"), value(verdict, "Frames"), value(verdict, "ExampleFrames")) == (1, 12, 8),
      "animation valid over 12 frames")
check(value(verdict, "PairsChecked") == 12 * 15 + 11 * 16, "pairs in space and time")
print("pvbatch check kinds: ok")
