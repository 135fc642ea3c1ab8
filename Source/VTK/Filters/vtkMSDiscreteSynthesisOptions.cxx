// SPDX-License-Identifier: BSD-3-Clause
#include "vtkMSDiscreteSynthesisOptions.h"

#include "vtkMSDiscreteSynthesis.h"
#include "vtkMSEngineBridge.h"
#include "vtkMSLabelArrays.h"
#include "vtkMSLabelCounts.h"
#include "vtkMSLabelGridReader.h"
#include "vtkMSSynthesisRun.h"

#include "vtkDataArray.h"
#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkUnsignedCharArray.h"

#include "Core/Error.h"
#include "Core/Index.h"
#include "Core/TextLists.h"
#include "Discrete/OverlappingModel.h"
#include "Formats/TilePictures.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <optional>
#include <string>

namespace
{
/// Label maps "a:b,c:d" of a symmetry property (@p both: each pair both ways).
bool ReadMap(vtkMSDiscreteSynthesis* self, const char* property, const char* value, bool both,
  std::map<msynth::Label, msynth::Label>& map)
{
  try
  {
    map = msynth::ParseLabelPairs(value ? value : "", both, property);
    return true;
  }
  catch (const msynth::Error& e)
  {
    vtkErrorWithObjectMacro(self, << e.what() << ".");
    return false;
  }
}

/// The symmetries (D§3.5.2) and soft constraints (M07§4.2) of the filter's properties.
bool ReadSymmetryAndSoft(vtkMSDiscreteSynthesis* self, msynth::SynthesisOptions& options)
{
  const int* mirror = self->GetMirror();
  if (mirror[0] || mirror[1] || mirror[2])
  {
    std::map<msynth::Label, msynth::Label> swaps;
    if (!ReadMap(self, "MirrorSwaps", self->GetMirrorSwaps(), true, swaps))
      return false;
    for (std::size_t axis = 0; axis < 3; ++axis)
      options.Symmetry[axis].Map = swaps;
  }
  const int* translate = self->GetTranslate();
  if (translate[0] || translate[1] || translate[2])
  {
    std::map<msynth::Label, msynth::Label> shift;
    if (!ReadMap(self, "TranslationMap", self->GetTranslationMap(), false, shift))
      return false;
    for (std::size_t axis = 0; axis < 3; ++axis)
      options.Translate[axis].Map = shift;
  }
  if (self->GetRotate() &&
    !ReadMap(self, "RotationMap", self->GetRotationMap(), false, options.Rotate.Map))
    return false;
  try
  {
    const char* targets = self->GetTargetFractions();
    for (const auto& [label, fraction] :
      msynth::ParseLabelValues(targets ? targets : "", "TargetFractions", "fraction"))
    {
      options.Soft.TargetFractions[label] = fraction;
      options.Soft.Temperature = self->GetSoftTemperature();
    }
    if (self->GetActiveSource() != vtkMSDiscreteSynthesis::TILESET_SOURCE) // else tile names too
    {
      options.Counts = vtkMSLabelCounts::Read(self->GetCounts(), nullptr);
      options.Connected =
        vtkMSLabelCounts::ReadConnected(self->GetConnected(), nullptr, self->GetPath());
    }
  }
  catch (const msynth::Error& e)
  {
    vtkErrorWithObjectMacro(self, << e.what() << ".");
    return false;
  }
  return true;
}

/// The guide's regions for counts per region: its integer point array `Region` (values >= 0).
bool ReadGuideRegions(vtkMSDiscreteSynthesis* self, vtkImageData* guide, msynth::GuideVolume& v)
{
  vtkDataArray* regions = guide->GetPointData()->GetArray("Region");
  if (!regions)
    return true;
  if (regions->GetNumberOfComponents() != 1)
  {
    vtkErrorWithObjectMacro(self, << "The guide's array 'Region' must have one component.");
    return false;
  }
  v.Regions.resize(msynth::ToIndex(regions->GetNumberOfTuples()));
  for (vtkIdType t = 0; t < regions->GetNumberOfTuples(); ++t)
  {
    const double r = regions->GetTuple1(t);
    if (!(r >= 0.0 && r <= 2147483647.0) || r != std::floor(r))
    {
      vtkErrorWithObjectMacro(self, << "The guide's array 'Region' holds " << r << " at point " << t
                                    << "; regions are whole numbers from 0.");
      return false;
    }
    v.Regions[msynth::ToIndex(t)] = static_cast<std::int32_t>(r);
  }
  return true;
}

/// The guide volume (D§3.5.3) of input port 1: its point arrays Weight_<label> and Region.
bool ReadGuide(vtkMSDiscreteSynthesis* self, vtkImageData* guide, msynth::SynthesisOptions& options)
{
  msynth::GuideVolume volume;
  int dims[3];
  guide->GetDimensions(dims);
  volume.Dims = { { dims[0], dims[1], dims[2] } };
  std::vector<std::pair<std::string, std::vector<float>>> arrays;
  try
  {
    arrays = vtkMSSynthesisRun::GuideWeights(guide);
  }
  catch (const msynth::Error& e)
  {
    vtkErrorWithObjectMacro(self, << "The " << e.what() << " (Weight_<label>).");
    return false;
  }
  for (auto& [suffix, weights] : arrays)
  {
    char* end = nullptr;
    const long value = std::strtol(suffix.c_str(), &end, 10);
    if (end == suffix.c_str() || *end != '\0')
    {
      vtkErrorWithObjectMacro(self, << "Guide array 'Weight_" << suffix
                                    << "' must be named Weight_<label> with one component.");
      return false;
    }
    volume.Weights[static_cast<msynth::Label>(value)] = std::move(weights);
  }
  if (!ReadGuideRegions(self, guide, volume))
    return false;
  if (volume.Weights.empty() && volume.Regions.empty())
  {
    vtkWarningWithObjectMacro(
      self, << "The guide has no point array named Weight_<label> or Region; it has no effect.");
  }
  options.Guide = std::move(volume);
  return true;
}

} // namespace

namespace vtkMSDiscreteSynthesisOptions
{
/// The engine's options from the filter's sizes and symmetries (shared by RequestInformation,
/// which counts the time steps, and RequestData).
msynth::SynthesisOptions SizeOptions(vtkMSDiscreteSynthesis* self)
{
  msynth::SynthesisOptions options;
  for (int a = 0; a < 3; ++a)
  {
    options.Symmetry[msynth::ToIndex(a)].Enabled = self->GetMirror()[a] != 0;
    options.Translate[msynth::ToIndex(a)].Enabled = self->GetTranslate()[a] != 0;
    options.Translate[msynth::ToIndex(a)].Period = self->GetTranslationPeriod()[a];
    options.Size[a] = self->GridSize(a);
    options.BlockSize[a] = self->GetBlockSize()[a];
    options.Overlap[a] = self->GetBlockOverlap()[a];
  }
  options.Rotate.Enabled = self->GetRotate();
  options.SnapshotsPerBlock = self->GetCatalogSnapshotsPerBlock();
  return options;
}

/// The engine's options from every property of the filter (and the guide, when connected).
bool BuildOptions(
  vtkMSDiscreteSynthesis* self, vtkImageData* guide, msynth::SynthesisOptions& options)
{
  options = SizeOptions(self);
  options.AttemptsPerBlock = self->GetAttemptsPerBlock();
  options.BacktracksPerAttempt = self->GetBacktracksPerAttempt();
  options.RepairFailedBlocks = self->GetRepairFailedBlocks();
  options.StartFrom = static_cast<msynth::BlockStart>(self->GetBlockStart());
  options.BlocksWhenWholeFails = self->GetBlocksWhenWholeFails();
  options.Threads = self->GetNumberOfThreads();
  options.Seed = static_cast<std::uint64_t>(self->GetSeed());
  options.Choice = static_cast<msynth::LabelChoice>(self->GetLabelChoice());
  options.Order = static_cast<msynth::SiteOrder>(self->GetSiteOrder());
  for (int f = 0; f < 6; ++f)
    if (self->GetUseBoundary()[f] || self->GetBoundaryFace(f))
      options.Boundary[msynth::ToIndex(f)] = self->GetBoundaryLabels()[f];
  if (self->GetUseTrivialLabel())
    options.TrivialLabel = self->GetTrivialLabel();
  options.ResemblanceWindow = self->GetResemblanceWindow();
  options.Progress = vtkMSSynthesisRun::Progress(self);
  return ReadSymmetryAndSoft(self, options) && (!guide || ReadGuide(self, guide, options));
}

namespace
{
/// A map drawn with the tileset's tiles (msynth::PinsFromPicture), or a picture drawn in the
/// colours of an image sample (msynth::PatternSet::PinsFromPicture); @p name names it in errors.
msynth::LabelGrid PinsOfPicture(
  vtkMSDiscreteSynthesis* self, const msynth::RgbaImage& picture, const std::string& name)
{
  const int source = self->GetActiveSource();
  if (source == vtkMSDiscreteSynthesis::SAMPLE_SOURCE)
  {
    msynth::OverlappingOptions po;
    po.N = self->GetPatternSize();
    po.Symmetry = self->GetPatternSymmetry();
    po.PeriodicInput = self->GetPeriodicInput();
    po.Ground = self->GetGround();
    const std::string sample = self->GetSampleFile();
    const msynth::PatternSet patterns =
      msynth::ExtractPatterns(msynth::ReadImage(sample), po, sample);
    const int* translate = self->GetTranslate();
    return patterns.PinsFromPicture(picture, name, { { translate[0] != 0, translate[1] != 0 } });
  }
  const std::string file = self->GetTilesetFile();
  const msynth::Tileset tiles = source == vtkMSDiscreteSynthesis::TILESET_SOURCE
    ? msynth::ReadTilesetFile(file, self->GetTilesetSubset(), self->GetTilesFolder())
    : msynth::Tileset();
  if (source != vtkMSDiscreteSynthesis::TILESET_SOURCE || tiles.Voxel)
    throw msynth::Error("a picture pins the tiles of a 2D tileset or the patterns of an image "
                        "sample; this run's rules come from " +
      std::string(tiles.Voxel ? "a voxel tileset" : "a label grid example") +
      " (pin its sites with a label grid: .vti, .txt, .vox)");
  return msynth::PinsFromPicture(picture, name, msynth::LoadTilePictures(file, tiles));
}

/// The pins of FixedFile: a picture by its extension, else a label grid.
/// Where a label grid of pins whose extent does not start at 0 lies in the output: its
/// extent's first corner (a smaller grid placed in the world); empty at 0.
std::optional<std::array<std::int64_t, 3>> PlacedAt(vtkImageData* image)
{
  int extent[6];
  image->GetExtent(extent);
  if (extent[0] == 0 && extent[2] == 0 && extent[4] == 0)
    return std::nullopt;
  return std::array<std::int64_t, 3>{ { extent[0], extent[2], extent[4] } };
}

msynth::LabelGrid PinsOfFile(vtkMSDiscreteSynthesis* self, const std::string& path,
  std::optional<std::array<std::int64_t, 3>>& origin)
{
  if (msynth::IsImageFile(path))
    return PinsOfPicture(self, msynth::ReadImage(path), path);
  std::array<int, 3> first{};
  msynth::LabelGrid pins = vtkMSLabelArrays::ReadLabelGridFile(path, first);
  if (first[0] != 0 || first[1] != 0 || first[2] != 0)
    origin = std::array<std::int64_t, 3>{ { first[0], first[1], first[2] } };
  return pins;
}

/// The pins of input port 2: its labels, or a picture drawn with a tileset's tiles.
msynth::LabelGrid PinsOfInput(vtkMSDiscreteSynthesis* self, vtkImageData* fixed,
  std::optional<std::array<std::int64_t, 3>>& origin)
{
  if (vtkUnsignedCharArray* picture = vtkMSLabelArrays::PictureBytes(fixed))
    return PinsOfPicture(self,
      vtkMSLabelArrays::PictureRows(fixed, picture, "a picture of pinned tiles"),
      "the picture of pinned tiles");
  msynth::LabelGrid pins;
  std::string problem;
  if (!vtkMSLabelArrays::ReadLabels(fixed, nullptr, pins, problem))
    throw msynth::Error(problem);
  origin = PlacedAt(fixed);
  return pins;
}
} // namespace

/// The pinned sites of input port 2 (when connected), else of FixedFile: labels, -1 where free
/// (and 0 with FixedEmptyFree); or, with a tileset, a picture drawn with its tiles.
bool ReadPins(vtkMSDiscreteSynthesis* self, vtkImageData* fixed, msynth::SynthesisOptions& options)
{
  const std::string file = self->GetFixedFile();
  if (!fixed && file.empty())
    return true;
  try
  {
    std::optional<std::array<std::int64_t, 3>> origin;
    msynth::LabelGrid pins =
      fixed ? PinsOfInput(self, fixed, origin) : PinsOfFile(self, file, origin);
    options.PinsOrigin = origin;
    if (self->GetFixedEmptyFree())
      std::replace(pins.Data().begin(), pins.Data().end(), msynth::Label(0), msynth::FreeSite);
    options.Pins = std::move(pins);
    return true;
  }
  catch (const std::exception& e)
  {
    // "Fixed File 'NAME': problem" (the problem names the file itself when it read it).
    const std::string what = e.what(), named = "'" + file + "'";
    const std::string text = fixed
      ? "Bad pinned sites (Fixed input): " + what
      : "Fixed File " + (what.compare(0, named.size(), named) == 0 ? what : named + ": " + what);
    vtkErrorWithObjectMacro(self, << text);
    return false;
  }
}

} // namespace vtkMSDiscreteSynthesisOptions
