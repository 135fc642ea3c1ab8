// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Parts of the continuous label solver (internal header of ContinuousSynthesis.cxx): the block
// layout, the label draw and the order of the undecided vertices.
#include "Continuous/PlaneArrangement.h"
#include "Core/LabelDraw.h"
#include "Core/Random.h"
#include "Core/SynthesisChoices.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <set>
#include <tuple>
#include <vector>

namespace msynth
{
namespace detail
{

/// Vertices grouped into overlapping blocks: cells of half the block edge, a block is 2×2×2 cells.
struct BlockLayout
{
  std::array<std::int64_t, 3> Cells{ { 1, 1, 1 } };
  std::vector<std::vector<std::int64_t>> CellVertices;
  std::array<std::int64_t, 3> Blocks{ { 1, 1, 1 } };

  BlockLayout(const PlaneArrangement& arrangement, double edge)
  {
    const auto& p = arrangement.Parameters();
    const int dims = arrangement.Planar() ? 2 : 3;
    const double half = edge / 2;
    std::array<double, 3> lo{};
    for (int c = 0; c < 3; ++c)
    {
      lo[static_cast<std::size_t>(c)] =
        p.Origin[static_cast<std::size_t>(c)] + p.Quantum * static_cast<double>(p.BoxLow[c]);
      if (c < dims && edge > 0)
      {
        const double extent = p.Quantum * static_cast<double>(p.BoxHigh[c] - p.BoxLow[c]);
        this->Cells[static_cast<std::size_t>(c)] =
          std::max<std::int64_t>(1, static_cast<std::int64_t>(std::ceil(extent / half - 1e-9)));
        this->Blocks[static_cast<std::size_t>(c)] =
          std::max<std::int64_t>(1, this->Cells[static_cast<std::size_t>(c)] - 1);
      }
    }
    this->CellVertices.resize(
      static_cast<std::size_t>(this->Cells[0] * this->Cells[1] * this->Cells[2]));
    for (std::int64_t v = 0; v < arrangement.NumberOfVertices(); ++v)
    {
      std::array<std::int64_t, 3> cell{ { 0, 0, 0 } };
      for (int c = 0; c < dims; ++c)
      {
        if (edge > 0)
        {
          const double t = (arrangement.Position(v)[static_cast<std::size_t>(c)] -
                             lo[static_cast<std::size_t>(c)]) /
            half;
          cell[static_cast<std::size_t>(c)] =
            std::clamp<std::int64_t>(static_cast<std::int64_t>(std::floor(t)), 0,
              this->Cells[static_cast<std::size_t>(c)] - 1);
        }
      }
      this
        ->CellVertices[static_cast<std::size_t>(
          cell[0] + this->Cells[0] * (cell[1] + this->Cells[1] * cell[2]))]
        .push_back(v);
    }
  }

  std::int64_t NumberOfBlocks() const
  {
    return this->Blocks[0] * this->Blocks[1] * this->Blocks[2];
  }

  /// Blocks by their distance (in blocks, the largest difference along an axis) from the
  /// nearest block that holds a seed vertex, ties in scan order; scan order without seeds. So
  /// objects growing from seeds spread outward block by block.
  std::vector<std::int64_t> OrderFrom(const std::vector<std::int64_t>& seeds) const
  {
    std::vector<std::int64_t> order(static_cast<std::size_t>(this->NumberOfBlocks()));
    for (std::size_t i = 0; i < order.size(); ++i)
      order[i] = static_cast<std::int64_t>(i);
    if (seeds.empty())
      return order;
    std::vector<std::array<std::int64_t, 3>> from;
    for (std::size_t c = 0; c < this->CellVertices.size(); ++c)
    {
      for (std::int64_t v : this->CellVertices[c])
      {
        if (std::binary_search(seeds.begin(), seeds.end(), v))
        {
          const auto cell = static_cast<std::int64_t>(c);
          from.push_back({ { std::min(cell % this->Cells[0], this->Blocks[0] - 1),
            std::min((cell / this->Cells[0]) % this->Cells[1], this->Blocks[1] - 1),
            std::min(cell / (this->Cells[0] * this->Cells[1]), this->Blocks[2] - 1) } });
        }
      }
    }
    std::vector<std::int64_t> distance(order.size(), 0);
    for (std::size_t b = 0; b < order.size(); ++b)
    {
      const auto i = static_cast<std::int64_t>(b);
      const std::array<std::int64_t, 3> at{ { i % this->Blocks[0],
        (i / this->Blocks[0]) % this->Blocks[1], i / (this->Blocks[0] * this->Blocks[1]) } };
      std::int64_t best = std::numeric_limits<std::int64_t>::max();
      for (const auto& f : from)
        best = std::min(best,
          std::max({ std::abs(at[0] - f[0]), std::abs(at[1] - f[1]), std::abs(at[2] - f[2]) }));
      distance[b] = best;
    }
    std::stable_sort(order.begin(), order.end(),
      [&](std::int64_t a, std::int64_t b)
      { return distance[static_cast<std::size_t>(a)] < distance[static_cast<std::size_t>(b)]; });
    return order;
  }

  /// Vertices of block @p b in ascending (scan) order.
  std::vector<std::int64_t> Vertices(std::int64_t b) const
  {
    const std::int64_t bx = b % this->Blocks[0], by = (b / this->Blocks[0]) % this->Blocks[1],
                       bz = b / (this->Blocks[0] * this->Blocks[1]);
    std::vector<std::int64_t> out;
    for (std::int64_t z = bz; z < std::min(bz + 2, this->Cells[2]); ++z)
    {
      for (std::int64_t y = by; y < std::min(by + 2, this->Cells[1]); ++y)
      {
        for (std::int64_t x = bx; x < std::min(bx + 2, this->Cells[0]); ++x)
        {
          const auto& c = this->CellVertices[static_cast<std::size_t>(
            x + this->Cells[0] * (y + this->Cells[1] * z))];
          out.insert(out.end(), c.begin(), c.end());
        }
      }
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
    domain, words, [&](int b) { return weights[static_cast<std::size_t>(b)]; }, rng.Uniform());
}

/// The undecided vertices of a block in the order they are labelled: vertices on the front of
/// growing objects (connectivity constraints) before all others, then by the site order.
class SiteQueue
{
public:
  SiteQueue(SiteOrder order, std::int64_t n, Random& rng)
    : Order(order)
    , Counts(static_cast<std::size_t>(n), 0)
    , Front(static_cast<std::size_t>(n), 0)
    , Key(static_cast<std::size_t>(n))
  {
    for (std::int64_t i = 0; i < n; ++i)
    {
      this->Key[static_cast<std::size_t>(i)] =
        order == SiteOrder::ScanLine ? static_cast<std::uint64_t>(i) : rng.Next();
    }
  }

  void Update(std::int64_t i, int count)
  {
    auto& old = this->Counts[static_cast<std::size_t>(i)];
    if (old > 1)
      this->Pending.erase(this->Entry(i, old));
    old = count;
    if (count > 1)
      this->Pending.insert(this->Entry(i, count));
  }

  /// Puts vertex @p i on the growth front (labelled before the vertices off it).
  void SetFront(std::int64_t i)
  {
    if (this->Front[static_cast<std::size_t>(i)])
      return;
    const int count = this->Counts[static_cast<std::size_t>(i)];
    this->Update(i, 0);
    this->Front[static_cast<std::size_t>(i)] = 1;
    this->Update(i, count);
  }
  bool OnFront(std::int64_t i) const { return this->Front[static_cast<std::size_t>(i)] != 0; }

  /// The next undecided vertex, or -1.
  std::int64_t Next() const
  {
    return this->Pending.empty() ? -1 : std::get<2>(*this->Pending.begin());
  }
  std::int64_t Remaining() const { return static_cast<std::int64_t>(this->Pending.size()); }

private:
  std::tuple<int, std::uint64_t, std::int64_t> Entry(std::int64_t i, int count) const
  {
    const int rank = (this->Front[static_cast<std::size_t>(i)] ? 0 : 1 << 28) +
      (this->Order == SiteOrder::MinimumEntropy ? count : 0);
    return { rank, this->Key[static_cast<std::size_t>(i)], i };
  }

  SiteOrder Order;
  std::vector<int> Counts;
  std::vector<char> Front;
  std::vector<std::uint64_t> Key;
  std::set<std::tuple<int, std::uint64_t, std::int64_t>> Pending;
};

} // namespace detail
} // namespace msynth
