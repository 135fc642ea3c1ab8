// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Parts of the continuous label solver (internal header of ContinuousSynthesis.cxx): the block
// layout, the label draw and the order of the undecided vertices.
#include "Continuous/PlaneArrangement.h"
#include "Core/Index.h"
#include "Core/LabelDraw.h"
#include "Core/Random.h"
#include "Core/SynthesisChoices.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <functional>
#include <limits>
#include <queue>
#include <tuple>
#include <vector>

namespace msynth
{
namespace detail
{

/**
 * Vertices grouped into overlapping blocks (T§4.5.6): cells of half the block edge, a block is
 * 2 × 2 × 2 cells, one cell apart: the shared box-block grid (Core/BlockSynthesis.h's
 * PlanBoxBlocks) over the cells. With NonTouching phases, the blocks of a phase lie further
 * apart than the longest arrangement edge (in cells), so no block reads a vertex another one
 * labels.
 */
struct BlockLayout
{
  std::array<std::int64_t, 3> Cells{ { 1, 1, 1 } };
  std::vector<std::vector<std::int64_t>> CellVertices;
  std::vector<BoxBlock<3>> Grid; ///< the blocks by phase, then in scan order, in cells
  int Phases = 1;
  /// A cell's edge (half the block edge; 0: one block). Blocks of a NonTouching phase lie at
  /// least a cell apart, so a block may read the vertices nearer than this outside it.
  double CellEdge = 0;

  BlockLayout(const PlaneArrangement& arrangement, double edge, PhasePolicy policy)
  {
    const auto& p = arrangement.Parameters();
    const int dims = arrangement.Planar() ? 2 : 3;
    const double half = edge / 2;
    this->CellEdge = half;
    std::array<double, 3> lo{};
    for (std::size_t c = 0; c < 3; ++c)
    {
      lo[c] = p.Origin[c] + p.Quantum * static_cast<double>(p.BoxLow[c]);
      if (static_cast<int>(c) < dims && edge > 0)
      {
        const double extent = p.Quantum * static_cast<double>(p.BoxHigh[c] - p.BoxLow[c]);
        this->Cells[c] =
          std::max<std::int64_t>(1, static_cast<std::int64_t>(std::ceil(extent / half - 1e-9)));
      }
    }
    this->CellVertices.resize(ToIndex(this->Cells[0] * this->Cells[1] * this->Cells[2]));
    std::vector<std::array<std::int64_t, 3>> cellOf(
      ToIndex(arrangement.NumberOfVertices()), { { 0, 0, 0 } });
    for (std::int64_t v = 0; v < arrangement.NumberOfVertices(); ++v)
    {
      auto& cell = cellOf[ToIndex(v)];
      for (std::size_t c = 0; static_cast<int>(c) < dims && edge > 0; ++c)
      {
        const double t = (arrangement.Position(v)[c] - lo[c]) / half;
        cell[c] =
          std::clamp<std::int64_t>(static_cast<std::int64_t>(std::floor(t)), 0, this->Cells[c] - 1);
      }
      this->CellVertices[ToIndex(cell[0] + this->Cells[0] * (cell[1] + this->Cells[1] * cell[2]))]
        .push_back(v);
    }
    // The longest edge in cells: how far apart the blocks of a phase must be.
    std::int64_t reach = 1;
    for (std::int64_t v = 0; v < arrangement.NumberOfVertices(); ++v)
      for (const auto* l = arrangement.LinksBegin(v); l != arrangement.LinksEnd(v); ++l)
        for (std::size_t c = 0; l->Vertex >= 0 && c < 3; ++c)
          reach = std::max(reach, std::abs(cellOf[ToIndex(v)][c] - cellOf[ToIndex(l->Vertex)][c]));
    this->Grid = PlanBoxBlocks<3>(this->Cells, { { 2, 2, 2 } }, { { 1, 1, 1 } }, policy,
      this->Phases, reach, PhaseDigits::AxisOrder);
  }

  std::int64_t NumberOfBlocks() const { return static_cast<std::int64_t>(this->Grid.size()); }

  /// Blocks by their distance (in blocks, the largest difference along an axis) from the
  /// nearest block that holds a seed vertex, ties in scan order; scan order without seeds. So
  /// objects growing from seeds spread outward block by block.
  std::vector<std::int64_t> OrderFrom(const std::vector<std::int64_t>& seeds) const
  {
    std::vector<std::int64_t> order(this->Grid.size());
    for (std::size_t i = 0; i < order.size(); ++i)
      order[i] = static_cast<std::int64_t>(i);
    if (seeds.empty())
      return order;
    // A block's origin (in cells) is its place in the block grid; a seed's cell lies in the
    // block of the same origin, clamped to the last block.
    const BoxBlock<3>& last = this->Grid.back();
    std::vector<std::array<std::int64_t, 3>> from;
    for (std::size_t c = 0; c < this->CellVertices.size(); ++c)
    {
      for (std::int64_t v : this->CellVertices[c])
      {
        if (std::binary_search(seeds.begin(), seeds.end(), v))
        {
          const auto cell = static_cast<std::int64_t>(c);
          from.push_back({ { std::min(cell % this->Cells[0], last.Origin[0]),
            std::min((cell / this->Cells[0]) % this->Cells[1], last.Origin[1]),
            std::min(cell / (this->Cells[0] * this->Cells[1]), last.Origin[2]) } });
        }
      }
    }
    std::vector<std::int64_t> distance(order.size(), 0);
    for (std::size_t b = 0; b < order.size(); ++b)
    {
      const auto& at = this->Grid[b].Origin;
      std::int64_t best = std::numeric_limits<std::int64_t>::max();
      for (const auto& f : from)
        best = std::min(best,
          std::max({ std::abs(at[0] - f[0]), std::abs(at[1] - f[1]), std::abs(at[2] - f[2]) }));
      distance[b] = best;
    }
    std::stable_sort(order.begin(), order.end(),
      [&](std::int64_t a, std::int64_t b) { return distance[ToIndex(a)] < distance[ToIndex(b)]; });
    return order;
  }

  /// Vertices of block @p b in ascending (scan) order.
  std::vector<std::int64_t> Vertices(std::int64_t b) const
  {
    const BoxBlock<3>& block = this->Grid[ToIndex(b)];
    std::vector<std::int64_t> out;
    std::array<std::int64_t, 3> c;
    const auto& o = block.Origin;
    for (c[2] = o[2]; c[2] < o[2] + block.Dims[2]; ++c[2])
      for (c[1] = o[1]; c[1] < o[1] + block.Dims[1]; ++c[1])
        for (c[0] = o[0]; c[0] < o[0] + block.Dims[0]; ++c[0])
        {
          const auto& cell =
            this->CellVertices[ToIndex(c[0] + this->Cells[0] * (c[1] + this->Cells[1] * c[2]))];
          out.insert(out.end(), cell.begin(), cell.end());
        }
    std::sort(out.begin(), out.end());
    return out;
  }
};

/// A label of @p domain (@p count labels): uniformly, or proportionally to @p weights when
/// not empty.
inline int PickLabel(const std::uint64_t* domain, int words, int count,
  const std::vector<double>& weights, Random& rng)
{
  if (weights.empty())
    return NthLabel(domain, words, rng.Below(static_cast<std::uint64_t>(count)));
  return DrawLabel(
    domain, words, [&](int b) { return weights[ToIndex(b)]; }, rng.Uniform());
}

/// The undecided vertices of a block in the order they are labelled: vertices on the front of
/// growing objects (connectivity constraints) before all others, then by the site order.
class SiteQueue
{
public:
  SiteQueue(SiteOrder order, std::int64_t n, Random& rng)
    : Order(order)
    , Counts(ToIndex(n), 0)
    , Front(ToIndex(n), 0)
    , Key(ToIndex(n))
  {
    for (std::int64_t i = 0; i < n; ++i)
    {
      this->Key[ToIndex(i)] =
        order == SiteOrder::ScanLine ? static_cast<std::uint64_t>(i) : rng.Next();
    }
  }

  void Update(std::int64_t i, int count)
  {
    auto& old = this->Counts[ToIndex(i)];
    this->Undecided += (count > 1 ? 1 : 0) - (old > 1 ? 1 : 0);
    const bool same = old > 1 && count > 1 && this->Entry(i, old) == this->Entry(i, count);
    old = count;
    if (count > 1 && !same) // the entry it had is left in the heap, stale
      this->Pending.push(this->Entry(i, count));
  }

  /// Puts vertex @p i on the growth front (labelled before the vertices off it); @p lead: on
  /// the front of a type grown from seeds (labelled before the rest of the front: a road network
  /// grows from its seed before the houses beside it start on the ground).
  void SetFront(std::int64_t i, bool lead = false)
  {
    const char level = lead ? 2 : 1;
    if (this->Front[ToIndex(i)] >= level)
      return;
    const int count = this->Counts[ToIndex(i)];
    this->Update(i, 0);
    this->Front[ToIndex(i)] = level;
    this->Update(i, count);
  }
  bool OnFront(std::int64_t i) const { return this->Front[ToIndex(i)] != 0; }

  /// The next undecided vertex, or -1.
  std::int64_t Next()
  {
    while (!this->Pending.empty())
    {
      const auto& top = this->Pending.top();
      const std::int64_t i = std::get<2>(top);
      const int count = this->Counts[ToIndex(i)];
      if (count > 1 && this->Entry(i, count) == top)
        return i;
      this->Pending.pop(); // stale: the vertex was decided or its entry changed since
    }
    return -1;
  }
  std::int64_t Remaining() const { return this->Undecided; }

private:
  std::tuple<int, std::uint64_t, std::int64_t> Entry(std::int64_t i, int count) const
  {
    const int rank = (2 - this->Front[ToIndex(i)]) * (1 << 27) +
      (this->Order == SiteOrder::MinimumEntropy ? count : 0);
    return { rank, this->Key[ToIndex(i)], i };
  }

  SiteOrder Order;
  std::vector<int> Counts;
  std::vector<char> Front;
  std::vector<std::uint64_t> Key;
  using Item = std::tuple<int, std::uint64_t, std::int64_t>;
  /// The smallest entry on top; entries of vertices decided or changed since stay until they
  /// surface (a vertex's current entry is the one Entry gives for its count).
  std::priority_queue<Item, std::vector<Item>, std::greater<Item>> Pending;
  std::int64_t Undecided = 0; ///< vertices with more than one label left
};

} // namespace detail
} // namespace msynth
