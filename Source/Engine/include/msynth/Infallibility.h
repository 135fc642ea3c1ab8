// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/**
 * @file Infallibility.h
 * @brief Proving an example infallible (dissertation §3.3.7): Algorithm 3.1 then cannot fail.
 *
 * Theorem 3.3.6: if Algorithm 3.6 (catalogs computed only within small regions R, r ≥ 2)
 * cannot fail, the example is infallible. With 2×2(×2) regions filled in scan order, each new
 * site p sees only its already placed neighbours in the cube below/behind it. So Algorithm 3.6
 * cannot fail exactly when, for every consistent placement of those corners (every pair of
 * corners one step apart allowed by the rules), some label at p agrees with the corners next to
 * it. In 2D this is Eq. 3.11 plus the boundary cases (a site with only a left, or only a lower,
 * neighbour: every label needs a successor along each axis). The corners are enumerated here
 * with backtracking; the analysis is a sufficient condition ("proved" or "not proved").
 *
 * The proof follows the scan-line order of Algorithms 3.1 and 3.6: with other site orders a new
 * site may have placed neighbours on any side, and proved examples were seen to fail with
 * random order (ProvedExamplesNeverFailAlgorithm31 checks scan-line order only).
 */
#include "msynth/AdjacencyRules.h"

#include <array>
#include <cstdint>
#include <string>

namespace msynth
{

struct InfallibilityReport
{
  bool Proved = false;
  bool Exhausted = false;          ///< the enumeration stopped at the configuration limit
  std::int64_t Configurations = 0; ///< consistent corner configurations checked
  std::string Explanation;         ///< why (a counterexample when not proved)
  /// "whole-model synthesis (Algorithm 3.1)" when proved, else block synthesis.
  std::string Recommendation;
};

/**
 * Checks the 2×2(×2)-region condition for outputs of @p outputSize (axes of size 1 are left
 * out, so 2D outputs give Eq. 3.11). Stops, not proved, after @p maxConfigurations.
 */
InfallibilityReport AnalyzeInfallibility(const AdjacencyRules& rules,
  const std::array<std::int64_t, 3>& outputSize, std::int64_t maxConfigurations = 10000000);

} // namespace msynth
