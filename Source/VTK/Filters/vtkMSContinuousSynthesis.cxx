// SPDX-License-Identifier: BSD-3-Clause
#include "vtkMSContinuousSynthesis.h"

#include "vtkMSEngineBridge.h"

#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkIdTypeArray.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkIntArray.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkStreamingDemandDrivenPipeline.h"

#include "Continuous/ContinuousSynthesis.h"
#include "Core/Error.h"

#include <algorithm>
#include <cmath>

struct vtkMSContinuousSynthesis::Cache
{
  vtkMTimeType FilterTime = 0;
  vtkMTimeType ExampleTime = 0;
  vtkMTimeType ArrangementTime = 0;
  msynth::ContinuousSynthesisResult Result;
  std::vector<msynth::ContinuousSnapshot> Snapshots;
};

vtkStandardNewMacro(vtkMSContinuousSynthesis);

vtkMSContinuousSynthesis::vtkMSContinuousSynthesis()
{
  this->SetNumberOfInputPorts(2);
}

vtkMSContinuousSynthesis::~vtkMSContinuousSynthesis() = default;

void vtkMSContinuousSynthesis::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Seed: " << this->Seed << "\n";
  os << indent << "BlockSize: " << this->BlockSize << "\n";
  os << indent << "Attempts: " << this->Attempts << "\n";
  os << indent << "SiteOrder: " << this->SiteOrder << "\n";
  os << indent << "LabelChoice: " << this->LabelChoice << "\n";
  os << indent << "NumberOfSnapshots: " << this->NumberOfSnapshots << "\n";
}

int vtkMSContinuousSynthesis::FillInputPortInformation(int, vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkPolyData");
  return 1;
}

int vtkMSContinuousSynthesis::RequestInformation(
  vtkInformation*, vtkInformationVector**, vtkInformationVector* outputVector)
{
  vtkMSEngineBridge::SetTimeSteps(outputVector->GetInformationObject(0),
    this->NumberOfSnapshots > 0 ? static_cast<std::size_t>(this->NumberOfSnapshots) + 1 : 0);
  return 1;
}

int vtkMSContinuousSynthesis::RequestData(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  vtkPolyData* example = vtkPolyData::GetData(inputVector[0], 0);
  vtkPolyData* arrangementData = vtkPolyData::GetData(inputVector[1], 0);
  vtkPolyData* output = vtkPolyData::GetData(outputVector, 0);
  if (!arrangementData)
  {
    vtkErrorMacro(
      << "no arrangement input (port 1): connect the ModelSynth Plane Arrangement filter");
    return 0;
  }
  if (vtkMSEngineBridge::UpdatePiece(outputVector->GetInformationObject(0)) > 0 &&
    arrangementData->GetNumberOfPoints() == 0)
  {
    return 1; // in parallel, the arrangement lives on piece 0
  }
  if (!this->Cached)
  {
    this->Cached.reset(new Cache);
  }
  Cache& cache = *this->Cached;
  try
  {
    const bool fresh = cache.FilterTime != this->GetMTime() || !example ||
      cache.ExampleTime != example->GetMTime() ||
      cache.ArrangementTime != arrangementData->GetMTime();
    if (fresh)
    {
      const auto record = vtkMSEngineBridge::LoadArrangement(arrangementData->GetFieldData(),
        vtkMSEngineBridge::ExampleName(arrangementData) + " (arrangement)");
      msynth::PolyhedralExample ex;
      const auto analysis = vtkMSEngineBridge::AnalyzeExample(
        example, record.AngleToleranceDegrees, record.MaximumSmallInteger, ex);
      if (analysis.Families().AllNormals() != record.Normals)
      {
        throw msynth::Error(ex.Source +
          ": the arrangement was built from another example (its plane "
          "families differ)");
      }
      const msynth::PlaneArrangement arrangement(analysis.Families(), record.Parameters);
      if (arrangement.NumberOfVertices() != arrangementData->GetNumberOfPoints())
      {
        throw msynth::Error(ex.Source + ": the arrangement input has " +
          std::to_string(arrangementData->GetNumberOfPoints()) +
          " points but its parameters give " + std::to_string(arrangement.NumberOfVertices()) +
          " vertices");
      }
      msynth::ContinuousSynthesisOptions options;
      options.Seed = static_cast<std::uint64_t>(this->Seed);
      options.BlockSize = this->BlockSize;
      options.Attempts = this->Attempts;
      options.Order = static_cast<msynth::SiteOrder>(this->SiteOrder);
      options.Choice =
        this->LabelChoice == 1 ? msynth::LabelChoice::Frequency : msynth::LabelChoice::Uniform;
      options.Snapshots = this->NumberOfSnapshots;
      cache.Snapshots.clear();
      options.OnSnapshot = [&cache](const msynth::ContinuousSnapshot& s)
      { cache.Snapshots.push_back(s); };
      options.Progress = [this](double f)
      {
        this->UpdateProgress(f);
        return !this->GetAbortExecute();
      };
      cache.Result = msynth::SynthesizeContinuous(analysis, arrangement, options);
      // A cancelled run is not kept: the next update runs again.
      cache.FilterTime =
        cache.Result.Status == msynth::SynthesisStatus::Cancelled ? 0 : this->GetMTime();
      cache.ExampleTime = example->GetMTime();
      cache.ArrangementTime = arrangementData->GetMTime();
    }
  }
  catch (const std::bad_alloc&)
  {
    cache.FilterTime = 0;
    vtkErrorMacro(<< "Synthesis needs more memory than is available (arrangement of "
                  << arrangementData->GetNumberOfPoints() << " vertices).");
    return 0;
  }
  catch (const std::exception& e)
  {
    cache.FilterTime = 0;
    vtkErrorMacro(<< e.what());
    return 0;
  }
  const auto& result = cache.Result;
  if (!result.Succeeded())
  {
    if (result.Status != msynth::SynthesisStatus::Cancelled)
    {
      vtkErrorMacro(<< vtkMSEngineBridge::ExampleName(example) << ": " << result.Message);
    }
    return 0;
  }
  output->ShallowCopy(arrangementData);
  const vtkIdType n = arrangementData->GetNumberOfPoints();
  vtkNew<vtkIntArray> label;
  label->SetName("Label");
  label->SetNumberOfValues(n);
  vtkNew<vtkIntArray> size;
  size->SetName("CatalogSize");
  size->SetNumberOfValues(n);
  vtkNew<vtkFloatArray> entropy;
  entropy->SetName("Entropy");
  entropy->SetNumberOfValues(n);
  for (vtkIdType v = 0; v < n; ++v)
  {
    label->SetValue(v, result.Labels[static_cast<std::size_t>(v)]);
    size->SetValue(v, 1);
    entropy->SetValue(v, 0.0f);
  }
  if (!cache.Snapshots.empty())
  {
    const std::size_t step = vtkMSEngineBridge::RequestedStep(
      outputVector->GetInformationObject(0), cache.Snapshots.size());
    const auto& snap = cache.Snapshots[step];
    for (vtkIdType v = 0; v < n; ++v)
    {
      label->SetValue(v, snap.Labels[static_cast<std::size_t>(v)]);
      size->SetValue(v, snap.CatalogSize[static_cast<std::size_t>(v)]);
      entropy->SetValue(v, snap.Entropy[static_cast<std::size_t>(v)]);
    }
    vtkMSEngineBridge::AddFieldValue<vtkIdTypeArray>(
      output->GetFieldData(), "Step", static_cast<vtkIdType>(snap.Step));
    vtkMSEngineBridge::AddFieldValue<vtkIdTypeArray>(
      output->GetFieldData(), "ActiveBlock", static_cast<vtkIdType>(snap.Block));
    output->GetInformation()->Set(vtkDataObject::DATA_TIME_STEP(), static_cast<double>(step));
  }
  output->GetPointData()->AddArray(label);
  if (!cache.Snapshots.empty())
  {
    // The finished model at every time step, so that mesh extraction downstream does not
    // depend on the time shown.
    vtkNew<vtkIntArray> model;
    model->SetName("ModelLabel");
    model->SetNumberOfValues(n);
    for (vtkIdType v = 0; v < n; ++v)
    {
      model->SetValue(v, result.Labels[static_cast<std::size_t>(v)]);
    }
    output->GetPointData()->AddArray(model);
  }
  output->GetPointData()->AddArray(size);
  output->GetPointData()->AddArray(entropy);
  output->GetPointData()->SetActiveScalars("Label");
  vtkFieldData* fields = output->GetFieldData();
  vtkMSEngineBridge::AddFieldValue<vtkIntArray>(fields, "Success", 1);
  vtkMSEngineBridge::AddStatistics(fields, result.Statistics, result.Status, result.Message);
  vtkMSEngineBridge::AddFieldValue<vtkIdTypeArray>(
    fields, "Seed", static_cast<vtkIdType>(this->Seed));
  return 1;
}
