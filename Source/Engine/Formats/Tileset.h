// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/**
 * @file Tileset.h
 * @brief Simple-tiled tilesets in the XML format popularised by WaveFunctionCollapse:
 *
 *     <set unique="False">
 *       <tiles> <tile name="corner" symmetry="L" weight="0.5"/> ... </tiles>
 *       <neighbors> <neighbor left="corner 1" right="line"/> ... </neighbors>
 *       <subsets> <subset name="small"> <tile name="corner"/> ... </subset> </subsets>
 *     </set>
 *
 * Each tile has a symmetry class that fixes how many distinct orientations it has: X (1),
 * I (2), \ (2), L (4), T (4), F (8). Orientation k + 1 is orientation k turned 90°
 * counter-clockwise; orientations 4-7 (class F) are 0-3 mirrored left-right. Every orientation
 * of every tile is one label. A neighbor entry "A i" left of "B j" names A and B each in the
 * orientation reached from orientation 0 by dihedral element i (j), 0-7 (DihedralAction; 0
 * when omitted), and holds in all 8 rotations and reflections of that two-tile configuration,
 * which gives the allowed pairs along x (left → right) and y (bottom → top). `<set size>` and
 * `unique`, `<subsets>` and tile `weight` are read too.
 */
#include "Discrete/AdjacencyRules.h"

#include <array>
#include <cstdint>
#include <istream>
#include <map>
#include <string>
#include <utility>
#include <vector>

namespace msynth
{

struct TilesetTile
{
  std::string Name;
  char Symmetry = 'X'; ///< X, I, \, L, T or F
  double Weight = 1.0;
  int FirstLabel = 0; ///< label of orientation 0; orientation k is FirstLabel + k
  int Orientations = 1;
  /// Voxel tilesets: the label of the tile's image under each symmetry (SymmetryGroup order).
  std::vector<int> SymmetryLabels;
};

struct Tileset
{
  bool Unique = false; ///< one image per orientation (else per tile, rotated)
  int TileSize = 0;    ///< `<set size="...">`: the tile images' width in pixels (0: not given)
  /// `<set turned="false">`: the tiles are never turned (pattern exemplars' tiles, each drawn
  /// as is): every tile has one orientation (class X) and its `connects` sides are as written.
  bool Turned = true;
  std::vector<TilesetTile> Tiles;
  std::vector<int> LabelTile;        ///< per label: index into Tiles
  std::vector<int> LabelOrientation; ///< per label: orientation (voxel sets: a symmetry giving it)
  std::array<std::vector<std::pair<int, int>>, 3> Pairs; ///< allowed (first, second) per axis
  /// Per label, the sides a path through it connects (a tile's `connects="right top"`, turned
  /// with its orientation): bit 0 +x (right), 1 -x (left), 2 +y (top), 3 -y (bottom); -1 for a
  /// tile that does not say (it joins its neighbours through every side).
  std::vector<int> LabelSides;

  /// MarkovJunior voxel tilesets (root <tileset>, Formats/VoxelTileset.h): a label is a tile's
  /// distinct image under the square's 8 symmetries (the cube's 48 with FullSymmetry).
  bool Voxel = false;
  bool FullSymmetry = false;
  std::array<int, 3> VoxelSize{ { 0, 0, 0 } };         ///< S, S, SZ
  std::string TilesFolder;                             ///< where the tiles' .vox files were read
  std::vector<std::vector<std::uint32_t>> LabelVoxels; ///< per label: VoxelBlock voxels

  int NumberOfLabels() const { return static_cast<int>(this->LabelTile.size()); }
  /// The label name as the format's published sets name images: "tile k" (or "tile").
  std::string LabelName(int label) const;
  /// Each label's image turned 90° counter-clockwise (the same tile's next orientation): the
  /// label map of rotation symmetry (Rotation::Map) for outputs of this tileset.
  std::map<Label, Label> TurnMap() const;
  /// A voxel tileset's labels mirrored across the plane normal to @p axis (x -> S-1-x for 0):
  /// the label map of reflection symmetry (Mirror::Map). Empty for a simple-tiled set, and for
  /// z without FullSymmetry unless every image is its own mirror image in z. @throw Error then.
  std::map<Label, Label> MirrorMap(int axis) const;
  /// Adjacency rules (label values 0..n-1, weights from the tiles) for 2D synthesis.
  AdjacencyRules Rules() const;
};

/// Orientation reached from @p orientation of a tile of class @p symmetry by turning it 90°
/// counter-clockwise (@p mirror false) or mirroring it left-right (@p mirror true).
int TransformOrientation(char symmetry, int orientation, bool mirror);
/**
 * The orientation reached from @p orientation by element @p element (0-7) of the dihedral
 * group, numbered as WaveFunctionCollapse numbers it: 0 the identity, 1-3 one to three quarter
 * turns counter-clockwise, 4-7 those followed by the left-right mirror. "tile k" in a neighbor
 * rule means DihedralAction(symmetry, 0, k), so "b_i 3" (class I) is orientation 1.
 */
int DihedralAction(char symmetry, int orientation, int element);
/// The sides @p sides (bits +x, -x, +y, -y) after dihedral element @p element (as DihedralAction).
int TransformSides(int sides, int element);
/// Number of distinct orientations of class @p symmetry (1, 2, 4 or 8), 0 for an unknown class.
int OrientationCount(char symmetry);
/// A tile's `weight` attribute (both tileset formats): a finite positive number, else false.
bool ParseTileWeight(const std::string& text, double& weight);

/**
 * The folder of a tileset's images, in either layout the published sets use: `NAME.xml` beside
 * a folder `NAME/`, or the older `NAME/data.xml` with the images beside it.
 */
std::string TilesetImageFolder(const std::string& xmlPath);
/// The image of @p orientation of @p tile (`tile.png`, or `tile k.png` in a unique set; `.bmp`
/// when only that exists, as older sets have it).
std::string TileImageFile(
  const std::string& xmlPath, const Tileset& set, const TilesetTile& tile, int orientation);

/**
 * Reads a tileset; @p name is used in error messages, @p subset selects a <subset> ("" for all
 * tiles). A `<tileset>` root is a MarkovJunior voxel tileset (VoxelTileset.h), its tiles read
 * from @p tiles (VoxelTilesFolder; @p name is then the XML's path). @throw Error "'name', line
 * N: problem" for malformed XML, unknown tiles, symmetry classes or orientations.
 */
Tileset ReadTileset(std::istream& in, const std::string& name, const std::string& subset = "",
  const std::string& tiles = "");
Tileset ReadTilesetFile(
  const std::string& path, const std::string& subset = "", const std::string& tiles = "");

} // namespace msynth
