// SPDX-License-Identifier: BSD-3-Clause
#include "vtkMSLabelArrays.h"

#include "vtkMSEngineBridge.h"
#include "vtkMSFieldData.h"
#include "vtkMSLabelArrays.h"
#include "vtkMSLabelGridReader.h"
#include "vtkMSPipeline.h"

#include "vtkAlgorithm.h"
#include "vtkCellArray.h"
#include "vtkCellArrayIterator.h"
#include "vtkCellData.h"
#include "vtkCommand.h"
#include "vtkDataArray.h"
#include "vtkDoubleArray.h"
#include "vtkExecutive.h"
#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkIdList.h"
#include "vtkIdTypeArray.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkIntArray.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSmartPointer.h"
#include "vtkStreamingDemandDrivenPipeline.h"
#include "vtkStringArray.h"
#include "vtkType.h"
#include "vtkTypeInt32Array.h"
#include "vtkTypeInt64Array.h"
#include "vtkUnsignedCharArray.h"

#include "Core/Error.h"
#include "Core/Index.h"
#include "Discrete/VoxelSurface.h"
#include "Formats/Image.h"
#include "Formats/VoxelTileset.h"

#include <algorithm>

#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <map>
#include <vector>

namespace
{
/// @p cells filled with @p surface's quads through raw pointers, ids of @p ArrayT's width.
template <typename ArrayT>
void FillQuads(const msynth::VoxelSurface& surface, vtkCellArray* cells)
{
  using Id = typename ArrayT::ValueType;
  const std::size_t n = surface.Quads.size();
  vtkNew<ArrayT> offsets;
  vtkNew<ArrayT> connectivity;
  offsets->SetNumberOfValues(static_cast<vtkIdType>(n + 1));
  connectivity->SetNumberOfValues(static_cast<vtkIdType>(4 * n));
  Id* offset = offsets->GetPointer(0);
  Id* corner = connectivity->GetPointer(0);
  for (std::size_t q = 0; q <= n; ++q)
    offset[q] = static_cast<Id>(4 * q);
  for (std::size_t q = 0; q < n; ++q)
    for (std::size_t k = 0; k < 4; ++k)
      corner[4 * q + k] = static_cast<Id>(surface.Quads[q][k]);
  cells->SetData(offsets, connectivity);
}

/**
 * @p surface as quads in @p output with the cell scalars `Label`. @p compact (the files of large
 * voxel models): single-precision points and, where they fit, 32-bit ids (a third less to
 * store and to compress).
 */
void FillSurfaceMesh(const msynth::VoxelSurface& surface, bool compact, vtkPolyData* output)
{
  const std::size_t np = surface.Points.size();
  vtkNew<vtkPoints> points;
  points->SetDataType(compact ? VTK_FLOAT : VTK_DOUBLE);
  points->SetNumberOfPoints(static_cast<vtkIdType>(np));
  if (compact)
  {
    float* xyz = vtkFloatArray::SafeDownCast(points->GetData())->GetPointer(0);
    for (std::size_t i = 0; i < np; ++i)
      for (std::size_t a = 0; a < 3; ++a)
        xyz[3 * i + a] = static_cast<float>(surface.Points[i][a]);
  }
  else
  {
    double* xyz = vtkDoubleArray::SafeDownCast(points->GetData())->GetPointer(0);
    for (std::size_t i = 0; i < np; ++i)
      std::copy(surface.Points[i].begin(), surface.Points[i].end(), xyz + 3 * i);
  }
  vtkNew<vtkCellArray> quads;
  if (compact && np < (std::size_t(1) << 31) && 4 * surface.Quads.size() < (std::size_t(1) << 31))
    FillQuads<vtkTypeInt32Array>(surface, quads);
  else
    FillQuads<vtkTypeInt64Array>(surface, quads);
  vtkNew<vtkIntArray> labels;
  labels->SetName("Label");
  labels->SetNumberOfValues(static_cast<vtkIdType>(surface.QuadLabels.size()));
  std::copy(surface.QuadLabels.begin(), surface.QuadLabels.end(), labels->GetPointer(0));
  output->SetPoints(points);
  output->SetPolys(quads);
  output->GetCellData()->SetScalars(labels);
}

/// The field array `PaletteRGBA` of @p palette (index 0 the empty voxel's entry).
vtkSmartPointer<vtkUnsignedCharArray> NewPaletteArray(
  const std::vector<std::array<std::uint8_t, 4>>& palette)
{
  auto colours = vtkSmartPointer<vtkUnsignedCharArray>::New();
  colours->SetName("PaletteRGBA");
  colours->SetNumberOfComponents(4);
  for (const auto& rgba : palette)
    colours->InsertNextTypedTuple(rgba.data());
  return colours;
}
} // namespace

bool vtkMSLabelArrays::IsIntegerArray(vtkDataArray* array)
{
  switch (array ? array->GetDataType() : VTK_VOID)
  {
    case VTK_CHAR:
    case VTK_SIGNED_CHAR:
    case VTK_UNSIGNED_CHAR:
    case VTK_SHORT:
    case VTK_UNSIGNED_SHORT:
    case VTK_INT:
    case VTK_UNSIGNED_INT:
    case VTK_LONG:
    case VTK_UNSIGNED_LONG:
    case VTK_LONG_LONG:
    case VTK_UNSIGNED_LONG_LONG:
    case VTK_ID_TYPE:
      return true;
    default:
      return false;
  }
}

bool vtkMSLabelArrays::CheckLabelArray(
  vtkImageData* image, vtkDataArray* array, std::string& problem)
{
  if (!image || !array)
  {
    problem = "no label array";
    return false;
  }
  const std::string name = array->GetName() ? array->GetName() : "(unnamed)";
  if (!IsIntegerArray(array))
  {
    problem = "array '" + name + "' holds " + array->GetDataTypeAsString() +
      " values; labels must be integers";
    return false;
  }
  if (array->GetNumberOfComponents() != 1)
  {
    problem = "array '" + name + "' has " + std::to_string(array->GetNumberOfComponents()) +
      " components; labels need exactly one";
    return false;
  }
  if (array->GetNumberOfTuples() != image->GetNumberOfPoints())
  {
    problem = "array '" + name + "' has " + std::to_string(array->GetNumberOfTuples()) +
      " values for " + std::to_string(image->GetNumberOfPoints()) + " sites";
    return false;
  }
  if (image->GetNumberOfPoints() == 0)
  {
    problem = "the label grid has no sites";
    return false;
  }
  double range[2];
  array->GetRange(range, 0);
  if (range[0] < std::numeric_limits<std::int32_t>::min() ||
    range[1] > std::numeric_limits<std::int32_t>::max())
  {
    problem = "array '" + name + "' has values outside the 32-bit integer range";
    return false;
  }
  return true;
}

vtkDataArray* vtkMSLabelArrays::FindLabelArray(vtkImageData* image, vtkDataArray* selected)
{
  if (selected || !image)
  {
    return selected;
  }
  vtkDataArray* labels = image->GetPointData()->GetArray("Label");
  return labels ? labels : image->GetPointData()->GetScalars();
}

bool vtkMSLabelArrays::ReadLabels(
  vtkImageData* image, vtkDataArray* selected, msynth::LabelGrid& grid, std::string& problem)
{
  vtkDataArray* labels = image ? FindLabelArray(image, selected) : nullptr;
  if (!labels)
  {
    problem = "the image has no label array (point array 'Label' or the active scalars)";
    return false;
  }
  if (!CheckLabelArray(image, labels, problem))
  {
    return false;
  }
  grid = ToLabelGrid(image, labels);
  return true;
}

msynth::LabelGrid vtkMSLabelArrays::ToLabelGrid(vtkImageData* image, vtkDataArray* labels)
{
  int dims[3];
  image->GetDimensions(dims);
  std::vector<msynth::Label> values(msynth::ToIndex(labels->GetNumberOfTuples()));
  for (vtkIdType i = 0; i < labels->GetNumberOfTuples(); ++i)
  {
    values[msynth::ToIndex(i)] = static_cast<msynth::Label>(labels->GetTuple1(i));
  }
  return msynth::LabelGrid({ { dims[0], dims[1], dims[2] } }, std::move(values));
}

vtkIntArray* vtkMSLabelArrays::NewLabelArray(const msynth::LabelGrid& grid, const char* name)
{
  vtkIntArray* array = vtkIntArray::New();
  array->SetName(name);
  array->SetNumberOfTuples(grid.NumberOfSites());
  std::copy(grid.Data().begin(), grid.Data().end(), array->GetPointer(0));
  return array;
}

bool vtkMSLabelArrays::VoxelSurface(vtkImageData* image, int empty, int piece, int pieces,
  vtkPolyData* output, std::string& problem, bool merge)
{
  output->Initialize();
  if (!image || image->GetNumberOfPoints() == 0)
  {
    return true;
  }
  msynth::LabelGrid grid;
  if (!ReadLabels(image, nullptr, grid, problem))
  {
    return false;
  }
  for (auto& label : grid.Data())
  {
    label = label == VTK_INT_MIN ? empty : label;
  }
  const double* spacing = image->GetSpacing();
  const std::array<double, 3> step{ { spacing[0], spacing[1], spacing[2] } };
  FillSurfaceMesh(merge
      ? msynth::ExtractMergedVoxelSurface(grid, empty, FirstSitePosition(image), step)
      : msynth::ExtractVoxelSurface(
          grid, empty, FirstSitePosition(image), step, msynth::PieceSlab(grid, piece, pieces)),
    merge, output);
  AddPaletteColors(image->GetFieldData(), output);
  return true;
}

void vtkMSLabelArrays::AddPaletteColors(vtkFieldData* fields, vtkPolyData* mesh)
{
  auto* palette =
    vtkUnsignedCharArray::SafeDownCast(fields ? fields->GetAbstractArray("PaletteRGBA") : nullptr);
  auto* labels = vtkIntArray::SafeDownCast(mesh->GetCellData()->GetArray("Label"));
  if (!palette || palette->GetNumberOfComponents() != 4 || !labels)
  {
    return;
  }
  vtkNew<vtkUnsignedCharArray> colours;
  colours->SetName("PaletteColor");
  colours->SetNumberOfComponents(4);
  colours->SetNumberOfTuples(labels->GetNumberOfTuples());
  const unsigned char none[4] = { 0, 0, 0, 0 };
  for (vtkIdType c = 0; c < labels->GetNumberOfTuples(); ++c)
  {
    const int label = labels->GetValue(c);
    colours->SetTypedTuple(c,
      label >= 0 && label < palette->GetNumberOfTuples() ? palette->GetPointer(4 * label) : none);
  }
  mesh->GetCellData()->AddArray(colours);
}

bool vtkMSLabelArrays::FillGeometryPort(
  vtkImageData* image, bool generate, int empty, vtkInformation* geometryInfo, std::string& problem)
{
  vtkPolyData* geometry = vtkPolyData::GetData(geometryInfo);
  geometry->Initialize();
  return !generate ||
    VoxelSurface(image, empty, vtkMSPipeline::UpdatePiece(geometryInfo),
      vtkMSPipeline::UpdateNumberOfPieces(geometryInfo), geometry, problem);
}

bool vtkMSLabelArrays::TileVoxels(
  const msynth::Tileset& set, vtkImageData* model, vtkImageData* voxels, std::string& problem)
{
  voxels->Initialize();
  msynth::LabelGrid grid;
  if (!model || model->GetNumberOfPoints() == 0)
    return true;
  if (!ReadLabels(model, nullptr, grid, problem))
    return false;
  std::vector<std::array<std::uint8_t, 4>> palette;
  msynth::LabelGrid composed;
  try
  {
    composed = msynth::ComposeVoxels(set, grid, palette, true);
  }
  catch (const std::exception& e)
  {
    problem = e.what();
    return false;
  }
  const auto& d = composed.Dimensions();
  voxels->SetDimensions(static_cast<int>(d[0]), static_cast<int>(d[1]), static_cast<int>(d[2]));
  std::array<double, 3> origin;
  std::array<double, 3> spacing;
  TileVoxelPlacement(set, model, origin, spacing);
  voxels->SetSpacing(spacing.data());
  voxels->SetOrigin(origin.data());
  vtkSmartPointer<vtkIntArray> labels;
  labels.TakeReference(NewLabelArray(composed, "Label"));
  voxels->GetPointData()->SetScalars(labels);
  voxels->GetFieldData()->AddArray(NewPaletteArray(palette));
  return true;
}

void vtkMSLabelArrays::TileVoxelPlacement(const msynth::Tileset& set, vtkImageData* model,
  std::array<double, 3>& origin, std::array<double, 3>& spacing)
{
  const double* step = model->GetSpacing();
  const std::array<double, 3> first = FirstSitePosition(model);
  for (std::size_t a = 0; a < 3; ++a)
  {
    // A site's cell [p - h/2, p + h/2] holds its tile's voxels.
    spacing[a] = step[a] / set.VoxelSize[a];
    origin[a] = first[a] - step[a] / 2 + spacing[a] / 2;
  }
}

void vtkMSLabelArrays::MergedVoxelMesh(const msynth::LabelGrid& voxels,
  const std::vector<std::array<std::uint8_t, 4>>& palette, const std::array<double, 3>& origin,
  const std::array<double, 3>& spacing, vtkPolyData* output)
{
  output->Initialize();
  FillSurfaceMesh(msynth::ExtractMergedVoxelSurface(voxels, 0, origin, spacing), true, output);
  vtkNew<vtkFieldData> fields;
  fields->AddArray(NewPaletteArray(palette));
  AddPaletteColors(fields, output);
}

std::array<double, 3> vtkMSLabelArrays::FirstSitePosition(vtkImageData* image)
{
  const double* spacing = image->GetSpacing();
  const double* origin = image->GetOrigin();
  int extent[6];
  image->GetExtent(extent);
  return { { origin[0] + extent[0] * spacing[0], origin[1] + extent[2] * spacing[1],
    origin[2] + extent[4] * spacing[2] } };
}

vtkUnsignedCharArray* vtkMSLabelArrays::PictureBytes(vtkImageData* image)
{
  if (!image || image->GetPointData()->GetArray("Label"))
    return nullptr;
  auto* bytes = vtkUnsignedCharArray::SafeDownCast(image->GetPointData()->GetScalars());
  const int nc = bytes ? bytes->GetNumberOfComponents() : 0;
  return nc >= 1 && nc <= 4 ? bytes : nullptr;
}

msynth::RgbaImage vtkMSLabelArrays::PictureRows(
  vtkImageData* image, vtkUnsignedCharArray* bytes, const std::string& what)
{
  int dims[3];
  image->GetDimensions(dims);
  if (dims[2] != 1)
    throw msynth::Error(what + " must be flat (it is " + std::to_string(dims[2]) + " pixels deep)");
  msynth::RgbaImage picture;
  picture.Width = dims[0];
  picture.Height = dims[1];
  picture.Pixels.resize(msynth::ToIndex(dims[0]) * msynth::ToIndex(dims[1]) * 4);
  const int nc = bytes->GetNumberOfComponents();
  std::uint8_t* out = picture.Pixels.data();
  for (int y = 0; y < dims[1]; ++y)
    for (int x = 0; x < dims[0]; ++x, out += 4)
    {
      const unsigned char* in =
        bytes->GetPointer(nc * (x + static_cast<vtkIdType>(dims[0]) * (dims[1] - 1 - y)));
      const bool grey = nc <= 2;
      for (int c = 0; c < 3; ++c)
        out[c] = in[grey ? 0 : c];
      out[3] = nc == 2 || nc == 4 ? in[nc - 1] : 255;
    }
  return picture;
}

void vtkMSLabelArrays::SetPicture(vtkImageData* output, const msynth::RgbaImage& picture)
{
  output->SetExtent(0, picture.Width - 1, 0, picture.Height - 1, 0, 0);
  vtkNew<vtkUnsignedCharArray> rgba;
  rgba->SetName("RGBA");
  rgba->SetNumberOfComponents(4);
  rgba->SetNumberOfTuples(static_cast<vtkIdType>(picture.Width) * picture.Height);
  for (int y = 0; y < picture.Height; ++y) // VTK's rows are bottom first, the picture's top first
    std::copy(picture.At(0, picture.Height - 1 - y),
      picture.At(0, picture.Height - 1 - y) + 4 * picture.Width,
      rgba->GetPointer(4 * static_cast<vtkIdType>(y) * picture.Width));
  output->GetPointData()->SetScalars(rgba);
}

msynth::LabelGrid vtkMSLabelArrays::ReadLabelGridFile(
  const std::string& path, std::array<int, 3>& first)
{
  vtkNew<vtkMSLabelGridReader> reader;
  reader->GenerateGeometryOff();
  reader->SetFileName(path.c_str());
  std::string messages;
  if (!vtkMSEngineBridge::Execute(reader, messages))
    throw msynth::Error(messages);
  msynth::LabelGrid grid;
  if (!vtkMSLabelArrays::ReadLabels(reader->GetOutput(), nullptr, grid, messages))
    throw msynth::Error::InFile(path, messages);
  int extent[6];
  reader->GetOutput()->GetExtent(extent);
  first = { { extent[0], extent[2], extent[4] } };
  return grid;
}
