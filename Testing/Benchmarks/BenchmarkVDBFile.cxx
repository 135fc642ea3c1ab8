// SPDX-License-Identifier: BSD-3-Clause
#include "BenchmarkFixtures.h"

#include "VDB/VDBFile.h"

#include <benchmark/benchmark.h>

#include <array>
#include <cmath>
#include <vector>

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

namespace
{
/// A closed UV sphere of radius 1 with @p n × 2n quads split into triangles (about 4n²
/// triangles; n = 158 gives 99,540), outward.
void Sphere(int n, std::vector<std::array<double, 3>>& points,
  std::vector<std::vector<std::int32_t>>& triangles)
{
  const double pi = 3.14159265358979323846;
  points.push_back({ 0, 0, -1 });
  for (int i = 1; i < n; ++i)
  {
    const double phi = pi * i / n - pi / 2;
    for (int j = 0; j < 2 * n; ++j)
    {
      const double theta = pi * j / n;
      points.push_back(
        { std::cos(phi) * std::cos(theta), std::cos(phi) * std::sin(theta), std::sin(phi) });
    }
  }
  points.push_back({ 0, 0, 1 });
  const auto ring = [n](int i, int j) { return 1 + (i - 1) * 2 * n + (j % (2 * n)); };
  const int top = static_cast<int>(points.size()) - 1;
  for (int j = 0; j < 2 * n; ++j)
  {
    triangles.push_back({ 0, ring(1, j + 1), ring(1, j) });
    triangles.push_back({ top, ring(n - 1, j), ring(n - 1, j + 1) });
    for (int i = 1; i + 1 < n; ++i)
    {
      triangles.push_back({ ring(i, j), ring(i, j + 1), ring(i + 1, j + 1) });
      triangles.push_back({ ring(i, j), ring(i + 1, j + 1), ring(i + 1, j) });
    }
  }
}
} // namespace

// Target: a 100,000-triangle mesh to a narrow-band level set at 512³ (voxel = the
// mesh's extent / 512) in under 10 s, written to a .vdb file with its fog volume.
static void BM_VDBMeshLevelSet(benchmark::State& state)
{
  std::vector<std::array<double, 3>> points;
  std::vector<std::vector<std::int32_t>> triangles;
  Sphere(158, points, triangles);
  const std::string path = std::string(MSYNTH_TEST_TMP) + "/bench-levelset.vdb";
  msynth::vdb::MeshGridView mesh;
  mesh.Name = "surface";
  mesh.Points = &points;
  mesh.Polygons = &triangles;
  mesh.VoxelSize = 2.0 / static_cast<double>(state.range(0));
  mesh.HalfWidth = 3;
  mesh.FogName = state.range(1) ? "density" : "";
  for (auto _ : state)
  {
    msynth::vdb::WriteFile(path, {}, { mesh }, {});
  }
  state.counters["triangles"] = static_cast<double>(triangles.size());
  state.counters["resolution"] = static_cast<double>(state.range(0));
}
BENCHMARK(BM_VDBMeshLevelSet)
  ->Args({ 64, 1 })
  ->Args({ 512, 0 })
  ->Args({ 512, 1 })
  ->Unit(benchmark::kMillisecond);
