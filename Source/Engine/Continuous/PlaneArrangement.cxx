// SPDX-License-Identifier: BSD-3-Clause
#include "Continuous/PlaneArrangement.h"

#include "Continuous/PolyhedralAnalysis.h"
#include "Core/Error.h"

#include "Continuous/Point3Math.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>
#include <string>

namespace msynth
{
namespace
{
using Wide = __int128;

[[noreturn]] void Overflow()
{
  throw Error("plane arrangement: exact coordinates exceed 128-bit integers (the output box is "
              "too large for the example's plane directions)");
}

Wide Mul(Wide a, Wide b)
{
  Wide r;
  if (__builtin_mul_overflow(a, b, &r))
  {
    Overflow();
  }
  return r;
}

Wide Add(Wide a, Wide b)
{
  Wide r;
  if (__builtin_add_overflow(a, b, &r))
  {
    Overflow();
  }
  return r;
}

Wide Abs(Wide a)
{
  return a < 0 ? -a : a;
}

Wide Gcd(Wide a, Wide b)
{
  a = Abs(a);
  b = Abs(b);
  while (b != 0)
  {
    const Wide t = a % b;
    a = b;
    b = t;
  }
  return a;
}

/// Floor of a / b for b > 0.
Wide FloorDiv(Wide a, Wide b)
{
  const Wide q = a / b;
  return (a % b != 0 && a < 0) ? q - 1 : q;
}

Wide CeilDiv(Wide a, Wide b)
{
  return -FloorDiv(-a, b);
}

/// An exact rational point Num / Den with Den > 0, reduced.
struct Exact
{
  std::array<Wide, 3> Num{};
  Wide Den = 1;

  void Reduce()
  {
    if (this->Den < 0)
    {
      this->Den = -this->Den;
      for (auto& v : this->Num)
      {
        v = -v;
      }
    }
    Wide g = Gcd(Gcd(Gcd(this->Num[0], this->Num[1]), this->Num[2]), this->Den);
    if (g > 1)
    {
      for (auto& v : this->Num)
      {
        v /= g;
      }
      this->Den /= g;
    }
  }
};

Wide DotNum(const IntVec3& n, const Exact& x)
{
  return Add(Add(Mul(n[0], x.Num[0]), Mul(n[1], x.Num[1])), Mul(n[2], x.Num[2]));
}

IntVec3 Primitive(IntVec3 d)
{
  const std::int64_t g = std::gcd(std::gcd(std::abs(d[0]), std::abs(d[1])), std::abs(d[2]));
  if (g > 1)
  {
    for (auto& c : d)
    {
      c /= g;
    }
  }
  // Canonical sign: first non-zero component positive.
  for (auto c : d)
  {
    if (c != 0)
    {
      if (c < 0)
      {
        for (auto& e : d)
        {
          e = -e;
        }
      }
      break;
    }
  }
  return d;
}

IntVec3 CrossInt(const IntVec3& a, const IntVec3& b)
{
  return { a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0] };
}

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

} // namespace

double ArrangementParameters::Spacing(const PlaneFamilySet& families, int family) const
{
  const IntVec3& n = families.Normal(family);
  const double len = std::sqrt(static_cast<double>(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]));
  return static_cast<double>(this->Spacings.at(static_cast<std::size_t>(family))) * this->Quantum /
    len;
}

ArrangementParameters DefaultArrangementParameters(const PolyhedralExample& example,
  const PolyhedralAnalysis& analysis, const Point3& size, double spacing,
  const std::vector<double>& spacings)
{
  ArrangementParameters p;
  p.Planar = analysis.Planar();
  const int dims = p.Planar ? 2 : 3;
  const std::string where = example.Source.empty() ? "example" : example.Source;
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
  Point3 lo = example.Points.at(0), hi = lo;
  for (const auto& q : example.Points)
  {
    for (int c = 0; c < 3; ++c)
    {
      lo[c] = std::min(lo[c], q[c]);
      hi[c] = std::max(hi[c], q[c]);
    }
  }
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
  std::vector<std::vector<double>> values(static_cast<std::size_t>(m));
  std::vector<double> first(static_cast<std::size_t>(m), 0.0);
  const auto& elements = analysis.Boundary();
  const auto valueOf = [&](int f, const Point3& q)
  {
    const IntVec3& n = set.Normal(f);
    const Point3 r = point3::Sub(q, lo);
    return (static_cast<double>(n[0]) * r[0] + static_cast<double>(n[1]) * r[1] +
             static_cast<double>(n[2]) * r[2]) /
      p.Quantum;
  };
  for (std::size_t e = 0; e < elements.size(); ++e)
  {
    const int f = analysis.ElementFamily()[e];
    const double v = valueOf(f, example.Points[static_cast<std::size_t>(elements[e].Points[0])]);
    if (values[static_cast<std::size_t>(f)].empty())
    {
      first[static_cast<std::size_t>(f)] = v;
    }
    values[static_cast<std::size_t>(f)].push_back(v);
  }
  std::vector<double> world(static_cast<std::size_t>(m));
  for (int f = 0; f < m; ++f)
  {
    auto& vs = values[static_cast<std::size_t>(f)];
    double vmin = vs.empty() ? 0 : vs[0], vmax = vmin;
    for (const auto& q : example.Points)
    {
      const double v = valueOf(f, q);
      vmin = std::min(vmin, v);
      vmax = std::max(vmax, v);
    }
    vs.push_back(vmin);
    vs.push_back(vmax);
    const double extent = vmax - vmin;
    double g = ApproximateGcd(vs, 1e-4 * extent + 0.5);
    g = std::max(g, extent / 256.0);
    p.Spacings.push_back(std::max<std::int64_t>(1, std::llround(g)));
    world[static_cast<std::size_t>(f)] = p.Spacing(set, f);
  }
  if (spacings.empty() && spacing > 0 && m > 0)
  {
    // One factor for every family: scale the exact coordinates themselves, so the integer
    // spacings and offsets, and every coincidence of planes, stay exactly as derived.
    p.Quantum *= spacing / *std::min_element(world.begin(), world.end());
  }
  if (!spacings.empty())
  {
    for (int f = 0; f < m; ++f)
    {
      const double target = spacings[static_cast<std::size_t>(f)];
      if (!(target > 0) || !std::isfinite(target))
      {
        throw Error(where + ": plane spacings must be positive and finite");
      }
      const double units = std::floor(target / world[static_cast<std::size_t>(f)] *
          static_cast<double>(p.Spacings[static_cast<std::size_t>(f)]) +
        0.5);
      if (units > std::ldexp(1.0, 40))
      {
        throw Error(where + ": a plane spacing is too large for exact coordinates");
      }
      p.Spacings[static_cast<std::size_t>(f)] =
        std::max<std::int64_t>(1, static_cast<std::int64_t>(units));
    }
  }
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
  for (int f = 0; f < m; ++f)
  {
    const std::int64_t s = p.Spacings[static_cast<std::size_t>(f)];
    const std::int64_t v = std::llround(first[static_cast<std::size_t>(f)]);
    p.Offsets.push_back(((v % s) + s) % s);
  }
  return p;
}

PlaneArrangement::PlaneArrangement(const PlaneFamilySet& families, ArrangementParameters parameters)
  : Set(families)
  , Params(std::move(parameters))
{
  const int m = this->Set.Size();
  const int dim = this->Params.Planar ? 2 : 3;
  if (m > 64)
  {
    throw Error("plane arrangement: more than 64 plane families");
  }
  if (static_cast<int>(this->Params.Offsets.size()) != m ||
    static_cast<int>(this->Params.Spacings.size()) != m)
  {
    throw Error("plane arrangement: one offset and one spacing per family are needed");
  }
  for (int f = 0; f < m; ++f)
  {
    if (this->Params.Spacings[static_cast<std::size_t>(f)] <= 0)
    {
      throw Error("plane arrangement: spacings must be positive");
    }
  }
  for (int c = 0; c < 3; ++c)
  {
    if (this->Params.BoxHigh[c] < this->Params.BoxLow[c])
    {
      throw Error("plane arrangement: the output box is empty");
    }
  }
  const IntVec3& lo = this->Params.BoxLow;
  const IntVec3& hi = this->Params.BoxHigh;
  const auto normal = [&](int f) -> const IntVec3& { return this->Set.Normal(f); };
  const auto offset = [&](int f)
  { return static_cast<Wide>(this->Params.Offsets[static_cast<std::size_t>(f)]); };
  const auto spacingOf = [&](int f)
  { return static_cast<Wide>(this->Params.Spacings[static_cast<std::size_t>(f)]); };

  // Range of plane indices of each family that meet the box.
  std::vector<std::array<Wide, 2>> range(static_cast<std::size_t>(m));
  for (int f = 0; f < m; ++f)
  {
    Wide vmin = 0, vmax = 0;
    for (int c = 0; c < 3; ++c)
    {
      const Wide a = Mul(normal(f)[c], lo[c]), b = Mul(normal(f)[c], hi[c]);
      vmin = Add(vmin, std::min(a, b));
      vmax = Add(vmax, std::max(a, b));
    }
    range[static_cast<std::size_t>(f)] = { CeilDiv(vmin - offset(f), spacingOf(f)),
      FloorDiv(vmax - offset(f), spacingOf(f)) };
  }

  // Generating tuples: dim families with independent normals. Each vertex is generated only
  // by the lexicographically first independent tuple among the families through it.
  const auto determinant = [&](const int* t) -> Wide
  {
    if (dim == 2)
    {
      return Mul(normal(t[0])[0], normal(t[1])[1]) - Mul(normal(t[0])[1], normal(t[1])[0]);
    }
    const IntVec3 c = CrossInt(normal(t[1]), normal(t[2]));
    return Add(
      Add(Mul(normal(t[0])[0], c[0]), Mul(normal(t[0])[1], c[1])), Mul(normal(t[0])[2], c[2]));
  };
  struct Tuple
  {
    std::array<int, 3> F{};
    std::array<Wide, 3> Lo{};
    std::array<Wide, 3> Count{};
    std::size_t Base = 0; // into Dense
  };
  std::vector<Tuple> tuples;
  std::map<std::array<int, 3>, std::size_t> tupleIndex;
  Wide denseSize = 0;
  {
    std::array<int, 3> t{ { 0, 0, 0 } };
    const auto consider = [&]()
    {
      if (determinant(t.data()) == 0)
      {
        return;
      }
      Tuple tu;
      tu.F = t;
      Wide cells = 1;
      for (int i = 0; i < dim; ++i)
      {
        const auto& r = range[static_cast<std::size_t>(t[static_cast<std::size_t>(i)])];
        tu.Lo[static_cast<std::size_t>(i)] = r[0];
        tu.Count[static_cast<std::size_t>(i)] = std::max<Wide>(0, r[1] - r[0] + 1);
        cells = Mul(cells, tu.Count[static_cast<std::size_t>(i)]);
      }
      tu.Base = static_cast<std::size_t>(denseSize);
      denseSize = Add(denseSize, cells);
      tupleIndex[t] = tuples.size();
      tuples.push_back(tu);
    };
    for (t[0] = 0; t[0] < m; ++t[0])
    {
      for (t[1] = t[0] + 1; t[1] < m; ++t[1])
      {
        if (dim == 2)
        {
          t[2] = -1;
          consider();
          continue;
        }
        for (t[2] = t[1] + 1; t[2] < m; ++t[2])
        {
          consider();
        }
      }
    }
  }
  // Candidates are the plane-index boxes of the tuples; most lie in the output box.
  const Wide maxCandidates = std::max<Wide>(Wide(8) * this->Params.MaxVertices, Wide(10000000));
  if (denseSize > maxCandidates || denseSize > Wide(2000000000))
  {
    throw Error("plane arrangement: about " +
      std::to_string(static_cast<long long>(std::min<Wide>(denseSize, Wide(1) << 62))) +
      " candidate vertices, more than the limit of " + std::to_string(this->Params.MaxVertices) +
      " vertices allows; use a smaller box or a larger "
      "spacing");
  }
  std::vector<std::int32_t> dense(static_cast<std::size_t>(denseSize), -1);

  // Solves the tuple's planes for their intersection point.
  const auto solve = [&](const Tuple& tu, const std::array<Wide, 3>& value) -> Exact
  {
    Exact x;
    const int* f = tu.F.data();
    if (dim == 2)
    {
      const IntVec3& a = normal(f[0]);
      const IntVec3& b = normal(f[1]);
      x.Den = Mul(a[0], b[1]) - Mul(a[1], b[0]);
      x.Num[0] = Mul(value[0], b[1]) - Mul(value[1], a[1]);
      x.Num[1] = Mul(value[1], a[0]) - Mul(value[0], b[0]);
      x.Num[2] = 0;
    }
    else
    {
      // X = (v0 (n1×n2) + v1 (n2×n0) + v2 (n0×n1)) / det.
      const IntVec3 c0 = CrossInt(normal(f[1]), normal(f[2]));
      const IntVec3 c1 = CrossInt(normal(f[2]), normal(f[0]));
      const IntVec3 c2 = CrossInt(normal(f[0]), normal(f[1]));
      for (int c = 0; c < 3; ++c)
      {
        x.Num[static_cast<std::size_t>(c)] =
          Add(Add(Mul(value[0], c0[c]), Mul(value[1], c1[c])), Mul(value[2], c2[c]));
      }
      x.Den = determinant(f);
    }
    x.Reduce();
    return x;
  };
  const auto inBox = [&](const Exact& x)
  {
    for (int c = 0; c < dim; ++c)
    {
      if (x.Num[static_cast<std::size_t>(c)] < Mul(lo[c], x.Den) ||
        x.Num[static_cast<std::size_t>(c)] > Mul(hi[c], x.Den))
      {
        return false;
      }
    }
    return true;
  };
  // Families with a plane through x, and the plane index of each (valid where the bit is set).
  std::vector<Wide> planeIndex(static_cast<std::size_t>(m));
  const auto familiesThrough = [&](const Exact& x)
  {
    std::uint64_t mask = 0;
    for (int f = 0; f < m; ++f)
    {
      const Wide r = DotNum(normal(f), x) - Mul(offset(f), x.Den);
      const Wide s = Mul(spacingOf(f), x.Den);
      if (r % s == 0)
      {
        mask |= std::uint64_t(1) << f;
        planeIndex[static_cast<std::size_t>(f)] = r / s;
      }
    }
    return mask;
  };
  const auto firstTuple = [&](std::uint64_t mask) -> const Tuple*
  {
    std::vector<int> fs;
    for (int f = 0; f < m; ++f)
    {
      if ((mask >> f) & 1u)
      {
        fs.push_back(f);
      }
    }
    const int k = static_cast<int>(fs.size());
    std::array<int, 3> t{ { -1, -1, -1 } };
    for (int a = 0; a < k; ++a)
    {
      for (int b = a + 1; b < k; ++b)
      {
        if (dim == 2)
        {
          t = { { fs[static_cast<std::size_t>(a)], fs[static_cast<std::size_t>(b)], -1 } };
          if (determinant(t.data()) != 0)
          {
            return &tuples[tupleIndex.at(t)];
          }
          continue;
        }
        for (int c = b + 1; c < k; ++c)
        {
          t = { { fs[static_cast<std::size_t>(a)], fs[static_cast<std::size_t>(b)],
            fs[static_cast<std::size_t>(c)] } };
          if (determinant(t.data()) != 0)
          {
            return &tuples[tupleIndex.at(t)];
          }
        }
      }
    }
    return nullptr;
  };
  const auto denseSlot = [&](const Tuple& tu) -> std::size_t
  {
    Wide idx = 0;
    for (int i = 0; i < dim; ++i)
    {
      const Wide c = planeIndex[static_cast<std::size_t>(tu.F[static_cast<std::size_t>(i)])] -
        tu.Lo[static_cast<std::size_t>(i)];
      idx = idx * tu.Count[static_cast<std::size_t>(i)] + c;
    }
    return tu.Base + static_cast<std::size_t>(idx);
  };

  // 1. Vertices.
  std::vector<Exact> exact;
  std::vector<std::uint64_t> masks;
  for (const Tuple& tu : tuples)
  {
    std::array<Wide, 3> c{ { 0, 0, 0 } };
    std::array<Wide, 3> value{ { 0, 0, 0 } };
    const Wide n2 = dim == 3 ? tu.Count[2] : 1;
    for (c[0] = 0; c[0] < tu.Count[0]; ++c[0])
    {
      for (c[1] = 0; c[1] < tu.Count[1]; ++c[1])
      {
        for (c[2] = 0; c[2] < n2; ++c[2])
        {
          for (int i = 0; i < dim; ++i)
          {
            const int f = tu.F[static_cast<std::size_t>(i)];
            value[static_cast<std::size_t>(i)] = Add(offset(f),
              Mul(
                tu.Lo[static_cast<std::size_t>(i)] + c[static_cast<std::size_t>(i)], spacingOf(f)));
          }
          const Exact x = solve(tu, value);
          if (!inBox(x))
          {
            continue;
          }
          const std::uint64_t mask = familiesThrough(x);
          if (firstTuple(mask) != &tu)
          {
            continue;
          }
          if (static_cast<std::int64_t>(exact.size()) >= this->Params.MaxVertices)
          {
            throw Error("plane arrangement: more than " + std::to_string(this->Params.MaxVertices) +
              " vertices; use a smaller box or a larger spacing");
          }
          dense[denseSlot(tu)] = static_cast<std::int32_t>(exact.size());
          exact.push_back(x);
          masks.push_back(mask);
        }
      }
    }
  }

  // 2. Scan-line order: by z, then y, then x (exactly), so ids follow the solver's sweep.
  const std::size_t n = exact.size();
  std::vector<std::int32_t> order(n);
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(),
    [&](std::int32_t a, std::int32_t b)
    {
      const Exact& p = exact[static_cast<std::size_t>(a)];
      const Exact& q = exact[static_cast<std::size_t>(b)];
      for (int c = 2; c >= 0; --c)
      {
        const Wide l = Mul(p.Num[static_cast<std::size_t>(c)], q.Den);
        const Wide r = Mul(q.Num[static_cast<std::size_t>(c)], p.Den);
        if (l != r)
        {
          return l < r;
        }
      }
      return false;
    });
  std::vector<std::int32_t> rank(n);
  for (std::size_t i = 0; i < n; ++i)
  {
    rank[static_cast<std::size_t>(order[i])] = static_cast<std::int32_t>(i);
  }
  for (auto& id : dense)
  {
    if (id >= 0)
    {
      id = rank[static_cast<std::size_t>(id)];
    }
  }
  {
    std::vector<Exact> sortedExact(n);
    std::vector<std::uint64_t> sortedMasks(n);
    for (std::size_t i = 0; i < n; ++i)
    {
      sortedExact[i] = exact[static_cast<std::size_t>(order[i])];
      sortedMasks[i] = masks[static_cast<std::size_t>(order[i])];
    }
    exact.swap(sortedExact);
    this->Masks.swap(sortedMasks);
  }
  this->Positions.resize(n);
  for (std::size_t i = 0; i < n; ++i)
  {
    for (int c = 0; c < 3; ++c)
    {
      this->Positions[i][static_cast<std::size_t>(c)] =
        this->Params.Origin[static_cast<std::size_t>(c)] +
        this->Params.Quantum * static_cast<double>(exact[i].Num[static_cast<std::size_t>(c)]) /
          static_cast<double>(exact[i].Den);
    }
  }

  // 3. Direction classes: every line direction of the arrangement, both ways.
  std::map<IntVec3, int> directionIndex;
  const auto lineDirection = [&](int a, int b) -> IntVec3
  {
    if (dim == 2)
    {
      const IntVec3& na = normal(a);
      return Primitive({ -na[1], na[0], 0 });
    }
    return Primitive(CrossInt(normal(a), normal(b)));
  };
  for (int a = 0; a < m; ++a)
  {
    for (int b = dim == 2 ? a : a + 1; b < (dim == 2 ? a + 1 : m); ++b)
    {
      const IntVec3 d = lineDirection(a, b);
      if (d == IntVec3{ 0, 0, 0 } || directionIndex.count(d))
      {
        continue;
      }
      directionIndex[d] = static_cast<int>(this->Directions.size());
      this->Directions.push_back(d);
      this->Directions.push_back({ -d[0], -d[1], -d[2] });
    }
  }

  // 4. Links: from each vertex both ways along every line through it to the next vertex.
  this->LinkStart.assign(n + 1, 0);
  std::vector<int> lines;
  for (std::size_t v = 0; v < n; ++v)
  {
    const Exact& x = exact[v];
    const std::uint64_t mask = this->Masks[v];
    lines.clear();
    for (int a = 0; a < m; ++a)
    {
      if (!((mask >> a) & 1u))
      {
        continue;
      }
      for (int b = dim == 2 ? a : a + 1; b < (dim == 2 ? a + 1 : m); ++b)
      {
        if (!((mask >> b) & 1u))
        {
          continue;
        }
        const IntVec3 d = lineDirection(a, b);
        if (d == IntVec3{ 0, 0, 0 })
        {
          continue;
        }
        const int k = directionIndex.at(d);
        if (std::find(lines.begin(), lines.end(), k) == lines.end())
        {
          lines.push_back(k);
        }
      }
    }
    std::sort(lines.begin(), lines.end());
    for (int k : lines)
    {
      for (int sign = 0; sign < 2; ++sign)
      {
        const int dc = k + sign;
        const IntVec3& d = this->Directions[static_cast<std::size_t>(dc)];
        // Nearest crossing t = tn / td > 0 with another family's plane.
        Wide bestN = -1, bestD = 1;
        for (int f = 0; f < m; ++f)
        {
          const Wide s = static_cast<Wide>(normal(f)[0]) * d[0] +
            static_cast<Wide>(normal(f)[1]) * d[1] + static_cast<Wide>(normal(f)[2]) * d[2];
          if (s == 0)
          {
            continue;
          }
          const Wide value = DotNum(normal(f), x) - Mul(offset(f), x.Den); // relative, × Den
          const Wide step = Mul(spacingOf(f), x.Den);
          const Wide c = s > 0 ? FloorDiv(value, step) + 1 : CeilDiv(value, step) - 1;
          // t = (c·S·Den − value) / (Den · s)
          Wide tn = Mul(c, step) - value;
          Wide td = Mul(x.Den, s);
          if (td < 0)
          {
            tn = -tn;
            td = -td;
          }
          if (bestN < 0 || Mul(tn, bestD) < Mul(bestN, td))
          {
            bestN = tn;
            bestD = td;
          }
        }
        std::int32_t target = -1;
        if (bestN > 0)
        {
          Exact y;
          for (int c = 0; c < 3; ++c)
          {
            y.Num[static_cast<std::size_t>(c)] =
              Add(Mul(x.Num[static_cast<std::size_t>(c)], bestD), Mul(Mul(bestN, d[c]), x.Den));
          }
          y.Den = Mul(x.Den, bestD);
          y.Reduce();
          if (inBox(y))
          {
            const Tuple* tu = firstTuple(familiesThrough(y));
            if (!tu)
            {
              throw Error("plane arrangement: internal error (a crossing is not a vertex)");
            }
            target = dense[denseSlot(*tu)];
            if (target < 0)
            {
              throw Error("plane arrangement: internal error (a vertex was not generated)");
            }
          }
        }
        this->Links.push_back({ target, static_cast<std::int32_t>(dc) });
        if (target < 0)
        {
          ++this->OuterEdges;
        }
        else if (static_cast<std::size_t>(target) > v)
        {
          ++this->InnerEdges;
        }
      }
    }
    this->LinkStart[v + 1] = static_cast<std::int64_t>(this->Links.size());
  }
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
