// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/**
 * @file vtkMSCheckKinds.h
 * @brief Internal to vtkMSCheckModel (not wrapped): the verdict as field data, and the checks of
 * models that are not label images against examples: a picture against its image sample's
 * windows, a voxel model against a voxel tileset, and a label model's counts and connected
 * network. Each throws msynth::Error on bad input; the filter reports it.
 */
#include "Core/LabelGrid.h"
#include "Formats/PolyhedralExample.h"

#include <cstdint>
#include <string>
#include <vector>

class vtkFieldData;
class vtkImageData;

namespace vtkMSCheckKinds
{
/// The verdict's arrays: Valid, Violations, PairsChecked, Problems (one line each).
void AddVerdict(vtkFieldData* out, bool valid, std::int64_t violations, std::int64_t pairs,
  const std::vector<std::string>& problems);

/// How a picture is checked against its sample (vtkMSCheckModel's sample properties).
struct PictureCheck
{
  std::string SampleFile;
  int PatternSize = 3;
  int PatternSymmetry = 8;
  bool PeriodicInput = true;
  bool Ground = false;
  bool PeriodicOutput[2] = { false, false };
};

/// The picture @p model (colour scalars) against the windows of its sample (OverlappingModel.h:
/// CheckPicture); the verdict with `Violations` the problems found (at most @p limit, >= 1).
void CheckPicture(
  vtkImageData* model, const PictureCheck& check, std::size_t limit, vtkFieldData* out);

/// The voxel model @p model (palette indices, field data `PaletteRGBA`) against the voxel
/// tileset @p tileset (tiles in @p tiles): the verdict and `Cells` (VoxelTileset.h:
/// CheckVoxelModel).
void CheckVoxels(vtkImageData* model, const std::string& tileset, const std::string& tiles,
  std::size_t limit, vtkFieldData* out);

/// What a label model's pins, counts and network are checked for.
struct NetworkRequest
{
  std::string Counts;    ///< "L:MIN:MAX,..."
  std::string Connected; ///< "LABELS[:N]"
  std::string Path;      ///< "A;B;...": sites x,y[,z] or labels
  std::string Tileset;   ///< the names and sides (a tileset file), "" for values only
  std::string Subset;
  std::string Tiles;
  std::string Source; ///< the names' source in messages
  std::string Guide;  ///< the guide (.vti) whose `Region` array counts "region=R:..." read
  /// Pinned sites (a label grid .vti, .txt, .vox of the model's size, or a smaller .vti placed
  /// by its extent) the model must hold, "" for none; with PinsEmptyFree label 0 is free too.
  std::string Pins;
  bool PinsEmptyFree = false;
};

/**
 * The pins, counts and network of @p request in @p model (LabelChecks.h) as field data:
 * `PinsChecked`, `PinsMissed`, `PinsKept`; `CountNames`,
 * `CountMinimum`, `CountMaximum`, `CountAchieved`, `CountsKept`; `ConnectedLabels`,
 * `ConnectedMaximum`, `ConnectedComponents`, `ConnectedKept`, with a path `ConnectedPathSites`,
 * `PathComponents`, `PathJoined`; `Findings`, one line per count, network and path. Returns
 * whether all are kept (true when nothing was asked).
 */
bool CheckNetwork(const msynth::LabelGrid& model, const NetworkRequest& request, vtkFieldData* out);

/**
 * The structure of the 3D polyhedral @p model against its @p example's (ModelStructure.h), on
 * voxels and reach from @p spacing (the smallest plane spacing, 0 when unknown), as field data:
 * one tuple per measure in `ResemblanceMeasure`, `ResemblanceExample`, `ResemblanceModel`,
 * `ResemblanceBounds`, `ResemblancePasses`; `ResemblanceFailed` counts the measures out of
 * bounds. Planar examples add nothing. Returns the number out of bounds.
 */
int AddResemblance(vtkFieldData* out, const msynth::PolyhedralExample& example,
  const msynth::PolyhedralExample& model, double spacing);
} // namespace vtkMSCheckKinds
