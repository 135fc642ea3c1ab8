// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/**
 * @file DiscreteSynthesis.h
 * @brief Discrete model synthesis (dissertation ch. 3): Algorithm 3.1 (the whole model at
 * once) and Algorithm 3.4 (modify the model in overlapping blocks, from a trivial consistent
 * start, rolling a block back when it fails).
 *
 * Both are one loop: a block as large as the output is Algorithm 3.1. Every returned model
 * satisfies the adjacency constraint (Eq. 3.3); a failure of Algorithm 3.1 is reported as a
 * failure with the site where the catalog became empty, never returned as a model.
 *
 * Determinism: each block attempt draws from its own generator derived from (seed, block,
 * attempt), and blocks are visited in phases such that blocks of one phase never touch (not
 * even through a neighbour layer). The result therefore depends only on the inputs and the
 * seed, and blocks of one phase can later run concurrently with the same result.
 */
#include "Core/BlockSynthesis.h"
#include "Core/Index.h"
#include "Core/LabelGrid.h"
#include "Core/SynthesisChoices.h"
#include "Discrete/AdjacencyRules.h"

#include <algorithm>
#include <array>
#include <cstdint>
#include <functional>
#include <limits>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace msynth
{

/// The six faces of the output box, in the order of SynthesisOptions::Boundary (the order of
/// VTK bounds: x min, x max, y min, y max, z min, z max).
enum Face : int
{
  FaceMinX = 0,
  FaceMaxX = 1,
  FaceMinY = 2,
  FaceMaxY = 3,
  FaceMinZ = 4,
  FaceMaxZ = 5
};

/// A site of SynthesisOptions::Pins that is not pinned.
constexpr Label FreeSite = -1;

/**
 * Large-scale constraints (dissertation §3.5.3): a guide grid stretched over the output box
 * giving, per cell, a weight for each label (its relative probability there). Output site p
 * reads cell floor((p + 1/2) · Dims / Size) on each axis. A weight of zero removes the label
 * from the catalog at those sites, and the removal propagates; labels without weights have
 * weight 1 everywhere.
 */
struct GuideVolume
{
  std::array<std::int64_t, 3> Dims{ { 1, 1, 1 } };
  /// Label value → one weight per guide cell (x fastest), each ≥ 0 and finite.
  std::map<Label, std::vector<float>> Weights;
  /// The guide's regions for label counts per region (LabelCount::Region): one region number
  /// (≥ 0) per guide cell (x fastest); a site belongs to its cell's region. Empty: none.
  std::vector<std::int32_t> Regions;

  /// The cell (x fastest) holding site @p p of an output of @p size sites:
  /// floor((p + 1/2) · Dims / size) per axis, in integers.
  std::int64_t CellOf(
    const std::array<std::int64_t, 3>& p, const std::array<std::int64_t, 3>& size) const
  {
    std::int64_t c[3];
    for (int a = 0; a < 3; ++a)
      c[a] = std::min(this->Dims[a] - 1, ((2 * p[a] + 1) * this->Dims[a]) / (2 * size[a]));
    return c[0] + this->Dims[0] * (c[1] + this->Dims[1] * c[2]);
  }
};

/**
 * Reflection symmetry (dissertation §3.5.2) about the middle plane of an axis: the output
 * satisfies M(n − 1 − x) = f(M(x)) along that axis, where f maps each label to its mirror image
 * (labels not listed map to themselves). f must be an involution that preserves the example's
 * rules (T_a[b, c] = T_a[f(c), f(b)] along the axis, T[b, c] = T[f(b), f(c)] across it), and the
 * maps of several mirrored axes must commute. The lower half is synthesized and mirrored.
 */
struct Mirror
{
  bool Enabled = false;
  std::map<Label, Label> Map;
};

/**
 * Translation symmetry (dissertation §3.5.2) along one axis: M(x + P) = f(M(x)) for a period P,
 * and the model continues across each period: T[M(P − 1), f(M(0))] along the axis. With
 * P = the output size and f the identity the output tiles seamlessly (a periodic model). f maps
 * each label to its image one period on (labels not listed map to themselves); it must be a
 * permutation of the labels that preserves the example's rules along every axis
 * (T[b, c] = T[f(b), f(c)]), and the maps of several translated axes must commute. One period
 * is synthesized, with the seam as extra constraints, and repeated.
 */
struct Translation
{
  bool Enabled = false;
  std::int64_t Period = 0; ///< P; 0 means the output size (a tileable model)
  std::map<Label, Label> Map;
};

/**
 * Rotation symmetry (dissertation §3.5.2) by 90° about the vertical axis through the centre of
 * the output (which must be square in x and y): M(n − 1 − y, x, z) = f(M(x, y, z)), the model
 * turned a quarter counter-clockwise is f of itself. f maps each label to its image turned a
 * quarter counter-clockwise (a tileset's orientation k to k + 1); f⁴ must be the identity and f
 * must carry the rules along x to those along y: T_x[b, c] = T_y[f(b), f(c)],
 * T_y[b, c] = T_x[f(c), f(b)], T_z[b, c] = T_z[f(b), f(c)]. A quadrant is synthesized, with the
 * seams to its turned copies as extra constraints, and turned into the other three.
 */
struct Rotation
{
  bool Enabled = false;
  std::map<Label, Label> Map;
};

/**
 * Soft constraints (2007 paper, §4.2): each block's change is kept with the Metropolis
 * probability min(1, f(M') / f(M)), otherwise rolled back, so models that fit better are more
 * likely. Built in: target fractions of labels, with f(M) = exp(−E / T) and
 * E = N · Σ_b (fraction_b − target_b)² over the labels given (computed from label counts, so
 * each decision is cheap). Optionally a user fitness f(M) > 0 (larger is better), evaluated on
 * the whole model after every block. Needs block synthesis (Algorithm 3.1 has no previous model
 * to compare with). Decisions are made in block order, so results do not depend on threads.
 */
struct SoftConstraint
{
  std::map<Label, double> TargetFractions;
  double Temperature = 0.01;
  std::function<double(const LabelGrid&)> Fitness;
  bool Active() const { return !this->TargetFractions.empty() || static_cast<bool>(this->Fitness); }
};

/**
 * How block synthesis starts. Algorithm 3.4 starts from a trivial model (one label, or layers),
 * which every block must close its structures against: for sets whose structures cannot close
 * inside one block (wires that must reach a component, ramps longer than a block) every block
 * keeps the trivial label, a valid but blank model. An undecided start (as in POMS and Breakout
 * Model Synthesis) leaves every site free until a block decides it; a block is then constrained
 * only by decided sites around it, so structures continue across blocks. It cannot keep
 * paths closed the way the trivial start does (a block ringed by decided sites may meet an odd
 * number of line ends), so neither start suits every set.
 */
enum class BlockStart
{
  /// A probe chooses (ChooseBlockStart): the trivial start unless it leaves a probe world
  /// blank where an undecided start, else a whole-model start, succeeds with more variety.
  Automatic,
  Trivial,   ///< Algorithm 3.4's start (or the given SynthesisOptions::Start)
  Undecided, ///< every site free until a block decides it; sites no block decides fail the run
             /// A whole-model solution (Algorithm 3.1, same seed, no blocks) that the blocks then
             /// modify: for sets whose structures reach the model's faces (MarkovJunior's
             /// Partition: lines end only at lines), which neither other start lets a block draw. A
             /// failed whole run fails the run.
  WholeModel
};

/**
 * A count constraint: the number of output sites holding any of the labels @p Values (one
 * label, or the orientations of a tile) lies in [Minimum, Maximum] (SynthesisOptions::Counts).
 */
struct LabelCount
{
  std::vector<Label> Values;
  std::string Name; ///< as the user named it (a label value or a tile name), for messages
  std::int64_t Minimum = 0;
  std::int64_t Maximum = std::numeric_limits<std::int64_t>::max();
  /// The guide region (GuideVolume::Regions) whose sites are counted; -1: the whole output.
  std::int32_t Region = -1;
};

/// A count constraint of a finished run with the number of sites that hold its label.
struct LabelCountResult
{
  LabelCount Requested;
  std::int64_t Achieved = 0;
};

/**
 * A connectivity constraint (SynthesisOptions::Connected): the output sites holding any of the
 * labels @p Values form at most @p Maximum connected components. Two such sites p and
 * q = p + e_a are joined when the side of p's label toward +a and the side of q's label toward
 * -a both connect (Sides); labels without an entry connect through every side (face
 * neighbours).
 */
struct ConnectedNetwork
{
  std::vector<Label> Values;
  std::string Name; ///< as the user named the labels, for messages
  std::int64_t Maximum = 1;
  /// Per label value, the sides it connects through: bit 2a the side toward +a, bit 2a+1 the
  /// side toward -a (a tileset's `connects`); a label not listed connects through every side.
  std::map<Label, std::uint8_t> Sides;
  /**
   * A path (`--path`): these sites (x, y, z) and every site holding one of PathLabels (values,
   * each one of Values) are joined by one component of the network: each listed site holds a
   * network label, and one component holds them all. The repairs keep it as they keep Maximum
   * (Connectivity.h); they never lower the number of sites holding PathLabels. Empty: none.
   */
  std::vector<std::array<std::int64_t, 3>> PathSites;
  std::vector<Label> PathLabels;
  /**
   * `LABELS:open`, the meaning of a network in a world without bounds (Connectivity.h): no
   * component is closed off; every block keeps only attempts whose network components inside
   * its footprint reach its ring, the world's border or a pin. Maximum does not apply, nor do
   * repairs, so regions and streams take it.
   */
  bool Open = false;
  bool Active() const { return !this->Values.empty(); }
  bool HasPath() const { return !this->PathSites.empty() || !this->PathLabels.empty(); }
};

/// What a run did about SynthesisOptions::Connected.
struct ConnectedResult
{
  bool Requested = false;
  std::int64_t Maximum = 1;
  std::string Name;
  std::int64_t Before = 0;     ///< components when the blocks were done, before the repairs
  std::int64_t Components = 0; ///< components of the result
  std::int64_t Repairs = 0;    ///< boxes re-synthesized and kept (each joined or removed one)
  std::int64_t Redone = 0;     ///< block attempts redone because they closed a component off
  /// With a path: the sites it joins (the listed sites and the path labels' sites at the end),
  /// and the components holding them before the repairs (1 at the end).
  std::int64_t PathSites = 0;
  std::int64_t PathComponentsBefore = 0;
};

/// The block edge (sites per axis) of SynthesisOptions::BlocksWhenWholeFails.
constexpr std::int64_t FallbackBlockEdge = 32;

struct SynthesisOptions
{
  /// Output size n_x × n_y × n_z (n_z = 1 for 2D).
  std::array<std::int64_t, 3> Size{ { 1, 1, 1 } };
  /// Block size m (Algorithm 3.4); 0 on an axis means the whole axis. All zero (or ≥ Size) is
  /// Algorithm 3.1.
  std::array<std::int64_t, 3> BlockSize{ { 0, 0, 0 } };
  /// Overlap between consecutive blocks; -1 means half the block (the dissertation's choice).
  std::array<std::int64_t, 3> Overlap{ { -1, -1, -1 } };
  /// Attempts per block before the block is left as it was (Algorithm 3.1: attempts overall).
  int AttemptsPerBlock = 10;
  /**
   * Choices an attempt may undo when a catalog becomes empty (chronological backtracking, a
   * deviation from Algorithms 3.1 and 3.4, which end the attempt there). 0: none, as the
   * dissertation.
   */
  std::int64_t BacktracksPerAttempt = 1000;
  /**
   * Blocks whose attempts all failed are tried again once every other block is done (their
   * surroundings have changed): up to three more passes over the phases, each running the
   * blocks still failed with twice as many attempts, new random streams, alternating
   * minimum-entropy and scan-line order. Part of the schedule (a region of a world takes them
   * in; any thread count gives the same model). Not with catalog snapshots (whose count is fixed
   * before the run) or soft constraints.
   */
  bool RepairFailedBlocks = true;
  /**
   * When whole-model synthesis (no blocks) fails every attempt, synthesize the model again in
   * blocks of FallbackBlockEdge sites per axis (at most the output; not with snapshots, whose
   * number is fixed beforehand), saying so in the message. Default on.
   */
  bool BlocksWhenWholeFails = true;
  std::uint64_t Seed = 0;
  LabelChoice Choice = LabelChoice::Uniform;
  /// The example grid, for LabelChoice::Resemblance (not owned; must outlive the call).
  const LabelGrid* Example = nullptr;
  /// Half-width w of the resemblance window (2w + 1 sites per axis). Default 1.
  int ResemblanceWindow = 1;
  SiteOrder Order = SiteOrder::ScanLine;
  /**
   * Labels (values) fixed on the boundary layer of each face, in the order -x, +x, -y, +y, -z,
   * +z (Fig. 3.11: ground along the bottom, empty elsewhere). Faces of axes of size 1 are
   * ignored. Where faces meet, the first face in the order -z, +z, -y, +y, -x, +x wins.
   */
  std::array<std::optional<Label>, 6> Boundary;
  /// The label of the trivial start (a value); empty: chosen automatically (value 0 if it is
  /// adjacent to itself along every axis, else the first such label in value order).
  std::optional<Label> TrivialLabel;
  /// How block synthesis starts (BlockStart).
  BlockStart StartFrom = BlockStart::Automatic;
  /**
   * The start of block synthesis instead of a model of one trivial label (Algorithm 3.4, lines
   * 3-5): label values over the output (over the synthesized period with translation symmetry;
   * not with mirrors or rotation), satisfying the adjacency constraint, the boundary labels and
   * the guide. Empty: a trivial label, else layers of labels (BlockSolver::TrivialStart).
   */
  std::optional<LabelGrid> Start;
  /**
   * With StartFrom Automatic: the blocks start undecided, and only where that run fails from the
   * given Start (or the automatic start without one). An image sample that does not repeat sets
   * it (OverlappingModel: its tiled start shows along the block borders); a region or a stream
   * of such a world starts undecided (UndecidedWorld).
   */
  bool UndecidedFirst = false;
  /**
   * Pinned sites, to complete a partial model: label values over the output, FreeSite where
   * the site is to be synthesized. Pinned labels are kept: whole-model synthesis starts its
   * catalog from them; block synthesis first places each pin into the start with a block of the
   * run's size around it, and no block changes them afterwards. Pins that contradict the rules,
   * the boundary labels or each other (through propagation over the pins' box and 16 sites around
   * it) are an Error before any work. Not with mirror, translation or rotation symmetry.
   * Regions of a world take the pins that fall in their window (SynthesizeRegion).
   */
  std::optional<LabelGrid> Pins;
  /**
   * Where Pins' site (0, 0, 0) lies in the output (world coordinates): a pin grid smaller than
   * the output, placed (it must lie inside the output). Empty: Pins covers the output exactly.
   */
  std::optional<std::array<std::int64_t, 3>> PinsOrigin;
  /// Reflection symmetry per axis (x, y, z).
  std::array<Mirror, 3> Symmetry;
  /// Translation symmetry per axis (x, y, z); cannot be combined with mirrors or rotation.
  std::array<Translation, 3> Translate;
  /// Rotation symmetry about the vertical axis; cannot be combined with mirrors or translation.
  Rotation Rotate;
  /// Soft constraints; inactive by default.
  SoftConstraint Soft;
  /**
   * Label counts: each listed label holds between its Minimum and Maximum sites of the output
   * (a hard constraint; Discrete/LabelCounts.h). The range is split over the blocks, each
   * keeping the sites it writes last within its share; the choice prefers a label below its
   * share and bans one that reached it; an attempt that misses its share fails and is tried
   * again. Counts the rules, sizes, boundary labels or pins make impossible are an Error before
   * any work. A count with a Region counts only the sites of that guide region; a label may be
   * counted once in the whole output or once per region. Not with symmetry, soft constraints or
   * regions of a world. Empty: none.
   */
  std::vector<LabelCount> Counts;
  /**
   * A connected network (Discrete/Connectivity.h): the sites of its labels form at most Maximum
   * components. Blocks redo an attempt that closes a component off (it touches no site a later
   * block writes) while that leaves too many; when the blocks are done, boxes around the
   * smallest surplus components are synthesized again until they join another or vanish; a
   * model that still has too many fails with one line. Not with symmetry, soft constraints,
   * label counts or regions of a world; runs on one thread. Inactive: none.
   */
  ConnectedNetwork Connected;
  /// Large-scale constraints; empty for none.
  std::optional<GuideVolume> Guide;
  /// Threads for block synthesis (blocks of a phase run concurrently); 0: one per core. The
  /// model is the same for any number of threads. Runs with snapshots, runs with translation
  /// or rotation symmetry (whose seams link distant blocks) and runs with a soft-constraint
  /// fitness function (which sees the whole model after every block) use one thread.
  int Threads = 0;
  /// Blocks spread over processes (Core/BlockSynthesis.h); inactive by default. Runs with
  /// snapshots, with translation or rotation seams, or with a fitness function run every block
  /// on every process instead.
  BlockExchange Exchange;
  /// Called after each block (one thread) or each phase (several) with the fraction done, on
  /// the calling thread; returning false cancels the run.
  std::function<bool(double)> Progress;
  /**
   * Catalog snapshots (time steps): one at the start, then SnapshotsPerBlock per block, taken
   * when the fraction of decided sites of the block first reaches 1/S, 2/S, ..., 1 (the last is
   * the committed block). A block that fails repeats its previous state, so there are always
   * exactly 1 + Blocks × SnapshotsPerBlock snapshots (see CountSnapshots). 0: none.
   */
  int SnapshotsPerBlock = 0;
  std::function<void(const CatalogSnapshot&)> OnSnapshot;
};

struct SynthesisResult
{
  /// Succeeded when Model is a complete consistent model. In block mode a model is always
  /// returned unless cancelled (failed blocks keep their previous, consistent labels; see
  /// Statistics.Failures).
  SynthesisStatus Status = SynthesisStatus::Failed;
  bool Succeeded() const { return this->Status == SynthesisStatus::Succeeded; }
  std::string Message;
  LabelGrid Model; ///< label values
  /// Per site, the index of the last block that changed it (-1: never changed).
  std::vector<std::int32_t> LastBlock;
  SynthesisStatistics Statistics;
  /// SynthesisOptions::Counts with the number of sites of each label in Model.
  std::vector<LabelCountResult> Counts;
  /// SynthesisOptions::Connected and what the run did about it.
  ConnectedResult Connected;
};

/**
 * The region [@p low, @p high) of the world that @p world's options describe (Size is the
 * world's): the labels a whole run with the same options gives at those sites (the repair
 * passes of RepairFailedBlocks are part of the world's schedule), computed by the blocks of the
 * region's dependency cone alone (Core/ WorldSchedule.h) in a window around it, so its cost is set
 * by the region, not the world. Statistics count the blocks run. Pins (in world coordinates,
 * placed by PinsOrigin) that fall in the window are taken, the window grown to hold the pin
 * placements it meets. No symmetry, soft constraints, guide, given start, snapshots,
 * resemblance, counts or connected network (each needs the whole world).
 * @throw Error for those options or a region outside the world.
 */
SynthesisResult SynthesizeRegion(const AdjacencyRules& rules, const SynthesisOptions& world,
  const std::array<std::int64_t, 3>& low, const std::array<std::int64_t, 3>& high);

/// How a streamed run (SynthesizeStreamed) cuts its world: slabs of Thickness sites along Axis
/// (the last may be thinner), each spanning the world on the other axes.
struct StreamLayout
{
  int Axis = 1;
  std::int64_t Thickness = 1;
  int Chunks = 1;
  /// The box [low, high) of chunk @p j in the world.
  void Box(int j, std::array<std::int64_t, 3>& low, std::array<std::int64_t, 3>& high) const;
  /// Sites in one layer across Axis.
  std::int64_t Cross() const
  {
    return this->World[0] * this->World[1] * this->World[2] / this->World[ToIndex(this->Axis)];
  }
  /// Layers across Axis that make about @p sites sites (at least 1).
  std::int64_t LayersOf(std::int64_t sites) const
  {
    return std::max<std::int64_t>(1, sites / std::max<std::int64_t>(1, this->Cross()));
  }
  std::array<std::int64_t, 3> World{ { 1, 1, 1 } };
};

/// The layout of a streamed run of @p world: along the axis with the most blocks (the higher
/// axis on a tie), slabs of @p thickness sites (0: about 2^21 sites a slab, at least one block
/// step). @throw Error when the world is one block.
StreamLayout PlanStream(const SynthesisOptions& world, std::int64_t thickness = 0);

/// A finished slab of a streamed world. Its box starts Shared (0 or 1) layers before the
/// layout's slab: the previous slab's last layer, as the pieces of a VTK image share their
/// border points (and so every pair of neighbours lies in one slab).
struct StreamChunk
{
  int Index = 0;
  std::int64_t Shared = 0;
  std::array<std::int64_t, 3> Low{}, High{}; ///< its box in the world
  LabelGrid Model;                           ///< its labels (values)
  std::vector<std::int32_t> LastBlock;       ///< per site, the world key of its last block
  /// The world's blocks that failed for good (every pass over them ran) whose first layer along
  /// the axis is one of this slab's own (not the shared one): each failed block in one slab.
  std::vector<BlockFailure> Failures;
};

/**
 * The world of @p world's options computed slab by slab in bounded memory: the blocks run as a
 * wavefront along the layout's axis (each phase of each pass trailing the one before it by the
 * blocks' reach), a window at a time, each window carrying its labels and failed blocks into
 * the next; every slab is handed to @p onChunk (false cancels) as soon as no later block can
 * change it, then dropped. The slabs equal the same sites of a whole run (Synthesize, or
 * SynthesizeRegion): the order respects every dependency of the world's schedule. From
 * @p firstChunk on (a resumed run), only the blocks the slabs from there need run (none when it is
 * the number of slabs: the earlier run finished them all); @p kept are the failures the earlier
 * run handed out with the slabs before (their StreamChunk::Failures). Memory is set
 * by the slab and the wavefront's depth (phases × passes × reach), not by the world. The result
 * has no Model; its failures (Failures, BlocksFailed) are the world's, as an uninterrupted run
 * reports them; its other counts are of the blocks this run ran. Options as SynthesizeRegion.
 */
SynthesisResult SynthesizeStreamed(const AdjacencyRules& rules, const SynthesisOptions& world,
  const StreamLayout& layout, const std::function<bool(StreamChunk&&)>& onChunk, int firstChunk = 0,
  const std::vector<BlockFailure>& kept = {});

/**
 * Block synthesis of rules none of whose labels may touch itself on every axis (MarkovJunior's
 * PartitionedEdges, say) has no trivial start of one label (Algorithm 3.4, lines 3-5): sets
 * @p options.Start to a whole-model solution (Algorithm 3.1, same seed), which the blocks then
 * modify. Leaves the options as they are (the layered start, or its error) when that fails,
 * without blocks, with a given start, or with symmetries (which take no given start).
 */
void StartFromWholeModel(const AdjacencyRules& rules, SynthesisOptions& options);

/**
 * Block synthesis from BlockStart::WholeModel: a whole-model run of @p options (Algorithm 3.1,
 * the same seed; no snapshots, no messages, so every process computes the same one), then the
 * blocks over it as a given start; the statistics' StartFrom is "whole". A failed whole run is
 * the result, its message saying so.
 */
SynthesisResult SynthesizeFromWholeModel(
  const AdjacencyRules& rules, const SynthesisOptions& options);

/**
 * The start BlockStart::Automatic resolves to for @p options (the world's options for a region),
 * a function of the example, options and seed alone: Trivial without blocks, with a given
 * start, soft constraints, symmetry or snapshots, and with pins or a guide when the probe is not
 * the whole output. Otherwise a probe world of the run's blocks (4 block steps past one block
 * per axis, at most the output) is synthesized from the trivial start; where it looks blank (its
 * trivial label on over 90 % of the sites, or on over 1.25 times the label's share of the
 * example by weight), it is synthesized again from an undecided start, which is chosen
 * when it decides every site with no failed block and with more variety (more than 1.25 times
 * the distinct labels, or a most frequent label's share under 0.8 times the trivial run's);
 * failing that, from a whole-model start (BlockStart::WholeModel), chosen on the same terms.
 * When the probe is the whole output, its chosen result is returned in @p done. Returns the
 * options' own choice when it is not Automatic.
 */
BlockStart ChooseBlockStart(const AdjacencyRules& rules, const SynthesisOptions& options,
  std::optional<SynthesisResult>* done = nullptr);

/// Bytes the catalog snapshots of a run hold: CountSnapshots × sites × 12 (label, catalog size,
/// entropy).
double SnapshotBytes(const SynthesisOptions& options);

/// @throw Error naming the need when SnapshotBytes exceeds @p limit bytes.
void CheckSnapshotMemory(const SynthesisOptions& options, double limit);

/**
 * A fingerprint of a run's inputs that processes compare before they exchange blocks: the names
 * of its files (tileset, sample), the example's labels, the sizes, block sizes and seed. Never
 * 0 (0 means "not synthesizing").
 */
std::uint64_t RunFingerprint(const std::vector<std::string>& files,
  const std::vector<Label>& labels, const SynthesisOptions& options);

/// The number of blocks Synthesize will visit for these options (sizes only).
std::int64_t CountBlocks(const SynthesisOptions& options);
/// The number of snapshots Synthesize will report: 1 + CountBlocks × SnapshotsPerBlock (0 if
/// SnapshotsPerBlock is 0).
std::int64_t CountSnapshots(const SynthesisOptions& options);

/**
 * @brief Runs discrete model synthesis.
 * @throw Error on invalid options: a size below 1, a boundary or trivial label the rules do
 * not know, or block synthesis without a usable trivial start (then the message says why).
 */
SynthesisResult Synthesize(const AdjacencyRules& rules, const SynthesisOptions& options);

/**
 * A model more than one site long along an axis on which no two labels may be neighbours (a 2D
 * tileset or a flat example asked for a 3D size) cannot exist: said at once, with the size that
 * can, instead of as a catalog emptied in every attempt. Whole runs, regions and streams call it.
 * @throw Error naming the axis and the size.
 */
void CheckAxesWithoutPairs(const AdjacencyRules& rules, const SynthesisOptions& options);

/**
 * A model that repeats every P sites along a translated axis needs rows of labels that close
 * after P steps; when the rules' rows along it close only after multiples of d and d does not
 * divide P (WaveFunctionCollapse's Chess, N = 2, at periodic size 47), no model exists: said at
 * once with the period, instead of as a failed run or its block fallback (Discrete/PeriodCheck).
 * @throw Error naming the axis, the example's period and a size that may work.
 */
void CheckTranslationPeriods(const AdjacencyRules& rules, const SynthesisOptions& options);

/// @p world as a region (SynthesizeRegion calls it) or a stream (its caller does) computes it:
/// with UndecidedFirst, the undecided start and no given start (a world whose undecided run
/// fails falls back to the given one: its regions and streams do not).
SynthesisOptions UndecidedWorld(const SynthesisOptions& world);

} // namespace msynth
