"""pvbatch: the plugin's glTF writer. CreateWriter picks it for .glb; the mesh of a label grid
(Label Geometry) is written and read back by VTK's glTF reader: as many triangles as the
mesh's quads make, one mesh per label. A continuous model (Arrangement Mesh) through the same
writer: a mesh per object type, named by the example; and through the Label Grid Writer as .vox
(voxelized)."""
import json
import os
import struct

from paraview import servermanager
from paraview.simple import *  # noqa: F401,F403
from vtkmodules.vtkIOGeometry import vtkGLTFReader

from pvbatch_testing import DATA, TMP, check, load_plugin

load_plugin(globals())


reader = ModelSynthLabelGridReader(FileName=os.path.join(DATA, "Examples", "Village.vti"))
geometry = ModelSynthLabelGeometry(Input=reader)
path = os.path.join(TMP, "pvbatch-village.glb")
if os.path.exists(path):
    os.remove(path)
writer = CreateWriter(path, geometry)
check(writer.GetXMLName() == "MSGLTFWriter", "writer chosen for .glb: " + writer.GetXMLName())
writer.UpdatePipeline()
del writer

mesh = servermanager.Fetch(geometry)
labels = mesh.GetCellData().GetArray("Label")
quads = {}
for c in range(mesh.GetNumberOfCells()):
    check(mesh.GetCell(c).GetNumberOfPoints() == 4, "voxel faces are quads")
    label = int(labels.GetValue(c))
    quads[label] = quads.get(label, 0) + 1

gltf = vtkGLTFReader()
gltf.SetFileName(path)
gltf.Update()
counts = []
iterator = gltf.GetOutput().NewIterator()
iterator.InitTraversal()
while not iterator.IsDoneWithTraversal():
    counts.append(iterator.GetCurrentDataObject().GetNumberOfCells())
    iterator.GoToNextItem()
check(counts == [2 * quads[label] for label in sorted(quads)],
      "triangles per mesh %s, quads per label %s" % (counts, quads))

# A continuous model: the house example's types, walls and roofs.
house = ModelSynthPolyhedralExampleReader(FileName=os.path.join(DATA, "Continuous", "house.obj"))
arrangement = ModelSynthPlaneArrangement(Input=house, OutputSize=[12, 12, 6])
solver = ModelSynthContinuousSynthesis(Input=house, Arrangement=arrangement, Seed=3, Grounded=1)
model = ModelSynthArrangementMesh(Input=house, Arrangement=solver)
path = os.path.join(TMP, "pvbatch-houses.glb")
if os.path.exists(path):
    os.remove(path)
writer = CreateWriter(path, model)
check(writer.GetXMLName() == "MSGLTFWriter", "writer chosen for .glb: " + writer.GetXMLName())
writer.UpdatePipeline()
del writer
gltf = vtkGLTFReader()
gltf.SetFileName(path)
gltf.Update()
check(gltf.GetOutput().GetNumberOfBlocks() > 0, "VTK's glTF reader reads " + path)
with open(path, "rb") as f:
    blob = f.read()
length, = struct.unpack("<I", blob[12:16])
names = sorted(m["name"] for m in json.loads(blob[20:20 + length])["meshes"])
check(names == ["roof", "wall"], "one mesh per object type, named by the example: %s" % names)
vox = os.path.join(TMP, "pvbatch-houses.vox")
if os.path.exists(vox):
    os.remove(vox)
writer = CreateWriter(vox, model)
check(writer.GetXMLName() == "MSLabelGridWriter", "writer chosen for .vox: " + writer.GetXMLName())
writer.UpdatePipeline()
del writer
check(os.path.getsize(vox) > 100, "the model voxelized into " + vox)
print("pvbatch glTF OK")
