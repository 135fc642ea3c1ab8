// SPDX-License-Identifier: BSD-3-Clause
// model.vdb of a discrete run (`synthesize`, each slab of `--stream`): the label grid for
// inspection and the grids a renderer shades (vtkMSOpenVDBWriter's render grids); a voxel
// tileset's at the resolution of its tiles' voxels, as model.vox and mesh.vtp.
#include "Common.h"
#include "Synthesize.h"

#include "vtkFieldData.h"
#include "vtkImageData.h"
#include "vtkIntArray.h"
#include "vtkMSLabelArrays.h"
#include "vtkMSOpenVDBWriter.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkSmartPointer.h"
#include "vtkUnsignedCharArray.h"

#include "Core/Index.h"
#include "Formats/VoxModel.h"
#include "Formats/VoxelTileset.h"

namespace msynth
{
namespace cli
{

void WriteModelVolume(vtkImageData* model, const SynthesizeOptions& o, const std::string& path,
  const char* command, const char* progress)
{
  vtkNew<vtkMSOpenVDBWriter> vdb;
  vdb->SetInputData(model);
  vdb->SetFileName(path.c_str());
  vdb->WriteFloatLabelsOn();
  vdb->SetEmptyLabel(o.Empty.empty() ? 0 : o.Empty[0]); // the solid sites: not --empty's label
  vdb->AddMetadata("msynth_command", command);
  vdb->AddMetadata("seed", std::to_string(o.Seed).c_str());
  if (progress)
  {
    ProgressBar bar(vdb, progress);
    Run(vdb);
  }
  else
    Run(vdb);
}

void WriteTileVoxelVolume(vtkImageData* model, const msynth::Tileset& set,
  const msynth::VoxModel& vox, const SynthesizeOptions& o, const std::string& path)
{
  // The voxels where mesh.vtp has them: Label the palette index (0 empty, as in model.vox),
  // Tile the label of the site each voxel belongs to (the tile's name keys surface_NAME).
  std::array<double, 3> origin;
  std::array<double, 3> spacing;
  vtkMSLabelArrays::TileVoxelPlacement(set, model, origin, spacing);
  const auto& d = vox.Grid.Dimensions();
  vtkNew<vtkImageData> voxels;
  voxels->SetDimensions(static_cast<int>(d[0]), static_cast<int>(d[1]), static_cast<int>(d[2]));
  voxels->SetOrigin(origin.data());
  voxels->SetSpacing(spacing.data());
  vtkSmartPointer<vtkIntArray> labels;
  labels.TakeReference(vtkMSLabelArrays::NewLabelArray(vox.Grid, "Label"));
  voxels->GetPointData()->AddArray(labels);
  vtkDataArray* sites = model->GetPointData()->GetArray("Label");
  int m[3];
  model->GetDimensions(m);
  vtkNew<vtkIntArray> tiles;
  tiles->SetName("Tile");
  tiles->SetNumberOfValues(static_cast<vtkIdType>(d[0] * d[1] * d[2]));
  vtkIdType i = 0;
  for (std::int64_t z = 0; z < d[2]; ++z)
    for (std::int64_t y = 0; y < d[1]; ++y)
      for (std::int64_t x = 0; x < d[0]; ++x, ++i)
      {
        const vtkIdType site = x / set.VoxelSize[0] +
          m[0] * (y / set.VoxelSize[1] + vtkIdType(m[1]) * (z / set.VoxelSize[2]));
        tiles->SetValue(i, static_cast<int>(sites->GetTuple1(site)));
      }
  voxels->GetPointData()->AddArray(tiles);
  voxels->GetFieldData()->ShallowCopy(model->GetFieldData());
  vtkNew<vtkUnsignedCharArray> palette;
  palette->SetName("PaletteRGBA");
  palette->SetNumberOfComponents(4);
  for (const auto& rgba : vox.Palette)
    palette->InsertNextTypedTuple(rgba.data());
  voxels->GetFieldData()->AddArray(palette);
  vtkNew<vtkMSOpenVDBWriter> vdb;
  vdb->SetInputData(voxels);
  vdb->SetFileName(path.c_str());
  vdb->WriteFloatLabelsOn();
  vdb->SetNameArrayName("Tile");
  vdb->AddMetadata("msynth_command", "synthesize");
  vdb->AddMetadata("seed", std::to_string(o.Seed).c_str());
  ProgressBar bar(vdb, "model.vdb");
  Run(vdb);
}

} // namespace cli
} // namespace msynth
