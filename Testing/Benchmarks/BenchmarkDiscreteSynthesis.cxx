// SPDX-License-Identifier: BSD-3-Clause
#include "BenchmarkFixtures.h"

#include "Discrete/DiscreteSynthesis.h"
#include "Discrete/OverlappingModel.h"
#include "Discrete/VoxelSurface.h"
#include "Formats/Tileset.h"

#include <algorithm>
#include <map>
#include <sstream>
#include <vector>

#include <benchmark/benchmark.h>

namespace
{
const msynth::AdjacencyRules& CityRules()
{
  static const msynth::AdjacencyRules rules = msynth::AdjacencyRules::FromExample(
    msynth::ExampleAnalysis::FromExample(msynth_bench::City100()));
  return rules;
}

void RunSynthesis(benchmark::State& state, const msynth::SynthesisOptions& options)
{
  const auto& rules = CityRules();
  std::int64_t failed = 0, runs = 0;
  for (auto _ : state)
  {
    const auto result = msynth::Synthesize(rules, options);
    failed += !result.Succeeded();
    ++runs;
    benchmark::DoNotOptimize(result.Model.Data().data());
  }
  const double sites = static_cast<double>(options.Size[0] * options.Size[1] * options.Size[2]);
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * sites));
  state.counters["labels"] = rules.NumberOfLabels();
  state.counters["failed_runs"] = static_cast<double>(failed) / static_cast<double>(runs);
  state.counters["ns_per_site"] =
    benchmark::Counter(sites * static_cast<double>(state.iterations()),
      benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}
} // namespace

// Target: ~100 labels, 40×40×10, whole model, under 100 ms.
static void BM_SynthesizeWhole40x40x10(benchmark::State& state)
{
  msynth::SynthesisOptions o;
  o.Size = { { 40, 40, 10 } };
  o.AttemptsPerBlock = 1;
  o.Order = static_cast<msynth::SiteOrder>(state.range(0));
  RunSynthesis(state, o);
}
BENCHMARK(BM_SynthesizeWhole40x40x10)->Arg(0)->Arg(2)->Unit(benchmark::kMillisecond);

// Targets: 100×100×10 with 20×20 blocks under 1 s; sites from 10^4 to 10^7 at a flat
// time per site (n × n × 10 with 20 × 20 × 10 blocks).
// Second argument: threads (the model is the same for any count).
static void BM_SynthesizeBlocks(benchmark::State& state)
{
  msynth::SynthesisOptions o;
  const std::int64_t n = state.range(0);
  o.Size = { { n, n, 10 } };
  o.BlockSize = { { 20, 20, 10 } };
  o.Threads = static_cast<int>(state.range(1));
  RunSynthesis(state, o);
}
BENCHMARK(BM_SynthesizeBlocks)
  ->Args({ 32, 1 })
  ->Args({ 100, 1 })
  ->Args({ 100, 2 })
  ->Args({ 316, 1 })
  ->Args({ 316, 2 })
  ->Unit(benchmark::kMillisecond);

// The cost of label counts (SynthesisOptions::Counts): the runs above (first argument: n, 0 for
// the whole 40 × 40 × 10 model) with the three commonest labels of the same run without counts
// held to 90 % to 105 % of their sites there (second argument 1: 50 % to 90 %, which the
// commonest label, mostly decided by propagation, cannot meet), and one rarer label to 100 % to
// 400 % (150 % to 400 %); second argument 2: each of the four to 0 to 400 %, always met (the
// bookkeeping's cost alone). failed_runs tells whether the counts were met.
static void BM_SynthesizeCounts(benchmark::State& state)
{
  msynth::SynthesisOptions o;
  const std::int64_t n = state.range(0);
  o.Size = n > 0 ? std::array<std::int64_t, 3>{ { n, n, 10 } }
                 : std::array<std::int64_t, 3>{ { 40, 40, 10 } };
  o.BlockSize = n > 0 ? std::array<std::int64_t, 3>{ { 20, 20, 10 } }
                      : std::array<std::int64_t, 3>{ { 0, 0, 0 } };
  o.Threads = 1;
  const msynth::LabelGrid plain = msynth::Synthesize(CityRules(), o).Model;
  std::map<msynth::Label, std::int64_t> sites;
  for (msynth::Label v : plain.Data())
    ++sites[v];
  std::vector<std::pair<std::int64_t, msynth::Label>> order;
  for (const auto& [v, c] : sites)
    order.emplace_back(c, v);
  std::sort(order.rbegin(), order.rend());
  for (std::size_t i = 0; i < 4 && i < order.size(); ++i)
  {
    msynth::LabelCount c;
    const std::size_t at = i < 3 ? i : order.size() / 4; // a label of the upper middle
    c.Values = { order[at].second };
    c.Name = std::to_string(order[at].second);
    const std::int64_t had = order[at].first;
    const bool hard = state.range(1) == 1, wide = state.range(1) == 2;
    c.Minimum = wide ? 0 : (i < 3 ? had * (hard ? 50 : 90) / 100 : had * (hard ? 150 : 100) / 100);
    c.Maximum = wide ? had * 4 : (i < 3 ? had * (hard ? 90 : 105) / 100 : had * 4);
    o.Counts.push_back(c);
  }
  state.counters["counts"] = static_cast<double>(o.Counts.size());
  RunSynthesis(state, o);
}
BENCHMARK(BM_SynthesizeCounts)
  ->Args({ 0, 0 })
  ->Args({ 100, 0 })
  ->Args({ 0, 1 })
  ->Args({ 100, 1 })
  ->Args({ 0, 2 })
  ->Args({ 100, 2 })
  ->Iterations(1)
  ->Unit(benchmark::kMillisecond);
// 10^7 sites: run explicitly (--benchmark_filter=BM_SynthesizeBlocksLarge), about a minute.
static void BM_SynthesizeBlocksLarge(benchmark::State& state)
{
  BM_SynthesizeBlocks(state);
}
BENCHMARK(BM_SynthesizeBlocksLarge)
  ->Args({ 1000, 1 })
  ->Args({ 1000, 2 })
  ->Iterations(1)
  ->Unit(benchmark::kMillisecond);

// Resemblance-weighted choice (2007 paper, Eqs. 2-6): each choice scans the example's windows.
static void BM_SynthesizeResemblance(benchmark::State& state)
{
  static const msynth::LabelGrid example = msynth_bench::City100();
  msynth::SynthesisOptions o;
  const std::int64_t n = state.range(0);
  o.Size = { { n, n, 10 } };
  o.BlockSize = { { 20, 20, 10 } };
  o.Choice = msynth::LabelChoice::Resemblance;
  o.Example = &example;
  o.Threads = 1;
  RunSynthesis(state, o);
}
BENCHMARK(BM_SynthesizeResemblance)->Arg(40)->Iterations(1)->Unit(benchmark::kMillisecond);

// 2D tileset at 128 x 128 (target: under 20 ms). A small set of 3 tiles (7 labels:
// empty, a line and a corner in all orientations) until the published sets are bundled.
static void BM_Tileset128(benchmark::State& state)
{
  static const char* const xml = R"(<set>
    <tiles><tile name="empty" symmetry="X"/><tile name="line" symmetry="I"/>
           <tile name="corner" symmetry="L"/></tiles>
    <neighbors>
      <neighbor left="empty" right="empty"/><neighbor left="line 1" right="empty"/>
      <neighbor left="line" right="line"/><neighbor left="line" right="corner 1"/>
      <neighbor left="corner" right="empty"/><neighbor left="corner 1" right="line"/>
      <neighbor left="corner 1" right="corner"/><neighbor left="empty" right="corner"/>
    </neighbors></set>)";
  std::istringstream in(xml);
  const msynth::AdjacencyRules rules = msynth::ReadTileset(in, "bench.xml").Rules();
  msynth::SynthesisOptions o;
  o.Size = { { 128, 128, 1 } };
  o.Order = static_cast<msynth::SiteOrder>(state.range(0));
  std::int64_t failed = 0, runs = 0;
  for (auto _ : state)
  {
    o.Seed = static_cast<std::uint64_t>(runs++);
    const auto r = msynth::Synthesize(rules, o);
    failed += !r.Succeeded();
  }
  state.counters["labels"] = rules.NumberOfLabels();
  state.counters["failed_runs"] = static_cast<double>(failed) / static_cast<double>(runs);
}
BENCHMARK(BM_Tileset128)->Arg(0)->Arg(2)->Unit(benchmark::kMillisecond);

// Symmetry (§3.5.2): 100×100×10 in 20×20×10 blocks, tileable in x and y (range 1: translation
// with period = size) — the seams link distant blocks, so one thread; compare with
// BM_SynthesizeBlocks/100/1.
static void BM_SynthesizeTileable(benchmark::State& state)
{
  msynth::SynthesisOptions o;
  o.Size = { { 100, 100, 10 } };
  o.BlockSize = { { 20, 20, 10 } };
  o.Translate[0].Enabled = o.Translate[1].Enabled = true;
  RunSynthesis(state, o);
}
BENCHMARK(BM_SynthesizeTileable)->Unit(benchmark::kMillisecond);

namespace
{
/// A rooms-like 16 x 16 image sample: walls one pixel thick, rooms, doors (as the bundled
/// Data/Samples/Rooms.png).
msynth::RgbaImage RoomsSample()
{
  static const char* const rows[] = { "WWWWWWWWWWWWWWWW", "W    W         W", "W    W         W",
    "W              W", "W    W         W", "WWWWWW WWWWWWWWW", "W       W      W",
    "W       W      W", "W              W", "W       W      W", "W       W      W",
    "WWWW WWWWWWW WWW", "W         W    W", "W              W", "W         W    W",
    "WWWWWWWWWWWWWWWW" };
  msynth::RgbaImage image;
  image.Width = image.Height = 16;
  for (const char* row : rows)
    for (const char* c = row; *c; ++c)
      for (const int v : { *c == 'W' ? 20 : 235, *c == 'W' ? 20 : 235, 225, 255 })
        image.Pixels.push_back(static_cast<std::uint8_t>(v));
  return image;
}
} // namespace

// Image samples (the overlapping model): patterns and rules of a 16 x 16 sample with all eight
// symmetries (range 0: pattern size N).
static void BM_ImagePatterns(benchmark::State& state)
{
  const msynth::RgbaImage sample = RoomsSample();
  msynth::OverlappingOptions o;
  o.N = static_cast<int>(state.range(0));
  int patterns = 0;
  for (auto _ : state)
  {
    const msynth::PatternSet set = msynth::ExtractPatterns(sample, o, "rooms");
    benchmark::DoNotOptimize(set.Rules());
    patterns = set.NumberOfPatterns();
  }
  state.counters["patterns"] = patterns;
}
BENCHMARK(BM_ImagePatterns)->Arg(2)->Arg(3)->Arg(4)->Unit(benchmark::kMillisecond);

// A 256 x 256 picture from the rooms sample (N = 3, 8 symmetries) in 32 x 32 blocks, minimum
// entropy, frequency-weighted, picture composed; range 0: backtracks per attempt.
static void BM_ImageSample256(benchmark::State& state)
{
  const msynth::PatternSet set =
    msynth::ExtractPatterns(RoomsSample(), msynth::OverlappingOptions(), "rooms");
  const msynth::AdjacencyRules rules = set.Rules();
  const msynth::Periodic bounded{ { false, false } };
  msynth::SynthesisOptions o;
  o.Size = set.SitesFor(256, 256, bounded);
  o.BlockSize = { { 32, 32, 1 } };
  o.Order = msynth::SiteOrder::MinimumEntropy;
  o.Choice = msynth::LabelChoice::Frequency;
  o.Threads = 1;
  o.BacktracksPerAttempt = state.range(0);
  set.Configure(o, bounded);
  std::int64_t failedBlocks = 0, runs = 0;
  for (auto _ : state)
  {
    o.Seed = static_cast<std::uint64_t>(runs++);
    const auto r = msynth::Synthesize(rules, o);
    failedBlocks += r.Statistics.BlocksFailed;
    benchmark::DoNotOptimize(set.Compose(r.Model, bounded));
  }
  state.counters["failed_blocks"] = static_cast<double>(failedBlocks) / static_cast<double>(runs);
}
BENCHMARK(BM_ImageSample256)->Arg(0)->Arg(1000)->Unit(benchmark::kMillisecond);

// The voxel surface of a synthesized model: the Geometry output of the solvers and the reader
// (what a viewer shows) and `mesh.vtp`. Target: well under the synthesis of the same model.
static void BM_VoxelSurface(benchmark::State& state)
{
  msynth::SynthesisOptions options;
  const std::int64_t n = state.range(0);
  options.Size = { n, n, 10 };
  options.BlockSize = { 20, 20, 10 };
  options.Seed = 1;
  const msynth::LabelGrid model = msynth::Synthesize(CityRules(), options).Model;
  std::size_t quads = 0;
  for (auto _ : state)
  {
    const msynth::VoxelSurface surface =
      msynth::ExtractVoxelSurface(model, 0, { { 0, 0, 0 } }, { { 1, 1, 1 } });
    quads = surface.Quads.size();
    benchmark::DoNotOptimize(surface.Quads.data());
  }
  state.SetItemsProcessed(state.iterations() * n * n * 10);
  state.counters["quads"] = static_cast<double>(quads);
}
BENCHMARK(BM_VoxelSurface)->Arg(100)->Arg(316)->Unit(benchmark::kMillisecond);
