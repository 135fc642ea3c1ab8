"""pvbatch: the plugin's glTF writer. CreateWriter picks it for .glb; the mesh of a label grid
(Label Geometry) is written and read back by VTK's glTF reader: as many triangles as the
mesh's quads make, one mesh per label."""
import os

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
print("pvbatch glTF OK")
