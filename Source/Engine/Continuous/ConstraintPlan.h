// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The constraints of ContinuousConstraints compiled for one arrangement (internal header of the
// continuous solver): label masks per vertex, the types each label and each edge evaluation
// holds, the seeds, and the label weights.
#include "Continuous/ContinuousConstraints.h"
#include "Core/Index.h"

#include <array>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

namespace msynth
{
namespace detail
{

/// Bit @p t of a type or family set.
inline std::uint64_t Bit(int t)
{
  return std::uint64_t(1) << t;
}
/// Adds label @p label to the label bit set @p set.
inline void SetLabel(std::vector<std::uint64_t>& set, std::size_t label)
{
  set[label >> 6] |= std::uint64_t(1) << (label & 63);
}

class ConstraintPlan
{
public:
  ConstraintPlan(const PolyhedralAnalysis& analysis, const PlaneArrangement& arrangement,
    const ContinuousConstraints& constraints, std::uint64_t seed);

  /// ANDs every label removal of the constraints into vertex @p v's catalog (Words() words).
  void Restrict(std::int64_t v, std::uint64_t* domain) const;

  /// Object types as bits: bit t for the t-th type in ascending order (bit 0: empty space).
  int NumberOfTypes() const { return static_cast<int>(this->Types.size()); }
  int TypeAt(int t) const { return this->Types[ToIndex(t)]; }
  std::uint64_t SolidMask() const { return this->Solid; }
  std::uint64_t LabelTypes(int label) const { return this->TypesOfLabel[ToIndex(label)]; }
  /// The types of label @p label evaluated along direction class @p d (what the edge touches).
  std::uint64_t EdgeTypes(int d, int label) const
  {
    return this->TypesOfEdge[ToIndex(d) * this->K + ToIndex(label)];
  }
  /// Fraction of label @p label's cones holding type bit @p t.
  double Occupancy(int label, int t) const
  {
    return this->Share[ToIndex(label) * this->Types.size() + ToIndex(t)];
  }

  /// Connectivity: the types that only grow next to their group (0: none).
  std::uint64_t GrowMask() const { return this->Grow; }
  /// Grounded with seeds: the types grown from their seeds, whose front is labelled first.
  std::uint64_t LeadMask() const { return this->GroundSeeded; }
  /// Single types grown from seeds (`--connected TYPE`, not "solid"): networks kept whole at the
  /// end (RemoveStrayParts) and never emptied for the proportions.
  std::uint64_t NetworkMask() const { return this->Networks; }
  /**
   * The growing types that may not be chosen where the decided neighbours reach the types
   * @p reach: every group of growing types that @p reach does not meet. A group is the solid as
   * a whole (grounded runs, "solid" connectivity: a roof may start on a wall) or one type (it
   * grows only next to itself); a type in several groups needs each of them reached.
   */
  std::uint64_t Unreached(std::uint64_t reach) const
  {
    std::uint64_t out = 0;
    for (std::uint64_t group : this->GrowGroups)
      if (!(reach & group))
        out |= group;
    return out;
  }
  /// Types that may start at vertex @p v (seeds; the ground when grounded).
  std::uint64_t StartTypes(std::int64_t v) const;
  /// Types a seed at @p v should start (the pick prefers labels holding them).
  std::uint64_t SeedTypes(std::int64_t v) const;
  bool OnGround(std::int64_t v) const;
  /// The seed vertices (ascending).
  const std::vector<std::int64_t>& Seeds() const { return this->SeedVertices; }

  /// Whether labels are drawn with weights from the constraints.
  bool Weighted() const
  {
    return this->HasGuideWeights || this->Proportions || this->FillTarget > 0;
  }
  /**
   * The constraints' factor for label @p label at vertex @p v, given the solid shares so far
   * (@p tally: occupancy per type bit, summed over the labelled vertices).
   */
  double Factor(std::int64_t v, int label, const std::vector<double>& tally) const;
  /// Labellings tried per block, the best kept (ContinuousConstraints::BlockCandidates when
  /// proportions are steered, else 1).
  int Candidates() const { return this->Proportions ? this->Constraints.BlockCandidates : 1; }
  /// How far the solid shares of @p tally are from the targets (sum of squared differences).
  double Mismatch(const std::vector<double>& tally) const;
  /// MatchError (ContinuousConstraints.h) of a labelling of the whole arrangement.
  double MatchError(const std::vector<std::int32_t>& labels) const;

  struct Removed
  {
    std::int64_t Floating = 0;    ///< grounded runs: parts that did not touch the ground
    std::int64_t BeyondSeeds = 0; ///< connectivity: parts beyond the seeds' count
  };
  /**
   * Empties stray connected solid parts (always consistent: a part's vertices see only empty
   * space once it is gone): in grounded runs every part that does not touch the ground; when
   * every solid type grows from seeds, all but the largest parts (by vertices), as many as the
   * seeds (with blocks, a later block can split a grown part).
   */
  Removed RemoveStrayParts(std::vector<std::int32_t>& labels, int emptyLabel) const;
  /// Shares within this fraction of their targets (relative) are what proportions promise.
  static constexpr double ProportionTolerance = 0.25;
  /// KeepProportionateParts stops once every share is this near (the steering's vertex
  /// occupancy differs a little from the volume the mesh holds).
  static constexpr double ProportionMargin = 0.04;
  struct Proportioned
  {
    std::int64_t Removed = 0;   ///< parts emptied
    double VolumeRemoved = 0;   ///< the fraction of the solid volume they held (no cap)
    std::vector<int> Outside;   ///< object types still further than ProportionTolerance
    std::string Reason;         ///< per such type, its share, the example's, and why
    std::vector<double> Shares; ///< per type bit: its share of the solid volume left
    double Worst = 0;           ///< the largest relative deviation of a share from its target
    double Sum = 0;             ///< the relative deviations added up
    double Kept = 0;            ///< the solid volume left
  };
  /**
   * With proportions steered (and no guide, which asks for types in places, masks included):
   * empties whole solid parts, one at a time, each the one whose
   * removal brings the types' shares nearest the targets (largest relative deviation first),
   * while that is nearer than keeping it and some type is further than ProportionMargin off.
   * Always consistent, as RemoveStrayParts; deterministic (ties: the part found first). The
   * parts' volumes come from the labels' mesh, traced on @p threads threads (0: one per core;
   * the same parts emptied for any count).
   */
  Proportioned KeepProportionateParts(
    std::vector<std::int32_t>& labels, int emptyLabel, unsigned threads) const;
  /// What RedrawForProportions needs of the solver.
  struct BlockRedraw
  {
    std::int64_t Blocks = 0; ///< the blocks of the layout
    /// The vertices of a block, ascending.
    std::function<std::vector<std::int64_t>(std::int64_t)> Vertices;
    /// Labels a block of the model again (the rest fixed), drawing from a generator keyed by
    /// the second argument; false when every attempt failed (the model then unchanged).
    std::function<bool(std::int64_t, std::uint64_t)> Redraw;
    /// Empties the stray and narrow parts of the model, as after the blocks; returns how many:
    /// floating, beyond the seeds, narrow.
    std::function<std::array<std::int64_t, 3>()> Clean;
    std::function<bool()> Stopped; ///< the run is being cancelled
  };
  struct Redrawn
  {
    std::int64_t Blocks = 0;             ///< redrawn blocks kept
    std::int64_t Tried = 0;              ///< redraws tried
    std::array<std::int64_t, 3> Parts{}; ///< parts Clean emptied after the kept ones
  };
  /**
   * Redraws blocks of the model (below the level of a part) where emptying whole parts
   * (KeepProportionateParts, which follows) cannot do well alone. First, when the emptying would
   * still leave a type further than ProportionTolerance from its target (a part that holds every
   * type; one building whose dome outgrew its storey walls): the blocks holding most of the type
   * furthest above its target (by vertex occupancy) are redrawn, and a redraw is kept when the
   * shares the emptying would then leave come nearer the targets (the largest relative
   * deviation, then their sum), until they are within RedrawTarget or no tried block improves.
   * Then, while the shares are within RedrawTarget but the emptying would remove more than
   * RefillAbove of the solid: the blocks holding least solid (with a ground vertex, when
   * grounded) are redrawn, kept when the emptying then keeps more solid volume with every share
   * still within RedrawTarget. Each round tries the first RedrawBlocks blocks (groups of blocks
   * in a large model, RedrawGroup) twice and ends at its first kept redraw; RedrawBudget redraws
   * at most. A redraw is one attempt of the block
   * solver, the rest fixed, the draw steered by the model's shares: consistent, and
   * deterministic (keys: the phase, round, block and attempt). @p labels is the model the hooks
   * act on.
   */
  Redrawn RedrawForProportions(std::vector<std::int32_t>& labels, int emptyLabel, unsigned threads,
    const BlockRedraw& blocks) const;
  /// RedrawForProportions stops once every share left is this near its target.
  static constexpr double RedrawTarget = 0.2;
  /// RedrawForProportions fills bare ground again while the emptying would remove more than this
  /// fraction of the solid.
  static constexpr double RefillAbove = 0.5;
  /// Redraws tried at most per run, and blocks tried per round (each twice).
  static constexpr int RedrawBudget = 96, RedrawBlocks = 8;
  /// A model of n ≥ RedrawGroupsFrom blocks redraws groups of n / RedrawGroup blocks at a time
  /// (one block moves a large model's shares too little), a smaller one a block at a time.
  static constexpr std::int64_t RedrawGroup = 100, RedrawGroupsFrom = 1000;
  /// Empties every connected solid part holding one of @p vertices; returns how many.
  std::int64_t EmptyPartsAt(std::vector<std::int32_t>& labels, int emptyLabel,
    const std::vector<std::int64_t>& vertices) const;
  /// Whether RemoveStrayParts has anything to do.
  bool RemovesStrayParts() const;
  /// When every solid type grows from seeds, the number of seeds; else 0.
  std::int64_t SeedsOfAllSolid() const;

private:
  std::int64_t CellOf(std::int64_t v) const;
  /// The type bit of object type @p type, or −1.
  int BitOf(int type) const;
  void PlanGround();
  void PlanThickness();
  void PlanWidth(const ThicknessConstraint& c);
  void PlanOverhang();
  void PlanGuide();
  void PlanTargets();
  void PlanSeeds(std::uint64_t seed);
  void PlanFill();

  const PolyhedralAnalysis& Analysis;
  const PlaneArrangement& Arrangement;
  const ContinuousConstraints& Constraints;
  std::size_t K = 0;
  int Words = 0;
  std::vector<int> Types;
  std::uint64_t Solid = 0, Grow = 0;
  std::vector<std::uint64_t> GrowGroups; ///< type bits that grow together (see Unreached)
  std::vector<std::uint64_t> TypesOfLabel, TypesOfEdge;
  std::vector<double> Share;
  int GroundAxis = 2;
  double GroundLevel = 0, GroundTolerance = 0;
  std::vector<std::uint64_t> GroundAllowed, AboveAllowed; ///< label bit sets
  struct Slabs
  {
    int Family = 0, Spacings = 1;
    std::int64_t Lowest = 0;
    std::uint64_t Needs = 0; ///< a width: its families (bits); applies at vertices on all of them
    std::vector<std::uint64_t> OuterAllowed, InnerAllowed; ///< label bit sets
  };
  std::vector<Slabs> Thickness;
  std::vector<std::vector<std::uint64_t>> WithType; ///< per type bit: labels holding it
  std::vector<std::pair<int, const std::vector<float>*>> GuideWeights; ///< type bit → weights
  bool HasGuideWeights = false;
  bool Proportions = false;
  std::vector<double> Target; ///< per type bit: share of the solid
  std::uint64_t FillMask = 0; ///< connected types (type bits), steered toward FillTarget
  double FillTarget = 0;      ///< their share of the example's bounding box
  /// Grounded with seeds: the types that start at their seeds (on the ground) only; the other
  /// solid types start anywhere on the ground (a road network from one seed among houses).
  std::uint64_t GroundSeeded = 0;
  std::uint64_t Networks = 0; ///< NetworkMask
  std::vector<std::int64_t> SeedVertices;
  std::vector<std::uint64_t> SeedMask; ///< per seed vertex
};

/// Connected solid parts of a labelled arrangement: a component id per vertex (−1: no solid),
/// vertices joined along every edge whose evaluation holds solid. Returns the number of parts.
std::int64_t SolidComponents(const PlaneArrangement& arrangement,
  const std::vector<std::int32_t>& labels, const std::function<std::uint64_t(int, int)>& edgeSolid,
  std::uint64_t solidMask, const std::vector<std::uint64_t>& labelTypes,
  std::vector<std::int64_t>& component);

} // namespace detail
} // namespace msynth
