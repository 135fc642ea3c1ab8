// SPDX-License-Identifier: BSD-3-Clause
#include "vtkMSPlaneArrangement.h"

#include "vtkMSArrangementStorage.h"
#include "vtkMSEngineBridge.h"
#include "vtkMSFieldData.h"
#include "vtkMSPipeline.h"
#include "vtkMSPolyhedra.h"

#include "vtkCellArray.h"
#include "vtkCellData.h"
#include "vtkFieldData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkIntArray.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkStringArray.h"
#include "vtkTypeInt64Array.h"

#include "Continuous/ContinuousSynthesis.h"
#include "Core/Error.h"

#include <algorithm>

vtkStandardNewMacro(vtkMSPlaneArrangement);

vtkMSPlaneArrangement::vtkMSPlaneArrangement() = default;
vtkMSPlaneArrangement::~vtkMSPlaneArrangement() = default;

void vtkMSPlaneArrangement::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "OutputSize: " << this->OutputSize[0] << " " << this->OutputSize[1] << " "
     << this->OutputSize[2] << "\n";
  os << indent << "Spacing: " << this->Spacing << "\n";
  os << indent << "AngleTolerance: " << this->AngleTolerance << "\n";
  os << indent << "MaximumSmallInteger: " << this->MaximumSmallInteger << "\n";
  os << indent << "MaximumVertices: " << this->MaximumVertices << "\n";
}

namespace
{
/// The arrangement as poly data: its vertices (families through each, catalog size) and its
/// inner edges with their direction classes.
void FillArrangement(vtkPolyData* output, const msynth::PlaneArrangement& arrangement,
  const msynth::ArrangementRules& rules)
{
  const vtkIdType n = arrangement.NumberOfVertices();
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  points->SetNumberOfPoints(n);
  vtkNew<vtkTypeInt64Array> families;
  families->SetName("Families");
  families->SetNumberOfValues(n);
  vtkNew<vtkIntArray> count;
  count->SetName("NumberOfFamilies");
  count->SetNumberOfValues(n);
  vtkNew<vtkIntArray> catalog;
  catalog->SetName("CatalogSize");
  catalog->SetNumberOfValues(n);
  vtkNew<vtkCellArray> verts;
  vtkNew<vtkCellArray> lines;
  vtkNew<vtkIntArray> direction;
  direction->SetName("Direction");
  for (vtkIdType v = 0; v < n; ++v)
  {
    points->SetPoint(v, arrangement.Position(v).data());
    families->SetValue(v, static_cast<vtkTypeInt64>(arrangement.FamilyMask(v)));
    count->SetValue(v, __builtin_popcountll(arrangement.FamilyMask(v)));
    catalog->SetValue(v, rules.InitialCount(v));
    verts->InsertNextCell(1, &v);
    direction->InsertNextValue(-1);
  }
  for (vtkIdType v = 0; v < n; ++v)
  {
    for (const auto* l = arrangement.LinksBegin(v); l != arrangement.LinksEnd(v); ++l)
    {
      if (l->Vertex > v)
      {
        const vtkIdType ends[2] = { v, l->Vertex };
        lines->InsertNextCell(2, ends);
        direction->InsertNextValue(l->Direction);
      }
    }
  }
  output->SetPoints(points);
  output->SetVerts(verts);
  output->SetLines(lines);
  output->GetPointData()->AddArray(families);
  output->GetPointData()->AddArray(count);
  output->GetPointData()->AddArray(catalog);
  output->GetPointData()->SetActiveScalars("CatalogSize");
  output->GetCellData()->AddArray(direction);
}
} // namespace

int vtkMSPlaneArrangement::RequestData(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  vtkPolyData* input = vtkPolyData::GetData(inputVector[0], 0);
  vtkPolyData* output = vtkPolyData::GetData(outputVector, 0);
  if (vtkMSPipeline::UpdatePiece(outputVector->GetInformationObject(0)) > 0)
  {
    return 1; // the arrangement is built once, on piece 0
  }
  try
  {
    msynth::PolyhedralExample example;
    const auto analysis = vtkMSPolyhedra::AnalyzeExample(
      input, this->AngleTolerance, this->MaximumSmallInteger, example);
    msynth::Point3 size{};
    double bounds[6];
    input->GetBounds(bounds);
    for (int c = 0; c < 3; ++c)
    {
      size[static_cast<std::size_t>(c)] =
        this->OutputSize[c] > 0 ? this->OutputSize[c] : 4 * (bounds[2 * c + 1] - bounds[2 * c]);
    }
    vtkMSArrangementStorage::ArrangementRecord record;
    record.Parameters =
      msynth::DefaultArrangementParameters(example, analysis, size, this->Spacing, {});
    record.Parameters.MaxVertices = this->MaximumVertices;
    record.Normals = analysis.Families().AllNormals();
    record.AngleToleranceDegrees = this->AngleTolerance;
    record.MaximumSmallInteger = this->MaximumSmallInteger;
    const msynth::PlaneArrangement arrangement(analysis.Families(), record.Parameters);
    const msynth::ArrangementRules rules(analysis, arrangement);

    FillArrangement(output, arrangement, rules);
    vtkMSArrangementStorage::StoreArrangement(record, output->GetFieldData());
    vtkNew<vtkStringArray> file;
    file->SetName("ExampleFile");
    file->InsertNextValue(vtkMSFieldData::ExampleName(input));
    output->GetFieldData()->AddArray(file);
  }
  catch (const msynth::Error& e)
  {
    vtkErrorMacro(<< e.what());
    return 0;
  }
  return 1;
}
