// SPDX-License-Identifier: BSD-3-Clause
#include "vtkMSPolyhedra.h"

#include "vtkMSEngineBridge.h"
#include "vtkMSFieldData.h"
#include "vtkMSLabelArrays.h"

#include "vtkAlgorithm.h"
#include "vtkCellArray.h"
#include "vtkCellArrayIterator.h"
#include "vtkCellData.h"
#include "vtkCommand.h"
#include "vtkDataArray.h"
#include "vtkDoubleArray.h"
#include "vtkExecutive.h"
#include "vtkFieldData.h"
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
#include "vtkTypeInt64Array.h"

#include "Core/Error.h"
#include "Core/Index.h"

#include <cmath>
#include <cstdint>
#include <limits>
#include <map>
#include <vector>

msynth::PolyhedralExample vtkMSPolyhedra::ToPolyhedralExample(
  vtkPolyData* polygons, const std::string& name)
{
  msynth::PolyhedralExample example;
  example.Source = name;
  if (!polygons || !polygons->GetPolys() || polygons->GetNumberOfPolys() == 0)
  {
    throw msynth::Error::InFile(name, "has no polygons");
  }
  // Readable type names, as the example reader stores them (TypeIds[i] is named TypeNames[i]).
  auto* typeIds = vtkDataArray::SafeDownCast(polygons->GetFieldData()->GetAbstractArray("TypeIds"));
  auto* typeNames =
    vtkStringArray::SafeDownCast(polygons->GetFieldData()->GetAbstractArray("TypeNames"));
  if (typeIds && typeNames && typeIds->GetNumberOfValues() == typeNames->GetNumberOfValues())
  {
    for (vtkIdType i = 0; i < typeIds->GetNumberOfValues(); ++i)
    {
      example.TypeNames[static_cast<int>(typeIds->GetTuple1(i))] = typeNames->GetValue(i);
    }
  }
  const vtkIdType numberOfPoints = polygons->GetNumberOfPoints();
  example.Points.resize(msynth::ToIndex(numberOfPoints));
  for (vtkIdType i = 0; i < numberOfPoints; ++i)
  {
    double p[3];
    polygons->GetPoint(i, p);
    example.Points[i] = { p[0], p[1], p[2] };
  }
  // Polygons come after vertices and lines in cell order; only polygons are faces.
  const vtkIdType firstPoly = polygons->GetNumberOfVerts() + polygons->GetNumberOfLines();
  vtkDataArray* types = polygons->GetCellData()->GetArray("ObjectType");
  vtkDataArray* ids = polygons->GetCellData()->GetArray("ObjectId");
  std::vector<int> faceTypes;
  std::vector<int> faceIds;
  vtkNew<vtkIdList> cell;
  auto iterator = vtk::TakeSmartPointer(polygons->GetPolys()->NewIterator());
  vtkIdType index = firstPoly;
  for (iterator->GoToFirstCell(); !iterator->IsDoneWithTraversal();
       iterator->GoToNextCell(), ++index)
  {
    iterator->GetCurrentCell(cell);
    std::vector<int> face;
    for (vtkIdType k = 0; k < cell->GetNumberOfIds(); ++k)
    {
      face.push_back(static_cast<int>(cell->GetId(k)));
    }
    example.Faces.push_back(std::move(face));
    const double type = types ? types->GetComponent(index, 0) : 1.0;
    if (!(type >= 1 && type <= 32767) || type != static_cast<int>(type))
    {
      throw msynth::Error::InFile(name,
        "polygon " + std::to_string(index - firstPoly) + " has ObjectType " + std::to_string(type) +
          "; types are integers 1..32767");
    }
    faceTypes.push_back(static_cast<int>(type));
    if (ids)
    {
      const double id = ids->GetComponent(index, 0);
      if (!(id >= 0 && id < 1e9) || id != static_cast<int>(id))
      {
        throw msynth::Error::InFile(
          name, "polygon " + std::to_string(index - firstPoly) + " has an invalid ObjectId");
      }
      faceIds.push_back(static_cast<int>(id));
    }
  }
  if (!ids)
  {
    msynth::AssignObjectsByConnectivity(example, faceTypes);
    return example;
  }
  // Renumber the given object ids densely, in order of appearance; the names the example
  // reader gives them (ObjectNames by id), else their ids.
  auto* names =
    vtkStringArray::SafeDownCast(polygons->GetFieldData()->GetAbstractArray("ObjectNames"));
  auto nameOf = [names](int id) -> std::string
  {
    if (names && id < names->GetNumberOfValues() && !names->GetValue(id).empty())
    {
      return names->GetValue(id);
    }
    return "object " + std::to_string(id);
  };
  std::map<int, int> dense;
  for (std::size_t f = 0; f < faceIds.size(); ++f)
  {
    auto it = dense.find(faceIds[f]);
    if (it == dense.end())
    {
      it = dense.emplace(faceIds[f], example.NumberOfObjects()).first;
      example.ObjectTypes.push_back(faceTypes[f]);
      example.ObjectNames.push_back(nameOf(faceIds[f]));
    }
    else if (example.ObjectTypes[it->second] != faceTypes[f])
    {
      throw msynth::Error::InFile(
        name, "object '" + nameOf(faceIds[f]) + "' has polygons of different ObjectType");
    }
    example.FaceObject.push_back(it->second);
  }
  return example;
}

void vtkMSPolyhedra::FromPolyhedralExample(
  const msynth::PolyhedralExample& example, vtkPolyData* output)
{
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  points->SetNumberOfPoints(static_cast<vtkIdType>(example.Points.size()));
  for (std::size_t i = 0; i < example.Points.size(); ++i)
  {
    points->SetPoint(static_cast<vtkIdType>(i), example.Points[i].data());
  }
  vtkNew<vtkCellArray> polys;
  vtkNew<vtkIntArray> types;
  types->SetName("ObjectType");
  vtkNew<vtkIntArray> ids;
  ids->SetName("ObjectId");
  for (std::size_t f = 0; f < example.Faces.size(); ++f)
  {
    polys->InsertNextCell(static_cast<vtkIdType>(example.Faces[f].size()));
    for (int v : example.Faces[f])
    {
      polys->InsertCellPoint(v);
    }
    types->InsertNextValue(example.ObjectTypes[example.FaceObject[f]]);
    ids->InsertNextValue(example.FaceObject[f]);
  }
  output->Initialize();
  output->SetPoints(points);
  output->SetPolys(polys);
  output->GetCellData()->AddArray(types);
  output->GetCellData()->AddArray(ids);
}

msynth::PolyhedralAnalysis vtkMSPolyhedra::AnalyzeExample(vtkPolyData* polygons,
  double angleToleranceDegrees, int maximumSmallInteger, msynth::PolyhedralExample& example)
{
  example = vtkMSPolyhedra::ToPolyhedralExample(polygons, vtkMSFieldData::ExampleName(polygons));
  msynth::ValidateExample(example);
  msynth::PolyhedralAnalysis::Options options;
  options.AngleTolerance = angleToleranceDegrees * 3.14159265358979323846 / 180.0;
  options.MaxSmallInteger = maximumSmallInteger;
  return msynth::PolyhedralAnalysis::Analyze(example, options);
}

msynth::ContinuousMesh vtkMSPolyhedra::ToContinuousMesh(vtkPolyData* model, const std::string& name)
{
  vtkDataArray* object = model->GetCellData()->GetArray("ObjectType");
  vtkDataArray* inside = object ? object : model->GetCellData()->GetArray("InsideType");
  vtkDataArray* outside = model->GetCellData()->GetArray("OutsideType");
  if (!inside || (!object && !outside))
  {
    throw msynth::Error::InFile(name,
      "not a continuous model: it needs cell arrays InsideType "
      "and OutsideType (3D) or ObjectType (2D)");
  }
  std::vector<msynth::Point3> points(msynth::ToIndex(model->GetNumberOfPoints()));
  for (vtkIdType i = 0; i < model->GetNumberOfPoints(); ++i)
  {
    model->GetPoint(i, points[msynth::ToIndex(i)].data());
  }
  std::vector<std::vector<std::int32_t>> polygons;
  std::vector<std::int32_t> in, out;
  auto it = vtk::TakeSmartPointer(model->GetPolys()->NewIterator());
  vtkIdType cell = model->GetNumberOfVerts() + model->GetNumberOfLines();
  for (it->GoToFirstCell(); !it->IsDoneWithTraversal(); it->GoToNextCell(), ++cell)
  {
    vtkIdType n;
    const vtkIdType* ids;
    it->GetCurrentCell(n, ids);
    polygons.emplace_back(ids, ids + n);
    in.push_back(static_cast<std::int32_t>(inside->GetTuple1(cell)));
    if (!object)
    {
      out.push_back(static_cast<std::int32_t>(outside->GetTuple1(cell)));
    }
  }
  try
  {
    return msynth::MeshFromPolygons(
      object != nullptr, std::move(points), std::move(polygons), std::move(in), std::move(out));
  }
  catch (const msynth::Error& e)
  {
    throw msynth::Error::InFile(name, e.what());
  }
}
