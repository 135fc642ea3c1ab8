// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Label images read beforehand, offered as time steps 0, 1, ... (what ParaView's file series is):
// `animate`'s several example files, `check --animation`'s frames.
#include "vtkImageAlgorithm.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkSmartPointer.h"
#include "vtkStreamingDemandDrivenPipeline.h"

#include <algorithm>
#include <vector>

/// Frames read beforehand, offered as time steps 0, 1, ... (what ParaView's file series is).
class vtkMSFrameSeries : public vtkImageAlgorithm
{
public:
  static vtkMSFrameSeries* New();
  vtkTypeMacro(vtkMSFrameSeries, vtkImageAlgorithm);
  void AddFrame(vtkImageData* frame) { this->Frames.emplace_back(frame); }

protected:
  vtkMSFrameSeries() { this->SetNumberOfInputPorts(0); }
  int RequestInformation(
    vtkInformation*, vtkInformationVector**, vtkInformationVector* out) override
  {
    vtkInformation* info = out->GetInformationObject(0);
    std::vector<double> times(this->Frames.size());
    for (std::size_t t = 0; t < times.size(); ++t)
      times[t] = static_cast<double>(t);
    info->Set(
      vtkStreamingDemandDrivenPipeline::TIME_STEPS(), times.data(), static_cast<int>(times.size()));
    const double range[2] = { 0.0, times.empty() ? 0.0 : times.back() };
    info->Set(vtkStreamingDemandDrivenPipeline::TIME_RANGE(), range, 2);
    if (!this->Frames.empty())
      info->Set(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), this->Frames[0]->GetExtent(), 6);
    return 1;
  }
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector* out) override
  {
    vtkInformation* info = out->GetInformationObject(0);
    std::size_t t = 0;
    if (info->Has(vtkStreamingDemandDrivenPipeline::UPDATE_TIME_STEP()))
      t = static_cast<std::size_t>(
        std::max(0.0, info->Get(vtkStreamingDemandDrivenPipeline::UPDATE_TIME_STEP()) + 0.5));
    if (t >= this->Frames.size())
      return 0;
    vtkImageData* output = vtkImageData::GetData(info);
    output->ShallowCopy(this->Frames[t]);
    output->GetInformation()->Set(vtkDataObject::DATA_TIME_STEP(), static_cast<double>(t));
    return 1;
  }

private:
  std::vector<vtkSmartPointer<vtkImageData>> Frames;
};
