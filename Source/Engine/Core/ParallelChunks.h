// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/**
 * @file ParallelChunks.h
 * @brief Independent pieces of work on threads: chunks 0..N-1 taken in turn by up to @p threads
 * threads. Each chunk writes only its own results, so callers that combine them in chunk order
 * get the same outcome for any thread count. The first failing chunk's exception (lowest index,
 * as a serial run would meet it) is rethrown.
 */
#include <algorithm>
#include <atomic>
#include <cstddef>
#include <exception>
#include <system_error>
#include <thread>
#include <vector>

namespace msynth
{

/// Runs @p work(chunk) for every chunk in [0, @p chunks) on @p threads threads (0: one per core).
template <class Work>
void RunChunks(std::size_t chunks, unsigned threads, Work&& work)
{
  if (threads == 0)
    threads = std::max(1u, std::thread::hardware_concurrency());
  std::vector<std::exception_ptr> failures(chunks);
  std::atomic<std::size_t> next{ 0 };
  std::atomic<std::size_t> firstFailure{ chunks };
  const auto run = [&]
  {
    for (std::size_t c = next++; c < chunks; c = next++)
    {
      if (c > firstFailure.load())
        continue; // a serial run would have stopped before this chunk
      try
      {
        work(c);
      }
      catch (...)
      {
        failures[c] = std::current_exception();
        std::size_t seen = firstFailure.load();
        while (c < seen && !firstFailure.compare_exchange_weak(seen, c))
        {
        }
      }
    }
  };
  std::vector<std::thread> pool;
  const std::size_t extra = std::min<std::size_t>(threads, chunks) - (chunks > 0 ? 1 : 0);
  for (std::size_t t = 0; t < extra; ++t)
  {
    try
    {
      pool.emplace_back(run);
    }
    catch (const std::system_error&)
    {
      break; // fewer threads: the same outcome, later
    }
  }
  run();
  for (auto& t : pool)
    t.join();
  if (firstFailure.load() < chunks)
    std::rethrow_exception(failures[firstFailure.load()]);
}

} // namespace msynth
