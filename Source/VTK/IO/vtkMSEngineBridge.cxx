// SPDX-License-Identifier: BSD-3-Clause
#include "vtkMSEngineBridge.h"

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

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <map>
#include <vector>

vtkStandardNewMacro(vtkMSEngineBridge);

vtkMSEngineBridge::~vtkMSEngineBridge()
{
  this->Reset();
}

namespace
{
/// @p algorithm and every algorithm upstream of it, each once, upstream ones first.
void WithUpstream(vtkAlgorithm* algorithm, std::vector<vtkAlgorithm*>& out)
{
  if (std::find(out.begin(), out.end(), algorithm) != out.end())
    return;
  for (int p = 0; p < algorithm->GetNumberOfInputPorts(); ++p)
    for (int c = 0; c < algorithm->GetNumberOfInputConnections(p); ++c)
      if (vtkAlgorithm* in = algorithm->GetInputAlgorithm(p, c))
        WithUpstream(in, out);
  out.push_back(algorithm);
}
} // namespace

bool vtkMSEngineBridge::Execute(
  vtkAlgorithm* algorithm, std::string& messages, bool informationOnly)
{
  // Upstream algorithms (a reader of a damaged file) are heard too: when the update fails,
  // their reasons come first, instead of only "<filter> failed".
  std::vector<vtkAlgorithm*> pipeline;
  WithUpstream(algorithm, pipeline);
  std::vector<vtkSmartPointer<vtkMSEngineBridge>> upstream;
  for (std::size_t i = 0; i + 1 < pipeline.size(); ++i)
  {
    upstream.push_back(vtkSmartPointer<vtkMSEngineBridge>::New());
    upstream.back()->Watch(pipeline[i]);
  }
  vtkNew<vtkMSEngineBridge> errors;
  errors->Watch(algorithm);
  vtkExecutive* executive = algorithm->GetExecutive();
  int status = 0;
  std::string thrown;
  try
  {
    // A third-party reader may throw (std::bad_alloc for a size read from a damaged file):
    // that is a failed update, not the end of the process.
    status = informationOnly ? executive->UpdateInformation() : executive->Update();
  }
  catch (const std::bad_alloc&)
  {
    thrown = std::string(algorithm->GetClassName()) + " ran out of memory (a damaged file?)";
  }
  catch (const std::exception& e)
  {
    thrown = std::string(algorithm->GetClassName()) + " failed: " + e.what();
  }
  const bool ok = status != 0 && !errors->HasErrors() && thrown.empty();
  messages = errors->GetMessages() + thrown;
  if (!ok)
    for (auto it = upstream.rbegin(); it != upstream.rend(); ++it)
      if ((*it)->HasErrors() && messages.find((*it)->GetMessages()) == std::string::npos)
        messages = (*it)->GetMessages() + (messages.empty() ? "" : "; " + messages);
  if (!ok && messages.empty())
  {
    messages = std::string(algorithm->GetClassName()) + " failed";
  }
  return ok;
}

void vtkMSEngineBridge::Watch(vtkObject* source)
{
  this->Reset();
  this->Source = source;
  this->Tag = source->AddObserver(vtkCommand::ErrorEvent, this, &vtkMSEngineBridge::OnError);
}

void vtkMSEngineBridge::Reset()
{
  if (this->Source)
  {
    this->Source->RemoveObserver(this->Tag);
  }
  this->Source = nullptr;
  this->Messages.clear();
}

void vtkMSEngineBridge::OnError(vtkObject*, unsigned long, void* data)
{
  std::string message = data ? static_cast<const char*>(data) : "unknown error";
  // VTK prefixes messages with "ERROR: In <file>, line N\n<class> (<address>): "; keep the text.
  const auto pos = message.rfind("): ");
  if (pos != std::string::npos)
  {
    message = message.substr(pos + 3);
  }
  while (!message.empty() && (message.back() == '\n' || message.back() == ' '))
  {
    message.pop_back();
  }
  if (!this->Messages.empty())
  {
    this->Messages += "; ";
  }
  this->Messages += message;
}
