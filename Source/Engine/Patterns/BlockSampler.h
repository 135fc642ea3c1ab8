// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/**
 * @file BlockSampler.h
 * @brief The samplers on a PatternProblem (internal to Patterns/): BLOCKSS and single-site
 * Metropolis–Hastings, chosen by PatternOptions::Method.
 */
#include "Patterns/PatternProblem.h"

#include <functional>
#include <string>

namespace msynth
{
namespace detail
{

/// Receives each kept sample: tile indices, per-site last change, seconds since the start.
using SampleSink =
  std::function<void(const std::vector<std::int32_t>&, const std::vector<std::int64_t>&, double)>;

/// Mends each kept sample's tile indices in place before it is taken (a connected network's
/// repairs); the chain goes on from the mended pattern. Returns why the sample could not be
/// mended ("" when it was).
using SampleRepair = std::function<std::string(std::vector<std::int32_t>&)>;

/**
 * Runs the burn-in and the samples of @p options on @p problem from @p start (tile indices; empty:
 * drawn at random), counting moves in @p result. @p repair (may be empty) mends each kept sample
 * first; the sites it changes take the move count as their last change; a sample it cannot mend
 * moves on by another sample's moves and is mended again, ten tries in all.
 * @return false when the progress callback cancelled. @throw Error when MaxMoves runs out.
 */
bool RunSampler(const PatternProblem& problem, const PatternOptions& options,
  const std::vector<std::int32_t>& start, PatternResult& result, const SampleSink& take,
  const SampleRepair& repair = SampleRepair());

} // namespace detail
} // namespace msynth
