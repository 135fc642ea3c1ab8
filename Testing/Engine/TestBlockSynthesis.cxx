// SPDX-License-Identifier: BSD-3-Clause
// The block machinery every solver shares (Core/BlockSynthesis.h): the block grid and its
// phases, the trivial-start choice, attempts, and the run over phases on threads and processes.
#include "Core/BlockSynthesis.h"

#include "Core/Error.h"

#include <gtest/gtest.h>

#include <condition_variable>
#include <map>
#include <mutex>
#include <new>
#include <set>
#include <thread>

using namespace msynth;

namespace
{
/// Whether two boxes, each grown by one site (the neighbour layer), overlap.
template <std::size_t D>
bool Touch(const BoxBlock<D>& a, const BoxBlock<D>& b)
{
  for (std::size_t k = 0; k < D; ++k)
    if (a.Origin[k] + a.Dims[k] + 1 <= b.Origin[k] || b.Origin[k] + b.Dims[k] + 1 <= a.Origin[k])
      return false;
  return true;
}
} // namespace

TEST(BlockSynthesis, BlocksCoverTheModelAndPhasesNeverTouch)
{
  for (const auto& c :
    std::vector<std::array<std::int64_t, 3>>{ { 1, 1, 1 }, { 3, 5, 1 }, { 8, 8, 3 } })
  {
    const std::array<std::int64_t, 3> n{ { 40, 23, 7 } };
    std::array<std::int64_t, 3> m{}, step{};
    for (std::size_t a = 0; a < 3; ++a)
    {
      m[a] = std::min(c[a] * 2 + 1, n[a]);
      step[a] = std::max<std::int64_t>(1, m[a] - m[a] / 2);
    }
    int phases = 0;
    const auto blocks = PlanBoxBlocks<3>(n, m, step, PhasePolicy::NonTouching, phases);
    std::vector<int> covered(static_cast<std::size_t>(n[0] * n[1] * n[2]), 0);
    std::set<std::int64_t> indices;
    for (std::size_t i = 0; i < blocks.size(); ++i)
    {
      const auto& b = blocks[i];
      indices.insert(b.Index);
      ASSERT_LT(b.Phase, phases);
      if (i > 0)
      {
        ASSERT_LE(blocks[i - 1].Phase, b.Phase) << "ordered by phase";
      }
      for (std::int64_t z = b.Origin[2]; z < b.Origin[2] + b.Dims[2]; ++z)
        for (std::int64_t y = b.Origin[1]; y < b.Origin[1] + b.Dims[1]; ++y)
          for (std::int64_t x = b.Origin[0]; x < b.Origin[0] + b.Dims[0]; ++x)
            ++covered[static_cast<std::size_t>(x + n[0] * (y + n[1] * z))];
      for (std::size_t j = 0; j < i; ++j)
      {
        if (blocks[j].Phase == b.Phase)
        {
          EXPECT_FALSE(Touch(blocks[j], b)) << "blocks " << blocks[j].Index << " and " << b.Index;
        }
      }
    }
    EXPECT_EQ(indices.size(), blocks.size());
    EXPECT_EQ(*indices.rbegin(), static_cast<std::int64_t>(blocks.size()) - 1);
    for (int k : covered)
      ASSERT_GT(k, 0) << "every site lies in a block";
  }
}

TEST(BlockSynthesis, SequentialBlocksRunInScanOrder)
{
  const std::array<std::int64_t, 4> n{ { 9, 5, 1, 6 } }, m{ { 4, 5, 1, 2 } },
    step{ { 2, 3, 1, 1 } };
  int phases = 0;
  const auto blocks = PlanBoxBlocks<4>(n, m, step, PhasePolicy::Sequential, phases);
  ASSERT_EQ(blocks.size(), 4u * 1u * 1u * 5u);
  EXPECT_EQ(phases, static_cast<int>(blocks.size()));
  for (std::size_t i = 0; i < blocks.size(); ++i)
  {
    EXPECT_EQ(blocks[i].Index, static_cast<std::int64_t>(i));
    EXPECT_EQ(blocks[i].Phase, static_cast<int>(i));
  }
  // x fastest, time last; the last block along an axis is clipped to the model.
  EXPECT_EQ(blocks[1].Origin[0], 2);
  EXPECT_EQ(blocks[3].Origin[0], 6);
  EXPECT_EQ(blocks[3].Dims[0], 3);
  EXPECT_EQ(blocks[4].Origin[3], 1);
  EXPECT_EQ(BlockStarts(10, 10, 5), (std::vector<std::int64_t>{ 0 }));
  EXPECT_EQ(BlockStarts(10, 4, 2), (std::vector<std::int64_t>{ 0, 2, 4, 6 }));
}

TEST(BlockSynthesis, TrivialLabelPrefersZeroThenTheFirstUsable)
{
  auto usable = [](int b) { return b == 2 || b == 4; };
  EXPECT_EQ(ChooseTrivialLabel(6, 4, usable), 4);
  EXPECT_EQ(ChooseTrivialLabel(6, 1, usable), 2);
  EXPECT_EQ(ChooseTrivialLabel(6, -1, usable), 2);
  EXPECT_EQ(ChooseTrivialLabel(6, 0, [](int) { return false; }), -1);
}

namespace
{
/// A toy solver: block i succeeds at attempt (i mod 3) unless i is a multiple of 7, and writes
/// a value drawn from (seed, i, attempt) into its cell; Finish records the order it saw.
struct Toy
{
  std::vector<std::int64_t> Cells;
  std::vector<std::size_t> Finished;
  SynthesisStatistics Stats;

  SynthesisStatus Run(BlockRunner& runner, const std::vector<int>& phases)
  {
    Cells.assign(phases.size(), -1);
    BlockRunner::Hooks hooks;
    hooks.Run = [&](unsigned worker, std::size_t i)
    {
      return runner.Attempts(worker, 5,
        [&](int attempt, std::int64_t& assignments)
        {
          ++assignments;
          if (i % 7 == 0 || attempt < static_cast<int>(i % 3))
            return std::int64_t(i);
          Cells[i] = static_cast<std::int64_t>(i * 100 + static_cast<std::size_t>(attempt));
          return std::int64_t(-1);
        });
    };
    hooks.Finish = [&](std::size_t i, const BlockOutcome&) { Finished.push_back(i); };
    hooks.Pack = [&](std::size_t i, BlockRunner::Bytes& out) { out.Put(Cells[i]); };
    hooks.Unpack = [&](std::size_t i, BlockRunner::Bytes& in, bool remote)
    {
      const std::int64_t v = in.Get();
      if (remote)
        Cells[i] = v;
    };
    return runner.Run(phases, hooks, Stats);
  }
};

std::vector<int> Phases()
{
  std::vector<int> phases;
  for (int p = 0; p < 4; ++p)
    for (int k = 0; k < 9; ++k)
      phases.push_back(p);
  return phases;
}
} // namespace

TEST(BlockSynthesis, RunnerGivesTheSameResultOnAnyNumberOfThreadsAndProcesses)
{
  const auto phases = Phases();
  BlockRunner::Policy serial;
  serial.Serial = true;
  BlockRunner one(serial, phases.size());
  Toy reference;
  ASSERT_EQ(reference.Run(one, phases), SynthesisStatus::Succeeded);
  EXPECT_EQ(reference.Stats.Blocks, 36);
  EXPECT_EQ(reference.Stats.BlocksFailed, 6); // 0, 7, 14, 21, 28, 35
  EXPECT_EQ(reference.Stats.BlocksAccepted, 30);
  EXPECT_EQ(reference.Stats.Threads, 1);
  for (std::size_t i = 0; i < reference.Finished.size(); ++i)
  {
    EXPECT_EQ(reference.Finished[i], i) << "Finish in block order";
  }

  BlockRunner::Policy threaded;
  threaded.Threads = 4;
  BlockRunner many(threaded, phases.size());
  Toy parallel;
  ASSERT_EQ(parallel.Run(many, phases), SynthesisStatus::Succeeded);
  EXPECT_EQ(parallel.Cells, reference.Cells);
  EXPECT_EQ(parallel.Finished, reference.Finished);
  EXPECT_EQ(parallel.Stats.Attempts, reference.Stats.Attempts);

  // Three processes in one: each all-gather waits for the others (threads stand for ranks).
  std::mutex mutex;
  std::condition_variable ready;
  std::map<int, std::vector<std::vector<char>>> rounds; // round -> bytes per rank
  std::vector<int> round(3, 0);
  std::vector<Toy> ranks(3);
  std::vector<std::thread> pool;
  for (int r = 0; r < 3; ++r)
  {
    pool.emplace_back(
      [&, r]()
      {
        BlockRunner::Policy policy;
        policy.Threads = 1;
        policy.Exchange.Rank = r;
        policy.Exchange.Processes = 3;
        policy.Exchange.AllGather = [&, r](const std::vector<char>& mine)
        {
          std::unique_lock<std::mutex> lock(mutex);
          const int k = round[static_cast<std::size_t>(r)]++;
          auto& all = rounds[k];
          all.resize(3);
          all[static_cast<std::size_t>(r)] = mine;
          ready.notify_all();
          ready.wait(lock,
            [&]()
            {
              for (const auto& b : rounds[k])
                if (b.empty())
                  return false;
              return true;
            });
          return rounds[k];
        };
        BlockRunner runner(policy, phases.size());
        EXPECT_EQ(runner.Processes(), 3);
        ranks[static_cast<std::size_t>(r)].Run(runner, phases);
      });
  }
  for (auto& t : pool)
    t.join();
  for (const Toy& t : ranks)
  {
    EXPECT_EQ(t.Cells, reference.Cells);
    EXPECT_EQ(t.Stats.BlocksFailed, reference.Stats.BlocksFailed);
    EXPECT_EQ(t.Stats.Processes, 3);
  }
}

TEST(BlockSynthesis, ProgressCancelsBetweenBlocksAndInside)
{
  const auto phases = Phases();
  BlockRunner::Policy policy;
  policy.Serial = true;
  int calls = 0;
  policy.Progress = [&calls](double f)
  {
    EXPECT_GE(f, 0.0);
    EXPECT_LE(f, 1.0);
    return ++calls < 4;
  };
  BlockRunner runner(policy, phases.size());
  Toy toy;
  EXPECT_EQ(toy.Run(runner, phases), SynthesisStatus::Cancelled);
  EXPECT_EQ(toy.Finished.size(), 4u);
  EXPECT_STREQ(ToString(SynthesisStatus::Cancelled), "cancelled");
}

TEST(BlockSynthesis, StatisticsHaveOneNaming)
{
  SynthesisStatistics s;
  s.Blocks = 9;
  s.BlocksAccepted = 7;
  s.BlocksFailed = 2;
  s.Attempts = 15;
  s.Seconds = 0.5;
  std::map<std::string, double> fields;
  for (const auto& f : StatisticsFields(s))
    fields[f.Name] = f.Value;
  EXPECT_EQ(fields.at("Blocks"), 9);
  EXPECT_EQ(fields.at("FailedAttempts"), 8);
  EXPECT_EQ(fields.at("Seconds"), 0.5);
  EXPECT_EQ(Summary(s, false), "7 of 9 blocks synthesized, 2 left at their previous labels");
  EXPECT_EQ(Summary(s, true), "whole-model synthesis succeeded");
}

TEST(BlockSynthesis, TruncatedExchangeIsAnError)
{
  BlockRunner::Bytes b;
  b.Put(7);
  EXPECT_EQ(b.Get(), 7);
  EXPECT_THROW(b.Get(), Error);
}

// An exception inside a block (a solver's Error, bad_alloc) on a worker thread must not end the
// process in std::terminate: it is rethrown on the calling thread after the phase joins, as one
// Error naming the block; on one thread it names the block too.
TEST(BlockSynthesis, AnExceptionInAWorkerReachesTheCallerNamingItsBlock)
{
  const auto phases = Phases();
  for (int threads : { 1, 2, 4 })
  {
    for (bool outOfMemory : { false, true })
    {
      BlockRunner::Policy policy;
      policy.Threads = threads;
      BlockRunner runner(policy, phases.size());
      BlockRunner::Hooks hooks;
      hooks.Run = [&](unsigned, std::size_t i)
      {
        if (i == 12 || i == 14)
        {
          if (outOfMemory)
            throw std::bad_alloc();
          throw Error("the catalog of site (1, 2, 0) is empty");
        }
        return BlockOutcome{};
      };
      hooks.Finish = [](std::size_t, const BlockOutcome&) {};
      SynthesisStatistics stats;
      std::string what;
      try
      {
        runner.Run(phases, hooks, stats);
      }
      catch (const Error& e)
      {
        what = e.what();
      }
      const std::string expected = outOfMemory
        ? "block 13 of 36 ran out of memory"
        : "block 13 of 36: the catalog of site (1, 2, 0) is empty";
      EXPECT_EQ(what, expected) << threads << " threads";
    }
  }
}
