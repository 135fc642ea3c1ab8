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

bool vtkMSEngineBridge::Execute(
  vtkAlgorithm* algorithm, std::string& messages, bool informationOnly)
{
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
