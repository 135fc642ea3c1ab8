// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/**
 * @file SampleList.h
 * @brief Sample lists (`samples.xml`) of the original model-synthesis program and of
 * WaveFunctionCollapse: a `<samples>` element whose children are runs, in order:
 *
 *     <overlapping name="Flowers" N="3" symmetry="2" ground="-4" periodic="True"/>
 *     <simpletiled name="Knots" subset="Dense" width="24" height="24" periodic="True"/>
 *     <tiledmodel name="castle.txt" width="40" length="40" height="10" blockWidth="10"/>
 *
 * Files are found beside the list as each program lays them out: an overlapping sample at
 * `samples/NAME.png` (or `.bmp`); a tileset at `tilesets/NAME.xml` or `samples/NAME/data.xml`;
 * a tiled model at `samples/NAME` (or `samples/NAME.txt`); each also directly beside the list,
 * and in this project's own layout (`Samples/`, `Tilesets/`, `Examples/`, as in `Data/`).
 * Defaults are WaveFunctionCollapse's: overlapping N 2, symmetry 8, periodic input, bounded
 * output; two screenshots (outputs) per entry, one for a tiled model. The output is `size` ×
 * `size` (48 pixels for an image sample, 24 tiles for a tileset, when absent), and `width` or
 * `height`, when given, replaces one side, as WaveFunctionCollapse reads its own lists. `ground` is
 * on for any value but `False` and 0 (the older lists give the pattern index, e.g. -4). A tiled
 * model's sizes are width (x), length (y) and height (z); with no length, height is the second
 * axis, as the original program reads them. Attributes neither program uses are ignored; `limit`
 * and `textOutput` are accepted and not used.
 */
#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace msynth
{

struct SampleEntry
{
  enum Kinds
  {
    Overlapping,
    SimpleTiled,
    TiledModel
  };
  Kinds Kind = Overlapping;
  std::string Element; ///< as written: overlapping, simpletiled, tiledmodel
  std::string Name;
  std::string Subset;
  std::string File; ///< the example found for it (the first candidate when none exists)
  std::array<std::int64_t, 3> Size{ { 0, 0, 1 } };  ///< pixels, tiles or sites
  std::array<std::int64_t, 3> Block{ { 0, 0, 0 } }; ///< blockWidth, blockLength, blockHeight
  int N = 2;
  int Symmetry = 8;
  bool PeriodicInput = true;
  bool Periodic = false;
  bool Ground = false;
  int Screenshots = 2;
  int Line = 0; ///< in the list
};

/**
 * The entries of the sample list @p path. @throw Error "'path', line N: problem" for malformed
 * XML, a root other than <samples>, an entry without a name, or values that are not numbers,
 * booleans or sizes in range. Elements other than the three kinds are skipped.
 */
std::vector<SampleEntry> ReadSampleList(const std::string& path);

} // namespace msynth
