// SPDX-License-Identifier: BSD-3-Clause
// Continuous example analysis (target: a 1,000-polygon example with 10 plane families
// in under 1 s).
#include "Continuous/PolyhedralAnalysis.h"

#include <benchmark/benchmark.h>

#include <cmath>

namespace
{

/// @p count separate prisms over a regular 18-gon (9 side families + the horizontal one = 10
/// families, 20 faces each), laid out on a grid; with @p touching they stand on a slab of a
/// second object type, so edges are split where objects meet.
msynth::PolyhedralExample Prisms(int count, bool touching)
{
  msynth::PolyhedralExample e;
  e.Source = "benchmark";
  const int sides = 18;
  const int columns = static_cast<int>(std::ceil(std::sqrt(double(count))));
  for (int k = 0; k < count; ++k)
  {
    const double cx = 3.0 * (k % columns), cy = 3.0 * (k / columns);
    const int base = static_cast<int>(e.Points.size());
    for (int z = 0; z < 2; ++z)
    {
      for (int i = 0; i < sides; ++i)
      {
        const double a = 2 * M_PI * i / sides;
        e.Points.push_back({ cx + std::cos(a), cy + std::sin(a), z * 2.0 });
      }
    }
    std::vector<int> bottom, top;
    for (int i = 0; i < sides; ++i)
    {
      bottom.push_back(base + sides - 1 - i);
      top.push_back(base + sides + i);
      const int j = (i + 1) % sides;
      e.Faces.push_back({ base + i, base + j, base + sides + j, base + sides + i });
      e.FaceObject.push_back(k);
    }
    e.Faces.push_back(bottom);
    e.FaceObject.push_back(k);
    e.Faces.push_back(top);
    e.FaceObject.push_back(k);
    e.ObjectTypes.push_back(1);
    e.ObjectNames.push_back("prism " + std::to_string(k));
  }
  if (touching)
  {
    const double w = 3.0 * columns;
    const int b = static_cast<int>(e.Points.size());
    for (double z : { -1.0, 0.0 })
    {
      e.Points.push_back({ -2, -2, z });
      e.Points.push_back({ w, -2, z });
      e.Points.push_back({ w, w, z });
      e.Points.push_back({ -2, w, z });
    }
    const int o = count;
    for (const std::vector<int>& f :
      std::vector<std::vector<int>>{ { b + 3, b + 2, b + 1, b + 0 }, { b + 4, b + 5, b + 6, b + 7 },
        { b + 0, b + 1, b + 5, b + 4 }, { b + 1, b + 2, b + 6, b + 5 },
        { b + 2, b + 3, b + 7, b + 6 }, { b + 3, b + 0, b + 4, b + 7 } })
    {
      e.Faces.push_back(f);
      e.FaceObject.push_back(o);
    }
    e.ObjectTypes.push_back(2);
    e.ObjectNames.push_back("slab");
  }
  msynth::ValidateExample(e);
  return e;
}

} // namespace

static void BM_PolyhedralAnalysis(benchmark::State& state)
{
  const auto example = Prisms(static_cast<int>(state.range(0)), state.range(1) != 0);
  int labels = 0;
  int families = 0;
  for (auto _ : state)
  {
    const auto analysis = msynth::PolyhedralAnalysis::Analyze(example);
    labels = analysis.NumberOfLabels();
    families = analysis.Families().Size();
  }
  state.counters["polygons"] = static_cast<double>(example.Faces.size());
  state.counters["families"] = families;
  state.counters["labels"] = labels;
}
// 2 × 20 = 40 polygons (smoke size), then 50 prisms = 1,000 polygons, alone and on a slab.
BENCHMARK(BM_PolyhedralAnalysis)
  ->Args({ 2, 0 })
  ->Args({ 50, 0 })
  ->Args({ 50, 1 })
  ->Unit(benchmark::kMillisecond);

static void BM_ValidateExample(benchmark::State& state)
{
  auto example = Prisms(static_cast<int>(state.range(0)), false);
  for (auto _ : state)
  {
    msynth::ValidateExample(example);
  }
  state.counters["polygons"] = static_cast<double>(example.Faces.size());
}
BENCHMARK(BM_ValidateExample)->Arg(50)->Unit(benchmark::kMillisecond);
