// SPDX-License-Identifier: BSD-3-Clause
#include "vtkMSArrangementMesh.h"

#include "vtkMSArrangementStorage.h"
#include "vtkMSCheckKinds.h"
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

#include "Continuous/ContinuousConstraints.h"
#include "Continuous/ContinuousMesh.h"
#include "Continuous/DetailSubstitution.h"
#include "Continuous/FeatureWidth.h"
#include "Core/Error.h"
#include "Core/Index.h"

vtkStandardNewMacro(vtkMSArrangementMesh);

vtkMSArrangementMesh::vtkMSArrangementMesh()
{
  this->SetNumberOfInputPorts(3);
}

vtkMSArrangementMesh::~vtkMSArrangementMesh() = default;

void vtkMSArrangementMesh::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "CheckModel: " << this->CheckModel << "\n";
}

int vtkMSArrangementMesh::FillInputPortInformation(int port, vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkPolyData");
  if (port == 2)
    info->Set(vtkAlgorithm::INPUT_IS_OPTIONAL(), 1);
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

namespace
{
/// The detail mesh (port 2) substituted for every part of object type @p typeText.
msynth::DetailResult Substitute(const msynth::ContinuousMesh& mesh,
  const msynth::PolyhedralExample& ex, vtkPolyData* detail, const std::string& typeText)
{
  if (typeText.empty())
    throw msynth::Error("a detail mesh is connected but DetailType names no object type");
  // TYPE or TYPE+TYPE...: the pieces of one bounding volume.
  std::vector<int> types;
  for (std::size_t at = 0; at <= typeText.size();)
  {
    const std::size_t plus = std::min(typeText.find('+', at), typeText.size());
    types.push_back(msynth::ParseObjectType(typeText.substr(at, plus - at), ex.TypeNames));
    at = plus + 1;
  }
  // The bounding volume: the example's objects of those types, their bounding box.
  msynth::Point3 low{}, high{};
  bool any = false;
  for (std::size_t f = 0; f < ex.Faces.size(); ++f)
  {
    const int type = ex.ObjectTypes[msynth::ToIndex(ex.FaceObject[f])];
    if (std::find(types.begin(), types.end(), type) == types.end())
      continue;
    for (int i : ex.Faces[f])
      for (std::size_t c = 0; c < 3; ++c)
      {
        const double x = ex.Points[msynth::ToIndex(i)][c];
        low[c] = any ? std::min(low[c], x) : x;
        high[c] = any ? std::max(high[c], x) : x;
      }
    any = true;
  }
  if (!any)
    throw msynth::Error(ex.Source + ": no object of type " + typeText + " to substitute");
  const auto detailModel = vtkMSPolyhedra::ToPolyhedralExample(detail, "detail mesh");
  return msynth::SubstituteDetail(mesh, types, detailModel, low, high);
}

/// Field data: `DetailScales` (x, y, z scale per substituted part) and `DetailAnisotropy` (the
/// largest relative difference of a part's scales).
void AddPlacements(vtkPolyData* output, const std::vector<msynth::DetailPlacement>& placements)
{
  vtkNew<vtkDoubleArray> scales;
  scales->SetName("DetailScales");
  scales->SetNumberOfComponents(3);
  double worst = 0;
  for (const auto& p : placements)
  {
    scales->InsertNextTuple(p.Scale.data());
    worst = std::max(worst, p.Anisotropy);
  }
  output->GetFieldData()->AddArray(scales);
  vtkMSFieldData::AddFieldValue<vtkDoubleArray>(output->GetFieldData(), "DetailAnisotropy", worst);
}

/// The finished model's labels of @p labelled (ModelLabel when the solver shows catalog time
/// steps, else Label). @throw msynth::Error naming @p where when there is no such integer
/// array with one value per vertex.
vtkDataArray* ModelLabelArray(vtkPolyData* labelled, const std::string& where)
{
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
  return labelArray;
}

/**
 * What the synthesized model (before any substitution) measures, as field data: the smallest
 * plane spacing (a check holds features to a fraction of it) and its narrowest feature, on its
 * polygons (FeatureWidth.h), and the structure a person sees (parts, their sizes, what they
 * front) against the example's (ModelStructure.h).
 */
void AddMeasures(vtkFieldData* out, const msynth::PolyhedralExample& ex,
  const msynth::ContinuousMesh& model, double spacing)
{
  const msynth::FeatureWidth width = msynth::SmallestFeature(model, spacing);
  vtkMSFieldData::AddFieldValue<vtkDoubleArray>(out, "SmallestSpacing", spacing);
  vtkMSFieldData::AddFieldValue<vtkDoubleArray>(out, "SmallestFeature", width.Width);
  vtkMSFieldData::AddFieldValue<vtkDoubleArray>(
    out, "SmallestFeatureFraction", spacing > 0 ? width.Width / spacing : 0.0);
  vtkMSCheckKinds::AddResemblance(out, ex, msynth::MeshToModel(model, ex.TypeNames), spacing);
}

/// Each type's share of the solid volume (area in 2D) of @p mesh as it is: VolumeShare_TYPE.
void AddVolumeShares(vtkPolyData* output, const msynth::ContinuousMesh& mesh)
{
  const auto volumes = msynth::TypeVolumes(mesh);
  double solid = 0;
  for (const auto& [type, volume] : volumes)
    solid += volume;
  for (const auto& [type, volume] : volumes)
    vtkMSFieldData::AddFieldValue<vtkDoubleArray>(output->GetFieldData(),
      ("VolumeShare_" + std::to_string(type)).c_str(), solid > 0 ? volume / solid : 0.0);
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
    vtkDataArray* labelArray = ModelLabelArray(labelled, where);
    msynth::PolyhedralExample ex;
    const auto analysis = vtkMSPolyhedra::AnalyzeExample(
      example, record.AngleToleranceDegrees, record.MaximumSmallInteger, ex);
    if (analysis.Families().AllNormals() != record.Normals)
    {
      throw msynth::Error(ex.Source + ": the arrangement was built from another example");
    }
    const auto built =
      vtkMSArrangementStorage::SharedArrangement(analysis.Families(), record.Parameters);
    const msynth::PlaneArrangement& arrangement = *built;
    if (arrangement.NumberOfVertices() != labelled->GetNumberOfPoints())
    {
      throw msynth::Error(ex.Source + ": the labelled arrangement does not match its parameters");
    }
    std::vector<std::int32_t> labels(msynth::ToIndex(labelled->GetNumberOfPoints()));
    for (vtkIdType v = 0; v < labelled->GetNumberOfPoints(); ++v)
    {
      labels[msynth::ToIndex(v)] = static_cast<std::int32_t>(labelArray->GetTuple1(v));
    }
    msynth::ContinuousMesh mesh = msynth::ExtractMesh(analysis, arrangement, labels);
    vtkPolyData* detail = vtkPolyData::GetData(inputVector[2], 0);
    msynth::ContinuousMesh synthesized;
    std::vector<msynth::DetailPlacement> placements;
    if (detail)
    {
      // Bounding volumes (TVCG 4.8): the detailed object replaces every part of its type.
      synthesized = mesh;
      auto substituted = Substitute(mesh, ex, detail, this->DetailType);
      mesh = std::move(substituted.Mesh);
      placements = std::move(substituted.Placements);
    }

    FillMesh(output, mesh);
    if (detail)
      AddPlacements(output, placements);
    AddTypeNames(output, ex);
    AddVolumeShares(output, mesh);
    // The direction snapping the example was analyzed with, so a check of the model (msynth
    // check) analyzes it the same way.
    vtkMSFieldData::AddFieldValue<vtkDoubleArray>(
      output->GetFieldData(), "AngleTolerance", record.AngleToleranceDegrees);
    vtkMSFieldData::AddFieldValue<vtkIntArray>(
      output->GetFieldData(), "MaximumSmallInteger", record.MaximumSmallInteger);
    const double spacing = vtkMSArrangementStorage::SmallestSpacing(labelled->GetFieldData());
    AddMeasures(output->GetFieldData(), ex, detail ? synthesized : mesh, spacing);
    if (this->CheckModel)
    {
      // The synthesized model (before any substitution) against the example.
      const auto report =
        msynth::CheckContinuousModel(analysis, detail ? synthesized : mesh, ex.TypeNames, spacing);
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
