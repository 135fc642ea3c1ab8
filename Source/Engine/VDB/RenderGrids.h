// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/**
 * @file RenderGrids.h
 * @brief The grids a renderer shades, made from a label volume (a discrete model): no OpenVDB
 * types here; the grids are made in the OpenVDB module (RenderGrids.cxx) as the file is written.
 *
 * For a label volume (one label per voxel, the voxels of GridHeader's geometry) the file gets,
 * all with the label grid's transform (index (i, j, k) at Origin + (i, j, k) * Spacing):
 * - `density`: FloatGrid, `GRID_CLASS` fog volume: 1 at the solid voxels (label != EmptyLabel
 *   and not INT_MIN, the undecided sites of a catalog snapshot), inactive 0 elsewhere;
 * - `color`: Vec3SGrid of linear RGB at the solid voxels (Colors of their label), inactive
 *   (0, 0, 0) elsewhere; Blender's Color Attribute node reads it by this name;
 * - `surface`: FloatGrid, `GRID_CLASS` level set: the exact signed distance from each voxel
 *   centre to the boundary of the solid voxels' union (each voxel the box of Spacing around its
 *   centre; outside the volume is empty), negative inside, active where it is below
 *   HalfWidth voxels (the narrow band), inactive ±HalfWidth * VoxelSize elsewhere (the
 *   background, VoxelSize the smallest spacing);
 * - `surface_NAME` per name of Names: the same of the solid voxels whose NameKeys value has
 *   that name, written only while voxels × names ≤ LabelSurfaceBudget (each costs a pass over
 *   its names' bounding box); `surface`'s metadata `msynth_label_surfaces` says which were
 *   written or why none were.
 */
#include "VDB/VDBFile.h"

#include <array>
#include <cmath>
#include <cstdint>
#include <map>
#include <string>
#include <vector>

namespace msynth
{
namespace vdb
{

/// A label volume to write as render grids (see the file's description).
struct LabelRenderView
{
  GridHeader Geometry; ///< IndexMin, Dims, Origin, Spacing (Name, Type, Background unused)
  const std::int32_t* Labels = nullptr; ///< Geometry.NumberOfVoxels() labels, x fastest
  std::int32_t EmptyLabel = 0;          ///< the label of empty voxels
  /// Linear RGB per label (labels missing here are grey, 0.5).
  std::map<std::int32_t, std::array<float, 3>> Colors;
  /// The key of each voxel's name (x fastest as Labels), or nullptr: the labels themselves.
  const std::int32_t* NameKeys = nullptr;
  /// Names of keys; keys of one name make one `surface_NAME`.
  std::map<std::int32_t, std::string> Names;
  double HalfWidth = 3.0;          ///< narrow band half width, in voxels (≥ 1)
  double LabelSurfaceBudget = 2e7; ///< the most voxels × names of `surface_NAME` grids
};

/// A display (sRGB) colour component in [0, 1] as a linear one, as glTF and renderers use.
inline float LinearFromSrgb(double c)
{
  c = c < 0 ? 0 : (c > 1 ? 1 : c);
  return static_cast<float>(c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4));
}

/// Whether `surface_NAME` grids of @p names names over @p voxels voxels fit @p budget.
inline bool LabelSurfacesFit(std::int64_t voxels, std::size_t names, double budget)
{
  return static_cast<double>(voxels) * static_cast<double>(names) <= budget;
}

/// A name as a grid name's suffix: characters other than letters, digits, '-' and '.' become '_'.
inline std::string GridNameSuffix(std::string name)
{
  for (char& c : name)
  {
    const bool kept = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') ||
      c == '-' || c == '.';
    c = kept ? c : '_';
  }
  return name;
}

/**
 * @brief Writes @p grids, the level sets of @p meshes and the render grids of @p labels to
 * @p path, atomically (as the other WriteFile overloads).
 * @throw Error naming the file: also for a label volume without labels or a band narrower
 * than one voxel.
 */
void WriteFile(const std::string& path, const std::vector<DenseGridView>& grids,
  const std::vector<MeshGridView>& meshes, const std::vector<LabelRenderView>& labels,
  const MetadataMap& metadata);

} // namespace vdb
} // namespace msynth
