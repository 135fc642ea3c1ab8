// SPDX-License-Identifier: BSD-3-Clause
#include "vtkMSOpenVDBReader.h"

#include "vtkErrorCode.h"
#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkIntArray.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkStreamingDemandDrivenPipeline.h"
#include "vtkStringArray.h"

#include "Core/Index.h"
#include "Core/Memory.h"
#include "VDB/VDBFile.h"

#include <algorithm>
#include <cstring>
#include <sys/stat.h>

vtkStandardNewMacro(vtkMSOpenVDBReader);

struct vtkMSOpenVDBReader::Internals
{
  // What the cache was read with.
  std::string Key;
  // Grids kept for the output (sharing the first grid's transform) and the union extent.
  msynth::vdb::FileContents Contents;
  int Extent[6] = { 0, 0, 0, 0, 0, 0 };
  double Origin[3] = { 0, 0, 0 };
  double Spacing[3] = { 1, 1, 1 };
};

vtkMSOpenVDBReader::vtkMSOpenVDBReader()
  : Internal(new Internals)
{
  this->SetNumberOfInputPorts(0);
}

vtkMSOpenVDBReader::~vtkMSOpenVDBReader() = default;

int vtkMSOpenVDBReader::CanReadFile(const char* name)
{
  if (!name)
  {
    return 0;
  }
  const std::string s(name);
  return s.size() > 4 && s.compare(s.size() - 4, 4, ".vdb") == 0 ? 1 : 0;
}

namespace
{
/// The union of the extents of @p grids: of their data grids (no class) when there are any.
void MergedExtent(
  const std::vector<msynth::vdb::DenseGrid>& grids, std::int64_t lo[3], std::int64_t hi[3])
{
  const bool data = std::any_of(grids.begin(), grids.end(),
    [](const msynth::vdb::DenseGrid& g) { return g.Header.GridClass.empty(); });
  for (int a = 0; a < 3; ++a)
  {
    lo[a] = INT64_MAX;
    hi[a] = INT64_MIN;
  }
  for (const auto& grid : grids)
  {
    const auto& h = grid.Header;
    if (data && !h.GridClass.empty())
      continue;
    for (int a = 0; a < 3; ++a)
    {
      lo[a] = std::min<std::int64_t>(lo[a], h.IndexMin[a]);
      hi[a] = std::max<std::int64_t>(hi[a], h.IndexMin[a] + h.Dims[a] - 1);
    }
  }
}
} // namespace

bool vtkMSOpenVDBReader::Load()
{
  this->SetErrorCode(vtkErrorCode::NoError);
  if (this->FileName.empty())
  {
    vtkErrorMacro(<< "No file name was given.");
    this->SetErrorCode(vtkErrorCode::NoFileNameError);
    return false;
  }
  struct stat info;
  if (::stat(this->FileName.c_str(), &info) != 0 || !S_ISREG(info.st_mode))
  {
    vtkErrorMacro(<< "'" << this->FileName << "': no such file.");
    this->SetErrorCode(vtkErrorCode::FileNotFoundError);
    return false;
  }
  const std::string key = this->FileName + '\n' + this->GridName + '\n' +
    std::to_string(this->MaximumNumberOfVoxels) + '\n' + std::to_string(info.st_mtime) + '\n' +
    std::to_string(info.st_size);
  if (key == this->Internal->Key)
  {
    return true;
  }
  this->Internal->Key.clear();

  msynth::vdb::FileContents contents;
  try
  {
    msynth::vdb::ReadOptions options;
    options.MaxVoxels = this->MaximumNumberOfVoxels;
    if (!this->GridName.empty())
    {
      options.GridNames.push_back(this->GridName);
    }
    contents = msynth::vdb::ReadFile(this->FileName, options);
  }
  catch (const std::exception& e)
  {
    vtkErrorMacro(<< e.what());
    this->SetErrorCode(vtkErrorCode::FileFormatError);
    return false;
  }
  if (contents.Grids.empty())
  {
    vtkErrorMacro(<< "'" << this->FileName << "': has no grid ModelSynth can read.");
    this->SetErrorCode(vtkErrorCode::FileFormatError);
    return false;
  }

  // Keep the grids that share the first grid's transform; merge their extents: those of the
  // data grids (no class) when there are any, as level sets and fog volumes made from them
  // (a label grid's render grids) lie in them but for the level sets' band (padding).
  const auto& first = contents.Grids.front().Header;
  std::vector<msynth::vdb::DenseGrid> kept;
  for (auto& grid : contents.Grids)
  {
    const auto& h = grid.Header;
    if (h.Origin != first.Origin || h.Spacing != first.Spacing)
    {
      vtkWarningMacro(<< "'" << this->FileName << "': grid '" << h.Name
                      << "' has another transform than grid '" << first.Name
                      << "'; skipped (select it with GridName).");
      continue;
    }
    kept.push_back(std::move(grid));
  }
  std::int64_t lo[3], hi[3];
  MergedExtent(kept, lo, hi);
  std::int64_t voxels = 1;
  for (int a = 0; a < 3; ++a)
  {
    const std::int64_t n = hi[a] - lo[a] + 1;
    if (n > this->MaximumNumberOfVoxels / voxels)
    {
      vtkErrorMacro(<< "'" << this->FileName << "': the grids span more than the limit of "
                    << this->MaximumNumberOfVoxels << " voxels.");
      this->SetErrorCode(vtkErrorCode::FileFormatError);
      return false;
    }
    voxels *= n;
    this->Internal->Extent[2 * a] = static_cast<int>(lo[a]);
    this->Internal->Extent[2 * a + 1] = static_cast<int>(hi[a]);
    this->Internal->Origin[a] = first.Origin[a];
    this->Internal->Spacing[a] = first.Spacing[a];
  }
  contents.Grids = std::move(kept);
  this->Internal->Contents = std::move(contents);
  this->Internal->Key = key;
  return true;
}

int vtkMSOpenVDBReader::RequestInformation(
  vtkInformation*, vtkInformationVector**, vtkInformationVector* outputVector)
{
  if (!this->Load())
  {
    return 0;
  }
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  outInfo->Set(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), this->Internal->Extent, 6);
  outInfo->Set(vtkDataObject::ORIGIN(), this->Internal->Origin, 3);
  outInfo->Set(vtkDataObject::SPACING(), this->Internal->Spacing, 3);
  return 1;
}

int vtkMSOpenVDBReader::RequestData(
  vtkInformation*, vtkInformationVector**, vtkInformationVector* outputVector)
{
  if (!this->Load())
  {
    return 0;
  }
  vtkImageData* output = vtkImageData::GetData(outputVector, 0);
  const int* ext = this->Internal->Extent;
  output->SetExtent(const_cast<int*>(ext));
  output->SetOrigin(this->Internal->Origin);
  output->SetSpacing(this->Internal->Spacing);
  const vtkIdType nx = ext[1] - ext[0] + 1, ny = ext[3] - ext[2] + 1;
  const vtkIdType n = output->GetNumberOfPoints();

  for (const auto& grid : this->Internal->Contents.Grids)
  {
    const auto& h = grid.Header;
    const int nc = msynth::vdb::ComponentCount(h.Type);
    vtkSmartPointer<vtkDataArray> array;
    if (h.Type == msynth::vdb::ValueType::Int32)
    {
      array = vtkSmartPointer<vtkIntArray>::New();
    }
    else
    {
      array = vtkSmartPointer<vtkFloatArray>::New();
    }
    array->SetName(h.Name.c_str());
    array->SetNumberOfComponents(nc);
    array->SetNumberOfTuples(n);
    msynth::AdviseHugePages(array->GetVoidPointer(0), msynth::ToIndex(n * nc) * 4);
    array->Fill(h.Background);
    // Copy the grid's box, clipped to the output's, row by row (x fastest in both; a row of
    // values of the array's own type at a time: a virtual call per value took 8 s for 2^28
    // voxels).
    const bool ints = h.Type == msynth::vdb::ValueType::Int32;
    std::int64_t from[3], to[3]; // the grid's own indices of the part inside the output
    for (int a = 0; a < 3; ++a)
    {
      from[a] = std::max<std::int64_t>(0, ext[2 * a] - std::int64_t(h.IndexMin[a]));
      to[a] = std::min<std::int64_t>(h.Dims[a], ext[2 * a + 1] - std::int64_t(h.IndexMin[a]) + 1);
    }
    const std::size_t rowBytes = to[0] > from[0] ? msynth::ToIndex((to[0] - from[0]) * nc) * 4 : 0;
    for (std::int64_t k = from[2]; k < to[2] && rowBytes > 0; ++k)
    {
      for (std::int64_t j = from[1]; j < to[1]; ++j)
      {
        const auto src = msynth::ToIndex((from[0] + h.Dims[0] * (j + h.Dims[1] * k)) * nc);
        const vtkIdType dst = (h.IndexMin[0] + from[0] - ext[0]) +
          nx * ((h.IndexMin[1] - ext[2] + j) + ny * (h.IndexMin[2] - ext[4] + k));
        std::memcpy(array->GetVoidPointer(dst * nc),
          ints ? static_cast<const void*>(grid.Ints.data() + src)
               : static_cast<const void*>(grid.Floats.data() + src),
          rowBytes);
      }
    }
    output->GetPointData()->AddArray(array);
  }
  if (output->GetPointData()->GetNumberOfArrays() > 0)
  {
    output->GetPointData()->SetActiveScalars(output->GetPointData()->GetArrayName(0));
  }
  for (const auto& kv : this->Internal->Contents.Metadata)
  {
    vtkNew<vtkStringArray> value;
    value->SetName(kv.first.c_str());
    value->InsertNextValue(kv.second);
    output->GetFieldData()->AddArray(value);
  }
  return 1;
}

void vtkMSOpenVDBReader::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "FileName: " << this->FileName << "\n";
  os << indent << "GridName: " << this->GridName << "\n";
  os << indent << "MaximumNumberOfVoxels: " << this->MaximumNumberOfVoxels << "\n";
}
