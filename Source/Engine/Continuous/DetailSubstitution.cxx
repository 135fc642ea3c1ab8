// SPDX-License-Identifier: BSD-3-Clause
#include "Continuous/DetailSubstitution.h"

#include "Core/Error.h"
#include "Core/Index.h"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace msynth
{

namespace
{
std::int64_t Root(std::vector<std::int64_t>& parent, std::int64_t i)
{
  while (parent[ToIndex(i)] != i)
  {
    parent[ToIndex(i)] = parent[ToIndex(parent[ToIndex(i)])];
    i = parent[ToIndex(i)];
  }
  return i;
}

/// Appends a copy of @p detail to @p out, mapped from the bounding volume's box [@p low,
/// @p high] onto the part's box of @p placement (whose scale and anisotropy it sets), its
/// polygons of @p type toward empty space.
void PlaceDetail(ContinuousMesh& out, DetailPlacement& placement, const PolyhedralExample& detail,
  const Point3& low, const Point3& high, int type)
{
  double smallest = 0, largest = 0;
  for (std::size_t c = 0; c < 3; ++c)
  {
    placement.Scale[c] = (placement.High[c] - placement.Low[c]) / (high[c] - low[c]);
    smallest = c == 0 ? placement.Scale[c] : std::min(smallest, placement.Scale[c]);
    largest = c == 0 ? placement.Scale[c] : std::max(largest, placement.Scale[c]);
  }
  placement.Anisotropy = largest > 0 ? (largest - smallest) / largest : 0;
  const auto first = static_cast<std::int32_t>(out.Points.size());
  for (const auto& q : detail.Points)
  {
    Point3 p{};
    for (std::size_t c = 0; c < 3; ++c)
      p[c] = placement.Low[c] + (q[c] - low[c]) * placement.Scale[c];
    out.Points.push_back(p);
    out.PointVertex.push_back(-1);
  }
  for (const auto& face : detail.Faces)
  {
    std::vector<std::int32_t> poly;
    for (int i : face)
      poly.push_back(first + i);
    out.Polygons.push_back(std::move(poly));
    out.InsideType.push_back(type);
    out.OutsideType.push_back(0);
  }
}
} // namespace

DetailResult SubstituteDetail(const ContinuousMesh& model, const std::vector<int>& types,
  const PolyhedralExample& detail, const Point3& low, const Point3& high)
{
  if (types.empty())
    throw Error("detail substitution: no object type to substitute");
  const int type = types[0];
  auto inSet = [&types](int t) { return std::find(types.begin(), types.end(), t) != types.end(); };
  if (model.Planar)
    throw Error("detail substitution: the model is 2D; bounding volumes are for 3D models");
  if (detail.Faces.empty())
    throw Error("detail substitution: the detail mesh '" + detail.Source + "' has no polygons");
  for (std::size_t c = 0; c < 3; ++c)
    if (!(high[c] > low[c]))
      throw Error("detail substitution: the bounding volume of type " + std::to_string(type) +
        " has an empty box");
  DetailResult result;
  ContinuousMesh& out = result.Mesh;
  out.Planar = false;
  out.Points = model.Points;
  out.PointVertex = model.PointVertex;
  // Parts of the type: its polygons joined by shared points.
  std::vector<std::int64_t> parent(model.Points.size());
  std::iota(parent.begin(), parent.end(), std::int64_t(0));
  auto ofType = [&](std::size_t f)
  { return inSet(model.InsideType[f]) || inSet(model.OutsideType[f]); };
  for (std::size_t f = 0; f < model.Polygons.size(); ++f)
  {
    if (!ofType(f))
      continue;
    for (std::size_t k = 1; k < model.Polygons[f].size(); ++k)
      parent[ToIndex(Root(parent, model.Polygons[f][k]))] = Root(parent, model.Polygons[f][0]);
  }
  std::vector<std::int64_t> partOf(model.Points.size(), -1);
  for (std::size_t f = 0; f < model.Polygons.size(); ++f)
  {
    const auto& poly = model.Polygons[f];
    if (!ofType(f))
    {
      out.Polygons.push_back(poly);
      out.InsideType.push_back(model.InsideType[f]);
      out.OutsideType.push_back(model.OutsideType[f]);
      continue;
    }
    const auto root = ToIndex(Root(parent, poly[0]));
    if (partOf[root] < 0)
    {
      partOf[root] = static_cast<std::int64_t>(result.Placements.size());
      DetailPlacement p;
      p.Low = model.Points[ToIndex(poly[0])];
      p.High = p.Low;
      result.Placements.push_back(p);
    }
    auto& placement = result.Placements[ToIndex(partOf[root])];
    for (auto i : poly)
      for (std::size_t c = 0; c < 3; ++c)
      {
        placement.Low[c] = std::min(placement.Low[c], model.Points[ToIndex(i)][c]);
        placement.High[c] = std::max(placement.High[c], model.Points[ToIndex(i)][c]);
      }
    // A face shared with another object stays as that object's face toward empty space.
    const bool inside = inSet(model.InsideType[f]);
    const int other = inside ? model.OutsideType[f] : model.InsideType[f];
    if (other == 0 || inSet(other))
      continue; // toward empty space, or between pieces of the bounding volume
    out.Polygons.push_back(poly);
    if (inside)
      std::reverse(out.Polygons.back().begin(), out.Polygons.back().end());
    out.InsideType.push_back(other);
    out.OutsideType.push_back(0);
  }
  // A copy of the detail per part, from the bounding volume's box onto the part's box.
  for (auto& placement : result.Placements)
    PlaceDetail(out, placement, detail, low, high, type);
  return result;
}

} // namespace msynth
