// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/**
 * @file VoxelSurface.h
 * @brief The surface of a label grid seen as voxels: every site is a cube (its point ± half
 * the spacing); a face is emitted wherever a non-empty site meets a different label or the
 * outside, oriented outward from that site. Each label's faces therefore form closed,
 * consistently oriented surfaces (where two labels meet there is one face for each).
 */
#include "Core/LabelGrid.h"

#include <array>
#include <cstdint>
#include <vector>

namespace msynth
{

struct VoxelSurface
{
  std::vector<std::array<double, 3>> Points;
  std::vector<std::array<std::int64_t, 4>> Quads; ///< counter-clockwise seen from outside
  std::vector<Label> QuadLabels;                  ///< label of the voxel each quad bounds
};

/// The sites with Begin <= coordinate < End along Axis (a piece of a grid split in slabs).
struct SiteSlab
{
  int Axis = 2;
  std::int64_t Begin = 0;
  std::int64_t End = INT64_MAX;
};

/// Extracts the voxel surface of @p grid; sites with label @p empty produce nothing, and
/// neither do sites outside @p slab. Faces are decided by the whole grid, so the surfaces of
/// slabs that tile the grid put together are the surface of the grid.
VoxelSurface ExtractVoxelSurface(const LabelGrid& grid, Label empty,
  const std::array<double, 3>& origin, const std::array<double, 3>& spacing,
  const SiteSlab& slab = SiteSlab());

/**
 * The voxel surface of @p grid with its faces merged: the faces of one label that face one way
 * in one plane become rectangles (greedy, row by row, in scan order). Each label covers the
 * same area in each direction as in ExtractVoxelSurface, with far fewer quads; where rectangles
 * meet there are T-junctions, so this is a surface to render and export (mesh.vtp of a voxel
 * model), not a closed mesh.
 */
VoxelSurface ExtractMergedVoxelSurface(const LabelGrid& grid, Label empty,
  const std::array<double, 3>& origin, const std::array<double, 3>& spacing);

/// The slab of piece @p piece of @p pieces (0 <= piece < pieces) that splits @p grid evenly
/// along its longest axis (pieces beyond the axis's length get empty slabs).
SiteSlab PieceSlab(const LabelGrid& grid, int piece, int pieces);

} // namespace msynth
