// SPDX-License-Identifier: BSD-3-Clause
#include "Discrete/Connectivity.h"
#include "Discrete/NetworkComponents.h"

#include "Core/Error.h"
#include "Core/Index.h"
#include "Core/WorldSchedule.h"
#include "Discrete/MirrorPlan.h"
#include "Discrete/SymmetryPlan.h"

#include <algorithm>
#include <array>
#include <limits>
#include <set>

namespace msynth
{
namespace detail
{
namespace
{

/// Refuses path sites outside the model or pinned to a label the network does not hold, and
/// path labels that are not the network's, with one line.
void CheckPath(
  const ConnectedNetwork& network, const SynthesisOptions& options, const std::string& name)
{
  const Coord& n = options.Size;
  for (const Coord& p : network.PathSites)
  {
    for (std::size_t a = 0; a < 3; ++a)
      if (p[a] < 0 || p[a] >= n[a])
        throw Error("the path's site " + Format(p) + " is outside the model (" +
          std::to_string(n[0]) + " x " + std::to_string(n[1]) + " x " + std::to_string(n[2]) +
          " sites)");
    if (options.Pins)
    {
      const Label pin = options.Pins->Data()[ToIndex(p[0] + n[0] * (p[1] + n[1] * p[2]))];
      if (pin != FreeSite &&
        std::find(network.Values.begin(), network.Values.end(), pin) == network.Values.end())
        throw Error("the path's site " + Format(p) + " is pinned to label " + std::to_string(pin) +
          ", which cannot carry " + name);
    }
  }
  for (Label v : network.PathLabels)
    if (std::find(network.Values.begin(), network.Values.end(), v) == network.Values.end())
      throw Error("the path's label " + std::to_string(v) + " cannot carry " + name +
        " (it is not one of the network's labels)");
}
} // namespace

std::vector<Component> FindComponents(const NetworkRule& rule,
  const std::vector<std::int32_t>& model, const Coord& n, std::vector<std::int32_t>* ids)
{
  std::vector<Component> out;
  std::vector<std::int32_t> scratch;
  std::vector<std::int32_t>& seen = ids ? *ids : scratch;
  std::vector<std::int64_t> stack;
  Flood(
    rule, n, [&](std::int64_t s) { return model[ToIndex(s)]; }, [](std::int64_t) { return false; },
    [&](const Component& c) { out.push_back(c); }, seen, stack);
  return out;
}

std::string NetworkName(const ConnectedNetwork& network)
{
  return "the network of " + (network.Name.empty() ? std::string("its labels") : network.Name);
}

NetworkRule::NetworkRule(const AdjacencyRules& rules, const ConnectedNetwork& network)
{
  this->Mask.assign(ToIndex(rules.NumberOfLabels()), -1);
  for (Label v : network.Values)
  {
    const int b = rules.IndexOf(v);
    if (b < 0)
      continue;
    const auto side = network.Sides.find(v);
    this->Mask[ToIndex(b)] = side == network.Sides.end() ? 63 : side->second;
  }
  this->Path.assign(this->Mask.size(), 0);
  for (Label v : network.PathLabels)
  {
    const int b = rules.IndexOf(v);
    if (b >= 0)
      this->Path[ToIndex(b)] = 1;
  }
}

void CheckConnectedRequest(const AdjacencyRules& rules, const SynthesisOptions& options)
{
  const ConnectedNetwork& network = options.Connected;
  if (!network.Active())
  {
    if (network.HasPath())
      throw Error("a path (--path) needs a network of labels to carry it (--connected LABELS)");
    return;
  }
  const std::string name = NetworkName(network);
  if (AnyMirror(options) || AnySeamSymmetry(options))
    throw Error(name +
      " cannot be combined with symmetry (only a part of the output is "
      "synthesized)");
  if (options.Soft.Active())
    throw Error(name + " cannot be combined with soft constraints (which roll blocks back)");
  if (network.Open && network.HasPath())
    throw Error(name + ":open takes no path (a path is joined by repairs of the whole model)");
  if (network.Maximum < 1)
    throw Error(name + " asks for at most " + std::to_string(network.Maximum) +
      " components (need at least 1)");
  std::set<Label> seen;
  for (Label v : network.Values)
  {
    if (rules.IndexOf(v) < 0)
      throw Error(name + ": label " + std::to_string(v) + " does not occur in the example");
    if (!seen.insert(v).second)
      throw Error(name + ": label " + std::to_string(v) + " is named twice");
  }
  for (const auto& side : network.Sides)
    if (side.second > 63)
      throw Error(name + ": label " + std::to_string(side.first) + " has sides beyond 6");
  CheckPath(network, options, name);
}

std::int64_t CountComponents(
  const NetworkRule& rule, const std::vector<std::int32_t>& model, const Coord& n)
{
  return static_cast<std::int64_t>(FindComponents(rule, model, n).size());
}

NetworkGuard::NetworkGuard(
  const NetworkRule& rule, std::int64_t maximum, const std::vector<Block>& blocks, const Coord& n)
  : Rule(rule)
  , Maximum(maximum)
  , N(n)
{
  std::int64_t indices = 0;
  for (const Block& b : blocks)
    indices = std::max(indices, b.Index + 1);
  this->Position.assign(ToIndex(indices), -1);
  this->OwnerPosition.assign(ToIndex(n[0] * n[1] * n[2]), -1);
  this->VisitCall.assign(ToIndex(n[0] * n[1] * n[2]), 0);
  this->VisitFlood.assign(ToIndex(n[0] * n[1] * n[2]), 0);
  for (std::size_t i = 0; i < blocks.size(); ++i) // in run order: the last to cover a site owns it
  {
    const Block& b = blocks[i];
    this->Position[ToIndex(b.Index)] = static_cast<std::int32_t>(i);
    this->Blocks.push_back(b);
    ForEachSite(
      b, n, [&](std::size_t s) { this->OwnerPosition[s] = static_cast<std::int32_t>(i); });
  }
}

NetworkGuard::NetworkGuard(const NetworkRule& rule, const Coord& n, const Coord& off,
  const Coord& world, const LabelGrid* pins)
  : Rule(rule)
  , Maximum(0)
  , N(n)
  , Open(true)
  , Off(off)
  , World(world)
  , Pins(pins)
{
}

bool NetworkGuard::KeepsOpen(
  const Block& block, const Catalog& cat, const std::vector<std::int32_t>& model)
{
  // The footprint F and its ring R (clipped to the model): a flood over the network's sites of
  // F ∪ R; a component with a site in F must reach R, the world's border or a pin.
  const Coord& n = this->N;
  const Coord& o = block.Origin;
  Coord lo, hi, d;
  for (std::size_t a = 0; a < 3; ++a)
  {
    lo[a] = std::max<std::int64_t>(0, o[a] - 1);
    hi[a] = std::min(n[a], o[a] + block.Dims[a] + 1);
    d[a] = hi[a] - lo[a];
  }
  const auto at = [&](std::int64_t b) -> Coord {
    return { { lo[0] + b % d[0], lo[1] + (b / d[0]) % d[1], lo[2] + b / (d[0] * d[1]) } };
  };
  const auto inside = [&](const Coord& p)
  {
    for (std::size_t a = 0; a < 3; ++a)
      if (p[a] < o[a] || p[a] >= o[a] + block.Dims[a])
        return false;
    return true;
  };
  const auto label = [&](const Coord& p) -> std::int32_t
  {
    if (inside(p))
      return static_cast<std::int32_t>(cat.Single(
        (p[0] - o[0]) + block.Dims[0] * ((p[1] - o[1]) + block.Dims[1] * (p[2] - o[2]))));
    return model[ToIndex(p[0] + n[0] * (p[1] + n[1] * p[2]))];
  };
  const auto reaches = [&](const Coord& p)
  {
    if (!inside(p))
      return true; // the ring: the block does not decide what lies beyond
    for (std::size_t a = 0; a < 3; ++a)
    {
      const std::int64_t w = p[a] + this->Off[a];
      if (this->World[a] > 1 && (w == 0 || w == this->World[a] - 1))
        return true;
    }
    return this->Pins &&
      this->Pins->Data()[ToIndex(p[0] + n[0] * (p[1] + n[1] * p[2]))] != FreeSite;
  };
  const std::int64_t total = d[0] * d[1] * d[2];
  std::vector<char> seen(ToIndex(total), 0);
  std::vector<std::int64_t> stack;
  for (std::int64_t first = 0; first < total; ++first)
  {
    if (seen[ToIndex(first)] || !inside(at(first)) || this->Rule.Sides(label(at(first))) < 0)
      continue;
    bool open = false;
    seen[ToIndex(first)] = 1;
    stack.assign(1, first);
    while (!stack.empty())
    {
      const Coord p = at(stack.back());
      stack.pop_back();
      open = open || reaches(p);
      const int sides = this->Rule.Sides(label(p));
      for (int e = 0; e < 6; ++e)
      {
        const std::size_t a = ToIndex(e / 2);
        Coord q = p;
        q[a] += e % 2 == 0 ? 1 : -1;
        if (!((sides >> e) & 1) || q[a] < lo[a] || q[a] >= hi[a])
          continue;
        const int other = this->Rule.Sides(label(q));
        const std::int64_t t = (q[0] - lo[0]) + d[0] * ((q[1] - lo[1]) + d[1] * (q[2] - lo[2]));
        if (other < 0 || !((other >> (e ^ 1)) & 1) || seen[ToIndex(t)])
          continue;
        seen[ToIndex(t)] = 1;
        stack.push_back(t);
      }
    }
    if (!open)
    {
      ++this->Redone;
      return false;
    }
  }
  return true;
}

template <class LabelFn, class OpenFn>
std::int64_t NetworkGuard::ClosedAround(const Block& block, LabelFn&& label, OpenFn&& isOpen)
{
  // Floods from the network's sites in the block and from those facing it through a connecting
  // side; a flood ends as soon as it meets an open site (or a site an open flood saw): only the
  // closed-off components are walked whole. (stack: the breadth-first queue)
  const Coord& n = this->N;
  const std::int64_t stride[3] = { 1, n[0], n[0] * n[1] };
  if (++this->Call == 0) // wrapped: forget every mark
  {
    std::fill(this->VisitCall.begin(), this->VisitCall.end(), 0);
    this->Call = 1;
  }
  const std::uint32_t call = this->Call;
  std::vector<char> floodOpen;
  std::vector<std::int64_t> stack;
  std::int64_t closed = 0;
  auto flood = [&](std::int64_t first)
  {
    if (this->VisitCall[ToIndex(first)] == call)
      return;
    const auto id = static_cast<std::int32_t>(floodOpen.size());
    floodOpen.push_back(0);
    this->VisitCall[ToIndex(first)] = call;
    this->VisitFlood[ToIndex(first)] = id;
    stack.assign(1, first);
    bool open = false;
    // Breadth first: the open sites (those later blocks write, some in this block's overlap)
    // lie near the block, the finished ones farther away.
    for (std::size_t head = 0; head < stack.size() && !open; ++head)
    {
      const std::int64_t s = stack[head];
      open = isOpen(s);
      const int sides = this->Rule.Sides(label(s));
      for (int d = 0; d < 6 && !open; ++d)
      {
        const std::size_t a = ToIndex(d / 2);
        const std::int64_t along = (s / stride[a]) % n[a];
        if (!((sides >> d) & 1) || (d % 2 == 0 ? along + 1 >= n[a] : along == 0))
          continue;
        const std::int64_t q = s + (d % 2 == 0 ? stride[a] : -stride[a]);
        if (isOpen(q))
        {
          open = true; // the side faces a site still to be written
          break;
        }
        const int other = this->Rule.Sides(label(q));
        if (other < 0 || !((other >> (d ^ 1)) & 1))
          continue;
        if (this->VisitCall[ToIndex(q)] == call)
        {
          open = open || floodOpen[ToIndex(this->VisitFlood[ToIndex(q)])] != 0;
          continue; // its own flood's site, or an open flood's (a closed flood is whole)
        }
        this->VisitCall[ToIndex(q)] = call;
        this->VisitFlood[ToIndex(q)] = id;
        stack.push_back(q);
      }
    }
    floodOpen[ToIndex(id)] = open ? 1 : 0;
    closed += open ? 0 : 1;
  };
  ForEachSite(block, n,
    [&](std::size_t s)
    {
      if (this->Rule.Sides(label(static_cast<std::int64_t>(s))) >= 0)
        flood(static_cast<std::int64_t>(s));
    });
  ForEachRingSite(block, n,
    [&](std::int64_t s, int toward, std::int64_t)
    {
      const int sides = this->Rule.Sides(label(s));
      if (sides >= 0 && ((sides >> toward) & 1)) // a connecting side faces the block
        flood(s);
    });
  return closed;
}

template <class LabelFn>
bool NetworkGuard::AnyOpenAfter(std::int32_t now, LabelFn&& label) const
{
  const Coord& n = this->N;
  const std::int64_t stride[3] = { 1, n[0], n[0] * n[1] };
  for (std::size_t i = ToIndex(now) + 1; i < this->Blocks.size(); ++i)
  {
    bool open = false;
    ForEachSite(this->Blocks[i], n,
      [&](std::size_t site)
      {
        const auto s = static_cast<std::int64_t>(site);
        if (open)
          return;
        if (this->Rule.Sides(label(s)) >= 0)
        {
          open = true; // a network site still to be written
          return;
        }
        for (int d = 0; d < 6 && !open; ++d)
        {
          const std::size_t a = ToIndex(d / 2);
          const std::int64_t along = (s / stride[a]) % n[a];
          if (d % 2 == 0 ? along + 1 >= n[a] : along == 0)
            continue;
          const int other = this->Rule.Sides(label(s + (d % 2 == 0 ? stride[a] : -stride[a])));
          open = other >= 0 && ((other >> (d ^ 1)) & 1); // a connecting side faces it
        }
      });
    if (open)
      return true;
  }
  return false;
}

bool NetworkGuard::Keeps(
  const Block& block, const Catalog& cat, const std::vector<std::int32_t>& model)
{
  if (this->Open)
    return this->KeepsOpen(block, cat, model);
  // Closed-off components stay as they are (no later block writes their sites or the sites
  // their sides face), and every component the attempt's sites touch was open before it (they
  // were still to be written). So the attempt adds exactly the closed-off components among
  // those it touches after it (ClosedAround), and only when it adds some are the closed-off
  // components before it counted (once per block) and is the rest of the model looked at.
  const std::int32_t now = this->Position[ToIndex(block.Index)];
  const Coord& n = this->N;
  const Coord& o = block.Origin;
  auto inBlock = [&](std::int64_t s, std::int64_t& local)
  {
    const Coord p{ { s % n[0], (s / n[0]) % n[1], s / (n[0] * n[1]) } };
    for (std::size_t a = 0; a < 3; ++a)
      if (p[a] < o[a] || p[a] >= o[a] + block.Dims[a])
        return false;
    local = (p[0] - o[0]) + block.Dims[0] * ((p[1] - o[1]) + block.Dims[1] * (p[2] - o[2]));
    return true;
  };
  auto labelAfter = [&](std::int64_t s)
  {
    std::int64_t local = 0;
    return inBlock(s, local) ? static_cast<std::int32_t>(cat.Single(local)) : model[ToIndex(s)];
  };
  auto openAfter = [&](std::int64_t s)
  { return this->OwnerPosition[ToIndex(s)] > now || labelAfter(s) < 0; };
  const std::int64_t added = this->ClosedAround(block, labelAfter, openAfter);
  if (added == 0)
    return true;
  const std::int64_t limit =
    this->AnyOpenAfter(now, labelAfter) ? this->Maximum - 1 : this->Maximum;
  bool keeps = added <= limit; // at least: no closed-off component before
  if (keeps && this->ClosedFor != block.Index)
  {
    std::int64_t closed = 0;
    std::vector<std::int32_t> seen;
    std::vector<std::int64_t> stack;
    Flood(
      this->Rule, n, [&](std::int64_t s) { return model[ToIndex(s)]; },
      [&](std::int64_t s)
      { return this->OwnerPosition[ToIndex(s)] >= now || model[ToIndex(s)] < 0; },
      [&](const Component& c) { closed += c.Open ? 0 : 1; }, seen, stack);
    this->ClosedFor = block.Index;
    this->ClosedBefore = closed;
  }
  keeps = keeps && this->ClosedBefore + added <= limit;
  if (!keeps)
    ++this->Redone;
  return keeps;
}

NetworkRun::NetworkRun(const AdjacencyRules& rules, const SynthesisOptions& options,
  const std::vector<Block>& blocks, BlockSolver& solver, const RegionCone* cone)
  : Rule(rules, options.Connected)
{
  if (options.Connected.Open) // every block, in a window of a world too
  {
    this->Guard = std::make_unique<NetworkGuard>(this->Rule, solver.Size(),
      cone ? cone->WindowLow : Coord{ { 0, 0, 0 } }, cone ? cone->World : solver.Size(),
      options.Pins ? &*options.Pins : nullptr);
    solver.UseNetwork(this->Guard.get());
  }
  else if (blocks.size() > 1)
  {
    this->Guard =
      std::make_unique<NetworkGuard>(this->Rule, options.Connected.Maximum, blocks, solver.Size());
    solver.UseNetwork(this->Guard.get());
  }
}

bool NetworkRun::Keep(const SynthesisOptions& options, BlockSolver& solver, SharedModel& shared,
  const std::vector<Block>& blocks, SynthesisResult& r)
{
  ConnectedResult& out = r.Connected;
  out.Requested = true;
  out.Maximum = options.Connected.Maximum;
  out.Name = options.Connected.Name;
  out.Redone = this->Guard ? this->Guard->Refused() : 0;
  solver.UseNetwork(nullptr);
  if (options.Connected.Open) // no repairs: each block kept its part
  {
    out.Maximum = 0;
    out.Before = out.Components = CountComponents(this->Rule, shared.Model, solver.Size());
    return true;
  }
  std::int64_t next = 0;
  for (const Block& b : blocks)
    next = std::max(next, b.Index + 1);
  const std::string failure =
    RepairNetwork(solver, shared, this->Rule, options, next, r.Statistics, out);
  if (failure.empty())
    return true;
  r.Status = SynthesisStatus::Failed;
  r.Message = failure;
  return false;
}

} // namespace detail
} // namespace msynth
