// SPDX-License-Identifier: BSD-3-Clause
#include "vtkMSArrangementStorage.h"

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

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <map>
#include <mutex>
#include <vector>

void vtkMSArrangementStorage::StoreArrangement(
  const ArrangementRecord& record, vtkFieldData* fields)
{
  const auto& p = record.Parameters;
  const auto doubles = [&](const char* name, std::initializer_list<double> values)
  {
    vtkNew<vtkDoubleArray> a;
    a->SetName(name);
    for (double v : values)
    {
      a->InsertNextValue(v);
    }
    fields->AddArray(a);
  };
  const auto integers = [&](
                          const char* name, const std::vector<std::int64_t>& values, int components)
  {
    vtkNew<vtkTypeInt64Array> a;
    a->SetName(name);
    a->SetNumberOfComponents(components);
    for (auto v : values)
    {
      a->InsertNextValue(v);
    }
    fields->AddArray(a);
  };
  doubles("ArrangementOrigin", { p.Origin[0], p.Origin[1], p.Origin[2] });
  doubles("ArrangementQuantum", { p.Quantum });
  doubles("AngleTolerance", { record.AngleToleranceDegrees });
  integers("ArrangementBox",
    { p.BoxLow[0], p.BoxLow[1], p.BoxLow[2], p.BoxHigh[0], p.BoxHigh[1], p.BoxHigh[2] }, 1);
  std::vector<std::int64_t> normals;
  for (const auto& n : record.Normals)
  {
    normals.insert(normals.end(), n.begin(), n.end());
  }
  integers("FamilyNormals", normals, 3);
  integers("FamilyOffsets", p.Offsets, 1);
  integers("FamilySpacings", p.Spacings, 1);
  integers("Planar", { p.Planar ? 1 : 0 }, 1);
  integers("MaximumSmallInteger", { record.MaximumSmallInteger }, 1);
  integers("MaximumVertices", { p.MaxVertices }, 1);
}

vtkMSArrangementStorage::ArrangementRecord vtkMSArrangementStorage::LoadArrangement(
  vtkFieldData* fields, const std::string& where)
{
  const auto array = [&](const char* name, vtkIdType minimum) -> vtkDataArray*
  {
    vtkDataArray* a = fields ? fields->GetArray(name) : nullptr;
    if (!a || a->GetNumberOfValues() < minimum)
    {
      throw msynth::Error(where + ": field data array '" + std::string(name) +
        "' is missing or too short; the input must come from the ModelSynth Plane Arrangement "
        "filter");
    }
    return a;
  };
  const auto integer = [](vtkDataArray* a, vtkIdType i)
  { return static_cast<std::int64_t>(a->GetVariantValue(i).ToTypeInt64()); };
  ArrangementRecord r;
  auto& p = r.Parameters;
  vtkDataArray* origin = array("ArrangementOrigin", 3);
  for (int c = 0; c < 3; ++c)
  {
    p.Origin[msynth::ToIndex(c)] = origin->GetComponent(c, 0);
  }
  p.Quantum = array("ArrangementQuantum", 1)->GetTuple1(0);
  r.AngleToleranceDegrees = array("AngleTolerance", 1)->GetTuple1(0);
  vtkDataArray* box = array("ArrangementBox", 6);
  for (int c = 0; c < 3; ++c)
  {
    p.BoxLow[c] = integer(box, c);
    p.BoxHigh[c] = integer(box, c + 3);
  }
  vtkDataArray* normals = array("FamilyNormals", 3);
  vtkDataArray* offsets = array("FamilyOffsets", 1);
  vtkDataArray* spacings = array("FamilySpacings", 1);
  const vtkIdType m = normals->GetNumberOfValues() / 3;
  if (normals->GetNumberOfValues() != 3 * m || offsets->GetNumberOfValues() != m ||
    spacings->GetNumberOfValues() != m)
  {
    throw msynth::Error(where + ": the arrangement's family arrays disagree in length");
  }
  for (vtkIdType f = 0; f < m; ++f)
  {
    r.Normals.push_back(
      { integer(normals, 3 * f), integer(normals, 3 * f + 1), integer(normals, 3 * f + 2) });
    p.Offsets.push_back(integer(offsets, f));
    p.Spacings.push_back(integer(spacings, f));
  }
  p.Planar = integer(array("Planar", 1), 0) != 0;
  r.MaximumSmallInteger = static_cast<int>(integer(array("MaximumSmallInteger", 1), 0));
  p.MaxVertices = integer(array("MaximumVertices", 1), 0);
  if (!(p.Quantum > 0))
  {
    throw msynth::Error(where + ": the arrangement's quantum is not positive");
  }
  return r;
}

double vtkMSArrangementStorage::SmallestSpacing(vtkFieldData* fields)
{
  if (!fields || !fields->GetArray("FamilySpacings"))
    return 0;
  const ArrangementRecord record = LoadArrangement(fields, "the arrangement");
  const msynth::PlaneFamilySet families(record.Normals);
  double smallest = 0;
  for (int f = 0; f < families.Size(); ++f)
  {
    const double world = record.Parameters.Spacing(families, f);
    smallest = f == 0 ? world : std::min(smallest, world);
  }
  return smallest;
}

namespace
{
bool SameParameters(const msynth::ArrangementParameters& a, const msynth::ArrangementParameters& b)
{
  return a.Origin == b.Origin && a.Quantum == b.Quantum && a.BoxLow == b.BoxLow &&
    a.BoxHigh == b.BoxHigh && a.Offsets == b.Offsets && a.Spacings == b.Spacings &&
    a.Planar == b.Planar && a.MaxVertices == b.MaxVertices;
}
} // namespace

std::shared_ptr<const msynth::PlaneArrangement> vtkMSArrangementStorage::SharedArrangement(
  const msynth::PlaneFamilySet& families, const msynth::ArrangementParameters& parameters)
{
  static std::mutex lock;
  static std::shared_ptr<const msynth::PlaneArrangement> last;
  const std::lock_guard<std::mutex> hold(lock);
  if (!last || last->Families().AllNormals() != families.AllNormals() ||
    !SameParameters(last->Parameters(), parameters))
  {
    last.reset(); // the old one's memory first
    last = std::make_shared<const msynth::PlaneArrangement>(families, parameters);
  }
  return last;
}
