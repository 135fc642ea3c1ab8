// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/**
 * @file ContinuousSynthesis.h
 * @brief The label solver of continuous model synthesis (dissertation §4.5, Algorithm 4.1) on
 * the vertices of a PlaneArrangement.
 *
 * The constraint: two vertices joined by an edge along d are compatible when their labels
 * evaluate to the same neighbourhood along the edge (eval(L_u, d) = eval(L_v, −d), §4.5.5), and
 * an edge leaving the output box must evaluate to empty. It is compiled into a
 * CompatibilityRelation with two direction classes per line direction, and solved by the same
 * propagation engine as discrete synthesis (Propagation.h).
 */
#include "Continuous/ContinuousConstraints.h"
#include "Continuous/PlaneArrangement.h"
#include "Continuous/PolyhedralAnalysis.h"
#include "Continuous/RunEnds.h"
#include "Core/BlockSynthesis.h"
#include "Core/Index.h"
#include "Core/Propagation.h"
#include "Core/SynthesisChoices.h"

#include <functional>
#include <string>

namespace msynth
{

class ArrangementRules : public CompatibilityRelation
{
public:
  ArrangementRules(const PolyhedralAnalysis& analysis, const PlaneArrangement& arrangement);

  /// The example's label of empty space (the trivial model's label everywhere).
  int EmptyLabel() const { return this->Empty; }
  /**
   * The catalog a vertex starts with (Words() words): labels whose families all have a plane
   * through @p v, and that are empty along every edge of @p v leaving the output box — but for
   * edges leaving with a positive component along an axis of @p seamAxes (bits: mirror seams),
   * which may hold anything.
   */
  void InitialDomain(std::int64_t v, std::uint64_t* out, int seamAxes = 0) const;
  /// Number of labels in InitialDomain(v).
  int InitialCount(std::int64_t v) const;
  /// Id of eval(label, direction class d) among all evaluated neighbourhoods.
  int EvaluationId(int d, int label) const
  {
    return this->Evaluations[ToIndex(d) * this->NumberOfLabels() + label];
  }

  /// Within this fraction of the smallest spacing of a plane not through it, a vertex takes
  /// only volume labels (the arrangement's faces there are slivers).
  static constexpr double SurfaceClearance = 1e-3;
  /**
   * 0: no plane that does not pass through vertex @p v comes within MinimumFeatureFraction of
   * the smallest spacing; 1: one does (a corner at @p v may be narrow: NarrowCorners); 2: one
   * comes within SurfaceClearance, and @p v takes only volume labels.
   */
  int ClearanceAt(std::int64_t v) const { return this->Clearance[ToIndex(v)]; }
  /**
   * The corners of a labelling (vertices with a vertex label) closer than MinimumFeatureFraction
   * of the smallest spacing to a face, edge or corner on a plane that does not pass through them.
   */
  std::vector<std::int64_t> NarrowCorners(const std::vector<std::int32_t>& labels) const;

private:
  void KeepCornersApart(const PolyhedralAnalysis& analysis);
  const PlaneArrangement& Arrangement;
  int Empty = -1;
  std::vector<FeatureKind> LabelKinds;
  std::vector<int> SurfaceLabels;           ///< labels of any kind but Volume
  double Smallest = 0;                      ///< the smallest world spacing
  std::vector<char> Clearance;              ///< per vertex, see ClearanceAt
  std::vector<std::uint64_t> LabelFamilies; ///< family mask per label
  std::vector<int> Evaluations;             ///< [direction][label]
  std::vector<std::uint64_t> EmptyToward;   ///< [direction][word]: eval is empty
};

struct ArrangementMirror;

struct ContinuousSynthesisOptions
{
  std::uint64_t Seed = 0;
  /// Block edge in plane spacings (of the family with the largest spacing); 0 labels the whole
  /// arrangement at once (Algorithm 4.1 as written). Blocks overlap by half (§4.5.6). Negative:
  /// automatic, AutomaticBlockSize (room for the example's parts when Runs are followed).
  double BlockSize = 0;
  int Attempts = 20; ///< tries per block (or for the whole model) before giving up
  /// Threads for blocks (non-touching blocks of a phase run concurrently); 0: one per core. The
  /// model does not depend on it. Runs with connectivity seeds (blocks spread outward from them
  /// one after the other) and with snapshots use one thread.
  int Threads = 0;
  /// Processes (MPI ranks) sharing the blocks of each phase: each runs its share and the
  /// finished blocks' labels are exchanged after the phase, so every process ends with the
  /// whole model, the same as one process computes. Inactive by default; serial runs ignore it.
  BlockExchange Exchange;
  /// Which undecided vertex is labelled next: scan line (z, then y, then x; the dissertation),
  /// a seeded random order, or the fewest remaining labels first (ties at random).
  SiteOrder Order = SiteOrder::MinimumEntropy;
  /// Uniform (the dissertation) or weighted by how often the label occurs in the example.
  LabelChoice Choice = LabelChoice::Uniform;
  /// With Frequency: the weight of each label (LatticeOccurrences); empty: the analysis's
  /// Occurrences (each sampled feature once).
  std::vector<double> LabelWeights;
  /// The example's runs along x and y (MeasureRuns): labels that would end a type's run are
  /// drawn with the example's chance of ending at its length (RunEnds.h); empty: memoryless.
  ExampleRuns Runs;
  /// Dimensional, connectivity, ground, guide and proportion constraints (TVCG §4.5–4.7).
  ContinuousConstraints Constraints;
  /// Reflection symmetry across these axes (bit 0 x, bit 1 y, bit 2 z; 0 none): see
  /// ContinuousMirror.h. Not with snapshots.
  int MirrorAxes = 0;
  /// Internal: set by the mirrored runs on the part of the arrangement they label (the seams'
  /// rules), outermost first.
  std::vector<const ArrangementMirror*> PartOf;
  int Snapshots = 0; ///< catalog snapshots after the start, at even fractions of the work
  std::function<void(const CatalogSnapshot&)> OnSnapshot;
  /// Called with the fraction done; return false to cancel (Status Cancelled, no labels).
  std::function<bool(double)> Progress;
};

struct ContinuousSynthesisResult
{
  SynthesisStatus Status = SynthesisStatus::Failed;
  bool Succeeded() const { return this->Status == SynthesisStatus::Succeeded; }
  std::vector<std::int32_t> Labels; ///< per arrangement vertex (example label ids)
  /// Blocks, attempts, failed blocks (BlockFailure::EmptyIndex: the vertex whose catalog
  /// emptied), assignments, backtracks (labels withdrawn because their propagation failed).
  SynthesisStatistics Statistics;
  std::string Message;  ///< why it failed, or a summary
  double BlockSize = 0; ///< the block edge used, in plane spacings (0: the whole model)
  SiteOrder Order = SiteOrder::MinimumEntropy; ///< the vertex order used
  /// Grounded runs: solid parts that did not touch the ground and were emptied.
  std::int64_t FloatingPartsRemoved = 0;
  /// Solid parts emptied because a corner came closer than MinimumFeatureFraction of the
  /// smallest spacing to another plane's face, edge or corner (ArrangementRules::NarrowCorners).
  std::int64_t NarrowPartsRemoved = 0;
  /// Proportions steered: solid parts emptied to bring the types' shares within the tolerance
  /// (ConstraintPlan::KeepProportionateParts), and the types still outside it with why ("").
  std::int64_t ProportionPartsRemoved = 0;
  /// The fraction of the solid volume those parts held (uncapped; see continuous-synthesis.md).
  double ProportionVolumeRemoved = 0;
  std::string ProportionsOutside;
  /// Proportions steered: blocks synthesized again and kept where emptying whole parts could
  /// not bring the shares within the tolerance, or would empty more than half of the solid
  /// (ConstraintPlan::RedrawForProportions).
  std::int64_t ProportionBlocksRedrawn = 0;
  /// Connectivity of every solid type from seeds: smaller parts beyond the seeds' count, emptied
  /// (with blocks, a later block can split a grown part).
  std::int64_t PartsBeyondSeedsRemoved = 0;
  /// With several model candidates: which was kept (0-based; its seed is Seed + this) and its
  /// MatchError; −1 and 0 otherwise.
  int ModelChosen = -1;
  double MatchError = 0;
};

/**
 * Labels the arrangement. With blocks, starts from the all-empty model (always consistent) and
 * relabels overlapping blocks phase by phase (non-touching blocks of a phase concurrently; with
 * connectivity seeds one by one outward from them), rolling a block back when every attempt
 * fails, so the result is always consistent. Seeded and deterministic: the same model for any
 * number of threads.
 */
ContinuousSynthesisResult SynthesizeContinuous(const PolyhedralAnalysis& analysis,
  const PlaneArrangement& arrangement, const ContinuousSynthesisOptions& options);

/**
 * Constraints.ModelCandidates whole models (seeds Seed, Seed + 1, ...), the successful one
 * with the smallest MatchError kept (the first on ties); SynthesizeContinuous calls it when
 * there are several. Progress covers all of them. @throw Error with snapshots (they are of one
 * run).
 */
ContinuousSynthesisResult SynthesizeCandidates(const PolyhedralAnalysis& analysis,
  const PlaneArrangement& arrangement, const ContinuousSynthesisOptions& options);

/**
 * Non-trihedral vertex labels (TVCG §4.4: four or more planes through a point, as at a
 * pyramid's apex) and how many arrangement vertices could hold each: those through which a plane
 * of every family of the label passes. A label without sites is an over-constrained system of
 * spacing equations (Eq. 4.25): that feature cannot appear in the output.
 */
struct NonTrihedralSites
{
  int Label = -1;
  int Planes = 0;         ///< plane families through the vertex
  std::int64_t Sites = 0; ///< arrangement vertices where it may go
};
std::vector<NonTrihedralSites> FindNonTrihedralSites(
  const PolyhedralAnalysis& analysis, const PlaneArrangement& arrangement);

/**
 * Checks labels on an arrangement against the rules, edge by edge, with the evaluation code
 * (not the compiled bit sets). Returns an empty string when consistent, else the first problem.
 */
std::string CheckArrangementLabels(const PolyhedralAnalysis& analysis,
  const PlaneArrangement& arrangement, const std::vector<std::int32_t>& labels);

} // namespace msynth
