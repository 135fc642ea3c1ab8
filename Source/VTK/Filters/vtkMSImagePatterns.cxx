// SPDX-License-Identifier: BSD-3-Clause
#include "vtkMSImagePatterns.h"

#include "vtkDoubleArray.h"
#include "vtkIdTypeArray.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkIntArray.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkStreamingDemandDrivenPipeline.h"
#include "vtkStringArray.h"
#include "vtkTable.h"
#include "vtkUnsignedCharArray.h"

#include "Core/Index.h"
#include "Discrete/OverlappingModel.h"
#include "Formats/Image.h"

vtkStandardNewMacro(vtkMSImagePatterns);

vtkMSImagePatterns::vtkMSImagePatterns()
{
  this->SetNumberOfInputPorts(0);
  this->SetNumberOfOutputPorts(3);
}

int vtkMSImagePatterns::FillOutputPortInformation(int port, vtkInformation* info)
{
  info->Set(vtkDataObject::DATA_TYPE_NAME(), port == 0 ? "vtkImageData" : "vtkTable");
  return 1;
}

vtkTypeBool vtkMSImagePatterns::ProcessRequest(
  vtkInformation* request, vtkInformationVector** inInfo, vtkInformationVector* outInfo)
{
  if (request->Has(vtkDemandDrivenPipeline::REQUEST_INFORMATION()))
  {
    // The patterns' extent (N × N × k) before the data: a sample is small to read.
    msynth::PatternSet set;
    if (!this->Extract(set))
      return 0;
    const int n = set.Options.N;
    const int extent[6] = { 0, n - 1, 0, n - 1, 0, set.NumberOfPatterns() - 1 };
    outInfo->GetInformationObject(0)->Set(
      vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), extent, 6);
    return 1;
  }
  if (request->Has(vtkDemandDrivenPipeline::REQUEST_DATA()))
    return this->RequestData(request, inInfo, outInfo);
  return this->Superclass::ProcessRequest(request, inInfo, outInfo);
}

bool vtkMSImagePatterns::Extract(msynth::PatternSet& set)
{
  if (this->SampleFile.empty())
  {
    vtkErrorMacro(<< "No SampleFile.");
    return false;
  }
  try
  {
    msynth::OverlappingOptions o;
    o.N = this->PatternSize;
    o.Symmetry = this->PatternSymmetry;
    o.PeriodicInput = this->PeriodicInput;
    set = msynth::ExtractPatterns(msynth::ReadImage(this->SampleFile), o, this->SampleFile);
  }
  catch (const std::exception& e)
  {
    vtkErrorMacro(<< e.what());
    return false;
  }
  return true;
}

namespace
{
/// Port 0: slice z is pattern z, rows bottom first.
void FillPatterns(vtkImageData* image, const msynth::PatternSet& set)
{
  const int n = set.Options.N;
  image->SetDimensions(n, n, set.NumberOfPatterns());
  vtkNew<vtkUnsignedCharArray> rgba;
  rgba->SetName("RGBA");
  rgba->SetNumberOfComponents(4);
  rgba->SetNumberOfTuples(static_cast<vtkIdType>(n) * n * set.NumberOfPatterns());
  for (int t = 0; t < set.NumberOfPatterns(); ++t)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i)
        rgba->SetTypedTuple(
          (static_cast<vtkIdType>(t) * n + j) * n + i, set.Colours[set.At(t, i, n - 1 - j)].data());
  image->GetPointData()->SetScalars(rgba);
}

/// Port 1: the allowed pairs; port 2: the labels, counts and frequencies.
void FillTables(vtkTable* pairs, vtkTable* labels, const msynth::PatternSet& set)
{
  vtkNew<vtkIntArray> axis, from, to, label;
  vtkNew<vtkStringArray> direction;
  axis->SetName("Axis");
  direction->SetName("Direction");
  from->SetName("From");
  to->SetName("To");
  for (int a = 0; a < 2; ++a)
    for (const auto& p : set.Pairs[msynth::ToIndex(a)])
    {
      axis->InsertNextValue(a);
      direction->InsertNextValue(a == 0 ? "+x" : "+y");
      from->InsertNextValue(p.first);
      to->InsertNextValue(p.second);
    }
  pairs->AddColumn(axis);
  pairs->AddColumn(direction);
  pairs->AddColumn(from);
  pairs->AddColumn(to);
  vtkNew<vtkIdTypeArray> count;
  vtkNew<vtkDoubleArray> frequency;
  label->SetName("Label");
  count->SetName("Count");
  frequency->SetName("Frequency");
  double total = 0.0;
  for (const double c : set.Counts)
    total += c;
  for (int t = 0; t < set.NumberOfPatterns(); ++t)
  {
    label->InsertNextValue(t);
    count->InsertNextValue(static_cast<vtkIdType>(set.Counts[msynth::ToIndex(t)]));
    frequency->InsertNextValue(set.Counts[msynth::ToIndex(t)] / total);
  }
  labels->AddColumn(label);
  labels->AddColumn(count);
  labels->AddColumn(frequency);
}
} // namespace

int vtkMSImagePatterns::RequestData(
  vtkInformation*, vtkInformationVector**, vtkInformationVector* outputVector)
{
  msynth::PatternSet set;
  if (!this->Extract(set))
    return 0;
  FillPatterns(vtkImageData::GetData(outputVector, 0), set);
  FillTables(vtkTable::GetData(outputVector, 1), vtkTable::GetData(outputVector, 2), set);
  return 1;
}

void vtkMSImagePatterns::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "SampleFile: " << this->SampleFile << "\n";
  os << indent << "PatternSize: " << this->PatternSize << "\n";
  os << indent << "PatternSymmetry: " << this->PatternSymmetry << "\n";
  os << indent << "PeriodicInput: " << this->PeriodicInput << "\n";
}
