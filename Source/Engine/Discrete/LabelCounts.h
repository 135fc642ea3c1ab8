// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/**
 * @file LabelCounts.h
 * @brief Label counts (SynthesisOptions::Counts, internal): the checks made before any work, and
 * the split of each label's range over the blocks of a run.
 *
 * Each site belongs to the block of the world's lattice (Core/WorldSchedule.h) that writes it
 * last in the run's order (phase, then scan order): its *own* sites. No later block of the run
 * changes them, so when every block keeps the number of a label's sites among its own within its
 * share, the whole model keeps the label's range. A count of the whole output is a count of the
 * world, shared by position alone: site s of the world (x fastest, N sites) carries
 * floor(MIN (s + 1) / N) - floor(MIN s / N) units of the minimum and as many of the span
 * MAX - MIN, and a block's share is [its own sites' minimum units, that + their span units]. The
 * shares add up to exactly [MIN, MAX] over the world and depend on nothing but the block's
 * position, so a region or a stream of a world (WindowRun.h) keeps the shares of the whole run:
 * guaranteed per block of the lattice, hence in any union of blocks' own sites, and the world's
 * total when the whole world is computed. Sites fixed by boundary labels or pins count in the
 * block that owns them; a block whose fixed sites leave its share impossible is refused. A block
 * run again in a repair pass must also leave the count of every other block's own sites inside it
 * unchanged. With a connected network kept by repairs of the whole model (Connectivity.h) the
 * shares are planned over the range narrowed by a quarter of its span on each side (the full
 * range when pins leave a block no room for that): the repairs, which keep the whole range
 * (BlockSolver::SetCountsOfModel), then have room to lay or lift counted labels.
 *
 * A count of a guide region (LabelCount::Region) counts the sites whose guide cell belongs to
 * the region: its range is split over the run's blocks in proportion to their own free sites in
 * the region (cumulative rounding in block order; guides are refused in regions of a world). Each
 * site has a *slot*: 0 when its region is counted by no count, else 1 + the counted region's place;
 * a label and a slot name at most one count.
 */
#include "Core/Index.h"
#include "Core/WorldSchedule.h"
#include "Discrete/BlockSolver.h"

#include <cstdint>
#include <optional>
#include <unordered_map>
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

/// Every block any pass of @p cone may run, once each, in window coordinates: the blocks whose
/// counts a window of a world keeps.
std::vector<Block> CountedBlocks(const RegionCone& cone);

struct OwnPrefix;

/// The shares of a run's blocks (see the file comment).
class CountBudget
{
public:
  /**
   * Plans the shares of @p options.Counts over @p blocks (in run order, keys of the world's
   * lattice) of a model of @p n sites whose fixed label indices are @p fixed (-1: free); the
   * model is the window of @p cone in its world when given, else the world.
   * @throw Error when the fixed sites already make a count impossible.
   */
  CountBudget(const AdjacencyRules& rules, const SynthesisOptions& options,
    const std::vector<Block>& blocks, const Coord& n, const std::vector<std::int32_t>& fixed,
    const RegionCone* cone = nullptr);

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
  /// The block (BoxBlock::Index, the world's key) that writes model site @p s last.
  std::int64_t Owner(std::size_t s) const { return this->Owners[s]; }
  std::int64_t Minimum(std::int64_t block, std::size_t c) const
  {
    return this->Min[this->Rows.at(block) * this->Counted.size() + c];
  }
  std::int64_t Maximum(std::int64_t block, std::size_t c) const
  {
    return this->Max[this->Rows.at(block) * this->Counted.size() + c];
  }
  /// Count @p c's range over the whole model (its MIN and MAX): what a connected network's
  /// repairs keep (BlockSolver::SetCountsOfModel).
  std::int64_t RangeMinimum(std::size_t c) const { return this->WholeMin[c]; }
  std::int64_t RangeMaximum(std::size_t c) const { return this->WholeMax[c]; }

private:
  /// The shares of count @p c of the world (the file comment): by each block's prefix of own
  /// sites in index order (@p owners).
  void WorldShares(const LabelCount& want, std::size_t c, const std::vector<Block>& blocks,
    const OwnPrefix& owners, const Coord& off, const std::vector<std::int64_t>& free,
    const std::vector<std::int64_t>& pinned);
  /// The shares of count @p c of a guide region: @p total fixed sites and @p open free ones
  /// there, split by the blocks' own free sites in run order.
  void RegionShares(const LabelCount& want, std::size_t c, const std::vector<std::int64_t>& free,
    const std::vector<std::int64_t>& pinned, std::int64_t total, std::int64_t open);

  std::vector<int> Counted;
  std::vector<int> PositionOf;     ///< [slot][label index]
  std::size_t K = 0;               ///< labels
  std::vector<std::int32_t> Slots; ///< per site; empty: every site is of slot 0
  std::vector<std::int64_t> Owners;
  std::unordered_map<std::int64_t, std::size_t> Rows; ///< block key → its place in the run
  std::vector<std::int64_t> Min, Max;                 ///< [block's place][counted label]
  std::vector<std::int64_t> WholeMin, WholeMax;       ///< per count, its MIN and MAX
};

} // namespace detail
} // namespace msynth
