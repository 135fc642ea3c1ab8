// SPDX-License-Identifier: BSD-3-Clause
#include "Continuous/FeatureWidth.h"

#include "Continuous/Point3Math.h"
#include "Core/Index.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <unordered_map>

namespace msynth
{
namespace
{
using point3::Add;
using point3::Cross;
using point3::Dot;
using point3::Norm;
using point3::Sub;

/// A part of the boundary: a polygon (3D) or a segment (2D), with its plane (line) n·x = d.
struct Part
{
  std::vector<Point3> Corners;
  Point3 Normal{};
  double Offset = 0;
};

double SegmentDistance(const Point3& p, const Point3& a, const Point3& b)
{
  const Point3 ab = Sub(b, a);
  const double len2 = Dot(ab, ab);
  const double t = len2 > 0 ? std::clamp(Dot(Sub(p, a), ab) / len2, 0.0, 1.0) : 0.0;
  return Norm(Sub(p, Add(a, ab, t)));
}

/// Distance from @p p to the part: to the polygon's interior when p projects into it, else to
/// its edges (a segment's distance in 2D).
double PartDistance(const Point3& p, const Part& part)
{
  const auto& c = part.Corners;
  double best = HUGE_VAL;
  const std::size_t n = c.size();
  for (std::size_t i = 0; i < (n == 2 ? 1 : n); ++i)
    best = std::min(best, SegmentDistance(p, c[i], c[(i + 1) % n]));
  if (n < 3)
    return best;
  // Inside test in the plane, dropping the normal's largest component.
  const Point3& nn = part.Normal;
  int drop = 0;
  for (int k = 1; k < 3; ++k)
    if (std::abs(nn[k]) > std::abs(nn[drop]))
      drop = k;
  const int u = (drop + 1) % 3, v = (drop + 2) % 3;
  bool inside = false;
  for (std::size_t i = 0, j = n - 1; i < n; j = i++)
  {
    const double yi = c[i][v], yj = c[j][v];
    if ((yi > p[v]) != (yj > p[v]))
    {
      const double x = c[j][u] + (p[v] - yj) / (yi - yj) * (c[i][u] - c[j][u]);
      inside = inside != (p[u] < x);
    }
  }
  return inside ? std::abs(Dot(nn, p) - part.Offset) : best;
}

/// The boundary of a planar mesh: polygon edges not shared by two faces of the same type.
std::vector<std::array<std::int32_t, 2>> PlanarBoundary(const ContinuousMesh& mesh)
{
  std::map<std::pair<std::int32_t, std::int32_t>, std::vector<std::int32_t>> typesOf;
  for (std::size_t f = 0; f < mesh.Polygons.size(); ++f)
  {
    const auto& poly = mesh.Polygons[f];
    for (std::size_t i = 0; i < poly.size(); ++i)
    {
      const std::int32_t a = poly[i], b = poly[(i + 1) % poly.size()];
      typesOf[{ std::min(a, b), std::max(a, b) }].push_back(mesh.InsideType[f]);
    }
  }
  std::vector<std::array<std::int32_t, 2>> out;
  for (const auto& [edge, types] : typesOf)
    if (types.size() == 1 || types[0] != types[1])
      out.push_back({ edge.first, edge.second });
  return out;
}

/// The parts of the boundary and, per point, the unit normals of the parts through it.
void CollectParts(const ContinuousMesh& mesh, double areaTolerance, std::vector<Part>& parts,
  std::vector<std::vector<std::int32_t>>& partsAt)
{
  partsAt.assign(mesh.Points.size(), {});
  // Points at the same position are one (a mesh read back may repeat them per object).
  std::map<Point3, std::int32_t> first;
  std::vector<std::int32_t> same(mesh.Points.size());
  for (std::size_t i = 0; i < mesh.Points.size(); ++i)
    same[i] = first.emplace(mesh.Points[i], static_cast<std::int32_t>(i)).first->second;
  const auto add = [&](Part part, const std::vector<std::int32_t>& ids)
  {
    for (auto i : ids)
      partsAt[ToIndex(same[ToIndex(i)])].push_back(static_cast<std::int32_t>(parts.size()));
    parts.push_back(std::move(part));
  };
  if (mesh.Planar)
  {
    for (const auto& e : PlanarBoundary(mesh))
    {
      Part part;
      const Point3& a = mesh.Points[ToIndex(e[0])];
      const Point3& b = mesh.Points[ToIndex(e[1])];
      const Point3 d = Sub(b, a);
      const double len = Norm(d);
      if (!(len > 0))
        continue;
      part.Corners = { a, b };
      part.Normal = { -d[1] / len, d[0] / len, 0 };
      part.Offset = Dot(part.Normal, a);
      add(std::move(part), { e[0], e[1] });
    }
    return;
  }
  for (const auto& poly : mesh.Polygons)
  {
    Part part;
    Point3 newell{};
    for (std::size_t i = 0; i < poly.size(); ++i)
    {
      const Point3& a = mesh.Points[ToIndex(poly[i])];
      const Point3& b = mesh.Points[ToIndex(poly[(i + 1) % poly.size()])];
      newell = Add(newell, Cross(a, b), 1.0);
      part.Corners.push_back(a);
    }
    const double twice = Norm(newell);
    if (poly.size() < 3 || !(twice > 2 * areaTolerance))
      continue; // no plane to measure against
    part.Normal = { newell[0] / twice, newell[1] / twice, newell[2] / twice };
    part.Offset = Dot(part.Normal, part.Corners[0]);
    add(std::move(part), poly);
  }
}

/// Whether the normals of @p ids span the space (3D: three independent; 2D: two).
bool IsCorner(const std::vector<Part>& parts, const std::vector<std::int32_t>& ids, bool planar)
{
  constexpr double independent = 1e-6;
  for (std::size_t i = 0; i < ids.size(); ++i)
    for (std::size_t j = i + 1; j < ids.size(); ++j)
    {
      const Point3 c = Cross(parts[ToIndex(ids[i])].Normal, parts[ToIndex(ids[j])].Normal);
      if (Norm(c) <= independent)
        continue;
      if (planar)
        return true;
      for (std::size_t k = j + 1; k < ids.size(); ++k)
        if (std::abs(Dot(c, parts[ToIndex(ids[k])].Normal)) > independent)
          return true;
    }
  return false;
}

using CellKey = std::array<std::int64_t, 3>;
struct CellHash
{
  std::size_t operator()(const CellKey& k) const
  {
    // A hash, not an index: negative cells wrap on purpose.
    return static_cast<std::uint64_t>(k[0] * 73856093) ^
      static_cast<std::uint64_t>(k[1] * 19349663) ^ static_cast<std::uint64_t>(k[2] * 83492791);
  }
};
} // namespace

FeatureWidth SmallestFeature(const ContinuousMesh& mesh, double radius)
{
  FeatureWidth out;
  out.Width = radius;
  if (mesh.Points.empty() || !(radius > 0) || !std::isfinite(radius))
    return out;
  Point3 lo = mesh.Points[0], hi = lo;
  for (const auto& p : mesh.Points)
    for (int c = 0; c < 3; ++c)
    {
      lo[c] = std::min(lo[c], p[c]);
      hi[c] = std::max(hi[c], p[c]);
    }
  const double diagonal = Norm(Sub(hi, lo));
  const double touching = 1e-9 * std::max(diagonal, 1e-300);
  std::vector<Part> parts;
  std::vector<std::vector<std::int32_t>> partsAt;
  CollectParts(mesh, 1e-14 * diagonal * diagonal, parts, partsAt);
  // A grid of cells at least the radius wide (and no more than 256 along the diagonal), each
  // listing the parts whose bounding boxes meet it.
  const double cell = std::max(radius, diagonal / 256);
  const auto keyOf = [&](const Point3& p, double shift)
  {
    CellKey k{};
    for (int c = 0; c < 3; ++c)
      k[ToIndex(c)] = static_cast<std::int64_t>(std::floor((p[c] + shift - lo[c]) / cell));
    return k;
  };
  std::unordered_map<CellKey, std::vector<std::int32_t>, CellHash> grid;
  for (std::size_t i = 0; i < parts.size(); ++i)
  {
    Point3 a = parts[i].Corners[0], b = a;
    for (const auto& q : parts[i].Corners)
      for (int c = 0; c < 3; ++c)
      {
        a[c] = std::min(a[c], q[c]);
        b[c] = std::max(b[c], q[c]);
      }
    const CellKey ka = keyOf(a, 0), kb = keyOf(b, 0);
    for (auto x = ka[0]; x <= kb[0]; ++x)
      for (auto y = ka[1]; y <= kb[1]; ++y)
        for (auto z = ka[2]; z <= kb[2]; ++z)
          grid[{ x, y, z }].push_back(static_cast<std::int32_t>(i));
  }
  std::vector<std::size_t> seen(parts.size(), 0);
  std::size_t stamp = 0;
  for (std::size_t p = 0; p < mesh.Points.size(); ++p)
  {
    if (!IsCorner(parts, partsAt[p], mesh.Planar))
      continue;
    ++out.Corners;
    ++stamp;
    const Point3& q = mesh.Points[p];
    const CellKey ka = keyOf(q, -radius), kb = keyOf(q, radius);
    for (auto x = ka[0]; x <= kb[0]; ++x)
      for (auto y = ka[1]; y <= kb[1]; ++y)
        for (auto z = ka[2]; z <= kb[2]; ++z)
        {
          const auto it = grid.find({ x, y, z });
          if (it == grid.end())
            continue;
          for (auto i : it->second)
          {
            if (seen[ToIndex(i)] == stamp)
              continue;
            seen[ToIndex(i)] = stamp;
            const Part& part = parts[ToIndex(i)];
            if (std::abs(Dot(part.Normal, q) - part.Offset) <= touching)
              continue; // a plane through the corner
            const double d = PartDistance(q, part);
            if (d > touching && d < out.Width)
            {
              out.Width = d;
              out.Where = q;
              out.Found = true;
            }
          }
        }
  }
  return out;
}

} // namespace msynth
