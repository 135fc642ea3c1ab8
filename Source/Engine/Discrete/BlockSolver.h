// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/**
 * @file BlockSolver.h
 * @brief The discrete solver of one block (internal): Algorithm 3.4's lines 9-29 on a catalog
 * (Discrete/Catalog.h) over the block, with what constrains the block from outside (the model
 * around it, boundary layers, mirror planes, symmetry seams) and the label choice (uniform,
 * frequency, resemblance of M07§3, the guide of D§3.5.3), plus the trivial start and catalog
 * snapshots. One solver a worker thread; all of them share one SharedModel. The run over the
 * blocks is Core/BlockDriver.h's BlockDriver, whose client Discrete/DiscreteSynthesis.cxx makes.
 *
 * BlockSolver.cxx holds the block attempt, the trivial start and the snapshots;
 * BlockSolverWeights.cxx the label weights (guide, resemblance) and the site constraints.
 */
#include "Core/BlockDriver.h"
#include "Core/Index.h"
#include "Core/Random.h"
#include "Discrete/Catalog.h"
#include "Discrete/DiscreteSynthesis.h"
#include "Discrete/MirrorPlan.h"
#include "Discrete/SymmetryPlan.h"

#include <array>
#include <cstdint>
#include <functional>
#include <map>
#include <string>
#include <vector>

namespace msynth
{
struct RegionCone;

namespace detail
{

class CountBudget;
class NetworkGuard;

/// A group of touching pins by its box in world coordinates (low corner, high corner), and the
/// scale of its placement block (BlockSolver::PlacePins: 1, 2, 4, ...).
using PinScales = std::map<std::array<std::int64_t, 6>, std::int64_t>;

/// Thrown by BlockSolver::PlacePins in a window of a world: a group's placement block must grow
/// to Scale, which the window was not planned for.
struct PinScaleNeeded
{
  std::array<std::int64_t, 6> Group;
  std::int64_t Scale = 1;
};

using Coord = std::array<std::int64_t, 3>;
using Block = BoxBlock<3>;

/// "(x, y, z)".
inline std::string Format(const Coord& c)
{
  return "(" + std::to_string(c[0]) + ", " + std::to_string(c[1]) + ", " + std::to_string(c[2]) +
    ")";
}

/// A box's size, "NX x NY x NZ".
inline std::string FormatSize(const Coord& n)
{
  return std::to_string(n[0]) + " x " + std::to_string(n[1]) + " x " + std::to_string(n[2]);
}

/// Visits the model index of every site of @p block (x fastest).
template <typename Visit>
void ForEachSite(const Block& block, const Coord& n, Visit&& visit)
{
  Coord p;
  for (p[2] = block.Origin[2]; p[2] < block.Origin[2] + block.Dims[2]; ++p[2])
    for (p[1] = block.Origin[1]; p[1] < block.Origin[1] + block.Dims[1]; ++p[1])
      for (p[0] = block.Origin[0]; p[0] < block.Origin[0] + block.Dims[0]; ++p[0])
        visit(ToIndex(p[0] + n[0] * (p[1] + n[1] * p[2])));
}

/// The model being synthesized, shared by the solvers of all threads. Blocks of one phase
/// never touch, so threads write disjoint sites.
struct SharedModel
{
  std::vector<std::int32_t> Model;     ///< label indices; -1 unassigned
  std::vector<std::int32_t> Fixed;     ///< boundary label indices; -1 free
  std::vector<std::int32_t> LastBlock; ///< block that last changed each site
};

/// The solver of one worker: its own catalog and scratch space over the shared model.
class BlockSolver
{
public:
  /// A solver over @p shared; the first solver of a run sizes it, later ones (one per extra
  /// thread) share it.
  BlockSolver(const AdjacencyRules& rules, const SynthesisOptions& options, const MirrorPlan* plan,
    const SymmetryPlan* seams, SharedModel& shared);

  /// Boundary layers (Fig. 3.11), with precedence -z, +z, -y, +y, -x, +x.
  void ApplyBoundary();

  /// SynthesisOptions::Pins as fixed labels, checked (PinnedSites.cxx). Returns their number.
  std::int64_t ApplyPins();
  /// Block synthesis: each group of touching pins not in the start yet gets a block around it
  /// (its box grown by half a block of size @p m on each side, doubled while it cannot be solved).
  /// With @p cone the model is a window of a world: draws and block boxes are the world's, and
  /// a block that must grow past its size in @p scales (1 when not listed) throws
  /// PinScaleNeeded (the window holds those sizes only: WindowRun.h).
  void PlacePins(const Coord& m, std::uint64_t seed, std::int64_t& assignments,
    const RegionCone* cone = nullptr, const PinScales* scales = nullptr);

  /// The start of Algorithm 3.4 (lines 3-5), checked for consistency (TrivialStart.cxx): one
  /// trivial label everywhere, else one per layer along an axis. Returns the label most sites
  /// start with.
  int TrivialStart();

  /// One attempt at a block (lines 9-29 of Algorithm 3.4). Returns -1 on success, else the
  /// model index of the site whose catalog became empty.
  std::int64_t RunBlock(const Block& block, Random& rng, std::int64_t& assignments);

  /// After a block: emit its snapshots (padded to SnapshotsPerBlock with the final state).
  void CommitSnapshots(std::int64_t assignments);

  /// Before the first block: the snapshot of the start.
  void StartSnapshots();

  /// Whether the run reports catalog snapshots.
  bool Snapshots() const { return this->Options.SnapshotsPerBlock > 0 && this->Options.OnSnapshot; }

  /// Joins a run: @p driver (may be null) tells when it is being cancelled; @p worker is this
  /// solver's worker number there.
  void Attach(BlockDriver* driver, unsigned worker)
  {
    this->Driver = driver;
    this->Worker = worker;
  }

  /// Attempts per block (the options').
  int Attempts() const { return this->Options.AttemptsPerBlock; }

  /// The size of the model (the part synthesized, for a symmetric output).
  const Coord& Size() const { return this->N; }

  /// The order of the sites in a block (the options', until a repair pass sets another).
  SiteOrder Order() const { return this->SiteOrderNow; }
  void SetOrder(SiteOrder order) { this->SiteOrderNow = order; }

  /// Choices undone by backtracking, over all blocks so far.
  std::int64_t Backtracks() const { return this->Backtracked; }

  /// Drops the snapshots of the block just run (it keeps its previous labels).
  void DropSnapshots() { this->Pending.clear(); }

  /// Keeps label counts by @p budget from now on (not owned; nullptr: none). BlockCounts.cxx.
  void UseCounts(const CountBudget* budget) { this->Budget = budget; }
  /// In a repair pass every block has run: a block must keep the others' own counts.
  void SetRepairing(bool repairing) { this->Repairing = repairing; }
  /**
   * A connected network's repairs (NetworkRepair.cxx) run boxes over a finished model: with
   * @p whole every site of a box counts, and a box is kept when each count of the model stays
   * in its range (CountBudget::RangeMinimum, RangeMaximum; one already outside may not move
   * farther out): a count's labels are not drawn once the range leaves the box none, and a box
   * without a SiteBias is steered toward it as a block is. Off: the blocks' shares.
   */
  void SetCountsOfModel(bool whole) { this->CountsOfModel = whole; }
  /// Attempts that solved their block but missed its label counts, over all blocks so far.
  std::int64_t CountMisses() const { return this->Misses; }
  /// Attempts of SetCountsOfModel boxes that met a count at its range's end (its labels could
  /// not be drawn there any more), over all so far.
  std::int64_t CountLimits() const { return this->Limits; }

  /// Checks each solved block against a connected network by @p guard (not owned; nullptr:
  /// none); Connectivity.h.
  void UseNetwork(NetworkGuard* guard) { this->Network = guard; }
  /// Whether the coming attempt is its block's last (kept even when it closes a component off).
  void SetFinalAttempt(bool last) { this->FinalAttempt = last; }
  /// Multiplies the weight of each label index by @p scale's (not owned; nullptr: none) in the
  /// weighted choice (a network's repairs).
  void ScaleWeights(const std::vector<double>* scale) { this->Scale = scale; }
  /// Per model site and label index, a multiplier of the weight in the choice there (a network
  /// repair's box steered along a gap; Connectivity.cxx).
  using SiteBias = std::function<double(std::int64_t site, int b)>;
  /// Multiplies the choice's weights by @p bias (not owned; nullptr: none), after ScaleWeights.
  void BiasWeights(const SiteBias* bias) { this->Bias = bias; }

private:
  friend class BlockSearch;

  /// Pinned labels next to each other or to boundary labels that the rules never put together.
  void CheckPinnedPairs() const;
  /// Arc consistency from the fixed labels over the pins' box [@p lo, @p hi], grown by 16 sites.
  void CheckPinsPropagate(const Coord& lo, const Coord& hi);

  /// Label counts (BlockCounts.cxx): the block's own sites and their decided counts after the
  /// block is constrained.
  void StartCounts(const Block& block);
  /// Brings Have and Left up to date with the catalog's changes since the last call.
  void SyncCounts();
  /// Re-tallies own site @p local from the catalog.
  void TallySite(std::int64_t local);
  /// The label of a free own site @p local, drawn with the counted labels' weights steered
  /// toward the block's shares (see CountBudget).
  int ChooseCounted(std::int64_t local, Random& rng);
  /// The weights a counted choice at @p local starts from, as ChooseLabel's (resemblance or
  /// site weights, a network repair's steering), before the counts move them.
  void CountedWeights(std::int64_t local, std::vector<double>& weight);
  /// Whether the solved block keeps its shares (and, repairing, the other blocks' counts).
  bool CountsKept(const Block& block);
  /// The least and most sites of count @p c the current block's own sites may hold.
  std::int64_t ShareMinimum(std::size_t c) const;
  std::int64_t ShareMaximum(std::size_t c) const;

  /// The example as label indices, and the window offsets, for LabelChoice::Resemblance.
  void SetUpResemblance();

  /// The decided label index at model site @p q during the current block (-1: undecided).
  int DecidedLabel(const Coord& q) const;

  /// L(k) of Eqs. 4-5 for every label of the catalog at @p local (written to @p weights):
  /// the number of example sites holding k whose window is at the minimum distance d0.
  void ResemblanceWeights(std::int64_t local, std::vector<double>& weights);

  /// Dense guide weights [cell][label index] and, per cell, the mask of labels allowed there.
  void SetUpGuide(const GuideVolume& guide);

  /// Unary constraints of a free site @p p: the guide (at the site and, with symmetry, at each
  /// of its mirror images for the mirrored label) and the mirror planes' last layers.
  bool KeepSiteConstraints(Catalog& cat, std::int64_t local, const Coord& p);

  int LabelIndex(Label value, const char* what) const;

  /// Calls @p fn(p, q, axis) for every pair of sites q = p + 1 along an axis, in scan order.
  template <typename Fn>
  void ForEachAdjacentPair(Fn&& fn) const
  {
    Coord p;
    for (p[2] = 0; p[2] < this->N[2]; ++p[2])
      for (p[1] = 0; p[1] < this->N[1]; ++p[1])
        for (p[0] = 0; p[0] < this->N[0]; ++p[0])
          for (int axis = 0; axis < 3; ++axis)
          {
            Coord q = p;
            if (++q[axis] < this->N[axis])
              fn(p, q, axis);
          }
  }

  /// SynthesisOptions::Start in the model, checked. Returns its commonest label.
  int GivenStart(const LabelGrid& start);

  /// The labels site @p s may hold (@p out: Words() words): its boundary label, else those the
  /// guide and the symmetry's unary constraints allow.
  void SiteMask(std::size_t s, std::uint64_t* out) const;

  /// Per layer along @p axis, the labels all its sites may hold that are adjacent to themselves
  /// along the output's other axes.
  std::vector<std::uint64_t> LayerMasks(int axis) const;

  /// One label per layer along @p axis forming a consistent start, or empty.
  std::vector<int> LayeredStart(int axis) const;

  /// The start (@p what names it, @p t its commonest label) against the mirror planes, the
  /// guide, Eq. 3.3 and the seams.
  void CheckStart(int t, const std::string& what) const;

  /// The start must also satisfy the symmetry's seams and unary constraints.
  void CheckStartAgainstSeams(const std::string& start) const;

  /// Lines 12-17 of Algorithm 3.4 for @p block on the reset catalog: fixed labels inside, the
  /// labels around it, unary site constraints, then propagation. Fills @p free with the free
  /// sites (local indices); returns -1, or the local site whose catalog became empty.
  std::int64_t ConstrainBlock(const Block& block, std::vector<std::int64_t>& free);

  /// Translation/rotation seams from site @p p (local @p local) to sites outside @p block.
  bool ConstrainAcrossSeams(const Block& block, std::int64_t local, const Coord& p);

  /// A label for site @p local drawn from its catalog: by resemblance (M07 Eqs. 4-6) or by
  /// weight, each times the guide's weight of the site's region (D§3.5.3).
  int ChooseLabel(std::int64_t local, Random& rng);

  /// Minimum-entropy order with a priority queue (no full scan per step): entries are pushed
  /// when a site's catalog changes and skipped when stale.
  template <typename AssignFn>
  std::int64_t AssignByEntropy(
    const std::vector<std::int64_t>& free, Random& rng, AssignFn&& assign);

  /// Entropy of the weighted labels still possible at @p local of the current catalog (the
  /// guide's weights included).
  double Entropy(const Catalog& cat, std::int64_t local) const;

  /// The whole model now: outside the active block, the model; inside, the catalog.
  CatalogSnapshot Capture(const Block* active, std::int64_t assignments) const;

  /// During an attempt: capture when the block's decided fraction reaches the next milestone.
  void MaybeCapture(const Block& block, std::int64_t assignments);

  bool HasGuide() const { return !this->GuideWeights.empty(); }

  /// The guide cell of model site @p p.
  std::int64_t GuideCell(const Coord& p) const
  {
    // The guide spans the full output, also when only a part of it is synthesized.
    return this->Options.Guide->CellOf(
      p, this->Plan ? this->Plan->Full : (this->Seams ? this->Seams->Full : this->N));
  }

  float GuideWeight(std::int64_t cell, int b) const
  {
    return this->GuideWeights[ToIndex(cell * this->Rules.NumberOfLabels() + b)];
  }

  /// The weight of label @p b at a site of guide cell @p cell (the base weight without a guide).
  double SiteWeight(std::int64_t cell, int b) const
  {
    return this->HasGuide() ? this->Weight(b) * this->GuideWeight(cell, b) : this->Weight(b);
  }

  /// The guide cell of a site of the current catalog region.
  std::int64_t GuideCellOfLocal(std::int64_t local) const
  {
    const Coord c = this->Cat.Coordinates(local);
    const Coord& o = this->Cat.Origin();
    return this->GuideCell({ { o[0] + c[0], o[1] + c[1], o[2] + c[2] } });
  }

  double Weight(int b) const
  {
    return this->Options.Choice == LabelChoice::Frequency ? this->Rules.Weights()[ToIndex(b)] : 1.0;
  }

  std::int64_t Index(const Coord& p) const
  {
    return p[0] + this->N[0] * (p[1] + this->N[1] * p[2]);
  }

  Coord Coordinates(std::int64_t index) const
  {
    return { { index % this->N[0], (index / this->N[0]) % this->N[1],
      index / (this->N[0] * this->N[1]) } };
  }

  /// Whether the run is being cancelled (the driver's poll, every 1024th of @p assignments, or
  /// every one when labels are many: with thousands of an image sample's patterns an assignment
  /// and its propagation take up to a tenth of a second); the block's decided sites tell the
  /// progress callback how far it is.
  bool Poll(std::int64_t assignments)
  {
    return this->Driver && (detail::PollDue(assignments) || this->Cat.NumberOfLabels() > 256) &&
      this->Driver->Stopped(this->Worker,
        static_cast<double>(this->Cat.Decided()) /
          static_cast<double>(std::max<std::int64_t>(1, this->Cat.NumberOfSites())));
  }

  const AdjacencyRules& Rules;
  const SynthesisOptions& Options;
  Catalog Cat;
  const MirrorPlan* Plan;                        ///< symmetric synthesis of a half, or nullptr
  const SymmetryPlan* Seams;                     ///< translation/rotation: a domain, or nullptr
  std::vector<int> ExampleIndex;                 ///< resemblance: the example as label indices
  std::vector<std::array<int, 3>> WindowOffsets; ///< resemblance: window offsets but the centre
  std::vector<std::int64_t> ResemblanceCounts;
  std::vector<double> ChoiceWeights;
  std::vector<std::uint64_t> MaskScratch;
  std::vector<std::int64_t> FreeSites;   ///< the current block's free sites (local indices)
  std::vector<float> GuideWeights;       ///< [guide cell][label index]; empty: no guide
  std::vector<std::uint64_t> GuideMasks; ///< [guide cell][word]: labels with weight > 0
  std::vector<CatalogSnapshot> Pending;  ///< snapshots of the current attempt
  BlockDriver* Driver = nullptr;         ///< the run (cancellation), or nullptr
  unsigned Worker = 0;                   ///< this solver's worker number in Driver
  std::int64_t Steps = 0;
  std::int64_t Backtracked = 0;                 ///< choices undone by BlockSearch, over all blocks
  SiteOrder SiteOrderNow = SiteOrder::ScanLine; ///< the options' (a repair pass's may differ)
  std::vector<std::int64_t> Position; ///< scan orders: each free site's place in the order
  double FullEntropy = 0.0;
  Coord N{ { 1, 1, 1 } };
  std::vector<std::int32_t>& Model;     ///< label indices; -1 unassigned (shared)
  std::vector<std::int32_t>& Fixed;     ///< boundary label indices; -1 free (shared)
  std::vector<std::int32_t>& LastBlock; ///< block that last changed each site (shared)
  std::vector<double> WLogW;
  const CountBudget* Budget = nullptr; ///< label counts, or nullptr
  NetworkGuard* Network = nullptr;     ///< a connected network's check, or nullptr
  bool FinalAttempt = false;
  const std::vector<double>* Scale = nullptr; ///< per label index, or nullptr
  const SiteBias* Bias = nullptr;             ///< per model site and label index, or nullptr
  bool Repairing = false;
  bool CountsOfModel = false; ///< SetCountsOfModel
  bool LimitedNow = false;    ///< this attempt met a count at its range's end (CountLimits)
  std::int64_t Limits = 0;
  std::int64_t Misses = 0;
  std::vector<std::int64_t> BoxMin, BoxMax; ///< CountsOfModel: per count, the box's range
  std::int64_t OwnBlock = -1;               ///< the block whose shares apply (counts)
  std::vector<std::int32_t> Own;            ///< per local site: 0, or 1 + its count slot if own
  std::vector<std::int64_t> Have;           ///< per counted label: own sites decided to hold it
  std::int64_t Left = 0;                    ///< own sites still to choose
  std::vector<double> Steer;                ///< the counted choice's weights
  std::vector<int> Tally;                   ///< per own site: its count, -1 none, -2 undecided
  std::vector<std::int64_t> Offered; ///< per count: own choices whose catalog held its labels
  std::int64_t Choices = 0;          ///< choices at own sites in this attempt
  std::size_t ChangedSeen = 0;       ///< catalog changes already tallied
};

/**
 * The assignments of one block attempt with bounded chronological backtracking (a deviation
 * from Algorithm 3.4, whose attempt ends at the first empty catalog): a choice whose
 * propagation empties a catalog is undone and ruled out at its site; when that empties a
 * catalog too, the choice before it is undone and ruled out, and so on, at most
 * SynthesisOptions::BacktracksPerAttempt times. Undoing uses the catalog's trail, which is
 * dropped (and the search goes on without backtracking) when it would exceed MaximumTrailWords.
 */
class BlockSearch
{
public:
  /// The trail's bound, in 64-bit words (128 MiB).
  static constexpr std::size_t MaximumTrailWords = std::size_t(1) << 24;

  BlockSearch(BlockSolver& solver, const Block& block, Random& rng, std::int64_t& assignments);
  ~BlockSearch();
  BlockSearch(const BlockSearch&) = delete;
  BlockSearch& operator=(const BlockSearch&) = delete;

  /// Assigns site @p local (local index) a label when it still has several. Returns -1, or a
  /// site whose catalog is empty when no choice is left to undo or the budget is spent (or the
  /// run is being cancelled).
  std::int64_t Assign(std::int64_t local);
  /// After an Assign that backtracked, the site whose choice was ruled out (every site decided
  /// after it is as it was before that choice); else -1.
  std::int64_t Resume() const { return this->ResumeAt; }

private:
  struct Decision
  {
    std::int64_t Local;
    int Label;
    std::size_t Mark;
  };
  /// Drops the choices (and their trail) that the remaining budget can no longer undo.
  void Trim();
  BlockSolver& Solver;
  const Block& Current;
  Random& Rng;
  std::int64_t& Assignments;
  std::vector<Decision> Stack;
  std::vector<std::uint64_t> Others;
  std::int64_t Budget = 0;
  std::int64_t ResumeAt = -1;
  bool Searching = false;
};

} // namespace detail
} // namespace msynth
