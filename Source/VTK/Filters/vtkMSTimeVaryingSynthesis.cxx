// SPDX-License-Identifier: BSD-3-Clause
#include "vtkMSTimeVaryingSynthesis.h"

#include "vtkMSEngineBridge.h"
#include "vtkMSFieldData.h"
#include "vtkMSLabelArrays.h"
#include "vtkMSPipeline.h"
#include "vtkMSSynthesisRun.h"

#include "vtkIdTypeArray.h"

#include "Discrete/TimeVarying.h"

#include "Core/Index.h"
#include "vtkDataArray.h"
#include "vtkFieldData.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationDoubleVectorKey.h"
#include "vtkInformationVector.h"
#include "vtkIntArray.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkStreamingDemandDrivenPipeline.h"

#include <exception>
#include <string>
#include <vector>

vtkStandardNewMacro(vtkMSTimeVaryingSynthesis);

/// The last result, reused while neither the filter nor the example frames change.
struct vtkMSTimeVaryingSynthesis::Cache
{
  vtkMSSynthesisCache<msynth::TimeVaryingResult> Run;
  std::vector<msynth::LabelGrid> Example; ///< the frames the result was computed from
};

vtkMSTimeVaryingSynthesis::vtkMSTimeVaryingSynthesis()
  : Cached(std::make_unique<Cache>())
{
  this->SetNumberOfInputPorts(1);
  this->SetNumberOfOutputPorts(2);
}

vtkMSTimeVaryingSynthesis::~vtkMSTimeVaryingSynthesis() = default;

vtkImageData* vtkMSTimeVaryingSynthesis::GetOutput()
{
  return vtkImageData::SafeDownCast(this->GetOutputDataObject(0));
}

vtkPolyData* vtkMSTimeVaryingSynthesis::GetGeometryOutput()
{
  return vtkPolyData::SafeDownCast(this->GetOutputDataObject(1));
}

int vtkMSTimeVaryingSynthesis::FillInputPortInformation(int, vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkImageData");
  return 1;
}

int vtkMSTimeVaryingSynthesis::FillOutputPortInformation(int port, vtkInformation* info)
{
  info->Set(vtkDataObject::DATA_TYPE_NAME(), port == 0 ? "vtkImageData" : "vtkPolyData");
  return 1;
}

int vtkMSTimeVaryingSynthesis::RequestInformation(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  vtkMSPipeline::SetOutputLabelGrid(
    inputVector[0]->GetInformationObject(0), outInfo, this->OutputSize);
  for (int port = 0; port < 2; ++port)
  {
    vtkInformation* info = outputVector->GetInformationObject(port);
    vtkMSPipeline::SetTimeSteps(info, msynth::ToIndex(this->NumberOfFrames));
    info->Set(CAN_HANDLE_PIECE_REQUEST(), 1);
  }
  return 1;
}

int vtkMSTimeVaryingSynthesis::RequestUpdateExtent(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  vtkInformation* inInfo = inputVector[0]->GetInformationObject(0);
  vtkMSPipeline::RequestWholeExtentOnPieceZero(
    inInfo, vtkMSPipeline::UpdatePiece(outputVector->GetInformationObject(0)));
  // Every frame of the example (one request when its frames are z slices or it has no time).
  std::vector<double> times{ 0.0 };
  const auto key = vtkStreamingDemandDrivenPipeline::TIME_STEPS();
  if (!this->ExampleTimeFromZ && inInfo->Has(key) && inInfo->Length(key) > 0)
  {
    times.assign(inInfo->Get(key), inInfo->Get(key) + inInfo->Length(key));
  }
  else if (inInfo->Has(vtkStreamingDemandDrivenPipeline::TIME_STEPS()))
  {
    times = { inInfo->Get(key)[0] };
  }
  inInfo->Set(
    vtkMultiTimeStepAlgorithm::UPDATE_TIME_STEPS(), times.data(), static_cast<int>(times.size()));
  return 1;
}

vtkTypeBool vtkMSTimeVaryingSynthesis::ProcessRequest(
  vtkInformation* request, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  const vtkTypeBool result = this->Superclass::ProcessRequest(request, inputVector, outputVector);
  vtkInformation* inInfo =
    inputVector && inputVector[0] ? inputVector[0]->GetInformationObject(0) : nullptr;
  if (inInfo && request->Has(vtkStreamingDemandDrivenPipeline::REQUEST_UPDATE_EXTENT()))
  {
    // Later passes skip RequestUpdateExtent and would copy the output's extent upstream.
    vtkMSPipeline::RequestWholeExtentOnPieceZero(
      inInfo, vtkMSPipeline::UpdatePiece(outputVector->GetInformationObject(0)));
  }
  return result;
}

namespace
{
/// The example frames: each input, or with @p fromZ the z slices of each. False with @p problem.
bool ReadFrames(const std::vector<vtkSmartPointer<vtkDataObject>>& inputs, bool fromZ,
  std::vector<msynth::LabelGrid>& frames, std::string& problem)
{
  for (std::size_t i = 0; i < inputs.size(); ++i)
  {
    msynth::LabelGrid grid;
    if (!vtkMSLabelArrays::ReadLabels(
          vtkImageData::SafeDownCast(inputs[i]), nullptr, grid, problem))
    {
      problem = "Bad example frame " + std::to_string(i) + ": " + problem;
      return false;
    }
    if (!fromZ)
    {
      frames.push_back(std::move(grid));
      continue;
    }
    for (auto& slice : msynth::TimeVaryingGrid::FromSlices(grid).Frames)
      frames.push_back(std::move(slice));
  }
  return true;
}

/// The engine's options from the filter's properties.
msynth::TimeVaryingOptions OptionsOf(vtkMSTimeVaryingSynthesis* self)
{
  msynth::TimeVaryingOptions options;
  const int* size = self->GetOutputSize();
  const int* block = self->GetBlockSize();
  options.Size = { { size[0], size[1], size[2], self->GetNumberOfFrames() } };
  options.BlockSize = { { block[0], block[1], block[2], block[3] } };
  const int* overlap = self->GetBlockOverlap();
  options.Overlap = { { overlap[0], overlap[1], overlap[2], overlap[3] } };
  options.AttemptsPerBlock = self->GetAttemptsPerBlock();
  options.Seed = static_cast<std::uint64_t>(self->GetSeed());
  options.Choice = self->GetLabelChoice() == vtkMSTimeVaryingSynthesis::FREQUENCY
    ? msynth::LabelChoice::Frequency
    : msynth::LabelChoice::Uniform;
  options.Order = self->GetSiteOrder() == vtkMSTimeVaryingSynthesis::RANDOM
    ? msynth::SiteOrder::Random
    : msynth::SiteOrder::ScanLine;
  options.Loop = self->GetLoop();
  options.Progress = vtkMSSynthesisRun::Progress(self);
  return options;
}
} // namespace

int vtkMSTimeVaryingSynthesis::Execute(vtkInformation* request,
  const std::vector<vtkSmartPointer<vtkDataObject>>& inputs, vtkInformationVector* outputVector)
{
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  vtkImageData* output = vtkImageData::GetData(outInfo);
  vtkPolyData* geometry = vtkPolyData::GetData(outputVector, 1);
  geometry->Initialize();
  if (vtkMSPipeline::UpdatePiece(outInfo) != 0)
  {
    output->Initialize(); // piece 0 holds the model
    return 1;
  }
  std::vector<msynth::LabelGrid> frames;
  std::string problem;
  if (!ReadFrames(inputs, this->ExampleTimeFromZ, frames, problem))
  {
    vtkErrorMacro(<< problem);
    return 0;
  }
  Cache& cache = *this->Cached;
  if (cache.Run.Fresh(this, {}) || cache.Example != frames)
  {
    cache.Run.Clear();
    const msynth::TimeVaryingOptions options = OptionsOf(this);
    const std::string what =
      "A time-varying model of " + std::to_string(this->NumberOfFrames) + " frames";
    if (!vtkMSSynthesisRun::Solve(this, what,
          [&]()
          {
            msynth::TimeVaryingGrid example;
            example.Frames = frames;
            cache.Run.Result = msynth::SynthesizeTimeVarying(
              msynth::TimeVaryingRules::FromExample(example), options);
          }))
    {
      return 0;
    }
    cache.Example = std::move(frames);
    cache.Run.Keep(this, {}, cache.Run.Result.Succeeded());
  }
  const msynth::TimeVaryingResult& result = cache.Run.Result;
  if (!vtkMSSynthesisRun::Report(this, result.Status, result.Message))
  {
    return 0;
  }
  const std::size_t step = vtkMSPipeline::RequestedStep(
    vtkMSPipeline::RequestingPort(request, outputVector), result.Model.Frames.size());
  const msynth::LabelGrid& frame = result.Model.Frames[step];
  output->SetExtent(
    0, this->OutputSize[0] - 1, 0, this->OutputSize[1] - 1, 0, this->OutputSize[2] - 1);
  double spacing[3] = { 1, 1, 1 }, origin[3] = { 0, 0, 0 };
  outInfo->Get(vtkDataObject::SPACING(), spacing);
  outInfo->Get(vtkDataObject::ORIGIN(), origin);
  output->SetSpacing(spacing);
  output->SetOrigin(origin);
  vtkIntArray* labels = vtkMSLabelArrays::NewLabelArray(frame, "Label");
  output->GetPointData()->SetScalars(labels);
  labels->Delete();
  output->GetInformation()->Set(vtkDataObject::DATA_TIME_STEP(), static_cast<double>(step));
  vtkFieldData* fd = output->GetFieldData();
  const msynth::SynthesisStatistics& s = result.Statistics;
  vtkMSFieldData::AddFieldValue<vtkIntArray>(fd, "Frame", static_cast<int>(step));
  vtkMSFieldData::AddFieldValue<vtkIntArray>(fd, "Frames", this->NumberOfFrames);
  vtkMSFieldData::AddFieldValue<vtkIntArray>(fd, "Loop", this->Loop ? 1 : 0);
  vtkMSFieldData::AddFieldValue<vtkIntArray>(
    fd, "ExampleFrames", static_cast<int>(cache.Example.size()));
  vtkMSFieldData::AddStatistics(fd, s, result.Status, result.Message);
  vtkMSFieldData::AddFieldValue<vtkIdTypeArray>(fd, "Seed", static_cast<vtkIdType>(this->Seed));
  // Piece 0 holds the whole model, and so the whole surface.
  if (this->GenerateGeometry &&
    !vtkMSLabelArrays::VoxelSurface(output, this->EmptyLabel, 0, 1, geometry, problem))
  {
    output->Initialize();
    vtkErrorMacro(<< "The frame's geometry: " << problem);
    return 0;
  }
  geometry->GetInformation()->Set(vtkDataObject::DATA_TIME_STEP(), static_cast<double>(step));
  return 1;
}

void vtkMSTimeVaryingSynthesis::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "OutputSize: " << this->OutputSize[0] << " " << this->OutputSize[1] << " "
     << this->OutputSize[2] << "\n";
  os << indent << "NumberOfFrames: " << this->NumberOfFrames << "\n";
  os << indent << "BlockSize: " << this->BlockSize[0] << " " << this->BlockSize[1] << " "
     << this->BlockSize[2] << " " << this->BlockSize[3] << "\n";
  os << indent << "BlockOverlap: " << this->BlockOverlap[0] << " " << this->BlockOverlap[1] << " "
     << this->BlockOverlap[2] << " " << this->BlockOverlap[3] << "\n";
  os << indent << "Seed: " << this->Seed << "\n";
  os << indent << "Loop: " << this->Loop << "\n";
  os << indent << "ExampleTimeFromZ: " << this->ExampleTimeFromZ << "\n";
  os << indent << "GenerateGeometry: " << this->GenerateGeometry << " (EmptyLabel "
     << this->EmptyLabel << ")\n";
}
