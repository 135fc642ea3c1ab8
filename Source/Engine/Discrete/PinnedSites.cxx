// SPDX-License-Identifier: BSD-3-Clause
// Pinned sites (completing a partial model): the pins checked against the rules and each other
// before any work, then kept as fixed labels; with blocks, placed into the trivial start first.
#include "Core/Error.h"
#include "Core/Random.h"
#include "Discrete/BlockSolver.h"

#include <algorithm>
#include <string>

namespace msynth
{
namespace detail
{
namespace
{
const char* const AxisNames[3] = { "x", "y", "z" };

/// Sites the propagation check's catalog may span (about 16 bytes a label word a site): beyond
/// it, only the pins' own pairs are checked before the run.
constexpr std::int64_t MaximumCheckedSites = std::int64_t(1) << 24;
/// How far around the pins' box the propagation check reaches.
constexpr std::int64_t PinMargin = 16;
} // namespace

std::int64_t BlockSolver::ApplyPins()
{
  if (!this->Options.Pins)
    return 0;
  const LabelGrid& pins = *this->Options.Pins;
  if (this->Plan || this->Seams)
    throw Error("pinned sites cannot be combined with mirror, translation or rotation symmetry");
  if (pins.Dimensions() != this->N)
    throw Error("the pinned sites cover " + Format(pins.Dimensions()) + " sites, the output " +
      Format(this->N));
  const auto& values = this->Rules.LabelValues();
  std::int64_t count = 0;
  Coord lo = this->N, hi{ { -1, -1, -1 } };
  for (std::size_t s = 0; s < this->Model.size(); ++s)
  {
    const Label value = pins.Data()[s];
    if (value == FreeSite)
      continue;
    const Coord p = this->Coordinates(static_cast<std::int64_t>(s));
    for (int a = 0; a < 3; ++a)
    {
      lo[a] = std::min(lo[a], p[a]);
      hi[a] = std::max(hi[a], p[a]);
    }
    const int b = this->Rules.IndexOf(value);
    if (b < 0)
      throw Error("site " + Format(p) + " is pinned to label " + std::to_string(value) +
        ", which does not occur in the example");
    if (this->Fixed[s] >= 0 && this->Fixed[s] != b)
      throw Error("site " + Format(p) + " is pinned to label " + std::to_string(value) +
        ", but the boundary there is label " +
        std::to_string(values[static_cast<std::size_t>(this->Fixed[s])]));
    this->Fixed[s] = b;
    ++count;
  }
  if (count == 0)
    return 0;
  this->CheckPinnedPairs();
  this->CheckPinsPropagate(lo, hi);
  return count;
}

void BlockSolver::CheckPinnedPairs() const
{
  const LabelGrid& pins = *this->Options.Pins;
  const auto& values = this->Rules.LabelValues();
  this->ForEachAdjacentPair(
    [&](const Coord& p, const Coord& q, int axis)
    {
      const auto s = static_cast<std::size_t>(this->Index(p));
      const auto t = static_cast<std::size_t>(this->Index(q));
      const int a = this->Fixed[s], b = this->Fixed[t];
      const bool pinned = pins.Data()[s] != FreeSite || pins.Data()[t] != FreeSite;
      if (!pinned || a < 0 || b < 0 || this->Rules.Allowed(2 * axis, a, b))
        return;
      throw Error("the labels " + std::to_string(values[static_cast<std::size_t>(a)]) + " at " +
        Format(p) + " and " + std::to_string(values[static_cast<std::size_t>(b)]) + " at " +
        Format(q) + " cannot meet: the example never puts them next to each other along " +
        AxisNames[axis]);
    });
}

void BlockSolver::CheckPinsPropagate(const Coord& lo, const Coord& hi)
{
  // Arc consistency from the fixed labels over the pins' box grown by PinMargin sites (clipped
  // to the model): pins whose consequences contradict each other empty a catalog between them.
  // The box, not the whole model: a few pins in 4000 x 4000 sites cost 6 s and 470 MB that way.
  Coord origin, dims;
  std::int64_t sites = 1;
  for (int a = 0; a < 3; ++a)
  {
    origin[a] = std::max<std::int64_t>(0, lo[a] - PinMargin);
    dims[a] = std::min(this->N[a], hi[a] + PinMargin + 1) - origin[a];
    sites *= dims[a];
  }
  if (sites > MaximumCheckedSites)
    return;
  Catalog& cat = this->Cat;
  cat.Reset(origin, dims);
  std::int64_t empty = -1;
  for (std::int64_t local = 0; local < sites && empty < 0; ++local)
  {
    const Coord c = cat.Coordinates(local);
    const int b = this->Fixed[static_cast<std::size_t>(
      this->Index({ { origin[0] + c[0], origin[1] + c[1], origin[2] + c[2] } }))];
    if (b >= 0 && !cat.Assign(local, b))
      empty = local;
  }
  if (empty < 0)
    empty = cat.Propagate();
  if (empty >= 0)
  {
    const Coord c = cat.Coordinates(empty);
    throw Error("the pinned sites cannot all hold: with them, no label fits site " +
      Format({ { origin[0] + c[0], origin[1] + c[1], origin[2] + c[2] } }));
  }
}

void BlockSolver::PlacePins(const Coord& m, std::uint64_t seed, std::int64_t& assignments)
{
  // Each group of touching pins not yet in the model gets a block around it: its bounding box
  // grown by half a block on each side (at least a block), solved against the start around it
  // with the pins inside fixed; a block that cannot be solved doubles, up to the whole model.
  const LabelGrid& pins = *this->Options.Pins;
  const auto& values = this->Rules.LabelValues();
  for (std::size_t s = 0; s < this->Model.size(); ++s)
  {
    const int b = this->Fixed[s];
    if (pins.Data()[s] == FreeSite || this->Model[s] == b)
      continue;
    Coord lo, hi;
    this->PinGroupBox(static_cast<std::int64_t>(s), lo, hi);
    std::int64_t empty = -1;
    Block block;
    block.Index = -1; // LastBlock: placed with the pins
    for (std::int64_t scale = 1;; scale *= 2)
    {
      bool whole = true;
      for (int a = 0; a < 3; ++a)
      {
        const std::int64_t want = std::max(m[a], hi[a] - lo[a] + 1 + m[a]) * scale;
        block.Dims[a] = std::min(want, this->N[a]);
        block.Origin[a] = std::clamp<std::int64_t>(
          (lo[a] + hi[a] + 1 - block.Dims[a]) / 2, 0, this->N[a] - block.Dims[a]);
        whole = whole && block.Dims[a] == this->N[a];
      }
      for (int attempt = 0; attempt < this->Options.AttemptsPerBlock; ++attempt)
      {
        Random rng = Random::Derived(seed, static_cast<std::uint64_t>(s),
          (std::uint64_t(0x9175) << 32) + static_cast<std::uint64_t>(scale * 1000 + attempt));
        empty = this->RunBlock(block, rng, assignments); // -1: solved
        if (empty < 0)
          break;
      }
      if (empty < 0 || whole)
        break;
    }
    if (empty >= 0)
      throw Error("the pin " + std::to_string(values[static_cast<std::size_t>(b)]) + " at " +
        Format(this->Coordinates(static_cast<std::int64_t>(s))) +
        " cannot be placed: no labelling of the whole model around it fits the start (the "
        "catalog empties at " +
        Format(this->Coordinates(empty)) + ")");
  }
}

void BlockSolver::PinGroupBox(std::int64_t first, Coord& lo, Coord& hi) const
{
  const LabelGrid& pins = *this->Options.Pins;
  lo = hi = this->Coordinates(first);
  std::vector<std::int64_t> stack{ first };
  std::vector<char> seen(this->Model.size(), 0);
  seen[static_cast<std::size_t>(first)] = 1;
  while (!stack.empty())
  {
    const Coord p = this->Coordinates(stack.back());
    stack.pop_back();
    for (int a = 0; a < 3; ++a)
    {
      lo[a] = std::min(lo[a], p[a]);
      hi[a] = std::max(hi[a], p[a]);
    }
    for (int d = 0; d < 6; ++d)
    {
      Coord q = p;
      q[d / 2] += (d & 1) ? -1 : 1;
      if (q[d / 2] < 0 || q[d / 2] >= this->N[d / 2])
        continue;
      const auto t = static_cast<std::size_t>(this->Index(q));
      if (!seen[t] && pins.Data()[t] != FreeSite)
      {
        seen[t] = 1;
        stack.push_back(static_cast<std::int64_t>(t));
      }
    }
  }
}

} // namespace detail
} // namespace msynth
