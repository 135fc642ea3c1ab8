// SPDX-License-Identifier: BSD-3-Clause
#include "BenchmarkFixtures.h"

#include "msynth/VDBFile.h"

#include <benchmark/benchmark.h>

namespace
{
msynth::vdb::DenseGridView LabelView(const msynth::LabelGrid& g)
{
  msynth::vdb::DenseGridView view;
  view.Header.Name = "Label";
  view.Header.Type = msynth::vdb::ValueType::Int32;
  view.Header.Dims = g.Dimensions();
  view.Values = g.Data().data();
  return view;
}
} // namespace

// An n³ label volume (the empty label as inactive background) written to a .vdb file.
static void BM_VDBWriteLabels(benchmark::State& state)
{
  const std::int64_t n = state.range(0);
  const msynth::LabelGrid labels = msynth_bench::City(n, n);
  const std::string path = std::string(MSYNTH_TEST_TMP) + "/bench-labels.vdb";
  for (auto _ : state)
  {
    msynth::vdb::WriteFile(path, { LabelView(labels) }, {});
  }
  state.SetItemsProcessed(state.iterations() * labels.NumberOfSites());
}
BENCHMARK(BM_VDBWriteLabels)->Arg(32)->Arg(128)->Arg(256)->Unit(benchmark::kMillisecond);

// Reading the same volume back into a dense grid.
static void BM_VDBReadLabels(benchmark::State& state)
{
  const std::int64_t n = state.range(0);
  const msynth::LabelGrid labels = msynth_bench::City(n, n);
  const std::string path = std::string(MSYNTH_TEST_TMP) + "/bench-read.vdb";
  msynth::vdb::WriteFile(path, { LabelView(labels) }, {});
  for (auto _ : state)
  {
    auto contents = msynth::vdb::ReadFile(path);
    benchmark::DoNotOptimize(contents.Grids.front().Ints.data());
  }
  state.SetItemsProcessed(state.iterations() * labels.NumberOfSites());
}
BENCHMARK(BM_VDBReadLabels)->Arg(32)->Arg(128)->Arg(256)->Unit(benchmark::kMillisecond);
