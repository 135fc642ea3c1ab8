// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/**
 * @file LabelCounts.h
 * @brief Label counts (SynthesisOptions::Counts, internal): the checks made before any work, and
 * the split of each label's range over the blocks of a run.
 *
 * Each site belongs to the block that writes it last in the run's order (phase, then scan
 * order): its *own* sites. No later block of the run changes them, so when every block keeps
 * the number of a label's sites among its own within its share, the whole model keeps the
 * label's range. The shares split the range in proportion to each block's own free sites
 * (cumulative rounding, so they add up exactly and depend on sizes alone, not threads); sites
 * fixed by boundary labels or pins count where they lie. A block run again in a repair pass
 * must also leave the count of every other block's own sites inside it unchanged.
 *
 * A count of a guide region (LabelCount::Region) counts the sites whose guide cell belongs to
 * the region: its range is split over the blocks in proportion to their own free sites in the
 * region. Each site has a *slot*: 0 when its region is counted by no count, else 1 + the
 * counted region's place; a label and a slot name at most one count.
 */
#include "Core/Index.h"
#include "Discrete/BlockSolver.h"

#include <cstdint>
#include <optional>
#include <vector>

namespace msynth
{
namespace detail
{

/// Refuses counts the rules, the sizes and the options make impossible, or options that cannot
/// keep counts (symmetry, soft constraints), with one line. Needs no model.
void CheckCountRequest(const AdjacencyRules& rules, const SynthesisOptions& options);

/// The number of sites of each counted label of @p model (label values), in the whole model or
/// in the count's region of @p guide.
std::vector<LabelCountResult> CountLabels(const std::vector<LabelCount>& counts,
  const LabelGrid& model, const std::optional<GuideVolume>& guide);

/// One line naming the first count @p results miss, or empty when all are kept.
std::string CountMiss(const std::vector<LabelCountResult>& results);

/**
 * @p r with its counts (@p finished: a model was made), failed with one line when a count is
 * missed; @p misses attempts solved their block but missed its counts (named in a failure).
 */
SynthesisResult CountsKept(
  const SynthesisOptions& options, SynthesisResult r, std::int64_t misses, bool finished);

/// The shares of a run's blocks (see the file comment).
class CountBudget
{
public:
  /**
   * Plans the shares of @p options.Counts over @p blocks (in run order) of a model of @p n sites
   * whose fixed label indices are @p fixed (-1: free).
   * @throw Error when the fixed sites already make a count impossible.
   */
  CountBudget(const AdjacencyRules& rules, const SynthesisOptions& options,
    const std::vector<Block>& blocks, const Coord& n, const std::vector<std::int32_t>& fixed);

  /// The counts' positions 0, 1, ... (one per SynthesisOptions::Counts entry).
  const std::vector<int>& Labels() const { return this->Counted; }
  /// The count (position in Labels()) that label index @p b counts in at a site of slot
  /// @p slot (see the file comment), or -1.
  int Position(int b, std::int32_t slot) const
  {
    return this->PositionOf[ToIndex(slot) * this->K + ToIndex(b)];
  }
  /// The slot of model site @p s.
  std::int32_t Slot(std::size_t s) const { return this->Slots.empty() ? 0 : this->Slots[s]; }
  /// The block (BoxBlock::Index) that writes model site @p s last.
  std::int32_t Owner(std::size_t s) const { return this->Owners[s]; }
  std::int64_t Minimum(std::int64_t block, std::size_t c) const
  {
    return this->Min[ToIndex(block) * this->Counted.size() + c];
  }
  std::int64_t Maximum(std::int64_t block, std::size_t c) const
  {
    return this->Max[ToIndex(block) * this->Counted.size() + c];
  }

private:
  std::vector<int> Counted;
  std::vector<int> PositionOf;     ///< [slot][label index]
  std::size_t K = 0;               ///< labels
  std::vector<std::int32_t> Slots; ///< per site; empty: every site is of slot 0
  std::vector<std::int32_t> Owners;
  std::vector<std::int64_t> Min, Max; ///< [block index][counted label]
};

} // namespace detail
} // namespace msynth
