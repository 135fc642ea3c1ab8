// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/**
 * @file Connectivity.h
 * @brief Connected networks (SynthesisOptions::Connected, internal): the network's components,
 * the check of a solved block, and the repairs after the blocks.
 *
 * Components are found by a flood over face neighbours joined through connecting sides
 * (ConnectedNetwork::Sides). In block synthesis a site is *open* while a later block of the run
 * writes it (the block that writes it last has not run: LabelCounts.h's owners); a component is
 * open when one of its sites, or a neighbour one of its connecting sides faces, is open: it may
 * still grow into another. A component with no open site is *closed off*: it stays as it is. A
 * block attempt that leaves more closed-off components than the run may keep (Maximum − 1 while
 * open components remain, Maximum at the end) and more than before it is redone, except its
 * last attempt, which is kept as Algorithm 3.4 keeps it. When the blocks are done (or after a
 * whole model), each surplus component, smallest first, gets boxes synthesized again
 * (NetworkRepair.cxx): over gaps to other components, drawn steered along each gap (labels that
 * connect along it; the other sites keep theirs), then freely, then boxes around it (grown by
 * 1, 2, 4, ... sites), until a result has fewer components (it joined another or vanished); a
 * model left with more than Maximum fails, as does one whose repairs made 64 box attempts per
 * component and path site they started with (the work is bounded).
 * Pins hold throughout (a box keeps the fixed labels inside it, as a block does). With label
 * counts (LabelCounts.h) each block keeps its shares (planned a quarter of each range's span
 * inside it, room for the repairs), and each repair box keeps the model's counts in their ranges
 * (BlockSolver::SetCountsOfModel: a count's labels are no longer drawn once the sites outside
 * the box leave it none; free boxes are also steered toward the rest; an attempt that would
 * move a count out is redone), so the network, the counts and the pins hold together; a network
 * the repairs cannot join within the counts fails in one line that says how many attempts the
 * counts held back or turned down.
 * With a path (ConnectedNetwork::PathSites, PathLabels) the repairs first bring each listed
 * site into the network (boxes around it), then join the components holding path sites (boxes
 * over the gap to the nearest other such): a result is kept when it is nearer, compared in
 * the order listed sites outside the network, components holding path sites, components.
 *
 * An *open* network (ConnectedNetwork::Open, `LABELS:open`) is what connected means in a world
 * without bounds: no component is closed off, every one reaches the world's border or a pinned
 * site. Each block enforces it on what it reads (its footprint and the ring around it): an attempt
 * is redone when a component of the network's sites of that box with a site in the footprint
 * reaches neither the ring, nor the world's border, nor a pin (the last attempt is kept, as
 * Algorithm 3.4 keeps it). This is a function of what the block reads, so regions and streams
 * equal the whole run. Guaranteed: no component lies closed off inside the footprint of the
 * block that wrote it last (a component closed off across several blocks can remain: `check
 * --connected LABELS:open` finds it).
 */
#include "Core/Index.h"
#include "Discrete/BlockSolver.h"

#include <cstdint>
#include <memory>
#include <vector>

namespace msynth
{
namespace detail
{

/// The network's labels as label indices, and how two of them join.
class NetworkRule
{
public:
  NetworkRule(const AdjacencyRules& rules, const ConnectedNetwork& network);
  /// The sides label index @p b connects through (bit 2a: toward +a, 2a+1: toward -a), or -1
  /// when it is not a network label (or @p b < 0, undecided).
  int Sides(std::int32_t b) const { return b < 0 ? -1 : this->Mask[ToIndex(b)]; }

  /// The number of label indices.
  int Labels() const { return static_cast<int>(this->Mask.size()); }
  /// Whether label index @p b is one of the path's labels (ConnectedNetwork::PathLabels).
  bool OnPath(int b) const { return this->Path[ToIndex(b)] != 0; }

private:
  std::vector<int> Mask;
  std::vector<char> Path;
};

/// Refuses a network the rules or options cannot keep (unknown labels, Maximum < 1, symmetry,
/// soft constraints), with one line. Needs no model.
void CheckConnectedRequest(const AdjacencyRules& rules, const SynthesisOptions& options);

/// The number of the network's components in @p model (label indices over @p n; -1 undecided).
std::int64_t CountComponents(
  const NetworkRule& rule, const std::vector<std::int32_t>& model, const Coord& n);

/// The check of a solved block in block synthesis (see the file comment). One thread.
class NetworkGuard
{
public:
  /// @p blocks in run order over a model of @p n sites.
  NetworkGuard(const NetworkRule& rule, std::int64_t maximum, const std::vector<Block>& blocks,
    const Coord& n);
  /// An open network's check (see the file comment) over a model of @p n sites lying at @p off
  /// in a world of @p world sites, with @p pins (model-sized, or nullptr).
  NetworkGuard(const NetworkRule& rule, const Coord& n, const Coord& off, const Coord& world,
    const LabelGrid* pins);
  /// Whether the attempt whose labels are in @p cat (over @p block) may be kept in @p model.
  bool Keeps(const Block& block, const Catalog& cat, const std::vector<std::int32_t>& model);
  /// Attempts Keeps refused.
  std::int64_t Refused() const { return this->Redone; }

private:
  bool KeepsOpen(const Block& block, const Catalog& cat, const std::vector<std::int32_t>& model);

  /// The closed-off components among those the attempt's sites touch (see Keeps).
  template <class LabelFn, class OpenFn>
  std::int64_t ClosedAround(const Block& block, LabelFn&& label, OpenFn&& isOpen);
  /// Whether any component is open after the attempt (a network site, or a connecting side,
  /// at a site a later block writes), looked for from the later blocks' sites.
  template <class LabelFn>
  bool AnyOpenAfter(std::int32_t now, LabelFn&& label) const;

  const NetworkRule& Rule;
  std::int64_t Maximum;
  Coord N;
  std::vector<Block> Blocks;            ///< in run order
  std::vector<std::uint32_t> VisitCall; ///< per site, the local flood call that saw it last
  std::vector<std::int32_t> VisitFlood; ///< per site, which of that call's floods saw it
  std::uint32_t Call = 0;
  std::int64_t ClosedFor = -1; ///< the block index ClosedBefore was counted for
  std::int64_t ClosedBefore = 0;
  bool Open = false;
  Coord Off{ { 0, 0, 0 } }, World{ { 1, 1, 1 } };
  const LabelGrid* Pins = nullptr;
  std::vector<std::int32_t> OwnerPosition; ///< per site, the run position of its last block
  std::vector<std::int32_t> Position;      ///< per block index, its run position
  std::int64_t Redone = 0;
};

/**
 * After the blocks (or a whole model) on @p shared (NetworkRepair.cxx): the surplus components
 * re-synthesized in boxes by @p solver (block indices from @p firstIndex, draws from @p
 * options.Seed) until at most Maximum remain. Fills @p out; returns an empty string, or one line
 * saying why the network could not be kept.
 */
std::string RepairNetwork(BlockSolver& solver, SharedModel& shared, const NetworkRule& rule,
  const SynthesisOptions& options, std::int64_t firstIndex, SynthesisStatistics& stats,
  ConnectedResult& out);

/// A run's network: its rule and, with several blocks, the check @p solver makes of each.
class NetworkRun
{
public:
  NetworkRun(const AdjacencyRules& rules, const SynthesisOptions& options,
    const std::vector<Block>& blocks, BlockSolver& solver, const RegionCone* cone = nullptr);
  /**
   * After the blocks: the surplus components repaired (RepairNetwork, with block indices past
   * those of @p blocks) and @p r's figures filled; false, with @p r failed, when too many remain.
   */
  bool Keep(const SynthesisOptions& options, BlockSolver& solver, SharedModel& shared,
    const std::vector<Block>& blocks, SynthesisResult& r);

private:
  NetworkRule Rule;
  std::unique_ptr<NetworkGuard> Guard;
};

} // namespace detail
} // namespace msynth
