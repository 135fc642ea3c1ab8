// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/**
 * @file PatternSynthesis.h
 * @brief Factor-graph pattern synthesis (Yeh et al. 2012): BLOCKSS (§6, Algorithms 1–2) and
 * the two baselines of §8, single-site Metropolis–Hastings and a pure constraint solver (our
 * discrete model synthesis on the hard factors).
 *
 * BLOCKSS is a block sampler. Each sample (Algorithm 1) draws slice thresholds for the current
 * pattern: every hard factor must stay 1; a soft factor currently at 1 + ε must stay observed
 * with probability ε / (1 + ε) (u ~ U[0, 1 + ε] exceeds 1), one at 1 binds nothing. Then
 * BlockSampleSAT (Algorithm 2) moves until every factor of the slice is satisfied: with
 * probability p_walk a WalkSAT move at an unsatisfied factor (with p_flip a random replacement
 * block there, else the block of a shape covering the factor that satisfies the most slice
 * factors), otherwise an annealing move (a random block anywhere, kept with probability
 * min(1, exp(Δc / T)) where c counts satisfied slice factors). Replacement blocks are copied
 * from the exemplars; a block tile that a site's zone or fixed label forbids is not copied
 * (the site keeps its tile), so zones and fixed sites hold throughout.
 *
 * Deviation: Algorithm 2 returns as soon as the slice is satisfied, so consecutive samples
 * differ by one block. As SampleSAT does, each sample here first makes MovesPerSample moves
 * (default: one per site) and then runs until the slice is satisfied; 0 is the paper.
 *
 * Hard pairs come from all exemplars (they say which tiles fit, whatever the style); soft
 * factors anchored in a zone come from that zone's exemplars (style zoning, §4, Fig. 15).
 */
#include "Core/BlockSynthesis.h"
#include "Core/LabelGrid.h"
#include "Discrete/DiscreteSynthesis.h"
#include "Patterns/FactorGraph.h"

#include <array>
#include <cstdint>
#include <functional>
#include <map>
#include <string>
#include <vector>

namespace msynth
{

enum class PatternMethod
{
  BlockSS,            ///< BLOCKSS (§6)
  MetropolisHastings, ///< single-site MH; invalid configurations weigh 1e-8 (§8.2)
  ConstraintSolver    ///< discrete model synthesis on the hard factors only (§8.1)
};

/// Where BLOCKSS starts.
enum class PatternStart
{
  Random, ///< tiles drawn uniformly from those each site allows (Algorithm 1)
  /// a pattern of the constraint solver, which satisfies the hard factors from the start: the
  /// slices then only move it towards the soft factors (our addition; see PatternSynthesis.h)
  Solver
};

struct PatternOptions
{
  /// Output size in sites (nz = 1 for 2D).
  std::array<std::int64_t, 3> Size{ { 1, 1, 1 } };
  /// Soft higher-order factor shapes (§5.2); pair shapes (2H, 2V, 2D) are always hard.
  std::vector<Stencil> SoftFactors;
  /// Pairs allowed besides the exemplars' (a tileset's neighbor rules); with them the
  /// exemplars may be none.
  LabelPairs ExtraPairs;
  double Epsilon = 0.1;
  /// Replacement-block shapes; empty: BlockScheme(6).
  std::vector<Stencil> Blocks;
  /**
   * Zoning (§4): a zone id per output site (x fastest), or empty for one zone 0. Zones listed
   * in ZoneTiles allow only those label values; zones in ZoneExemplars take their soft factors
   * from those exemplars (indices into the exemplar list).
   */
  std::vector<std::int32_t> SiteZone;
  std::map<std::int32_t, std::vector<Label>> ZoneTiles;
  std::map<std::int32_t, std::vector<int>> ZoneExemplars;
  /// Fixed sites: a value per output site; values that are tiles fix the site, others (e.g.
  /// -1) leave it free. Empty: none.
  std::vector<Label> Fixed;
  /**
   * Symmetry by mirroring (§8.4, Fig. 14): along each enabled axis the lower half is
   * synthesized and mirrored, M(n − 1 − x) = f(M(x)) with f the label map (identity where not
   * listed). f must be an involution that keeps the exemplars' pairs (T[b, c] = T[f(c), f(b)]
   * along the axis, T[b, c] = T[f(b), f(c)] across it). Zones and fixed sites hold over the whole
   * output (a site of the half meets those of its mirror images, mapped); style zones are read
   * in the synthesized half.
   */
  std::array<bool, 3> Mirror{ { false, false, false } };
  std::map<Label, Label> MirrorMap;
  /**
   * A connected network (our addition, as SynthesisOptions::Connected): the sites holding its
   * labels form at most Maximum components, joined through the labels' Sides, and its path
   * (PathSites, PathLabels) lies in one of them. Each kept sample is repaired before it is
   * taken: the surplus components, smallest first, get boxes over gaps to other components
   * (steered along each gap, then freely; else around them) solved again on the hard pairs by
   * the discrete solver (Discrete/Connectivity.h's repairs; zones and fixed sites hold there),
   * and the chain goes on from the repaired pattern. A sample the repairs cannot bring to Maximum
   * moves on by another sample's moves from the partly repaired pattern and is repaired again,
   * ten tries in all before the run fails. The constraint solver runs with the network. Not
   * with mirroring. A path without labels, or a listed site outside the output or whose zone or
   * fixed label allows none of the network's tiles, is an error. Inactive: none.
   */
  ConnectedNetwork Connected;

  PatternMethod Method = PatternMethod::BlockSS;
  PatternStart Start = PatternStart::Random;
  int Samples = 1;
  int BurnIn = 5; ///< samples discarded first (§8: the paper discards five)
  double Temperature = 0.25;
  double WalkProbability = 0.6;
  double FlipProbability = 0.1;
  /// Moves before a sample may end (see the deviation above); -1: one per site.
  std::int64_t MovesPerSample = -1;
  /// Moves allowed in all before the run fails; -1: 20,000 per site (at least 10^7).
  std::int64_t MaxMoves = -1;
  /**
   * Soft walk (our addition): while the slice is satisfied, a WalkSAT move may go to a soft
   * factor whose configuration no exemplar shows and place the covering block that satisfies
   * the most slice factors and, among those, the most soft factors. Off: Algorithm 2 as
   * published, whose moves then are all annealing moves.
   */
  bool SoftWalk = true;
  /// Candidates the WalkSAT move compares (0: every block of the chosen shape).
  int CandidatesPerMove = 0;
  std::uint64_t Seed = 0;
  /// Called now and then with the fraction done; returning false cancels the run.
  std::function<bool(double)> Progress;
};

struct PatternSample
{
  LabelGrid Labels; ///< label values
  /// Per site, the soft factors anchored there whose configuration an exemplar shows.
  std::vector<std::int32_t> SatisfiedSoft;
  /// Per site, the move that last changed it (0: the initial pattern).
  std::vector<std::int64_t> LastChange;
  double LogProbability = 0.0; ///< unnormalised: Σ log φ over the soft factors
  std::int64_t Moves = 0;      ///< moves since the run began, when this sample was taken
  double Seconds = 0.0;        ///< since the run began
  /// With PatternOptions::Connected: the network before and after the sample's repairs.
  ConnectedResult Connected;
};

struct PatternResult
{
  /// Succeeded, or Cancelled when the progress callback asked to stop (no samples then).
  SynthesisStatus Status = SynthesisStatus::Succeeded;
  std::vector<PatternSample> Samples;
  std::int64_t Moves = 0;
  std::int64_t WalkMoves = 0;
  std::int64_t AnnealingMoves = 0;
  std::int64_t AcceptedAnnealingMoves = 0;
  std::int64_t FirstValidMoves = 0; ///< moves until the hard factors first all held
  double FirstValidSeconds = 0.0;   ///< time until then
  double Seconds = 0.0;
  std::int64_t HardFactors = 0;
  std::int64_t SoftFactors = 0;
  int Tiles = 0;
  std::int64_t ReplacementBlocks = 0;
  /// Moves of the network's repairs' discrete solver (assignments), over all samples.
  std::int64_t NetworkAssignments = 0;
  double NetworkSeconds = 0.0; ///< time spent in the network's repairs
};

/**
 * Zone lists as the filters and the command line write them: items "Z:a,b,c" separated by ';'
 * (zone Z, then its labels or exemplar numbers). @throw Error naming @p what and the item.
 */
std::map<std::int32_t, std::vector<std::int32_t>> ParseZoneLists(
  const std::string& text, const std::string& what);
/// Label pairs "a:b,c:d" that are each other's mirror images (both directions). @throw Error.
std::map<Label, Label> ParseMirrorSwaps(const std::string& text);

/**
 * Runs pattern synthesis from @p exemplars. @throw Error on bad options (sizes, a 3D output
 * from 2D exemplars, zones or fixed sites of the wrong size or with labels the exemplars do
 * not hold, a zone that allows no tile, a mirror map that breaks the pairs) and when no
 * pattern satisfying the hard factors is found within MaxMoves (the message says how far it
 * got).
 */
PatternResult SynthesizePattern(
  const std::vector<LabelGrid>& exemplars, const PatternOptions& options);

} // namespace msynth
