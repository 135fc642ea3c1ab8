// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/**
 * @file ConsistencyCheck.h
 * @brief Checks a model against an example (Eq. 3.1) without any solver data structure: the
 * allowed pairs are recomputed from the example grid itself, then every adjacent pair of the
 * model is looked up. Used by tests and by `msynth check` to verify outputs independently.
 */
#include "Core/LabelGrid.h"

#include <array>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace msynth
{

struct ConsistencyViolation
{
  std::array<std::int64_t, 3> Site{ { 0, 0, 0 } }; ///< x, the first site of the pair
  int Axis = 0;                                    ///< the pair is (x, x + axis); 3: time
  std::int64_t Time = -1;                          ///< the frame of a time-varying model
  Label From = 0;
  Label To = 0;
  std::string Describe() const;
};

struct ConsistencyReport
{
  bool Consistent = true;
  std::int64_t PairsChecked = 0;
  std::int64_t Violations = 0;             ///< all violations counted
  std::vector<ConsistencyViolation> First; ///< the first few, in scan order
};

/// Every adjacent pair (x, x + d) of @p model must occur in @p example (Eq. 3.1).
ConsistencyReport CheckConsistency(
  const LabelGrid& example, const LabelGrid& model, std::size_t maxReported = 10);

/// Every adjacent pair of @p model must be listed in @p allowed (per axis, (first, second)
/// label pairs, e.g. a tileset's expanded neighbors).
ConsistencyReport CheckConsistency(const std::array<std::vector<std::pair<int, int>>, 3>& allowed,
  const LabelGrid& model, std::size_t maxReported = 10);

/// Every adjacent pair of @p model must occur along its axis in one of @p examples or be listed
/// in @p allowed (a tileset's pairs); the exemplars of pattern synthesis, or a mix.
ConsistencyReport CheckConsistency(const std::vector<LabelGrid>& examples,
  const std::array<std::vector<std::pair<int, int>>, 3>& allowed, const LabelGrid& model,
  std::size_t maxReported = 10);

} // namespace msynth
