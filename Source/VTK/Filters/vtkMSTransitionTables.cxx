// SPDX-License-Identifier: BSD-3-Clause
#include "vtkMSTransitionTables.h"

#include "vtkMSEngineBridge.h"
#include "vtkMSLabelArrays.h"
#include "vtkMSPipeline.h"

#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkIdTypeArray.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkIntArray.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkStreamingDemandDrivenPipeline.h"
#include "vtkStringArray.h"
#include "vtkTable.h"

#include "Core/Index.h"
#include "Discrete/AdjacencyRules.h"
#include "Discrete/ExampleAnalysis.h"
#include "Discrete/Infallibility.h"

vtkStandardNewMacro(vtkMSTransitionTables);

vtkMSTransitionTables::vtkMSTransitionTables()
{
  this->SetNumberOfOutputPorts(2);
  this->SetInputArrayToProcess(0, 0, 0, vtkDataObject::FIELD_ASSOCIATION_POINTS, "Label");
}

int vtkMSTransitionTables::FillInputPortInformation(int, vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkImageData");
  return 1;
}

int vtkMSTransitionTables::RequestUpdateExtent(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  vtkInformation* inInfo = inputVector[0]->GetInformationObject(0);
  vtkMSPipeline::RequestWholeExtentOnPieceZero(inInfo, vtkMSPipeline::UpdatePiece(outInfo));
  return 1;
}

namespace
{
template <typename ArrayT>
vtkSmartPointer<ArrayT> NewColumn(const char* name, int components = 1)
{
  auto array = vtkSmartPointer<ArrayT>::New();
  array->SetName(name);
  array->SetNumberOfComponents(components);
  return array;
}
} // namespace

namespace
{
/// Port 0: the allowed pairs per axis (Eq. 3.2 counts), and as 2-component arrays in @p pairs.
void FillTransitions(vtkTable* transitions, const msynth::ExampleAnalysis& analysis,
  vtkSmartPointer<vtkIntArray> (&pairs)[3])
{
  const auto& values = analysis.Labels();
  static const char* const directions[3] = { "+x", "+y", "+z" };
  auto axis = NewColumn<vtkIntArray>("Axis");
  auto direction = NewColumn<vtkStringArray>("Direction");
  auto from = NewColumn<vtkIntArray>("From");
  auto to = NewColumn<vtkIntArray>("To");
  auto count = NewColumn<vtkIdTypeArray>("Count");
  pairs[0] = NewColumn<vtkIntArray>("TransitionsX", 2);
  pairs[1] = NewColumn<vtkIntArray>("TransitionsY", 2);
  pairs[2] = NewColumn<vtkIntArray>("TransitionsZ", 2);
  for (int a = 0; a < 3; ++a)
  {
    for (const auto& t : analysis.Transitions(a))
    {
      const int b = values[msynth::ToIndex(t.From)];
      const int c = values[msynth::ToIndex(t.To)];
      axis->InsertNextValue(a);
      direction->InsertNextValue(directions[a]);
      from->InsertNextValue(b);
      to->InsertNextValue(c);
      count->InsertNextValue(static_cast<vtkIdType>(t.Count));
      const int tuple[2] = { b, c };
      pairs[a]->InsertNextTypedTuple(tuple);
    }
  }
  transitions->AddColumn(axis);
  transitions->AddColumn(direction);
  transitions->AddColumn(from);
  transitions->AddColumn(to);
  transitions->AddColumn(count);
}

/// Port 1: the labels, their counts and frequencies over @p sites.
void FillLabels(vtkTable* labels, const msynth::ExampleAnalysis& analysis, double sites)
{
  const auto& values = analysis.Labels();
  auto label = NewColumn<vtkIntArray>("Label");
  auto index = NewColumn<vtkIntArray>("Index");
  auto labelCount = NewColumn<vtkIdTypeArray>("Count");
  auto frequency = NewColumn<vtkDoubleArray>("Frequency");
  for (int b = 0; b < analysis.NumberOfLabels(); ++b)
  {
    label->InsertNextValue(values[msynth::ToIndex(b)]);
    index->InsertNextValue(b);
    labelCount->InsertNextValue(static_cast<vtkIdType>(analysis.LabelCounts()[msynth::ToIndex(b)]));
    frequency->InsertNextValue(
      static_cast<double>(analysis.LabelCounts()[msynth::ToIndex(b)]) / sites);
  }
  labels->AddColumn(label);
  labels->AddColumn(index);
  labels->AddColumn(labelCount);
  labels->AddColumn(frequency);
}

/// The field data of both tables: labels, counts, pairs, the infallibility verdict (D§3.3.7)
/// for outputs shaped like the example (2D examples give 2D outputs), the example's file.
void AddTableFields(vtkTable* transitions, vtkTable* labels,
  const msynth::ExampleAnalysis& analysis, vtkImageData* input,
  const vtkSmartPointer<vtkIntArray> (&pairs)[3])
{
  vtkAbstractArray* label = labels->GetColumnByName("Label");
  vtkAbstractArray* labelCount = labels->GetColumnByName("Count");
  auto labelValues = NewColumn<vtkIntArray>("Labels");
  labelValues->DeepCopy(label);
  labelValues->SetName("Labels");
  auto labelCounts = NewColumn<vtkIdTypeArray>("LabelCounts");
  labelCounts->DeepCopy(labelCount);
  labelCounts->SetName("LabelCounts");
  int dims[3];
  input->GetDimensions(dims);
  const msynth::InfallibilityReport verdict =
    msynth::AnalyzeInfallibility(msynth::AdjacencyRules::FromExample(analysis),
      { { dims[0] > 1 ? 2 : 1, dims[1] > 1 ? 2 : 1, dims[2] > 1 ? 2 : 1 } });
  vtkNew<vtkIntArray> infallible;
  infallible->SetName("Infallible");
  infallible->InsertNextValue(verdict.Proved ? 1 : 0);
  vtkNew<vtkStringArray> explanation;
  explanation->SetName("InfallibilityExplanation");
  explanation->InsertNextValue(verdict.Explanation);
  vtkNew<vtkStringArray> recommendation;
  recommendation->SetName("Recommendation");
  recommendation->InsertNextValue(verdict.Recommendation);
  vtkNew<vtkIntArray> region; // the region size of the proof (or of the last region tried)
  region->SetName("InfallibilityRegion");
  region->SetNumberOfComponents(3);
  region->InsertNextTypedTuple(verdict.Region.data());
  for (vtkTable* table : { transitions, labels })
  {
    vtkFieldData* fd = table->GetFieldData();
    fd->AddArray(infallible);
    fd->AddArray(explanation);
    fd->AddArray(recommendation);
    fd->AddArray(region);
    fd->AddArray(labelValues);
    fd->AddArray(labelCounts);
    for (const auto& p : pairs)
    {
      fd->AddArray(p);
    }
    if (vtkAbstractArray* file = input->GetFieldData()->GetAbstractArray("ExampleFile"))
    {
      fd->AddArray(file);
    }
  }
}
} // namespace

int vtkMSTransitionTables::RequestData(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  vtkImageData* input = vtkImageData::GetData(inputVector[0], 0);
  vtkTable* transitions = vtkTable::GetData(outputVector, 0);
  vtkTable* labels = vtkTable::GetData(outputVector, 1);
  if (!input)
  {
    vtkErrorMacro(<< "No input image.");
    return 0;
  }
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  if (vtkMSPipeline::UpdatePiece(outInfo) > 0)
  {
    return 1; // piece 0 computes the tables (see class documentation)
  }
  // No (or an empty) selection, as when ParaView's domain has not seen the data yet: use the
  // point array "Label", else the active scalars.
  vtkDataArray* array =
    vtkMSLabelArrays::FindLabelArray(input, this->GetInputArrayToProcess(0, inputVector));
  if (!array)
  {
    vtkErrorMacro(<< "The input has no label array (expected an integer point array, by "
                     "default 'Label').");
    return 0;
  }
  std::string problem;
  if (!vtkMSLabelArrays::CheckLabelArray(input, array, problem))
  {
    vtkErrorMacro(<< problem);
    return 0;
  }

  msynth::ExampleAnalysis analysis;
  try
  {
    analysis = msynth::ExampleAnalysis::FromExample(vtkMSLabelArrays::ToLabelGrid(input, array));
  }
  catch (const std::exception& e)
  {
    vtkErrorMacro(<< "Example analysis failed: " << e.what());
    return 0;
  }
  vtkSmartPointer<vtkIntArray> pairs[3];
  FillTransitions(transitions, analysis, pairs);
  FillLabels(labels, analysis, static_cast<double>(input->GetNumberOfPoints()));
  AddTableFields(transitions, labels, analysis, input, pairs);
  return 1;
}

void vtkMSTransitionTables::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
}
