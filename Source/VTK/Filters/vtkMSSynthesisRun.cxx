// SPDX-License-Identifier: BSD-3-Clause
#include "vtkMSSynthesisRun.h"

#include "vtkMSEngineBridge.h"
#include "vtkMSFieldData.h"

#include "vtkCommunicator.h"
#include "vtkDataSet.h"
#include "vtkFloatArray.h"
#include "vtkIdTypeArray.h"
#include "vtkIntArray.h"
#include "vtkMultiProcessController.h"
#include "vtkNew.h"
#include "vtkPointData.h"

#include "Core/Error.h"
#include "Core/Index.h"

#include <algorithm>
#include <new>

namespace vtkMSSynthesisRun
{
std::vector<std::pair<std::string, std::vector<float>>> GuideWeights(vtkDataSet* guide)
{
  std::vector<std::pair<std::string, std::vector<float>>> out;
  vtkPointData* pd = guide->GetPointData();
  for (int i = 0; i < pd->GetNumberOfArrays(); ++i)
  {
    vtkDataArray* array = pd->GetArray(i);
    const std::string name = array && array->GetName() ? array->GetName() : "";
    if (name.rfind("Weight_", 0) != 0)
      continue;
    if (array->GetNumberOfComponents() != 1)
      throw msynth::Error("guide array '" + name + "' must have one component");
    std::vector<float> weights(msynth::ToIndex(array->GetNumberOfTuples()));
    for (vtkIdType t = 0; t < array->GetNumberOfTuples(); ++t)
      weights[msynth::ToIndex(t)] = static_cast<float>(array->GetTuple1(t));
    out.emplace_back(name.substr(7), std::move(weights));
  }
  return out;
}

std::function<bool(double)> Progress(vtkAlgorithm* filter)
{
  return [filter](double fraction)
  {
    filter->UpdateProgress(fraction);
    return !filter->CheckAbort();
  };
}

bool Solve(vtkAlgorithm* filter, const std::string& what, const std::function<void()>& solve)
{
  try
  {
    solve();
    return true;
  }
  catch (const std::bad_alloc&)
  {
    vtkErrorWithObjectMacro(filter, << what << " needs more memory than is available.");
  }
  catch (const std::exception& e)
  {
    vtkErrorWithObjectMacro(filter, << e.what());
  }
  return false;
}

bool Report(vtkAlgorithm* filter, msynth::SynthesisStatus status, const std::string& message,
  const std::string& context)
{
  if (status == msynth::SynthesisStatus::Failed)
  {
    vtkErrorWithObjectMacro(filter, << (context.empty() ? "" : context + ": ") << message);
  }
  return status == msynth::SynthesisStatus::Succeeded;
}

msynth::BlockExchange ProcessExchange(std::int64_t fingerprint)
{
  msynth::BlockExchange exchange;
  vtkMultiProcessController* controller = vtkMultiProcessController::GetGlobalController();
  if (!controller || controller->GetNumberOfProcesses() < 2)
    return exchange;
  auto mine = static_cast<vtkIdType>(fingerprint);
  vtkIdType low = 0, high = 0;
  controller->AllReduce(&mine, &low, 1, vtkCommunicator::MIN_OP);
  controller->AllReduce(&mine, &high, 1, vtkCommunicator::MAX_OP);
  if (low == 0 || low != high)
    return exchange;
  exchange.Rank = controller->GetLocalProcessId();
  exchange.Processes = controller->GetNumberOfProcesses();
  exchange.AllGather = [controller](const std::vector<char>& bytes)
  {
    // The lengths first, then the bytes of every rank.
    const int ranks = controller->GetNumberOfProcesses();
    vtkIdType length = static_cast<vtkIdType>(bytes.size());
    std::vector<vtkIdType> lengths(msynth::ToIndex(ranks)), offsets(lengths.size());
    controller->AllGather(&length, lengths.data(), 1);
    vtkIdType total = 0;
    for (std::size_t r = 0; r < lengths.size(); ++r)
    {
      offsets[r] = total;
      total += lengths[r];
    }
    std::vector<char> all(msynth::ToIndex(std::max<vtkIdType>(total, 1)));
    controller->AllGatherV(bytes.data(), all.data(), length, lengths.data(), offsets.data());
    std::vector<std::vector<char>> parts(lengths.size());
    for (std::size_t r = 0; r < lengths.size(); ++r)
      parts[r].assign(all.begin() + offsets[r], all.begin() + offsets[r] + lengths[r]);
    return parts;
  };
  return exchange;
}

void AddCatalog(
  vtkDataSet* output, const std::vector<std::int32_t>& size, const std::vector<float>& entropy)
{
  vtkNew<vtkIntArray> sizes;
  sizes->SetName("CatalogSize");
  sizes->SetNumberOfTuples(static_cast<vtkIdType>(size.size()));
  std::copy(size.begin(), size.end(), sizes->GetPointer(0));
  output->GetPointData()->AddArray(sizes);
  vtkNew<vtkFloatArray> entropies;
  entropies->SetName("Entropy");
  entropies->SetNumberOfTuples(static_cast<vtkIdType>(entropy.size()));
  std::copy(entropy.begin(), entropy.end(), entropies->GetPointer(0));
  output->GetPointData()->AddArray(entropies);
}

void AddStep(vtkDataSet* output, std::int64_t step, std::int64_t block, std::int64_t assignments)
{
  vtkMSFieldData::AddFieldValue<vtkIdTypeArray>(
    output->GetFieldData(), "Step", static_cast<vtkIdType>(step));
  vtkMSFieldData::AddFieldValue<vtkIdTypeArray>(
    output->GetFieldData(), "ActiveBlock", static_cast<vtkIdType>(block));
  vtkMSFieldData::AddFieldValue<vtkIdTypeArray>(
    output->GetFieldData(), "StepAssignments", static_cast<vtkIdType>(assignments));
}

}
