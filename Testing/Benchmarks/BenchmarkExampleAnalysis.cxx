// SPDX-License-Identifier: BSD-3-Clause
#include "BenchmarkFixtures.h"

#include "Discrete/ExampleAnalysis.h"

#include <benchmark/benchmark.h>

// Eq. 3.2 over an n × n × n/2 example.
static void BM_ExampleAnalysis(benchmark::State& state)
{
  const std::int64_t n = state.range(0);
  const msynth::LabelGrid example = msynth_bench::City(n, n / 2);
  for (auto _ : state)
  {
    auto analysis = msynth::ExampleAnalysis::FromExample(example);
    benchmark::DoNotOptimize(analysis.NumberOfLabels());
  }
  state.SetItemsProcessed(state.iterations() * example.NumberOfSites());
  state.counters["sites"] = static_cast<double>(example.NumberOfSites());
}
BENCHMARK(BM_ExampleAnalysis)->Arg(32)->Arg(64)->Arg(128)->Unit(benchmark::kMillisecond);
