// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/**
 * @file SoftConstraints.h
 * @brief Soft constraints (M07§4.2): each synthesized block is kept or rolled back with the
 * Metropolis probability, from the label counts of the model (target fractions) and an
 * optional fitness of the whole model. Decisions are made in block order.
 */
#include "Discrete/BlockSolver.h"
#include "Discrete/DiscreteSynthesis.h"

#include <cstdint>
#include <vector>

namespace msynth
{
namespace detail
{

class SoftConstraints
{
public:
  /// Over the model @p shared of @p n sites and its @p blocks blocks; rejections are counted in
  /// @p stats. Inactive (every block kept) when @p options has no soft constraint.
  /// @throw Error on a label the example lacks, a fraction outside [0, 1] or a temperature
  /// that is not positive.
  SoftConstraints(const AdjacencyRules& rules, const SynthesisOptions& options, SharedModel& shared,
    const Coord& n, std::size_t blocks, SynthesisStatistics& stats);

  /// Remembers block @p i's labels before it changes (thread-safe across blocks).
  void Save(std::size_t i, const Block& block);

  /// Keeps the synthesized block @p i (true) or restores its saved labels (false).
  bool Decide(std::size_t i, const Block& block);

private:
  /// N · (fraction − target)² of label @p b at @p count sites (0 without a target).
  double Energy(int b, std::int64_t count) const;
  LabelGrid ModelGrid() const;

  const AdjacencyRules& Rules;
  const SoftConstraint& Options;
  std::uint64_t Seed;
  SharedModel& Shared;
  Coord N;
  SynthesisStatistics& Stats;
  std::vector<double> Target;                   ///< per label index; -1: none
  std::vector<std::int64_t> Counts;             ///< per label index, in the current model
  double Fitness = 0.0;                         ///< of the current model
  std::vector<std::vector<std::int32_t>> Saved; ///< per block: (label, last block) per site
};

} // namespace detail
} // namespace msynth
