// SPDX-License-Identifier: BSD-3-Clause
#include "Resemblance.h"

#include "Common.h"

#include "vtkDataArray.h"
#include "vtkFieldData.h"
#include "vtkIntArray.h"
#include "vtkStringArray.h"

#include <iomanip>
#include <ostream>
#include <sstream>

namespace msynth::cli
{
namespace
{
struct Arrays
{
  vtkStringArray* Measure = nullptr;
  vtkStringArray* Bounds = nullptr;
  vtkDataArray* Example = nullptr;
  vtkDataArray* Model = nullptr;
  vtkDataArray* Passes = nullptr;
  vtkIdType Count() const { return this->Measure ? this->Measure->GetNumberOfValues() : 0; }
};

Arrays ArraysOf(vtkFieldData* fd)
{
  Arrays a;
  if (!fd)
    return a;
  a.Measure = vtkStringArray::SafeDownCast(fd->GetAbstractArray("ResemblanceMeasure"));
  a.Bounds = vtkStringArray::SafeDownCast(fd->GetAbstractArray("ResemblanceBounds"));
  a.Example = fd->GetArray("ResemblanceExample");
  a.Model = fd->GetArray("ResemblanceModel");
  a.Passes = fd->GetArray("ResemblancePasses");
  const vtkIdType n = a.Measure ? a.Measure->GetNumberOfValues() : -1;
  if (!a.Bounds || !a.Example || !a.Model || !a.Passes || a.Bounds->GetNumberOfValues() != n ||
    a.Example->GetNumberOfTuples() != n || a.Model->GetNumberOfTuples() != n ||
    a.Passes->GetNumberOfTuples() != n)
    a.Measure = nullptr;
  return a;
}

std::string Figure(double v)
{
  std::ostringstream s;
  s << std::setprecision(3) << v;
  return s.str();
}
} // namespace

int ResemblanceFailed(vtkFieldData* fd)
{
  const Arrays a = ArraysOf(fd);
  if (!a.Measure)
    return -1;
  int failed = 0;
  for (vtkIdType i = 0; i < a.Count(); ++i)
    failed += a.Passes->GetTuple1(i) != 0 ? 0 : 1;
  return failed;
}

void PrintResemblance(vtkFieldData* fd, std::ostream& out)
{
  const Arrays a = ArraysOf(fd);
  if (!a.Measure || a.Count() == 0)
    return;
  out << "structure against the example (parts of each type): " << a.Count() - ResemblanceFailed(fd)
      << " of " << Counted(a.Count(), "measure") << " within bounds\n";
  std::size_t width = 0;
  for (vtkIdType i = 0; i < a.Count(); ++i)
    width = std::max(width, a.Measure->GetValue(i).size());
  for (vtkIdType i = 0; i < a.Count(); ++i)
    out << "  " << std::left << std::setw(static_cast<int>(width)) << a.Measure->GetValue(i)
        << "  example " << std::setw(7) << Figure(a.Example->GetTuple1(i)) << " model "
        << std::setw(7) << Figure(a.Model->GetTuple1(i)) << " (" << a.Bounds->GetValue(i) << ") "
        << (a.Passes->GetTuple1(i) != 0 ? "ok" : "OUT") << std::right << "\n";
}

std::string ResemblanceSummary(vtkFieldData* fd)
{
  const Arrays a = ArraysOf(fd);
  if (!a.Measure)
    return "";
  std::string out;
  for (vtkIdType i = 0; i < a.Count(); ++i)
    if (a.Passes->GetTuple1(i) == 0)
      out += (out.empty() ? "; out: " : ", ") + a.Measure->GetValue(i) + " " +
        Figure(a.Model->GetTuple1(i)) + " against " + Figure(a.Example->GetTuple1(i));
  return std::to_string(a.Count() - ResemblanceFailed(fd)) + " of " +
    Counted(a.Count(), "measure") + " within bounds" + out;
}

std::string ResemblanceJson(vtkFieldData* fd)
{
  const Arrays a = ArraysOf(fd);
  std::string json = "[";
  for (vtkIdType i = 0; a.Measure && i < a.Count(); ++i)
    json += std::string(i ? ", " : "") + "{\"measure\": " + JsonString(a.Measure->GetValue(i)) +
      ", \"example\": " + JsonNumber(a.Example->GetTuple1(i)) +
      ", \"model\": " + JsonNumber(a.Model->GetTuple1(i)) +
      ", \"bounds\": " + JsonString(a.Bounds->GetValue(i)) +
      ", \"passes\": " + (a.Passes->GetTuple1(i) != 0 ? "true" : "false") + "}";
  return json + "]";
}
} // namespace msynth::cli
