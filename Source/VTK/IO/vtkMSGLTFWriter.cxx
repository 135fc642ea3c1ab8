// SPDX-License-Identifier: BSD-3-Clause
#include "vtkMSGLTFWriter.h"

#include "vtkAlgorithm.h"
#include "vtkCellArray.h"
#include "vtkCellData.h"
#include "vtkDataArray.h"
#include "vtkErrorCode.h"
#include "vtkFieldData.h"
#include "vtkIdList.h"
#include "vtkInformation.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSmartPointer.h"
#include "vtkStringArray.h"

#include "vtkMSOnDemand.h"
#include "vtkMSPolyhedra.h"

#include "Continuous/ContinuousMesh.h"
#include "Core/Index.h"
#include "Core/LabelColor.h"
#include "Formats/GltfFile.h"

#include <array>
#include <cmath>
#include <cstdio>
#include <exception>
#include <map>
#include <unordered_map>
#include <vector>

vtkStandardNewMacro(vtkMSGLTFWriter);

namespace
{
/// A group of cells: label, then colour (RGBA bytes; all 256 when uncoloured).
using GroupKey = std::pair<long long, std::array<int, 4>>;

struct Group
{
  msynth::GltfPart Part;
  std::unordered_map<vtkIdType, std::uint32_t> Vertex; // input point -> the part's vertex
};

std::string GroupName(const GroupKey& key, bool labelled, bool coloured)
{
  std::string name = labelled ? "label " + std::to_string(key.first) : "mesh";
  if (coloured)
  {
    char hex[8];
    std::snprintf(hex, sizeof(hex), "#%02x%02x%02x", key.second[0] & 255, key.second[1] & 255,
      key.second[2] & 255);
    name += std::string(" ") + hex;
  }
  return name;
}

std::array<double, 4> GroupColor(const GroupKey& key, bool labelled, bool coloured)
{
  if (coloured)
    return { key.second[0] / 255.0, key.second[1] / 255.0, key.second[2] / 255.0,
      key.second[3] / 255.0 };
  if (!labelled)
    return { 0.7, 0.7, 0.7, 1.0 };
  const auto rgb = msynth::LabelColor(static_cast<int>(key.first));
  return { rgb[0], rgb[1], rgb[2], 1.0 };
}

/// The triangles of @p mesh grouped by label and colour, as glTF parts in key order.
std::vector<msynth::GltfPart> GroupTriangles(
  vtkPolyData* mesh, vtkDataArray* labels, vtkDataArray* colors)
{
  std::map<GroupKey, Group> groups;
  vtkPoints* points = mesh->GetPoints();
  vtkCellArray* polys = mesh->GetPolys();
  vtkNew<vtkIdList> ids;
  vtkIdType cell = mesh->GetNumberOfVerts() + mesh->GetNumberOfLines(); // polys come next
  for (polys->InitTraversal(); polys->GetNextCell(ids); ++cell)
  {
    if (ids->GetNumberOfIds() != 3)
      continue; // degenerate leftovers of the triangulation
    GroupKey key{ 0, { 256, 256, 256, 256 } };
    if (labels)
      key.first = std::llround(labels->GetComponent(cell, 0));
    if (colors)
      for (int c = 0; c < 4; ++c)
        key.second[msynth::ToIndex(c)] = c < colors->GetNumberOfComponents()
          ? static_cast<int>(colors->GetComponent(cell, c))
          : 255;
    Group& group = groups[key];
    for (vtkIdType k = 0; k < 3; ++k)
    {
      const vtkIdType id = ids->GetId(k);
      auto found = group.Vertex.find(id);
      if (found == group.Vertex.end())
      {
        const auto index = static_cast<std::uint32_t>(group.Part.Positions.size() / 3);
        found = group.Vertex.emplace(id, index).first;
        double p[3];
        points->GetPoint(id, p);
        for (double x : p)
          group.Part.Positions.push_back(static_cast<float>(x));
      }
      group.Part.Triangles.push_back(found->second);
    }
  }
  std::vector<msynth::GltfPart> parts;
  for (auto& entry : groups)
  {
    entry.second.Part.Name = GroupName(entry.first, labels != nullptr, colors != nullptr);
    entry.second.Part.Color = GroupColor(entry.first, labels != nullptr, colors != nullptr);
    parts.push_back(std::move(entry.second.Part));
  }
  return parts;
}

/// The readable object type names of field data TypeNames (paired with TypeIds when present,
/// else by type id, as vtkMSArrangementMesh stores them).
std::map<int, std::string> TypeNames(vtkFieldData* fields)
{
  std::map<int, std::string> names;
  auto* text = vtkStringArray::SafeDownCast(fields->GetAbstractArray("TypeNames"));
  auto* ids = vtkDataArray::SafeDownCast(fields->GetAbstractArray("TypeIds"));
  if (!text)
    return names;
  for (vtkIdType i = 0; i < text->GetNumberOfValues(); ++i)
  {
    const int type = ids && i < ids->GetNumberOfTuples()
      ? static_cast<int>(std::llround(ids->GetTuple1(i)))
      : static_cast<int>(i);
    if (!text->GetValue(i).empty())
      names[type] = text->GetValue(i);
  }
  return names;
}

/// A continuous model's mesh (or a polyhedral example): one part per solid object type, its
/// closed surface (msynth::SurfacesByType: InsideType as is, OutsideType reversed),
/// flat-shaded with normals, named by the type's name.
std::vector<msynth::GltfPart> TypeParts(vtkPolyData* input, const std::string& path)
{
  const msynth::ContinuousMesh mesh = vtkMSPolyhedra::ToContinuousMesh(input, path);
  const std::map<int, std::string> names = TypeNames(input->GetFieldData());
  double bounds[6];
  input->GetBounds(bounds);
  const bool flat = input->GetNumberOfPoints() > 0 && bounds[5] <= bounds[4];
  std::vector<msynth::GltfPart> parts;
  for (const auto& [type, polygons] : msynth::SurfacesByType(mesh))
  {
    msynth::GltfPart part;
    const auto name = names.find(type);
    part.Name = name != names.end() ? name->second : "type " + std::to_string(type);
    const auto rgb = msynth::LabelColor(type);
    part.Color = { rgb[0], rgb[1], rgb[2], 1.0 };
    part.DoubleSided = flat; // a flat model is seen from above and below
    msynth::AppendFlatPolygons(part, mesh.Points, polygons);
    parts.push_back(std::move(part));
  }
  return parts;
}

/// Whether @p input is a continuous model's mesh or a polyhedral example: no label array, and
/// object types per polygon (InsideType and OutsideType, or ObjectType).
bool HasObjectTypes(vtkPolyData* input, const std::string& labelArray)
{
  vtkCellData* cells = input->GetCellData();
  return !cells->GetArray(labelArray.c_str()) &&
    (cells->GetArray("ObjectType") ||
      (cells->GetArray("InsideType") && cells->GetArray("OutsideType")));
}
} // namespace

void vtkMSGLTFWriter::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "FileName: " << this->FileName << "\n";
  os << indent << "LabelArrayName: " << this->LabelArrayName << "\n";
  os << indent << "ColorArrayName: " << this->ColorArrayName << "\n";
}

int vtkMSGLTFWriter::FillInputPortInformation(int, vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkPolyData");
  return 1;
}

void vtkMSGLTFWriter::WriteData()
{
  this->SetErrorCode(vtkErrorCode::NoError);
  if (this->FileName.empty())
  {
    vtkErrorMacro(<< "No file name was given.");
    this->SetErrorCode(vtkErrorCode::NoFileNameError);
    return;
  }
  vtkPolyData* input = vtkPolyData::SafeDownCast(this->GetInput());
  if (!input)
  {
    vtkErrorMacro(<< "'" << this->FileName << "': cannot be written: the input is no mesh");
    this->SetErrorCode(vtkErrorCode::UnknownError);
    return;
  }
  try
  {
    if (HasObjectTypes(input, this->LabelArrayName))
    {
      msynth::WriteGlbFile(
        this->FileName, TypeParts(input, this->FileName), "ModelSynth (vtkMSGLTFWriter)");
      return;
    }
    vtkNew<vtkPolyData> surface; // polygons and strips only: verts and lines have no faces
    surface->SetPoints(input->GetPoints());
    surface->SetPolys(input->GetPolys());
    surface->SetStrips(input->GetStrips());
    surface->GetCellData()->PassData(input->GetCellData());
    vtkNew<vtkPolyData> empty;
    if (input->GetNumberOfVerts() + input->GetNumberOfLines() > 0)
    {
      // Cell data of polygons and strips follows the verts and lines: keep only their tuples.
      surface->GetCellData()->Initialize();
      const vtkIdType first = input->GetNumberOfVerts() + input->GetNumberOfLines();
      surface->GetCellData()->CopyAllocate(input->GetCellData(), input->GetNumberOfPolys());
      for (vtkIdType c = 0; c < input->GetNumberOfPolys() + input->GetNumberOfStrips(); ++c)
        surface->GetCellData()->CopyData(input->GetCellData(), first + c, c);
    }
    vtkSmartPointer<vtkAlgorithm> triangles = vtkMSOnDemand::NewTriangulator();
    triangles->SetInputDataObject(
      0, input->GetPoints() ? surface.GetPointer() : empty.GetPointer());
    triangles->Update();
    vtkPolyData* mesh = vtkPolyData::SafeDownCast(triangles->GetOutputDataObject(0));
    vtkDataArray* labels = mesh->GetCellData()->GetArray(this->LabelArrayName.c_str());
    vtkDataArray* colors = mesh->GetCellData()->GetArray(this->ColorArrayName.c_str());
    if (colors && colors->GetNumberOfComponents() != 3 && colors->GetNumberOfComponents() != 4)
      colors = nullptr;
    msynth::WriteGlbFile(
      this->FileName, GroupTriangles(mesh, labels, colors), "ModelSynth (vtkMSGLTFWriter)");
  }
  catch (const std::exception& e)
  {
    vtkErrorMacro(<< e.what());
    this->SetErrorCode(vtkErrorCode::CannotOpenFileError);
  }
}
