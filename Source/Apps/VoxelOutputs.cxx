// SPDX-License-Identifier: BSD-3-Clause
// The outputs of `msynth synthesize` for a voxel tileset (MarkovJunior's <tileset>): the model
// as its tiles' voxels.
#include "Common.h"
#include "Synthesize.h"

#include "vtkImageData.h"
#include "vtkMSGLTFWriter.h"
#include "vtkMSLabelArrays.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkXMLPolyDataWriter.h"

#include "Core/Index.h"
#include "Formats/Image.h"
#include "Formats/VoxModel.h"
#include "Formats/VoxelTileset.h"

#include <algorithm>
#include <stdexcept>

namespace msynth
{
namespace cli
{

void WriteTileVoxels(vtkImageData* model, const msynth::Tileset& set, const SynthesizeOptions& o,
  const std::string& dir, const std::function<bool(const char*)>& wanted,
  std::vector<std::string>& written)
{
  msynth::VoxModel vox;
  vox.Grid = msynth::ComposeVoxels(set,
    vtkMSLabelArrays::ToLabelGrid(model, model->GetPointData()->GetArray("Label")), vox.Palette);
  if (wanted("vox"))
  {
    msynth::WriteVoxSceneFile(dir + "/model.vox", vox);
    written.push_back(dir + "/model.vox");
  }
  if ((wanted("mesh") || wanted("glb")) && o.Pieces.empty())
  {
    // One surface of coplanar faces merged into rectangles, coloured by the palette, for both,
    // made from the voxels composed above (no second copy of a model of 10^7 voxels).
    std::array<double, 3> origin;
    std::array<double, 3> spacing;
    vtkMSLabelArrays::TileVoxelPlacement(set, model, origin, spacing);
    vtkNew<vtkPolyData> mesh;
    vtkMSLabelArrays::MergedVoxelMesh(vox.Grid, vox.Palette, origin, spacing, mesh);
    if (wanted("mesh"))
    {
      const bool small = mesh->GetNumberOfPoints() < (vtkIdType(1) << 31);
      // Past a million faces zlib took most of the run (13-23 s CPU of a 64 x 64 x 32-tile
      // Pipes model), LZ4 a tenth of that; ParaView reads both.
      const bool large = mesh->GetNumberOfCells() >= (vtkIdType(1) << 20);
      WriteXML<vtkXMLPolyDataWriter>(dir + "/mesh.vtp", mesh.GetPointer(), small, large);
      written.push_back(dir + "/mesh.vtp");
    }
    if (wanted("glb"))
    {
      vtkNew<vtkMSGLTFWriter> writer; // a mesh per palette colour
      writer->SetInputData(mesh);
      writer->SetFileName((dir + "/mesh.glb").c_str());
      Run(writer);
      written.push_back(dir + "/mesh.glb");
    }
  }
  if (wanted("vdb"))
    WriteTileVoxelVolume(model, set, vox, o, dir + "/model.vdb"); // listed by WriteOutputs
  const auto& d = vox.Grid.Dimensions();
  if (wanted("picture"))
  {
    if (d[2] != 1)
      throw std::runtime_error("--outputs picture: the view from above is made of a 2D voxel "
                               "tileset's models (tiles one voxel high)");
    msynth::RgbaImage picture;
    picture.Width = static_cast<int>(d[0]);
    picture.Height = static_cast<int>(d[1]);
    picture.Pixels.assign(msynth::ToIndex(d[0] * d[1]) * 4, 0);
    for (std::int64_t y = 0; y < d[1]; ++y) // rows from the top: y up
      for (std::int64_t x = 0; x < d[0]; ++x)
      {
        const auto& c = vox.Palette[msynth::ToIndex(vox.Grid.At(x, y, 0))];
        std::copy(c.begin(), c.end(), picture.Pixels.begin() + 4 * ((d[1] - 1 - y) * d[0] + x));
      }
    msynth::WritePng(dir + "/picture.png", picture);
    written.push_back(dir + "/picture.png");
  }
}

} // namespace cli
} // namespace msynth
