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
 * When the 2×2 condition fails on a 2D output, larger regions r_x × r_y are tried (up to
 * maxRegion per axis): the dissertation notes that Fig. 3.4(a) needs 3×2. Algorithm 3.6 then
 * picks the label at p from the catalog computed by propagation inside the window
 * [p − 1, p + r − 2] (the placed row below and left neighbour, and the unplaced sites to the
 * right and above as lookahead). Its reachable states are enumerated as a fixpoint: a state is
 * the placed row-below part of the window, the last r_x labels of the current row, and how many
 * sites lie right of p and rows above it (capped at the window's reach). The row below is
 * over-approximated by the set of (r_x + 1)-long windows that any generated row has shown, so
 * the enumeration is finite and covers every run; no failure among its states proves the
 * example infallible for every output size (Theorem 3.3.6).
 *
 * The proof follows the scan-line order of Algorithms 3.1 and 3.6: with other site orders a new
 * site may have placed neighbours on any side, and proved examples were seen to fail with
 * random order (ProvedExamplesNeverFailAlgorithm31 checks scan-line order only).
 */
#include "Discrete/AdjacencyRules.h"

#include <array>
#include <cstdint>
#include <string>

namespace msynth
{

struct InfallibilityReport
{
  bool Proved = false;
  bool Exhausted = false;          ///< the enumeration stopped at the configuration limit
  std::int64_t Configurations = 0; ///< consistent configurations (or window states) checked
  /// The region size of the proof (or of the last region tried), per axis of the output.
  std::array<int, 3> Region{ { 2, 2, 2 } };
  std::string Explanation; ///< why (a counterexample when not proved)
  /// "whole-model synthesis (Algorithm 3.1)" when proved, else block synthesis.
  std::string Recommendation;
};

/**
 * Checks the 2×2(×2)-region condition for outputs of @p outputSize (axes of size 1 are left
 * out, so 2D outputs give Eq. 3.11); for 2D outputs that it does not prove, then regions up to
 * @p maxRegion sites per axis (2: only 2×2; larger regions need k ≤ 64 labels). Each region
 * stops, not proved, after @p maxConfigurations configurations or states.
 */
InfallibilityReport AnalyzeInfallibility(const AdjacencyRules& rules,
  const std::array<std::int64_t, 3>& outputSize, std::int64_t maxConfigurations = 10000000,
  int maxRegion = 3);

/**
 * Algorithm 3.6 with an @p rx × @p ry region on 2D outputs along axes @p axes (scan order: the
 * first fastest), for every output size: the window-state enumeration described above.
 * Needs k ≤ 64 labels and 2 ≤ rx, ry ≤ 6.
 */
InfallibilityReport AnalyzeRegion2D(const AdjacencyRules& rules, const std::array<int, 2>& axes,
  int rx, int ry, std::int64_t maxStates = 2000000);

} // namespace msynth
