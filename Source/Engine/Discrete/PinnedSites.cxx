// SPDX-License-Identifier: BSD-3-Clause
// Pinned sites (completing a partial model): the pins checked against the rules and each other
// before any work, then kept as fixed labels; with blocks, placed into the trivial start first.
#include "Core/Error.h"
#include "Core/Index.h"
#include "Core/Random.h"
#include "Core/WorldSchedule.h"
#include "Discrete/BlockSolver.h"
#include "Discrete/WindowRun.h"

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
    throw Error("the pinned sites cover " + FormatSize(pins.Dimensions()) + " sites, the output " +
      FormatSize(this->N) + ": expected a grid of the output's size");
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
        ", but the boundary there is label " + std::to_string(values[ToIndex(this->Fixed[s])]));
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
      const auto s = ToIndex(this->Index(p));
      const auto t = ToIndex(this->Index(q));
      const int a = this->Fixed[s], b = this->Fixed[t];
      const bool pinned = pins.Data()[s] != FreeSite || pins.Data()[t] != FreeSite;
      if (!pinned || a < 0 || b < 0 || this->Rules.Allowed(2 * axis, a, b))
        return;
      throw Error("the labels " + std::to_string(values[ToIndex(a)]) + " at " + Format(p) +
        " and " + std::to_string(values[ToIndex(b)]) + " at " + Format(q) +
        " cannot meet: the example never puts them next to each other along " + AxisNames[axis]);
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
    const int b =
      this
        ->Fixed[ToIndex(this->Index({ { origin[0] + c[0], origin[1] + c[1], origin[2] + c[2] } }))];
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

namespace
{
/// The first placement block of a group of pins over [@p lo, @p hi] (world coordinates) in a
/// world of @p world sites with blocks of @p m, at @p scale: its origin and size.
void PlacementBlock(const Coord& lo, const Coord& hi, const Coord& m, const Coord& world,
  std::int64_t scale, Coord& origin, Coord& dims)
{
  for (int a = 0; a < 3; ++a)
  {
    const std::int64_t want = std::max(m[a], hi[a] - lo[a] + 1 + m[a]) * scale;
    dims[a] = std::min(want, world[a]);
    origin[a] = std::clamp<std::int64_t>((lo[a] + hi[a] + 1 - dims[a]) / 2, 0, world[a] - dims[a]);
  }
}

/// The bounding box [@p lo, @p hi] of the face-connected group of pinned sites of @p pins that
/// holds @p first, each of them marked in @p seen (a flag per site of @p pins).
void PinGroupBounds(
  const LabelGrid& pins, std::int64_t first, std::vector<char>& seen, Coord& lo, Coord& hi)
{
  const Coord& d = pins.Dimensions();
  const auto at = [&d](std::int64_t s) -> Coord {
    return { { s % d[0], (s / d[0]) % d[1], s / (d[0] * d[1]) } };
  };
  lo = hi = at(first);
  std::vector<std::int64_t> stack{ first };
  seen[ToIndex(first)] = 1;
  while (!stack.empty())
  {
    const Coord p = at(stack.back());
    stack.pop_back();
    for (int a = 0; a < 3; ++a)
    {
      lo[a] = std::min(lo[a], p[a]);
      hi[a] = std::max(hi[a], p[a]);
    }
    for (int e = 0; e < 6; ++e)
    {
      Coord q = p;
      q[e / 2] += (e & 1) ? -1 : 1;
      if (q[e / 2] < 0 || q[e / 2] >= d[e / 2])
        continue;
      const auto t = ToIndex(q[0] + d[0] * (q[1] + d[1] * q[2]));
      if (!seen[t] && pins.Data()[t] != FreeSite)
      {
        seen[t] = 1;
        stack.push_back(static_cast<std::int64_t>(t));
      }
    }
  }
}
} // namespace

void BlockSolver::PlacePins(const Coord& m, std::uint64_t seed, std::int64_t& assignments,
  const RegionCone* cone, const PinScales* scales)
{
  // Each group of touching pins not yet in the model gets a block around it: its bounding box
  // grown by half a block on each side (at least a block), solved against the start around it
  // with the pins inside fixed; a block that cannot be solved doubles, up to the whole model.
  // In a window of a world, boxes and draws are the world's (the window at its offset).
  const LabelGrid& pins = *this->Options.Pins;
  const auto& values = this->Rules.LabelValues();
  const Coord off = cone ? cone->WindowLow : Coord{ { 0, 0, 0 } };
  const Coord world = cone ? cone->World : this->N;
  for (std::size_t s = 0; s < this->Model.size(); ++s)
  {
    const int b = this->Fixed[s];
    if (pins.Data()[s] == FreeSite || this->Model[s] == b)
      continue;
    Coord lo, hi;
    std::vector<char> seen(pins.Data().size(), 0);
    PinGroupBounds(pins, static_cast<std::int64_t>(s), seen, lo, hi);
    const Coord site = this->Coordinates(static_cast<std::int64_t>(s));
    const auto key = static_cast<std::uint64_t>(
      (site[0] + off[0]) + world[0] * ((site[1] + off[1]) + world[1] * (site[2] + off[2])));
    for (int a = 0; a < 3; ++a)
    {
      lo[a] += off[a];
      hi[a] += off[a];
    }
    const std::array<std::int64_t, 6> group{ { lo[0], lo[1], lo[2], hi[0], hi[1], hi[2] } };
    const auto planned = scales ? scales->find(group) : PinScales::const_iterator();
    const std::int64_t allowed = scales && planned != scales->end() ? planned->second : 1;
    std::int64_t empty = -1;
    Block block;
    block.Index = -1; // LastBlock: placed with the pins
    for (std::int64_t scale = 1;; scale *= 2)
    {
      PlacementBlock(lo, hi, m, world, scale, block.Origin, block.Dims);
      bool whole = true;
      for (int a = 0; a < 3; ++a)
      {
        whole = whole && block.Dims[a] == world[a];
        block.Origin[a] -= off[a];
      }
      for (int attempt = 0; attempt < this->Options.AttemptsPerBlock; ++attempt)
      {
        Random rng = Random::Derived(seed, key,
          (std::uint64_t(0x9175) << 32) + static_cast<std::uint64_t>(scale * 1000 + attempt));
        empty = this->RunBlock(block, rng, assignments); // -1: solved
        if (empty < 0)
          break;
      }
      if (empty < 0 || whole)
        break;
      if (cone && scale >= allowed) // the window holds blocks up to the planned scale only
        throw PinScaleNeeded{ group, 2 * scale };
    }
    if (empty >= 0)
      throw Error("the pin " + std::to_string(values[ToIndex(b)]) + " at " +
        Format(this->Coordinates(static_cast<std::int64_t>(s))) +
        " cannot be placed: no labelling of the whole model around it fits the start (the "
        "catalog empties at " +
        Format(this->Coordinates(empty)) + ")");
  }
}

LabelGrid PinsOfBox(const SynthesisOptions& world, const Coord& low, const Coord& high)
{
  const LabelGrid& pins = *world.Pins;
  const Coord o = world.PinsOrigin.value_or(Coord{ { 0, 0, 0 } });
  const Coord& d = pins.Dimensions();
  for (int a = 0; a < 3; ++a)
    if (o[a] < 0 || o[a] + d[a] > world.Size[a])
      throw Error("the pinned sites cover " + FormatSize(d) + " sites from " + Format(o) +
        ", which is not inside the output " + FormatSize(world.Size));
  const Coord n{ { high[0] - low[0], high[1] - low[1], high[2] - low[2] } };
  LabelGrid out(n, std::vector<Label>(ToIndex(n[0] * n[1] * n[2]), FreeSite));
  Coord from, to;
  for (int a = 0; a < 3; ++a)
  {
    from[a] = std::max(low[a], o[a]);
    to[a] = std::min(high[a], o[a] + d[a]);
    if (from[a] >= to[a])
      return out;
  }
  for (std::int64_t z = from[2]; z < to[2]; ++z)
    for (std::int64_t y = from[1]; y < to[1]; ++y)
      for (std::int64_t x = from[0]; x < to[0]; ++x)
        out.Data()[ToIndex((x - low[0]) + n[0] * ((y - low[1]) + n[1] * (z - low[2])))] =
          pins.At(x - o[0], y - o[1], z - o[2]);
  return out;
}

void GrowWindowForPins(
  const SynthesisOptions& world, const Coord& m, RegionCone& cone, const PinScales& scales)
{
  // The groups of touching pins of the pin grid, each's first placement block with its ring.
  const LabelGrid& pins = *world.Pins;
  const Coord o = world.PinsOrigin.value_or(Coord{ { 0, 0, 0 } });
  std::vector<std::array<Coord, 2>> reach; // [low, high) per group
  std::vector<char> seen(pins.Data().size(), 0);
  for (std::size_t first = 0; first < seen.size(); ++first)
  {
    if (seen[first] || pins.Data()[first] == FreeSite)
      continue;
    Coord lo, hi;
    PinGroupBounds(pins, static_cast<std::int64_t>(first), seen, lo, hi);
    for (int a = 0; a < 3; ++a)
    {
      lo[a] += o[a];
      hi[a] += o[a];
    }
    Coord origin, dims;
    const auto planned = scales.find({ { lo[0], lo[1], lo[2], hi[0], hi[1], hi[2] } });
    PlacementBlock(
      lo, hi, m, world.Size, planned == scales.end() ? 1 : planned->second, origin, dims);
    std::array<Coord, 2> box;
    for (int a = 0; a < 3; ++a)
    {
      box[0][a] = std::max<std::int64_t>(0, origin[a] - 1);
      box[1][a] = std::min(world.Size[a], origin[a] + dims[a] + 1);
    }
    reach.push_back(box);
  }
  // Grow the window to every reach that meets it, until none is left out.
  for (bool grown = true; grown;)
  {
    grown = false;
    for (const auto& box : reach)
    {
      bool meets = true, inside = true;
      for (int a = 0; a < 3; ++a)
      {
        meets = meets && box[0][a] < cone.WindowHigh[a] && box[1][a] > cone.WindowLow[a];
        inside = inside && box[0][a] >= cone.WindowLow[a] && box[1][a] <= cone.WindowHigh[a];
      }
      if (!meets || inside)
        continue;
      for (int a = 0; a < 3; ++a)
      {
        cone.WindowLow[a] = std::min(cone.WindowLow[a], box[0][a]);
        cone.WindowHigh[a] = std::max(cone.WindowHigh[a], box[1][a]);
      }
      grown = true;
    }
  }
}

} // namespace detail
} // namespace msynth
