// SPDX-License-Identifier: BSD-3-Clause
#include "vtkMSPlaneArrangement.h"

#include "vtkMSArrangementStorage.h"
#include "vtkMSEngineBridge.h"
#include "vtkMSFieldData.h"
#include "vtkMSPipeline.h"
#include "vtkMSPolyhedra.h"

#include "vtkCellArray.h"
#include "vtkCellData.h"
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
#include "vtkTypeInt64Array.h"

#include "Continuous/ContinuousSynthesis.h"
#include "Core/Error.h"
#include "Core/Index.h"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <sstream>
#include <string>

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

vtkMSPlaneArrangement::Corners vtkMSPlaneArrangement::Build(
  vtkPolyData* input, vtkPolyData* output, double angleTolerance, int maximumSmallInteger)
{
  this->Warnings.clear();
  msynth::PolyhedralExample example;
  const auto analysis =
    vtkMSPolyhedra::AnalyzeExample(input, angleTolerance, maximumSmallInteger, example);
  msynth::Point3 size{};
  double bounds[6];
  input->GetBounds(bounds);
  for (int c = 0; c < 3; ++c)
  {
    size[msynth::ToIndex(c)] =
      this->OutputSize[c] > 0 ? this->OutputSize[c] : 4 * (bounds[2 * c + 1] - bounds[2 * c]);
  }
  vtkMSArrangementStorage::ArrangementRecord record;
  record.Parameters =
    msynth::DefaultArrangementParameters(example, analysis, size, this->Spacing, {});
  record.Parameters.MaxVertices = this->MaximumVertices;
  record.Normals = analysis.Families().AllNormals();
  record.AngleToleranceDegrees = angleTolerance;
  record.MaximumSmallInteger = maximumSmallInteger;
  const auto built =
    vtkMSArrangementStorage::SharedArrangement(analysis.Families(), record.Parameters);
  const msynth::PlaneArrangement& arrangement = *built;
  const msynth::ArrangementRules rules(analysis, arrangement);

  output->Initialize();
  FillArrangement(output, arrangement, rules);
  vtkMSArrangementStorage::StoreArrangement(record, output->GetFieldData());
  vtkNew<vtkStringArray> file;
  file->SetName("ExampleFile");
  file->InsertNextValue(vtkMSFieldData::ExampleName(input));
  output->GetFieldData()->AddArray(file);
  // How far the exact plane directions are from the example's faces (each face's own normal
  // against its family's direction), and whether the directions are small integers.
  double worst = 0;
  bool offLattice = false;
  const auto& set = analysis.Families();
  for (std::size_t e = 0; e < analysis.Boundary().size(); ++e)
  {
    const auto& n = set.Normal(analysis.ElementFamily()[e]);
    const auto& u = analysis.Boundary()[e].Normal;
    const double len = std::sqrt(
      double(n[0]) * double(n[0]) + double(n[1]) * double(n[1]) + double(n[2]) * double(n[2]));
    const double dot = std::abs(n[0] * u[0] + n[1] * u[1] + n[2] * u[2]) / len;
    worst = std::max(worst, std::acos(std::min(1.0, dot)) * 180 / 3.14159265358979323846);
  }
  for (int f = 0; f < set.Size(); ++f)
    for (auto c : set.Normal(f))
      offLattice = offLattice || std::abs(static_cast<double>(c)) > this->MaximumSmallInteger;
  vtkMSFieldData::AddFieldValue<vtkDoubleArray>(
    output->GetFieldData(), "DirectionChangeDegrees", worst);
  // Non-trihedral vertices (four or more planes, TVCG §4.4): where they can go.
  const auto nonTrihedral = msynth::FindNonTrihedralSites(analysis, arrangement);
  vtkIdType without = 0;
  std::string missing;
  for (const auto& n : nonTrihedral)
  {
    if (n.Sites == 0)
    {
      ++without;
      missing += (missing.empty() ? "" : "; ") + analysis.Label(n.Label).Expression + " (" +
        std::to_string(n.Planes) + " planes)";
    }
  }
  vtkMSFieldData::AddFieldValue<vtkIdTypeArray>(
    output->GetFieldData(), "NonTrihedralLabels", static_cast<vtkIdType>(nonTrihedral.size()));
  vtkMSFieldData::AddFieldValue<vtkIdTypeArray>(
    output->GetFieldData(), "NonTrihedralLabelsWithoutSites", without);
  Corners corners;
  corners.NonTrihedral = !nonTrihedral.empty();
  corners.OnLattice = !offLattice && without == 0;
  const std::string name = vtkMSFieldData::ExampleName(input);
  std::ostringstream text;
  if (without > 0)
  {
    text << name << ": over-constrained plane spacing: " << without << " of " << nonTrihedral.size()
         << " vertices where four or more planes meet have no place in the arrangement, so the "
            "output cannot have them: "
         << missing
         << ". Their planes meet only where the example has them; try another plane spacing (a "
            "divisor of the derived one) or an example whose faces fit a lattice.";
    this->Warnings.push_back(text.str());
    text.str("");
  }
  if (maximumSmallInteger != this->MaximumSmallInteger)
    text << name << ": plane directions snapped to integers up to " << maximumSmallInteger
         << " so that exact coordinates fit; faces turn by up to " << worst << " degrees";
  else if (angleTolerance > this->AngleTolerance)
    text << name
         << ": four or more planes meet at a corner of the example, so plane directions were "
            "snapped to small integers (TVCG 4.4: normals modified to fit a lattice); faces turn "
            "by up to "
         << worst << " degrees";
  if (!text.str().empty())
    this->Warnings.push_back(text.str());
  return corners;
}

void vtkMSPlaneArrangement::Warn()
{
  for (const auto& w : this->Warnings)
    vtkWarningMacro(<< w);
}

bool vtkMSPlaneArrangement::BuildOnLattice(vtkPolyData* input, vtkPolyData* output)
{
  // Four or more planes meeting at a corner need directions on a small-integer lattice (with
  // large integers the planes only nearly meet, and the arrangement fills with slivers). When
  // the directions as given are not, they are snapped to small integers within growing
  // tolerances (the paper's second way out of Eq. 4.25), and the change is reported.
  std::string overflow;
  try
  {
    const Corners as = this->Build(input, output, this->AngleTolerance, this->MaximumSmallInteger);
    if (!as.NonTrihedral || as.OnLattice)
      return true; // as given
  }
  catch (const msynth::Error& e)
  {
    if (std::string(e.what()).find("128-bit") == std::string::npos)
      throw;
    overflow = e.what(); // directions of large integers overflowed: try the lattice first
  }
  for (double degrees : { 0.5, 1.0, 2.0, 3.0 })
  {
    if (degrees <= this->AngleTolerance)
      continue;
    try
    {
      const Corners c = this->Build(input, output, degrees, this->MaximumSmallInteger);
      if (c.NonTrihedral && c.OnLattice)
        return true;
    }
    catch (const msynth::Error&)
    {
      // e.g. the coarser directions merge faces into a non-planar family: try the next
    }
  }
  if (!overflow.empty())
    throw msynth::Error(overflow); // on to the coarser snapping levels
  return false;
}

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
    // Directions as given first; when exact coordinates would exceed 128-bit integers (plane
    // directions of large integers, e.g. a rotated polygon), again with directions snapped to
    // ever smaller integers, within tolerances that grow accordingly (the change is reported).
    struct Snap
    {
      double Degrees;
      int Integer;
    };
    const Snap snaps[] = { { this->AngleTolerance, this->MaximumSmallInteger },
      { std::max(this->AngleTolerance, 0.012), 4096 },
      { std::max(this->AngleTolerance, 0.09), 512 }, { std::max(this->AngleTolerance, 0.7), 64 } };
    for (std::size_t level = 0;; ++level)
    {
      try
      {
        if (level > 0 || !this->BuildOnLattice(input, output))
          this->Build(input, output, snaps[level].Degrees, snaps[level].Integer);
        this->Warn();
        break;
      }
      catch (const msynth::Error& e)
      {
        if (level + 1 == std::size(snaps) ||
          std::string(e.what()).find("128-bit") == std::string::npos)
          throw;
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
