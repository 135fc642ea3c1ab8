// SPDX-License-Identifier: BSD-3-Clause
#include "vtkMSPatternSynthesis.h"

#include "vtkMSFieldData.h"
#include "vtkMSLabelArrays.h"
#include "vtkMSLabelCounts.h"
#include "vtkMSPipeline.h"
#include "vtkMSSynthesisRun.h"

#include "Core/Error.h"
#include "Discrete/DiscreteSynthesis.h"
#include "Formats/Tileset.h"
#include "Patterns/PatternQuality.h"
#include "Patterns/PatternSynthesis.h"

#include "Core/Index.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
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

#include <algorithm>
#include <string>
#include <vector>

vtkStandardNewMacro(vtkMSPatternSynthesis);

struct vtkMSPatternSynthesis::Cache
{
  vtkMSSynthesisCache<msynth::PatternResult> Run;
  std::vector<msynth::LabelGrid> Exemplars;
  std::vector<msynth::Stencil> SoftShapes;
};

vtkMSPatternSynthesis::vtkMSPatternSynthesis()
  : Cached(std::make_unique<Cache>())
{
  this->SetNumberOfInputPorts(3);
  this->SetNumberOfOutputPorts(1);
}

vtkMSPatternSynthesis::~vtkMSPatternSynthesis() = default;

int vtkMSPatternSynthesis::FillInputPortInformation(int port, vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkImageData");
  if (port == 0)
    info->Set(vtkAlgorithm::INPUT_IS_REPEATABLE(), 1);
  // Optional for the pipeline so that a missing exemplar is this filter's error, with its words.
  info->Set(vtkAlgorithm::INPUT_IS_OPTIONAL(), 1);
  return 1;
}

int vtkMSPatternSynthesis::RequestInformation(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  vtkMSPipeline::SetOutputLabelGrid(
    inputVector[0]->GetInformationObject(0), outInfo, this->OutputSize);
  vtkMSPipeline::SetTimeSteps(outInfo, msynth::ToIndex(this->Samples));
  outInfo->Set(CAN_HANDLE_PIECE_REQUEST(), 1);
  return 1;
}

int vtkMSPatternSynthesis::RequestUpdateExtent(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  // Inputs are exemplars, zones and fixed sites, not pieces of the output: piece 0 reads them
  // whole and does the work (in parallel, other pieces are empty).
  const int piece = vtkMSPipeline::UpdatePiece(outputVector->GetInformationObject(0));
  for (int port = 0; port < 3; ++port)
    for (int i = 0; i < inputVector[port]->GetNumberOfInformationObjects(); ++i)
      vtkMSPipeline::RequestWholeExtentOnPieceZero(
        inputVector[port]->GetInformationObject(i), piece);
  return 1;
}

namespace
{

/// An integer image's values: @p preferred, else `Label`, else the active scalars.
bool ReadIntegers(
  vtkImageData* image, const char* preferred, msynth::LabelGrid& grid, std::string& problem)
{
  vtkDataArray* selected = image->GetPointData()->GetArray(preferred);
  return vtkMSLabelArrays::ReadLabels(image, selected, grid, problem);
}

/// The image of @p sample: extent from @p size, spacing and origin as the pipeline asks, the
/// labels as scalars, and the SatisfiedSoft and LastChange arrays.
void FillOutput(vtkImageData* output, vtkInformation* outInfo, const int size[3],
  const msynth::PatternSample& sample)
{
  output->SetExtent(0, size[0] - 1, 0, size[1] - 1, 0, size[2] - 1);
  double spacing[3] = { 1, 1, 1 }, origin[3] = { 0, 0, 0 };
  outInfo->Get(vtkDataObject::SPACING(), spacing);
  outInfo->Get(vtkDataObject::ORIGIN(), origin);
  output->SetSpacing(spacing);
  output->SetOrigin(origin);
  vtkIntArray* labels = vtkMSLabelArrays::NewLabelArray(sample.Labels, "Label");
  output->GetPointData()->SetScalars(labels);
  labels->Delete();
  vtkNew<vtkIntArray> satisfied;
  satisfied->SetName("SatisfiedSoft");
  satisfied->SetNumberOfTuples(static_cast<vtkIdType>(sample.SatisfiedSoft.size()));
  for (std::size_t i = 0; i < sample.SatisfiedSoft.size(); ++i)
    satisfied->SetValue(static_cast<vtkIdType>(i), sample.SatisfiedSoft[i]);
  output->GetPointData()->AddArray(satisfied);
  vtkNew<vtkIdTypeArray> last;
  last->SetName("LastChange");
  last->SetNumberOfTuples(static_cast<vtkIdType>(sample.LastChange.size()));
  for (std::size_t i = 0; i < sample.LastChange.size(); ++i)
    last->SetValue(static_cast<vtkIdType>(i), static_cast<vtkIdType>(sample.LastChange[i]));
  output->GetPointData()->AddArray(last);
}

std::string MethodName(int method)
{
  return method == vtkMSPatternSynthesis::METROPOLIS_HASTINGS ? "mh"
    : method == vtkMSPatternSynthesis::CONSTRAINT_SOLVER      ? "csp"
                                                              : "blockss";
}

} // namespace

int vtkMSPatternSynthesis::RequestData(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  vtkImageData* output = vtkImageData::GetData(outInfo);
  if (vtkMSPipeline::UpdatePiece(outInfo) != 0)
  {
    output->Initialize(); // piece 0 holds the pattern
    return 1;
  }
  const int exemplarCount = inputVector[0]->GetNumberOfInformationObjects();
  if (exemplarCount == 0 && this->TilesetFile.empty())
  {
    vtkErrorMacro(<< "Pattern synthesis needs at least one exemplar or a tileset.");
    return 0;
  }
  std::vector<vtkDataObject*> inputs;
  std::vector<msynth::LabelGrid> exemplars;
  if (!this->ReadExemplars(inputVector[0], inputs, exemplars))
    return 0;
  msynth::PatternOptions options;
  options.Size = { { this->OutputSize[0], this->OutputSize[1], this->OutputSize[2] } };
  const std::int64_t sites = options.Size[0] * options.Size[1] * options.Size[2];
  if (!this->ParseLists(options))
    return 0;
  if (!this->ReadZonesAndFixed(inputVector, options, inputs))
    return 0;
  for (int a = 0; a < 3; ++a)
    options.Mirror[msynth::ToIndex(a)] = this->Mirror[a] != 0;
  options.Epsilon = this->Epsilon;
  options.Method = this->Method == METROPOLIS_HASTINGS ? msynth::PatternMethod::MetropolisHastings
    : this->Method == CONSTRAINT_SOLVER                ? msynth::PatternMethod::ConstraintSolver
                                                       : msynth::PatternMethod::BlockSS;
  options.Start =
    this->Start == SOLVER_START ? msynth::PatternStart::Solver : msynth::PatternStart::Random;
  options.Samples = this->Samples;
  options.BurnIn = this->BurnIn;
  options.Temperature = this->Temperature;
  options.WalkProbability = this->WalkProbability;
  options.FlipProbability = this->FlipProbability;
  options.MovesPerSample = this->MovesPerSample;
  options.MaxMoves = this->MaxMoves;
  options.Seed = static_cast<std::uint64_t>(this->Seed);
  options.Progress = vtkMSSynthesisRun::Progress(this);

  Cache& cache = *this->Cached;
  if (cache.Run.Fresh(this, inputs) || cache.Exemplars != exemplars)
  {
    cache.Run.Clear();
    const std::string what = "A pattern of " + std::to_string(sites) + " sites";
    if (!vtkMSSynthesisRun::Solve(
          this, what, [&]() { cache.Run.Result = msynth::SynthesizePattern(exemplars, options); }))
    {
      return 0;
    }
    if (cache.Run.Result.Status ==
      msynth::SynthesisStatus::Cancelled) // the one cancel path of the synthesis filters
    {
      output->Initialize();
      return vtkMSSynthesisRun::Report(this, msynth::SynthesisStatus::Cancelled, "") ? 1 : 0;
    }
    cache.Exemplars = std::move(exemplars);
    cache.SoftShapes = options.SoftFactors;
    cache.Run.Keep(this, inputs, true);
  }
  const msynth::PatternResult& result = cache.Run.Result;
  const std::size_t step = vtkMSPipeline::RequestedStep(outInfo, result.Samples.size());
  const msynth::PatternSample& sample = result.Samples[step];

  FillOutput(output, outInfo, this->OutputSize, sample);
  output->GetInformation()->Set(vtkDataObject::DATA_TIME_STEP(), static_cast<double>(step));

  this->AddFields(output->GetFieldData(), result, sample);
  return 1;
}

bool vtkMSPatternSynthesis::ReadExemplars(vtkInformationVector* exemplarPort,
  std::vector<vtkDataObject*>& inputs, std::vector<msynth::LabelGrid>& exemplars)
{
  std::string problem;
  for (int i = 0; i < exemplarPort->GetNumberOfInformationObjects(); ++i)
  {
    vtkImageData* image = vtkImageData::GetData(exemplarPort, i);
    msynth::LabelGrid grid;
    if (!image || !vtkMSLabelArrays::ReadLabels(image, nullptr, grid, problem))
    {
      vtkErrorMacro(<< "Exemplar " << i + 1 << " (" << vtkMSFieldData::ExampleName(image)
                    << "): " << (image ? problem : std::string("not an image")));
      return false;
    }
    inputs.push_back(image);
    exemplars.push_back(std::move(grid));
  }
  return true;
}

bool vtkMSPatternSynthesis::ParseLists(msynth::PatternOptions& options)
{
  try
  {
    options.SoftFactors = msynth::ParseStencils(this->SoftFactors);
    options.Blocks = this->BlockShapes.empty()
      ? msynth::BlockScheme(this->BlockScheme, this->OutputSize[2] > 1)
      : msynth::ParseStencils(this->BlockShapes);
    for (const auto& [zone, labels] : msynth::ParseZoneLists(this->ZoneTiles, "ZoneTiles"))
      options.ZoneTiles[zone] = labels;
    for (const auto& [zone, numbers] : msynth::ParseZoneLists(this->ZoneExemplars, "ZoneExemplars"))
      for (std::int32_t e : numbers)
        options.ZoneExemplars[zone].push_back(e - 1); // numbered from 1 in the interface
    options.MirrorMap = msynth::ParseMirrorSwaps(this->MirrorSwaps);
    msynth::Tileset tiles;
    if (!this->TilesetFile.empty())
    {
      tiles = msynth::ReadTilesetFile(this->TilesetFile, this->TilesetSubset);
      for (std::size_t a = 0; a < 3; ++a)
        for (const auto& [b, c] : tiles.Pairs[a])
          options.ExtraPairs[a].emplace_back(b, c);
    }
    if (!this->ConnectedTilesetFile.empty())
      tiles = msynth::ReadTilesetFile(this->ConnectedTilesetFile);
    const bool named = !this->TilesetFile.empty() || !this->ConnectedTilesetFile.empty();
    options.Connected =
      vtkMSLabelCounts::ReadConnected(this->Connected, named ? &tiles : nullptr, this->Path);
    msynth::LabelGrid::CheckDimensions(options.Size[0], options.Size[1], options.Size[2]);
  }
  catch (const msynth::Error& e)
  {
    vtkErrorMacro(<< e.what());
    return false;
  }
  return true;
}

bool vtkMSPatternSynthesis::ReadZonesAndFixed(vtkInformationVector** inputVector,
  msynth::PatternOptions& options, std::vector<vtkDataObject*>& inputs)
{
  std::string problem;
  const std::int64_t sites = options.Size[0] * options.Size[1] * options.Size[2];
  if (vtkImageData* zones = vtkImageData::GetData(inputVector[1], 0))
  {
    msynth::LabelGrid grid;
    if (!ReadIntegers(zones, "Zone", grid, problem))
    {
      vtkErrorMacro(<< "Zones (" << vtkMSFieldData::ExampleName(zones) << "): " << problem);
      return false;
    }
    options.SiteZone.resize(msynth::ToIndex(sites));
    msynth::GuideVolume stretch; // zones are stretched over the output as guides are
    stretch.Dims = grid.Dimensions();
    for (std::int64_t z = 0; z < options.Size[2]; ++z)
      for (std::int64_t y = 0; y < options.Size[1]; ++y)
        for (std::int64_t x = 0; x < options.Size[0]; ++x)
          options.SiteZone[msynth::ToIndex(x + options.Size[0] * (y + options.Size[1] * z))] =
            grid.Data()[msynth::ToIndex(stretch.CellOf({ { x, y, z } }, options.Size))];
    inputs.push_back(zones);
  }
  if (vtkImageData* fixed = vtkImageData::GetData(inputVector[2], 0))
  {
    msynth::LabelGrid grid;
    if (!ReadIntegers(fixed, "Label", grid, problem))
    {
      vtkErrorMacro(<< "Fixed sites (" << vtkMSFieldData::ExampleName(fixed) << "): " << problem);
      return false;
    }
    if (grid.Dimensions() != options.Size)
    {
      vtkErrorMacro(<< "Fixed sites (" << vtkMSFieldData::ExampleName(fixed) << "): the image has "
                    << grid.Size(0) << " x " << grid.Size(1) << " x " << grid.Size(2)
                    << " sites, the output " << options.Size[0] << " x " << options.Size[1] << " x "
                    << options.Size[2] << ".");
      return false;
    }
    options.Fixed = grid.Data();
    inputs.push_back(fixed);
  }
  return true;
}

void vtkMSPatternSynthesis::AddFields(
  vtkFieldData* fd, const msynth::PatternResult& result, const msynth::PatternSample& sample)
{
  const Cache& cache = *this->Cached;
  const std::size_t step = msynth::ToIndex(&sample - result.Samples.data());
  vtkMSFieldData::AddFieldValue<vtkIntArray>(fd, "Sample", static_cast<int>(step));
  vtkMSFieldData::AddFieldValue<vtkIntArray>(
    fd, "Samples", static_cast<int>(result.Samples.size()));
  vtkMSFieldData::AddFieldValue<vtkDoubleArray>(fd, "LogProbability", sample.LogProbability);
  vtkNew<vtkStringArray> shapes; // the soft shapes, for vtkMSCheckModel and statistics.json
  shapes->SetName("SoftShapes");
  std::string names;
  for (const msynth::Stencil& s : cache.SoftShapes)
  {
    vtkMSFieldData::AddFieldValue<vtkDoubleArray>(
      fd, ("KL_" + s.Name).c_str(), msynth::PatternKL(cache.Exemplars, sample.Labels, s));
    names += (names.empty() ? "" : ",") + s.Name;
  }
  shapes->InsertNextValue(names);
  fd->AddArray(shapes);
  vtkMSFieldData::AddFieldValue<vtkIdTypeArray>(fd, "SampleMoves", sample.Moves);
  vtkMSFieldData::AddFieldValue<vtkDoubleArray>(fd, "SampleSeconds", sample.Seconds);
  const std::pair<const char*, std::int64_t> counts[] = { { "Moves", result.Moves },
    { "WalkMoves", result.WalkMoves }, { "AnnealingMoves", result.AnnealingMoves },
    { "AcceptedAnnealingMoves", result.AcceptedAnnealingMoves },
    { "FirstValidMoves", result.FirstValidMoves }, { "HardFactors", result.HardFactors },
    { "SoftFactors", result.SoftFactors }, { "Tiles", result.Tiles },
    { "ReplacementBlocks", result.ReplacementBlocks } };
  for (const auto& [name, value] : counts)
    vtkMSFieldData::AddFieldValue<vtkIdTypeArray>(fd, name, static_cast<vtkIdType>(value));
  vtkMSFieldData::AddFieldValue<vtkDoubleArray>(fd, "FirstValidSeconds", result.FirstValidSeconds);
  vtkMSFieldData::AddFieldValue<vtkDoubleArray>(fd, "Seconds", result.Seconds);
  vtkMSLabelCounts::AddConnectedFields(fd, sample.Connected);
  if (sample.Connected.Requested)
    vtkMSFieldData::AddFieldValue<vtkDoubleArray>(fd, "NetworkSeconds", result.NetworkSeconds);
  vtkNew<vtkStringArray> method;
  method->SetName("Method");
  method->InsertNextValue(MethodName(this->Method));
  fd->AddArray(method);
  vtkMSFieldData::AddFieldValue<vtkIdTypeArray>(fd, "Seed", this->Seed);
}

void vtkMSPatternSynthesis::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "TilesetFile: " << this->TilesetFile << "\n";
  os << indent << "OutputSize: " << this->OutputSize[0] << " " << this->OutputSize[1] << " "
     << this->OutputSize[2] << "\n";
  os << indent << "SoftFactors: " << this->SoftFactors << "\n";
  os << indent << "Epsilon: " << this->Epsilon << "\n";
  os << indent << "BlockScheme: " << this->BlockScheme << "\n";
  os << indent << "BlockShapes: " << this->BlockShapes << "\n";
  os << indent << "Method: " << MethodName(this->Method) << "\n";
  os << indent << "Start: " << (this->Start == SOLVER_START ? "solver" : "random") << "\n";
  os << indent << "Samples: " << this->Samples << "\n";
  os << indent << "BurnIn: " << this->BurnIn << "\n";
  os << indent << "Seed: " << this->Seed << "\n";
  os << indent << "ZoneTiles: " << this->ZoneTiles << "\n";
  os << indent << "ZoneExemplars: " << this->ZoneExemplars << "\n";
  os << indent << "Mirror: " << this->Mirror[0] << " " << this->Mirror[1] << " " << this->Mirror[2]
     << "\n";
  os << indent << "MirrorSwaps: " << this->MirrorSwaps << "\n";
  os << indent << "Connected: " << this->Connected << "\n";
  os << indent << "ConnectedTilesetFile: " << this->ConnectedTilesetFile << "\n";
  os << indent << "Path: '" << this->Path << "'\n";
}
