// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/**
 * @file Synthesize.h
 * @brief The options of `msynth synthesize`, shared by its two kinds: discrete synthesis of a
 * label grid, tileset or image sample (SynthesizeCommand.cxx) and continuous synthesis of a
 * polyhedral example (ContinuousCommand.cxx).
 */
#include "Examples.h" // for PolyhedralReading

#include <array>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

namespace CLI
{
class App;
class Option;
}
class vtkAlgorithm;
class vtkImageData;
class vtkMSDiscreteSynthesis;
class vtkMSLabelGridReader;
class vtkXMLImageDataReader;

namespace msynth
{
struct Tileset;
struct VoxModel;
namespace cli
{

struct SynthesizeOptions;
/// --via-infallible (AnalyzeCommand.cxx, beside analyze --infallible).
CLI::Option* AddViaInfallible(CLI::App& synthesize, SynthesizeOptions& o);

struct SynthesizeOptions
{
  std::string Example;
  std::string Out = "msynth-output";
  std::vector<double> Size; ///< sites (discrete) or example units (continuous)
  std::int64_t Seed = 0;
  int Attempts = 10;              ///< per block (continuous: default 20)
  std::int64_t Backtracks = 1000; ///< per attempt (discrete)
  bool NoRepair = false;          ///< no second try at failed blocks
  std::string Start;              ///< how blocks start: auto (empty), trivial, undecided, whole
  bool NoFallback = false;        ///< no blocks when the whole model fails
  bool ViaInfallible = false;     ///< Algorithm 3.1 on an infallible refinement (D§3.3.8)
  std::string Order;              ///< empty: scanline (discrete), automatic (continuous)
  std::string Choice = "uniform";
  int Snapshots = 0;
  // Discrete.
  std::array<int, 3> Size3{ { 0, 0, 0 } }; ///< Size in sites
  std::vector<int> Block{ 0, 0, 0 };
  std::vector<int> Overlap{ -1, -1, -1 };
  std::vector<int> Region{ 0, 0, 0, 0, 0, 0 };
  bool Stream = false; ///< compute the world slab by slab (StreamCommand.cxx)
  bool Resume = false; ///< resume an interrupted stream
  int Slab = 0;        ///< a stream's slab thickness in sites (0: automatic)
  int Threads = 0;
  std::vector<int> Ground, Empty; ///< at most one value each
  std::string Outputs;            ///< comma-separated kinds; empty: what the example calls for
  std::string Pieces;
  std::string Guide;
  std::string Fixed;           ///< pinned sites: a label grid of the output size, -1 free
  bool FixedEmptyFree = false; ///< label 0 of the pinned sites (a .vox's empty) is free too
  std::string Subset;
  std::string Tiles; ///< a voxel tileset's tiles folder ("" : beside the XML)
  std::vector<std::string> Targets;
  std::vector<std::string> Counts;
  std::vector<std::string> Path; ///< --path: sites x,y[,z] and labels the network joins
  double Temperature = 0.01;
  std::string Mirror, Translate; ///< sets of axes
  std::vector<std::string> Swaps, Shifts, Turns;
  std::vector<int> Period{ 0, 0, 0 };
  bool Rotate = false;
  // Image samples.
  int Pattern = 3;
  int Symmetry = 8;
  bool NoPeriodicInput = false;
  bool SampleGround = false; ///< --ground without a label, for an image sample
  // Continuous.
  PolyhedralReading Reading; ///< --types and --up
  double Spacing = 0;
  double Blocks = -1; ///< --blocks; negative: automatic (the filter's)
  double Voxel = 0;
  bool Grounded = false;
  std::vector<std::string> Thickness, Overhang, Connected;
  bool NoProportions = false;
  bool NoSizes = false; ///< --no-sizes: runs ended with the same odds at any length
  bool Sizes = true;    ///< --sizes, the default (kept for scripts that give it)
  int Candidates = 1;
  int Models = 1;     ///< whole-model candidates
  std::string Detail; ///< TYPE=FILE
};

/// Discrete synthesis into the staging folder @p dir.
int SynthesizeDiscrete(const SynthesizeOptions& o, const std::string& dir);
/// The example of @p o read by @p reader (a label grid) or named to @p synthesis (a tileset, an
/// image sample), and every option of @p o set on @p synthesis.
void SetUpDiscrete(
  const SynthesizeOptions& o, vtkMSLabelGridReader* reader, vtkMSDiscreteSynthesis* synthesis);
/// The picture of a tileset model or image sample's patterns as @p path (with a note and no
/// file when the tileset has no tile images).
void WritePicture(vtkImageData* model, const SynthesizeOptions& o, const std::string& path,
  std::vector<std::string>& written);
/// DIR/statistics.json from the model's field data, with @p extra members (JSON values by name).
void WriteStatistics(vtkImageData* model, const SynthesizeOptions& o, const std::string& dir,
  const std::vector<std::pair<std::string, std::string>>& extra = {});
/// The files to write: --outputs, or what the example calls for.
std::string OutputsWanted(const SynthesizeOptions& o, bool tileset, const msynth::Tileset* voxels);
/**
 * The world of @p o computed slab by slab in bounded memory (`--stream`, `--resume`;
 * StreamCommand.cxx): DIR/labels.pvti over DIR/labels/labels_J.vti, per-slab pictures and VDB
 * volumes and an overview picture, written as slabs finish into DIR/.msynth-stream (which an
 * interrupted run leaves for --resume) and published together at the end.
 */
int SynthesizeStream(const SynthesizeOptions& o, const std::string& dir);
/// Whether a block run of @p o would not comfortably fit in memory (over half of what is
/// available) and can be streamed instead (no option that needs the whole world); says so.
bool StreamsForMemory(const SynthesizeOptions& o);
/// --stream, --slab and --resume on @p s, each passed to @p discrete (discrete synthesis only).
void AddStreamOptions(
  CLI::App& s, SynthesizeOptions& o, const std::function<void(CLI::Option*)>& discrete);
/// Reads the guide volume (.vti) at @p path with @p guide (errors name the file) and connects it
/// to input @p port of @p synthesis.
void ConnectGuide(
  vtkAlgorithm* synthesis, int port, vtkXMLImageDataReader* guide, const std::string& path);
/**
 * A voxel tileset's model as its tiles' voxels (VoxelOutputs.cxx): model.vox (MagicaVoxel,
 * several models in the scene past 256 voxels a side), mesh.vtp (the voxel surface, colours in
 * the cell array `PaletteColor`; with --pieces WriteMesh's pieces instead) and, for a 2D set,
 * picture.png (the view from above).
 */
void WriteTileVoxels(vtkImageData* model, const msynth::Tileset& set, const SynthesizeOptions& o,
  const std::string& dir, const std::function<bool(const char*)>& wanted,
  std::vector<std::string>& written);
/**
 * model.vdb of the discrete model @p model at @p path (ModelVolume.cxx): its point arrays
 * (`Label` also as `Label_float`) and the render grids `density`, `color`, `surface`,
 * `surface_NAME` of its solid sites (those not of --empty's label); metadata
 * `msynth_command` = @p command and the seed; a progress bar named @p progress (none: null).
 */
void WriteModelVolume(vtkImageData* model, const SynthesizeOptions& o, const std::string& path,
  const char* command, const char* progress);
/**
 * A voxel tileset's model.vdb (ModelVolume.cxx) at the resolution of its tiles' voxels @p vox,
 * placed as mesh.vtp: `Label` the palette index (0 empty, as model.vox), `Tile` the label of
 * each voxel's site, and the render grids (colours from the palette, `surface_TILE` per tile).
 */
void WriteTileVoxelVolume(vtkImageData* model, const msynth::Tileset& set,
  const msynth::VoxModel& vox, const SynthesizeOptions& o, const std::string& path);
/**
 * The sizes of @p o against each other (SynthesizeChecks.cxx): a --region inside the world of
 * --size, an image sample's picture at least its pattern wide. @throw UsageError naming the
 * option and the bound that is out. Prints a note when --block is larger than the model.
 */
void CheckDiscreteSizes(const SynthesizeOptions& o);
/// The option of the other kind of synthesis that does what @p name does (--block and
/// --blocks, --ground and --grounded), as "; ... takes ..." for the refusal of @p name ("" when
/// there is none).
std::string Counterpart(const std::string& name, bool polyhedral);
/// --ground and --empty against the labels of the label-grid example @p example (nullptr: of
/// the tileset of @p o).
/// @throw UsageError naming the option, the example and its labels.
void CheckBoundaryLabels(const SynthesizeOptions& o, vtkImageData* example);
/// Runs @p synthesis (RunSynthesis), its messages about the pinned sites naming --fixed and
/// its file.
void RunDiscrete(vtkAlgorithm* synthesis, const SynthesizeOptions& o);
/// Continuous synthesis into the staging folder @p dir.
int SynthesizeContinuous(const SynthesizeOptions& o, const std::string& dir);

} // namespace cli
} // namespace msynth
