// SPDX-License-Identifier: BSD-3-Clause
// vtkMSArrangementStorage::SharedArrangement: the filters of a pipeline share one build of the
// plane arrangement. Asked again for the same families and parameters it returns the same
// object; asked for others, an arrangement equal to a fresh build of those (never the kept one),
// and a vertex limit still refuses.
#include "vtkMSArrangementStorage.h"

#include "msynthTestUtilities.h"

#include "Continuous/PolyhedralAnalysis.h"
#include "Core/Error.h"
#include "Formats/PolyhedralExample.h"

#include <iostream>

int TestMSSharedArrangement(int, char*[])
{
  msynth::PolyhedralExample example =
    msynth::ReadOBJExample(msynth_test::DataFile("Continuous/house.obj"));
  msynth::ValidateExample(example);
  const auto analysis = msynth::PolyhedralAnalysis::Analyze(example);
  const auto& families = analysis.Families();
  const auto a = msynth::DefaultArrangementParameters(example, analysis, { 8, 8, 6 }, 0, {});
  const auto b = msynth::DefaultArrangementParameters(example, analysis, { 10, 8, 6 }, 0, {});
  const msynth::PlaneArrangement freshA(families, a), freshB(families, b);
  int failures = 0;
  const auto expect = [&failures](bool ok, const char* what)
  {
    if (!ok)
    {
      std::cerr << "FAILED: " << what << "\n";
      ++failures;
    }
  };
  const auto first = vtkMSArrangementStorage::SharedArrangement(families, a);
  const auto again = vtkMSArrangementStorage::SharedArrangement(families, a);
  expect(first.get() == again.get(), "the same parameters give the same build");
  expect(first->NumberOfVertices() == freshA.NumberOfVertices(), "the build is a's");
  const auto other = vtkMSArrangementStorage::SharedArrangement(families, b);
  expect(other.get() != first.get(), "other parameters give another build");
  expect(other->NumberOfVertices() == freshB.NumberOfVertices() &&
      other->Parameters().BoxHigh == b.BoxHigh,
    "the build is b's");
  expect(first->NumberOfVertices() == freshA.NumberOfVertices(), "a holder keeps its build");
  auto shifted = a;
  shifted.Offsets[0] += 1;
  const auto moved = vtkMSArrangementStorage::SharedArrangement(families, shifted);
  expect(moved->Parameters().Offsets == shifted.Offsets, "an offset is part of the key");
  auto limited = a;
  limited.MaxVertices = 10;
  bool refused = false;
  try
  {
    vtkMSArrangementStorage::SharedArrangement(families, limited);
  }
  catch (const msynth::Error&)
  {
    refused = true;
  }
  expect(refused, "a vertex limit still refuses");
  return failures == 0 ? 0 : 1;
}
