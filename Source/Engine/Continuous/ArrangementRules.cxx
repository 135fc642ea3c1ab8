// SPDX-License-Identifier: BSD-3-Clause
// The continuous solver's rules (D§4.5.5: eval(a, d) = eval(b, −d) compiled into a
// CompatibilityRelation), the independent edge-by-edge check of a labelling, and the sites of
// non-trihedral labels (TVCG §4.4). The solver itself is ContinuousSynthesis.cxx.
#include "Continuous/ContinuousSynthesis.h"

#include "Continuous/FeatureWidth.h"
#include "Core/Error.h"
#include "Core/Index.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>

namespace msynth
{
ArrangementRules::ArrangementRules(
  const PolyhedralAnalysis& analysis, const PlaneArrangement& arrangement)
  : Arrangement(arrangement)
{
  const PlaneFamilySet& set = arrangement.Families();
  if (set.AllNormals() != analysis.Families().AllNormals())
  {
    throw Error("the plane arrangement was built for other plane families than the example's");
  }
  const int k = analysis.NumberOfLabels();
  const int directions = arrangement.NumberOfDirections();
  this->Allocate(k, std::max(directions, 1));
  this->Empty = analysis.Find(NeighbourhoodLabel::Constant(0));
  if (this->Empty < 0)
  {
    throw Error("the example has no empty space around it");
  }
  for (const auto& info : analysis.Labels())
  {
    std::uint64_t mask = 0;
    for (int f : info.Label.Families)
    {
      mask |= std::uint64_t(1) << f;
    }
    this->LabelFamilies.push_back(mask);
  }
  this->KeepCornersApart(analysis);
  std::map<NeighbourhoodLabel, int> ids;
  const int emptyId = ids.emplace(NeighbourhoodLabel::Constant(0), 0).first->second;
  this->Evaluations.resize(ToIndex(directions) * k);
  for (int d = 0; d < directions; ++d)
  {
    for (int a = 0; a < k; ++a)
    {
      const NeighbourhoodLabel e = analysis.Label(a).Label.Evaluate(set, arrangement.Direction(d));
      const int id = ids.emplace(e, static_cast<int>(ids.size())).first->second;
      this->Evaluations[ToIndex(d) * k + a] = id;
    }
  }
  const int w = this->Words();
  this->EmptyToward.assign(ToIndex(directions) * w, 0);
  std::vector<std::vector<int>> bucket(ids.size());
  for (int d = 0; d < directions; ++d)
  {
    // Labels b at the far end of an edge along d see it along the opposite class d ^ 1.
    for (auto& b : bucket)
    {
      b.clear();
    }
    for (int b = 0; b < k; ++b)
    {
      bucket[ToIndex(this->EvaluationId(d ^ 1, b))].push_back(b);
    }
    for (int a = 0; a < k; ++a)
    {
      const int id = this->EvaluationId(d, a);
      for (int b : bucket[ToIndex(id)])
      {
        this->AllowOne(d, a, b);
      }
      if (id == emptyId)
      {
        this->EmptyToward[ToIndex(d) * w + (a >> 6)] |= std::uint64_t(1) << (a & 63);
      }
    }
  }
  this->Finish();
}

void ArrangementRules::KeepCornersApart(const PolyhedralAnalysis& analysis)
{
  // Slivers: where a plane of another family passes within a fraction of the smallest spacing of
  // a vertex without going through it (planes of directions of large integers nearly meet), a
  // corner there may be that close to a face, edge or corner on the other plane (NarrowCorners
  // finds those of a model). Within a thousandth of a spacing, where the arrangement's own faces
  // are slivers, the model's surface does not pass at all (only volume labels), so no polygon of
  // the mesh has an edge shorter than that.
  const PlaneArrangement& arr = this->Arrangement;
  const PlaneFamilySet& set = arr.Families();
  const ArrangementParameters& p = arr.Parameters();
  const int m = set.Size();
  double smallest = 0;
  std::vector<double> world(ToIndex(m));
  for (int f = 0; f < m; ++f)
  {
    world[ToIndex(f)] = p.Spacing(set, f);
    smallest = f == 0 ? world[0] : std::min(smallest, world[ToIndex(f)]);
  }
  for (int a = 0; a < analysis.NumberOfLabels(); ++a)
  {
    this->LabelKinds.push_back(analysis.Label(a).Kind);
    if (analysis.Label(a).Kind != FeatureKind::Volume)
      this->SurfaceLabels.push_back(a);
  }
  this->Smallest = smallest;
  this->Clearance.assign(ToIndex(arr.NumberOfVertices()), 0);
  if (!(smallest > 0))
    return;
  for (std::int64_t v = 0; v < arr.NumberOfVertices(); ++v)
  {
    const Point3& q = arr.Position(v);
    double nearest = HUGE_VAL; // the nearest plane not through v
    for (int f = 0; f < m; ++f)
    {
      if ((arr.FamilyMask(v) >> f) & 1u)
        continue;
      const IntVec3& n = set.Normal(f);
      double x = 0;
      for (int c = 0; c < 3; ++c)
        x += static_cast<double>(n[ToIndex(c)]) * (q[c] - p.Origin[c]) / p.Quantum;
      const double s = (x - static_cast<double>(p.Offsets[ToIndex(f)])) /
        static_cast<double>(p.Spacings[ToIndex(f)]);
      nearest = std::min(nearest, std::abs(s - std::round(s)) * world[ToIndex(f)]);
    }
    this->Clearance[ToIndex(v)] = nearest < SurfaceClearance * smallest ? 2
      : nearest < MinimumFeatureFraction * smallest                     ? 1
                                                                        : 0;
  }
}

std::vector<std::int64_t> ArrangementRules::NarrowCorners(
  const std::vector<std::int32_t>& labels) const
{
  // A corner (a vertex label) within the fraction of a spacing of a plane g not through it is
  // narrow when a vertex near it on that plane has a type change across g (a face, edge or
  // corner on g). Near: within a few of the largest spacings, the size of the arrangement's
  // faces, so a face of g passing close to the corner has such a vertex (more removes a part
  // that was wide enough, never keeps a narrow one the search misses on the faces' vertices).
  std::vector<std::int64_t> out;
  const PlaneArrangement& arr = this->Arrangement;
  const PlaneFamilySet& set = arr.Families();
  const ArrangementParameters& p = arr.Parameters();
  const double apart = MinimumFeatureFraction * this->Smallest;
  double largest = 0;
  for (int f = 0; f < set.Size(); ++f)
    largest = std::max(largest, p.Spacing(set, f));
  const double reach = 3 * largest;
  const auto kind = [&](std::int64_t v) { return this->LabelKinds[ToIndex(labels[ToIndex(v)])]; };
  const auto cellOf = [&](const Point3& q)
  {
    return std::array<std::int64_t, 3>{ static_cast<std::int64_t>(std::floor(q[0] / reach)),
      static_cast<std::int64_t>(std::floor(q[1] / reach)),
      static_cast<std::int64_t>(std::floor(q[2] / reach)) };
  };
  std::map<std::array<std::int64_t, 3>, std::vector<std::int64_t>> grid;
  for (std::int64_t v = 0; v < arr.NumberOfVertices(); ++v)
    if (kind(v) != FeatureKind::Volume)
      grid[cellOf(arr.Position(v))].push_back(v);
  for (std::int64_t v = 0; v < arr.NumberOfVertices(); ++v)
  {
    if (this->Clearance[ToIndex(v)] != 1 || kind(v) != FeatureKind::Vertex)
      continue;
    const Point3& q = arr.Position(v);
    const auto c = cellOf(q);
    bool narrow = false;
    for (std::int64_t dx = -1; dx <= 1 && !narrow; ++dx)
      for (std::int64_t dy = -1; dy <= 1 && !narrow; ++dy)
        for (std::int64_t dz = -1; dz <= 1 && !narrow; ++dz)
        {
          const auto it = grid.find({ c[0] + dx, c[1] + dy, c[2] + dz });
          if (it == grid.end())
            continue;
          for (std::int64_t u : it->second)
          {
            const Point3& r = arr.Position(u);
            const std::uint64_t across =
              this->LabelFamilies[ToIndex(labels[ToIndex(u)])] & ~arr.FamilyMask(v);
            for (int g = 0; g < set.Size() && !narrow && across != 0; ++g)
            {
              if (!((across >> g) & 1u))
                continue;
              const IntVec3& n = set.Normal(g);
              const double len =
                std::sqrt(static_cast<double>(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]));
              double d = 0;
              for (int k = 0; k < 3; ++k)
                d += static_cast<double>(n[ToIndex(k)]) * (q[k] - r[k]);
              narrow = std::abs(d) / len < apart;
            }
            if (narrow)
              break;
          }
        }
    if (narrow)
      out.push_back(v);
  }
  return out;
}

void ArrangementRules::InitialDomain(std::int64_t v, std::uint64_t* out, int seamAxes) const
{
  const int w = this->Words();
  std::fill(out, out + w, 0);
  const std::uint64_t mask = this->Arrangement.FamilyMask(v);
  for (int a = 0; a < this->NumberOfLabels(); ++a)
  {
    if ((this->LabelFamilies[ToIndex(a)] & ~mask) == 0)
    {
      out[a >> 6] |= std::uint64_t(1) << (a & 63);
    }
  }
  if (this->Clearance[ToIndex(v)] == 2)
    for (int a : this->SurfaceLabels)
      out[a >> 6] &= ~(std::uint64_t(1) << (a & 63));
  for (const auto* l = this->Arrangement.LinksBegin(v); l != this->Arrangement.LinksEnd(v); ++l)
  {
    bool acrossSeam = false;
    for (int a = 0; a < 3; ++a)
      acrossSeam = acrossSeam ||
        (((seamAxes >> a) & 1) && this->Arrangement.Direction(l->Direction)[ToIndex(a)] > 0);
    if (l->Vertex < 0 && !acrossSeam)
    {
      const std::uint64_t* e = this->EmptyToward.data() + ToIndex(l->Direction) * w;
      for (int i = 0; i < w; ++i)
      {
        out[i] &= e[i];
      }
    }
  }
}

int ArrangementRules::InitialCount(std::int64_t v) const
{
  std::vector<std::uint64_t> bits(ToIndex(this->Words()));
  this->InitialDomain(v, bits.data());
  int n = 0;
  for (auto b : bits)
  {
    n += __builtin_popcountll(b);
  }
  return n;
}

std::vector<NonTrihedralSites> FindNonTrihedralSites(
  const PolyhedralAnalysis& analysis, const PlaneArrangement& arrangement)
{
  std::vector<NonTrihedralSites> out;
  for (int a = 0; a < analysis.NumberOfLabels(); ++a)
  {
    const auto& info = analysis.Label(a);
    if (info.Kind != FeatureKind::Vertex ||
      info.Label.Families.size() < (analysis.Planar() ? 3u : 4u))
      continue;
    std::uint64_t mask = 0;
    for (int f : info.Label.Families)
      mask |= std::uint64_t(1) << f;
    NonTrihedralSites s;
    s.Label = a;
    s.Planes = static_cast<int>(info.Label.Families.size());
    for (std::int64_t v = 0; v < arrangement.NumberOfVertices(); ++v)
      s.Sites += (arrangement.FamilyMask(v) & mask) == mask ? 1 : 0;
    out.push_back(s);
  }
  return out;
}

std::string CheckArrangementLabels(const PolyhedralAnalysis& analysis,
  const PlaneArrangement& arrangement, const std::vector<std::int32_t>& labels)
{
  const PlaneFamilySet& set = arrangement.Families();
  const std::int64_t n = arrangement.NumberOfVertices();
  if (static_cast<std::int64_t>(labels.size()) != n)
  {
    return "there are " + std::to_string(labels.size()) + " labels for " + std::to_string(n) +
      " vertices";
  }
  const NeighbourhoodLabel empty = NeighbourhoodLabel::Constant(0);
  for (std::int64_t v = 0; v < n; ++v)
  {
    const int a = labels[ToIndex(v)];
    if (a < 0 || a >= analysis.NumberOfLabels())
    {
      return "vertex " + std::to_string(v) + " has no example label";
    }
    const NeighbourhoodLabel& la = analysis.Label(a).Label;
    for (int f : la.Families)
    {
      if (!((arrangement.FamilyMask(v) >> f) & 1u))
      {
        return "vertex " + std::to_string(v) +
          " has a label on a plane that does not pass through it";
      }
    }
    for (const auto* l = arrangement.LinksBegin(v); l != arrangement.LinksEnd(v); ++l)
    {
      const IntVec3& d = arrangement.Direction(l->Direction);
      const NeighbourhoodLabel here = la.Evaluate(set, d);
      if (l->Vertex < 0)
      {
        if (here != empty)
        {
          return "vertex " + std::to_string(v) + " is not empty toward the outside of the box";
        }
        continue;
      }
      const NeighbourhoodLabel& lb = analysis.Label(labels[ToIndex(l->Vertex)]).Label;
      if (here != lb.Evaluate(set, { -d[0], -d[1], -d[2] }))
      {
        return "vertices " + std::to_string(v) + " and " + std::to_string(l->Vertex) +
          " disagree about the edge between them";
      }
    }
  }
  return {};
}

} // namespace msynth
