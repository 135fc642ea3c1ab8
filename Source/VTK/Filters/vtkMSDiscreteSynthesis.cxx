// SPDX-License-Identifier: BSD-3-Clause
#include "vtkMSDiscreteSynthesis.h"

#include "Discrete/InfallibleRefinement.h"
#include "vtkMSDiscreteSynthesisOptions.h"

#include "vtkMSEngineBridge.h"
#include "vtkMSFieldData.h"
#include "vtkMSLabelArrays.h"
#include "vtkMSLabelCounts.h"
#include "vtkMSPatternImage.h"
#include "vtkMSPipeline.h"
#include "vtkMSSynthesisRun.h"
#include "vtkMSTileImage.h"

#include "vtkDoubleArray.h"
#include "vtkExtentTranslator.h"
#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkIdTypeArray.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationIntegerRequestKey.h"
#include "vtkInformationIntegerVectorKey.h"
#include "vtkInformationStringVectorKey.h"
#include "vtkInformationVector.h"
#include "vtkIntArray.h"
#include "vtkMultiProcessController.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkStreamingDemandDrivenPipeline.h"
#include "vtkStringArray.h"

#include "Core/BlockDriver.h"
#include "Core/BlockSynthesis.h"
#include "Core/TextLists.h"
#include "Discrete/DiscreteSynthesis.h"
#include "Discrete/OverlappingModel.h"
#include "Formats/Image.h"
#include "Formats/Tileset.h"

#include "Core/Error.h"
#include "Core/Index.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <map>
#include <sstream>
#include <stdexcept>

using vtkMSDiscreteSynthesisOptions::BuildOptions;
using vtkMSDiscreteSynthesisOptions::ReadPins;
using vtkMSDiscreteSynthesisOptions::SizeOptions;

vtkStandardNewMacro(vtkMSDiscreteSynthesis);

/// The last run: its result and snapshots, and what it was computed from.
struct vtkMSDiscreteSynthesis::Internals
{
  vtkMSSynthesisCache<msynth::SynthesisResult> Cache;
  std::vector<msynth::CatalogSnapshot> Snapshots;
  msynth::Tileset Tiles; ///< the tileset of the last run, when TilesetFile is set
  /// The requested extent the last run computed (ComputeRequestedExtent); all -1: the world.
  std::array<int, 6> Extent{ { -1, -1, -1, -1, -1, -1 } };
  /// A streamed run under way (StreamWorld).
  struct StreamRequest
  {
    vtkIdType Thickness = 0;
    int First = 0;
    std::vector<msynth::BlockFailure> Kept;
    std::function<bool(vtkImageData*, int, int)> Receive;
    vtkImageData* Input = nullptr;
  };
  std::unique_ptr<StreamRequest> Stream;
  vtkImageData* CurrentSlab = nullptr; ///< the slab SlabEvent is about
};

int vtkMSDiscreteSynthesis::GetActiveSource() const
{
  if (this->Source != AUTOMATIC_SOURCE)
    return this->Source;
  if (!this->TilesetFile.empty())
    return TILESET_SOURCE;
  return this->SampleFile.empty() ? EXAMPLE_SOURCE : SAMPLE_SOURCE;
}

int vtkMSDiscreteSynthesis::GridSize(int axis) const
{
  if (this->GetActiveSource() != SAMPLE_SOURCE || axis == 2)
    return this->OutputSize[axis];
  // A picture of W pixels: W sites where it repeats, else W − N + 1 (the last window's pixels
  // end the row).
  return this->Translate[axis] ? this->OutputSize[axis]
                               : this->OutputSize[axis] - this->PatternSize + 1;
}

bool vtkMSDiscreteSynthesis::ProducesSubExtents() const
{
  return this->ComputeRequestedExtent && !this->HasRegion() &&
    this->GetActiveSource() != SAMPLE_SOURCE;
}

bool vtkMSDiscreteSynthesis::HasRegion() const
{
  for (int v : this->Region)
    if (v != 0)
      return true;
  return false;
}

vtkMSDiscreteSynthesis::vtkMSDiscreteSynthesis()
  : Internal(std::make_unique<Internals>())
{
  this->SetNumberOfInputPorts(3);
  this->SetNumberOfOutputPorts(2);
  this->SetInputArrayToProcess(0, 0, 0, vtkDataObject::FIELD_ASSOCIATION_POINTS, "Label");
}

vtkMSDiscreteSynthesis::~vtkMSDiscreteSynthesis() = default;

int vtkMSDiscreteSynthesis::FillInputPortInformation(int port, vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkImageData");
  // The guide (port 1) and the pinned sites (port 2) are optional; so is the example (port 0)
  // when a tileset or a sample gives the rules.
  (void)port;
  info->Set(vtkAlgorithm::INPUT_IS_OPTIONAL(), 1);
  return 1;
}

int vtkMSDiscreteSynthesis::FillOutputPortInformation(int port, vtkInformation* info)
{
  info->Set(vtkDataObject::DATA_TYPE_NAME(), port == 0 ? "vtkImageData" : "vtkPolyData");
  return 1;
}

vtkPolyData* vtkMSDiscreteSynthesis::GetGeometryOutput()
{
  return vtkPolyData::SafeDownCast(this->GetOutputDataObject(1));
}

namespace
{
/// Pieces as slabs across the axis whose blocks' phase digit changes slowest (X/Y/Z_SLAB_MODE),
/// as the engine orders the digits (PhaseDigitOrder: the axis of most block origins last): a
/// slab's dependency cone reaches least far along it (Core/WorldSchedule.h).
int PieceSplitMode(vtkMSDiscreteSynthesis* self)
{
  std::array<std::int64_t, 3> n{}, size{}, overlap{}, m{}, step{}, origins{};
  for (int a = 0; a < 3; ++a)
  {
    n[a] = self->GridSize(a);
    size[a] = self->GetBlockSize()[a];
    overlap[a] = self->GetBlockOverlap()[a];
  }
  msynth::BlockGeometry<3>(n, size, overlap, m, step);
  for (std::size_t a = 0; a < 3; ++a)
    origins[a] = static_cast<std::int64_t>(msynth::BlockStarts(n[a], m[a], step[a]).size());
  return msynth::PhaseDigitOrder<3>(origins, msynth::PhaseDigits::FewestOriginsFirst)[2];
}

/// What is wrong with axis @p a of @p self's Region in the grid @p grid (empty when nothing).
std::string RegionProblem(vtkMSDiscreteSynthesis* self, const int grid[3], int a)
{
  const int* r = self->GetRegion();
  const int lo = r[a], hi = r[a + 3];
  if (lo >= 0 && hi <= grid[a] && lo < hi)
    return std::string();
  std::string text = "Region";
  for (int i = 0; i < 6; ++i)
    text += " " + std::to_string(r[i]);
  const std::string axis(1, static_cast<char>('x' + a));
  return text + " is not a non-empty box inside OutputSize (x0 y0 z0 x1 y1 z1): " +
    (lo < 0            ? axis + "0 is below 0."
        : hi > grid[a] ? axis + "1 is past OutputSize's " + std::to_string(grid[a]) + "."
                       : axis + "0 is not below " + axis + "1.");
}
} // namespace

int vtkMSDiscreteSynthesis::RequestInformation(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  int grid[3];
  for (int a = 0; a < 3; ++a)
  {
    grid[a] = this->GridSize(a);
    if (grid[a] < 1)
    {
      vtkErrorMacro(<< "OutputSize must be at least 1 on every axis"
                    << (this->GetActiveSource() != SAMPLE_SOURCE
                           ? ""
                           : " and, for an image sample, PatternSize (" +
                             std::to_string(this->PatternSize) + ") in x and y")
                    << ", got " << this->OutputSize[0] << " " << this->OutputSize[1] << " "
                    << this->OutputSize[2] << ".");
      return 0;
    }
  }
  if (this->GetActiveSource() == SAMPLE_SOURCE && this->OutputSize[2] != 1)
  {
    vtkErrorMacro(<< "An image sample makes a 2D picture: OutputSize must be 1 in z, got "
                  << this->OutputSize[2] << ".");
    return 0;
  }
  if (this->HasRegion())
  {
    for (int a = 0; a < 3; ++a)
    {
      const int lo = this->Region[a], hi = this->Region[a + 3];
      const std::string problem = RegionProblem(this, grid, a);
      if (!problem.empty())
      {
        vtkErrorMacro(<< problem);
        return 0;
      }
      grid[a] = hi - lo;
    }
  }
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  vtkMSPipeline::SetOutputLabelGrid(inputVector[0]->GetInformationObject(0), outInfo, grid);
  if (this->HasRegion())
  {
    double spacing[3], origin[3];
    outInfo->Get(vtkDataObject::SPACING(), spacing);
    outInfo->Get(vtkDataObject::ORIGIN(), origin);
    for (int a = 0; a < 3; ++a)
      origin[a] += spacing[a] * this->Region[a];
    outInfo->Set(vtkDataObject::ORIGIN(), origin, 3);
  }
  if (this->GetActiveSource() != SAMPLE_SOURCE)
    outInfo->Remove(vtkMSPatternImage::PATTERN_PICTURE());
  else
  {
    const int pattern[3] = { this->PatternSize, this->Translate[0] != 0, this->Translate[1] != 0 };
    outInfo->Set(vtkMSPatternImage::PATTERN_PICTURE(), pattern, 3);
  }
  // A tileset model names its tileset, so Tile Image finds the images without one of its own.
  if (this->GetActiveSource() != TILESET_SOURCE)
    outInfo->Remove(vtkMSTileImage::TILESET());
  else
  {
    outInfo->Set(vtkMSTileImage::TILESET(), this->TilesetFile.c_str(), 0);
    outInfo->Set(vtkMSTileImage::TILESET(), this->TilesetSubset.c_str(), 1);
  }

  if (this->ProducesSubExtents())
  {
    outInfo->Set(CAN_PRODUCE_SUB_EXTENT(), 1);
    outInfo->Set(vtkExtentTranslator::UPDATE_SPLIT_MODE(), PieceSplitMode(this));
  }
  else
    outInfo->Remove(CAN_PRODUCE_SUB_EXTENT());
  vtkInformation* geometryInfo = outputVector->GetInformationObject(1);
  geometryInfo->Set(CAN_HANDLE_PIECE_REQUEST(), 1);
  vtkMSPipeline::SetTimeSteps(outInfo, 0);
  vtkMSPipeline::SetTimeSteps(geometryInfo, 0);
  if (this->CatalogSnapshotsPerBlock > 0)
  {
    const msynth::SynthesisOptions options = SizeOptions(this);
    const std::int64_t steps = msynth::CountSnapshots(options);
    try
    {
      msynth::CheckSnapshotMemory(options, static_cast<double>(this->MaximumSnapshotMemory));
    }
    catch (const std::exception& e)
    {
      vtkErrorMacro(<< e.what() << " (MaximumSnapshotMemory).");
      return 0;
    }
    vtkMSPipeline::SetTimeSteps(outInfo, msynth::ToIndex(steps));
    vtkMSPipeline::SetTimeSteps(geometryInfo, msynth::ToIndex(steps));
  }
  return 1;
}

int vtkMSDiscreteSynthesis::RequestUpdateExtent(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector*)
{
  // The solver needs the whole example, the whole guide and all the pins.
  for (int port = 0; port < 3; ++port)
  {
    vtkInformation* inInfo = inputVector[port]->GetInformationObject(0);
    if (!inInfo)
    {
      continue;
    }
    int whole[6];
    inInfo->Get(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), whole);
    inInfo->Set(vtkStreamingDemandDrivenPipeline::UPDATE_EXTENT(), whole, 6);
    inInfo->Set(vtkStreamingDemandDrivenPipeline::EXACT_EXTENT(), 1);
    // Every rank (pvbatch --mpi) gets all of it, so all can share the blocks.
    inInfo->Set(vtkStreamingDemandDrivenPipeline::UPDATE_PIECE_NUMBER(), 0);
    inInfo->Set(vtkStreamingDemandDrivenPipeline::UPDATE_NUMBER_OF_PIECES(), 1);
  }
  return 1;
}

namespace
{
/**
 * Under MPI every rank reads the whole example (RequestUpdateExtent) and runs the filter; the
 * blocks are spread only when every rank is about to synthesize from the same example, which
 * the ranks first agree on (a fingerprint of the example and the sizes), so no rank waits for
 * one that will not exchange.
 */
/// With ComputeRequestedExtent, the update extent asked of @p outInfo when it is smaller than
/// the world; else all -1.
std::array<int, 6> RequestedExtent(vtkMSDiscreteSynthesis* self, vtkInformation* outInfo)
{
  std::array<int, 6> none{ { -1, -1, -1, -1, -1, -1 } }, whole{}, update{};
  if (!self->ProducesSubExtents() ||
    !outInfo->Has(vtkStreamingDemandDrivenPipeline::UPDATE_EXTENT()))
    return none;
  outInfo->Get(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), whole.data());
  outInfo->Get(vtkStreamingDemandDrivenPipeline::UPDATE_EXTENT(), update.data());
  for (int a = 0; a < 3; ++a)
    if (update[2 * a] > update[2 * a + 1]) // an empty request: nothing smaller to compute
      return none;
  return update == whole ? none : update;
}

void SetUpExchange(
  vtkMSDiscreteSynthesis* self, vtkDataArray* labels, bool fresh, msynth::SynthesisOptions& options)
{
  vtkMultiProcessController* controller = vtkMultiProcessController::GetGlobalController();
  if (!self->GetDistributeBlocks() || !controller || controller->GetNumberOfProcesses() < 2)
    return;
  vtkIdType fingerprint = 0;
  if (fresh)
  {
    const int source = self->GetActiveSource();
    std::vector<msynth::Label> values;
    for (vtkIdType i = 0; labels && i < labels->GetNumberOfTuples(); ++i)
      values.push_back(static_cast<msynth::Label>(labels->GetTuple1(i)));
    fingerprint = static_cast<vtkIdType>(msynth::RunFingerprint(
      { source == vtkMSDiscreteSynthesis::TILESET_SOURCE ? self->GetTilesetFile() : "",
        source == vtkMSDiscreteSynthesis::SAMPLE_SOURCE ? self->GetSampleFile() : "" },
      values, options));
  }
  options.Exchange = vtkMSSynthesisRun::ProcessExchange(fingerprint);
}

/// What the example says of its labels goes with the model: its file, the text format's piece
/// names and trailer, a .vox palette (for vtkMSLabelGridWriter, the OpenVDB label_names); with
/// a tileset, the names of its labels.
void AddExampleFields(
  vtkFieldData* fd, vtkImageData* input, const char* tilesetFile, const msynth::Tileset* tiles)
{
  if (tiles)
  {
    // Label i is orientation k of a tile: its name as the tileset's images are named.
    vtkNew<vtkStringArray> names;
    names->SetName("TileNames");
    for (int b = 0; b < tiles->NumberOfLabels(); ++b)
      names->InsertNextValue(tiles->LabelName(b));
    fd->AddArray(names);
    vtkMSFieldData::AddFieldValue<vtkStringArray>(fd, "TilesetFile", std::string(tilesetFile));
    if (tiles->Voxel) // the table (tile, symmetry) per label
    {
      vtkMSFieldData::AddFieldValue<vtkStringArray>(fd, "TilesFolder", tiles->TilesFolder);
      vtkNew<vtkStringArray> tile;
      tile->SetName("LabelTile");
      vtkNew<vtkIntArray> symmetry;
      symmetry->SetName("LabelSymmetry");
      for (int b = 0; b < tiles->NumberOfLabels(); ++b)
      {
        const auto i = msynth::ToIndex(b);
        tile->InsertNextValue(tiles->Tiles[msynth::ToIndex(tiles->LabelTile[i])].Name);
        symmetry->InsertNextValue(tiles->LabelOrientation[i]);
      }
      fd->AddArray(tile);
      fd->AddArray(symmetry);
    }
  }
  for (const char* name :
    { "ExampleFile", "PieceLabels", "PieceNames", "TextModelTrailer", "PaletteRGBA" })
    if (vtkAbstractArray* array = input ? input->GetFieldData()->GetAbstractArray(name) : nullptr)
      fd->AddArray(array);
}
} // namespace

bool vtkMSDiscreteSynthesis::Solve(
  vtkImageData* input, vtkDataArray* labels, msynth::SynthesisOptions& options)
{
  Internals& run = *this->Internal;
  run.Snapshots.clear();
  if (options.SnapshotsPerBlock > 0)
    options.OnSnapshot = [&run](const msynth::CatalogSnapshot& snap)
    { run.Snapshots.push_back(snap); };
  const std::string what = "A " + std::to_string(this->OutputSize[0]) + " x " +
    std::to_string(this->OutputSize[1]) + " x " + std::to_string(this->OutputSize[2]) + " model";
  return vtkMSSynthesisRun::Solve(this, what,
    [&]()
    {
      if (this->GetActiveSource() == SAMPLE_SOURCE)
      {
        if (this->ViaInfallible)
          throw std::runtime_error("ViaInfallible needs a label-grid example, not a sample");
        this->SolveSample(options);
        return;
      }
      if (this->GetActiveSource() != TILESET_SOURCE)
      {
        const msynth::LabelGrid example = vtkMSLabelArrays::ToLabelGrid(input, labels);
        if (this->ViaInfallible)
        {
          if (this->HasRegion() || this->Internal->Extent[0] >= 0 || this->Internal->Stream)
            throw std::runtime_error("ViaInfallible makes the whole model: no region or stream");
          run.Cache.Result = msynth::SynthesizeViaInfallible(example, options);
          return;
        }
        const auto analysis = msynth::ExampleAnalysis::FromExample(example);
        options.Example = &example;
        run.Cache.Result = this->Run(msynth::AdjacencyRules::FromExample(analysis), options);
        return;
      }
      if (options.Choice == msynth::LabelChoice::Resemblance)
        throw std::runtime_error(
          "resemblance-weighted choice needs an example grid, not a tileset");
      if (this->ViaInfallible)
        throw std::runtime_error("ViaInfallible needs a label-grid example, not a tileset");
      run.Tiles =
        msynth::ReadTilesetFile(this->TilesetFile, this->TilesetSubset, this->TilesFolder);
      if (options.Rotate.Enabled && options.Rotate.Map.empty())
        options.Rotate.Map = run.Tiles.TurnMap(); // each tile turns to its next orientation
      for (int a = 0; a < 3; ++a) // a voxel tileset's images pair with their mirror images
      {
        auto& mirror = options.Symmetry[msynth::ToIndex(a)];
        if (run.Tiles.Voxel && mirror.Enabled && mirror.Map.empty())
          mirror.Map = run.Tiles.MirrorMap(a);
      }
      options.Counts = vtkMSLabelCounts::Read(this->Counts, &run.Tiles);
      options.Connected = vtkMSLabelCounts::ReadConnected(this->Connected, &run.Tiles, this->Path);
      const msynth::AdjacencyRules rules = run.Tiles.Rules();
      if (run.Tiles.Voxel)
        msynth::StartFromWholeModel(rules, options);
      run.Cache.Result = this->Run(rules, options);
    });
}

msynth::SynthesisResult vtkMSDiscreteSynthesis::Run(
  const msynth::AdjacencyRules& rules, const msynth::SynthesisOptions& options)
{
  if (const auto* stream = this->Internal->Stream.get())
  {
    if (this->HasRegion() || this->Internal->Extent[0] >= 0)
      throw std::runtime_error(
        "a streamed world is the whole world: clear Region and ComputeRequestedExtent");
    const msynth::StreamLayout layout = msynth::PlanStream(options, stream->Thickness);
    return msynth::SynthesizeStreamed(
      rules, msynth::UndecidedWorld(options), layout,
      [&](msynth::StreamChunk&& c)
      {
        msynth::SynthesisResult piece;
        piece.Status = msynth::SynthesisStatus::Succeeded;
        piece.Message = "slab " + std::to_string(c.Index) + " of a streamed world";
        piece.Model = std::move(c.Model);
        piece.LastBlock = std::move(c.LastBlock);
        piece.Statistics.BlocksFailed = static_cast<std::int64_t>(c.Failures.size());
        piece.Statistics.Failures = std::move(c.Failures);
        int extent[6];
        for (std::size_t a = 0; a < 3; ++a)
        {
          extent[2 * a] = static_cast<int>(c.Low[a]);
          extent[2 * a + 1] = static_cast<int>(c.High[a]) - 1;
        }
        vtkNew<vtkImageData> slab;
        this->FillOutput(stream->Input, slab, 0, piece, extent);
        return stream->Receive(slab, c.Index, layout.Chunks);
      },
      stream->First, stream->Kept);
  }
  const std::array<int, 6>& e = this->Internal->Extent;
  if (e[0] >= 0) // a requested extent of the world
    return msynth::SynthesizeRegion(
      rules, options, { { e[0], e[2], e[4] } }, { { e[1] + 1, e[3] + 1, e[5] + 1 } });
  if (!this->HasRegion())
    return msynth::Synthesize(rules, options);
  return msynth::SynthesizeRegion(rules, options,
    { { this->Region[0], this->Region[1], this->Region[2] } },
    { { this->Region[3], this->Region[4], this->Region[5] } });
}

void vtkMSDiscreteSynthesis::SolveSample(msynth::SynthesisOptions& options)
{
  if (options.Choice == msynth::LabelChoice::Resemblance)
    throw std::runtime_error("resemblance-weighted choice needs an example grid, not a sample");
  msynth::OverlappingOptions po;
  po.N = this->PatternSize;
  po.Symmetry = this->PatternSymmetry;
  po.PeriodicInput = this->PeriodicInput;
  po.Ground = this->Ground;
  const msynth::PatternSet patterns =
    msynth::ExtractPatterns(msynth::ReadImage(this->SampleFile), po, this->SampleFile);
  patterns.Configure(options, { { this->Translate[0] != 0, this->Translate[1] != 0 } });
  this->Internal->Cache.Result = this->Run(patterns.Rules(), options);
}

void vtkMSDiscreteSynthesis::FillOutput(vtkImageData* input, vtkImageData* output, std::size_t step,
  const msynth::SynthesisResult& result, const int e[6])
{
  const Internals& run = *this->Internal;
  const auto& size = result.Model.Dimensions();
  if (e[0] >= 0) // where the requested extent lies in the world
    output->SetExtent(e[0], e[1], e[2], e[3], e[4], e[5]);
  else
    output->SetExtent(0, static_cast<int>(size[0]) - 1, 0, static_cast<int>(size[1]) - 1, 0,
      static_cast<int>(size[2]) - 1);
  // The example's grid, or the unit grid at 0 for a tileset or a sample (as RequestInformation
  // says): the output may already hold the region's origin from the pipeline information.
  const double unit[3] = { 1, 1, 1 }, zero[3] = { 0, 0, 0 };
  output->SetSpacing(input ? input->GetSpacing() : unit);
  output->SetOrigin(input ? input->GetOrigin() : zero);
  if (this->HasRegion()) // the region where it lies in the world
  {
    double origin[3];
    output->GetOrigin(origin);
    const double* spacing = output->GetSpacing();
    for (int a = 0; a < 3; ++a)
      origin[a] += spacing[a] * this->Region[a];
    output->SetOrigin(origin);
  }
  vtkSmartPointer<vtkIntArray> label;
  label.TakeReference(vtkMSLabelArrays::NewLabelArray(result.Model, "Label"));
  output->GetPointData()->SetScalars(label);
  if (!run.Snapshots.empty())
  {
    const msynth::CatalogSnapshot& snap = run.Snapshots[step];
    for (std::size_t i = 0; i < snap.Labels.size(); ++i)
      label->SetValue(static_cast<vtkIdType>(i),
        snap.Labels[i] == msynth::CatalogSnapshot::Undecided ? vtkMSLabelArrays::Undecided
                                                             : snap.Labels[i]);
    vtkMSSynthesisRun::AddCatalog(output, snap.CatalogSize, snap.Entropy);
    vtkMSSynthesisRun::AddStep(output, snap.Step, snap.Block, snap.Assignments);
    output->GetInformation()->Set(vtkDataObject::DATA_TIME_STEP(), static_cast<double>(step));
  }
  vtkNew<vtkIntArray> lastBlock;
  lastBlock->SetName("LastBlock");
  lastBlock->SetNumberOfTuples(static_cast<vtkIdType>(result.LastBlock.size()));
  std::copy(result.LastBlock.begin(), result.LastBlock.end(), lastBlock->GetPointer(0));
  output->GetPointData()->AddArray(lastBlock);
  vtkFieldData* fd = output->GetFieldData();
  vtkMSFieldData::AddFieldValue<vtkIdTypeArray>(fd, "Seed", this->Seed);
  vtkMSFieldData::AddStatistics(fd, result.Statistics, result.Status, result.Message);
  vtkMSLabelCounts::AddFields(fd, result.Counts);
  vtkMSLabelCounts::AddConnectedFields(fd, result.Connected);
  AddExampleFields(fd, input, this->TilesetFile.c_str(),
    this->GetActiveSource() != TILESET_SOURCE ? nullptr : &run.Tiles);
  if (this->GetActiveSource() ==
    TILESET_SOURCE) // the labels' numbering depends on it (vtkMSTileImage)
    vtkMSFieldData::AddFieldValue<vtkStringArray>(fd, "TilesetSubset", this->TilesetSubset);
  if (this->GetActiveSource() == SAMPLE_SOURCE)
  {
    // What vtkMSPatternImage needs to compose the picture.
    vtkMSFieldData::AddFieldValue<vtkStringArray>(fd, "SampleFile", this->SampleFile);
    vtkMSFieldData::AddFieldValue<vtkIntArray>(fd, "PatternSize", this->PatternSize);
    vtkMSFieldData::AddFieldValue<vtkIntArray>(fd, "PatternSymmetry", this->PatternSymmetry);
    vtkMSFieldData::AddFieldValue<vtkIntArray>(fd, "PeriodicInput", this->PeriodicInput ? 1 : 0);
    vtkMSFieldData::AddFieldValue<vtkIntArray>(fd, "Ground", this->Ground ? 1 : 0);
    vtkNew<vtkIntArray> periodic;
    periodic->SetName("PeriodicOutput");
    periodic->InsertNextValue(this->Translate[0] != 0);
    periodic->InsertNextValue(this->Translate[1] != 0);
    fd->AddArray(periodic);
  }
}

namespace
{
/// Ends an armed stream with the update that streams (StreamNextUpdate).
template <class Request, class Cache>
struct StreamDisarm
{
  std::unique_ptr<Request>& Stream;
  Cache& Kept;
  ~StreamDisarm()
  {
    if (this->Stream)
    {
      this->Stream.reset();
      this->Kept.Clear(); // not the output's own result
    }
  }
};
template <class Request, class Cache>
StreamDisarm(std::unique_ptr<Request>&, Cache&) -> StreamDisarm<Request, Cache>;
} // namespace

int vtkMSDiscreteSynthesis::RequestData(
  vtkInformation* request, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  vtkImageData* input = vtkImageData::GetData(inputVector[0], 0);
  vtkImageData* guide = vtkImageData::GetData(inputVector[1], 0);
  vtkImageData* fixed = vtkImageData::GetData(inputVector[2], 0);
  vtkImageData* output = vtkImageData::GetData(outputVector, 0);
  const StreamDisarm disarm{ this->Internal->Stream, this->Internal->Cache };
  vtkDataArray* labels = nullptr;
  const int source = this->GetActiveSource();
  if (this->Source == AUTOMATIC_SOURCE && !this->TilesetFile.empty() && !this->SampleFile.empty())
  {
    vtkErrorMacro(<< "Set a TilesetFile or a SampleFile, not both (or choose one with SetSource).");
    return 0;
  }
  if ((source == TILESET_SOURCE && this->TilesetFile.empty()) ||
    (source == SAMPLE_SOURCE && this->SampleFile.empty()))
  {
    vtkErrorMacro(<< "The source is "
                  << (source == TILESET_SOURCE ? "a tileset" : "an image sample") << " but no "
                  << (source == TILESET_SOURCE ? "TilesetFile" : "SampleFile") << " is set.");
    return 0;
  }
  if (source == EXAMPLE_SOURCE)
  {
    if (!input)
    {
      vtkErrorMacro(<< "No input example (and no TilesetFile or SampleFile).");
      return 0;
    }
    // An empty selection (ParaView's domain before the data exists) falls back to "Label".
    labels = vtkMSLabelArrays::FindLabelArray(input, this->GetInputArrayToProcess(0, inputVector));
    std::string problem;
    if (!labels)
    {
      vtkErrorMacro(
        << "The example has no label array (an integer point array, by default 'Label').");
      return 0;
    }
    if (!vtkMSLabelArrays::CheckLabelArray(input, labels, problem))
    {
      vtkErrorMacro(<< "Bad example: " << problem);
      return 0;
    }
  }
  msynth::SynthesisOptions options;
  if (!BuildOptions(this, guide, options) || !ReadPins(this, fixed, options))
    return 0;
  const Internals& run = *this->Internal;
  auto& cache = this->Internal->Cache;
  const std::array<int, 6> extent = RequestedExtent(this, outputVector->GetInformationObject(0));
  const bool fresh =
    run.Stream || cache.Fresh(this, { input, guide, fixed }) || extent != run.Extent;
  this->Internal->Extent = extent;
  if (run.Stream)
    run.Stream->Input = input;
  else if (extent[0] < 0)
    SetUpExchange(this, labels, fresh, options);
  if (fresh)
  {
    cache.Clear();
    if (!this->Solve(input, labels, options))
      return 0;
    cache.Keep(this, { input, guide, fixed }, cache.Result.Succeeded());
  }
  if (!vtkMSSynthesisRun::Report(this, cache.Result.Status, cache.Result.Message))
    return 0;
  // The time step asked for (steps are 0, 1, 2, ...), on the port that asked.
  const std::size_t step = run.Snapshots.empty()
    ? 0
    : vtkMSPipeline::RequestedStep(
        vtkMSPipeline::RequestingPort(request, outputVector), run.Snapshots.size());
  this->FillOutput(input, output, step, cache.Result, run.Extent.data());
  std::string problem;
  // A voxel tileset's model shows its tiles' voxels, else the sites as voxels.
  vtkNew<vtkImageData> voxels;
  const bool tileVoxels =
    this->GetActiveSource() == TILESET_SOURCE && run.Tiles.Voxel && this->GenerateGeometry;
  if (tileVoxels && !vtkMSLabelArrays::TileVoxels(run.Tiles, output, voxels, problem))
  {
    output->Initialize();
    vtkErrorMacro(<< "The model's voxels: " << problem);
    return 0;
  }
  if (!vtkMSLabelArrays::FillGeometryPort(tileVoxels ? voxels.GetPointer() : output,
        this->GenerateGeometry, tileVoxels ? 0 : this->EmptyLabel,
        outputVector->GetInformationObject(1), problem))
  {
    output->Initialize();
    vtkErrorMacro(<< "The model's geometry: " << problem);
    return 0;
  }
  if (!run.Snapshots.empty())
    vtkPolyData::GetData(outputVector, 1)
      ->GetInformation()
      ->Set(vtkDataObject::DATA_TIME_STEP(), static_cast<double>(step));
  return 1;
}

void vtkMSDiscreteSynthesis::StreamNextUpdate(vtkIdType thickness, int first,
  const std::function<bool(vtkImageData*, int, int)>& receive,
  const std::vector<msynth::BlockFailure>& kept)
{
  auto request = std::make_unique<Internals::StreamRequest>();
  request->Thickness = thickness;
  request->First = first;
  request->Kept = kept;
  request->Receive = receive;
  this->Internal->Stream = std::move(request);
  this->Modified();
}

void vtkMSDiscreteSynthesis::StreamNextUpdate(vtkIdType thickness, int first)
{
  this->StreamNextUpdate(thickness, first,
    [this](vtkImageData* slab, int index, int count)
    {
      this->Internal->CurrentSlab = slab;
      this->CurrentSlabIndex = index;
      this->NumberOfSlabs = count;
      this->InvokeEvent(SlabEvent, &index);
      this->Internal->CurrentSlab = nullptr;
      return !this->AbortExecute;
    });
}

vtkImageData* vtkMSDiscreteSynthesis::GetCurrentSlab()
{
  return this->Internal->CurrentSlab;
}

void vtkMSDiscreteSynthesis::SetBoundaryFace(int face, int use)
{
  if (face >= 0 && face < 6 && this->BoundaryFaces[face] != use)
  {
    this->BoundaryFaces[face] = use;
    this->Modified();
  }
}

int vtkMSDiscreteSynthesis::GetBoundaryFace(int face) const
{
  return face >= 0 && face < 6 ? this->BoundaryFaces[face] : 0;
}

void vtkMSDiscreteSynthesis::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "OutputSize: " << this->OutputSize[0] << " " << this->OutputSize[1] << " "
     << this->OutputSize[2] << "\n";
  os << indent << "Region: " << this->Region[0] << " " << this->Region[1] << " " << this->Region[2]
     << " " << this->Region[3] << " " << this->Region[4] << " " << this->Region[5] << "\n";
  os << indent << "BlockSize: " << this->BlockSize[0] << " " << this->BlockSize[1] << " "
     << this->BlockSize[2] << "\n";
  os << indent << "AttemptsPerBlock: " << this->AttemptsPerBlock << "\n";
  os << indent << "BacktracksPerAttempt: " << this->BacktracksPerAttempt << "\n";
  os << indent << "RepairFailedBlocks: " << this->RepairFailedBlocks << "\n";
  os << indent << "BlockStart: " << this->BlockStart << "\n";
  os << indent << "Source: " << this->Source << "\n";
  os << indent << "ComputeRequestedExtent: " << this->ComputeRequestedExtent << "\n";
  os << indent << "BlocksWhenWholeFails: " << this->BlocksWhenWholeFails << "\n";
  os << indent << "ViaInfallible: " << this->ViaInfallible << "\n";
  os << indent << "Seed: " << this->Seed << "\n";
  os << indent << "LabelChoice: " << this->LabelChoice << "\n";
  os << indent << "SiteOrder: " << this->SiteOrder << "\n";
  os << indent << "Mirror: " << this->Mirror[0] << " " << this->Mirror[1] << " " << this->Mirror[2]
     << "\n";
  os << indent << "Translate: " << this->Translate[0] << " " << this->Translate[1] << " "
     << this->Translate[2] << " (period " << this->TranslationPeriod[0] << " "
     << this->TranslationPeriod[1] << " " << this->TranslationPeriod[2] << ", map '"
     << this->TranslationMap << "')\n";
  os << indent << "DistributeBlocks: " << this->DistributeBlocks << "\n";
  os << indent << "Rotate: " << this->Rotate << " (map '" << this->RotationMap << "')\n";
  os << indent << "GenerateGeometry: " << this->GenerateGeometry << " (EmptyLabel "
     << this->EmptyLabel << ")\n";
  os << indent << "TilesFolder: '" << this->TilesFolder << "'\n";
  os << indent << "Counts: '" << this->Counts << "'\n";
  os << indent << "Connected: '" << this->Connected << "'\n";
  os << indent << "Path: '" << this->Path << "'\n";
  os << indent << "SampleFile: '" << this->SampleFile << "' (pattern " << this->PatternSize
     << ", symmetry " << this->PatternSymmetry << ", periodic input " << this->PeriodicInput
     << ", ground " << this->Ground << ")\n";
}
