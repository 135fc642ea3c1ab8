// SPDX-License-Identifier: BSD-3-Clause
#include "vtkMSOpenVDBWriter.h"

#include "vtkMSEngineBridge.h"

#include "vtkCellData.h"
#include "vtkDataArray.h"
#include "vtkErrorCode.h"
#include "vtkFieldData.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkStreamingDemandDrivenPipeline.h"
#include "vtkStringArray.h"

#include "msynth/Error.h"
#include "msynth/VDBFile.h"

#include <cstdint>
#include <limits>
#include <list>
#include <vector>

vtkStandardNewMacro(vtkMSOpenVDBWriter);

struct vtkMSOpenVDBWriter::Internals
{
  msynth::vdb::MetadataMap Metadata;
};

vtkMSOpenVDBWriter::vtkMSOpenVDBWriter()
  : Internal(new Internals)
{
}

vtkMSOpenVDBWriter::~vtkMSOpenVDBWriter() = default;

void vtkMSOpenVDBWriter::AddMetadata(const char* key, const char* value)
{
  if (key && value)
  {
    this->Internal->Metadata[key] = value;
    this->Modified();
  }
}

void vtkMSOpenVDBWriter::ClearMetadata()
{
  this->Internal->Metadata.clear();
  this->Modified();
}

int vtkMSOpenVDBWriter::FillInputPortInformation(int, vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkImageData");
  return 1;
}

vtkTypeBool vtkMSOpenVDBWriter::ProcessRequest(
  vtkInformation* request, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  if (request->Has(vtkStreamingDemandDrivenPipeline::REQUEST_UPDATE_EXTENT()))
  {
    // Piece 0 writes the whole image; other pieces need no data.
    vtkInformation* inInfo = inputVector[0]->GetInformationObject(0);
    vtkMSEngineBridge::RequestWholeExtentOnPieceZero(inInfo, this->Piece);
    return 1;
  }
  return this->Superclass::ProcessRequest(request, inputVector, outputVector);
}

vtkImageData* vtkMSOpenVDBWriter::GetImageDataInput()
{
  return vtkImageData::SafeDownCast(this->GetInput());
}

namespace
{
/// Value storage of the grids being written; a list so that views stay valid as it grows.
struct Buffers
{
  std::list<std::vector<std::int32_t>> Ints;
  std::list<std::vector<float>> Floats;
};

/// Appends @p array as a grid view (as floats when @p asFloat, even for integers). Returns
/// false (with @p skipped set) for arrays that do not map to a grid type.
bool AddArray(vtkDataArray* array, const std::string& name, const msynth::vdb::GridHeader& geometry,
  const char* association, double background, bool asFloat, Buffers& buffers,
  std::vector<msynth::vdb::DenseGridView>& views, std::string& skipped)
{
  const int nc = array->GetNumberOfComponents();
  const vtkIdType n = array->GetNumberOfTuples();
  msynth::vdb::DenseGridView view;
  view.Header = geometry;
  view.Header.Name = name;
  view.Header.Background = background;
  view.Header.Metadata["vtk_array"] = array->GetName() ? array->GetName() : "";
  view.Header.Metadata["vtk_association"] = association;
  if (nc == 1 && !asFloat && vtkMSEngineBridge::IsIntegerArray(array))
  {
    double range[2];
    array->GetRange(range, 0);
    if (range[0] < std::numeric_limits<std::int32_t>::min() ||
      range[1] > std::numeric_limits<std::int32_t>::max())
    {
      throw msynth::Error("array '" + name + "' has values outside the 32-bit integer range");
    }
    auto& values = buffers.Ints.emplace_back(static_cast<std::size_t>(n));
    for (vtkIdType i = 0; i < n; ++i)
    {
      values[static_cast<std::size_t>(i)] = static_cast<std::int32_t>(array->GetTuple1(i));
    }
    view.Header.Type = msynth::vdb::ValueType::Int32;
    view.Values = values.data();
  }
  else if (nc == 1 || nc == 3)
  {
    auto& values = buffers.Floats.emplace_back(static_cast<std::size_t>(n * nc));
    for (vtkIdType i = 0; i < n; ++i)
    {
      for (int c = 0; c < nc; ++c)
      {
        values[static_cast<std::size_t>(i * nc + c)] =
          static_cast<float>(array->GetComponent(i, c));
      }
    }
    view.Header.Type = nc == 1 ? msynth::vdb::ValueType::Float : msynth::vdb::ValueType::Vec3Float;
    view.Values = values.data();
  }
  else
  {
    skipped = "array '" + name + "' has " + std::to_string(nc) +
      " components (only 1 and 3 map to VDB grids)";
    return false;
  }
  views.push_back(std::move(view));
  return true;
}
} // namespace

void vtkMSOpenVDBWriter::WriteData()
{
  this->SetErrorCode(vtkErrorCode::NoError);
  if (this->Piece != 0)
  {
    return; // only the first piece writes (see class documentation)
  }
  if (this->FileName.empty())
  {
    vtkErrorMacro(<< "No file name was given.");
    this->SetErrorCode(vtkErrorCode::NoFileNameError);
    return;
  }
  vtkImageData* input = this->GetImageDataInput();
  if (!input)
  {
    vtkErrorMacro(<< "'" << this->FileName << "': not written: the input is not image data.");
    this->SetErrorCode(vtkErrorCode::UnknownError);
    return;
  }

  try
  {
    int extent[6];
    double origin[3], spacing[3];
    input->GetExtent(extent);
    input->GetOrigin(origin);
    input->GetSpacing(spacing);
    msynth::vdb::GridHeader points;
    for (int a = 0; a < 3; ++a)
    {
      points.IndexMin[a] = extent[2 * a];
      points.Dims[a] = std::int64_t(extent[2 * a + 1]) - extent[2 * a] + 1;
      points.Origin[a] = origin[a];
      points.Spacing[a] = spacing[a];
    }
    // Cells: one fewer along axes with more than one point, centred between the points.
    msynth::vdb::GridHeader cells = points;
    for (int a = 0; a < 3; ++a)
    {
      if (points.Dims[a] > 1)
      {
        cells.Dims[a] -= 1;
        cells.Origin[a] += 0.5 * spacing[a];
      }
    }
    if (input->GetNumberOfPoints() == 0)
    {
      throw msynth::Error("the input image is empty");
    }

    Buffers buffers;
    std::vector<msynth::vdb::DenseGridView> views;
    std::string skipped;
    auto addAll = [&](vtkDataSetAttributes* data, const msynth::vdb::GridHeader& geometry,
                    const char* association, bool cellData)
    {
      for (int i = 0; i < data->GetNumberOfArrays(); ++i)
      {
        vtkDataArray* array = data->GetArray(i);
        if (!array)
        {
          continue; // string or other non-numeric array
        }
        std::string name = array->GetName() ? array->GetName() : "array" + std::to_string(i);
        if (cellData && input->GetPointData()->GetAbstractArray(name.c_str()))
        {
          name += "_cell";
        }
        const bool isLabel = !cellData && name == this->LabelArrayName;
        if (!AddArray(array, name, geometry, association, isLabel ? this->EmptyLabel : 0.0, false,
              buffers, views, skipped))
        {
          vtkWarningMacro(<< "'" << this->FileName << "': " << skipped << "; skipped.");
          continue;
        }
        if (isLabel && this->WriteFloatLabels)
        {
          AddArray(array, name + "_float", geometry, association, this->EmptyLabel, true, buffers,
            views, skipped);
        }
      }
    };
    addAll(input->GetPointData(), points, "point", false);
    addAll(input->GetCellData(), cells, "cell", true);
    if (views.empty())
    {
      throw msynth::Error("the input has no array that maps to a VDB grid");
    }

    msynth::vdb::MetadataMap metadata;
    vtkFieldData* field = input->GetFieldData();
    for (int i = 0; field && i < field->GetNumberOfArrays(); ++i)
    {
      auto* strings = vtkStringArray::SafeDownCast(field->GetAbstractArray(i));
      if (strings && strings->GetName() && strings->GetNumberOfValues() == 1)
      {
        metadata[strings->GetName()] = strings->GetValue(0);
      }
    }
    for (const auto& kv : this->Internal->Metadata)
    {
      metadata[kv.first] = kv.second;
    }
    msynth::vdb::WriteFile(this->FileName, views, metadata);
  }
  catch (const std::exception& e)
  {
    const std::string what = e.what();
    // Engine errors about the file already start with its name.
    if (what.rfind("'" + this->FileName + "'", 0) == 0)
    {
      vtkErrorMacro(<< what);
    }
    else
    {
      vtkErrorMacro(<< "'" << this->FileName << "': not written: " << what);
    }
    this->SetErrorCode(vtkErrorCode::CannotOpenFileError);
  }
}

void vtkMSOpenVDBWriter::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "FileName: " << this->FileName << "\n";
  os << indent << "LabelArrayName: " << this->LabelArrayName << "\n";
  os << indent << "EmptyLabel: " << this->EmptyLabel << "\n";
  os << indent << "WriteFloatLabels: " << this->WriteFloatLabels << "\n";
  os << indent << "Piece: " << this->Piece << " of " << this->NumberOfPieces << "\n";
}
