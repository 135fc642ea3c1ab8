// SPDX-License-Identifier: BSD-3-Clause
// `msynth synthesize EXAMPLE --size ...`: the options of both kinds of synthesis, which kind the
// example calls for, and discrete synthesis of a label grid or tileset (D ch. 3) through
// vtkMSDiscreteSynthesis, writing the files the example calls for (or --outputs).
#include "Commands.h"
#include "Common.h"
#include "Synthesize.h"

#include "vtkDataArray.h"
#include "vtkFieldData.h"
#include "vtkImageData.h"
#include "vtkMSDiscreteSynthesis.h"
#include "vtkMSGLTFWriter.h"
#include "vtkMSLabelArrays.h"
#include "vtkMSLabelGeometry.h"
#include "vtkMSLabelGridReader.h"
#include "vtkMSLabelGridWriter.h"
#include "vtkMSPatternImage.h"
#include "vtkMSTileImage.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkSmartPointer.h"
#include "vtkStringArray.h"
#include "vtkUnsignedCharArray.h"
#include "vtkXMLImageDataReader.h"
#include "vtkXMLImageDataWriter.h"
#include "vtkXMLPolyDataWriter.h"

#include "Core/Error.h"
#include "Core/Index.h"
#include "Core/TextLists.h"
#include "Discrete/DiscreteSynthesis.h"
#include "Formats/Image.h"
#include "Formats/TilePictures.h"
#include "Formats/Tileset.h"
#include "Formats/VTKXMLCheck.h"
#include "Formats/VoxModel.h"
#include "Formats/VoxelTileset.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <functional>
#include <iostream>
#include <memory>
#include <set>
#include <sstream>
#include <sys/stat.h>

namespace msynth
{
namespace cli
{
namespace
{
const std::vector<std::string> Orders{ "scanline", "random", "entropy" };
const std::vector<std::string> Starts{ "auto", "trivial", "undecided", "whole" };
const std::vector<std::string> Choices{ "uniform", "frequency", "resemblance" };
const std::vector<std::string> OutputKinds{ "labels", "mesh", "glb", "vdb", "picture", "txt",
  "vox" };

const char* const OutputsHelp =
  "which files to write, from labels (labels.vti), mesh (mesh.vtp), glb (mesh.glb: binary glTF, a "
  "material per label, with any --pieces), vdb (model.vdb), picture (picture.png, tilesets), txt "
  "(model.txt), vox (model.vox); default: labels,picture for a tileset, labels,mesh,vdb for a "
  "label grid, plus txt or vox for such an example; polyhedral examples: labels "
  "(arrangement.vtp), mesh (model.vtp), vdb (model.vdb), glb (mesh.glb: a mesh and material per "
  "object type), all four by default, and vox (model.vox: the model voxelized, palette index = "
  "object type); statistics.json is always written";

/// "A:B" with two integers.
std::string LabelPair(const std::string& text)
{
  const auto colon = text.find(':');
  if (colon == std::string::npos)
    return "'" + Printable(text) + "' is not LABEL:LABEL";
  for (const std::string& part : { text.substr(0, colon), text.substr(colon + 1) })
  {
    char* end = nullptr;
    std::strtol(part.c_str(), &end, 10);
    if (part.empty() || *end != '\0')
      return "'" + Printable(text) + "' is not LABEL:LABEL (two integers)";
  }
  return std::string();
}

/// "L:F" with a label (an integer; an object type's name too for continuous synthesis) and a
/// fraction.
std::string LabelFraction(const std::string& text)
{
  const auto colon = text.find(':');
  char* end = nullptr;
  if (colon != std::string::npos)
  {
    const std::string label = text.substr(0, colon), fraction = text.substr(colon + 1);
    const bool labelOk = !label.empty();
    const double f = std::strtod(fraction.c_str(), &end);
    if (labelOk && !fraction.empty() && *end == '\0' && f >= 0 && f <= 1)
      return std::string();
  }
  return "'" + Printable(text) + "' is not LABEL:FRACTION (a fraction between 0 and 1)";
}

std::string Axes(const std::string& text)
{
  for (const char c : text)
    if (c < 'x' || c > 'z')
      return "'" + Printable(text) + "' is not a set of axes x, y, z";
  return text.empty() ? "no axes given" : std::string();
}

std::string OutputList(const std::string& text)
{
  std::stringstream items(text);
  std::string item;
  while (std::getline(items, item, ','))
    if (std::find(OutputKinds.begin(), OutputKinds.end(), item) == OutputKinds.end())
      return "unknown kind '" + Printable(item) + "' (labels, mesh, glb, vdb, picture, txt, vox)";
  return std::string();
}

struct Registered
{
  std::shared_ptr<SynthesizeOptions> Options;
  std::vector<CLI::Option*> DiscreteOnly, ContinuousOnly, SampleOnly, NotForSamples;
  CLI::Option* Ground = nullptr;
  CLI::App* Command = nullptr;
  CLI::Option* Attempts = nullptr;
  CLI::Option* Order = nullptr;
};

void AddDiscreteOptions(CLI::App& s, Registered& r)
{
  SynthesizeOptions& o = *r.Options;
  auto discrete = [&r](CLI::Option* option)
  { r.DiscreteOnly.push_back(option->group("Discrete synthesis (label grids, tilesets)")); };
  discrete(s.add_option("--block", o.Block,
              "synthesize in overlapping blocks of BX BY BZ sites (default: the whole model)")
             ->expected(3)
             ->check(CLI::Range(0, 1000000000)));
  discrete(s.add_option("--region", o.Region,
              "only the region X0 Y0 Z0 X1 Y1 Z1 (half-open) of the world of --size, computed "
              "from the blocks it depends on: the same sites as a whole run (an image sample's "
              "pattern sites: a picture of X1 - X0 + N - 1 pixels across, N the pattern size)")
             ->expected(6)
             ->check(CLI::Range(0, 2147483647)));
  discrete(s.add_option("--overlap", o.Overlap,
              "overlap of consecutive blocks OX OY OZ (default -1: half a block)")
             ->expected(3)
             ->check(CLI::Range(-1, 1000000000)));
  discrete(s.add_option("--backtracks", o.Backtracks,
              "choices an attempt may undo when a catalog becomes empty (0: none, as the "
              "dissertation)")
             ->check(CLI::Range(std::int64_t(0), std::int64_t(1) << 40)));
  discrete(s.add_flag("--no-repair", o.NoRepair,
    "leave blocks whose attempts all fail at their previous labels, without a second try "
    "after the other blocks"));
  discrete(s.add_flag("--no-fallback", o.NoFallback,
    "when whole-model synthesis fails every attempt, fail, rather than synthesize the model in "
    "32-site blocks instead"));
  discrete(s.add_option("--start", o.Start,
              "how blocks start: auto (default: trivial unless a probe finds it leaves the model "
              "blank), trivial (every site one label that fits anywhere), undecided (every site "
              "free until a block decides it) or whole (a whole-model solution the blocks modify)")
             ->check(CLI::IsMember(Starts)));
  s.add_option(
     "--threads", o.Threads, "threads for block synthesis (default: one per core; the same result)")
    ->check(CLI::Range(0, 1024));
  r.Ground = s.add_option("--ground", o.Ground,
                "fix LABEL along the bottom face (-z; -y in 2D); with an image sample, no "
                "LABEL: the sample's bottom-middle window along the bottom row only")
               ->expected(0, 1);
  discrete(r.Ground);
  discrete(s.add_option("--empty", o.Empty,
              "fix LABEL on every other face (usually 0) but those of translated axes")
             ->expected(1));
  s.add_option("--outputs", o.Outputs, OutputsHelp)->check(OutputList, "KINDS");
  discrete(s.add_option("--pieces", o.Pieces,
    "mesh each label with DIR/<label>.obj|.vtp|.ply|.stl (default: voxels), or with the "
    "pieces a .txt example names for it (DIR/round.obj for $round); with a tileset also "
    "DIR/<tile>.obj, turned for each orientation; files matching nothing are named"));
  s.add_option("--mirror", o.Mirror,
     "make the output mirror-symmetric along AXES (continuous: across a plane near the middle "
     "of the box for each axis)")
    ->check(Axes, "AXES")
    ->group("Constraints (both kinds)");
  discrete(s.add_option("--swap", o.Swaps, "labels A and B are each other's mirror images (A:B)")
             ->allow_extra_args(false)
             ->check(LabelPair, "A:B"));
  discrete(s.add_option("--translate", o.Translate,
              "make the output repeat along AXES; with the default period it tiles seamlessly")
             ->check(Axes, "AXES"));
  discrete(s.add_option("--period", o.Period, "periods PX PY PZ of the translated axes (0: size)")
             ->expected(3)
             ->check(CLI::Range(0, 1 << 30)));
  discrete(s.add_option("--shift", o.Shifts, "label A's image one period on is B (A:B)")
             ->allow_extra_args(false)
             ->check(LabelPair, "A:B"));
  discrete(s.add_flag("--rotate", o.Rotate,
    "make the output look the same turned 90 degrees about the vertical (square in x and y)"));
  discrete(s.add_option("--turn", o.Turns, "label A turned 90 degrees counter-clockwise is B")
             ->allow_extra_args(false)
             ->check(LabelPair, "A:B"));
  discrete(s.add_option("--subset", o.Subset, "with a tileset: use the tiles of its subset NAME"));
  discrete(s.add_option("--tiles", o.Tiles,
    "with a voxel tileset (MarkovJunior's <tileset>): the folder of its tiles' .vox files, as "
    "given or relative to the XML's folder (default: the folder named like the XML)"));
  s.add_option("--target", o.Targets,
     "soft constraint: aim for fraction F of label L (L:F; needs --block); continuous: share F "
     "of the solid volume for object type L (a number or name)")
    ->allow_extra_args(false)
    ->check(LabelFraction, "L:F")
    ->group("Constraints (both kinds)");
  discrete(s.add_option("--count", o.Counts,
              "sites holding label L (tileset: a label, a tile's name or \"tile k\") number MIN "
              "to MAX (L:MIN:MAX, or region=R:L:MIN:MAX in region R of the --guide's array "
              "Region; repeatable; with --fixed, --connected; not with symmetry or --target)")
             ->allow_extra_args(false));
  discrete(s.add_option("--temperature", o.Temperature,
              "temperature of the soft constraints' Metropolis acceptance")
             ->check(CLI::PositiveNumber));
  s.add_option("--guide", o.Guide,
     "large-scale constraints: image data (.vti) over the output box whose point arrays "
     "Weight_<label> (continuous: Weight_<type>) weight each label (0 forbids it there)")
    ->group("Constraints (both kinds)");
}

void AddFixedOptions(CLI::App& s, Registered& r)
{
  SynthesizeOptions& o = *r.Options;
  const std::string group = "Constraints (both kinds)";
  r.DiscreteOnly.push_back(
    s.add_option("--fixed", o.Fixed,
       "pinned sites, to complete a partial model: a label grid of the output size (.vti, "
       ".txt, .vox; a smaller .vti is placed by its extent) whose labels are kept and whose -1 "
       "sites are synthesized, or a picture (.png, .bmp) drawn with a 2D tileset's tiles or in "
       "an image sample's colours, transparent where free; pins that cannot hold are an error "
       "before any work")
      ->group(group));
  r.DiscreteOnly.push_back(
    s.add_flag("--fixed-empty-free", o.FixedEmptyFree,
       "with --fixed: sites of label 0 (a MagicaVoxel model's empty voxels) are synthesized too")
      ->needs("--fixed")
      ->group(group));
  r.DiscreteOnly.push_back(
    AddViaInfallible(s, o)->group("Discrete synthesis (label grids, tilesets)"));
}

void AddSampleOptions(CLI::App& s, Registered& r)
{
  SynthesizeOptions& o = *r.Options;
  for (CLI::Option* option : AddPatternOptions(s, o.Pattern, o.Symmetry, o.NoPeriodicInput))
  {
    r.SampleOnly.push_back(option);
    r.DiscreteOnly.push_back(option);
  }
}

void AddContinuousOptions(CLI::App& s, Registered& r)
{
  SynthesizeOptions& o = *r.Options;
  auto continuous = [&r](CLI::Option* option)
  { r.ContinuousOnly.push_back(option->group("Continuous synthesis (polyhedral examples)")); };
  continuous(s.add_option("--spacing", o.Spacing,
                "smallest plane spacing (default: derived from the example's planes)")
               ->check(NonNegativeReal()));
  continuous(
    s.add_option("--blocks", o.Blocks,
       "block edge in plane spacings (0: the whole model at once; default: twice the example's "
       "longest wall, slab or road, at least 4)")
      ->check(NonNegativeReal()));
  continuous(s.add_option("--voxel", o.Voxel,
                "voxel size of model.vdb and model.vox (default for model.vdb: a quarter of "
                "the smallest plane spacing, at least 1/256 of the model's extent, coarser where "
                "the level sets would hold over 10^6 voxels; for model.vox: half the smallest "
                "plane spacing, at least 1/256 of the extent, one MagicaVoxel model; "
                "statistics.json's VoxelSize and VoxVoxelSize)")
               ->check(NonNegativeReal()));
  for (CLI::Option* option : AddTypesOption(s, o.Reading))
    continuous(option);
  continuous(s.add_flag("--grounded", o.Grounded,
    "every solid part stands on the ground: the example's ground labels only on the bottom of the "
    "box, objects grown up from it, floating parts removed"));
  continuous(s.add_option("--thickness", o.Thickness,
                "dimensional constraint: object type TYPE is exactly N plane spacings thick "
                "across AXIS (x, y, z or hK for plane family K; N defaults to 1); N+ makes it "
                "whole multiples of N (wall:x:2+ and wall:y:2+: no one-spacing posts); several "
                "axes (TYPE:xy) make a width: one spacing across at least one of them")
               ->allow_extra_args(false));
  continuous(s.add_option("--overhang", o.Overhang,
                "TYPE reaches at most one plane spacing past what holds it up (its undersides "
                "are one spacing wide at most: eaves, no roofs spanning thin columns)")
               ->allow_extra_args(false));
  s.add_option("--connected", o.Connected,
     "grids, tilesets: the sites of LABELS (values or tile names, commas between) form at most N "
     "components (LABELS[:N], N 1 if left out), through the tiles' connecting sides. Polyhedral: "
     "TYPE (or 'solid') grows from SEEDS seeds (TYPE:SEEDS, default 1): that many objects")
    ->allow_extra_args(false)
    ->group("Constraints (both kinds)");
  r.DiscreteOnly.push_back(
    s.add_option("--path", o.Path,
       "with --connected: one component joins these sites (x,y[,z]) and labels' sites")
      ->group("Discrete synthesis (label grids, tilesets)"));
  continuous(s.add_option("--detail", o.Detail,
    "bounding volumes: substitute the closed mesh FILE for every part of object type TYPE in "
    "the output, mapped onto the part's bounding box from the example's (TYPE=FILE; "
    "TYPE+TYPE=FILE for a bounding volume of several pieces)"));
  continuous(s.add_option("--candidates", o.Candidates,
                "with proportions steered: labellings tried per block, the one closest to the "
                "example's proportions kept (default 1)")
               ->check(CLI::Range(1, 64)));
  continuous(s.add_option("--models", o.Models,
                "generate several, keep the best match: N whole models (seeds SEED, SEED+1, ...), "
                "the one closest to the guide, the proportions and the seeds kept")
               ->check(CLI::Range(1, 1000)));
  continuous(s.add_flag("--no-proportions", o.NoProportions,
    "do not steer the label choice toward the example's proportions of object types"));
  continuous(s.add_flag("--sizes", o.Sizes, "parts as long as the example's (the default)"));
  continuous(s.add_flag("--no-sizes", o.NoSizes,
    "walls, slabs, roads end along x or y with the same odds at any length (TVCG 2010)"));
}

/// Options of label grids that an image sample does not take, and the forms of --ground.
void CheckSampleKind(const Registered& r, bool sample)
{
  SynthesizeOptions& o = *r.Options;
  for (const CLI::Option* option : sample ? r.NotForSamples : r.SampleOnly)
    if (option->count() > 0)
      throw UsageError{ option->get_name() + " applies to " +
        (sample ? "label grids and tilesets" : "image samples (.png, .bmp)") + ", not to '" +
        o.Example + "'" };
  // Given without a value, --ground has no result but is in the parse order.
  const auto& order = r.Command->parse_order();
  const bool ground = std::find(order.begin(), order.end(), r.Ground) != order.end();
  if (ground && sample != o.Ground.empty())
    throw UsageError{ sample ? "--ground takes no LABEL with an image sample"
                             : "--ground needs a LABEL with a label grid or tileset" };
  o.SampleGround = sample && ground;
}

/// Refuses options of the other kind of synthesis, and sizes a label grid cannot have.
void CheckKind(const Registered& r, bool polyhedral)
{
  SynthesizeOptions& o = *r.Options;
  if (!polyhedral)
    CheckSampleKind(r, IsSample(o.Example));
  for (const CLI::Option* option : polyhedral ? r.DiscreteOnly : r.ContinuousOnly)
  {
    if (option->count() > 0)
    {
      throw UsageError{ option->get_name() + " applies to " +
        (polyhedral ? "label grids and tilesets" : "polyhedral examples") + ", not to '" +
        o.Example + "'" + Counterpart(option->get_name(), polyhedral) };
    }
  }
  if (polyhedral)
  {
    if (r.Attempts->count() == 0)
      o.Attempts = 20;
    if (o.Choice == "resemblance")
      throw UsageError{ "--choice resemblance applies to label grids, not to '" + o.Example + "'" };
    return;
  }
  for (const auto& target : o.Targets)
  {
    try
    {
      ParseLabelValues(target, "--target", "fraction");
    }
    catch (const Error&)
    {
      throw UsageError{ "--target " + Printable(target) +
        ": expected LABEL:FRACTION, a label grid's labels being integers" };
    }
  }
  for (std::size_t a = 0; a < 3; ++a)
  {
    const double v = o.Size[a];
    if (v < 1 || v > 1e9 || std::floor(v) != v)
      throw UsageError{ "--size of a label grid is in sites: integers between 1 and 10^9" };
    o.Size3[a] = static_cast<int>(v);
  }
  if (o.Order.empty())
    o.Order = "scanline";
}
} // namespace

// ---------------------------------------------------------------------------------------------
// Discrete synthesis
// ---------------------------------------------------------------------------------------------
namespace
{
/// The filter's settings from the options.
void Configure(vtkMSDiscreteSynthesis* synthesis, const SynthesizeOptions& o)
{
  synthesis->SetOutputSize(o.Size3.data());
  synthesis->SetBlockSize(o.Block.data());
  synthesis->SetBlockOverlap(o.Overlap.data());
  synthesis->SetRegion(o.Region.data());
  synthesis->SetSeed(static_cast<vtkIdType>(o.Seed));
  synthesis->SetAttemptsPerBlock(o.Attempts);
  synthesis->SetBacktracksPerAttempt(static_cast<vtkIdType>(o.Backtracks));
  synthesis->SetRepairFailedBlocks(!o.NoRepair);
  synthesis->SetBlocksWhenWholeFails(!o.NoFallback);
  synthesis->SetViaInfallible(o.ViaInfallible);
  synthesis->SetBlockStart(IndexIn(o.Start.empty() ? "auto" : o.Start, Starts));
  synthesis->SetNumberOfThreads(o.Threads);
  synthesis->SetSiteOrder(IndexIn(o.Order, Orders));
  synthesis->SetLabelChoice(IndexIn(o.Choice, Choices));
  // Ground along the bottom: -z in 3D, -y for a 2D (single-layer) output.
  const int bottom = o.Size3[2] > 1 ? 4 : 2;
  int use[6] = { 0, 0, 0, 0, 0, 0 }, labels[6] = { 0, 0, 0, 0, 0, 0 };
  for (int f = 0; f < 6; ++f)
  {
    const bool translated = o.Translate.find(static_cast<char>('x' + f / 2)) != std::string::npos;
    if (f == bottom && !o.Ground.empty())
    {
      use[f] = 1;
      labels[f] = o.Ground[0];
    }
    else if (f != bottom && !o.Empty.empty() && !translated)
    { // a translated axis has no faces: the model repeats across them
      use[f] = 1;
      labels[f] = o.Empty[0];
    }
  }
  synthesis->SetUseBoundary(use);
  synthesis->SetBoundaryLabels(labels);
  int mirror[3], translate[3];
  for (int a = 0; a < 3; ++a)
  {
    mirror[a] = o.Mirror.find(static_cast<char>('x' + a)) != std::string::npos;
    translate[a] = o.Translate.find(static_cast<char>('x' + a)) != std::string::npos;
  }
  synthesis->SetMirror(mirror);
  synthesis->SetTargetFractions(Joined(o.Targets).c_str());
  synthesis->SetSoftTemperature(o.Temperature);
  synthesis->SetCounts(Joined(o.Counts).c_str());
  synthesis->SetConnected(Joined(o.Connected).c_str());
  synthesis->SetPath(Joined(o.Path, ";").c_str());
  synthesis->SetMirrorSwaps(Joined(o.Swaps).c_str());
  synthesis->SetTranslate(translate);
  synthesis->SetTranslationPeriod(o.Period[0], o.Period[1], o.Period[2]);
  synthesis->SetTranslationMap(Joined(o.Shifts).c_str());
  synthesis->SetRotate(o.Rotate);
  synthesis->SetRotationMap(Joined(o.Turns).c_str());
  synthesis->SetCatalogSnapshotsPerBlock(o.Snapshots);
  if (IsSample(o.Example))
  {
    synthesis->SetSampleFile(o.Example.c_str());
    synthesis->SetPatternSize(o.Pattern);
    synthesis->SetPatternSymmetry(o.Symmetry);
    synthesis->SetPeriodicInput(!o.NoPeriodicInput);
    synthesis->SetGround(o.SampleGround);
  }
}

} // namespace

void ConnectGuide(
  vtkAlgorithm* synthesis, int port, vtkXMLImageDataReader* guide, const std::string& path)
{
  struct stat info;
  if (::stat(path.c_str(), &info) != 0)
  {
    throw std::runtime_error("'" + path + "': no such guide file");
  }
  msynth::CheckVTKXMLFile(path); // what VTK's reader trusts, first
  guide->SetFileName(path.c_str());
  std::string messages;
  if (!vtkMSEngineBridge::Execute(guide, messages))
  {
    throw std::runtime_error("'" + path + "': not a readable guide volume: " + messages);
  }
  synthesis->SetInputConnection(port, guide->GetOutputPort());
}

void WritePicture(vtkImageData* model, const SynthesizeOptions& o, const std::string& path,
  std::vector<std::string>& written)
{
  struct stat folder;
  if (!IsSample(o.Example))
  {
    // Tiles: each row of picture.png composed as it is written (Formats/TilePictures.h), not the
    // whole picture in memory first (vtkMSTileImage does that for pipelines).
    if (::stat(msynth::TilesetImageFolder(o.Example).c_str(), &folder) != 0)
    {
      std::cerr << "msynth: note: no picture: the tileset has no folder of tile images\n";
      return;
    }
    const msynth::Tileset set = msynth::ReadTilesetFile(o.Example, o.Subset, o.Tiles);
    int dims[3];
    model->GetDimensions(dims);
    vtkDataArray* labels = vtkMSLabelArrays::FindLabelArray(model, nullptr);
    std::vector<std::int32_t> values(msynth::ToIndex(labels ? labels->GetNumberOfTuples() : 0));
    for (std::size_t i = 0; i < values.size(); ++i)
      values[i] = static_cast<std::int32_t>(labels->GetTuple1(static_cast<vtkIdType>(i)));
    msynth::WriteTilePicture(
      path, values, dims[0], dims[1], msynth::LoadTilePictures(o.Example, set));
    written.push_back(path);
    return;
  }
  vtkNew<vtkMSPatternImage> patterns;
  patterns->SetPatternSize(o.Pattern);
  patterns->SetPeriodicOutput(
    o.Translate.find('x') != std::string::npos, o.Translate.find('y') != std::string::npos);
  patterns->SetInputData(model);
  std::string messages;
  if (!vtkMSEngineBridge::Execute(patterns, messages))
    throw std::runtime_error(messages);
  WritePicturePng(patterns->GetOutput(), path);
  written.push_back(path);
}

namespace
{

/// mesh.vtp (@p vtp) and mesh.glb (@p glb) of the model's geometry, with any --pieces.
void WriteMesh(vtkImageData* model, const SynthesizeOptions& o, bool tileset,
  const std::string& dir, std::vector<std::string>& written, bool vtp, bool glb)
{
  vtkNew<vtkMSLabelGeometry> geometry;
  geometry->SetInputData(model);
  geometry->SetEmptyLabel(o.Empty.empty() ? 0 : o.Empty[0]);
  geometry->SetPieceDirectory(o.Pieces.c_str());
  if (tileset)
  {
    geometry->SetTilesetFile(o.Example.c_str()); // pieces may be named by tile and turned
    geometry->SetTilesetSubset(o.Subset.c_str());
  }
  {
    ProgressBar bar(geometry, "mesh");
    Run(geometry);
  }
  if (auto* warning = vtkStringArray::SafeDownCast(
        geometry->GetOutput()->GetFieldData()->GetAbstractArray("PieceFolderWarning")))
    std::cerr << "msynth: warning: --pieces " << msynth::Printable(warning->GetValue(0)) << "\n";
  if (vtp)
  {
    WriteXML<vtkXMLPolyDataWriter>(dir + "/mesh.vtp", geometry->GetOutput());
    written.push_back(dir + "/mesh.vtp");
  }
  if (glb)
  {
    vtkNew<vtkMSGLTFWriter> writer;
    writer->SetInputData(geometry->GetOutput());
    writer->SetFileName((dir + "/mesh.glb").c_str());
    Run(writer);
    written.push_back(dir + "/mesh.glb");
  }
}

} // namespace

void WriteStatistics(vtkImageData* model, const SynthesizeOptions& o, const std::string& dir,
  const std::vector<std::pair<std::string, std::string>>& extra)
{
  vtkFieldData* fd = model->GetFieldData();
  StatisticsJson json;
  json.Text("example", o.Example)
    .Counts("size", { o.Size3[0], o.Size3[1], o.Size3[2] })
    .Counts("block", { o.Block[0], o.Block[1], o.Block[2] })
    .Count("seed", o.Seed)
    .Solver(fd)
    .LabelCounts(fd)
    .Connected(fd);
  // How blocks started (block synthesis only).
  if (auto* start = vtkStringArray::SafeDownCast(fd->GetAbstractArray("StartFrom")))
    json.Text("StartFrom", start->GetValue(0));
  for (const auto& [name, value] : extra)
    json.Raw(name, value);
  json.Text("Message", MessageOf(fd)).Write(dir + "/statistics.json");
}

std::string OutputsWanted(const SynthesizeOptions& o, bool tileset, const msynth::Tileset* voxels)
{
  if (!o.Outputs.empty())
    return o.Outputs;
  if (voxels) // a voxel tileset: the voxels in MagicaVoxel's format and as a mesh; 2D a picture
    return std::string("labels,vox,mesh,vdb") + (voxels->VoxelSize[2] == 1 ? ",picture" : "");
  const std::string ext = o.Example.size() > 4 ? o.Example.substr(o.Example.size() - 4) : "";
  std::string list = tileset || IsSample(o.Example) ? "labels,picture" : "labels,mesh,vdb";
  if (ext == ".txt")
    list += ",txt";
  if (ext == ".vox")
    list += ",vox";
  return list;
}

namespace
{
void WriteOutputs(vtkImageData* model, const SynthesizeOptions& o, bool tileset,
  const std::string& dir, std::vector<std::string>& written)
{
  // A voxel tileset's model is written as its tiles' voxels (WriteTileVoxels).
  const bool voxel = tileset && model->GetFieldData()->GetAbstractArray("LabelTile");
  msynth::Tileset voxels;
  if (voxel)
    voxels = msynth::ReadTilesetFile(o.Example, "", o.Tiles);
  const std::string list = OutputsWanted(o, tileset, voxel ? &voxels : nullptr);
  const auto wanted = [&list](const char* kind)
  { return ("," + list + ",").find(std::string(",") + kind + ",") != std::string::npos; };
  if (wanted("picture") && !tileset && !IsSample(o.Example))
  {
    throw std::runtime_error("--outputs picture: pictures are made of a tileset's images or an "
                             "image sample's pixels; '" +
      o.Example + "' is neither");
  }
  if (wanted("labels"))
  {
    WriteXML<vtkXMLImageDataWriter>(dir + "/labels.vti", model);
    written.push_back(dir + "/labels.vti");
  }
  if (voxel)
    WriteTileVoxels(model, voxels, o, dir, wanted, written);
  for (const char* kind : { "txt", "vox" })
  {
    if (voxel && std::string(kind) == "vox")
      continue; // written by WriteTileVoxels
    if (wanted(kind))
    {
      // The original program's text with the example's <Objects> trailer (for its loaders), or
      // MagicaVoxel with the example's palette.
      const std::string path = dir + "/model." + kind;
      vtkNew<vtkMSLabelGridWriter> same;
      same->SetInputData(model);
      same->SetFileName(path.c_str());
      Run(same);
      written.push_back(path);
    }
  }
  if ((wanted("mesh") || wanted("glb")) && (!voxel || !o.Pieces.empty()))
    WriteMesh(model, o, tileset, dir, written, wanted("mesh"), wanted("glb"));
  if (wanted("picture") && !voxel)
    WritePicture(model, o, dir + "/picture.png", written);
  if (wanted("vdb"))
  {
    if (!voxel) // a voxel tileset's is written by WriteTileVoxels
      WriteModelVolume(model, o, dir + "/model.vdb", "synthesize", "model.vdb");
    written.push_back(dir + "/model.vdb");
  }
}
} // namespace

void SetUpDiscrete(
  const SynthesizeOptions& o, vtkMSLabelGridReader* reader, vtkMSDiscreteSynthesis* synthesis)
{
  reader->GenerateGeometryOff();
  synthesis->GenerateGeometryOff(); // the mesh is made by vtkMSLabelGeometry, with any pieces
  if (IsTileset(o.Example))
  {
    synthesis->SetTilesetFile(o.Example.c_str());
    synthesis->SetTilesetSubset(o.Subset.c_str());
    synthesis->SetTilesFolder(o.Tiles.c_str());
    CheckBoundaryLabels(o, nullptr);
  }
  else if (!IsSample(o.Example))
  {
    reader->SetFileName(o.Example.c_str());
    Run(reader);
    CheckBoundaryLabels(o, reader->GetOutput());
    synthesis->SetInputConnection(reader->GetOutputPort());
  }
  if (!o.Fixed.empty()) // streamed runs take the pins too
  {
    CheckInputFile(o.Fixed);
    synthesis->SetFixedFile(o.Fixed.c_str());
    synthesis->SetFixedEmptyFree(o.FixedEmptyFree);
  }
  Configure(synthesis, o);
}

int SynthesizeDiscrete(const SynthesizeOptions& o, const std::string& dir)
{
  if (o.Stream || o.Resume || StreamsForMemory(o))
    return SynthesizeStream(o, dir);
  const auto start = std::chrono::steady_clock::now();
  vtkNew<vtkMSLabelGridReader> reader;
  vtkNew<vtkMSDiscreteSynthesis> synthesis;
  const bool tileset = IsTileset(o.Example);
  SetUpDiscrete(o, reader, synthesis);
  vtkNew<vtkXMLImageDataReader> guide;
  if (!o.Guide.empty())
  {
    ConnectGuide(synthesis, 1, guide, o.Guide);
  }
  {
    ProgressBar bar(synthesis);
    RunDiscrete(synthesis, o);
  }
  vtkImageData* model = synthesis->GetOutput();
  std::vector<std::string> written;
  WriteOutputs(model, o, tileset, dir, written);
  if (o.Snapshots > 0)
  {
    // The catalog at every snapshot: DIR/catalog_0001.vdb, ... (Label, CatalogSize, Entropy).
    WriteCatalogSequence(synthesis, dir, 0, "seed", std::to_string(o.Seed));
  }
  WriteStatistics(model, o, dir);
  written.push_back(dir + "/statistics.json");
  if (o.Snapshots > 0)
  {
    written.push_back(dir + "/catalog_0001.vdb ...");
  }
  // A summary a user reads first: the size, the labels used, blocks, and the time: in total
  // (reading, analysis, synthesis, writing the files) and of the synthesis alone (the
  // `Seconds` of statistics.json).
  std::set<long long> used;
  if (vtkDataArray* labels = model->GetPointData()->GetArray("Label"))
    for (vtkIdType i = 0; i < labels->GetNumberOfTuples(); ++i)
      used.insert(static_cast<long long>(labels->GetTuple1(i)));
  int dims[3];
  model->GetDimensions(dims);
  vtkFieldData* fd = model->GetFieldData();
  vtkDataArray* seconds = fd->GetArray("Seconds");
  char timing[96];
  std::snprintf(timing, sizeof(timing), "total %.2f s, synthesis %.2f s",
    std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(),
    seconds && seconds->GetNumberOfTuples() > 0 ? seconds->GetTuple1(0) : 0.0);
  // An image sample's sites are its patterns' places: the picture is a pattern wider.
  // A region's picture does not repeat: its last pattern's pixels end it.
  const bool region = std::any_of(o.Region.begin(), o.Region.end(), [](int v) { return v != 0; });
  const std::string picture = !IsSample(o.Example) ? ""
    : region
    ? " (a " + std::to_string(dims[0] + o.Pattern - 1) + " x " +
      std::to_string(dims[1] + o.Pattern - 1) + " picture of a region)"
    : " (a " + std::to_string(o.Size3[0]) + " x " + std::to_string(o.Size3[1]) + " picture)";
  std::cout << MessageOf(fd) << "\n"
            << dims[0] << " x " << dims[1] << " x " << dims[2]
            << (picture.empty() ? " sites, " : " pattern sites" + picture + ", ")
            << Counted(static_cast<long long>(used.size()),
                 picture.empty() ? "distinct label" : "distinct pattern")
            << ", " << Counted(CountOf(fd, "Blocks"), "block") << " ("
            << CountOf(fd, "BlocksFailed") << " failed), " << timing << "\n"
            << "wrote ";
  for (std::size_t i = 0; i < written.size(); ++i)
  {
    std::cout << (i ? ", " : "") << written[i];
  }
  std::cout << "\n";
  return 0;
}

CommandRunner AddSynthesize(CLI::App& app)
{
  Registered r;
  r.Options = std::make_shared<SynthesizeOptions>();
  SynthesizeOptions& o = *r.Options;
  CLI::App* s = app.add_subcommand("synthesize",
    "model synthesis from EXAMPLE: discrete for a label grid (.vti, .txt, .vox), a tileset "
    "(.xml) or an image sample (.png, .bmp: its N x N windows), continuous for a polyhedral "
    "example (.obj, .vtp, .ply, .stl). Writes the model and "
    "DIR/statistics.json; the files appear together, or not at all when the run fails or is "
    "interrupted");
  s->add_option("EXAMPLE", o.Example, "the example")->required();
  s->add_option("--size", o.Size,
     "output size NX NY NZ: sites for a label grid or tileset (NZ 1 for 2D), pixels for an "
     "image sample (NZ 1), example units for a polyhedral example (NZ ignored for a 2D one)")
    ->expected(3)
    ->required()
    ->check(NonNegativeReal());
  AddSeedOption(*s, o.Seed);
  r.Attempts =
    s->add_option("--attempts", o.Attempts, "attempts per block (default 10; continuous 20)")
      ->check(CLI::Range(1, 1000000));
  r.Order = AddOrderOption(*s, o.Order, Orders);
  r.Order->description(r.Order->get_description() +
    " (default scanline; for a polyhedral example entropy if grown from seeds or --no-sizes)");
  AddChoiceOption(*s, o.Choice, Choices);
  AddSnapshotsOption(*s, o.Snapshots,
    "catalog snapshots (per block for a label grid), also written as the sequence "
    "DIR/catalog_0001.vdb ... (Label, CatalogSize, Entropy)");
  AddOutOption(*s, o.Out);
  r.Command = s;
  AddDiscreteOptions(*s, r);
  AddStreamOptions(*s, o,
    [&r](CLI::Option* option)
    { r.DiscreteOnly.push_back(option->group("Discrete synthesis (label grids, tilesets)")); });
  AddSampleOptions(*s, r);
  AddFixedOptions(*s, r);
  AddContinuousOptions(*s, r);
  for (const char* name : { "--pieces", "--mirror", "--swap", "--rotate", "--turn", "--subset" })
    r.NotForSamples.push_back(s->get_option(name));
  return [r]()
  {
    const SynthesizeOptions& opts = *r.Options;
    CheckInputFile(opts.Example);
    const bool polyhedral = IsPolyhedral(opts.Example);
    CheckKind(r, polyhedral);
    if (!polyhedral)
      CheckDiscreteSizes(opts);
    return IntoFolder(opts.Out,
      [&](const std::string& dir)
      { return polyhedral ? SynthesizeContinuous(opts, dir) : SynthesizeDiscrete(opts, dir); });
  };
}

} // namespace cli
} // namespace msynth
