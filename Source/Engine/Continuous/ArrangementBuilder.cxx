// SPDX-License-Identifier: BSD-3-Clause
#include "Continuous/ArrangementBuilder.h"

#include "Core/Error.h"
#include "Core/Index.h"
#include "Core/ParallelChunks.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <numeric>
#include <string>

namespace msynth
{
namespace detail
{

ArrangementBuilder::ArrangementBuilder(
  const PlaneFamilySet& set, const ArrangementParameters& params)
  : Set(set)
  , Params(params)
  , M(set.Size())
  , Dim(params.Planar ? 2 : 3)
{
}

void ArrangementBuilder::Build(PlaneArrangement& out)
{
  this->CheckParameters();
  this->FindPlaneRanges();
  this->ListTuples();
  this->GenerateVertices();
  this->NumberInScanLineOrder(out);
  this->ListDirections(out);
  this->LinkVertices(out);
}

void ArrangementBuilder::CheckParameters() const
{
  if (this->M > 64)
  {
    throw Error("plane arrangement: more than 64 plane families");
  }
  if (static_cast<int>(this->Params.Offsets.size()) != this->M ||
    static_cast<int>(this->Params.Spacings.size()) != this->M)
  {
    throw Error("plane arrangement: one offset and one spacing per family are needed");
  }
  for (int f = 0; f < this->M; ++f)
  {
    if (this->Params.Spacings[ToIndex(f)] <= 0)
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
}

void ArrangementBuilder::FindPlaneRanges()
{
  const IntVec3& lo = this->Params.BoxLow;
  const IntVec3& hi = this->Params.BoxHigh;
  this->Range.resize(ToIndex(this->M));
  for (int f = 0; f < this->M; ++f)
  {
    Wide vmin = 0, vmax = 0;
    for (int c = 0; c < 3; ++c)
    {
      const Wide a = Mul(this->Normal(f)[c], lo[c]), b = Mul(this->Normal(f)[c], hi[c]);
      vmin = Add(vmin, std::min(a, b));
      vmax = Add(vmax, std::max(a, b));
    }
    this->Range[ToIndex(f)] = { CeilDiv(vmin - this->Offset(f), this->SpacingOf(f)),
      FloorDiv(vmax - this->Offset(f), this->SpacingOf(f)) };
  }
}

Wide ArrangementBuilder::Determinant(const int* t) const
{
  if (this->Dim == 2)
  {
    return Mul(this->Normal(t[0])[0], this->Normal(t[1])[1]) -
      Mul(this->Normal(t[0])[1], this->Normal(t[1])[0]);
  }
  const IntVec3 c = CrossInt(this->Normal(t[1]), this->Normal(t[2]));
  return Add(Add(Mul(this->Normal(t[0])[0], c[0]), Mul(this->Normal(t[0])[1], c[1])),
    Mul(this->Normal(t[0])[2], c[2]));
}

// Generating tuples: Dim families with independent normals. Each vertex is generated only by
// the lexicographically first independent tuple among the families through it.
void ArrangementBuilder::ListTuples()
{
  Wide rows = 0, candidates = 0;
  double fewest = 0; // the vertices there must be, about
  this->TupleAt.assign(ToIndex(this->M) * ToIndex(this->M) * ToIndex(this->M), -1);
  std::array<int, 3> t{ { 0, 0, 0 } };
  const auto consider = [&]()
  {
    if (this->Determinant(t.data()) == 0)
    {
      return;
    }
    Tuple tu;
    tu.F = t;
    Wide cells = 1;
    for (int i = 0; i < this->Dim; ++i)
    {
      const auto& r = this->Range[ToIndex(t[ToIndex(i)])];
      tu.Lo[ToIndex(i)] = r[0];
      tu.Count[ToIndex(i)] = std::max<Wide>(0, r[1] - r[0] + 1);
      cells = Mul(cells, tu.Count[ToIndex(i)]);
    }
    // Its points in the box, about: the box's volume times the points' density |det| / (the
    // product of the spacings). They are distinct vertices, so the most of any tuple is about a
    // lower bound of the arrangement's vertices.
    double points = std::abs(static_cast<double>(this->Determinant(t.data())));
    for (int i = 0; i < this->Dim; ++i)
      points *= static_cast<double>(this->Params.BoxHigh[i] - this->Params.BoxLow[i]) /
        static_cast<double>(this->SpacingOf(t[ToIndex(i)]));
    fewest = std::max(fewest, points);
    tu.RowBase = ToIndex(rows);
    rows = Add(rows, this->Dim == 3 ? Mul(tu.Count[0], tu.Count[1]) : tu.Count[0]);
    candidates = Add(candidates, cells);
    if (this->Dim == 3)
    {
      tu.Cross = { CrossInt(this->Normal(t[1]), this->Normal(t[2])),
        CrossInt(this->Normal(t[2]), this->Normal(t[0])),
        CrossInt(this->Normal(t[0]), this->Normal(t[1])) };
    }
    tu.Det = this->Determinant(t.data());
    this->TupleAt[this->TripleSlot(t[0], t[1], std::max(t[2], 0))] =
      static_cast<std::int32_t>(this->Tuples.size());
    this->Tuples.push_back(tu);
  };
  for (t[0] = 0; t[0] < this->M; ++t[0])
  {
    for (t[1] = t[0] + 1; t[1] < this->M; ++t[1])
    {
      if (this->Dim == 2)
      {
        t[2] = -1;
        consider();
        continue;
      }
      for (t[2] = t[1] + 1; t[2] < this->M; ++t[2])
      {
        consider();
      }
    }
  }
  // The candidates are the plane-index boxes of the tuples; only the part of each row (a line)
  // inside the output box is visited, and the rows' starts are kept (8 bytes a row).
  const auto limit = static_cast<double>(this->Params.MaxVertices);
  if (fewest > 1.05 * limit + 1000)
  {
    throw Error("plane arrangement: about " + std::to_string(std::llround(std::min(fewest, 1e18))) +
      " vertices, more than the limit of " + std::to_string(this->Params.MaxVertices) +
      " allows; use a smaller box or a larger spacing");
  }
  const Wide maxRows = std::max<Wide>(Wide(4) * this->Params.MaxVertices, Wide(10000000));
  if (rows > maxRows || candidates > (Wide(1) << 60))
  {
    throw Error("plane arrangement: " +
      std::to_string(static_cast<long long>(std::min<Wide>(rows, Wide(1) << 62))) +
      " lines of planes cross the box, more than the limit of " +
      std::to_string(this->Params.MaxVertices) +
      " vertices allows; use a smaller box or a larger spacing");
  }
  this->RowStart.assign(ToIndex(rows) + 1, 0);
}

std::array<Wide, 2> ArrangementBuilder::KeysInBox(const Tuple& tu, Wide c0, Wide c1) const
{
  // X(c2) = (A + c2 B) / Den along the row: each coordinate within the box bounds c2.
  const int f0 = tu.F[0], f1 = tu.F[1], f2 = tu.F[2];
  const Wide v0 = Add(this->Offset(f0), Mul(tu.Lo[0] + c0, this->SpacingOf(f0)));
  const Wide v1 = Add(this->Offset(f1), Mul(tu.Lo[1] + c1, this->SpacingOf(f1)));
  const Wide v2 = Add(this->Offset(f2), Mul(tu.Lo[2], this->SpacingOf(f2)));
  const Wide sign = tu.Det < 0 ? -1 : 1;
  const Wide den = sign * tu.Det;
  Wide first = 0, last = tu.Count[2] - 1;
  for (int c = 0; c < 3 && first <= last; ++c)
  {
    const Wide a =
      sign * Add(Add(Mul(v0, tu.Cross[0][c]), Mul(v1, tu.Cross[1][c])), Mul(v2, tu.Cross[2][c]));
    const Wide b = sign * Mul(this->SpacingOf(f2), tu.Cross[2][c]);
    const Wide low = Mul(this->Params.BoxLow[c], den) - a;
    const Wide high = Mul(this->Params.BoxHigh[c], den) - a;
    if (b == 0)
    {
      if (low > 0 || high < 0)
        return { 0, 0 };
      continue;
    }
    // low <= c2 b <= high
    const Wide lo = b > 0 ? CeilDiv(low, b) : CeilDiv(-high, -b);
    const Wide hi = b > 0 ? FloorDiv(high, b) : FloorDiv(-low, -b);
    first = std::max(first, lo);
    last = std::min(last, hi);
  }
  return first <= last ? std::array<Wide, 2>{ { first, last + 1 } } : std::array<Wide, 2>{};
}

Exact ArrangementBuilder::Solve(const Tuple& tu, const std::array<Wide, 3>& value) const
{
  Exact x;
  const int* f = tu.F.data();
  if (this->Dim == 2)
  {
    const IntVec3& a = this->Normal(f[0]);
    const IntVec3& b = this->Normal(f[1]);
    x.Den = Mul(a[0], b[1]) - Mul(a[1], b[0]);
    x.Num[0] = Mul(value[0], b[1]) - Mul(value[1], a[1]);
    x.Num[1] = Mul(value[1], a[0]) - Mul(value[0], b[0]);
    x.Num[2] = 0;
  }
  else
  {
    // X = (v0 (n1×n2) + v1 (n2×n0) + v2 (n0×n1)) / det.
    for (int c = 0; c < 3; ++c)
    {
      x.Num[ToIndex(c)] = Add(Add(Mul(value[0], tu.Cross[0][c]), Mul(value[1], tu.Cross[1][c])),
        Mul(value[2], tu.Cross[2][c]));
    }
    x.Den = tu.Det;
  }
  if (x.Den < 0)
  {
    x.Den = -x.Den;
    for (auto& v : x.Num)
    {
      v = -v;
    }
  }
  return x; // not reduced: most candidates are outside the box
}

bool ArrangementBuilder::InBox(const Exact& x) const
{
  for (int c = 0; c < this->Dim; ++c)
  {
    if (x.Num[ToIndex(c)] < Mul(this->Params.BoxLow[c], x.Den) ||
      x.Num[ToIndex(c)] > Mul(this->Params.BoxHigh[c], x.Den))
    {
      return false;
    }
  }
  return true;
}

std::uint64_t ArrangementBuilder::FamiliesThrough(
  const Exact& x, std::vector<Wide>& planeIndex) const
{
  std::uint64_t mask = 0;
  planeIndex.resize(ToIndex(this->M));
  for (int f = 0; f < this->M; ++f)
  {
    const Wide r = DotNum(this->Normal(f), x) - Mul(this->Offset(f), x.Den);
    const Wide s = Mul(this->SpacingOf(f), x.Den);
    const Wide q = Quot(r, s);
    if (q * s == r)
    {
      mask |= std::uint64_t(1) << f;
      planeIndex[ToIndex(f)] = q;
    }
  }
  return mask;
}

const ArrangementBuilder::Tuple* ArrangementBuilder::FirstTuple(std::uint64_t mask) const
{
  std::array<int, 64> fs;
  int k = 0;
  for (std::uint64_t m = mask; m != 0; m &= m - 1)
  {
    fs[ToIndex(k++)] = __builtin_ctzll(m);
  }
  for (int a = 0; a < k; ++a)
  {
    for (int b = a + 1; b < k; ++b)
    {
      for (int c = this->Dim == 2 ? b : b + 1; c < (this->Dim == 2 ? b + 1 : k); ++c)
      {
        const std::int32_t t = this->TupleAt[this->TripleSlot(
          fs[ToIndex(a)], fs[ToIndex(b)], this->Dim == 2 ? 0 : fs[ToIndex(c)])];
        if (t >= 0)
        {
          return &this->Tuples[ToIndex(t)];
        }
      }
    }
  }
  return nullptr;
}

std::size_t ArrangementBuilder::RowOf(
  const Tuple& tu, const std::vector<Wide>& planeIndex, std::int32_t& key) const
{
  Wide c[3] = { 0, 0, 0 };
  for (int i = 0; i < this->Dim; ++i)
    c[i] = planeIndex[ToIndex(tu.F[ToIndex(i)])] - tu.Lo[ToIndex(i)];
  key = static_cast<std::int32_t>(c[this->Dim - 1]);
  return tu.RowBase + ToIndex(this->Dim == 3 ? c[0] * tu.Count[1] + c[1] : c[0]);
}

// 1. Vertices: every point of a tuple's planes in the box, generated by its first tuple only.
// The candidates are cut into chunks of whole rows (one tuple, one first plane index, a run of
// second ones), generated on threads and joined in chunk order: the serial order.
void ArrangementBuilder::GenerateVertices()
{
  struct Rows
  {
    std::size_t Tuple;
    Wide C0, C1Begin, C1End;
  };
  std::vector<Rows> chunks;
  constexpr Wide ChunkCandidates = 1 << 15;
  for (std::size_t t = 0; t < this->Tuples.size(); ++t)
  {
    const Tuple& tu = this->Tuples[t];
    const Wide n2 = this->Dim == 3 ? tu.Count[2] : 1;
    const Wide rows = std::max<Wide>(1, ChunkCandidates / std::max<Wide>(1, n2));
    for (Wide c0 = 0; c0 < tu.Count[0]; ++c0)
    {
      for (Wide c1 = 0; c1 < tu.Count[1]; c1 += rows)
      {
        chunks.push_back({ t, c0, c1, std::min(tu.Count[1], c1 + rows) });
      }
    }
  }
  struct Found
  {
    std::vector<Exact> Vertices;
    std::vector<std::uint64_t> Masks;
    std::vector<std::size_t> Rows;
    std::vector<std::int32_t> Keys;
  };
  std::vector<Found> found(chunks.size());
  std::atomic<std::int64_t> total{ 0 };
  RunChunks(chunks.size(), this->Params.Threads,
    [&](std::size_t k)
    {
      const Rows& rows = chunks[k];
      const Tuple& tu = this->Tuples[rows.Tuple];
      Found& out = found[k];
      std::vector<Wide> planeIndex;
      std::array<Wide, 3> c{ { rows.C0, 0, 0 } };
      std::array<Wide, 3> value{ { 0, 0, 0 } };
      const Wide n2 = this->Dim == 3 ? tu.Count[2] : 1;
      for (c[1] = rows.C1Begin; c[1] < rows.C1End; ++c[1])
      {
        const std::array<Wide, 2> keys =
          this->Dim == 3 ? this->KeysInBox(tu, c[0], c[1]) : std::array<Wide, 2>{ { 0, n2 } };
        for (c[2] = keys[0]; c[2] < keys[1]; ++c[2])
        {
          for (int i = 0; i < this->Dim; ++i)
          {
            const int f = tu.F[ToIndex(i)];
            value[ToIndex(i)] =
              Add(this->Offset(f), Mul(tu.Lo[ToIndex(i)] + c[ToIndex(i)], this->SpacingOf(f)));
          }
          Exact x = this->Solve(tu, value);
          if (!this->InBox(x))
          {
            continue;
          }
          x.Reduce();
          const std::uint64_t mask = this->FamiliesThrough(x, planeIndex);
          if (this->FirstTuple(mask) != &tu)
          {
            continue;
          }
          if (++total > this->Params.MaxVertices)
          {
            throw Error("plane arrangement: more than " + std::to_string(this->Params.MaxVertices) +
              " vertices; use a smaller box or a larger spacing");
          }
          out.Vertices.push_back(x);
          out.Masks.push_back(mask);
          std::int32_t key = 0;
          out.Rows.push_back(this->RowOf(tu, planeIndex, key));
          out.Keys.push_back(key);
        }
      }
    });
  this->Vertices.reserve(ToIndex(total.load()));
  this->Masks.reserve(ToIndex(total.load()));
  this->Keys.reserve(ToIndex(total.load()));
  this->Ids.reserve(ToIndex(total.load()));
  // Chunks hold whole rows in row order, and each row's keys ascending: counting entries per
  // row gives the compressed rows.
  for (Found& f : found)
  {
    for (std::size_t i = 0; i < f.Vertices.size(); ++i)
    {
      this->RowStart[f.Rows[i] + 1] += 1;
      this->Keys.push_back(f.Keys[i]);
      this->Ids.push_back(static_cast<std::int32_t>(this->Vertices.size()));
      this->Vertices.push_back(f.Vertices[i]);
      this->Masks.push_back(f.Masks[i]);
    }
    f = Found();
  }
  std::partial_sum(this->RowStart.begin(), this->RowStart.end(), this->RowStart.begin());
}

// 2. Scan-line order: by z, then y, then x (exactly), so ids follow the solver's sweep.
void ArrangementBuilder::NumberInScanLineOrder(PlaneArrangement& out)
{
  const std::size_t n = this->Vertices.size();
  std::vector<std::int32_t> order(n);
  std::iota(order.begin(), order.end(), 0);
  const auto before = [this](std::int32_t a, std::int32_t b)
  {
    const Exact& p = this->Vertices[ToIndex(a)];
    const Exact& q = this->Vertices[ToIndex(b)];
    for (int c = 2; c >= 0; --c)
    {
      const Wide l = Mul(p.Num[ToIndex(c)], q.Den);
      const Wide r = Mul(q.Num[ToIndex(c)], p.Den);
      if (l != r)
      {
        return l < r;
      }
    }
    return false;
  };
  // Four quarters sorted on threads, then merged in pairs: vertices are distinct points, so the
  // order is the one total order whatever the threads.
  constexpr std::size_t Parts = 4;
  const auto cut = [n](std::size_t k) { return static_cast<std::ptrdiff_t>(n * k / Parts); };
  RunChunks(Parts, this->Params.Threads,
    [&](std::size_t k) { std::sort(order.begin() + cut(k), order.begin() + cut(k + 1), before); });
  RunChunks(2, this->Params.Threads,
    [&](std::size_t k)
    {
      std::inplace_merge(order.begin() + cut(2 * k), order.begin() + cut(2 * k + 1),
        order.begin() + cut(2 * k + 2), before);
    });
  std::inplace_merge(order.begin(), order.begin() + cut(2), order.end(), before);
  std::vector<std::int32_t> rank(n);
  for (std::size_t i = 0; i < n; ++i)
  {
    rank[ToIndex(order[i])] = static_cast<std::int32_t>(i);
  }
  for (auto& id : this->Ids)
    id = rank[ToIndex(id)];
  std::vector<Exact> sorted(n);
  out.Masks.resize(n);
  for (std::size_t i = 0; i < n; ++i)
  {
    sorted[i] = this->Vertices[ToIndex(order[i])];
    out.Masks[i] = this->Masks[ToIndex(order[i])];
  }
  this->Vertices.swap(sorted);
  out.Positions.resize(n);
  for (std::size_t i = 0; i < n; ++i)
  {
    for (int c = 0; c < 3; ++c)
    {
      out.Positions[i][ToIndex(c)] = this->Params.Origin[ToIndex(c)] +
        this->Params.Quantum * static_cast<double>(this->Vertices[i].Num[ToIndex(c)]) /
          static_cast<double>(this->Vertices[i].Den);
    }
  }
}

IntVec3 ArrangementBuilder::LineDirection(int a, int b) const
{
  if (this->Dim == 2)
  {
    const IntVec3& na = this->Normal(a);
    return Primitive({ -na[1], na[0], 0 });
  }
  return Primitive(CrossInt(this->Normal(a), this->Normal(b)));
}

// 3. Direction classes: every line direction of the arrangement, both ways.
void ArrangementBuilder::ListDirections(PlaneArrangement& out)
{
  for (int a = 0; a < this->M; ++a)
  {
    for (int b = this->Dim == 2 ? a : a + 1; b < (this->Dim == 2 ? a + 1 : this->M); ++b)
    {
      const IntVec3 d = this->LineDirection(a, b);
      if (d == IntVec3{ 0, 0, 0 } || this->DirectionIndex.count(d))
      {
        continue;
      }
      this->DirectionIndex[d] = static_cast<int>(out.Directions.size());
      out.Directions.push_back(d);
      out.Directions.push_back({ -d[0], -d[1], -d[2] });
    }
  }
}

std::int32_t ArrangementBuilder::NextAlong(
  const Exact& x, const IntVec3& d, std::vector<Wide>& scratch) const
{
  // Nearest crossing t = tn / td > 0 with another family's plane.
  Wide bestN = -1, bestD = 1;
  for (int f = 0; f < this->M; ++f)
  {
    const Wide s = static_cast<Wide>(this->Normal(f)[0]) * d[0] +
      static_cast<Wide>(this->Normal(f)[1]) * d[1] + static_cast<Wide>(this->Normal(f)[2]) * d[2];
    if (s == 0)
    {
      continue;
    }
    const Wide value = DotNum(this->Normal(f), x) - Mul(this->Offset(f), x.Den); // × Den
    const Wide step = Mul(this->SpacingOf(f), x.Den);
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
  if (bestN <= 0)
  {
    return -1;
  }
  Exact y;
  for (int c = 0; c < 3; ++c)
  {
    y.Num[ToIndex(c)] = Add(Mul(x.Num[ToIndex(c)], bestD), Mul(Mul(bestN, d[c]), x.Den));
  }
  y.Den = Mul(x.Den, bestD);
  y.Reduce();
  if (!this->InBox(y))
  {
    return -1;
  }
  const Tuple* tu = this->FirstTuple(this->FamiliesThrough(y, scratch));
  if (!tu)
  {
    throw Error("plane arrangement: internal error (a crossing is not a vertex)");
  }
  std::int32_t key = 0;
  const std::size_t row = this->RowOf(*tu, scratch, key);
  const auto begin = this->Keys.begin() + this->RowStart[row];
  const auto end = this->Keys.begin() + this->RowStart[row + 1];
  const auto at = std::lower_bound(begin, end, key);
  if (at == end || *at != key)
  {
    throw Error("plane arrangement: internal error (a vertex was not generated)");
  }
  return this->Ids[ToIndex(at - this->Keys.begin())];
}

void ArrangementBuilder::LinesThrough(std::uint64_t mask, std::vector<int>& lines) const
{
  lines.clear();
  for (int a = 0; a < this->M; ++a)
  {
    if (!((mask >> a) & 1u))
    {
      continue;
    }
    for (int b = this->Dim == 2 ? a : a + 1; b < (this->Dim == 2 ? a + 1 : this->M); ++b)
    {
      if (!((mask >> b) & 1u))
      {
        continue;
      }
      const IntVec3 d = this->LineDirection(a, b);
      if (d == IntVec3{ 0, 0, 0 })
      {
        continue;
      }
      const int k = this->DirectionIndex.at(d);
      if (std::find(lines.begin(), lines.end(), k) == lines.end())
      {
        lines.push_back(k);
      }
    }
  }
  std::sort(lines.begin(), lines.end());
}

// 4. Links: from each vertex both ways along every line through it to the next vertex. Runs of
// vertices are linked on threads and joined in vertex order.
void ArrangementBuilder::LinkVertices(PlaneArrangement& out)
{
  const std::size_t n = this->Vertices.size();
  constexpr std::size_t ChunkVertices = 1 << 13;
  const std::size_t chunks = (n + ChunkVertices - 1) / ChunkVertices;
  struct Linked
  {
    std::vector<PlaneArrangement::Link> Links;
    std::vector<std::int64_t> Count; ///< links per vertex
    std::int64_t Outer = 0, Inner = 0;
  };
  std::vector<Linked> linked(chunks);
  RunChunks(chunks, this->Params.Threads,
    [&](std::size_t k)
    {
      Linked& part = linked[k];
      std::vector<int> lines;
      std::vector<Wide> scratch;
      const std::size_t end = std::min(n, (k + 1) * ChunkVertices);
      for (std::size_t v = k * ChunkVertices; v < end; ++v)
      {
        this->LinesThrough(out.Masks[v], lines);
        for (int line : lines)
        {
          for (int sign = 0; sign < 2; ++sign)
          {
            const int dc = line + sign;
            const std::int32_t target =
              this->NextAlong(this->Vertices[v], out.Directions[ToIndex(dc)], scratch);
            part.Links.push_back({ target, static_cast<std::int32_t>(dc) });
            if (target < 0)
            {
              ++part.Outer;
            }
            else if (ToIndex(target) > v)
            {
              ++part.Inner;
            }
          }
        }
        part.Count.push_back(static_cast<std::int64_t>(2 * lines.size()));
      }
    });
  out.LinkStart.assign(n + 1, 0);
  std::size_t v = 0;
  for (Linked& part : linked)
  {
    out.Links.insert(out.Links.end(), part.Links.begin(), part.Links.end());
    for (const std::int64_t c : part.Count)
    {
      out.LinkStart[v + 1] = out.LinkStart[v] + c;
      ++v;
    }
    out.OuterEdges += part.Outer;
    out.InnerEdges += part.Inner;
    part = Linked();
  }
}

} // namespace detail
} // namespace msynth
