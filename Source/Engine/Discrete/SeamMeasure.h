// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/**
 * @file SeamMeasure.h
 * @brief Whether block borders show in a model synthesized in blocks (issue 44, item 4): the
 * frequencies of its W × W (× W) label windows that touch a block border against those of its
 * interior windows, and the same places in a whole run of the same size as the yardstick (the
 * whole run's own variation between those two sets of windows, which have the same sizes and
 * positions). `msynth quality --seams` prints it.
 *
 * A block of m sites starting at o is synthesized with its ring (sites o − 1 and o + m) held, so
 * a seam is where a block's ring held labels the block had to continue: the planes between
 * sites o − 1 and o and between o + m − 1 and o + m, for every block origin o of the lattice
 * (BlockStarts), except the world's own faces. A window touches a border when it holds a site
 * on either side of such a plane. Distances are total variation distances, ½ Σ |p(c) − q(c)|
 * over window configurations c: 0 for the same frequencies, 1 for disjoint ones.
 */
#include "Core/LabelGrid.h"

#include <array>
#include <cstdint>
#include <vector>

namespace msynth
{

/// The window statistics of a block run's borders, its interior and a whole run.
struct SeamMeasure
{
  int Window = 2;                     ///< window edge W in sites (1 along a flat axis)
  std::int64_t BorderWindows = 0;     ///< windows touching a block border
  std::int64_t InteriorWindows = 0;   ///< the other windows
  double BorderVsInterior = 0.0;      ///< distance of the model's border and interior windows
  double BorderTop = 0.0;             ///< share of the most frequent border window
  double InteriorTop = 0.0;           ///< share of the most frequent interior window
  bool HasWhole = false;              ///< whether a whole run was given (the fields below)
  double WholeBorderVsInterior = 0.0; ///< the whole run's windows at the same places
  double BorderVsWhole = 0.0;         ///< the model's border windows against all the whole run's
  double InteriorVsWhole = 0.0;       ///< the model's interior windows against all the whole run's
  double WholeBorderTop = 0.0; ///< share of the most frequent whole-run window at the borders
  /// BorderVsInterior − WholeBorderVsInterior: how much more the borders differ from the
  /// interior than the whole run's own windows at those places do (0 without a whole run).
  double Excess() const
  {
    return this->HasWhole ? this->BorderVsInterior - this->WholeBorderVsInterior : 0.0;
  }
};

/// The planes between sites p − 1 and p along each axis where a block's ring held labels, for a
/// grid of @p size sites in blocks of @p block sites overlapping by @p overlap (-1: half a
/// block), as BlockGeometry and BlockStarts lay them out; none along an axis the blocks span.
std::array<std::vector<std::int64_t>, 3> BlockBorderPlanes(const std::array<std::int64_t, 3>& size,
  const std::array<std::int64_t, 3>& block, const std::array<std::int64_t, 3>& overlap);

/**
 * The seam measure of @p model against the borders @p planes (BlockBorderPlanes), with
 * windows of @p window sites per axis (1 along a flat axis), and against @p whole (a whole run
 * of the same size; nullptr: none).
 * @throw Error when @p window is below 1 or larger than the model, or @p whole's size differs.
 */
SeamMeasure MeasureSeams(const LabelGrid& model,
  const std::array<std::vector<std::int64_t>, 3>& planes, int window,
  const LabelGrid* whole = nullptr);

} // namespace msynth
