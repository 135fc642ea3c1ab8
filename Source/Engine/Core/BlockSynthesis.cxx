// SPDX-License-Identifier: BSD-3-Clause
#include "Core/BlockSynthesis.h"

#include "Core/Error.h"
#include "Core/Index.h"
#include "Core/ProgressPoll.h"

#include <algorithm>
#include <atomic>
#include <cstring>
#include <exception>
#include <mutex>
#include <new>
#include <system_error>
#include <thread>

namespace msynth
{

const char* ToString(SynthesisStatus status)
{
  switch (status)
  {
    case SynthesisStatus::Succeeded:
      return "succeeded";
    case SynthesisStatus::Failed:
      return "failed";
    case SynthesisStatus::Cancelled:
      return "cancelled";
  }
  return "?";
}

std::vector<StatisticsField> StatisticsFields(const SynthesisStatistics& s)
{
  auto count = [](const char* name, std::int64_t v) {
    return StatisticsField{ name, static_cast<double>(v), true };
  };
  return { count("Blocks", s.Blocks), count("BlocksAccepted", s.BlocksAccepted),
    count("BlocksFailed", s.BlocksFailed), count("BlocksRejected", s.BlocksRejected),
    count("BlocksRepaired", s.BlocksRepaired), count("Attempts", s.Attempts),
    count("FailedAttempts", s.Attempts - s.BlocksAccepted), count("Assignments", s.Assignments),
    count("Backtracks", s.Backtracks), count("Phases", s.Phases), count("Threads", s.Threads),
    count("Processes", s.Processes), StatisticsField{ "Seconds", s.Seconds, false } };
}

std::string Summary(const SynthesisStatistics& s, bool wholeModel)
{
  if (wholeModel)
    return "whole-model synthesis succeeded";
  return std::to_string(s.BlocksAccepted) + " of " + std::to_string(s.Blocks) +
    " blocks synthesized, " + std::to_string(s.BlocksFailed) + " left at their previous labels" +
    (s.BlocksRejected
        ? ", " + std::to_string(s.BlocksRejected) + " rolled back by the soft constraints"
        : std::string()) +
    (s.BlocksRepaired ? ", " + std::to_string(s.BlocksRepaired) + " of them on a second try"
                      : std::string());
}

std::vector<std::int64_t> BlockStarts(std::int64_t n, std::int64_t m, std::int64_t step)
{
  std::vector<std::int64_t> starts{ 0 };
  while (starts.back() + m < n)
    starts.push_back(starts.back() + step);
  return starts;
}

template <std::size_t D>
std::vector<BoxBlock<D>> PlanBoxBlocks(const std::array<std::int64_t, D>& n,
  const std::array<std::int64_t, D>& m, const std::array<std::int64_t, D>& step, PhasePolicy policy,
  int& phases, std::int64_t reach, PhaseDigits digits)
{
  reach = std::max<std::int64_t>(reach, 0);
  std::array<std::vector<std::int64_t>, D> starts;
  std::array<int, D> period{};
  std::size_t count = 1;
  for (std::size_t a = 0; a < D; ++a)
  {
    starts[a] = BlockStarts(n[a], m[a], step[a]);
    period[a] = starts[a].size() > 1 ? static_cast<int>((m[a] + reach + step[a] - 1) / step[a]) : 1;
    count *= starts[a].size();
  }
  std::array<std::int64_t, D> origins{};
  for (std::size_t a = 0; a < D; ++a)
    origins[a] = static_cast<std::int64_t>(starts[a].size());
  std::array<int, D> radix{};
  int r = 1;
  for (int a : PhaseDigitOrder<D>(origins, digits))
  {
    radix[ToIndex(a)] = r;
    r *= period[ToIndex(a)];
  }
  std::vector<BoxBlock<D>> blocks(count);
  for (std::size_t index = 0; index < count; ++index)
  {
    BoxBlock<D>& b = blocks[index];
    b.Index = static_cast<std::int64_t>(index);
    std::size_t rest = index;
    int phase = 0;
    for (std::size_t a = 0; a < D; ++a)
    {
      const std::size_t i = rest % starts[a].size();
      rest /= starts[a].size();
      b.Origin[a] = starts[a][i];
      b.Dims[a] = std::min(m[a], n[a] - b.Origin[a]);
      phase += radix[a] * static_cast<int>(i % ToIndex(period[a]));
    }
    b.Phase = policy == PhasePolicy::NonTouching ? phase : static_cast<int>(index);
  }
  if (policy == PhasePolicy::NonTouching)
  {
    std::stable_sort(blocks.begin(), blocks.end(),
      [](const BoxBlock<D>& a, const BoxBlock<D>& b) { return a.Phase < b.Phase; });
    phases = 1;
    for (std::size_t a = 0; a < D; ++a)
      phases *= period[a];
  }
  else
  {
    phases = static_cast<int>(count);
  }
  return blocks;
}

template std::vector<BoxBlock<3>> PlanBoxBlocks<3>(const std::array<std::int64_t, 3>&,
  const std::array<std::int64_t, 3>&, const std::array<std::int64_t, 3>&, PhasePolicy, int&,
  std::int64_t, PhaseDigits);
template std::vector<BoxBlock<4>> PlanBoxBlocks<4>(const std::array<std::int64_t, 4>&,
  const std::array<std::int64_t, 4>&, const std::array<std::int64_t, 4>&, PhasePolicy, int&,
  std::int64_t, PhaseDigits);

int ChooseTrivialLabel(int k, int zero, const std::function<bool(int)>& usable)
{
  if (zero >= 0 && usable(zero))
    return zero;
  for (int b = 0; b < k; ++b)
    if (usable(b))
      return b;
  return -1;
}

// ---------------------------------------------------------------------------------------------
// BlockRunner
// ---------------------------------------------------------------------------------------------

void BlockRunner::Bytes::Put(std::int64_t v)
{
  char b[8];
  std::memcpy(b, &v, 8);
  this->Data.insert(this->Data.end(), b, b + 8);
}

std::int64_t BlockRunner::Bytes::Get()
{
  if (this->At + 8 > this->Data.size())
    throw Error("block exchange: a truncated result");
  std::int64_t v;
  std::memcpy(&v, this->Data.data() + this->At, 8);
  this->At += 8;
  return v;
}

struct BlockRunner::Internal
{
  Policy Options;
  std::size_t Blocks = 0;
  std::size_t Done = 0;
  std::size_t Processes = 1;
  std::size_t Rank = 0;
  std::atomic<bool> Stop{ false };
  detail::ProgressPoll Poll{ nullptr };

  bool Distributed() const { return this->Processes > 1; }
  double Fraction() const
  {
    return double(this->Done) / double(std::max<std::size_t>(this->Blocks, 1));
  }
  bool Report()
  {
    return this->Stop || (this->Options.Progress && !this->Options.Progress(this->Fraction()));
  }

  /// The all-gather of a phase [first, last): this process's outcomes and labels out, every
  /// other process's in. Returns whether any process asked to cancel.
  bool Exchange(std::size_t first, std::size_t last, const std::vector<std::size_t>& mine,
    std::vector<BlockOutcome>& outcomes, bool cancelledHere, const Hooks& hooks)
  {
    Bytes out;
    out.Put(cancelledHere ? 1 : 0);
    for (std::size_t i : mine)
    {
      const BlockOutcome& o = outcomes[i - first];
      out.Put(static_cast<std::int64_t>(i));
      out.Put(o.Empty);
      out.Put(o.Attempts);
      out.Put(o.Assignments);
      hooks.Pack(i, out);
    }
    auto all = this->Options.Exchange.AllGather(out.Data);
    if (all.size() != this->Processes)
      throw Error("block exchange: expected results from " + std::to_string(this->Processes) +
        " processes, got " + std::to_string(all.size()));
    bool anyCancelled = false;
    for (std::size_t p = 0; p < all.size(); ++p)
    {
      Bytes in;
      in.Data = std::move(all[p]);
      anyCancelled = in.Get() != 0 || anyCancelled;
      while (in.At < in.Data.size())
      {
        const auto i = ToIndex(in.Get());
        if (i < first || i >= last)
          throw Error(
            "block exchange: process " + std::to_string(p) + " sent a block of another phase");
        BlockOutcome& o = outcomes[i - first];
        o.Empty = in.Get();
        o.Attempts = static_cast<int>(in.Get());
        o.Assignments = in.Get();
        hooks.Unpack(i, in, p != this->Rank);
      }
    }
    return anyCancelled;
  }
};

namespace
{
/// The exception @p e that ended block @p i (of @p blocks) as one Error naming the block.
[[noreturn]] void RethrowInBlock(std::size_t i, std::size_t blocks, const std::exception_ptr& e)
{
  const std::string block = "block " + std::to_string(i + 1) + " of " + std::to_string(blocks);
  try
  {
    std::rethrow_exception(e);
  }
  catch (const std::bad_alloc&)
  {
    throw Error(block + " ran out of memory");
  }
  catch (const std::exception& x)
  {
    throw Error(block + ": " + x.what());
  }
  catch (...)
  {
    throw Error(block + " failed with an exception that is not a std::exception");
  }
}
/**
 * Runs blocks @p mine (indices; block i's outcome goes to outcomes[i - first]) on @p workers
 * threads, the calling one included. An exception in a worker stops the others (@p stop) and
 * is rethrown here after the join, naming its block (the first, in block order, that threw).
 */
void RunOnWorkers(unsigned workers, const std::vector<std::size_t>& mine, std::size_t first,
  std::size_t blocks, const BlockRunner::Hooks& hooks, std::atomic<bool>& stop,
  std::vector<BlockOutcome>& outcomes)
{
  std::atomic<std::size_t> next{ 0 };
  std::mutex failureMutex;
  std::exception_ptr failure;
  std::size_t failedBlock = blocks;
  std::atomic<bool> failed{ false };
  auto work = [&](unsigned worker)
  {
    for (std::size_t j; !failed.load() && (j = next++) < mine.size();)
    {
      try
      {
        outcomes[mine[j] - first] = hooks.Run(worker, mine[j]);
      }
      catch (...)
      {
        std::lock_guard<std::mutex> lock(failureMutex);
        if (mine[j] < failedBlock)
        {
          failedBlock = mine[j];
          failure = std::current_exception();
        }
        failed.store(true);
        stop.store(true); // the other workers' blocks end at their next poll
      }
    }
  };
  std::vector<std::thread> pool;
  for (unsigned w = 1; w < workers; ++w)
  {
    try
    {
      pool.emplace_back(work, w);
    }
    catch (const std::system_error&)
    {
      break; // no more threads to be had: the others and this one share the blocks
    }
  }
  work(0);
  for (auto& t : pool)
    t.join();
  if (failure)
    RethrowInBlock(failedBlock, blocks, failure);
}
} // namespace

BlockRunner::BlockRunner(Policy policy, std::size_t blocks)
  : State(std::make_unique<Internal>())
{
  Internal& s = *this->State;
  s.Blocks = blocks;
  s.Poll = detail::ProgressPoll(policy.Progress);
  // More threads than cores only costs memory (a solver each): clamp to the cores.
  const unsigned cores = std::max(1u, std::thread::hardware_concurrency());
  unsigned threads =
    policy.Threads > 0 ? std::min(static_cast<unsigned>(policy.Threads), cores) : cores;
  if (policy.Serial || blocks < 2)
    threads = 1;
  this->NumberOfWorkers = threads;
  const bool distributed = policy.Exchange.Active() && !policy.Serial;
  if (distributed &&
    (policy.Exchange.Rank < 0 || policy.Exchange.Rank >= policy.Exchange.Processes))
    throw Error("block exchange: rank " + std::to_string(policy.Exchange.Rank) + " of " +
      std::to_string(policy.Exchange.Processes) + " processes");
  s.Processes = distributed ? ToIndex(policy.Exchange.Processes) : 1;
  s.Rank = distributed ? ToIndex(policy.Exchange.Rank) : 0;
  s.Options = std::move(policy);
}

BlockRunner::~BlockRunner() = default;

int BlockRunner::Processes() const
{
  return static_cast<int>(this->State->Processes);
}

bool BlockRunner::Stopped(unsigned worker, double within)
{
  Internal& s = *this->State;
  const double block = std::clamp(within, 0.0, 1.0) / double(std::max<std::size_t>(s.Blocks, 1));
  if (worker == 0 && !s.Poll.Continue(std::min(1.0, s.Fraction() + block)))
    s.Stop.store(true);
  return s.Stop.load(std::memory_order_relaxed);
}

SynthesisStatus BlockRunner::Run(
  const std::vector<int>& phases, const Hooks& hooks, SynthesisStatistics& stats)
{
  Internal& s = *this->State;
  stats.Blocks = static_cast<std::int64_t>(phases.size());
  stats.Threads = static_cast<int>(this->NumberOfWorkers);
  stats.Processes = static_cast<int>(s.Processes);
  auto record = [&stats](const BlockOutcome& out)
  {
    stats.Attempts += out.Attempts;
    stats.Assignments += out.Assignments;
    if (out.Solved())
      ++stats.BlocksAccepted;
    else
      ++stats.BlocksFailed;
  };
  bool cancelled = false, cancelRequested = false;
  for (std::size_t first = 0; first < phases.size() && !cancelled;)
  {
    std::size_t last = first;
    while (last < phases.size() && phases[last] == phases[first])
      ++last;
    if (this->NumberOfWorkers == 1 && !s.Distributed())
    {
      for (std::size_t i = first; i < last && !cancelled; ++i)
      {
        BlockOutcome out;
        try
        {
          out = hooks.Run(0, i);
        }
        catch (...)
        {
          RethrowInBlock(i, phases.size(), std::current_exception());
        }
        hooks.Finish(i, out);
        record(out);
        ++s.Done;
        cancelled = s.Report();
      }
      first = last;
      continue;
    }
    // This process's blocks of the phase (all of them without distribution), on the workers.
    std::vector<BlockOutcome> outcomes(last - first);
    std::vector<std::size_t> mine;
    for (std::size_t i = first; i < last; ++i)
      if ((i - first) % s.Processes == s.Rank)
        mine.push_back(i);
    RunOnWorkers(this->NumberOfWorkers, mine, first, phases.size(), hooks, s.Stop, outcomes);
    if (s.Distributed()) // every process stops at the same phase
      cancelled = s.Exchange(first, last, mine, outcomes, cancelRequested, hooks);
    for (std::size_t i = first; i < last; ++i)
    {
      hooks.Finish(i, outcomes[i - first]); // in block order: deterministic
      record(outcomes[i - first]);
    }
    s.Done += last - first;
    const bool stopHere = s.Report();
    if (s.Distributed())
      cancelRequested = cancelRequested || stopHere;
    else
      cancelled = stopHere;
    first = last;
  }
  return cancelled ? SynthesisStatus::Cancelled : SynthesisStatus::Succeeded;
}

} // namespace msynth
