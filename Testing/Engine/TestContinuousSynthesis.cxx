// SPDX-License-Identifier: BSD-3-Clause
// Continuous model synthesis II (dissertation §4.5): the plane arrangement, the label solver and
// mesh extraction, each output checked by the example analysis run on the output mesh.
#include "Continuous/ConstraintPlan.h"
#include "Continuous/ContinuousMesh.h"
#include "Continuous/ContinuousSynthesis.h"
#include "Continuous/SolverParts.h"
#include "Core/Error.h"

#include "Fixtures.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <map>
#include <set>
#include <string>
#include <thread>

using namespace msynth;

namespace
{

using Loaded = msynth_test::LoadedPolyhedra;
const auto Load = msynth_test::LoadPolyhedra;

struct SynthesisRun
{
  ContinuousSynthesisResult Result;
  ContinuousMesh Mesh;
  ContinuousModelReport Report;
  std::int64_t Vertices = 0;
};

SynthesisRun Synthesize(
  const Loaded& l, const Point3& size, double spacing, std::uint64_t seed, double block)
{
  const ArrangementParameters p =
    DefaultArrangementParameters(l.Example, l.Analysis, size, spacing, {});
  const PlaneArrangement arrangement(l.Analysis.Families(), p);
  ContinuousSynthesisOptions options;
  options.Seed = seed;
  options.BlockSize = block;
  SynthesisRun r;
  r.Vertices = arrangement.NumberOfVertices();
  r.Result = SynthesizeContinuous(l.Analysis, arrangement, options);
  EXPECT_EQ(CheckArrangementLabels(l.Analysis, arrangement, r.Result.Labels), "");
  r.Mesh = ExtractMesh(l.Analysis, arrangement, r.Result.Labels);
  r.Report = CheckContinuousModel(l.Analysis, r.Mesh, l.Example.TypeNames);
  return r;
}

} // namespace

TEST(PlaneArrangement, CubeGivesAGrid)
{
  const Loaded l = Load("cube.obj");
  const ArrangementParameters p =
    DefaultArrangementParameters(l.Example, l.Analysis, { 3, 3, 3 }, 0, {});
  const PlaneArrangement a(l.Analysis.Families(), p);
  EXPECT_EQ(a.NumberOfVertices(), 64);
  EXPECT_EQ(a.NumberOfEdges(), 3 * 16 * 3);
  EXPECT_EQ(a.NumberOfBoundaryEdges(), 6 * 16);
  EXPECT_EQ(a.NumberOfDirections(), 6);
  for (int c = 0; c < 3; ++c)
  {
    EXPECT_NEAR(a.Position(63)[static_cast<std::size_t>(c)], 3.0, 1e-12);
  }
}

TEST(PlaneArrangement, TriangleIn2D)
{
  const Loaded l = Load("triangle2d.obj");
  ASSERT_TRUE(l.Analysis.Planar());
  const ArrangementParameters p =
    DefaultArrangementParameters(l.Example, l.Analysis, { 8, 6, 0 }, 1, {});
  const PlaneArrangement a(l.Analysis.Families(), p);
  EXPECT_GT(a.NumberOfVertices(), 0);
  EXPECT_EQ(a.NumberOfDirections(), 6);
  // Every vertex lies on at least two lines, and neighbours lie on a common line.
  for (std::int64_t v = 0; v < a.NumberOfVertices(); ++v)
  {
    EXPECT_GE(__builtin_popcountll(a.FamilyMask(v)), 2);
    EXPECT_NEAR(a.Position(v)[2], 0.0, 0.0);
  }
}

TEST(PlaneArrangement, FourPlanesThroughAPointGiveOneVertex)
{
  // Normals (1,0,0), (0,1,0), (0,0,1), (1,1,1): planes x+y+z = k pass through grid points.
  const PlaneFamilySet set({ { 1, 0, 0 }, { 0, 1, 0 }, { 0, 0, 1 }, { 1, 1, 1 } });
  ArrangementParameters p;
  p.BoxHigh = { 4, 4, 4 };
  p.Offsets = { 0, 0, 0, 0 };
  p.Spacings = { 1, 1, 1, 1 };
  const PlaneArrangement a(set, p);
  std::set<std::array<double, 3>> unique;
  std::int64_t onFour = 0;
  for (std::int64_t v = 0; v < a.NumberOfVertices(); ++v)
  {
    unique.insert(a.Position(v));
    onFour += a.FamilyMask(v) == 15u;
  }
  EXPECT_EQ(static_cast<std::int64_t>(unique.size()), a.NumberOfVertices());
  EXPECT_EQ(onFour, 125); // every grid point of the 5×5×5 grid is on a diagonal plane
}

TEST(PlaneArrangement, TheSameOnAnyNumberOfThreads)
{
  // The house's sloped families at a size whose vertices and links span many chunks.
  const Loaded l = Load("house.obj");
  ArrangementParameters p =
    DefaultArrangementParameters(l.Example, l.Analysis, { 14, 12, 10 }, 0.25, {});
  p.Threads = 1;
  const PlaneArrangement one(l.Analysis.Families(), p);
  ASSERT_GT(one.NumberOfVertices(), 40000);
  for (unsigned threads : { 2u, 3u })
  {
    p.Threads = threads;
    const PlaneArrangement many(l.Analysis.Families(), p);
    ASSERT_EQ(many.NumberOfVertices(), one.NumberOfVertices());
    EXPECT_EQ(many.NumberOfEdges(), one.NumberOfEdges());
    EXPECT_EQ(many.NumberOfBoundaryEdges(), one.NumberOfBoundaryEdges());
    for (std::int64_t v = 0; v < one.NumberOfVertices(); ++v)
    {
      ASSERT_EQ(many.Position(v), one.Position(v)) << v;
      ASSERT_EQ(many.FamilyMask(v), one.FamilyMask(v)) << v;
      ASSERT_EQ(many.LinksEnd(v) - many.LinksBegin(v), one.LinksEnd(v) - one.LinksBegin(v)) << v;
      for (auto a = many.LinksBegin(v), b = one.LinksBegin(v); a != many.LinksEnd(v); ++a, ++b)
      {
        ASSERT_EQ(a->Vertex, b->Vertex) << v;
        ASSERT_EQ(a->Direction, b->Direction) << v;
      }
    }
  }
  // Every link leads forward along its own direction, whatever built it.
  for (std::int64_t v = 0; v < one.NumberOfVertices(); v += 97)
  {
    for (auto k = one.LinksBegin(v); k != one.LinksEnd(v); ++k)
    {
      if (k->Vertex < 0)
        continue;
      const auto& d = one.Direction(k->Direction);
      const Point3& a = one.Position(v);
      const Point3& b = one.Position(k->Vertex);
      double along = 0, dd = 0;
      for (std::size_t c = 0; c < 3; ++c)
      {
        along += (b[c] - a[c]) * static_cast<double>(d[c]);
        dd += static_cast<double>(d[c] * d[c]);
      }
      EXPECT_GT(along, 0) << v;
      for (std::size_t c = 0; c < 3; ++c)
      {
        EXPECT_NEAR(b[c] - a[c], along / dd * static_cast<double>(d[c]), 1e-9) << v;
      }
    }
  }
  // A refusal is the same on threads.
  p.MaxVertices = 1000;
  EXPECT_THROW(PlaneArrangement(l.Analysis.Families(), p), Error);
}

TEST(PlaneArrangement, CostFollowsTheVerticesNotTheCandidates)
{
  // A wide, flat box under the house's sloped families: the index boxes of their planes hold
  // some 10^8 candidate points, nearly all above or below the box. Only each line's stretch
  // inside the box is visited and only the vertices are kept (a table over every candidate
  // refused this box, or took 4 bytes a candidate).
  const Loaded l = Load("house.obj");
  ArrangementParameters p =
    DefaultArrangementParameters(l.Example, l.Analysis, { 250, 250, 0.5 }, 0, {});
  p.MaxVertices = 2000000;
  const PlaneArrangement a(l.Analysis.Families(), p);
  ASSERT_GT(a.NumberOfVertices(), 250 * 250);
  // Every link leads to the nearest vertex along its line, which links back.
  for (std::int64_t v = 0; v < a.NumberOfVertices(); v += 101)
  {
    for (auto k = a.LinksBegin(v); k != a.LinksEnd(v); ++k)
    {
      if (k->Vertex < 0)
        continue;
      bool back = false;
      for (auto j = a.LinksBegin(k->Vertex); j != a.LinksEnd(k->Vertex); ++j)
        back = back || (j->Vertex == v && (j->Direction ^ 1) == k->Direction);
      EXPECT_TRUE(back) << v;
    }
  }
}

TEST(PlaneArrangement, RefusesTooManyVertices)
{
  const Loaded l = Load("cube.obj");
  ArrangementParameters p =
    DefaultArrangementParameters(l.Example, l.Analysis, { 30, 30, 30 }, 0, {});
  p.MaxVertices = 1000;
  EXPECT_THROW(PlaneArrangement(l.Analysis.Families(), p), Error);
  EXPECT_THROW(DefaultArrangementParameters(l.Example, l.Analysis, { -1, 3, 3 }, 0, {}), Error);
}

TEST(ContinuousSynthesis, CubeModelsPassTheCheck)
{
  const Loaded l = Load("cube.obj");
  for (std::uint64_t seed = 1; seed <= 3; ++seed)
  {
    const SynthesisRun r = Synthesize(l, { 6, 6, 4 }, 1, seed, 0);
    ASSERT_TRUE(r.Result.Succeeded()) << r.Result.Message;
    EXPECT_TRUE(r.Report.Valid) << r.Report.Problem;
    EXPECT_GT(r.Mesh.Polygons.size(), 0u);
    std::cout << "cube seed " << seed << ": " << r.Vertices << " vertices, "
              << r.Mesh.Polygons.size() << " polygons, " << r.Report.Objects << " objects, "
              << r.Report.DistinctLabels << " labels, "
              << (r.Result.Statistics.Attempts - r.Result.Statistics.BlocksAccepted)
              << " failed attempts\n";
  }
}

TEST(ContinuousSynthesis, BundledExamplesPassTheCheck)
{
  struct Case
  {
    const char* Name;
    Point3 Size;
    double Spacing;
  };
  // Every bundled example, in a box a few times its size.
  const Case cases[] = { { "triangle2d.obj", { 16, 12, 0 }, 1 },
    { "two-objects2d.obj", { 18, 12, 0 }, 0 }, { "concave2d.obj", { 12, 12, 0 }, 0 },
    { "cube.obj", { 5, 5, 3 }, 0 }, { "box-building.obj", { 16, 12, 10 }, 1 },
    { "l-prism.obj", { 8, 8, 3 }, 0 }, { "house.obj", { 18, 18, 8 }, 0 },
    { "tetrahedron.obj", { 4, 4, 4 }, 0.5 }, { "pentagonal-prism.obj", { 14, 14, 6 }, 1 },
    { "stairs.obj", { 8, 8, 6 }, 0 }, { "arch.obj", { 9, 5, 6 }, 0 },
    { "cottage.obj", { 6, 6, 6 }, 0 } };
  for (const Case& c : cases)
  {
    const Loaded l = Load(c.Name);
    const SynthesisRun r = Synthesize(l, c.Size, c.Spacing, 7, 4);
    ASSERT_TRUE(r.Result.Succeeded()) << c.Name << ": " << r.Result.Message;
    EXPECT_TRUE(r.Report.Valid) << c.Name << ": " << r.Report.Problem;
    EXPECT_GT(r.Mesh.Polygons.size(), 0u) << c.Name << ": an empty model proves nothing";
    std::cout << c.Name << ": " << r.Vertices << " vertices, " << r.Mesh.Polygons.size()
              << " polygons, " << r.Report.Objects << " objects, " << r.Report.DistinctLabels
              << " labels, " << (r.Result.Statistics.Attempts - r.Result.Statistics.BlocksAccepted)
              << " failed attempts, " << r.Result.Statistics.BlocksFailed << " failed blocks\n";
  }
}

TEST(ContinuousSynthesis, TetrahedraAreScaledCopies)
{
  // §4.6.4: a tetrahedron's only models are tetrahedra of several sizes (uniformly scaled
  // copies): every object of the output has four faces with the example's four normals.
  const Loaded l = Load("tetrahedron.obj");
  const SynthesisRun r = Synthesize(l, { 5, 5, 5 }, 0.5, 3, 0);
  ASSERT_TRUE(r.Result.Succeeded()) << r.Result.Message;
  ASSERT_TRUE(r.Report.Valid) << r.Report.Problem;
  const PolyhedralExample model = MeshToModel(r.Mesh, l.Example.TypeNames);
  ASSERT_GT(model.NumberOfObjects(), 0);
  for (int o = 0; o < model.NumberOfObjects(); ++o)
  {
    std::set<std::array<long, 3>> normals;
    for (std::size_t f = 0; f < model.Faces.size(); ++f)
    {
      if (model.FaceObject[f] != o)
      {
        continue;
      }
      const auto& face = model.Faces[f];
      const Point3& a = model.Points[static_cast<std::size_t>(face[0])];
      const Point3& b = model.Points[static_cast<std::size_t>(face[1])];
      const Point3& c = model.Points[static_cast<std::size_t>(face[2])];
      const Point3 u{ b[0] - a[0], b[1] - a[1], b[2] - a[2] },
        v{ c[0] - a[0], c[1] - a[1], c[2] - a[2] };
      Point3 n{ u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0] };
      const double len = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
      normals.insert({ std::lround(1000 * n[0] / len), std::lround(1000 * n[1] / len),
        std::lround(1000 * n[2] / len) });
    }
    EXPECT_EQ(normals.size(), 4u) << "object " << o;
  }
}

TEST(ContinuousSynthesis, SeededSnapshotsAndDeterminism)
{
  const Loaded l = Load("l-prism.obj");
  const ArrangementParameters p =
    DefaultArrangementParameters(l.Example, l.Analysis, { 6, 6, 3 }, 0, {});
  const PlaneArrangement arrangement(l.Analysis.Families(), p);
  for (double block : { 0.0, 2.0 })
  {
    std::vector<CatalogSnapshot> snapshots;
    ContinuousSynthesisOptions options;
    options.Seed = 11;
    options.BlockSize = block;
    options.Snapshots = 5;
    options.OnSnapshot = [&](const CatalogSnapshot& s) { snapshots.push_back(s); };
    const auto a = SynthesizeContinuous(l.Analysis, arrangement, options);
    ASSERT_TRUE(a.Succeeded()) << a.Message;
    ASSERT_EQ(snapshots.size(), 6u) << "block " << block;
    for (std::size_t i = 0; i < snapshots.size(); ++i)
    {
      EXPECT_EQ(snapshots[i].Step, static_cast<std::int64_t>(i));
      EXPECT_EQ(
        snapshots[i].CatalogSize.size(), static_cast<std::size_t>(arrangement.NumberOfVertices()));
    }
    // The start has choices, nothing decided; the end is the result.
    EXPECT_GT(
      *std::max_element(snapshots[0].CatalogSize.begin(), snapshots[0].CatalogSize.end()), 1);
    EXPECT_EQ(snapshots[0].Labels[0], CatalogSnapshot::Undecided);
    EXPECT_EQ(snapshots.back().Labels, a.Labels);
    options.OnSnapshot = nullptr;
    const auto b = SynthesizeContinuous(l.Analysis, arrangement, options);
    EXPECT_EQ(a.Labels, b.Labels) << "same seed, same model";
    options.Seed = 12;
    const auto c = SynthesizeContinuous(l.Analysis, arrangement, options);
    EXPECT_NE(a.Labels, c.Labels) << "another seed, another model";
  }
}

TEST(ContinuousSynthesis, CheckRejectsABrokenModel)
{
  const Loaded l = Load("cube.obj");
  const ArrangementParameters p =
    DefaultArrangementParameters(l.Example, l.Analysis, { 4, 4, 4 }, 0, {});
  const PlaneArrangement arrangement(l.Analysis.Families(), p);
  ContinuousSynthesisOptions options;
  options.Seed = 3;
  const auto r = SynthesizeContinuous(l.Analysis, arrangement, options);
  ASSERT_TRUE(r.Succeeded());
  ContinuousMesh mesh = ExtractMesh(l.Analysis, arrangement, r.Labels);
  ASSERT_GT(mesh.Polygons.size(), 1u);
  // A missing polygon leaves a hole; a flipped one breaks the orientation.
  ContinuousMesh holed = mesh;
  holed.Polygons.pop_back();
  holed.InsideType.pop_back();
  holed.OutsideType.pop_back();
  EXPECT_FALSE(CheckContinuousModel(l.Analysis, holed, l.Example.TypeNames).Valid);
  ContinuousMesh flipped = mesh;
  for (auto& poly : flipped.Polygons)
  {
    std::reverse(poly.begin(), poly.end());
  }
  EXPECT_FALSE(CheckContinuousModel(l.Analysis, flipped, l.Example.TypeNames).Valid);
  // Labels that disagree along an edge are caught by the label check.
  std::vector<std::int32_t> labels = r.Labels;
  const int inside = l.Analysis.Find(NeighbourhoodLabel::Constant(1));
  ASSERT_GE(inside, 0);
  std::int64_t centre = -1;
  for (std::int64_t v = 0; v < arrangement.NumberOfVertices(); ++v)
  {
    if (arrangement.Position(v) == Point3{ 2, 2, 2 })
    {
      centre = v;
    }
  }
  ASSERT_GE(centre, 0);
  labels[static_cast<std::size_t>(centre)] =
    labels[static_cast<std::size_t>(centre)] == inside ? 0 : inside;
  EXPECT_NE(CheckArrangementLabels(l.Analysis, arrangement, labels), "");
}

TEST(ContinuousSynthesis, CancellationStopsWithinABlock)
{
  // The whole model at once is one long block (about 130,000 vertices: well over the 100 ms
  // before the first poll, however fast the solver gets): the progress callback is polled inside
  // it, so a "stop" answer at the first poll ends the run within a fraction of a second, as a
  // cancelled run.
  const Loaded l = Load("house.obj");
  const ArrangementParameters p =
    DefaultArrangementParameters(l.Example, l.Analysis, { 60, 60, 10 }, 0, {});
  const PlaneArrangement arrangement(l.Analysis.Families(), p);
  ContinuousSynthesisOptions options;
  options.Seed = 2;
  int calls = 0;
  auto asked = std::chrono::steady_clock::now();
  options.Progress = [&calls, &asked](double)
  {
    asked = std::chrono::steady_clock::now();
    return ++calls < 1;
  };
  const ContinuousSynthesisResult r = SynthesizeContinuous(l.Analysis, arrangement, options);
  EXPECT_EQ(r.Status, SynthesisStatus::Cancelled) << calls << " polls";
  EXPECT_NE(r.Message.find("cancelled"), std::string::npos) << r.Message;
  EXPECT_EQ(calls, 1);
  // From the "stop" answer to the end of the run.
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - asked).count(), 1.0);
}

TEST(ContinuousSynthesis, BlocksOfAPhaseNeverTouch)
{
  // Recomputed from the layout's blocks and the arrangement's links, not from the phase
  // formula: two blocks of one phase share no vertex and no edge (neither reads what the other
  // labels). The sloped house has edges longer than a cell; the L-prism's are short.
  for (const char* name : { "house.obj", "l-prism.obj" })
  {
    const Loaded l = Load(name);
    const ArrangementParameters p =
      DefaultArrangementParameters(l.Example, l.Analysis, { 16, 16, 6 }, 0, {});
    const PlaneArrangement arrangement(l.Analysis.Families(), p);
    const detail::BlockLayout layout(arrangement, 2.0, PhasePolicy::NonTouching);
    std::vector<std::int64_t> blockOf(static_cast<std::size_t>(arrangement.NumberOfVertices()));
    int phases = 0, shared = 0;
    for (std::size_t first = 0; first < layout.Grid.size();)
    {
      std::size_t last = first;
      while (last < layout.Grid.size() && layout.Grid[last].Phase == layout.Grid[first].Phase)
        ++last;
      ++phases;
      std::fill(blockOf.begin(), blockOf.end(), -1);
      for (std::size_t b = first; b < last; ++b)
        for (std::int64_t v : layout.Vertices(static_cast<std::int64_t>(b)))
        {
          EXPECT_EQ(blockOf[static_cast<std::size_t>(v)], -1) << name << ": a shared vertex";
          blockOf[static_cast<std::size_t>(v)] = static_cast<std::int64_t>(b);
        }
      for (std::int64_t v = 0; v < arrangement.NumberOfVertices(); ++v)
        for (const auto* k = arrangement.LinksBegin(v); k != arrangement.LinksEnd(v); ++k)
        {
          const std::int64_t a = blockOf[static_cast<std::size_t>(v)];
          const std::int64_t b = k->Vertex < 0 ? -1 : blockOf[static_cast<std::size_t>(k->Vertex)];
          shared += a >= 0 && b >= 0 && a != b ? 1 : 0;
        }
      first = last;
    }
    EXPECT_EQ(shared, 0) << name << ": edges between blocks of one phase";
    EXPECT_LT(phases, static_cast<int>(layout.Grid.size())) << name << ": nothing concurrent";
  }
}

TEST(ContinuousSynthesis, ThreadsGiveTheSameModel)
{
  // Grounded houses with their proportions steered (the shares are global), 16 blocks in 9
  // phases: one thread and two give the same labels, each model checked by re-analysis.
  const Loaded l = Load("house.obj");
  const ArrangementParameters p =
    DefaultArrangementParameters(l.Example, l.Analysis, { 32, 32, 8 }, 0, {});
  const PlaneArrangement arrangement(l.Analysis.Families(), p);
  for (bool grounded : { false, true })
  {
    ContinuousSynthesisOptions options;
    options.Seed = 5;
    options.BlockSize = 4;
    options.Constraints.Grounded = grounded;
    options.Threads = 1;
    const ContinuousSynthesisResult one = SynthesizeContinuous(l.Analysis, arrangement, options);
    options.Threads = 2;
    const ContinuousSynthesisResult two = SynthesizeContinuous(l.Analysis, arrangement, options);
    ASSERT_TRUE(one.Succeeded()) << one.Message;
    ASSERT_TRUE(two.Succeeded()) << two.Message;
    EXPECT_EQ(one.Statistics.Threads, 1);
    if (std::thread::hardware_concurrency() >= 2)
    {
      EXPECT_EQ(two.Statistics.Threads, 2);
    }
    EXPECT_LT(two.Statistics.Phases, two.Statistics.Blocks);
    EXPECT_EQ(one.Labels, two.Labels) << "grounded " << grounded;
    EXPECT_EQ(one.Statistics.Assignments, two.Statistics.Assignments);
    EXPECT_EQ(CheckArrangementLabels(l.Analysis, arrangement, two.Labels), "");
    const auto report = CheckContinuousModel(
      l.Analysis, ExtractMesh(l.Analysis, arrangement, two.Labels), l.Example.TypeNames);
    EXPECT_TRUE(report.Valid) << report.Problem;
    EXPECT_GT(MeasureArrangement(l.Analysis, arrangement, two.Labels).Components, 0);
  }
  // Objects spreading outward from connectivity seeds: one block after the other.
  ContinuousSynthesisOptions seeded;
  seeded.Seed = 5;
  seeded.BlockSize = 4;
  seeded.Threads = 2;
  seeded.Constraints.Connected.push_back({ 0, 2 });
  const ContinuousSynthesisResult s = SynthesizeContinuous(l.Analysis, arrangement, seeded);
  ASSERT_TRUE(s.Succeeded()) << s.Message;
  EXPECT_EQ(s.Statistics.Threads, 1);
  EXPECT_EQ(s.Statistics.Phases, s.Statistics.Blocks);
}

TEST(ContinuousMesh, TheSameMeshOnAnyNumberOfThreads)
{
  // Faces are traced in chunks of 4096 vertices on threads and added in the vertices' order:
  // the mesh (points, polygons, types) is the same for 1, 2 and 3 threads, and FaceMeasures
  // (the proportion step's volumes) lists the same faces with their divergence-theorem terms.
  for (const char* name : { "house.obj", "triangle2d.obj" })
  {
    const Loaded l = Load(name);
    const bool planar = std::string(name) == "triangle2d.obj";
    const ArrangementParameters p = DefaultArrangementParameters(l.Example, l.Analysis,
      planar ? Point3{ 20, 20, 1 } : Point3{ 24, 24, 8 }, planar ? 0.1 : 0, {});
    const PlaneArrangement arrangement(l.Analysis.Families(), p);
    ASSERT_GT(arrangement.NumberOfVertices(), 3 * 4096) << name;
    ContinuousSynthesisOptions options;
    options.Seed = 3;
    options.BlockSize = 4;
    const ContinuousSynthesisResult r = SynthesizeContinuous(l.Analysis, arrangement, options);
    ASSERT_TRUE(r.Succeeded()) << r.Message;
    const ContinuousMesh one = ExtractMesh(l.Analysis, arrangement, r.Labels, 1);
    ASSERT_GT(one.Polygons.size(), 100u) << name;
    for (unsigned threads : { 2u, 3u })
    {
      const ContinuousMesh other = ExtractMesh(l.Analysis, arrangement, r.Labels, threads);
      EXPECT_EQ(one.Points, other.Points) << name << threads;
      EXPECT_EQ(one.PointVertex, other.PointVertex) << name << threads;
      EXPECT_EQ(one.Polygons, other.Polygons) << name << threads;
      EXPECT_EQ(one.InsideType, other.InsideType) << name << threads;
      EXPECT_EQ(one.OutsideType, other.OutsideType) << name << threads;
    }
    const auto faces = FaceMeasures(l.Analysis, arrangement, r.Labels, 2);
    ASSERT_EQ(faces.size(), one.Polygons.size()) << name;
    std::map<int, double> volumes;
    for (std::size_t f = 0; f < faces.size(); ++f)
    {
      EXPECT_EQ(faces[f].Corner, one.PointVertex[static_cast<std::size_t>(one.Polygons[f][0])]);
      EXPECT_EQ(faces[f].Inside, one.InsideType[f]);
      EXPECT_EQ(faces[f].Outside, planar ? 0 : one.OutsideType[f]);
      volumes[faces[f].Inside] += faces[f].Measure;
      volumes[faces[f].Outside] -= faces[f].Measure;
    }
    for (const auto& [type, volume] : TypeVolumes(one))
      EXPECT_NEAR(volumes[type], volume, 1e-6 * (1 + std::abs(volume))) << name << type;
  }
}

TEST(ContinuousSynthesis, BlocksSpreadOverProcessesGiveTheSameModel)
{
  // Two "processes" (threads with an all-gather, as MPI ranks under pvbatch) each run half of
  // every phase and exchange the blocks' labels and shares: both end with the one-process
  // model, with proportions steered (shares travel with the blocks) and grounded.
  const Loaded l = Load("house.obj");
  const ArrangementParameters p =
    DefaultArrangementParameters(l.Example, l.Analysis, { 32, 32, 8 }, 0, {});
  const PlaneArrangement arrangement(l.Analysis.Families(), p);
  for (bool grounded : { false, true })
  {
    ContinuousSynthesisOptions options;
    options.Seed = 7;
    options.BlockSize = 4;
    options.Threads = 1;
    options.Constraints.Grounded = grounded;
    const ContinuousSynthesisResult single = SynthesizeContinuous(l.Analysis, arrangement, options);
    ASSERT_TRUE(single.Succeeded()) << single.Message;
    const int ranks = 2;
    msynth_test::ThreadAllGather gather(ranks);
    std::vector<ContinuousSynthesisResult> results(static_cast<std::size_t>(ranks));
    std::vector<std::thread> pool;
    for (int r = 0; r < ranks; ++r)
      pool.emplace_back(
        [&, r]
        {
          ContinuousSynthesisOptions mine = options;
          mine.Exchange.Rank = r;
          mine.Exchange.Processes = ranks;
          mine.Exchange.AllGather = [&gather, r](const std::vector<char>& bytes)
          { return gather(r, bytes); };
          results[static_cast<std::size_t>(r)] =
            SynthesizeContinuous(l.Analysis, arrangement, mine);
        });
    for (auto& t : pool)
      t.join();
    for (const auto& r : results)
    {
      ASSERT_TRUE(r.Succeeded()) << r.Message;
      EXPECT_EQ(r.Statistics.Processes, ranks);
      EXPECT_LT(r.Statistics.Phases, r.Statistics.Blocks);
      EXPECT_EQ(r.Labels, single.Labels) << "grounded " << grounded;
      EXPECT_EQ(r.FloatingPartsRemoved, single.FloatingPartsRemoved);
    }
    EXPECT_EQ(CheckArrangementLabels(l.Analysis, arrangement, results[1].Labels), "");
  }
}

TEST(ContinuousMesh, LevelSetVoxelsGrowWithTheSurface)
{
  // A unit cube of type 1 (area 6) on a cube of type 2 (the face between them counts for both).
  ContinuousMesh mesh;
  for (int z = 0; z <= 2; ++z)
    for (int y = 0; y <= 1; ++y)
      for (int x = 0; x <= 1; ++x)
        mesh.Points.push_back({ double(x), double(y), double(z) });
  auto at = [](int x, int y, int z) { return static_cast<std::int32_t>(x + 2 * y + 4 * z); };
  auto add = [&](std::vector<std::int32_t> poly, int inside, int outside)
  {
    mesh.Polygons.push_back(std::move(poly));
    mesh.InsideType.push_back(inside);
    mesh.OutsideType.push_back(outside);
  };
  for (int z = 0; z < 2; ++z)
  {
    const int type = z + 1;
    add({ at(0, 0, z), at(1, 0, z), at(1, 0, z + 1), at(0, 0, z + 1) }, type, 0);
    add({ at(1, 1, z), at(0, 1, z), at(0, 1, z + 1), at(1, 1, z + 1) }, type, 0);
    add({ at(0, 1, z), at(0, 0, z), at(0, 0, z + 1), at(0, 1, z + 1) }, type, 0);
    add({ at(1, 0, z), at(1, 1, z), at(1, 1, z + 1), at(1, 0, z + 1) }, type, 0);
  }
  add({ at(0, 0, 0), at(0, 1, 0), at(1, 1, 0), at(1, 0, 0) }, 1, 0);
  add({ at(0, 0, 1), at(1, 0, 1), at(1, 1, 1), at(0, 1, 1) }, 1, 2);
  add({ at(0, 0, 2), at(1, 0, 2), at(1, 1, 2), at(0, 1, 2) }, 2, 0);
  // Surfaces of 12 square units: bands of 2 · 3 voxels hold 72 / voxel² voxels.
  EXPECT_DOUBLE_EQ(LevelSetVoxel(mesh, 0.4, 2, 3, 1e12), 0.1);         // a quarter spacing
  EXPECT_DOUBLE_EQ(LevelSetVoxel(mesh, 0.004, 2, 3, 1e12), 2.0 / 256); // 1/256 of the extent
  EXPECT_NEAR(LevelSetVoxel(mesh, 0.4, 2, 3, 72 / 0.25), 0.5, 1e-12);  // the budget
}

// Proportion steering (issue 29): among labels that all hold a type that is short, the one
// holding more of it weighs more (a porch's face, half its cones, over the edge that ends it, a
// quarter), so a scarce type grows rather than only starts; a type in excess ends sooner.
TEST(ContinuousConstraints, ShortTypesGrowByOccupancy)
{
  const Loaded l = Load("cottage.obj");
  const ArrangementParameters p =
    DefaultArrangementParameters(l.Example, l.Analysis, { 6, 6, 4 }, 0, {});
  const PlaneArrangement arrangement(l.Analysis.Families(), p);
  ContinuousConstraints constraints;
  const detail::ConstraintPlan plan(l.Analysis, arrangement, constraints, 1);
  ASSERT_TRUE(plan.Weighted());
  int porch = -1;
  for (int t = 1; t < plan.NumberOfTypes(); ++t)
    if (l.Example.TypeNames.at(plan.TypeAt(t)) == "porch")
      porch = t;
  ASSERT_GT(porch, 0);
  // A face and an edge of the porch alone (porch and empty space only).
  int face = -1, edge = -1;
  for (int a = 0; a < l.Analysis.NumberOfLabels(); ++a)
  {
    if (plan.LabelTypes(a) != (detail::Bit(0) | detail::Bit(porch)))
      continue;
    const double f = plan.Occupancy(a, porch);
    if (face < 0 && std::abs(f - 0.5) < 1e-9)
      face = a;
    if (edge < 0 && std::abs(f - 0.25) < 1e-9)
      edge = a;
  }
  ASSERT_GE(face, 0);
  ASSERT_GE(edge, 0);
  // Occupancy per type bit (0: empty space) with the porch about 0.06 of the solid (the
  // example: 0.084), then about 0.16. (Far from the target both factors reach their clamps.)
  std::vector<double> tally(static_cast<std::size_t>(plan.NumberOfTypes()), 0.0);
  for (int t = 1; t < plan.NumberOfTypes(); ++t)
    tally[static_cast<std::size_t>(t)] = t == porch ? 18 : 100;
  EXPECT_GT(plan.Factor(0, face, tally), 2 * plan.Factor(0, edge, tally));
  tally[static_cast<std::size_t>(porch)] = 60;
  EXPECT_LT(2 * plan.Factor(0, face, tally), plan.Factor(0, edge, tally));
  // Without the steering every label weighs the same.
  constraints.KeepProportions = false;
  const detail::ConstraintPlan unsteered(l.Analysis, arrangement, constraints, 1);
  EXPECT_EQ(unsteered.Factor(0, face, tally), unsteered.Factor(0, edge, tally));
}

// Voxels whose centres lie on a face (a 45-degree slope through the centres of voxels aligned with
// the model) fall to either side alike when sampled evenly, so the voxels add up to the volume;
// one nudged sample puts all of them on one side.
TEST(ContinuousMesh, VoxelizedEvenlyTiesSplit)
{
  // A wedge: the triangle (0, 0), (2, 0), (0, 2) in x and z, from y = 0 to 1 (volume 2).
  const ContinuousMesh wedge = MeshFromPolygons(false,
    { { 0, 0, 0 }, { 2, 0, 0 }, { 0, 0, 2 }, { 0, 1, 0 }, { 2, 1, 0 }, { 0, 1, 2 } },
    { { 0, 1, 2 }, { 3, 5, 4 }, { 0, 3, 4, 1 }, { 0, 2, 5, 3 }, { 1, 4, 5, 2 } }, { 1, 1, 1, 1, 1 },
    { 0, 0, 0, 0, 0 });
  auto count = [](const LabelGrid& grid)
  {
    int n = 0;
    for (std::int64_t z = 0; z < grid.Size(2); ++z)
      for (std::int64_t y = 0; y < grid.Size(1); ++y)
        for (std::int64_t x = 0; x < grid.Size(0); ++x)
          n += grid.At(x, y, z) == 1 ? 1 : 0;
    return n;
  };
  const std::array<std::int64_t, 3> dims{ { 4, 2, 4 } };
  EXPECT_EQ(count(VoxelizeModelEvenly(wedge, { 0, 0, 0 }, 0.5, dims)), 16); // 2 / 0.5^3
  // The 8 centres on the slope (x + z = 2) all on one side with one sample.
  EXPECT_EQ(std::abs(count(VoxelizeModel(wedge, { 0, 0, 0 }, 0.5, dims)) - 16), 4);
}
