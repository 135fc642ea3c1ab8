// SPDX-License-Identifier: BSD-3-Clause
#include "vtkMSNeighbourhoodLabels.h"

#include "vtkMSEngineBridge.h"
#include "vtkMSFieldData.h"
#include "vtkMSPipeline.h"
#include "vtkMSPolyhedra.h"

#include "vtkCellArray.h"
#include "vtkCellData.h"
#include "vtkDataObject.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkIdTypeArray.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkIntArray.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkStreamingDemandDrivenPipeline.h"
#include "vtkStringArray.h"
#include "vtkTable.h"
#include "vtkTypeInt64Array.h"

#include "Continuous/PolyhedralAnalysis.h"

#include <cmath>

vtkStandardNewMacro(vtkMSNeighbourhoodLabels);

vtkMSNeighbourhoodLabels::vtkMSNeighbourhoodLabels()
{
  this->SetNumberOfInputPorts(1);
  this->SetNumberOfOutputPorts(2);
}

vtkMSNeighbourhoodLabels::~vtkMSNeighbourhoodLabels() = default;

vtkTable* vtkMSNeighbourhoodLabels::GetLabelTable()
{
  return vtkTable::SafeDownCast(this->GetOutputDataObject(0));
}

vtkPolyData* vtkMSNeighbourhoodLabels::GetMarkedExample()
{
  return vtkPolyData::SafeDownCast(this->GetOutputDataObject(1));
}

int vtkMSNeighbourhoodLabels::FillInputPortInformation(int, vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkPolyData");
  return 1;
}

int vtkMSNeighbourhoodLabels::FillOutputPortInformation(int port, vtkInformation* info)
{
  info->Set(vtkDataObject::DATA_TYPE_NAME(), port == 0 ? "vtkTable" : "vtkPolyData");
  return 1;
}

namespace
{

vtkNew<vtkIntArray> IntColumn(const char* name)
{
  vtkNew<vtkIntArray> a;
  a->SetName(name);
  return a;
}

vtkNew<vtkStringArray> StringColumn(const char* name)
{
  vtkNew<vtkStringArray> a;
  a->SetName(name);
  return a;
}

std::string FamiliesText(const std::vector<int>& families)
{
  std::string s;
  for (int f : families)
  {
    s += (s.empty() ? "h" : " h") + std::to_string(f + 1);
  }
  return s;
}

/// Output 0: the catalog of labels, with the plane families as field data.
void FillCatalog(vtkTable* table, const msynth::PolyhedralAnalysis& analysis)
{
  const bool planar = analysis.Planar();
  const auto& set = analysis.Families();
  auto id = IntColumn("Id");
  auto kind = StringColumn("Kind");
  auto codimension = IntColumn("Codimension");
  auto families = StringColumn("Families");
  auto halfSpaces = IntColumn("HalfSpaces");
  auto expression = StringColumn("Expression");
  vtkNew<vtkIdTypeArray> occurrences;
  occurrences->SetName("Occurrences");
  auto typesPresent = StringColumn("ObjectTypes");
  for (int l = 0; l < analysis.NumberOfLabels(); ++l)
  {
    const auto& info = analysis.Label(l);
    id->InsertNextValue(l);
    kind->InsertNextValue(msynth::FeatureKindName(info.Kind, planar));
    codimension->InsertNextValue(static_cast<int>(info.Kind));
    families->InsertNextValue(FamiliesText(info.Label.Families));
    halfSpaces->InsertNextValue(static_cast<int>(info.Label.Families.size()));
    expression->InsertNextValue(info.Expression);
    occurrences->InsertNextValue(static_cast<vtkIdType>(info.Occurrences));
    std::string types;
    for (int t : info.Label.TypesPresent())
    {
      types += (types.empty() ? "" : " ") + std::to_string(t);
    }
    typesPresent->InsertNextValue(types);
  }
  table->Initialize();
  for (vtkAbstractArray* column : std::initializer_list<vtkAbstractArray*>{
         id, kind, codimension, families, halfSpaces, expression, occurrences, typesPresent })
  {
    table->AddColumn(column);
  }
  vtkNew<vtkTypeInt64Array> normals;
  normals->SetName("FamilyNormals");
  normals->SetNumberOfComponents(3);
  vtkNew<vtkDoubleArray> units;
  units->SetName("FamilyUnitNormals");
  units->SetNumberOfComponents(3);
  for (int f = 0; f < set.Size(); ++f)
  {
    const auto& n = set.Normal(f);
    const long long tuple[3] = { n[0], n[1], n[2] };
    normals->InsertNextTypedTuple(tuple);
    units->InsertNextTypedTuple(analysis.FamilyUnitNormals()[f].data());
  }
  table->GetFieldData()->AddArray(normals);
  table->GetFieldData()->AddArray(units);
  vtkNew<vtkIntArray> planarFlag;
  planarFlag->SetName("Planar");
  planarFlag->InsertNextValue(planar ? 1 : 0);
  table->GetFieldData()->AddArray(planarFlag);
}

/// Output 1: the example marked with label ids (features as vertices and lines, faces).
void FillMarkedExample(vtkPolyData* marked, const msynth::PolyhedralExample& example,
  const msynth::PolyhedralAnalysis& analysis)
{
  const bool planar = analysis.Planar();
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  for (const auto& p : example.Points)
  {
    points->InsertNextPoint(p.data());
  }
  vtkNew<vtkCellArray> verts, lines, polys;
  // Cell values per kind; vtkPolyData orders its cells verts, lines, polys.
  struct Values
  {
    std::vector<int> Label, Codimension, ObjectType;
    void Add(int label, int codimension, int objectType)
    {
      this->Label.push_back(label);
      this->Codimension.push_back(codimension);
      this->ObjectType.push_back(objectType);
    }
  };
  Values vertValues, lineValues, polyValues;
  for (const auto& feature : analysis.Features())
  {
    if (feature.Element >= 0 && !planar)
    {
      continue; // face samples: summarized per face below
    }
    const vtkIdType a = points->InsertNextPoint(feature.A.data());
    if (feature.A == feature.B)
    {
      verts->InsertNextCell(1, &a);
      vertValues.Add(feature.Label, static_cast<int>(feature.Kind), -1);
    }
    else
    {
      const vtkIdType ids[2] = { a, points->InsertNextPoint(feature.B.data()) };
      lines->InsertNextCell(2, ids);
      lineValues.Add(feature.Label, static_cast<int>(feature.Kind), -1);
    }
  }
  for (std::size_t f = 0; f < example.Faces.size(); ++f)
  {
    polys->InsertNextCell(static_cast<vtkIdType>(example.Faces[f].size()));
    for (int v : example.Faces[f])
    {
      polys->InsertCellPoint(v);
    }
    const int type = example.ObjectTypes[example.FaceObject[f]];
    if (planar)
    {
      polyValues.Add(analysis.Find(msynth::NeighbourhoodLabel::Constant(type)), 0, type);
    }
    else
    {
      polyValues.Add(analysis.ElementLabel()[f], 1, type);
    }
  }
  marked->Initialize();
  marked->SetPoints(points);
  marked->SetVerts(verts);
  marked->SetLines(lines);
  marked->SetPolys(polys);
  auto column = [&](const char* arrayName, std::vector<int> Values::*member)
  {
    auto array = IntColumn(arrayName);
    for (const Values* part : { &vertValues, &lineValues, &polyValues })
    {
      for (int v : part->*member)
      {
        array->InsertNextValue(v);
      }
    }
    return array;
  };
  auto label = column("LabelId", &Values::Label);
  auto codim = column("Codimension", &Values::Codimension);
  auto type = column("ObjectType", &Values::ObjectType);
  marked->GetCellData()->AddArray(label);
  marked->GetCellData()->AddArray(codim);
  marked->GetCellData()->AddArray(type);
  marked->GetCellData()->SetActiveScalars("LabelId");
}

} // namespace

int vtkMSNeighbourhoodLabels::RequestData(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  vtkPolyData* input = vtkPolyData::GetData(inputVector[0], 0);
  vtkTable* table = vtkTable::GetData(outputVector, 0);
  vtkPolyData* marked = vtkPolyData::GetData(outputVector, 1);
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  if (vtkMSPipeline::UpdatePiece(outInfo) > 0 && (!input || input->GetNumberOfPolys() == 0))
  {
    return 1; // in parallel, the example lives on piece 0 and is analyzed there only
  }
  const std::string name = vtkMSFieldData::ExampleName(input);
  try
  {
    msynth::PolyhedralExample example = vtkMSPolyhedra::ToPolyhedralExample(input, name);
    msynth::ValidateExample(example);
    msynth::PolyhedralAnalysis::Options options;
    options.AngleTolerance = this->AngleTolerance * M_PI / 180.0;
    options.MaxSmallInteger = this->MaximumSmallInteger;
    const auto analysis = msynth::PolyhedralAnalysis::Analyze(example, options);

    FillCatalog(table, analysis);
    FillMarkedExample(marked, example, analysis);
    if (input)
    {
      marked->GetFieldData()->PassData(input->GetFieldData());
      if (auto* file = input->GetFieldData()->GetAbstractArray("ExampleFile"))
      {
        table->GetFieldData()->AddArray(file);
      }
    }
  }
  catch (const std::exception& e)
  {
    table->Initialize();
    marked->Initialize();
    vtkErrorMacro(<< e.what());
    return 0;
  }
  return 1;
}

void vtkMSNeighbourhoodLabels::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "AngleTolerance: " << this->AngleTolerance << "\n";
  os << indent << "MaximumSmallInteger: " << this->MaximumSmallInteger << "\n";
}
