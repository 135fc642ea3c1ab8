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
 * With Ground, the grid's bottom row holds the ground pattern and no other row does.
 */
#include "Core/LabelGrid.h"
#include "Discrete/AdjacencyRules.h"
#include "Discrete/DiscreteSynthesis.h"
#include "Formats/Image.h"

#include <array>
#include <cstdint>
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
  /// The ground pattern fills the bottom row of the output and nowhere else: the window at the
  /// bottom middle of the sample (starting on its last row and wrapping to its top for a
  /// periodic output, its last N rows otherwise).
  bool Ground = false;
};

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
  std::array<std::vector<std::pair<int, int>>, 3> Pairs; ///< (b, c): c may follow b along +axis

  int NumberOfPatterns() const { return static_cast<int>(this->Counts.size()); }
  /// Pattern @p t's colour index at (@p x, @p y), y from the top.
  std::uint16_t At(int t, int x, int y) const
  {
    const int n = this->Options.N;
    return this->Cells[static_cast<std::size_t>((t * n + y) * n + x)];
  }
  /// Rules for the pattern grid: label values 0..k−1, weights the counts.
  AdjacencyRules Rules() const;
  /// The label grid size for a picture of @p width × @p height pixels. @throw Error when the
  /// picture is smaller than a pattern.
  std::array<std::int64_t, 3> SitesFor(
    std::int64_t width, std::int64_t height, bool periodicOutput) const;
  /// The ground pattern for a periodic or bounded output. @throw Error when the sample has no
  /// such window (a non-periodic sample asked for a wrapping one).
  int GroundPattern(bool periodicOutput) const;
  /// The guide that keeps the ground pattern on the bottom row of @p sites and off the others.
  GuideVolume GroundGuide(const std::array<std::int64_t, 3>& sites, bool periodicOutput) const;
  /// The picture of a grid of patterns (label values 0..k−1). @throw Error on other values.
  RgbaImage Compose(const LabelGrid& model, bool periodicOutput) const;
};

/**
 * The patterns of @p sample and their rules. @p name names the sample in errors.
 * @throw Error for bad options (N outside 1-8 or larger than the sample, symmetry outside 1-8),
 * more than 65536 colours or more than MaximumPatterns patterns.
 */
PatternSet ExtractPatterns(
  const RgbaImage& sample, const OverlappingOptions& options, const std::string& name);

/**
 * Checks a picture against its sample without the patterns' code: every N × N window of
 * @p picture (wrapping around its edges when @p periodicOutput) must be one of the sample's
 * windows or their first `Symmetry` dihedral images, colours compared as RGBA; with Ground, the
 * windows of the picture's bottom row must be the ground window and no other may be. Returns
 * the problems found (at most @p limit), empty when the picture is right.
 */
std::vector<std::string> CheckPicture(const RgbaImage& sample, const OverlappingOptions& options,
  const RgbaImage& picture, bool periodicOutput, std::size_t limit = 10);

} // namespace msynth
