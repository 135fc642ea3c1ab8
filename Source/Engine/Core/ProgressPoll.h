// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/**
 * @file ProgressPoll.h
 * @brief Cancellation inside a block (internal): the solvers call Continue() every so many
 * assignments; it calls the caller's progress callback at most every 100 ms (the filters'
 * abort flag, the command line's progress bar) and says whether to go on.
 */
#include <chrono>
#include <cstdint>
#include <functional>

namespace msynth
{
namespace detail
{

/// The one cadence of every solver's cancel poll: every 1024th step (assignment, move).
constexpr bool PollDue(std::int64_t step)
{
  return (step & 1023) == 0;
}

class ProgressPoll
{
public:
  explicit ProgressPoll(std::function<bool(double)> progress)
    : Progress(std::move(progress))
  {
  }
  /// False when the callback asked to stop; @p fraction is what it is told.
  bool Continue(double fraction)
  {
    if (!this->Progress)
      return true;
    const auto now = std::chrono::steady_clock::now();
    if (now - this->Last < std::chrono::milliseconds(100))
      return true;
    this->Last = now;
    return this->Progress(fraction);
  }

private:
  std::function<bool(double)> Progress;
  std::chrono::steady_clock::time_point Last = std::chrono::steady_clock::now();
};

} // namespace detail
} // namespace msynth
