// SPDX-License-Identifier: BSD-3-Clause
// Parts as long as the example's (RunEnds.h).
#include "Continuous/RunEnds.h"

#include "Continuous/ModelStructure.h"
#include "Core/Index.h"

#include <algorithm>
#include <cmath>
#include <set>

namespace msynth
{

double TypeRuns::EndChance(double length, double step) const
{
  const double low = length - 0.5 * step, high = length + 0.5 * step;
  auto above = [](const std::vector<double>& v, double x)
  { return static_cast<double>(v.end() - std::upper_bound(v.begin(), v.end(), x)); };
  const double reaching = above(this->Complete, low) + above(this->Cut, low);
  if (!(reaching > 0))
    return this->Complete.empty() ? -1.0 : 1.0; // the example's runs end before this length
  return (above(this->Complete, low) - above(this->Complete, high)) / reaching;
}

double TypeRuns::FitChance(double room, double step) const
{
  const double high = room + 0.5 * step;
  const auto fitting = static_cast<double>(
    std::upper_bound(this->Complete.begin(), this->Complete.end(), high) - this->Complete.begin());
  const auto longer = static_cast<double>(
    this->Cut.end() - std::upper_bound(this->Cut.begin(), this->Cut.end(), high));
  const double all = static_cast<double>(this->Complete.size()) + longer;
  return all > 0 ? fitting / all : -1.0;
}

double TypeRuns::Longest() const
{
  return std::max(this->Complete.empty() ? 0.0 : this->Complete.back(),
    this->Cut.empty() ? 0.0 : this->Cut.back());
}

double AutomaticBlockSize(const ExampleRuns& runs, double reference)
{
  double longest = 0;
  for (const auto& entry : runs)
    for (const TypeRuns& t : entry.second)
      if (!t.Complete.empty())
        longest = std::max(longest, t.Complete.back());
  constexpr double least = 4; // the default of blocks before runs were followed
  return reference > 0 ? std::max(least, std::ceil(2 * longest / reference - 1e-9)) : least;
}

ExampleRuns MeasureRuns(const PolyhedralExample& example, double voxel)
{
  ExampleRuns runs;
  if (example.Planar)
    return runs;
  const TypeVoxels g = ClassifyTypes(example, voxel);
  // Types with a face across the axes (a gabled roof, a prism's diagonal side) have rows that
  // narrow along it: every short run near the ridge would look like an end. Only box-like
  // types (every face across x, y or z: walls, slabs, roads) are followed.
  std::set<int> sloped;
  for (const BoundaryElement& e : BoundaryOf(example))
  {
    const double largest =
      std::max({ std::abs(e.Normal[0]), std::abs(e.Normal[1]), std::abs(e.Normal[2]) });
    if (largest < 1 - 1e-6)
      sloped.insert(example.ObjectTypes[ToIndex(e.Object)]);
  }
  for (int axis = 0; axis < 2; ++axis)
  {
    const std::int64_t n = g.Dims[ToIndex(axis)];
    const std::int64_t rows = g.Dims[0] * g.Dims[1] * g.Dims[2] / n;
    for (std::int64_t r = 0; r < rows; ++r)
    {
      // Row r's voxels along the axis: the other two coordinates from r.
      const std::int64_t a = r % g.Dims[ToIndex(1 - axis)], z = r / g.Dims[ToIndex(1 - axis)];
      auto at = [&](std::int64_t k)
      { return g.Types[ToIndex(axis == 0 ? g.Index(k, a, z) : g.Index(a, k, z))]; };
      for (std::int64_t k = 0; k < n;)
      {
        const int type = at(k);
        std::int64_t end = k + 1;
        while (end < n && at(end) == type)
          ++end;
        if (type != 0 && !sloped.count(type))
        {
          TypeRuns& t = runs[type][ToIndex(axis)];
          (k == 0 || end == n ? t.Cut : t.Complete)
            .push_back(static_cast<double>(end - k) * g.Voxel);
        }
        k = end;
      }
    }
  }
  for (auto& [type, axes] : runs)
    for (TypeRuns& t : axes)
    {
      std::sort(t.Complete.begin(), t.Complete.end());
      std::sort(t.Cut.begin(), t.Cut.end());
    }
  return runs;
}

namespace detail
{

RunEnds::RunEnds(
  const ExampleRuns& runs, const PlaneArrangement& arrangement, const ConstraintPlan& plan)
  : Arrangement(arrangement)
  , Plan(plan)
  , Runs(ToIndex(plan.NumberOfTypes()))
{
  for (int t = 1; t < plan.NumberOfTypes(); ++t)
  {
    // A type grown from seeds is drawn by its growth and fill (a network), not by lengths.
    const auto it = runs.find(plan.TypeAt(t));
    if (it == runs.end() || ((plan.LeadMask() >> t) & 1u))
      continue;
    this->Runs[ToIndex(t)] = it->second;
    this->Tracked |= std::uint64_t(1) << t;
  }
  for (int d = 0; d < arrangement.NumberOfDirections(); ++d)
  {
    const IntVec3& e = arrangement.Direction(d);
    if (e[2] == 0 && std::abs(e[0]) + std::abs(e[1]) == 1)
      this->Axes.push_back({ d, e[0] != 0 ? 0 : 1, e[0] + e[1] > 0 });
  }
}

std::int64_t RunEnds::Behind(std::int64_t v, int d) const
{
  for (const auto* l = this->Arrangement.LinksBegin(v); l != this->Arrangement.LinksEnd(v); ++l)
    if (l->Direction == (d ^ 1))
      return l->Vertex;
  return -1;
}

double RunEnds::Distance(std::int64_t a, std::int64_t b) const
{
  const Point3& p = this->Arrangement.Position(a);
  const Point3& q = this->Arrangement.Position(b);
  return std::sqrt(
    (p[0] - q[0]) * (p[0] - q[0]) + (p[1] - q[1]) * (p[1] - q[1]) + (p[2] - q[2]) * (p[2] - q[2]));
}

void RunEnds::Rescale(double chance, int t, int d, const std::vector<int>& candidates,
  std::vector<double>& weight) const
{
  if (chance < 0)
    return;
  // Kept soft: a run the example never ends here can still end where nothing else fits.
  chance = std::min(0.98, std::max(0.02, chance));
  double ending = 0, going = 0;
  for (std::size_t k = 0; k < candidates.size(); ++k)
    ((this->Plan.EdgeTypes(d, candidates[k]) >> t) & 1u ? going : ending) += weight[k];
  if (!(ending > 0) || !(going > 0))
    return;
  const double total = ending + going;
  for (std::size_t k = 0; k < candidates.size(); ++k)
    weight[k] *= (this->Plan.EdgeTypes(d, candidates[k]) >> t) & 1u ? (1 - chance) * total / going
                                                                    : chance * total / ending;
}

} // namespace detail
} // namespace msynth
