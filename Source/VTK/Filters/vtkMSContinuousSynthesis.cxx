// SPDX-License-Identifier: BSD-3-Clause
#include "vtkMSContinuousSynthesis.h"

#include "vtkMSArrangementStorage.h"
#include "vtkMSEngineBridge.h"
#include "vtkMSFieldData.h"
#include "vtkMSLabelArrays.h"
#include "vtkMSPipeline.h"
#include "vtkMSPolyhedra.h"
#include "vtkMSSynthesisRun.h"

#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkIdTypeArray.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkIntArray.h"
#include "vtkMultiProcessController.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkSmartPointer.h"
#include "vtkStreamingDemandDrivenPipeline.h"
#include "vtkStringArray.h"

#include "Continuous/ContinuousSynthesis.h"
#include "Continuous/LatticeCounts.h"
#include "Continuous/ModelStructure.h"
#include "Core/Error.h"
#include "Core/Fnv.h"
#include "Core/Index.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <sstream>

struct vtkMSContinuousSynthesis::Cache
{
  vtkMSSynthesisCache<msynth::ContinuousSynthesisResult> Run;
  std::vector<msynth::CatalogSnapshot> Snapshots;
  msynth::ArrangementMeasures Measures;
};

vtkStandardNewMacro(vtkMSContinuousSynthesis);

vtkMSContinuousSynthesis::vtkMSContinuousSynthesis()
  : Cached(std::make_unique<Cache>())
{
  this->SetNumberOfInputPorts(3);
}

vtkMSContinuousSynthesis::~vtkMSContinuousSynthesis() = default;

void vtkMSContinuousSynthesis::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Seed: " << this->Seed << "\n";
  os << indent << "BlockSize: " << this->BlockSize << "\n";
  os << indent << "Attempts: " << this->Attempts << "\n";
  os << indent << "NumberOfThreads: " << this->NumberOfThreads << "\n";
  os << indent << "DistributeBlocks: " << this->DistributeBlocks << "\n";
  os << indent << "SiteOrder: " << this->SiteOrder << "\n";
  os << indent << "LabelChoice: " << this->LabelChoice << "\n";
  os << indent << "NumberOfSnapshots: " << this->NumberOfSnapshots << "\n";
  os << indent << "Grounded: " << this->Grounded << "\n";
  os << indent << "Thickness: " << this->Thickness << "\n";
  os << indent << "Overhang: " << this->Overhang << "\n";
  os << indent << "Connected: " << this->Connected << "\n";
  os << indent << "KeepProportions: " << this->KeepProportions << "\n";
  os << indent << "ExampleSizes: " << this->ExampleSizes << "\n";
  os << indent << "TargetFractions: " << this->TargetFractions << "\n";
  os << indent << "BlockCandidates: " << this->BlockCandidates << "\n";
  os << indent << "ModelCandidates: " << this->ModelCandidates << "\n";
  os << indent << "Mirror: " << this->Mirror[0] << " " << this->Mirror[1] << " " << this->Mirror[2]
     << "\n";
}

int vtkMSContinuousSynthesis::FillInputPortInformation(int port, vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), port == 2 ? "vtkImageData" : "vtkPolyData");
  if (port == 2)
    info->Set(vtkAlgorithm::INPUT_IS_OPTIONAL(), 1);
  return 1;
}

int vtkMSContinuousSynthesis::RequestInformation(
  vtkInformation*, vtkInformationVector**, vtkInformationVector* outputVector)
{
  vtkMSPipeline::SetTimeSteps(outputVector->GetInformationObject(0),
    this->NumberOfSnapshots > 0 ? msynth::ToIndex(this->NumberOfSnapshots) + 1 : 0);
  return 1;
}

namespace
{
/// Entries of a property list: separated by commas, semicolons or spaces.
std::vector<std::string> Entries(const char* text)
{
  std::string s = text ? text : "";
  for (char& c : s)
    c = c == ',' || c == ';' ? ' ' : c;
  std::istringstream in(s);
  std::vector<std::string> out;
  for (std::string e; in >> e;)
    out.push_back(e);
  return out;
}

/// The constraints of the filter's properties and guide input (msynth::Error on bad entries).
msynth::ContinuousConstraints Constraints(vtkMSContinuousSynthesis* self, vtkImageData* guide,
  const msynth::PolyhedralExample& ex, const msynth::PlaneFamilySet& families)
{
  msynth::ContinuousConstraints c;
  c.Grounded = self->GetGrounded();
  c.KeepProportions = self->GetKeepProportions();
  c.BlockCandidates = self->GetBlockCandidates();
  c.ModelCandidates = self->GetModelCandidates();
  for (const auto& e : Entries(self->GetThickness()))
    c.Thickness.push_back(msynth::ParseThickness(e, families, ex.TypeNames));
  for (const auto& e : Entries(self->GetOverhang()))
    c.Overhang.push_back(msynth::ParseObjectType(e, ex.TypeNames));
  for (const auto& e : Entries(self->GetConnected()))
    c.Connected.push_back(msynth::ParseConnected(e, ex.TypeNames));
  for (const auto& e : Entries(self->GetTargetFractions()))
  {
    const auto colon = e.rfind(':');
    char* end = nullptr;
    const double f = colon == std::string::npos ? 0 : std::strtod(e.c_str() + colon + 1, &end);
    if (colon == std::string::npos || end == e.c_str() + colon + 1 || *end != '\0')
      throw msynth::Error("TargetFractions: '" + e + "' is not TYPE:FRACTION");
    c.TargetFractions[msynth::ParseObjectType(e.substr(0, colon), ex.TypeNames)] = f;
  }
  if (guide)
  {
    msynth::ContinuousGuide g;
    int dims[3];
    guide->GetDimensions(dims);
    g.Dims = { { dims[0], dims[1], dims[2] } };
    for (auto& [suffix, weights] : vtkMSSynthesisRun::GuideWeights(guide))
      g.Weights[msynth::ParseObjectType(suffix, ex.TypeNames)] = std::move(weights);
    if (g.Weights.empty())
      throw msynth::Error("the guide has no point array Weight_<type> (a type number or name)");
    c.Guide = std::move(g);
  }
  return c;
}

/// What the ranks compare before they share blocks: the solver's properties and the
/// arrangement's size (never 0).
std::int64_t Fingerprint(
  vtkMSContinuousSynthesis* self, const msynth::PlaneArrangement& arrangement)
{
  std::ostringstream text;
  const int* mirror = self->GetMirror();
  text << self->GetSeed() << ' ' << self->GetBlockSize() << ' ' << self->GetAttempts() << ' '
       << self->GetSiteOrder() << ' ' << self->GetLabelChoice() << ' '
       << self->GetNumberOfSnapshots() << ' ' << self->GetGrounded() << ' '
       << self->GetKeepProportions() << ' ' << self->GetExampleSizes() << ' '
       << self->GetBlockCandidates() << ' ' << self->GetModelCandidates() << ' ' << mirror[0]
       << mirror[1] << mirror[2] << ' ' << arrangement.NumberOfVertices() << '|'
       << (self->GetThickness() ? self->GetThickness() : "") << '|'
       << (self->GetOverhang() ? self->GetOverhang() : "") << '|'
       << (self->GetConnected() ? self->GetConnected() : "") << '|'
       << (self->GetTargetFractions() ? self->GetTargetFractions() : "");
  const std::string bytes = text.str();
  return static_cast<std::int64_t>(msynth::Fnv1a(bytes.data(), bytes.size()) | 1);
}

/// Rank 0's example, arrangement parameters (its field data) and guide, on every rank.
void ShareInputs(vtkMultiProcessController* controller, vtkSmartPointer<vtkPolyData>& example,
  vtkSmartPointer<vtkPolyData>& arrangement, vtkSmartPointer<vtkImageData>& guide)
{
  const bool root = controller->GetLocalProcessId() == 0;
  int present[2] = { example ? 1 : 0, guide ? 1 : 0 };
  controller->Broadcast(present, 2, 0);
  if (!root)
    example = vtkSmartPointer<vtkPolyData>::New();
  if (present[0])
    controller->Broadcast(example, 0);
  vtkNew<vtkPolyData> parameters;
  if (root)
    parameters->GetFieldData()->ShallowCopy(arrangement->GetFieldData());
  controller->Broadcast(parameters, 0);
  if (!root)
    arrangement = parameters.Get();
  if (!present[1])
    guide = nullptr;
  else
  {
    if (!root)
      guide = vtkSmartPointer<vtkImageData>::New();
    controller->Broadcast(guide, 0);
  }
}

/// The arrangement rebuilt exactly from its field data, checked against the example, and the
/// solver run on it; @p shared: with the blocks spread over the ranks.
msynth::ContinuousSynthesisResult Solve(vtkMSContinuousSynthesis* self, vtkPolyData* example,
  vtkPolyData* arrangementData, vtkImageData* guide, bool shared,
  std::vector<msynth::CatalogSnapshot>& snapshots, msynth::ArrangementMeasures& measures)
{
  const auto record = vtkMSArrangementStorage::LoadArrangement(arrangementData->GetFieldData(),
    vtkMSFieldData::ExampleName(arrangementData) + " (arrangement)");
  msynth::PolyhedralExample ex;
  const auto analysis = vtkMSPolyhedra::AnalyzeExample(
    example, record.AngleToleranceDegrees, record.MaximumSmallInteger, ex);
  if (analysis.Families().AllNormals() != record.Normals)
  {
    throw msynth::Error(
      ex.Source + ": the arrangement was built from another example (its plane families differ)");
  }
  msynth::ArrangementParameters parameters = record.Parameters;
  parameters.Threads = static_cast<unsigned>(self->GetNumberOfThreads());
  const auto built = vtkMSArrangementStorage::SharedArrangement(analysis.Families(), parameters);
  const msynth::PlaneArrangement& arrangement = *built;
  if (arrangement.NumberOfVertices() != arrangementData->GetNumberOfPoints() &&
    !(shared && arrangementData->GetNumberOfPoints() == 0)) // ranks > 0: its parameters alone
  {
    throw msynth::Error(ex.Source + ": the arrangement input has " +
      std::to_string(arrangementData->GetNumberOfPoints()) + " points but its parameters give " +
      std::to_string(arrangement.NumberOfVertices()) + " vertices");
  }
  msynth::ContinuousSynthesisOptions options;
  options.Seed = static_cast<std::uint64_t>(self->GetSeed());
  options.BlockSize = self->GetBlockSize();
  options.Attempts = self->GetAttempts();
  options.Threads = self->GetNumberOfThreads();
  options.Choice =
    self->GetLabelChoice() == 1 ? msynth::LabelChoice::Frequency : msynth::LabelChoice::Uniform;
  if (options.Choice == msynth::LabelChoice::Frequency)
    options.LabelWeights = msynth::LatticeOccurrences(ex, analysis, parameters);
  if (self->GetExampleSizes())
    // Runs measured on the structure measure's voxels: half the smallest plane spacing.
    options.Runs = msynth::MeasureRuns(ex,
      msynth::StructureVoxel(
        vtkMSArrangementStorage::SmallestSpacing(arrangementData->GetFieldData()),
        std::max(analysis.High()[0] - analysis.Low()[0], analysis.High()[1] - analysis.Low()[1])));
  options.Snapshots = self->GetNumberOfSnapshots();
  options.Constraints = Constraints(self, guide, ex, analysis.Families());
  // Automatic: a part's end drawn next to the vertices it has decided, where sizes are
  // followed; growth from seeds keeps its own front.
  options.Order = self->GetSiteOrder() != vtkMSContinuousSynthesis::AUTOMATIC_ORDER
    ? static_cast<msynth::SiteOrder>(self->GetSiteOrder())
    : (!options.Runs.empty() && options.Constraints.Connected.empty()
          ? msynth::SiteOrder::ScanLine
          : msynth::SiteOrder::MinimumEntropy);
  const int* mirror = self->GetMirror();
  options.MirrorAxes = (mirror[0] ? 1 : 0) | (mirror[1] ? 2 : 0) | (mirror[2] ? 4 : 0);
  snapshots.clear();
  options.OnSnapshot = [&snapshots](const msynth::CatalogSnapshot& s) { snapshots.push_back(s); };
  options.Progress = vtkMSSynthesisRun::Progress(self);
  if (shared)
    options.Exchange = vtkMSSynthesisRun::ProcessExchange(Fingerprint(self, arrangement));
  auto result = msynth::SynthesizeContinuous(analysis, arrangement, options);
  if (result.Succeeded())
    measures = msynth::MeasureArrangement(analysis, arrangement, result.Labels);
  return result;
}
} // namespace

int vtkMSContinuousSynthesis::RequestData(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  vtkPolyData* example = vtkPolyData::GetData(inputVector[0], 0);
  vtkPolyData* arrangementData = vtkPolyData::GetData(inputVector[1], 0);
  vtkPolyData* output = vtkPolyData::GetData(outputVector, 0);
  vtkImageData* guide = vtkImageData::GetData(inputVector[2], 0);
  if (!arrangementData)
  {
    vtkErrorMacro(
      << "no arrangement input (port 1): connect the ModelSynth Plane Arrangement filter");
    return 0;
  }
  Cache& cache = *this->Cached;
  bool fresh = cache.Run.Fresh(this, { example, arrangementData, guide });
  vtkMultiProcessController* controller = vtkMultiProcessController::GetGlobalController();
  bool together = false; // the ranks solve together
  if (this->DistributeBlocks && controller && controller->GetNumberOfProcesses() > 1)
  {
    // Rank 0 holds the arrangement and decides for every rank: they solve together, or not.
    const bool root = controller->GetLocalProcessId() == 0;
    int go = root && fresh && arrangementData->GetNumberOfPoints() > 0 ? 1 : 0;
    controller->Broadcast(&go, 1, 0);
    together = go != 0;
    if (together)
    {
      vtkSmartPointer<vtkPolyData> ex = example, parameters = arrangementData;
      vtkSmartPointer<vtkImageData> g = guide;
      ShareInputs(controller, ex, parameters, g);
      if (!root) // its share of the blocks; the model is output by rank 0
      {
        std::vector<msynth::CatalogSnapshot> snapshots;
        msynth::ArrangementMeasures measures;
        return vtkMSSynthesisRun::Solve(this, "Synthesis (a share of the blocks)",
                 [&]() { Solve(this, ex, parameters, g, true, snapshots, measures); })
          ? 1
          : 0;
      }
    }
    else if (!root)
      return 1;
  }
  else if (vtkMSPipeline::UpdatePiece(outputVector->GetInformationObject(0)) > 0 &&
    arrangementData->GetNumberOfPoints() == 0)
  {
    return 1; // in parallel, the arrangement lives on piece 0
  }
  if (fresh)
  {
    cache.Run.Clear();
    const std::string what = "Synthesis on an arrangement of " +
      std::to_string(arrangementData->GetNumberOfPoints()) + " vertices";
    if (!vtkMSSynthesisRun::Solve(this, what,
          [&]()
          {
            cache.Run.Result = Solve(
              this, example, arrangementData, guide, together, cache.Snapshots, cache.Measures);
          }))
    {
      return 0;
    }
    cache.Run.Keep(this, { example, arrangementData, guide }, cache.Run.Result.Succeeded());
  }
  const auto& result = cache.Run.Result;
  if (!vtkMSSynthesisRun::Report(
        this, result.Status, result.Message, vtkMSFieldData::ExampleName(example)))
  {
    return 0;
  }
  this->FillOutput(arrangementData, output, outputVector->GetInformationObject(0));
  return 1;
}

void vtkMSContinuousSynthesis::FillOutput(
  vtkPolyData* arrangementData, vtkPolyData* output, vtkInformation* outInfo)
{
  const Cache& cache = *this->Cached;
  const auto& result = cache.Run.Result;
  output->ShallowCopy(arrangementData);
  const vtkIdType n = arrangementData->GetNumberOfPoints();
  vtkNew<vtkIntArray> label;
  label->SetName("Label");
  label->SetNumberOfValues(n);
  for (vtkIdType v = 0; v < n; ++v)
  {
    label->SetValue(v, result.Labels[msynth::ToIndex(v)]);
  }
  if (cache.Snapshots.empty())
  {
    // The finished model: one label possible everywhere.
    vtkMSSynthesisRun::AddCatalog(output, std::vector<std::int32_t>(msynth::ToIndex(n), 1),
      std::vector<float>(msynth::ToIndex(n), 0.0f));
  }
  else
  {
    const std::size_t step = vtkMSPipeline::RequestedStep(outInfo, cache.Snapshots.size());
    const auto& snap = cache.Snapshots[step];
    for (vtkIdType v = 0; v < n; ++v)
    {
      const msynth::Label l = snap.Labels[msynth::ToIndex(v)];
      label->SetValue(v, l == msynth::CatalogSnapshot::Undecided ? vtkMSLabelArrays::Undecided : l);
    }
    vtkMSSynthesisRun::AddCatalog(output, snap.CatalogSize, snap.Entropy);
    vtkMSSynthesisRun::AddStep(output, snap.Step, snap.Block, snap.Assignments);
    output->GetInformation()->Set(vtkDataObject::DATA_TIME_STEP(), static_cast<double>(step));
    // The finished model at every time step, so that mesh extraction downstream does not
    // depend on the time shown.
    vtkNew<vtkIntArray> model;
    model->SetName("ModelLabel");
    model->SetNumberOfValues(n);
    for (vtkIdType v = 0; v < n; ++v)
    {
      model->SetValue(v, result.Labels[msynth::ToIndex(v)]);
    }
    output->GetPointData()->AddArray(model);
  }
  output->GetPointData()->AddArray(label);
  output->GetPointData()->SetActiveScalars("Label");
  vtkFieldData* fields = output->GetFieldData();
  vtkMSFieldData::AddFieldValue<vtkIntArray>(fields, "Success", 1);
  vtkMSFieldData::AddStatistics(fields, result.Statistics, result.Status, result.Message);
  vtkMSFieldData::AddFieldValue<vtkIdTypeArray>(fields, "Seed", static_cast<vtkIdType>(this->Seed));
  vtkMSFieldData::AddFieldValue<vtkDoubleArray>(fields, "BlockSize", result.BlockSize);
  vtkMSFieldData::AddFieldValue<vtkStringArray>(fields, "SiteOrder",
    result.Order == msynth::SiteOrder::ScanLine
      ? "scanline"
      : (result.Order == msynth::SiteOrder::Random ? "random" : "entropy"));
  const auto& m = cache.Measures;
  vtkMSFieldData::AddFieldValue<vtkIdTypeArray>(
    fields, "Components", static_cast<vtkIdType>(m.Components));
  vtkMSFieldData::AddFieldValue<vtkIdTypeArray>(
    fields, "GroundedComponents", static_cast<vtkIdType>(m.GroundedComponents));
  vtkMSFieldData::AddFieldValue<vtkIdTypeArray>(
    fields, "FloatingPartsRemoved", static_cast<vtkIdType>(result.FloatingPartsRemoved));
  vtkMSFieldData::AddFieldValue<vtkIdTypeArray>(
    fields, "NarrowPartsRemoved", static_cast<vtkIdType>(result.NarrowPartsRemoved));
  vtkMSFieldData::AddFieldValue<vtkIdTypeArray>(
    fields, "PartsBeyondSeedsRemoved", static_cast<vtkIdType>(result.PartsBeyondSeedsRemoved));
  vtkMSFieldData::AddFieldValue<vtkIdTypeArray>(
    fields, "ProportionPartsRemoved", static_cast<vtkIdType>(result.ProportionPartsRemoved));
  vtkMSFieldData::AddFieldValue<vtkDoubleArray>(
    fields, "ProportionVolumeRemoved", result.ProportionVolumeRemoved);
  vtkMSFieldData::AddFieldValue<vtkIdTypeArray>(
    fields, "ProportionBlocksRedrawn", static_cast<vtkIdType>(result.ProportionBlocksRedrawn));
  vtkMSFieldData::AddFieldValue<vtkStringArray>(
    fields, "ProportionsOutside", result.ProportionsOutside);
  for (const auto& [type, share] : m.TypeShares)
    vtkMSFieldData::AddFieldValue<vtkDoubleArray>(
      fields, ("TypeShare_" + std::to_string(type)).c_str(), share);
  if (result.ModelChosen >= 0)
  {
    vtkMSFieldData::AddFieldValue<vtkIntArray>(fields, "ModelChosen", result.ModelChosen);
    vtkMSFieldData::AddFieldValue<vtkDoubleArray>(fields, "MatchError", result.MatchError);
  }
}

std::string vtkMSContinuousSynthesis::CheckConstraints(
  vtkPolyData* example, double angleToleranceDegrees, int maximumSmallInteger)
{
  if (!example)
    return "no example to check the constraints against";
  try
  {
    msynth::PolyhedralExample ex;
    const auto analysis =
      vtkMSPolyhedra::AnalyzeExample(example, angleToleranceDegrees, maximumSmallInteger, ex);
    Constraints(this, nullptr, ex, analysis.Families());
  }
  catch (const std::exception& e)
  {
    return e.what();
  }
  return std::string();
}
