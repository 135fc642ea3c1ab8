// SPDX-License-Identifier: BSD-3-Clause
// Checked independently: every edge of each label's surface is used as often in one direction as
// in the other (closed and consistently oriented; voxels of one label touching only along an edge
// make non-manifold edges used twice each way), and the divergence theorem gives each label's
// volume as its voxel count times the voxel volume (so every face points outward).
#include "Discrete/VoxelSurface.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <random>
#include <set>
#include <tuple>

using namespace msynth;

namespace
{
void ExpectClosedOutward(const LabelGrid& g, Label empty, const std::array<double, 3>& spacing)
{
  const VoxelSurface s = ExtractVoxelSurface(g, empty, { { 1.0, -2.0, 0.5 } }, spacing);
  std::map<Label, std::map<std::pair<std::int64_t, std::int64_t>, int>> edges;
  std::map<Label, double> volume;
  for (std::size_t q = 0; q < s.Quads.size(); ++q)
  {
    const auto& quad = s.Quads[q];
    const Label b = s.QuadLabels[q];
    for (int v = 0; v < 4; ++v)
      ++edges[b]
             [{ quad[static_cast<std::size_t>(v)], quad[static_cast<std::size_t>((v + 1) % 4)] }];
    // Volume: sum over the two triangles of the quad of (p0 · (p1 × p2)) / 6.
    for (int t = 0; t < 2; ++t)
    {
      const auto& a = s.Points[static_cast<std::size_t>(quad[0])];
      const auto& b1 = s.Points[static_cast<std::size_t>(quad[static_cast<std::size_t>(t + 1)])];
      const auto& c = s.Points[static_cast<std::size_t>(quad[static_cast<std::size_t>(t + 2)])];
      volume[b] += (a[0] * (b1[1] * c[2] - b1[2] * c[1]) - a[1] * (b1[0] * c[2] - b1[2] * c[0]) +
                     a[2] * (b1[0] * c[1] - b1[1] * c[0])) /
        6.0;
    }
  }
  std::map<Label, std::int64_t> counts;
  for (Label v : g.Data())
    if (v != empty)
      ++counts[v];
  ASSERT_EQ(volume.size(), counts.size());
  for (const auto& kv : counts)
  {
    EXPECT_NEAR(volume[kv.first], double(kv.second) * spacing[0] * spacing[1] * spacing[2], 1e-9)
      << "label " << kv.first;
    for (const auto& e : edges[kv.first])
    {
      const auto reverse = edges[kv.first].find({ e.first.second, e.first.first });
      ASSERT_NE(reverse, edges[kv.first].end()) << "open edge";
      EXPECT_EQ(reverse->second, e.second) << "inconsistent orientation";
    }
  }
}
} // namespace

TEST(VoxelSurface, OneVoxelIsACube)
{
  LabelGrid g(1, 1, 1, 4);
  const VoxelSurface s = ExtractVoxelSurface(g, 0, { { 0, 0, 0 } }, { { 1, 1, 1 } });
  EXPECT_EQ(s.Quads.size(), 6u);
  EXPECT_EQ(s.Points.size(), 8u);
  ExpectClosedOutward(g, 0, { { 1, 1, 1 } });
}

TEST(VoxelSurface, ManifoldShapesUseEachEdgeOnceEachWay)
{
  LabelGrid g(3, 3, 2, 0);
  for (std::int64_t x = 0; x < 3; ++x)
    g.Set(x, 1, 0, 2); // a bar: manifold
  const VoxelSurface s = ExtractVoxelSurface(g, 0, { { 0, 0, 0 } }, { { 1, 1, 1 } });
  std::map<std::pair<std::int64_t, std::int64_t>, int> edges;
  for (const auto& q : s.Quads)
    for (int v = 0; v < 4; ++v)
      ++edges[{ q[static_cast<std::size_t>(v)], q[static_cast<std::size_t>((v + 1) % 4)] }];
  for (const auto& e : edges)
    EXPECT_EQ(e.second, 1);
  ExpectClosedOutward(g, 0, { { 1, 1, 1 } });
}

TEST(VoxelSurface, InternalFacesOfOneLabelAreRemoved)
{
  LabelGrid g(3, 2, 2, 1);
  const VoxelSurface s = ExtractVoxelSurface(g, 0, { { 0, 0, 0 } }, { { 1, 1, 1 } });
  EXPECT_EQ(s.Quads.size(), 2u * (3 * 2 + 3 * 2 + 2 * 2)); // the box's outer faces only
}

TEST(VoxelSurface, RandomGridsGiveClosedOutwardSurfacesPerLabel)
{
  std::mt19937 rng(3);
  for (int trial = 0; trial < 30; ++trial)
  {
    LabelGrid g(1 + rng() % 5, 1 + rng() % 5, 1 + rng() % 4);
    for (auto& v : g.Data())
      v = static_cast<Label>(rng() % 4);
    ExpectClosedOutward(g, 0, { { 0.5, 2.0, 1.5 } });
  }
}

TEST(VoxelSurface, PiecesPutTogetherAreTheWholeSurface)
{
  // The faces of every slab, as sets of corner positions with their label, add up to the whole
  // grid's faces: none lost or doubled at the seams between pieces.
  std::mt19937 rng(11);
  auto faces = [](const VoxelSurface& s)
  {
    std::multiset<std::pair<std::array<std::array<double, 3>, 4>, Label>> out;
    for (std::size_t q = 0; q < s.Quads.size(); ++q)
    {
      std::array<std::array<double, 3>, 4> corners;
      for (std::size_t v = 0; v < 4; ++v)
        corners[v] = s.Points[static_cast<std::size_t>(s.Quads[q][v])];
      out.insert({ corners, s.QuadLabels[q] });
    }
    return out;
  };
  for (int trial = 0; trial < 20; ++trial)
  {
    LabelGrid g(1 + rng() % 6, 1 + rng() % 6, 1 + rng() % 6);
    for (auto& v : g.Data())
      v = static_cast<Label>(rng() % 3);
    const auto whole = faces(ExtractVoxelSurface(g, 0, { { 0, 0, 0 } }, { { 1, 1, 1 } }));
    for (int pieces : { 1, 2, 3, 7 })
    {
      std::multiset<std::pair<std::array<std::array<double, 3>, 4>, Label>> joined;
      for (int p = 0; p < pieces; ++p)
      {
        const SiteSlab slab = PieceSlab(g, p, pieces);
        EXPECT_EQ(g.Dimensions()[static_cast<std::size_t>(slab.Axis)],
          *std::max_element(g.Dimensions().begin(), g.Dimensions().end()));
        for (auto& f : faces(ExtractVoxelSurface(g, 0, { { 0, 0, 0 } }, { { 1, 1, 1 } }, slab)))
          joined.insert(f);
      }
      EXPECT_EQ(joined, whole) << pieces << " pieces";
    }
  }
}

namespace
{
/// The unit faces a surface covers, as (label, outward axis direction 0..5, lowest corner),
/// read from the quads' points alone (unit spacing, origin 0: corners at lattice - 1/2). A
/// rectangle is split into its unit faces; its direction comes from its winding.
std::multiset<std::tuple<Label, int, std::array<std::int64_t, 3>>> UnitFaces(const VoxelSurface& s)
{
  std::multiset<std::tuple<Label, int, std::array<std::int64_t, 3>>> out;
  for (std::size_t q = 0; q < s.Quads.size(); ++q)
  {
    std::array<std::array<double, 3>, 4> p;
    for (std::size_t k = 0; k < 4; ++k)
      p[k] = s.Points[static_cast<std::size_t>(s.Quads[q][k])];
    std::array<double, 3> e1, e2, normal;
    for (int c = 0; c < 3; ++c)
    {
      e1[static_cast<std::size_t>(c)] =
        p[1][static_cast<std::size_t>(c)] - p[0][static_cast<std::size_t>(c)];
      e2[static_cast<std::size_t>(c)] =
        p[2][static_cast<std::size_t>(c)] - p[1][static_cast<std::size_t>(c)];
    }
    normal = { { e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2],
      e1[0] * e2[1] - e1[1] * e2[0] } };
    int axis = 0;
    for (int c = 1; c < 3; ++c)
      if (std::abs(normal[static_cast<std::size_t>(c)]) >
        std::abs(normal[static_cast<std::size_t>(axis)]))
        axis = c;
    const int direction = 2 * axis + (normal[static_cast<std::size_t>(axis)] > 0 ? 0 : 1);
    std::array<std::int64_t, 3> lo, hi;
    for (std::size_t c = 0; c < 3; ++c)
    {
      double a = p[0][c], b = p[0][c];
      for (const auto& corner : p)
      {
        a = std::min(a, corner[c]);
        b = std::max(b, corner[c]);
      }
      lo[c] = std::llround(a + 0.5);
      hi[c] = std::llround(b + 0.5);
    }
    EXPECT_EQ(lo[static_cast<std::size_t>(axis)], hi[static_cast<std::size_t>(axis)])
      << "a planar face";
    const auto u = static_cast<std::size_t>(axis == 0 ? 1 : 0),
               v = static_cast<std::size_t>(axis == 2 ? 1 : 2);
    for (std::int64_t i = lo[u]; i < hi[u]; ++i)
      for (std::int64_t j = lo[v]; j < hi[v]; ++j)
      {
        std::array<std::int64_t, 3> at = lo;
        at[u] = i;
        at[v] = j;
        out.insert({ s.QuadLabels[q], direction, at });
      }
  }
  return out;
}
} // namespace

TEST(VoxelSurface, MergedFacesCoverTheSameFacesInFewerQuads)
{
  // Random grids, and blocky ones (labels constant over 3 x 3 x 2 boxes) where merging pays:
  // the merged rectangles, split back into unit faces with the direction their winding gives,
  // are exactly the faces of the plain surface; and each label's enclosed volume is still its
  // voxel count (divergence theorem over the rectangles).
  std::mt19937 rng(5);
  for (int trial = 0; trial < 40; ++trial)
  {
    const bool blocky = trial % 2 == 1;
    LabelGrid g(1 + rng() % 9, 1 + rng() % 9, 1 + rng() % 6);
    const auto& n = g.Dimensions();
    std::map<std::array<std::int64_t, 3>, Label> boxes;
    for (std::int64_t z = 0; z < n[2]; ++z)
      for (std::int64_t y = 0; y < n[1]; ++y)
        for (std::int64_t x = 0; x < n[0]; ++x)
        {
          const std::array<std::int64_t, 3> box{ { x / 3, y / 3, z / 2 } };
          if (!boxes.count(box))
            boxes[box] = static_cast<Label>(rng() % 3);
          g.Set(x, y, z, blocky ? boxes[box] : static_cast<Label>(rng() % 3));
        }
    const VoxelSurface plain = ExtractVoxelSurface(g, 0, { { 0, 0, 0 } }, { { 1, 1, 1 } });
    const VoxelSurface merged = ExtractMergedVoxelSurface(g, 0, { { 0, 0, 0 } }, { { 1, 1, 1 } });
    EXPECT_EQ(UnitFaces(merged), UnitFaces(plain)) << "trial " << trial;
    EXPECT_LE(merged.Quads.size(), plain.Quads.size());
    if (blocky && plain.Quads.size() > 40)
    {
      EXPECT_LT(merged.Quads.size() * 2, plain.Quads.size()) << "trial " << trial;
    }
    std::map<Label, double> volume;
    for (std::size_t q = 0; q < merged.Quads.size(); ++q)
      for (int t = 0; t < 2; ++t)
      {
        const auto& a = merged.Points[static_cast<std::size_t>(merged.Quads[q][0])];
        const auto& b =
          merged.Points[static_cast<std::size_t>(merged.Quads[q][static_cast<std::size_t>(t + 1)])];
        const auto& c =
          merged.Points[static_cast<std::size_t>(merged.Quads[q][static_cast<std::size_t>(t + 2)])];
        volume[merged.QuadLabels[q]] +=
          (a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0]) +
            a[2] * (b[0] * c[1] - b[1] * c[0])) /
          6.0;
      }
    for (Label l : { 1, 2 })
      EXPECT_NEAR(
        volume[l], static_cast<double>(std::count(g.Data().begin(), g.Data().end(), l)), 1e-9);
  }
}
