// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/**
 * @file RunParts.h
 * @brief Internal to continuous synthesis (ContinuousSynthesis.cxx): what the workers of one run
 * share.
 */
#include "Continuous/ConstraintPlan.h"
#include "Continuous/ContinuousSynthesis.h"
#include "Continuous/RunEnds.h"
#include "Continuous/SolverParts.h"
#include "Core/BlockDriver.h"

#include <memory>
#include <vector>

namespace msynth
{
namespace detail
{

/**
 * What the workers of one run share, read-only while blocks run: the rules, each vertex's
 * starting catalog, the compiled constraints, the block layout and the schedule.
 */
struct RunParts
{
  RunParts(const PolyhedralAnalysis& analysis, const PlaneArrangement& arrangement,
    const ContinuousSynthesisOptions& options);

  const ArrangementRules Rules;
  std::unique_ptr<detail::ConstraintPlan> Plan;
  std::unique_ptr<detail::RunEnds> Ends; ///< runs as long as the example's (none: memoryless)
  double BlockSize = 0; ///< the block edge in plane spacings (options' or automatic)
  bool Whole = true;
  bool Parallel = true; ///< the schedule has phases of non-touching blocks
  std::unique_ptr<detail::BlockLayout> Layout;
  std::vector<std::uint64_t> Initial; ///< [vertex][word]: the catalog before anything is chosen
  std::vector<double> Weights;        ///< per label; empty: uniform
  std::vector<std::int64_t> Order;    ///< blocks (in the layout) in the order they are labelled
  BlockSchedule Schedule;             ///< per position in Order: its phase and generator key
};

} // namespace detail
} // namespace msynth
