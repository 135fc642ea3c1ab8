// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/**
 * @file OverlappingModel.h
 * @brief Image samples (the "overlapping model" of WaveFunctionCollapse, and of the original
 * model-synthesis program): the labels are the sample's N × N pixel windows ("patterns"),
 * weighted by how often they occur; pattern c may follow pattern b along an axis when the two
 * agree where they overlap, shifted by one pixel (N × (N − 1) pixels).
 *
 * Windows are read as WaveFunctionCollapse reads them: every window whose top-left pixel is in
 * the sample, wrapping around its edges with PeriodicInput (else only those inside it), rows
 * from the top, each with the first `Symmetry` of its eight dihedral images in the order
 * identity, mirror, quarter turn, mirror of the turn, half turn, its mirror, three quarter
 * turns, its mirror. Patterns are numbered by first occurrence in that scan.
 *
 * Synthesis is ordinary discrete synthesis on a label grid of patterns, y up: grid site (x, y)
 * is the window whose top-left pixel is picture pixel (x, H_s − 1 − y) of a picture H_s sites
 * high. A picture of W × H pixels needs (W − N + 1) × (H − N + 1) sites (each pixel of the last
 * N − 1 rows and columns comes from the last site's window), or W × H sites when it repeats
 * (periodic output: translation symmetry along x and y with the picture's size as period).
 * With Ground, the grid's bottom row holds ground patterns and no other row does: for an output
 * repeating along y the window at the bottom middle of the sample that starts on its last row
 * (wrapping to its top), as WaveFunctionCollapse; otherwise the windows of the sample's last N
 * rows, so the picture ends in the sample's bottom rows.
 */
#include "Core/Index.h"
#include "Core/LabelGrid.h"
#include "Discrete/AdjacencyRules.h"
#include "Discrete/DiscreteSynthesis.h"
#include "Formats/Image.h"

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace msynth
{

struct OverlappingOptions
{
  int N = 3;                 ///< pattern size in pixels (1-8)
  bool PeriodicInput = true; ///< windows wrap around the sample's edges
  int Symmetry = 8;          ///< 1-8: how many of each window's dihedral images are patterns
  /// Ground patterns fill the bottom row of the output and nowhere else (see above).
  bool Ground = false;
};

/// Whether the output picture repeats (tiles seamlessly) along x and along y.
using Periodic = std::array<bool, 2>;

/// The largest sample: 2^20 pixels (a 1024 x 1024 picture), so reading its windows is bounded.
constexpr std::int64_t MaximumSamplePixels = std::int64_t(1) << 20;

/// The largest number of patterns a sample may give (the rules take 6 k² bits).
constexpr int MaximumPatterns = 8192;

class PatternSet
{
public:
  OverlappingOptions Options;
  int SampleWidth = 0;
  int SampleHeight = 0;
  std::vector<std::array<std::uint8_t, 4>> Colours; ///< RGBA of each colour index
  std::vector<std::uint16_t> Sample;                ///< colour index per pixel, rows from the top
  std::vector<std::uint16_t> Cells;                 ///< N × N colour indices per pattern
  std::vector<double> Counts;                       ///< occurrences of each pattern
  /// Per sample pixel (rows from the top), the pattern of the window read there as it is (its
  /// identity image); -1 where no window starts (the last N − 1 rows and columns of a sample
  /// read without wrapping).
  std::vector<int> WindowPatterns;
  std::array<std::vector<std::pair<int, int>>, 3> Pairs; ///< (b, c): c may follow b along +axis

  int NumberOfPatterns() const { return static_cast<int>(this->Counts.size()); }
  /// Pattern @p t's colour index at (@p x, @p y), y from the top.
  std::uint16_t At(int t, int x, int y) const
  {
    const int n = this->Options.N;
    return this->Cells[ToIndex((t * n + y) * n + x)];
  }
  /// Rules for the pattern grid: label values 0..k−1, weights the counts.
  AdjacencyRules Rules() const;
  /// The label grid size for a picture of @p width × @p height pixels that repeats along x and
  /// y as @p periodic says. @throw Error when the picture is smaller than a pattern.
  std::array<std::int64_t, 3> SitesFor(
    std::int64_t width, std::int64_t height, const Periodic& periodic) const;
  /// The ground patterns for an output repeating along y or not. @throw Error when the sample
  /// has no such window (a non-periodic sample asked for a wrapping one).
  std::vector<int> GroundPatterns(bool periodicY) const;
  /// The guide that keeps the ground patterns on the bottom row of @p sites and off the others.
  GuideVolume GroundGuide(const std::array<std::int64_t, 3>& sites, bool periodicY) const;
  /**
   * The sample repeated over a grid of @p sites (site (x, y) is the window at (x mod width,
   * row mod height) of the sample), a consistent start for block synthesis that, unlike a
   * model of one pattern, leaves every block the sample's variety around it. Empty when the
   * sample does not wrap (PeriodicInput off), with Ground, or where the output repeats along an
   * axis by a length that is not a multiple of the sample's.
   */
  std::optional<LabelGrid> TiledStart(
    const std::array<std::int64_t, 3>& sites, const Periodic& periodic) const;
  /**
   * Sets up @p options (Size already the grid's) for these patterns: the ground guide with
   * Ground (@throw Error when @p options has a guide already), and for block synthesis an
   * undecided start first where the output does not repeat (UndecidedFirst: the tiled start's
   * wrap would show along the block borders) and, without a guide, the tiled start where there
   * is one.
   */
  void Configure(SynthesisOptions& options, const Periodic& periodic) const;
  /// The picture of a grid of patterns (label values 0..k−1). @throw Error on other values.
  RgbaImage Compose(const LabelGrid& model, const Periodic& periodic) const;
  /**
   * The inverse of Compose for a partly drawn picture (`--fixed map.png`): the site whose
   * N × N window (wrapping where @p periodic) holds no fully transparent pixel of a colour
   * the sample lacks is pinned to the pattern equal to that window; the others are free (-1).
   * @throw Error naming @p path and the window (its top-left pixel, rows from the top) that is
   * none of the patterns, or a picture smaller than a pattern.
   */
  LabelGrid PinsFromPicture(
    const RgbaImage& picture, const std::string& path, const Periodic& periodic) const;
};

/**
 * The patterns of @p sample and their rules. @p name names the sample in errors.
 * @throw Error for bad options (N outside 1-8 or larger than the sample, symmetry outside 1-8),
 * a sample over MaximumSamplePixels, more than 65536 colours or more than MaximumPatterns
 * patterns (all bounded before anything grows with them).
 */
PatternSet ExtractPatterns(
  const RgbaImage& sample, const OverlappingOptions& options, const std::string& name);

/**
 * Checks a picture against its sample without the patterns' code: every N × N window of
 * @p picture (wrapping around the edges along which it is @p periodic) must be one of the sample's
 * windows or their first `Symmetry` dihedral images, colours compared as RGBA; with Ground, the
 * windows of the picture's bottom row must be ground windows and no other may be. Returns
 * the problems found (at most @p limit), empty when the picture is right.
 */
std::vector<std::string> CheckPicture(const RgbaImage& sample, const OverlappingOptions& options,
  const RgbaImage& picture, const Periodic& periodic, std::size_t limit = 10);

} // namespace msynth
