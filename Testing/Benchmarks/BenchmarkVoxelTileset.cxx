// SPDX-License-Identifier: BSD-3-Clause
// Per-site speed of a voxel tileset (the bundled Pipes: 4 tiles, 85 images under the cube's 48
// symmetries) against the label-grid solver on an example with the same labels: a Pipes model
// read back as a label grid, whose rules are the pairs it shows (fewer than the tileset allows).
#include "Discrete/DiscreteSynthesis.h"
#include "Discrete/ExampleAnalysis.h"
#include "Formats/Tileset.h"

#include <benchmark/benchmark.h>

namespace
{
const msynth::AdjacencyRules& PipesRules()
{
  static const msynth::AdjacencyRules rules =
    msynth::ReadTilesetFile(std::string(MSYNTH_DATA) + "/Tilesets/Pipes.xml").Rules();
  return rules;
}

/// A 24 x 24 x 12 Pipes model (every one of the 85 labels occurs) as a label-grid example.
const msynth::AdjacencyRules& PipesExampleRules()
{
  static const msynth::AdjacencyRules rules = []()
  {
    msynth::SynthesisOptions o;
    o.Size = { { 24, 24, 12 } };
    o.BlockSize = { { 12, 12, 12 } };
    o.Seed = 1;
    const msynth::SynthesisResult r = msynth::Synthesize(PipesRules(), o);
    return msynth::AdjacencyRules::FromExample(msynth::ExampleAnalysis::FromExample(r.Model));
  }();
  return rules;
}

void Run(benchmark::State& state, const msynth::AdjacencyRules& rules)
{
  const std::int64_t n = state.range(0);
  msynth::SynthesisOptions o;
  o.Size = { { n, n, n / 2 } };
  o.BlockSize = { { 16, 16, 16 } };
  o.Threads = 1;
  std::int64_t failed = 0, runs = 0;
  for (auto _ : state)
  {
    o.Seed = static_cast<std::uint64_t>(runs);
    const auto result = msynth::Synthesize(rules, o);
    failed += result.Statistics.BlocksFailed > 0 || !result.Succeeded();
    ++runs;
    benchmark::DoNotOptimize(result.Model.Data().data());
  }
  const double sites = static_cast<double>(o.Size[0] * o.Size[1] * o.Size[2]);
  state.counters["labels"] = rules.NumberOfLabels();
  state.counters["failed_runs"] = static_cast<double>(failed) / static_cast<double>(runs);
  state.counters["ns_per_site"] =
    benchmark::Counter(sites * static_cast<double>(state.iterations()),
      benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}
} // namespace

static void BM_VoxelTilesetPipes(benchmark::State& state)
{
  Run(state, PipesRules());
}
BENCHMARK(BM_VoxelTilesetPipes)->Arg(16)->Arg(32)->Unit(benchmark::kMillisecond);

static void BM_VoxelTilesetSameLabelsAsGrid(benchmark::State& state)
{
  Run(state, PipesExampleRules());
}
BENCHMARK(BM_VoxelTilesetSameLabelsAsGrid)->Arg(16)->Arg(32)->Unit(benchmark::kMillisecond);
