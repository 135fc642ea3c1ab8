// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/**
 * @file FactorGraph.h
 * @brief Factor graphs over a grid of tile sites (Yeh et al. 2012, §3–5): the shapes of factors
 * and replacement blocks, and the factor functions learned from exemplars.
 *
 * A pattern is a label grid (2D, or 3D with depth). Its distribution is a product of factors
 * (Eq. 3), one per shape s and anchor site i whose scope fits in the grid:
 *  - hard pairwise factors φ2H, φ2V, φ2D (§5.1) along every axis of size > 1: 1 when the pair
 *    of labels occurs next to each other along that axis in some exemplar, else 0;
 *  - soft higher-order factors (§5.2) on chosen shapes: 1 + ε when the configuration under the
 *    shape occurs in an exemplar (of the anchor's zone), else 1.
 *
 * Shapes are stencils: offsets from the anchor, normalised so the smallest offset along each
 * axis is 0 (the anchor is the scope's lowest corner).
 */
#include "Core/Index.h"
#include "Core/LabelGrid.h"

#include <array>
#include <cstdint>
#include <string>
#include <unordered_set>
#include <utility>
#include <vector>

namespace msynth
{

/// A factor or block shape.
struct Stencil
{
  std::string Name;
  std::vector<std::array<int, 3>> Offsets;  ///< distinct, smallest along each axis 0
  std::array<int, 3> Extent{ { 1, 1, 1 } }; ///< largest offset + 1 per axis
  bool Is3D() const { return this->Extent[2] > 1; }
};

/**
 * A shape from its name:
 *  - `NH`, `NV`, `ND`: N sites in a row along x, y or z (`2H`, `4V`, ...);
 *  - `AxB`, `AxBxC`: a rectangle or box of A × B (× C) sites (`2x2`, `3x3`, `2x2x2`);
 *  - any stencil: offsets joined by `+`, each `x:y` or `x:y:z` (`0:0+1:0+1:1`, an L).
 * At most 64 sites and 64 per axis. @throw Error naming the text and the problem.
 */
Stencil ParseStencil(const std::string& text);
/// Comma-separated shapes ("2H,2V,4H,4V"); empty items are skipped.
std::vector<Stencil> ParseStencils(const std::string& list);
/// The soft shapes of a factor list (`msynth pattern --factors`): every shape but the pairs
/// 2H, 2V, 2D, which are always hard; comma-separated names ("" for none).
std::string SoftShapes(const std::string& factors);

/**
 * The replacement-block schemes B1–B6 (§8.3, Fig. 5), growing sets of block shapes. The
 * figure's shapes are not in the text; ours are, in 2D: B1 single sites; B2 + 2H, 2V; B3 + 2x2;
 * B4 + 3H, 3V; B5 + 3x3; B6 + 4H, 4V. In 3D every scheme also has its shapes' depth versions
 * (2D, 2x2x2, 3D, 3x3x3, 4D). @throw Error for a number outside 1–6.
 */
std::vector<Stencil> BlockScheme(int scheme, bool threeD);

/**
 * What the exemplars say (the analysis phase, §4): the tiles, the hard pairs and, for each soft
 * shape, the configurations each exemplar shows; and the replacement blocks (each block shape's
 * distinct configurations over all exemplars).
 */
struct FactorModel
{
  std::vector<Label> Tiles; ///< label values of the tiles, ascending
  int NumberOfTiles() const { return static_cast<int>(this->Tiles.size()); }
  int TileIndex(Label value) const { return IndexOfLabel(this->Tiles, value); }
  /// Exemplars' extent > 1 along each axis (pairs along an axis need it).
  std::array<bool, 3> AxisSeen{ { false, false, false } };
  /// Per axis, T × T bytes: Pairs[a][b * T + c] = 1 when tile c follows tile b along +a.
  std::array<std::vector<std::uint8_t>, 3> Pairs;
  std::vector<Stencil> SoftShapes;
  /// Observed[s][e]: keys (ConfigurationKey) of the configurations of shape s in exemplar e.
  std::vector<std::vector<std::unordered_set<std::uint64_t>>> Observed;
  std::vector<Stencil> BlockShapes;
  /// BlockTiles[b]: the distinct configurations of block shape b, |offsets| tile indices each.
  std::vector<std::vector<std::int32_t>> BlockTiles;
  int NumberOfExemplars = 0;

  bool Allowed(int axis, int b, int c) const
  {
    return this->Pairs[axis][ToIndex(b) * this->Tiles.size() + ToIndex(c)] != 0;
  }
};

/// The key of a configuration of tile indices (a 64-bit mix; the same tiles in the same order
/// give the same key).
inline std::uint64_t ConfigurationKey(const std::int32_t* tiles, std::size_t n)
{
  std::uint64_t h = 0x84222325cbf29ce4ull ^ n;
  for (std::size_t i = 0; i < n; ++i)
  {
    h ^= static_cast<std::uint64_t>(static_cast<std::uint32_t>(tiles[i])) + 0x9e3779b97f4a7c15ull;
    h *= 0xbf58476d1ce4e5b9ull;
    h ^= h >> 29;
  }
  return h;
}

/// Label pairs (first, second) allowed along +x, +y, +z besides the exemplars' (a tileset's
/// neighbor rules, as label values).
using LabelPairs = std::array<std::vector<std::pair<Label, Label>>, 3>;

/**
 * Learns the factors from @p exemplars (§5): the tiles are every label value an exemplar or
 * @p extra holds, the hard pairs the exemplars' and @p extra's. A shape that fits in no exemplar
 * learns nothing (a soft factor that is never 1 + ε; a block shape with no blocks, which is
 * dropped); single tiles (1x1, when a block shape) are blocks for every tile, so tiles that only
 * @p extra names can be placed. @throw Error for no exemplars and no extra pairs, more than
 * 65536 tiles, or no block shape with blocks.
 */
FactorModel LearnFactors(const std::vector<LabelGrid>& exemplars,
  const std::vector<Stencil>& softShapes, const std::vector<Stencil>& blockShapes,
  const LabelPairs& extra = LabelPairs());

} // namespace msynth
