"""Pictures for Documentation/concepts.md: the catalog of a tileset synthesis as it shrinks.
Run from the repository root after building:

    PYTHONPATH=build/lib/python3.11/site-packages /usr/bin/python3 Utilities/make-concept-pictures.py

Writes Documentation/images/catalog-evolving.png: the Lines tileset synthesized at 24 x 16 in one
block, fewest labels first, caught at five moments (snapshots as time steps). Each site is grey
by how many labels it may still take (dark: all of them, lighter: fewer) until it is decided,
then coloured by its label."""
import os

import numpy as np
import modelsynth
from vtkmodules.util.numpy_support import numpy_to_vtk, vtk_to_numpy
from vtkmodules.vtkCommonDataModel import vtkImageData
from vtkmodules.vtkCommonExecutionModel import vtkStreamingDemandDrivenPipeline as Pipeline
from vtkmodules.vtkIOImage import vtkPNGWriter

LABEL_COLOURS = np.array([[230, 230, 230], [204, 179, 128], [166, 51, 31], [89, 128, 191],
                          [89, 166, 89], [115, 115, 115], [230, 153, 51], [140, 89, 179]],
                         dtype=np.float64)


def main():
    synthesis = modelsynth.vtkMSDiscreteSynthesis()
    synthesis.SetTilesetFile(os.path.join("Data", "Tilesets", "Lines.xml"))
    synthesis.SetOutputSize(24, 16, 1)
    synthesis.SetCatalogSnapshotsPerBlock(4)
    synthesis.SetSiteOrderToMinimumEntropy()
    synthesis.SetSeed(3)
    synthesis.UpdateInformation()
    info = synthesis.GetOutputInformation(0)
    times = [info.Get(Pipeline.TIME_STEPS(), i) for i in range(info.Length(Pipeline.TIME_STEPS()))]
    panels = []
    for t in times:
        synthesis.UpdateTimeStep(t)
        image = synthesis.GetOutput()
        nx, ny, _ = image.GetDimensions()
        size = vtk_to_numpy(image.GetPointData().GetArray("CatalogSize")).reshape(ny, nx)
        label = vtk_to_numpy(image.GetPointData().GetArray("Label")).reshape(ny, nx)
        largest = max(int(size.max()), 2)
        grey = 235 - 150 * (size - 1) / (largest - 1)  # every label: dark
        rgb = np.where((size == 1)[..., None], LABEL_COLOURS[np.clip(label, 0, 7)],
                       np.repeat(grey[..., None], 3, axis=2))
        rgb = np.repeat(np.repeat(rgb, 12, axis=0), 12, axis=1)
        panels.append(np.pad(rgb, ((6, 6), (6, 6), (0, 0)), constant_values=255))
    picture = np.concatenate(panels, axis=1).astype(np.uint8)
    out = vtkImageData()
    out.SetDimensions(picture.shape[1], picture.shape[0], 1)
    out.GetPointData().SetScalars(numpy_to_vtk(picture.reshape(-1, 3), deep=1))  # rows bottom up
    writer = vtkPNGWriter()
    writer.SetInputData(out)
    writer.SetFileName(os.path.join("Documentation", "images", "catalog-evolving.png"))
    writer.Write()


if __name__ == "__main__":
    main()
