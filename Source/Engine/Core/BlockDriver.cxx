// SPDX-License-Identifier: BSD-3-Clause
#include "Core/BlockDriver.h"

#include <numeric>
#include <utility>

namespace msynth
{

BlockSchedule BlockSchedule::InSequence(std::vector<std::uint64_t> keys)
{
  BlockSchedule s;
  s.Phases.resize(keys.size());
  std::iota(s.Phases.begin(), s.Phases.end(), 0);
  s.Keys = std::move(keys);
  return s;
}

struct BlockDriver::Internal
{
  BlockRunner::Policy Policy;
  std::uint64_t Seed = 0;
  int Attempts = 1;
  std::unique_ptr<BlockRunner> Runner;
  BlockRunner* Current = nullptr; ///< the runner of the pass under way
  std::chrono::steady_clock::time_point Start;
};

BlockDriver::BlockDriver(BlockRunner::Policy policy, std::uint64_t seed, int attempts,
  std::size_t blocks, std::chrono::steady_clock::time_point start)
  : State(std::make_unique<Internal>())
{
  Internal& s = *this->State;
  s.Start = start;
  s.Policy = policy;
  s.Seed = seed;
  s.Attempts = attempts;
  s.Runner = std::make_unique<BlockRunner>(std::move(policy), blocks);
  s.Current = s.Runner.get();
}

BlockDriver::~BlockDriver() = default;

unsigned BlockDriver::Workers() const
{
  return this->State->Runner->Workers();
}

bool BlockDriver::Stopped(unsigned worker, double within)
{
  return this->State->Current->Stopped(worker, within);
}

double BlockDriver::Seconds() const
{
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - this->State->Start)
    .count();
}

SynthesisStatus BlockDriver::Run(const BlockSchedule& schedule, const BlockClient& client,
  SynthesisStatistics& stats, const BlockPass& pass)
{
  Internal& s = *this->State;
  std::unique_ptr<BlockRunner> serial;
  BlockRunner* runner = s.Runner.get();
  if (pass.Serial || pass.Later)
  {
    BlockRunner::Policy policy = s.Policy;
    policy.Serial = policy.Serial || pass.Serial;
    policy.Progress = nullptr;
    if (s.Policy.Progress && pass.Later) // an earlier pass reported the whole run: stay at its end
      policy.Progress = [progress = s.Policy.Progress](double) { return progress(1.0); };
    serial = std::make_unique<BlockRunner>(std::move(policy), schedule.Size());
    runner = serial.get();
  }
  struct Restore
  {
    Internal& S;
    ~Restore() { this->S.Current = this->S.Runner.get(); }
  } restore{ s };
  s.Current = runner;
  const int attempts = pass.Attempts > 0 ? pass.Attempts : s.Attempts;
  BlockRunner::Hooks hooks;
  hooks.Run = [&](unsigned worker, std::size_t i)
  {
    if (client.Enter)
      client.Enter(worker, i);
    return runner->Attempts(worker, attempts,
      [&](int attempt, std::int64_t& assignments)
      {
        Random rng = Random::Derived(
          s.Seed, schedule.Keys[i], static_cast<std::uint64_t>(attempt + pass.AttemptOffset));
        return client.Attempt(worker, i, attempt, rng, assignments);
      });
  };
  hooks.Finish = [&](std::size_t i, const BlockOutcome& out)
  {
    if (!out.Solved())
    {
      BlockFailure f;
      f.Block = static_cast<std::int64_t>(schedule.Keys[i]);
      f.Attempts = out.Attempts;
      if (client.Describe)
        client.Describe(i, out, f);
      stats.Failures.push_back(f);
    }
    if (client.After)
      client.After(i, out);
  };
  hooks.Pack = client.Pack;
  hooks.Unpack = client.Unpack;
  return runner->Run(schedule.Phases, hooks, stats);
}

bool BlockDriver::End(SynthesisStatus& status, std::string& message, SynthesisStatistics& stats,
  bool wholeModel, const std::function<std::string(const BlockFailure&)>& failure) const
{
  stats.Seconds = this->Seconds();
  if (status == SynthesisStatus::Cancelled)
  {
    message = "cancelled";
    return false;
  }
  if (wholeModel && stats.BlocksFailed > 0 && !stats.Failures.empty())
  {
    // Algorithm 3.1 / 4.1 failed: report it, never return the partial model.
    status = SynthesisStatus::Failed;
    message = failure(stats.Failures.front());
    return false;
  }
  return true;
}

std::string WholeModelFailure(
  const std::string& what, int attempts, const std::string& where, const std::string& advice)
{
  return what + " failed " +
    (attempts == 1 ? std::string("its only attempt")
                   : "in all " + std::to_string(attempts) + " attempts") +
    "; in the last, " + where + ". " + advice;
}

} // namespace msynth
