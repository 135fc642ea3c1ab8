// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/**
 * @file BlockSynthesis.h
 * @brief The block machinery every solver shares (D§3.3.6, Algorithm 3.4; D§3.3.7 for the
 * phases; T§4.5.6 for the continuous blocks): the block grid and its phases of non-touching
 * blocks, the trivial-start choice, a block's attempts each from its own generator, the run
 * over phases on threads and processes with cancellation, failure records, one status and one
 * statistics record for every solver.
 *
 * A solver keeps only what is its own: its neighbourhood (which sites a block holds and what
 * constrains them from outside) and its label choice. Discrete synthesis
 * (Discrete/DiscreteSynthesis.cxx), time-varying synthesis (Discrete/TimeVarying.cxx) and
 * continuous synthesis (Continuous/ContinuousSynthesis.cxx) are its clients.
 */
#include "Core/Index.h"
#include "Core/LabelGrid.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <cstdint>
#include <functional>
#include <iosfwd>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace msynth
{

/// How a run of any solver ended.
enum class SynthesisStatus
{
  Succeeded, ///< a complete consistent model (blocks that failed kept their previous labels)
  Failed,    ///< no model: whole-model synthesis (Algorithm 3.1 / 4.1) failed every attempt
  Cancelled  ///< the progress callback asked to stop; no model
};

/// "succeeded", "failed" or "cancelled".
const char* ToString(SynthesisStatus status);

/**
 * The state of the catalog over the whole model at one moment, for watching a solver work (every
 * solver reports these). Sites outside the block being synthesized hold their current label
 * (catalog size 1).
 */
struct CatalogSnapshot
{
  std::int64_t Step = 0;                 ///< 0 for the start, then 1, 2, ...
  std::int64_t Block = -1;               ///< block being synthesized (-1 at the start)
  std::int64_t Assignments = 0;          ///< label choices made so far
  std::vector<std::int32_t> CatalogSize; ///< labels still possible per site
  std::vector<float> Entropy;            ///< entropy of the (weighted) possible labels per site
  /// Where decided, the label (discrete: its value; continuous: the example's label id), else
  /// Undecided.
  std::vector<Label> Labels;
  static constexpr Label Undecided = -2147483647 - 1;
};

/// A block whose every attempt failed (the model keeps its previous labels there).
struct BlockFailure
{
  std::int64_t Block = 0;                  ///< index in scan order of the block grid
  std::array<std::int64_t, 3> Origin{};    ///< first site (continuous: first cell)
  std::array<std::int64_t, 3> EmptySite{}; ///< where the last attempt's catalog emptied
  std::int64_t Frame = -1;                 ///< time-varying: the frame of EmptySite
  std::int64_t EmptyIndex = -1; ///< the emptied site's index (continuous: arrangement vertex)
  int Attempts = 0;
};

/// What a run did, with the same names for every solver (StatisticsFields).
struct SynthesisStatistics
{
  std::int64_t Blocks = 0;
  std::int64_t BlocksAccepted = 0; ///< solved (including those the soft constraints rolled back)
  std::int64_t BlocksFailed = 0;
  std::int64_t BlocksRejected = 0; ///< synthesized but rolled back by the soft constraints
  /// Failed blocks synthesized by a second try after every other block (counted in
  /// BlocksAccepted, not in BlocksFailed).
  std::int64_t BlocksRepaired = 0;
  std::int64_t Attempts = 0;
  std::int64_t Assignments = 0;
  std::int64_t Backtracks = 0; ///< labels withdrawn because their propagation failed
  int Phases = 1;
  int Threads = 1;   ///< threads used
  int Processes = 1; ///< processes the blocks were spread over
  double Seconds = 0.0;
  std::vector<BlockFailure> Failures;
  std::optional<Label> TrivialLabel; ///< the trivial start used (block mode)
  /// How block synthesis started: "trivial" (Algorithm 3.4's start), "undecided" or "whole"
  /// (a whole-model solution); empty for whole-model synthesis.
  std::string StartFrom;
};

/// One figure of SynthesisStatistics under its one name.
struct StatisticsField
{
  std::string Name;
  double Value = 0.0;
  bool Integer = true; ///< a count (Seconds is the only one that is not)
};

/// The statistics in one order and naming, for field data and JSON: Blocks, BlocksAccepted,
/// BlocksFailed, BlocksRejected, BlocksRepaired, Attempts, FailedAttempts, Assignments,
/// Backtracks, Phases, Threads, Processes, Seconds.
std::vector<StatisticsField> StatisticsFields(const SynthesisStatistics& s);

/// The one-line summary of a finished run: "whole-model synthesis succeeded" or "A of B blocks
/// synthesized, F left at their previous labels[, R rolled back by the soft constraints]".
std::string Summary(const SynthesisStatistics& s, bool wholeModel);

/**
 * Distribution of block synthesis over processes (e.g. MPI ranks under pvbatch). Blocks of a
 * phase never touch, so each process runs its share of every phase (position in the phase
 * modulo Processes = Rank), and AllGather exchanges the results: it receives this process's
 * bytes and must return every process's bytes, in rank order (an all-gather). Each process
 * then holds the whole model, identical to a one-process run. Every process must call the
 * solver with the same inputs.
 */
struct BlockExchange
{
  int Rank = 0;
  int Processes = 1;
  std::function<std::vector<std::vector<char>>(const std::vector<char>&)> AllGather;
  bool Active() const { return this->Processes > 1 && static_cast<bool>(this->AllGather); }
};

// ---------------------------------------------------------------------------------------------
// The block grid
// ---------------------------------------------------------------------------------------------

/// Block origins along one axis of n sites: steps of @p step until a block of @p m covers it.
std::vector<std::int64_t> BlockStarts(std::int64_t n, std::int64_t m, std::int64_t step);

/// Which blocks may share a phase.
enum class PhasePolicy
{
  /// Blocks ceil((m + 1) / step) apart along every axis never touch (nor their neighbour
  /// layers), so a phase holds such blocks and may run them in any order, or concurrently.
  NonTouching,
  /// Every block is its own phase: blocks run one after the other in scan order.
  Sequential
};

/// One box block of a D-dimensional grid: [Origin, Origin + Dims), clipped to the model.
template <std::size_t D>
struct BoxBlock
{
  std::int64_t Index = 0; ///< position in scan order of the block grid (the seed's sub-key)
  std::array<std::int64_t, D> Origin{};
  std::array<std::int64_t, D> Dims{};
  int Phase = 0;
};

/// Which axis' digit of a phase number (the block's lattice position modulo the axis' period)
/// changes fastest.
enum class PhaseDigits
{
  /// The axis with the fewest block origins first, ties in axis order. A region's cone grows
  /// along an axis each time the axis' digit changes as the phases are walked backwards
  /// (Core/WorldSchedule.h), so the axis that changes every phase is the one the world bounds
  /// soonest, and the cone of a region in a wide, flat world stays a few blocks wide instead of
  /// reaching across it. The discrete solver's worlds, regions and streams.
  FewestOriginsFirst,
  /// Axis 0 first, the last axis slowest: every block of the lowest layer of blocks runs before
  /// those above. The continuous solver's: its grounded objects stand on what was chosen below
  /// (with the vertical digit fastest, the grounded town's walls fell to 0.30 of the solid
  /// volume in each of test_proportions' five seeds, against the example's 0.49).
  AxisOrder
};

/// The axes in the order of their phase digits (the first changes fastest), for a grid with
/// @p origins block origins along each axis.
template <std::size_t D>
std::array<int, D> PhaseDigitOrder(const std::array<std::int64_t, D>& origins, PhaseDigits digits)
{
  std::array<int, D> order{};
  for (std::size_t a = 0; a < D; ++a)
    order[a] = static_cast<int>(a);
  if (digits == PhaseDigits::FewestOriginsFirst)
    std::stable_sort(order.begin(), order.end(),
      [&](int a, int b) { return origins[ToIndex(a)] < origins[ToIndex(b)]; });
  return order;
}

/**
 * The blocks of a grid of @p n sites, blocks of @p m, origins @p step apart (indices in scan
 * order, axis 0 fastest; phase digits as @p digits), ordered by phase then scan order. @p phases
 * receives the number of phases. @p reach: how far (in sites, along any axis) a site's neighbours
 * may lie; NonTouching blocks of a phase are ceil((m + reach) / step) origins apart, so no block
 * reads a site another one writes (1 for the grids' six neighbours; the continuous solver's cells
 * pass the longest edge in cells).
 */
template <std::size_t D>
std::vector<BoxBlock<D>> PlanBoxBlocks(const std::array<std::int64_t, D>& n,
  const std::array<std::int64_t, D>& m, const std::array<std::int64_t, D>& step, PhasePolicy policy,
  int& phases, std::int64_t reach = 1, PhaseDigits digits = PhaseDigits::FewestOriginsFirst);

/// The phase of each block of @p blocks, in their order (what BlockRunner::Run takes).
template <std::size_t D>
std::vector<int> PhasesOf(const std::vector<BoxBlock<D>>& blocks)
{
  std::vector<int> phases;
  phases.reserve(blocks.size());
  for (const auto& b : blocks)
    phases.push_back(b.Phase);
  return phases;
}

/**
 * The label of the trivial start (Algorithm 3.4, lines 3-5) among @p k labels: label @p zero
 * (the index of value 0, or -1) when @p usable, else the first usable label; -1 when none is.
 */
int ChooseTrivialLabel(int k, int zero, const std::function<bool(int)>& usable);

// ---------------------------------------------------------------------------------------------
// A block's attempts and the run over phases
// ---------------------------------------------------------------------------------------------

/// The result of all attempts at one block.
struct BlockOutcome
{
  std::int64_t Empty = -1; ///< -1: solved; else where the last attempt's catalog emptied
  int Attempts = 0;
  std::int64_t Assignments = 0;
  bool Solved() const { return this->Empty < 0; }
};

/**
 * Runs blocks of a model phase by phase (Algorithm 3.4's outer loop, D§3.3.7's parallel
 * phases), on threads and processes, with cancellation. The solver gives a Run hook (all
 * attempts at one block on one worker; see Attempts) and a Finish hook (what follows a block:
 * keep or roll back, snapshots), and for processes Pack/Unpack of a block's labels.
 *
 * Determinism: a block's attempts draw from generators derived from (seed, block, attempt),
 * and blocks of a phase never touch, so the model does not depend on the number of threads or
 * processes. Finish is called in block order on the calling thread: right after each block when
 * one worker runs alone (Serial), after the whole phase otherwise.
 */
class BlockRunner
{
public:
  /// Serialized block labels for the process exchange.
  struct Bytes
  {
    std::vector<char> Data;
    std::size_t At = 0;
    void Put(std::int64_t v);
    std::int64_t Get(); ///< @throw Error when the data ends
  };

  struct Hooks
  {
    /// All attempts at block @p i on worker @p worker (0 is the calling thread's). Blocks of a
    /// phase run concurrently on different workers.
    std::function<BlockOutcome(unsigned worker, std::size_t i)> Run;
    /// After block @p i ran, in block order: keep or roll back, snapshots, failure details.
    std::function<void(std::size_t i, const BlockOutcome& outcome)> Finish;
    /// Processes: appends block @p i's labels; reads them back (@p remote: write into the model).
    std::function<void(std::size_t i, Bytes& out)> Pack;
    std::function<void(std::size_t i, Bytes& in, bool remote)> Unpack;
  };

  struct Policy
  {
    int Threads = 1;        ///< requested threads; 0: one per core (always clamped to the cores)
    BlockExchange Exchange; ///< processes; inactive by default
    bool Serial = false;    ///< one thread, one process (snapshots, seams, fitness functions)
    /// Fraction done after each block (one worker) or phase; false cancels. Also polled inside
    /// blocks (Stopped) at most every 100 ms.
    std::function<bool(double)> Progress;
  };

  BlockRunner(Policy policy, std::size_t blocks);
  ~BlockRunner();
  BlockRunner(const BlockRunner&) = delete;
  BlockRunner& operator=(const BlockRunner&) = delete;

  /// Workers that Run will use (the threads of the run).
  unsigned Workers() const { return this->NumberOfWorkers; }
  int Processes() const;

  /**
   * Runs the blocks, whose phases are @p phases (non-decreasing, one per block), adding their
   * counts to @p stats. Returns Cancelled when the progress callback asked to stop, else
   * Succeeded (blocks may have failed: see stats).
   */
  SynthesisStatus Run(
    const std::vector<int>& phases, const Hooks& hooks, SynthesisStatistics& stats);

  /**
   * For the solvers inside a block, every 1024 assignments or so: whether the run is being
   * cancelled. Worker 0 also polls the progress callback (at most every 100 ms), told the
   * blocks done and @p within, how much of its current block is (0 to 1).
   */
  bool Stopped(unsigned worker, double within = 0.0);

  /**
   * All attempts at a block: attempt a (0, 1, ...) gets the generator seed of (seed, block, a)
   * through @p attempt(rng-sub-key a, outcome), which returns -1 on success or the emptied
   * site; stops at the first success, after @p attempts, or when the run is being cancelled.
   */
  template <typename AttemptFn>
  BlockOutcome Attempts(unsigned worker, int attempts, AttemptFn&& attempt)
  {
    BlockOutcome out;
    while (out.Attempts < attempts)
    {
      const int a = out.Attempts++;
      out.Empty = attempt(a, out.Assignments);
      if (out.Empty < 0 || this->Stopped(worker))
        break;
    }
    return out;
  }

private:
  struct Internal;
  std::unique_ptr<Internal> State;
  unsigned NumberOfWorkers = 1;
};

} // namespace msynth
