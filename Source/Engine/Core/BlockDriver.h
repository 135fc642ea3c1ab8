// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/**
 * @file BlockDriver.h
 * @brief The one driver of every block solver (Algorithm 3.4's outer loop, D§3.3.7's phases,
 * T§4.5.6's continuous blocks): it owns the schedule of blocks and phases, each block's attempts
 * with their generators derived from (seed, block key, attempt), the clock, the failure records,
 * cancellation, and the status and message a run ends with.
 *
 * A solver is a BlockClient: how to enter a block, one attempt at it, what to keep after it, and
 * where a failed block's catalog emptied. Discrete synthesis (Discrete/DiscreteSynthesis.cxx),
 * time-varying synthesis (Discrete/TimeVarying.cxx) and continuous synthesis
 * (Continuous/ContinuousSynthesis.cxx) are its clients; pattern synthesis (Patterns/) uses its
 * clock, cancel poll and status.
 */
#include "Core/BlockSynthesis.h"
#include "Core/ProgressPoll.h"
#include "Core/Random.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace msynth
{

/// The schedule of a run: per block its phase and the sub-key of its generators.
struct BlockSchedule
{
  std::vector<int> Phases;         ///< one per block, non-decreasing
  std::vector<std::uint64_t> Keys; ///< block i's generators: Random::Derived(seed, Keys[i], a)

  /// The box blocks' phases and their indices in the block grid as keys.
  template <std::size_t D>
  static BlockSchedule Of(const std::vector<BoxBlock<D>>& blocks)
  {
    BlockSchedule s;
    for (const auto& b : blocks)
    {
      s.Phases.push_back(b.Phase);
      s.Keys.push_back(static_cast<std::uint64_t>(b.Index));
    }
    return s;
  }
  /// Blocks with these keys one after the other, each its own phase.
  static BlockSchedule InSequence(std::vector<std::uint64_t> keys);
  std::size_t Size() const { return this->Phases.size(); }
};

/// What a solver does with block i of the schedule; the driver does the rest.
struct BlockClient
{
  /// Optional: before the attempts at block i on worker @p worker (save state, gather sites).
  std::function<void(unsigned worker, std::size_t i)> Enter;
  /// One attempt at block i with its generator: -1 when solved, else where the catalog emptied
  /// (a solver-defined index). Adds its label choices to @p assignments.
  std::function<std::int64_t(
    unsigned worker, std::size_t i, int attempt, Random& rng, std::int64_t& assignments)>
    Attempt;
  /// Optional: after block i ran (and Describe), in block order on the calling thread (keep or
  /// roll back, snapshots, leave the block).
  std::function<void(std::size_t i, const BlockOutcome& outcome)> After;
  /// Optional: the details of failed block i's record (origin, emptied site); the driver has set
  /// Block (the key) and Attempts.
  std::function<void(std::size_t i, const BlockOutcome& outcome, BlockFailure& failure)> Describe;
  /// Processes: block i's labels out; read back (@p remote: write them into the model).
  std::function<void(std::size_t i, BlockRunner::Bytes& out)> Pack;
  std::function<void(std::size_t i, BlockRunner::Bytes& in, bool remote)> Unpack;
};

/// How the driver runs a schedule: a second pass over some blocks has over some blocks: its own
/// attempt streams, count and threads.
struct BlockPass
{
  int AttemptOffset = 0; ///< added to each attempt's number in its generator
  int Attempts = 0;      ///< attempts per block; 0: the driver's
  bool Serial = false;   ///< one block at a time on the calling thread
  /// A pass after the first: its own run over the phases, progress held at the end.
  bool Later = false;
};

class BlockDriver
{
public:
  /**
   * A driver for @p blocks blocks (the largest schedule it will run) whose attempts draw from
   * @p seed; @p attempts per block. The run's clock starts at @p start (its set-up counts).
   */
  BlockDriver(BlockRunner::Policy policy, std::uint64_t seed, int attempts, std::size_t blocks,
    std::chrono::steady_clock::time_point start = std::chrono::steady_clock::now());
  ~BlockDriver();
  BlockDriver(const BlockDriver&) = delete;
  BlockDriver& operator=(const BlockDriver&) = delete;

  /// The threads a run uses (one solver each).
  unsigned Workers() const;

  /**
   * Runs @p schedule: for each block Enter, then attempts until one succeeds or the attempts
   * are spent, then (in block order) for a failed block a BlockFailure into @p stats
   * (Describe), and After. Returns Cancelled when the progress callback asked to stop, else
   * Succeeded (blocks may have failed: see stats).
   */
  SynthesisStatus Run(const BlockSchedule& schedule, const BlockClient& client,
    SynthesisStatistics& stats, const BlockPass& pass = BlockPass());

  /// For solvers inside a block: whether the run is being cancelled (polls the progress
  /// callback on worker 0 at most every 100 ms). @p within: how much of worker 0's block is
  /// done (0 to 1), so that a run of one long block reports its progress too.
  bool Stopped(unsigned worker, double within = 0.0);
  /// The one cancel poll of the solvers' inner loops: Stopped, every 1024th of @p count.
  bool Poll(unsigned worker, std::int64_t count, double within = 0.0)
  {
    return detail::PollDue(count) && this->Stopped(worker, within);
  }

  /// Seconds since the run's start.
  double Seconds() const;

  /**
   * The end of a run: @p stats.Seconds set; a cancelled run gets the message "cancelled"; a
   * whole model with a failed block becomes Failed with @p failure's message (the first failed
   * block's record). Returns whether a model follows (Succeeded).
   */
  bool End(SynthesisStatus& status, std::string& message, SynthesisStatistics& stats,
    bool wholeModel, const std::function<std::string(const BlockFailure&)>& failure) const;

private:
  struct Internal;
  std::unique_ptr<Internal> State;
};

/**
 * The message of a whole model (Algorithm 3.1 or 4.1) that failed every attempt: "@p what
 * failed in all N attempts; @p where in the last. @p advice".
 */
std::string WholeModelFailure(
  const std::string& what, int attempts, const std::string& where, const std::string& advice);

/**
 * The block size and step of a D-dimensional grid of @p n sites: blocks of @p size (0 on an
 * axis: the whole axis), overlapping by @p overlap (-1: half the block, the dissertation's
 * choice; at most the block less one). Returns whether one block covers the grid.
 */
template <std::size_t D>
bool BlockGeometry(const std::array<std::int64_t, D>& n, const std::array<std::int64_t, D>& size,
  const std::array<std::int64_t, D>& overlap, std::array<std::int64_t, D>& m,
  std::array<std::int64_t, D>& step)
{
  bool whole = true;
  for (std::size_t a = 0; a < D; ++a)
  {
    m[a] = size[a] <= 0 ? n[a] : std::min(size[a], n[a]);
    whole = whole && m[a] == n[a];
    std::int64_t o = overlap[a] < 0 ? m[a] / 2 : overlap[a];
    o = std::min(o, m[a] - 1);
    step[a] = m[a] - o;
  }
  return whole;
}

} // namespace msynth
