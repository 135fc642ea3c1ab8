// SPDX-License-Identifier: BSD-3-Clause
#include "vtkMSCheckModel.h"

#include "vtkMSCheckKinds.h"
#include "vtkMSFieldData.h"
#include "vtkMSLabelArrays.h"
#include "vtkMSPipeline.h"
#include "vtkMSPolyhedra.h"

#include "vtkDataArray.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkIdTypeArray.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkIntArray.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPolyData.h"
#include "vtkStreamingDemandDrivenPipeline.h"
#include "vtkStringArray.h"

#include "Continuous/ContinuousMesh.h"
#include "Core/Error.h"
#include "Core/Index.h"
#include "Discrete/ConsistencyCheck.h"
#include "Discrete/TimeVarying.h"
#include "Formats/Tileset.h"
#include "Patterns/PatternQuality.h"

#include <algorithm>
#include <cmath>
#include <exception>

vtkStandardNewMacro(vtkMSCheckModel);

/// What a time-varying check collects over the executions of one update.
struct vtkMSCheckModel::TimeFrames
{
  std::size_t Step = 0;  ///< the execution under way
  std::size_t Steps = 1; ///< executions in all: the most time steps of model and example
  int Retries = 0;       ///< executions of this step whose inputs came at another time
  std::vector<double> ModelTimes, ExampleTimes;
  msynth::TimeVaryingGrid Model, Example;
};

vtkMSCheckModel::vtkMSCheckModel()
  : Frames(new TimeFrames)
{
  this->SetNumberOfInputPorts(2);
}

vtkMSCheckModel::~vtkMSCheckModel() = default;

int vtkMSCheckModel::FillInputPortInformation(int port, vtkInformation* info)
{
  info->Remove(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE());
  info->Append(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkImageData");
  info->Append(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkPolyData");
  if (port == 1)
  {
    info->Set(vtkAlgorithm::INPUT_IS_OPTIONAL(), 1);
    info->Set(vtkAlgorithm::INPUT_IS_REPEATABLE(), 1);
  }
  return 1;
}

int vtkMSCheckModel::RequestInformation(
  vtkInformation*, vtkInformationVector**, vtkInformationVector* outputVector)
{
  this->Frames->Step = 0; // a new pipeline pass starts with the first time step
  this->Frames->Retries = 0;
  if (this->TimeVarying) // one verdict for every time step together
  {
    outputVector->GetInformationObject(0)->Remove(vtkStreamingDemandDrivenPipeline::TIME_STEPS());
    outputVector->GetInformationObject(0)->Remove(vtkStreamingDemandDrivenPipeline::TIME_RANGE());
  }
  return 1;
}

namespace
{
/// Whether @p data is time step @p time (true when it does not say which it is).
bool Delivered(vtkDataObject* data, double time)
{
  vtkInformation* info = data ? data->GetInformation() : nullptr;
  return !info || !info->Has(vtkDataObject::DATA_TIME_STEP()) ||
    info->Get(vtkDataObject::DATA_TIME_STEP()) == time;
}

/// The time steps @p info announces (none: empty).
std::vector<double> TimeSteps(vtkInformation* info)
{
  const auto key = vtkStreamingDemandDrivenPipeline::TIME_STEPS();
  if (!info || !info->Has(key))
    return {};
  const double* t = info->Get(key);
  return std::vector<double>(t, t + info->Length(key));
}
} // namespace

int vtkMSCheckModel::RequestUpdateExtent(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector*)
{
  // The checks look at every site of the model and the examples.
  for (int port = 0; port < 2; ++port)
    for (int i = 0; i < inputVector[port]->GetNumberOfInformationObjects(); ++i)
      vtkMSPipeline::RequestWholeExtentOnPieceZero(inputVector[port]->GetInformationObject(i), 0);
  if (!this->TimeVarying)
    return 1;
  // A time-varying check executes once per time step, asking each input for its step.
  TimeFrames& f = *this->Frames;
  vtkInformation* example = inputVector[1]->GetInformationObject(0);
  f.ModelTimes = TimeSteps(inputVector[0]->GetInformationObject(0));
  f.ExampleTimes = this->ExampleTimeFromZ ? std::vector<double>() : TimeSteps(example);
  f.Steps = std::max<std::size_t>({ 1, f.ModelTimes.size(), f.ExampleTimes.size() });
  const auto key = vtkStreamingDemandDrivenPipeline::UPDATE_TIME_STEP();
  if (!f.ModelTimes.empty())
    inputVector[0]->GetInformationObject(0)->Set(
      key, f.ModelTimes[std::min(f.Step, f.ModelTimes.size() - 1)]);
  if (!f.ExampleTimes.empty())
    example->Set(key, f.ExampleTimes[std::min(f.Step, f.ExampleTimes.size() - 1)]);
  return 1;
}

namespace
{
/// The one string field data @p name of @p fd, "" when absent.
std::string Recorded(vtkFieldData* fd, const char* name)
{
  auto* a = vtkStringArray::SafeDownCast(fd ? fd->GetAbstractArray(name) : nullptr);
  return a && a->GetNumberOfValues() > 0 ? a->GetValue(0) : std::string();
}

/// One number of field data @p name, @p otherwise when absent.
double RecordedNumber(vtkFieldData* fd, const char* name, double otherwise)
{
  vtkDataArray* a = fd ? fd->GetArray(name) : nullptr;
  return a && a->GetNumberOfTuples() == 1 ? a->GetTuple1(0) : otherwise;
}

/// The first violations as arrays: ViolationSites, ViolationAxes, ViolationLabels; the verdict
/// @p valid (the pairs' and the other checks').
void AddViolations(vtkFieldData* out, const msynth::ConsistencyReport& report, bool valid)
{
  vtkNew<vtkIdTypeArray> sites;
  sites->SetName("ViolationSites");
  sites->SetNumberOfComponents(3);
  vtkNew<vtkIntArray> axes;
  axes->SetName("ViolationAxes");
  vtkNew<vtkIdTypeArray> times;
  times->SetName("ViolationTimes");
  vtkNew<vtkIntArray> labels;
  labels->SetName("ViolationLabels");
  labels->SetNumberOfComponents(2);
  std::vector<std::string> lines;
  for (const msynth::ConsistencyViolation& v : report.First)
  {
    const vtkIdType site[3] = { v.Site[0], v.Site[1], v.Site[2] };
    sites->InsertNextTypedTuple(site);
    axes->InsertNextValue(v.Axis);
    times->InsertNextValue(static_cast<vtkIdType>(v.Time));
    const int pair[2] = { v.From, v.To };
    labels->InsertNextTypedTuple(pair);
    lines.push_back(v.Describe());
  }
  vtkMSCheckKinds::AddVerdict(out, valid, report.Violations, report.PairsChecked, lines);
  out->AddArray(sites);
  out->AddArray(axes);
  out->AddArray(labels);
  if (!report.First.empty() && report.First.front().Time >= 0)
    out->AddArray(times);
}

/// KL_<shape> per shape of @p shapes and PatternLogProbability (PatternQuality.h).
void AddQuality(vtkFieldData* out, const std::vector<msynth::LabelGrid>& examples,
  const msynth::LabelGrid& model, const std::string& shapes, double epsilon)
{
  std::vector<msynth::Stencil> soft;
  for (const msynth::Stencil& s : msynth::ParseStencils(shapes))
  {
    vtkMSFieldData::AddFieldValue<vtkDoubleArray>(
      out, ("KL_" + s.Name).c_str(), msynth::PatternKL(examples, model, s));
    if (s.Offsets.size() > 2)
      soft.push_back(s);
  }
  vtkMSFieldData::AddFieldValue<vtkDoubleArray>(
    out, "PatternLogProbability", msynth::PatternLogProbability(examples, model, soft, epsilon));
}
} // namespace

bool vtkMSCheckModel::CheckLabels(
  vtkImageData* model, vtkInformationVector* examples, vtkFieldData* out)
{
  msynth::LabelGrid grid;
  std::string problem;
  if (!vtkMSLabelArrays::ReadLabels(model, nullptr, grid, problem))
  {
    vtkErrorMacro(<< "The model (" << vtkMSFieldData::ExampleName(model) << "): " << problem);
    return false;
  }
  std::vector<msynth::LabelGrid> grids;
  for (int i = 0; i < examples->GetNumberOfInformationObjects(); ++i)
  {
    vtkImageData* example = vtkImageData::GetData(examples, i);
    grids.emplace_back();
    if (!example || !vtkMSLabelArrays::ReadLabels(example, nullptr, grids.back(), problem))
    {
      vtkErrorMacro(<< "Example " << i + 1 << " ("
                    << (example ? vtkMSFieldData::ExampleName(example) : "not a label image")
                    << "): " << (example ? problem : "a label model needs label examples"));
      return false;
    }
  }
  vtkFieldData* fd = model->GetFieldData();
  const bool recorded = this->TilesetFile.empty() && grids.empty();
  const std::string tileset = recorded ? Recorded(fd, "TilesetFile") : this->TilesetFile;
  if (grids.empty() && tileset.empty())
  {
    vtkErrorMacro(<< "Nothing to check the model against: connect its example(s) or set a "
                     "TilesetFile.");
    return false;
  }
  msynth::ConsistencyReport report;
  try
  {
    std::array<std::vector<std::pair<int, int>>, 3> pairs;
    if (!tileset.empty())
      pairs = msynth::ReadTilesetFile(tileset,
        recorded ? Recorded(fd, "TilesetSubset") : this->TilesetSubset,
        recorded ? Recorded(fd, "TilesFolder") : this->TilesFolder)
                .Pairs;
    report = msynth::CheckConsistency(grids, pairs, grid, msynth::ToIndex(this->MaximumReported));
    // Counts and network: names of ConnectedTilesetFile, else of the tileset checked against.
    const bool own = !this->ConnectedTilesetFile.empty();
    vtkMSCheckKinds::NetworkRequest request{ this->Counts, this->Connected, this->Path,
      own ? this->ConnectedTilesetFile : tileset,
      own || !recorded ? this->TilesetSubset : Recorded(fd, "TilesetSubset"),
      own || !recorded ? this->TilesFolder : Recorded(fd, "TilesFolder"), {}, this->CountGuideFile,
      this->PinsFile, this->PinsEmptyFree };
    request.Source = !request.Tileset.empty() ? request.Tileset
      : examples->GetNumberOfInformationObjects() > 0
      ? vtkMSFieldData::ExampleName(vtkImageData::GetData(examples, 0))
      : std::string("the model");
    const bool kept = vtkMSCheckKinds::CheckNetwork(grid, request, out);
    AddViolations(out, report, report.Consistent && kept);
    // Shapes, else the soft shapes a pattern synthesis recorded.
    const std::string shapes = this->Shapes.empty() ? Recorded(fd, "SoftShapes") : this->Shapes;
    if (!shapes.empty())
      AddQuality(out, grids, grid, shapes, this->Epsilon);
  }
  catch (const std::exception& e)
  {
    vtkErrorMacro(<< e.what());
    return false;
  }
  return true;
}

bool vtkMSCheckModel::CheckContinuous(
  vtkPolyData* model, vtkInformationVector* examples, vtkFieldData* out)
{
  vtkPolyData* example = vtkPolyData::GetData(examples, 0);
  if (!example || examples->GetNumberOfInformationObjects() != 1)
  {
    vtkErrorMacro(<< "A continuous model is checked against one polyhedral example (port 1).");
    return false;
  }
  // The example analyzed with the direction snapping its arrangement used (recorded in the
  // model by the mesh filter; a rotated polygon's directions may have been snapped to fit exact
  // arithmetic), else the defaults.
  vtkFieldData* fd = model->GetFieldData();
  const double degrees = RecordedNumber(fd, "AngleTolerance", 0.01);
  const double largest = RecordedNumber(fd, "MaximumSmallInteger", 12);
  if (!(degrees > 0 && degrees <= 10) || !(largest >= 1 && largest <= 1000000))
  {
    vtkErrorMacro(<< "The model's AngleTolerance or MaximumSmallInteger is out of range.");
    return false;
  }
  try
  {
    msynth::PolyhedralExample ex;
    const msynth::PolyhedralAnalysis analysis =
      vtkMSPolyhedra::AnalyzeExample(example, degrees, static_cast<int>(largest), ex);
    const auto mesh = vtkMSPolyhedra::ToContinuousMesh(model, "the model");
    // Features are held to a fraction of the smallest plane spacing the mesh filter recorded.
    const double spacing = RecordedNumber(fd, "SmallestSpacing", 0);
    if (!(spacing >= 0) || !std::isfinite(spacing))
    {
      vtkErrorMacro(<< "The model's SmallestSpacing is out of range.");
      return false;
    }
    const auto report = msynth::CheckContinuousModel(analysis, mesh, ex.TypeNames, spacing);
    vtkMSCheckKinds::AddVerdict(out, report.Valid, report.Valid ? 0 : 1, 0,
      report.Valid ? std::vector<std::string>() : std::vector<std::string>{ report.Problem });
    vtkMSFieldData::AddFieldValue<vtkIntArray>(out, "Objects", report.Objects);
    vtkMSFieldData::AddFieldValue<vtkIntArray>(out, "DistinctLabels", report.DistinctLabels);
    vtkMSFieldData::AddFieldValue<vtkDoubleArray>(out, "SmallestFeature", report.SmallestFeature);
    vtkMSFieldData::AddFieldValue<vtkDoubleArray>(
      out, "SmallestFeatureFraction", spacing > 0 ? report.SmallestFeature / spacing : 0.0);
    // What a person sees (parts, their sizes, what they front) against the example.
    vtkMSCheckKinds::AddResemblance(out, ex, msynth::MeshToModel(mesh, ex.TypeNames), spacing);
  }
  catch (const std::exception& e)
  {
    vtkErrorMacro(<< e.what());
    return false;
  }
  return true;
}

bool vtkMSCheckModel::CheckOther(vtkImageData* model, vtkFieldData* out)
{
  try
  {
    const auto limit = msynth::ToIndex(this->MaximumReported);
    if (!this->SampleFile.empty())
    {
      vtkMSCheckKinds::PictureCheck check{ this->SampleFile, this->PatternSize,
        this->PatternSymmetry, this->PeriodicInput, this->Ground,
        { this->PeriodicOutput[0] != 0, this->PeriodicOutput[1] != 0 } };
      vtkMSCheckKinds::CheckPicture(model, check, limit, out);
    }
    else if (this->TilesetFile.empty())
      throw msynth::Error("A voxel model is checked against a voxel tileset: set TilesetFile.");
    else
      vtkMSCheckKinds::CheckVoxels(model, this->TilesetFile, this->TilesFolder, limit, out);
  }
  catch (const std::exception& e)
  {
    vtkErrorMacro(<< e.what());
    return false;
  }
  return true;
}

int vtkMSCheckModel::CheckTimeStep(
  vtkImageData* model, vtkInformationVector* examples, vtkInformation* request, vtkFieldData* out)
{
  TimeFrames& f = *this->Frames;
  try
  {
    const bool series = !this->ExampleTimeFromZ && !f.ExampleTimes.empty();
    if ((f.Step < f.ModelTimes.size() && !Delivered(model, f.ModelTimes[f.Step])) ||
      (series && f.Step < f.ExampleTimes.size() &&
        !Delivered(vtkDataObject::GetData(examples, 0), f.ExampleTimes[f.Step])))
    {
      // An input shared with another consumer (the synthesis reading the same series) was left
      // at that consumer's time step: ask again (nothing else moves it then).
      if (++f.Retries > 3)
        throw msynth::Error("Time step " + std::to_string(f.Step) +
          " of the model or the example did not arrive; give the check its own reader.");
      request->Set(vtkStreamingDemandDrivenPipeline::CONTINUE_EXECUTING(), 1);
      return 2;
    }
    f.Retries = 0;
    if (f.Step == 0)
      f.Model.Frames.clear(), f.Example.Frames.clear();
    std::string problem;
    msynth::LabelGrid grid;
    if (f.Step < std::max<std::size_t>(1, f.ModelTimes.size()) &&
      !vtkMSLabelArrays::ReadLabels(model, nullptr, grid, problem))
      throw msynth::Error("Frame " + std::to_string(f.Step) + " of the model: " + problem);
    if (!grid.Data().empty())
      f.Model.Frames.push_back(std::move(grid));
    const int connected = examples->GetNumberOfInformationObjects();
    for (int i = 0; i < connected && (f.Step == 0 || (series && f.Step < f.ExampleTimes.size()));
         ++i)
    {
      msynth::LabelGrid frame;
      vtkImageData* example = vtkImageData::GetData(examples, i);
      if (!example || !vtkMSLabelArrays::ReadLabels(example, nullptr, frame, problem))
        throw msynth::Error("Example " + std::to_string(i + 1) + ": " +
          (example ? problem : "a time-varying model needs label examples"));
      if (this->ExampleTimeFromZ)
        f.Example = msynth::TimeVaryingGrid::FromSlices(frame);
      else
        f.Example.Frames.push_back(std::move(frame));
    }
    if (++f.Step < f.Steps)
    {
      request->Set(vtkStreamingDemandDrivenPipeline::CONTINUE_EXECUTING(), 1);
      return 2;
    }
    request->Remove(vtkStreamingDemandDrivenPipeline::CONTINUE_EXECUTING());
    f.Step = 0;
    if (f.Example.Frames.empty())
      throw msynth::Error("Nothing to check the time-varying model against: connect its example.");
    const msynth::ConsistencyReport report =
      msynth::CheckTimeVarying(f.Example, f.Model, this->Loop);
    AddViolations(out, report, report.Consistent);
    vtkMSFieldData::AddFieldValue<vtkIntArray>(
      out, "Frames", static_cast<int>(f.Model.Frames.size()));
    vtkMSFieldData::AddFieldValue<vtkIntArray>(
      out, "ExampleFrames", static_cast<int>(f.Example.Frames.size()));
    return 1;
  }
  catch (const std::exception& e)
  {
    f.Step = 0;
    f.Retries = 0;
    request->Remove(vtkStreamingDemandDrivenPipeline::CONTINUE_EXECUTING());
    vtkErrorMacro(<< e.what());
    return 0;
  }
}

int vtkMSCheckModel::RequestData(
  vtkInformation* request, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  vtkDataObject* input = vtkDataObject::GetData(inputVector[0], 0);
  vtkDataObject* output = vtkDataObject::GetData(outputVector, 0);
  output->ShallowCopy(input);
  vtkNew<vtkFieldData> fields; // the model's own field data stays the input's
  fields->DeepCopy(input->GetFieldData());
  output->SetFieldData(fields);
  auto* image = vtkImageData::SafeDownCast(input);
  if (this->TimeVarying && image)
  {
    const int step = this->CheckTimeStep(image, inputVector[1], request, fields);
    if (step == 0)
      output->Initialize();
    return step == 0 ? 0 : 1;
  }
  const bool other = image && (!this->SampleFile.empty() || this->VoxelModel);
  const bool checked = other ? this->CheckOther(image, fields)
    : image                  ? this->CheckLabels(image, inputVector[1], fields)
            : this->CheckContinuous(vtkPolyData::SafeDownCast(input), inputVector[1], fields);
  if (!checked)
    output->Initialize(); // no verdict: no output
  return checked ? 1 : 0;
}

void vtkMSCheckModel::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "TilesetFile: " << this->TilesetFile << "\n";
  os << indent << "TilesetSubset: " << this->TilesetSubset << "\n";
  os << indent << "TilesFolder: " << this->TilesFolder << "\n";
  os << indent << "SampleFile: " << this->SampleFile << "\n";
  os << indent << "PatternSize: " << this->PatternSize << "\n";
  os << indent << "PatternSymmetry: " << this->PatternSymmetry << "\n";
  os << indent << "PeriodicInput: " << this->PeriodicInput << "\n";
  os << indent << "Ground: " << this->Ground << "\n";
  os << indent << "PeriodicOutput: " << this->PeriodicOutput[0] << " " << this->PeriodicOutput[1]
     << "\n";
  os << indent << "VoxelModel: " << this->VoxelModel << "\n";
  os << indent << "Counts: " << this->Counts << "\n";
  os << indent << "Connected: " << this->Connected << "\n";
  os << indent << "Path: " << this->Path << "\n";
  os << indent << "ConnectedTilesetFile: " << this->ConnectedTilesetFile << "\n";
  os << indent << "CountGuideFile: " << this->CountGuideFile << "\n";
  os << indent << "PinsFile: " << this->PinsFile << "\n";
  os << indent << "PinsEmptyFree: " << this->PinsEmptyFree << "\n";
  os << indent << "TimeVarying: " << this->TimeVarying << "\n";
  os << indent << "Loop: " << this->Loop << "\n";
  os << indent << "ExampleTimeFromZ: " << this->ExampleTimeFromZ << "\n";
  os << indent << "Shapes: " << this->Shapes << "\n";
  os << indent << "Epsilon: " << this->Epsilon << "\n";
  os << indent << "MaximumReported: " << this->MaximumReported << "\n";
}
