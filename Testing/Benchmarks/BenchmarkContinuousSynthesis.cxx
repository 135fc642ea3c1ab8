// SPDX-License-Identifier: BSD-3-Clause
// Continuous model synthesis (targets): a ~30-polygon example giving ~10,000 output
// polygons in under 5 s, and a plane arrangement of 10^6 vertices in under 10 s (time and
// memory against the number of vertices, §4.5.7).
#include "Continuous/ContinuousMesh.h"
#include "Continuous/ContinuousSynthesis.h"

#include <benchmark/benchmark.h>

#include <map>
#include <string>
#include <sys/resource.h>

namespace
{

struct Example
{
  msynth::PolyhedralExample Polyhedra;
  msynth::PolyhedralAnalysis Analysis;
};

const Example& Load(const std::string& name)
{
  static std::map<std::string, Example> cache;
  auto it = cache.find(name);
  if (it == cache.end())
  {
    Example e;
    e.Polyhedra = msynth::ReadOBJExample(std::string(MSYNTH_DATA) + "/Continuous/" + name);
    msynth::ValidateExample(e.Polyhedra);
    e.Analysis = msynth::PolyhedralAnalysis::Analyze(e.Polyhedra);
    it = cache.emplace(name, std::move(e)).first;
  }
  return it->second;
}

double PeakMegabytes()
{
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return static_cast<double>(usage.ru_maxrss) / 1024.0;
}

/// The whole chain after reading: arrangement, labels (blocks of 4 spacings), mesh. The
/// example is Data/Continuous/cottage.obj (23 polygons, 4 object types, 116 labels); the box
/// is S × S × 6 example units.
void BM_ContinuousChain(benchmark::State& state)
{
  const Example& e = Load("cottage.obj");
  const double s = static_cast<double>(state.range(0));
  std::int64_t vertices = 0;
  std::size_t polygons = 0;
  std::uint64_t seed = 1;
  for (auto _ : state)
  {
    const auto p =
      msynth::DefaultArrangementParameters(e.Polyhedra, e.Analysis, { s, s, 6 }, 0, {});
    const msynth::PlaneArrangement arrangement(e.Analysis.Families(), p);
    msynth::ContinuousSynthesisOptions options;
    options.Seed = seed++;
    options.BlockSize = 4;
    const auto result = msynth::SynthesizeContinuous(e.Analysis, arrangement, options);
    const auto mesh = msynth::ExtractMesh(e.Analysis, arrangement, result.Labels);
    vertices = arrangement.NumberOfVertices();
    polygons = mesh.Polygons.size();
    benchmark::DoNotOptimize(mesh.Polygons.data());
  }
  state.counters["example_polygons"] = static_cast<double>(e.Polyhedra.Faces.size());
  state.counters["labels"] = e.Analysis.NumberOfLabels();
  state.counters["vertices"] = static_cast<double>(vertices);
  state.counters["polygons"] = static_cast<double>(polygons);
}
BENCHMARK(BM_ContinuousChain)->Arg(4)->Arg(6)->Arg(12)->Unit(benchmark::kMillisecond);

/// The TVCG constraints on the house (24 × 24 × 10, blocks of 4): arg 0 none (proportions off,
/// the dissertation's draw), 1 grounded, 2 grounded + walls one storey, 3 the same mirrored.
void BM_ContinuousConstraints(benchmark::State& state)
{
  const Example& e = Load("house.obj");
  const auto p =
    msynth::DefaultArrangementParameters(e.Polyhedra, e.Analysis, { 24, 24, 10 }, 0, {});
  const msynth::PlaneArrangement arrangement(e.Analysis.Families(), p);
  msynth::ContinuousSynthesisOptions options;
  options.BlockSize = 4;
  options.Constraints.KeepProportions = state.range(0) > 0;
  options.Constraints.Grounded = state.range(0) >= 1;
  if (state.range(0) >= 2)
    options.Constraints.Thickness.push_back(
      { 1, msynth::FamilyAlongAxis(e.Analysis.Families(), 2), 1, {} });
  options.MirrorAxes = state.range(0) >= 3 ? 1 : 0;
  std::uint64_t seed = 1;
  std::int64_t parts = 0;
  for (auto _ : state)
  {
    options.Seed = seed++;
    const auto r = msynth::SynthesizeContinuous(e.Analysis, arrangement, options);
    if (!r.Succeeded())
      state.SkipWithError(r.Message.c_str());
    parts = msynth::MeasureArrangement(e.Analysis, arrangement, r.Labels).Components;
  }
  state.counters["vertices"] = static_cast<double>(arrangement.NumberOfVertices());
  state.counters["parts"] = static_cast<double>(parts);
}
BENCHMARK(BM_ContinuousConstraints)->DenseRange(0, 3)->Unit(benchmark::kMillisecond);

/// Continuous blocks on threads (issue 29 item 3): the house at 48 × 48 × 10 in blocks of 4
/// spacings, the solver alone (arrangement built once), with range(0) threads and range(1) = 1
/// grounded. Wall time (UseRealTime): the speed-up is the ratio of the two thread counts.
/// The house at 48 × 48 × 10 (issue 29's speed-up case): its arrangement, and the options of
/// the runs on it (blocks of 4 spacings, seed 5).
struct HouseRun
{
  const Example& E = Load("house.obj");
  const msynth::PlaneArrangement Arrangement{ E.Analysis.Families(),
    msynth::DefaultArrangementParameters(E.Polyhedra, E.Analysis, { 48, 48, 10 }, 0, {}) };
  msynth::ContinuousSynthesisOptions Options = []
  {
    msynth::ContinuousSynthesisOptions o;
    o.BlockSize = 4;
    o.Seed = 5;
    return o;
  }();
};

void BM_ContinuousThreads(benchmark::State& state)
{
  HouseRun house;
  const Example& e = house.E;
  const msynth::PlaneArrangement& arrangement = house.Arrangement;
  msynth::ContinuousSynthesisOptions& options = house.Options;
  options.Threads = static_cast<int>(state.range(0));
  options.Constraints.Grounded = state.range(1) == 1;
  for (auto _ : state)
  {
    const auto r = msynth::SynthesizeContinuous(e.Analysis, arrangement, options);
    if (!r.Succeeded())
      state.SkipWithError(r.Message.c_str());
    benchmark::DoNotOptimize(r.Labels.data());
  }
  state.counters["vertices"] = static_cast<double>(arrangement.NumberOfVertices());
}
BENCHMARK(BM_ContinuousThreads)
  ->Args({ 1, 0 })
  ->Args({ 2, 0 })
  ->Args({ 1, 1 })
  ->Args({ 2, 1 })
  ->UseRealTime()
  ->Unit(benchmark::kMillisecond);

/// The mesh of the house at 48 × 48 × 10 (plain, seed 5) on range(0) threads: the solver's
/// proportion step and model.vtp both extract it.
void BM_ExtractMesh(benchmark::State& state)
{
  const HouseRun house;
  const Example& e = house.E;
  const msynth::PlaneArrangement& arrangement = house.Arrangement;
  const auto r = msynth::SynthesizeContinuous(e.Analysis, arrangement, house.Options);
  std::size_t polygons = 0;
  for (auto _ : state)
  {
    const auto mesh =
      msynth::ExtractMesh(e.Analysis, arrangement, r.Labels, static_cast<unsigned>(state.range(0)));
    polygons = mesh.Polygons.size();
    benchmark::DoNotOptimize(mesh.Polygons.data());
  }
  state.counters["polygons"] = static_cast<double>(polygons);
}
BENCHMARK(BM_ExtractMesh)->Arg(1)->Arg(2)->UseRealTime()->Unit(benchmark::kMillisecond);

/// The independent check of a model (the example analysis run on the output).
void BM_ContinuousCheck(benchmark::State& state)
{
  const Example& e = Load("cottage.obj");
  const double s = static_cast<double>(state.range(0));
  const auto p = msynth::DefaultArrangementParameters(e.Polyhedra, e.Analysis, { s, s, 6 }, 0, {});
  const msynth::PlaneArrangement arrangement(e.Analysis.Families(), p);
  msynth::ContinuousSynthesisOptions options;
  options.BlockSize = 4;
  const auto result = msynth::SynthesizeContinuous(e.Analysis, arrangement, options);
  const auto mesh = msynth::ExtractMesh(e.Analysis, arrangement, result.Labels);
  for (auto _ : state)
  {
    const auto report = msynth::CheckContinuousModel(e.Analysis, mesh, e.Polyhedra.TypeNames);
    if (!report.Valid)
    {
      state.SkipWithError(report.Problem.c_str());
    }
  }
  state.counters["polygons"] = static_cast<double>(mesh.Polygons.size());
}
BENCHMARK(BM_ContinuousCheck)->Arg(6)->Unit(benchmark::kMillisecond);

/// Building the arrangement alone: the cube's 3 axis families (a grid of (N+1)^3 vertices), or
/// with range(1) = 1 the house's 5 families (two sloped), whose triples meet off the grid, or
/// with range(1) = 2 the town's 7 families (Data/Continuous/town.obj, 474 polygons; N x N x 8 at
/// its default spacings), on range(2) threads (the arrangement is the same for any count).
void BM_PlaneArrangement(benchmark::State& state)
{
  const int model = static_cast<int>(state.range(1));
  const Example& e = Load(model == 0 ? "cube.obj" : model == 1 ? "house.obj" : "town.obj");
  const double n = static_cast<double>(state.range(0));
  auto p =
    msynth::DefaultArrangementParameters(e.Polyhedra, e.Analysis, { n, n, model == 2 ? 8.0 : n },
      model == 1     ? 0.5
        : model == 0 ? 1.0
                     : 0.0,
      {});
  p.Threads = static_cast<unsigned>(state.range(2));
  std::int64_t vertices = 0, edges = 0;
  std::size_t bytes = 0;
  for (auto _ : state)
  {
    const msynth::PlaneArrangement arrangement(e.Analysis.Families(), p);
    vertices = arrangement.NumberOfVertices();
    edges = arrangement.NumberOfEdges();
    bytes = arrangement.MemoryBytes();
  }
  state.counters["vertices"] = static_cast<double>(vertices);
  state.counters["edges"] = static_cast<double>(edges);
  state.counters["bytes_per_vertex"] =
    static_cast<double>(bytes) / static_cast<double>(std::max<std::int64_t>(vertices, 1));
  state.counters["ns_per_vertex"] = benchmark::Counter(static_cast<double>(vertices),
    benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
  state.counters["peak_MB"] = PeakMegabytes();
}
BENCHMARK(BM_PlaneArrangement)
  ->Args({ 21, 0, 1 })
  ->Args({ 46, 0, 1 })
  ->Args({ 99, 0, 1 })
  ->Args({ 99, 0, 2 })
  ->Args({ 8, 1, 1 })
  ->Args({ 16, 1, 1 })
  ->Args({ 32, 1, 1 })
  ->Args({ 70, 1, 1 })
  ->Args({ 70, 1, 2 })
  ->Args({ 40, 2, 1 })
  ->Args({ 40, 2, 2 })
  ->UseRealTime()
  ->Unit(benchmark::kMillisecond);

} // namespace
