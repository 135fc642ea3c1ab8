// SPDX-License-Identifier: BSD-3-Clause
#include "vtkMSLabelGridWriter.h"

#include "vtkMSArrangementStorage.h"
#include "vtkMSEngineBridge.h"
#include "vtkMSLabelArrays.h"
#include "vtkMSPolyhedra.h"

#include "vtkDataArray.h"
#include "vtkErrorCode.h"
#include "vtkFieldData.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkObjectFactory.h"
#include "vtkPolyData.h"
#include "vtkStringArray.h"

#include "Continuous/ContinuousMesh.h"
#include "Core/AtomicFile.h"
#include "Core/Error.h"
#include "Core/Index.h"
#include "Core/LabelColor.h"
#include "Formats/TextModel.h"
#include "Formats/VoxModel.h"

#include <algorithm>
#include <array>
#include <cmath>

vtkStandardNewMacro(vtkMSLabelGridWriter);

void vtkMSLabelGridWriter::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "FileName: " << this->FileName << "\n";
  os << indent << "VoxelSize: " << this->VoxelSize << "\n";
  os << indent << "MaximumVoxelsPerAxis: " << this->MaximumVoxelsPerAxis << "\n";
  os << indent << "MaximumVoxels: " << this->MaximumVoxels << "\n";
}

int vtkMSLabelGridWriter::FillInputPortInformation(int, vtkInformation* info)
{
  info->Remove(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE());
  info->Append(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkImageData");
  info->Append(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkPolyData");
  return 1;
}

namespace
{
/// MagicaVoxel's file: one model up to 256 voxels a side, else a scene of such models.
void WriteVox(const std::string& path, const msynth::VoxModel& model)
{
  const auto& d = model.Grid.Dimensions();
  if (d[0] > 256 || d[1] > 256 || d[2] > 256)
    msynth::WriteVoxSceneFile(path, model);
  else
    msynth::WriteVoxModelFile(path, model);
}
} // namespace

void vtkMSLabelGridWriter::WriteModelVoxels(vtkPolyData* input)
{
  const std::string& path = this->FileName;
  msynth::ContinuousMesh mesh = vtkMSPolyhedra::ToContinuousMesh(input, path);
  double b[6];
  input->GetBounds(b);
  if (input->GetNumberOfPoints() == 0)
    b[0] = b[1] = b[2] = b[3] = b[4] = b[5] = 0;
  if (mesh.Planar && b[5] > b[4])
  {
    // A 3D polyhedral example (ObjectType): each object's faces as the inside of its type.
    mesh.Planar = false;
    mesh.OutsideType.assign(mesh.Polygons.size(), 0);
  }
  const int axes = mesh.Planar ? 2 : 3;
  double longest = 0;
  for (int a = 0; a < axes; ++a)
    longest = std::max(longest, b[2 * a + 1] - b[2 * a]);
  double voxel = this->VoxelSize;
  if (voxel <= 0)
  {
    // The mesh's record of its arrangement's smallest spacing (vtkMSArrangementMesh), else the
    // arrangement's own (its planes, when it carries them).
    vtkDataArray* recorded = input->GetFieldData()->GetArray("SmallestSpacing");
    const double spacing = recorded && recorded->GetNumberOfTuples() > 0
      ? recorded->GetTuple1(0)
      : vtkMSArrangementStorage::SmallestSpacing(input->GetFieldData());
    voxel = std::max(spacing / 2, longest / 256);
    if (!(voxel > 0))
      voxel = 1;
  }
  std::array<std::int64_t, 3> dims{ { 1, 1, 1 } };
  double total = 1;
  for (int a = 0; a < axes; ++a)
  {
    // A hair under a whole number of voxels stays that number (256 for the default).
    const double n = std::max(1.0, std::ceil((b[2 * a + 1] - b[2 * a]) / voxel - 1e-6));
    total *= n;
    if (n > this->MaximumVoxelsPerAxis)
      throw msynth::Error::InFile(path,
        "voxels of " + std::to_string(voxel) + " give " +
          std::to_string(static_cast<long long>(n)) + " along " + "xyz"[a] + ", more than " +
          std::to_string(this->MaximumVoxelsPerAxis) +
          " (MagicaVoxel's world reaches 1000 voxels from its centre); use larger voxels");
    dims[msynth::ToIndex(a)] = static_cast<std::int64_t>(n);
  }
  if (total > this->MaximumVoxels)
    throw msynth::Error::InFile(path,
      "voxels of " + std::to_string(voxel) + " give " +
        std::to_string(static_cast<long long>(total)) + " voxels, more than " +
        std::to_string(static_cast<long long>(this->MaximumVoxels)) + "; use larger voxels");
  for (int type : mesh.InsideType)
    if (type > 255)
      throw msynth::Error::InFile(path,
        "cannot hold object type " + std::to_string(type) +
          ": MagicaVoxel's palette indices are 1..255");
  for (int type : mesh.OutsideType)
    if (type > 255)
      throw msynth::Error::InFile(path,
        "cannot hold object type " + std::to_string(type) +
          ": MagicaVoxel's palette indices are 1..255");
  msynth::VoxModel model;
  model.Grid =
    msynth::VoxelizeModelEvenly(mesh, { b[0], b[2], mesh.Planar ? 0.0 : b[4] }, voxel, dims);
  model.Palette.resize(256);
  model.Palette[0] = { { 0, 0, 0, 0 } };
  for (int i = 1; i < 256; ++i)
  {
    const auto rgb = msynth::LabelColor(i);
    for (int c = 0; c < 3; ++c)
      model.Palette[msynth::ToIndex(i)][msynth::ToIndex(c)] =
        static_cast<std::uint8_t>(std::lround(255 * rgb[msynth::ToIndex(c)]));
    model.Palette[msynth::ToIndex(i)][3] = 255;
  }
  WriteVox(path, model);
  this->WrittenVoxelSize = voxel;
}

void vtkMSLabelGridWriter::WriteData()
{
  this->SetErrorCode(vtkErrorCode::NoError);
  if (this->FileName.empty())
  {
    vtkErrorMacro(<< "No file name was given.");
    this->SetErrorCode(vtkErrorCode::NoFileNameError);
    return;
  }
  const std::string& path = this->FileName;
  const auto endsWith = [&path](const char* ext)
  { return path.size() > 4 && path.compare(path.size() - 4, 4, ext) == 0; };
  if (auto* model = vtkPolyData::SafeDownCast(this->GetInput()))
  {
    try
    {
      if (!endsWith(".vox"))
        throw msynth::Error::InFile(
          path, "cannot be written: a continuous model (a mesh) is written as .vox only");
      this->WriteModelVoxels(model);
    }
    catch (const std::exception& e)
    {
      vtkErrorMacro(<< e.what());
      this->SetErrorCode(vtkErrorCode::CannotOpenFileError);
    }
    return;
  }
  vtkImageData* image = vtkImageData::SafeDownCast(this->GetInput());
  msynth::LabelGrid grid;
  std::string problem;
  if (!endsWith(".txt") && !endsWith(".vox"))
  {
    problem = "the extension must be .txt (the original program's format) or .vox (MagicaVoxel)";
  }
  else if (!image)
  {
    problem = "the input is not image data";
  }
  else
  {
    vtkMSLabelArrays::ReadLabels(image, nullptr, grid, problem);
  }
  if (!problem.empty())
  {
    vtkErrorMacro(<< "'" << path << "': cannot be written: " << problem);
    this->SetErrorCode(vtkErrorCode::UnknownError);
    return;
  }
  vtkFieldData* fields = image->GetFieldData();
  try
  {
    if (endsWith(".txt"))
    {
      msynth::TextModel model;
      model.Grid = std::move(grid);
      model.Header = msynth::GeneratedTextModelHeader();
      auto* trailer = vtkStringArray::SafeDownCast(fields->GetAbstractArray("TextModelTrailer"));
      if (trailer && trailer->GetNumberOfValues() > 0)
        model.Trailer = trailer->GetValue(0);
      msynth::WriteFileAtomically(
        path, [&](std::ostream& out) { msynth::WriteTextModel(out, model); });
    }
    else
    {
      msynth::VoxModel model;
      model.Grid = std::move(grid);
      vtkDataArray* palette = fields->GetArray("PaletteRGBA");
      if (palette && palette->GetNumberOfTuples() == 256 && palette->GetNumberOfComponents() == 4)
      {
        model.Palette.resize(256);
        for (vtkIdType i = 0; i < 256; ++i)
          for (int c = 0; c < 4; ++c)
            model.Palette[msynth::ToIndex(i)][msynth::ToIndex(c)] =
              static_cast<std::uint8_t>(palette->GetComponent(i, c));
      }
      WriteVox(path, model);
    }
  }
  catch (const std::exception& e)
  {
    vtkErrorMacro(<< e.what());
    this->SetErrorCode(vtkErrorCode::CannotOpenFileError);
  }
}
