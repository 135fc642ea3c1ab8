// SPDX-License-Identifier: BSD-3-Clause
// Synthesis at scale (issue 26 §4): the bundled Lines tileset at 10^6, 10^7 and 10^8 sites,
// the whole model and 32 x 32 blocks, with the time per site and the peak memory of the run.
// Not a timed test: the smoke test runs none of these (the smallest takes a second), and the
// figures go to Documentation/performance.md ("Blocks, threads and backtracking at scale").
#include "Discrete/DiscreteSynthesis.h"
#include "Formats/Tileset.h"

#include <cstdint>
#include <fstream>
#include <string>

#include <benchmark/benchmark.h>

namespace
{
const msynth::AdjacencyRules& LinesRules()
{
  static const msynth::AdjacencyRules rules =
    msynth::ReadTilesetFile(std::string(MSYNTH_DATA) + "/Tilesets/Lines.xml").Rules();
  return rules;
}

/// The process's peak resident memory so far (VmHWM), in MiB.
double PeakMiB()
{
  std::ifstream status("/proc/self/status");
  std::string key;
  while (status >> key)
  {
    if (key == "VmHWM:")
    {
      double kib = 0;
      status >> kib;
      return kib / 1024.0;
    }
  }
  return 0;
}

/// Restarts the peak (Linux: writing 5 to clear_refs resets VmHWM to the current size).
void ResetPeak()
{
  std::ofstream("/proc/self/clear_refs") << "5";
}

/// range(0): sites per side (1000, 3163, 10000); range(1): 1 for 32 x 32 blocks, 0 for the whole
/// model (not 32, so that the smoke test's filter "/32" leaves these out).
void BM_LinesAtScale(benchmark::State& state)
{
  const auto& rules = LinesRules();
  msynth::SynthesisOptions o;
  const std::int64_t n = state.range(0);
  o.Size = { { n, n, 1 } };
  if (state.range(1) > 0)
  {
    o.BlockSize = { { 32, 32, 1 } };
  }
  o.Threads = 1;
  o.Seed = 1;
  ResetPeak();
  const double before = PeakMiB();
  std::int64_t failed = 0, backtracks = 0;
  for (auto _ : state)
  {
    const auto result = msynth::Synthesize(rules, o);
    failed += !result.Succeeded();
    backtracks += result.Statistics.Backtracks;
    benchmark::DoNotOptimize(result.Model.Data().data());
  }
  const double sites = static_cast<double>(n * n);
  state.counters["ns_per_site"] =
    benchmark::Counter(sites * static_cast<double>(state.iterations()),
      benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
  state.counters["peak_MiB"] = PeakMiB();
  state.counters["start_MiB"] = before;
  state.counters["failed_runs"] = static_cast<double>(failed);
  state.counters["backtracks_per_site"] =
    static_cast<double>(backtracks) / (sites * static_cast<double>(state.iterations()));
}
} // namespace

BENCHMARK(BM_LinesAtScale)
  ->Args({ 1000, 0 })
  ->Args({ 3163, 0 })
  ->Args({ 10000, 0 })
  ->Args({ 1000, 1 })
  ->Args({ 3163, 1 })
  ->Args({ 10000, 1 })
  ->Iterations(1)
  ->Unit(benchmark::kSecond);
