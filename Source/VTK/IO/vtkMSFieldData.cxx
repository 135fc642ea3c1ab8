// SPDX-License-Identifier: BSD-3-Clause
#include "vtkMSFieldData.h"

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

#include <cmath>
#include <cstdint>
#include <limits>
#include <map>
#include <vector>

bool vtkMSFieldData::IsTiming(const char* name)
{
  if (!name)
    return false;
  const std::string n(name);
  return n == "Seconds" || n == "FirstValidSeconds" || n == "SampleSeconds" ||
    n == "NetworkSeconds";
}

vtkSmartPointer<vtkDataObject> vtkMSFieldData::WithoutTiming(vtkDataObject* data)
{
  vtkSmartPointer<vtkDataObject> copy = vtkSmartPointer<vtkDataObject>::Take(data->NewInstance());
  copy->ShallowCopy(data);
  vtkNew<vtkFieldData> fields;
  fields->ShallowCopy(data->GetFieldData());
  for (int i = fields->GetNumberOfArrays() - 1; i >= 0; --i)
    if (IsTiming(fields->GetArrayName(i)))
      fields->RemoveArray(i);
  copy->SetFieldData(fields);
  return copy;
}

std::string vtkMSFieldData::ExampleName(vtkDataObject* data)
{
  if (data)
  {
    if (auto* file =
          vtkStringArray::SafeDownCast(data->GetFieldData()->GetAbstractArray("ExampleFile")))
    {
      if (file->GetNumberOfValues() > 0 && !file->GetValue(0).empty())
      {
        return file->GetValue(0);
      }
    }
  }
  return "the input";
}

void vtkMSFieldData::AddStatistics(vtkFieldData* fields,
  const msynth::SynthesisStatistics& statistics, msynth::SynthesisStatus status,
  const std::string& message)
{
  for (const auto& f : msynth::StatisticsFields(statistics))
  {
    if (f.Integer)
      AddFieldValue<vtkIdTypeArray>(fields, f.Name.c_str(), static_cast<vtkIdType>(f.Value));
    else
      AddFieldValue<vtkDoubleArray>(fields, f.Name.c_str(), f.Value);
  }
  AddFieldValue<vtkStringArray>(fields, "Status", std::string(msynth::ToString(status)));
  AddFieldValue<vtkStringArray>(fields, "Message", message);
  if (statistics.TrivialLabel)
    AddFieldValue<vtkIntArray>(fields, "TrivialLabel", *statistics.TrivialLabel);
  if (!statistics.StartFrom.empty())
    AddFieldValue<vtkStringArray>(fields, "StartFrom", statistics.StartFrom);
  vtkNew<vtkIdTypeArray> origins, sites;
  origins->SetName("FailedBlockOrigins");
  origins->SetNumberOfComponents(3);
  sites->SetName("FailedBlockSites");
  sites->SetNumberOfComponents(3);
  for (const auto& f : statistics.Failures)
  {
    const vtkIdType o[3] = { f.Origin[0], f.Origin[1], f.Origin[2] };
    const vtkIdType e[3] = { f.EmptySite[0], f.EmptySite[1], f.EmptySite[2] };
    origins->InsertNextTypedTuple(o);
    sites->InsertNextTypedTuple(e);
  }
  fields->AddArray(origins);
  fields->AddArray(sites);
}
