// SPDX-License-Identifier: BSD-3-Clause
#include "vtkMSOpenVDBWriter.h"

#include "vtkMSArrangementStorage.h"
#include "vtkMSEngineBridge.h"
#include "vtkMSFieldData.h"
#include "vtkMSLabelArrays.h"
#include "vtkMSOnDemand.h"
#include "vtkMSPipeline.h"
#include "vtkMSPolyhedra.h"
#include "vtkMSRenderLabels.h"

#include "vtkAbstractArray.h"
#include "vtkAlgorithm.h"
#include "vtkCellArray.h"
#include "vtkCellArrayIterator.h"
#include "vtkCellData.h"
#include "vtkDataArray.h"
#include "vtkErrorCode.h"
#include "vtkFieldData.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkIntArray.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkSmartPointer.h"
#include "vtkStreamingDemandDrivenPipeline.h"
#include "vtkStringArray.h"
#include "vtkVariant.h"

#include "Continuous/ContinuousMesh.h"
#include "Core/Error.h"
#include "Core/Index.h"
#include "VDB/RenderGrids.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <list>
#include <map>
#include <vector>

vtkStandardNewMacro(vtkMSOpenVDBWriter);

struct vtkMSOpenVDBWriter::Internals
{
  msynth::vdb::MetadataMap Metadata;
};

vtkMSOpenVDBWriter::vtkMSOpenVDBWriter()
  : Internal(new Internals)
{
  this->SetNumberOfInputPorts(2);
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

int vtkMSOpenVDBWriter::FillInputPortInformation(int port, vtkInformation* info)
{
  info->Remove(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE());
  if (port == 1)
  {
    info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkPolyData");
    info->Set(vtkAlgorithm::INPUT_IS_OPTIONAL(), 1);
    return 1;
  }
  info->Append(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkImageData");
  info->Append(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkPolyData");
  return 1;
}

vtkTypeBool vtkMSOpenVDBWriter::ProcessRequest(
  vtkInformation* request, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  if (request->Has(vtkStreamingDemandDrivenPipeline::REQUEST_UPDATE_EXTENT()))
  {
    // Piece 0 writes the whole input; other pieces need no data.
    vtkInformation* inInfo = inputVector[0]->GetInformationObject(0);
    if (this->WritingSequence)
    {
      inInfo->Set(vtkStreamingDemandDrivenPipeline::UPDATE_TIME_STEP(), this->CurrentTime);
    }
    if (inInfo->Has(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT()))
    {
      vtkMSPipeline::RequestWholeExtentOnPieceZero(inInfo, this->Piece);
    }
    else if (this->Piece == 0)
    {
      inInfo->Set(vtkStreamingDemandDrivenPipeline::UPDATE_PIECE_NUMBER(), 0);
      inInfo->Set(vtkStreamingDemandDrivenPipeline::UPDATE_NUMBER_OF_PIECES(), 1);
    }
    if (vtkInformation* arrangement = inputVector[1]->GetInformationObject(0))
    {
      arrangement->Set(vtkStreamingDemandDrivenPipeline::UPDATE_PIECE_NUMBER(), 0);
      arrangement->Set(vtkStreamingDemandDrivenPipeline::UPDATE_NUMBER_OF_PIECES(), 1);
    }
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
  if (nc == 1 && !asFloat && vtkMSLabelArrays::IsIntegerArray(array))
  {
    double range[2];
    array->GetRange(range, 0);
    if (range[0] < std::numeric_limits<std::int32_t>::min() ||
      range[1] > std::numeric_limits<std::int32_t>::max())
    {
      throw msynth::Error("array '" + name + "' has values outside the 32-bit integer range");
    }
    auto& values = buffers.Ints.emplace_back(msynth::ToIndex(n));
    for (vtkIdType i = 0; i < n; ++i)
    {
      values[msynth::ToIndex(i)] = static_cast<std::int32_t>(array->GetTuple1(i));
    }
    view.Header.Type = msynth::vdb::ValueType::Int32;
    view.Values = values.data();
  }
  else if (nc == 1 || nc == 3)
  {
    auto& values = buffers.Floats.emplace_back(msynth::ToIndex(n * nc));
    for (vtkIdType i = 0; i < n; ++i)
    {
      for (int c = 0; c < nc; ++c)
      {
        values[msynth::ToIndex(i * nc + c)] = static_cast<float>(array->GetComponent(i, c));
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
/// File metadata: every single-valued array of @p field (strings such as ExampleFile, numbers
/// such as the solver's Seed and statistics; not the timing, so equal runs give equal files), then
/// the pairs given.
msynth::vdb::MetadataMap FileMetadata(vtkFieldData* field, const msynth::vdb::MetadataMap& extra)
{
  msynth::vdb::MetadataMap metadata;
  for (int i = 0; field && i < field->GetNumberOfArrays(); ++i)
  {
    vtkAbstractArray* array = field->GetAbstractArray(i);
    if (!array || !array->GetName() || array->GetNumberOfValues() != 1 ||
      vtkMSFieldData::IsTiming(array->GetName()))
    {
      continue;
    }
    if (auto* strings = vtkStringArray::SafeDownCast(array))
    {
      metadata[strings->GetName()] = strings->GetValue(0);
    }
    else if (auto* numbers = vtkDataArray::SafeDownCast(array))
    {
      metadata[numbers->GetName()] = array->GetVariantValue(0).ToString();
    }
  }
  // Names by id: the label grid reader's pieces (PieceLabels, PieceNames) and the object
  // types of continuous models (TypeIds, TypeNames), as "id:name;id:name".
  const std::pair<const char*, const char*> named[] = { { "PieceLabels", "PieceNames" },
    { "TypeIds", "TypeNames" } };
  const char* keys[] = { "label_names", "object_type_names" };
  for (int k = 0; k < 2 && field; ++k)
  {
    auto* ids = vtkDataArray::SafeDownCast(field->GetAbstractArray(named[k].first));
    auto* names = vtkStringArray::SafeDownCast(field->GetAbstractArray(named[k].second));
    if (ids && names && ids->GetNumberOfValues() == names->GetNumberOfValues() &&
      names->GetNumberOfValues() > 0)
    {
      std::string text;
      for (vtkIdType i = 0; i < names->GetNumberOfValues(); ++i)
      {
        text += (i ? ";" : "") + std::to_string(static_cast<long long>(ids->GetTuple1(i))) + ":" +
          names->GetValue(i);
      }
      metadata[keys[k]] = text;
      metadata.erase(named[k].first); // the single-valued case was added above
      metadata.erase(named[k].second);
    }
  }
  for (const auto& kv : extra)
  {
    metadata[kv.first] = kv.second;
  }
  return metadata;
}
} // namespace

namespace
{
/// The point and cell geometry of @p input as grid headers; cells are one fewer along axes with
/// more than one point, centred between the points.
void GridGeometries(
  vtkImageData* input, msynth::vdb::GridHeader& points, msynth::vdb::GridHeader& cells)
{
  int extent[6];
  double origin[3], spacing[3];
  input->GetExtent(extent);
  input->GetOrigin(origin);
  input->GetSpacing(spacing);
  for (int a = 0; a < 3; ++a)
  {
    points.IndexMin[a] = extent[2 * a];
    points.Dims[a] = std::int64_t(extent[2 * a + 1]) - extent[2 * a] + 1;
    points.Origin[a] = origin[a];
    points.Spacing[a] = spacing[a];
  }
  cells = points;
  for (int a = 0; a < 3; ++a)
  {
    if (points.Dims[a] > 1)
    {
      cells.Dims[a] -= 1;
      cells.Origin[a] += 0.5 * spacing[a];
    }
  }
}

/// Which array holds labels, and how they are written.
struct LabelPolicy
{
  std::string ArrayName;
  double Empty = 0;
  bool AlsoFloat = false;
};

/// Every numeric array of @p data as a grid of @p geometry (the label array also as float when
/// asked); the reasons for arrays that cannot be grids go to @p skipped.
void AddGrids(vtkDataSetAttributes* data, vtkImageData* input,
  const msynth::vdb::GridHeader& geometry, const char* association, bool cellData,
  const LabelPolicy& labels, Buffers& buffers, std::vector<msynth::vdb::DenseGridView>& views,
  std::vector<std::string>& skipped)
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
    const bool isLabel = !cellData && name == labels.ArrayName;
    std::string reason;
    if (!AddArray(array, name, geometry, association, isLabel ? labels.Empty : 0.0, false, buffers,
          views, reason))
    {
      skipped.push_back(reason);
      continue;
    }
    if (isLabel && labels.AlsoFloat)
    {
      AddArray(
        array, name + "_float", geometry, association, labels.Empty, true, buffers, views, reason);
    }
  }
}
} // namespace

namespace
{
/// The render view of the label grid among @p views (none without one) onto @p renders.
void AddRenderView(vtkMSOpenVDBWriter* self, vtkImageData* input,
  const std::vector<msynth::vdb::DenseGridView>& views,
  std::vector<msynth::vdb::LabelRenderView>& renders)
{
  // The integer point grids written above: the labels, and the keys of their names.
  const auto pointInts = [&views](const std::string& name) -> const msynth::vdb::DenseGridView*
  {
    for (const auto& view : views)
      if (view.Header.Name == name && view.Header.Type == msynth::vdb::ValueType::Int32 &&
        view.Header.Metadata.at("vtk_association") == "point")
        return &view;
    return nullptr;
  };
  const msynth::vdb::DenseGridView* labels = pointInts(self->GetLabelArrayName());
  if (!labels)
    return; // no label volume: nothing a renderer would shade as solid
  const msynth::vdb::DenseGridView* keys =
    std::string(self->GetNameArrayName()).empty() ? nullptr : pointInts(self->GetNameArrayName());
  msynth::vdb::LabelRenderView render;
  render.Geometry = labels->Header;
  render.Labels = static_cast<const std::int32_t*>(labels->Values);
  render.EmptyLabel = self->GetEmptyLabel();
  render.NameKeys = keys ? static_cast<const std::int32_t*>(keys->Values) : nullptr;
  render.HalfWidth = self->GetBandWidth();
  render.LabelSurfaceBudget = self->GetLabelSurfaceBudget();
  vtkMSRenderLabels::Describe(
    input->GetFieldData(), std::string(self->GetNameArrayName()).empty() || keys, render);
  renders.push_back(std::move(render));
}

} // namespace

void vtkMSOpenVDBWriter::WriteData()
{
  this->SetErrorCode(vtkErrorCode::NoError);
  if (this->Piece != 0)
  {
    return; // only the first piece writes (see class documentation)
  }
  if (!this->WritingSequence)
  {
    this->CurrentFileName = this->FileName;
  }
  if (this->FileName.empty())
  {
    vtkErrorMacro(<< "No file name was given.");
    this->SetErrorCode(vtkErrorCode::NoFileNameError);
    return;
  }
  vtkSmartPointer<vtkImageData> resampled;
  bool types = false; // a continuous model voxelized: its ObjectType labels
  if (auto* poly = vtkPolyData::SafeDownCast(this->GetInput()))
  {
    auto* arrangement = vtkPolyData::SafeDownCast(this->GetInputDataObject(1, 0));
    types =
      arrangement && (poly->GetNumberOfPolys() == 0 || poly->GetCellData()->GetArray("ObjectType"));
    if (poly->GetNumberOfPolys() > 0 && !types)
    {
      this->WriteMesh(poly);
      return;
    }
    try
    {
      resampled = types ? this->VoxelizeTypes(poly, arrangement) : this->ResamplePoints(poly);
    }
    catch (const std::exception& e)
    {
      this->ReportFailure(e.what());
      return;
    }
  }
  vtkImageData* input = resampled ? resampled.GetPointer() : this->GetImageDataInput();
  if (!input)
  {
    vtkErrorMacro(<< "'" << this->FileName
                  << "': not written: the input is neither image data nor a mesh.");
    this->SetErrorCode(vtkErrorCode::UnknownError);
    return;
  }

  try
  {
    msynth::vdb::GridHeader points, cells;
    GridGeometries(input, points, cells);
    if (input->GetNumberOfPoints() == 0)
    {
      throw msynth::Error("the input image is empty");
    }
    Buffers buffers;
    std::vector<msynth::vdb::DenseGridView> views;
    std::vector<std::string> skipped;
    const LabelPolicy labels = types
      ? LabelPolicy{ "ObjectType", 0.0, true }
      : LabelPolicy{ this->LabelArrayName, static_cast<double>(this->EmptyLabel),
          this->WriteFloatLabels };
    AddGrids(input->GetPointData(), input, points, "point", false, labels, buffers, views, skipped);
    AddGrids(input->GetCellData(), input, cells, "cell", true, labels, buffers, views, skipped);
    for (const auto& reason : skipped)
    {
      vtkWarningMacro(<< "'" << this->FileName << "': " << reason << "; skipped.");
    }
    if (views.empty())
    {
      throw msynth::Error("the input has no array that maps to a VDB grid");
    }
    std::vector<msynth::vdb::LabelRenderView> renders;
    if (this->WriteRenderGrids && !resampled) // label images only, not points resampled
      AddRenderView(this, input, views, renders);
    msynth::vdb::WriteFile(this->CurrentFileName, views, {}, renders,
      FileMetadata(input->GetFieldData(), this->Internal->Metadata));
  }
  catch (const std::exception& e)
  {
    this->ReportFailure(e.what());
  }
}

void vtkMSOpenVDBWriter::ReportFailure(const std::string& what)
{
  // Engine errors about the file already start with its name.
  const std::string& file = this->CurrentFileName.empty() ? this->FileName : this->CurrentFileName;
  if (what.rfind("'" + file + "'", 0) == 0)
  {
    vtkErrorMacro(<< what);
  }
  else
  {
    vtkErrorMacro(<< "'" << file << "': not written: " << what);
  }
  this->SetErrorCode(vtkErrorCode::CannotOpenFileError);
}

vtkSmartPointer<vtkImageData> vtkMSOpenVDBWriter::ResamplePoints(vtkPolyData* input)
{
  if (input->GetNumberOfPoints() == 0)
  {
    throw msynth::Error("the input has no points and no polygons");
  }
  double bounds[6];
  input->GetBounds(bounds);
  const double extent =
    std::max({ bounds[1] - bounds[0], bounds[3] - bounds[2], bounds[5] - bounds[4] });
  auto* arrangement = vtkPolyData::SafeDownCast(this->GetInputDataObject(1, 0));
  const double voxel = this->ChooseVoxel(arrangement ? arrangement : input, 2, 128, extent);
  this->WrittenVoxelSize = voxel;
  int dims[3];
  double total = 1;
  for (int a = 0; a < 3; ++a)
  {
    const double n = std::floor((bounds[2 * a + 1] - bounds[2 * a]) / voxel + 1e-9) + 1;
    total *= n;
    dims[a] = static_cast<int>(std::min(n, 1e9));
  }
  if (total > double(std::int64_t(1) << 28))
  {
    throw msynth::Error("resampling the points at voxel size " + std::to_string(voxel) + " needs " +
      std::to_string(static_cast<long long>(total)) +
      " voxels (more than 2^28); use a larger VoxelSize");
  }
  vtkNew<vtkImageData> grid;
  grid->SetDimensions(dims);
  grid->SetOrigin(bounds[0], bounds[2], bounds[4]);
  grid->SetSpacing(voxel, voxel, voxel);
  // Each voxel takes the values of the nearest point (a Voronoi kernel): labels stay labels.
  vtkSmartPointer<vtkAlgorithm> interpolator = vtkMSOnDemand::NewNearestPointResampler();
  interpolator->SetInputDataObject(0, grid);
  interpolator->SetInputDataObject(1, input);
  std::string messages;
  if (!vtkMSEngineBridge::Execute(interpolator, messages))
  {
    throw msynth::Error("resampling the points failed: " + messages);
  }
  vtkSmartPointer<vtkImageData> out =
    vtkImageData::SafeDownCast(interpolator->GetOutputDataObject(0));
  vtkNew<vtkImageData> copy;
  copy->ShallowCopy(out);
  copy->GetFieldData()->ShallowCopy(input->GetFieldData());
  // The interpolator gives floats; integer arrays (labels, counts) are integers again, exactly.
  vtkPointData* values = copy->GetPointData();
  for (int i = 0; i < values->GetNumberOfArrays(); ++i)
  {
    vtkDataArray* sampled = values->GetArray(i);
    vtkDataArray* original =
      sampled && sampled->GetName() ? input->GetPointData()->GetArray(sampled->GetName()) : nullptr;
    if (!original || !vtkMSLabelArrays::IsIntegerArray(original) ||
      original->GetNumberOfComponents() != 1)
    {
      continue;
    }
    vtkNew<vtkIntArray> integers;
    integers->SetName(sampled->GetName());
    integers->SetNumberOfValues(sampled->GetNumberOfTuples());
    for (vtkIdType t = 0; t < sampled->GetNumberOfTuples(); ++t)
    {
      integers->SetValue(t, static_cast<int>(std::llround(sampled->GetTuple1(t))));
    }
    values->AddArray(integers); // replaces the float array of the same name
  }
  return vtkSmartPointer<vtkImageData>(copy.GetPointer());
}

void vtkMSOpenVDBWriter::WriteMesh(vtkPolyData* input)
{
  try
  {
    if (input->GetNumberOfPolys() == 0)
    {
      throw msynth::Error("the mesh has no polygons");
    }
    double bounds[6];
    input->GetBounds(bounds);
    const double extent =
      std::max({ bounds[1] - bounds[0], bounds[3] - bounds[2], bounds[5] - bounds[4] });
    if (bounds[1] - bounds[0] <= 0 || bounds[3] - bounds[2] <= 0 || bounds[5] - bounds[4] <= 0)
    {
      throw msynth::Error(
        "the mesh is flat (a 2D model encloses no volume); level sets need closed 3D surfaces");
    }
    auto* arrangement = vtkPolyData::SafeDownCast(this->GetInputDataObject(1, 0));
    double voxel = this->ChooseVoxel(arrangement, 4, 256, extent);
    const bool continuous =
      input->GetCellData()->GetArray("InsideType") && input->GetCellData()->GetArray("OutsideType");
    if (this->VoxelSize <= 0 && this->LevelSetBudget > 0 && continuous)
      voxel = std::max(voxel,
        msynth::LevelSetVoxel(vtkMSPolyhedra::ToContinuousMesh(input, this->CurrentFileName), 0.0,
          0.0, this->BandWidth, this->LevelSetBudget));
    this->WrittenVoxelSize = voxel;
    if (arrangement)
      arrangement->GetBounds(bounds);
    this->GridDimensions(bounds, voxel, false);
    auto* names =
      vtkStringArray::SafeDownCast(input->GetFieldData()->GetAbstractArray("TypeNames"));
    // Polygons per grid: the whole model (its interfaces with empty space), and per type.
    std::vector<std::array<double, 3>> points;
    std::vector<std::vector<std::int32_t>> all;
    std::map<int, std::vector<std::vector<std::int32_t>>> perType;
    if (input->GetCellData()->GetArray("InsideType") &&
      input->GetCellData()->GetArray("OutsideType"))
    {
      msynth::ContinuousMesh model = vtkMSPolyhedra::ToContinuousMesh(input, this->CurrentFileName);
      perType = msynth::SurfacesByType(model);
      for (std::size_t f = 0; f < model.Polygons.size(); ++f)
      {
        if (model.OutsideType[f] == 0)
        {
          all.push_back(std::move(model.Polygons[f]));
        }
      }
      points = std::move(model.Points);
    }
    else
    {
      points.resize(msynth::ToIndex(input->GetNumberOfPoints()));
      for (vtkIdType i = 0; i < input->GetNumberOfPoints(); ++i)
      {
        input->GetPoint(i, points[msynth::ToIndex(i)].data());
      }
      auto polys = vtk::TakeSmartPointer(input->GetPolys()->NewIterator());
      for (polys->GoToFirstCell(); !polys->IsDoneWithTraversal(); polys->GoToNextCell())
      {
        vtkIdType n;
        const vtkIdType* ids;
        polys->GetCurrentCell(n, ids);
        all.emplace_back(ids, ids + n);
      }
    }
    std::vector<msynth::vdb::MeshGridView> meshes;
    msynth::vdb::MeshGridView whole;
    whole.Name = "surface";
    whole.Points = &points;
    whole.Polygons = &all;
    whole.VoxelSize = voxel;
    whole.HalfWidth = this->BandWidth;
    whole.FogName = this->WriteFog ? "density" : "";
    for (const auto& [type, polygons] : perType)
    {
      msynth::vdb::MeshGridView view = whole;
      std::string name = std::to_string(type);
      if (names && type >= 0 && type < names->GetNumberOfValues() && !names->GetValue(type).empty())
      {
        name = names->GetValue(type);
      }
      view.Name = "surface_" + name;
      view.Polygons = &polygons;
      view.FogName.clear();
      view.UnionOf.clear();
      view.Metadata["object_type"] = std::to_string(type);
      view.Metadata["object_type_name"] = name;
      meshes.push_back(view);
      whole.UnionOf.push_back(view.Name);
    }
    meshes.push_back(whole); // with types: the union of theirs (voxelized once, not twice)
    msynth::vdb::WriteFile(this->CurrentFileName, {}, meshes,
      FileMetadata(input->GetFieldData(), this->Internal->Metadata));
  }
  catch (const std::exception& e)
  {
    this->ReportFailure(e.what());
  }
}

double vtkMSOpenVDBWriter::ChooseVoxel(
  vtkPolyData* arrangement, double perSpacing, double perExtent, double extent)
{
  if (this->VoxelSize > 0)
    return this->VoxelSize;
  const double spacing =
    arrangement ? vtkMSArrangementStorage::SmallestSpacing(arrangement->GetFieldData()) : 0.0;
  if (spacing > 0)
  {
    double box[6];
    arrangement->GetBounds(box);
    extent = std::max({ box[1] - box[0], box[3] - box[2], box[5] - box[4] });
    const double voxel = std::max(spacing / perSpacing, extent / perExtent);
    return voxel > 0 ? voxel : 1.0;
  }
  return extent > 0 ? extent / perExtent : 1.0;
}

std::array<std::int64_t, 3> vtkMSOpenVDBWriter::GridDimensions(
  const double bounds[6], double voxel, bool planar)
{
  std::array<std::int64_t, 3> dims{ { 1, 1, 1 } };
  double total = 1;
  for (int c = 0; c < (planar ? 2 : 3); ++c)
  {
    const double n = std::max(1.0, std::ceil((bounds[2 * c + 1] - bounds[2 * c]) / voxel));
    total *= n;
    dims[msynth::ToIndex(c)] = static_cast<std::int64_t>(std::min(n, 1e18));
  }
  if (total > this->MaximumVoxels)
    throw msynth::Error("voxels of " + std::to_string(voxel) + " give more than " +
      std::to_string(static_cast<long long>(this->MaximumVoxels)) +
      " voxels (MaximumVoxels); use a larger VoxelSize");
  return dims;
}

vtkSmartPointer<vtkImageData> vtkMSOpenVDBWriter::VoxelizeTypes(
  vtkPolyData* model, vtkPolyData* arrangement)
{
  const bool planar = model->GetCellData()->GetArray("ObjectType") != nullptr;
  double box[6];
  arrangement->GetBounds(box);
  const double voxel = this->ChooseVoxel(arrangement, 4, 256,
    std::max({ box[1] - box[0], box[3] - box[2], planar ? 0.0 : box[5] - box[4] }));
  this->WrittenVoxelSize = voxel;
  const std::array<std::int64_t, 3> dims = this->GridDimensions(box, voxel, planar);
  const msynth::LabelGrid volume =
    msynth::VoxelizeModel(vtkMSPolyhedra::ToContinuousMesh(model, "model"),
      { box[0], box[2], planar ? 0.0 : box[4] }, voxel, dims);
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->SetDimensions(
    static_cast<int>(dims[0]), static_cast<int>(dims[1]), static_cast<int>(dims[2]));
  image->SetSpacing(voxel, voxel, voxel);
  image->SetOrigin(box[0] + voxel / 2, box[2] + voxel / 2, planar ? 0.0 : box[4] + voxel / 2);
  vtkSmartPointer<vtkIntArray> types;
  types.TakeReference(vtkMSLabelArrays::NewLabelArray(volume, "ObjectType"));
  image->GetPointData()->SetScalars(types);
  return image;
}

std::string vtkMSOpenVDBWriter::SequenceFileName(int index) const
{
  std::string stem = this->FileName, extension = ".vdb";
  const std::size_t dot = stem.rfind('.');
  const std::size_t slash = stem.rfind('/');
  if (dot != std::string::npos && (slash == std::string::npos || dot > slash))
  {
    extension = stem.substr(dot);
    stem = stem.substr(0, dot);
  }
  char number[16];
  std::snprintf(number, sizeof(number), "_%04d", index + 1);
  return stem + number + extension;
}

int vtkMSOpenVDBWriter::Write()
{
  this->CurrentFileName = this->FileName;
  if (!this->WriteTimeSteps || !this->GetInputAlgorithm())
  {
    return this->Superclass::Write();
  }
  this->GetInputAlgorithm()->UpdateInformation();
  vtkInformation* inInfo = this->GetInputInformation(0, 0);
  if (!inInfo || !inInfo->Has(vtkStreamingDemandDrivenPipeline::TIME_STEPS()))
  {
    return this->Superclass::Write(); // no time steps: one file
  }
  const int steps = inInfo->Length(vtkStreamingDemandDrivenPipeline::TIME_STEPS());
  const double* times = inInfo->Get(vtkStreamingDemandDrivenPipeline::TIME_STEPS());
  const std::vector<double> copy(times, times + steps);
  this->WritingSequence = true;
  int ok = 1;
  for (int i = 0; i < steps && ok; ++i)
  {
    this->CurrentFileName = this->SequenceFileName(i);
    this->CurrentTime = copy[msynth::ToIndex(i)];
    ok = this->Superclass::Write(); // asks the input for CurrentTime (ProcessRequest)
  }
  this->WritingSequence = false;
  this->CurrentFileName = this->FileName;
  return ok;
}

void vtkMSOpenVDBWriter::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "FileName: " << this->FileName << "\n";
  os << indent << "LabelArrayName: " << this->LabelArrayName << "\n";
  os << indent << "EmptyLabel: " << this->EmptyLabel << "\n";
  os << indent << "WriteFloatLabels: " << this->WriteFloatLabels << "\n";
  os << indent << "VoxelSize: " << this->VoxelSize << "\n";
  os << indent << "MaximumVoxels: " << this->MaximumVoxels << "\n";
  os << indent << "BandWidth: " << this->BandWidth << "\n";
  os << indent << "LevelSetBudget: " << this->LevelSetBudget << "\n";
  os << indent << "WriteFog: " << this->WriteFog << "\n";
  os << indent << "WriteTimeSteps: " << this->WriteTimeSteps << "\n";
  os << indent << "WriteRenderGrids: " << this->WriteRenderGrids << "\n";
  os << indent << "LabelSurfaceBudget: " << this->LabelSurfaceBudget << "\n";
  os << indent << "NameArrayName: " << this->NameArrayName << "\n";
  os << indent << "Piece: " << this->Piece << " of " << this->NumberOfPieces << "\n";
}
