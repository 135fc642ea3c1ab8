// SPDX-License-Identifier: BSD-3-Clause
#include "Continuous/PlaneArrangement.h"

#include "Continuous/ArrangementBuilder.h"

#include "Continuous/PolyhedralAnalysis.h"
#include "Core/Error.h"

#include "Continuous/Point3Math.h"
#include "Core/Index.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>
#include <set>
#include <string>

namespace msynth
{
namespace
{
/// Largest g with every value within tolerance of a multiple of g (Euclid on the gaps).
double ApproximateGcd(std::vector<double> values, double tolerance)
{
  std::sort(values.begin(), values.end());
  double g = 0;
  for (std::size_t i = 1; i < values.size(); ++i)
  {
    double h = values[i] - values[i - 1];
    if (h <= tolerance)
    {
      continue;
    }
    if (g == 0)
    {
      g = h;
      continue;
    }
    double a = std::max(g, h), b = std::min(g, h);
    while (b > tolerance)
    {
      double r = std::fmod(a, b);
      if (b - r <= tolerance)
      {
        r = 0;
      }
      a = b;
      b = r;
    }
    g = a;
  }
  return g;
}

/// A family's spacing in exact units: the approximate GCD of its faces' positions @p values and
/// its extremes @p vmin and @p vmax (faces spread by @p spread), at least 1/256 of the extent.
double FamilySpacing(std::vector<double> values, double vmin, double vmax, double spread)
{
  const double extent = vmax - vmin;
  const double tolerance = 1e-4 * extent + 0.5 + 2 * spread;
  const double faces = ApproximateGcd(values, tolerance);
  values.push_back(vmin);
  values.push_back(vmax);
  double g = ApproximateGcd(values, tolerance);
  // Extremes that are corners off the faces' lattice (an output model of a polygon with sides of
  // any length, used as an example) would collapse the spacing: the faces' own spacing then.
  if (g < extent / 256.0 && faces >= extent / 256.0)
    g = faces;
  return std::max(g, extent / 256.0);
}

} // namespace

double ArrangementParameters::Spacing(const PlaneFamilySet& families, int family) const
{
  const IntVec3& n = families.Normal(family);
  const double len = std::sqrt(static_cast<double>(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]));
  return static_cast<double>(this->Spacings.at(ToIndex(family))) * this->Quantum / len;
}

namespace
{
/// Per family, its position through the first corner of the example where four or more families'
/// faces meet (the corner rounded to the lattice of @p quantum from @p lo), or NaN.
std::vector<double> CornerAnchors(const PolyhedralExample& example,
  const PolyhedralAnalysis& analysis, double quantum, const Point3& lo)
{
  const PlaneFamilySet& set = analysis.Families();
  std::vector<double> anchors(ToIndex(set.Size()), std::nan(""));
  const auto& elements = analysis.Boundary();
  std::map<std::int32_t, std::set<int>> familiesAt; // example point → families of its faces
  for (std::size_t e = 0; e < elements.size(); ++e)
    for (auto i : elements[e].Points)
      familiesAt[i].insert(analysis.ElementFamily()[e]);
  for (const auto& [point, families] : familiesAt)
  {
    if (families.size() < 4)
      continue;
    const Point3& q = example.Points[ToIndex(point)];
    double x[3];
    for (std::size_t c = 0; c < 3; ++c)
      x[c] = std::round((q[c] - lo[c]) / quantum);
    for (int f : families)
    {
      auto& a = anchors[ToIndex(f)];
      if (!std::isnan(a))
        continue; // a family through two such corners keeps the first
      const IntVec3& n = set.Normal(f);
      a = static_cast<double>(n[0]) * x[0] + static_cast<double>(n[1]) * x[1] +
        static_cast<double>(n[2]) * x[2];
    }
  }
  return anchors;
}
} // namespace

namespace
{
/// Checks the requested output size (along the @p dims synthesized axes) and the common plane
/// spacing. @throw Error naming @p where.
void CheckSizeAndSpacing(const std::string& where, const Point3& size, int dims, double spacing)
{
  for (int c = 0; c < dims; ++c)
  {
    if (!(size[c] > 0) || !std::isfinite(size[c]))
    {
      throw Error(where + ": the output size must be positive and finite along every axis");
    }
  }
  if (!(spacing >= 0) || !std::isfinite(spacing))
  {
    throw Error(where + ": the plane spacing must be positive and finite");
  }
}

/// The example's bounding box, @p lo and @p hi. @throw std::out_of_range without points.
void ExampleBounds(const PolyhedralExample& example, Point3& lo, Point3& hi)
{
  lo = example.Points.at(0);
  hi = lo;
  for (const auto& q : example.Points)
  {
    for (int c = 0; c < 3; ++c)
    {
      lo[c] = std::min(lo[c], q[c]);
      hi[c] = std::max(hi[c], q[c]);
    }
  }
}

/// Replaces the derived integer spacings by the per-family @p spacings (world units), given
/// the derived spacings' world lengths @p world. @throw Error naming @p where.
void ApplyFamilySpacings(ArrangementParameters& p, const std::vector<double>& spacings,
  const std::vector<double>& world, const std::string& where)
{
  for (std::size_t f = 0; f < spacings.size(); ++f)
  {
    const double target = spacings[f];
    if (!(target > 0) || !std::isfinite(target))
    {
      throw Error(where + ": plane spacings must be positive and finite");
    }
    const double units = std::floor(target / world[f] * static_cast<double>(p.Spacings[f]) + 0.5);
    if (units > std::ldexp(1.0, 40))
    {
      throw Error(where + ": a plane spacing is too large for exact coordinates");
    }
    p.Spacings[f] = std::max<std::int64_t>(1, static_cast<std::int64_t>(units));
  }
}

/// The output box in lattice units: from 0 to @p size along the @p dims synthesized axes.
/// @throw Error naming @p where when it needs more than 2^40 units.
void SetOutputBox(ArrangementParameters& p, const Point3& size, int dims, const std::string& where)
{
  for (int c = 0; c < 3; ++c)
  {
    p.BoxLow[c] = 0;
    if (c < dims)
    {
      const double units = std::floor(size[c] / p.Quantum + 0.5);
      if (units > std::ldexp(1.0, 40))
      {
        throw Error(where +
          ": the output size is too large for exact coordinates (more than "
          "2^20 example diagonals)");
      }
      p.BoxHigh[c] = static_cast<std::int64_t>(units);
    }
  }
}
} // namespace

ArrangementParameters DefaultArrangementParameters(const PolyhedralExample& example,
  const PolyhedralAnalysis& analysis, const Point3& size, double spacing,
  const std::vector<double>& spacings)
{
  ArrangementParameters p;
  p.Planar = analysis.Planar();
  const int dims = p.Planar ? 2 : 3;
  const std::string where = example.Source.empty() ? "example" : example.Source;
  CheckSizeAndSpacing(where, size, dims, spacing);
  Point3 lo, hi;
  ExampleBounds(example, lo, hi);
  const double diag = point3::Norm(point3::Sub(hi, lo));
  // A power of two, so examples authored on binary fractions land on exact units.
  p.Quantum = std::ldexp(1.0, static_cast<int>(std::floor(std::log2(diag))) - 20);
  p.Origin = lo;
  const PlaneFamilySet& set = analysis.Families();
  const int m = set.Size();
  if (!spacings.empty() && static_cast<int>(spacings.size()) != m)
  {
    throw Error(where + ": " + std::to_string(spacings.size()) + " plane spacings given for " +
      std::to_string(m) + " plane families");
  }
  std::vector<std::vector<double>> values(ToIndex(m));
  std::vector<double> first(ToIndex(m), 0.0);
  const auto& elements = analysis.Boundary();
  const auto valueOf = [&](int f, const Point3& q)
  {
    const IntVec3& n = set.Normal(f);
    const Point3 r = point3::Sub(q, lo);
    return (static_cast<double>(n[0]) * r[0] + static_cast<double>(n[1]) * r[1] +
             static_cast<double>(n[2]) * r[2]) /
      p.Quantum;
  };
  // A face's position along its family's exact normal: the mean over its corners. When the
  // normal was snapped (a direction of large integers), the corners spread a little around it;
  // the spread widens the tolerance of the spacing so it does not split the face's plane.
  std::vector<double> spread(ToIndex(m), 0.0);
  for (std::size_t e = 0; e < elements.size(); ++e)
  {
    const int f = analysis.ElementFamily()[e];
    double v = 0, low = 0, high = 0;
    for (std::size_t k = 0; k < elements[e].Points.size(); ++k)
    {
      const double x = valueOf(f, example.Points[ToIndex(elements[e].Points[k])]);
      v += x;
      low = k == 0 ? x : std::min(low, x);
      high = k == 0 ? x : std::max(high, x);
    }
    v /= static_cast<double>(std::max<std::size_t>(elements[e].Points.size(), 1));
    spread[ToIndex(f)] = std::max(spread[ToIndex(f)], high - low);
    if (values[ToIndex(f)].empty())
    {
      first[ToIndex(f)] = v;
    }
    values[ToIndex(f)].push_back(v);
  }
  std::vector<double> world(ToIndex(m));
  for (int f = 0; f < m; ++f)
  {
    auto& vs = values[ToIndex(f)];
    double vmin = vs.empty() ? 0 : vs[0], vmax = vmin;
    for (const auto& q : example.Points)
    {
      const double v = valueOf(f, q);
      vmin = std::min(vmin, v);
      vmax = std::max(vmax, v);
    }
    const double g = FamilySpacing(vs, vmin, vmax, spread[ToIndex(f)]);
    p.Spacings.push_back(std::max<std::int64_t>(1, std::llround(g)));
    world[ToIndex(f)] = p.Spacing(set, f);
  }
  if (spacings.empty() && spacing > 0 && m > 0)
  {
    // One factor for every family: scale the exact coordinates themselves, so the integer
    // spacings and offsets, and every coincidence of planes, stay exactly as derived.
    p.Quantum *= spacing / *std::min_element(world.begin(), world.end());
  }
  if (!spacings.empty())
  {
    ApplyFamilySpacings(p, spacings, world, where);
  }
  SetOutputBox(p, size, dims, where);
  // Where four or more families meet at a corner of the example (a pyramid's apex, TVCG §4.4),
  // their planes go through that corner's exact lattice point, so they meet there in the output
  // too; with offsets from face means they would miss one another by rounding (and by the
  // snapping of large-integer directions).
  const std::vector<double> anchors = CornerAnchors(example, analysis, p.Quantum, lo);
  for (int f = 0; f < m; ++f)
  {
    const std::int64_t s = p.Spacings[ToIndex(f)];
    const double anchor = anchors[ToIndex(f)];
    const std::int64_t v = std::llround(std::isnan(anchor) ? first[ToIndex(f)] : anchor);
    p.Offsets.push_back(((v % s) + s) % s);
  }
  return p;
}

PlaneArrangement::PlaneArrangement(const PlaneFamilySet& families, ArrangementParameters parameters)
  : Set(families)
  , Params(std::move(parameters))
{
  detail::ArrangementBuilder(this->Set, this->Params).Build(*this);
}

std::vector<int> PlaneArrangement::FamiliesThrough(std::int64_t v) const
{
  std::vector<int> out;
  const std::uint64_t mask = this->FamilyMask(v);
  for (int f = 0; f < this->Set.Size(); ++f)
  {
    if ((mask >> f) & 1u)
    {
      out.push_back(f);
    }
  }
  return out;
}

std::size_t PlaneArrangement::MemoryBytes() const
{
  return this->Positions.capacity() * sizeof(Point3) +
    this->Masks.capacity() * sizeof(std::uint64_t) +
    this->LinkStart.capacity() * sizeof(std::int64_t) + this->Links.capacity() * sizeof(Link) +
    this->Directions.capacity() * sizeof(IntVec3);
}

} // namespace msynth
