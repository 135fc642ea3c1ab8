// SPDX-License-Identifier: BSD-3-Clause
// Time-varying synthesis (§3.5.4): the city example's z layers read as frames (a 2D example
// over time), synthesized to N × N sites × F frames in 16 × 16 × 8-frame blocks.
#include "BenchmarkFixtures.h"

#include "Discrete/TimeVarying.h"

#include <benchmark/benchmark.h>

static void BM_TimeVarying(benchmark::State& state)
{
  const msynth::LabelGrid city = msynth_bench::City100();
  const auto& d = city.Dimensions();
  msynth::TimeVaryingGrid example;
  for (std::int64_t z = 0; z < d[2]; ++z)
  {
    msynth::LabelGrid frame(d[0], d[1], 1);
    for (std::int64_t y = 0; y < d[1]; ++y)
      for (std::int64_t x = 0; x < d[0]; ++x)
        frame.Set(x, y, 0, city.At(x, y, z));
    example.Frames.push_back(frame);
  }
  const auto rules = msynth::TimeVaryingRules::FromExample(example);
  msynth::TimeVaryingOptions o;
  const std::int64_t n = state.range(0), frames = state.range(1);
  o.Size = { { n, n, 1, frames } };
  o.BlockSize = { { 16, 16, 1, 8 } };
  std::int64_t failedBlocks = 0;
  for (auto _ : state)
  {
    const auto r = msynth::SynthesizeTimeVarying(rules, o);
    failedBlocks += r.Statistics.BlocksFailed;
    benchmark::DoNotOptimize(r.Model.Frames.data());
  }
  const double sites = static_cast<double>(n * n * frames);
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * sites));
  state.counters["labels"] = rules.NumberOfLabels();
  state.counters["failed_blocks"] =
    static_cast<double>(failedBlocks) / static_cast<double>(state.iterations());
  state.counters["ns_per_site"] =
    benchmark::Counter(sites * static_cast<double>(state.iterations()),
      benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}
BENCHMARK(BM_TimeVarying)->Args({ 64, 32 })->Args({ 128, 64 })->Unit(benchmark::kMillisecond);
