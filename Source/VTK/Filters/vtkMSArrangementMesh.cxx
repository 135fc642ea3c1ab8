// SPDX-License-Identifier: BSD-3-Clause
#include "vtkMSArrangementMesh.h"

#include "vtkMSArrangementStorage.h"
#include "vtkMSEngineBridge.h"
#include "vtkMSFieldData.h"
#include "vtkMSLabelArrays.h"
#include "vtkMSPipeline.h"
#include "vtkMSPolyhedra.h"

#include "vtkCellArray.h"
#include "vtkCellData.h"
#include "vtkDataArray.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkIdTypeArray.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkIntArray.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkStringArray.h"

#include "Continuous/ContinuousMesh.h"
#include "Core/Error.h"

vtkStandardNewMacro(vtkMSArrangementMesh);

vtkMSArrangementMesh::vtkMSArrangementMesh()
{
  this->SetNumberOfInputPorts(2);
}

vtkMSArrangementMesh::~vtkMSArrangementMesh() = default;

void vtkMSArrangementMesh::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "CheckModel: " << this->CheckModel << "\n";
}

int vtkMSArrangementMesh::FillInputPortInformation(int, vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkPolyData");
  return 1;
}

namespace
{
/// The mesh's points (with their arrangement vertices) and polygons with their object types.
void FillMesh(vtkPolyData* output, const msynth::ContinuousMesh& mesh)
{
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  points->SetNumberOfPoints(static_cast<vtkIdType>(mesh.Points.size()));
  vtkNew<vtkIdTypeArray> vertex;
  vertex->SetName("ArrangementVertex");
  vertex->SetNumberOfValues(static_cast<vtkIdType>(mesh.Points.size()));
  for (std::size_t i = 0; i < mesh.Points.size(); ++i)
  {
    points->SetPoint(static_cast<vtkIdType>(i), mesh.Points[i].data());
    vertex->SetValue(static_cast<vtkIdType>(i), static_cast<vtkIdType>(mesh.PointVertex[i]));
  }
  vtkNew<vtkCellArray> polys;
  vtkNew<vtkIntArray> inside;
  inside->SetName(mesh.Planar ? "ObjectType" : "InsideType");
  vtkNew<vtkIntArray> outside;
  outside->SetName("OutsideType");
  std::vector<vtkIdType> ids;
  for (std::size_t f = 0; f < mesh.Polygons.size(); ++f)
  {
    ids.assign(mesh.Polygons[f].begin(), mesh.Polygons[f].end());
    polys->InsertNextCell(static_cast<vtkIdType>(ids.size()), ids.data());
    inside->InsertNextValue(mesh.InsideType[f]);
    if (!mesh.Planar)
    {
      outside->InsertNextValue(mesh.OutsideType[f]);
    }
  }
  output->SetPoints(points);
  output->SetPolys(polys);
  output->GetPointData()->AddArray(vertex);
  output->GetCellData()->AddArray(inside);
  if (!mesh.Planar)
  {
    output->GetCellData()->AddArray(outside);
  }
  output->GetCellData()->SetActiveScalars(inside->GetName());
}

/// The example's file and its object type names by type id (0: empty), e.g. for the VDB
/// writer's surface_<type>.
void AddTypeNames(vtkPolyData* output, const msynth::PolyhedralExample& ex)
{
  vtkNew<vtkStringArray> file;
  file->SetName("ExampleFile");
  file->InsertNextValue(ex.Source);
  output->GetFieldData()->AddArray(file);
  vtkNew<vtkStringArray> typeNames;
  typeNames->SetName("TypeNames");
  const int maxType = ex.TypeNames.empty() ? 0 : ex.TypeNames.rbegin()->first;
  typeNames->SetNumberOfValues(maxType + 1);
  typeNames->SetValue(0, "empty");
  for (const auto& [type, name] : ex.TypeNames)
  {
    if (type > 0)
    {
      typeNames->SetValue(type, name);
    }
  }
  vtkNew<vtkIntArray> typeIds; // paired with TypeNames, as the example reader does
  typeIds->SetName("TypeIds");
  for (int t = 0; t <= maxType; ++t)
  {
    typeIds->InsertNextValue(t);
  }
  output->GetFieldData()->AddArray(typeNames);
  output->GetFieldData()->AddArray(typeIds);
}
} // namespace

int vtkMSArrangementMesh::RequestData(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  vtkPolyData* example = vtkPolyData::GetData(inputVector[0], 0);
  vtkPolyData* labelled = vtkPolyData::GetData(inputVector[1], 0);
  vtkPolyData* output = vtkPolyData::GetData(outputVector, 0);
  if (!labelled)
  {
    vtkErrorMacro(<< "no labelled arrangement input (port 1): connect the ModelSynth Continuous "
                     "Synthesis filter");
    return 0;
  }
  if (vtkMSPipeline::UpdatePiece(outputVector->GetInformationObject(0)) > 0 &&
    labelled->GetNumberOfPoints() == 0)
  {
    return 1;
  }
  try
  {
    const std::string where = vtkMSFieldData::ExampleName(labelled);
    const auto record =
      vtkMSArrangementStorage::LoadArrangement(labelled->GetFieldData(), where + " (arrangement)");
    // The finished model (ModelLabel when the solver shows catalog time steps, else Label).
    vtkDataArray* labelArray = labelled->GetPointData()->GetArray("ModelLabel");
    if (!labelArray)
    {
      labelArray = labelled->GetPointData()->GetArray("Label");
    }
    if (!labelArray || labelArray->GetNumberOfComponents() != 1 ||
      labelArray->GetNumberOfTuples() != labelled->GetNumberOfPoints() ||
      !vtkMSLabelArrays::IsIntegerArray(labelArray))
    {
      throw msynth::Error(where +
        ": the arrangement input has no integer point array 'Label' with one "
        "value per vertex; connect the ModelSynth Continuous Synthesis filter");
    }
    msynth::PolyhedralExample ex;
    const auto analysis = vtkMSPolyhedra::AnalyzeExample(
      example, record.AngleToleranceDegrees, record.MaximumSmallInteger, ex);
    if (analysis.Families().AllNormals() != record.Normals)
    {
      throw msynth::Error(ex.Source + ": the arrangement was built from another example");
    }
    const msynth::PlaneArrangement arrangement(analysis.Families(), record.Parameters);
    if (arrangement.NumberOfVertices() != labelled->GetNumberOfPoints())
    {
      throw msynth::Error(ex.Source + ": the labelled arrangement does not match its parameters");
    }
    std::vector<std::int32_t> labels(static_cast<std::size_t>(labelled->GetNumberOfPoints()));
    for (vtkIdType v = 0; v < labelled->GetNumberOfPoints(); ++v)
    {
      labels[static_cast<std::size_t>(v)] = static_cast<std::int32_t>(labelArray->GetTuple1(v));
    }
    const msynth::ContinuousMesh mesh = msynth::ExtractMesh(analysis, arrangement, labels);

    FillMesh(output, mesh);
    AddTypeNames(output, ex);
    // The direction snapping the example was analyzed with, so a check of the model (msynth
    // check) analyzes it the same way.
    vtkMSFieldData::AddFieldValue<vtkDoubleArray>(
      output->GetFieldData(), "AngleTolerance", record.AngleToleranceDegrees);
    vtkMSFieldData::AddFieldValue<vtkIntArray>(
      output->GetFieldData(), "MaximumSmallInteger", record.MaximumSmallInteger);
    if (this->CheckModel)
    {
      const auto report = msynth::CheckContinuousModel(analysis, mesh, ex.TypeNames);
      vtkNew<vtkStringArray> check;
      check->SetName("ModelCheck");
      check->InsertNextValue(report.Valid ? "valid" : report.Problem);
      output->GetFieldData()->AddArray(check);
      if (!report.Valid)
      {
        throw msynth::Error(
          ex.Source + ": the synthesized model fails the check: " + report.Problem);
      }
    }
  }
  catch (const msynth::Error& e)
  {
    vtkErrorMacro(<< e.what());
    return 0;
  }
  return 1;
}
