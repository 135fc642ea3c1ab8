// SPDX-License-Identifier: BSD-3-Clause
#include "Discrete/Connectivity.h"

#include "Core/Error.h"
#include "Discrete/MirrorPlan.h"
#include "Discrete/SymmetryPlan.h"

#include <algorithm>
#include <limits>
#include <set>

namespace msynth
{
namespace detail
{
namespace
{

/// A component of the network found by Flood.
struct Component
{
  std::int64_t Sites = 0;
  bool Open = false;
  Coord Low{ { 0, 0, 0 } }, High{ { 0, 0, 0 } }; ///< bounding box, inclusive
};

/**
 * The components of the network over @p n sites whose label index at site s is label(s);
 * open(s) says whether a later block writes s. Calls @p found for each, in the order of their
 * first site.
 */
template <class LabelFn, class OpenFn, class FoundFn>
void Flood(const NetworkRule& rule, const Coord& n, LabelFn&& label, OpenFn&& open, FoundFn&& found,
  std::vector<std::uint8_t>& seen, std::vector<std::int64_t>& stack)
{
  const std::int64_t total = n[0] * n[1] * n[2];
  const std::int64_t stride[3] = { 1, n[0], n[0] * n[1] };
  seen.assign(static_cast<std::size_t>(total), 0);
  for (std::int64_t first = 0; first < total; ++first)
  {
    if (seen[static_cast<std::size_t>(first)] || rule.Sides(label(first)) < 0)
      continue;
    Component c;
    c.Low = { { first % n[0], (first / n[0]) % n[1], first / (n[0] * n[1]) } };
    c.High = c.Low;
    seen[static_cast<std::size_t>(first)] = 1;
    stack.assign(1, first);
    while (!stack.empty())
    {
      const std::int64_t s = stack.back();
      stack.pop_back();
      ++c.Sites;
      const Coord p{ { s % n[0], (s / n[0]) % n[1], s / (n[0] * n[1]) } };
      for (std::size_t a = 0; a < 3; ++a)
      {
        c.Low[a] = std::min(c.Low[a], p[a]);
        c.High[a] = std::max(c.High[a], p[a]);
      }
      c.Open = c.Open || open(s);
      const int sides = rule.Sides(label(s));
      for (int d = 0; d < 6; ++d)
      {
        const std::size_t a = static_cast<std::size_t>(d / 2);
        const bool up = d % 2 == 0;
        if (!((sides >> d) & 1) || (up ? p[a] + 1 >= n[a] : p[a] == 0))
          continue;
        const std::int64_t q = s + (up ? stride[a] : -stride[a]);
        if (open(q))
          c.Open = true; // the side faces a site still to be written
        const int other = rule.Sides(label(q));
        if (other < 0 || !((other >> (d ^ 1)) & 1) || seen[static_cast<std::size_t>(q)])
          continue;
        seen[static_cast<std::size_t>(q)] = 1;
        stack.push_back(q);
      }
    }
    found(c);
  }
}

std::vector<Component> FindComponents(
  const NetworkRule& rule, const std::vector<std::int32_t>& model, const Coord& n)
{
  std::vector<Component> out;
  std::vector<std::uint8_t> seen;
  std::vector<std::int64_t> stack;
  Flood(
    rule, n, [&](std::int64_t s) { return model[static_cast<std::size_t>(s)]; },
    [](std::int64_t) { return false; }, [&](const Component& c) { out.push_back(c); }, seen, stack);
  return out;
}

std::string NetworkName(const ConnectedNetwork& network)
{
  return "the network of " + (network.Name.empty() ? std::string("its labels") : network.Name);
}
} // namespace

NetworkRule::NetworkRule(const AdjacencyRules& rules, const ConnectedNetwork& network)
{
  this->Mask.assign(static_cast<std::size_t>(rules.NumberOfLabels()), -1);
  for (Label v : network.Values)
  {
    const int b = rules.IndexOf(v);
    if (b < 0)
      continue;
    const auto side = network.Sides.find(v);
    this->Mask[static_cast<std::size_t>(b)] = side == network.Sides.end() ? 63 : side->second;
  }
}

void CheckConnectedRequest(const AdjacencyRules& rules, const SynthesisOptions& options)
{
  const ConnectedNetwork& network = options.Connected;
  if (!network.Active())
    return;
  const std::string name = NetworkName(network);
  if (AnyMirror(options) || AnySeamSymmetry(options))
    throw Error(name +
      " cannot be combined with symmetry (only a part of the output is "
      "synthesized)");
  if (options.Soft.Active())
    throw Error(name + " cannot be combined with soft constraints (which roll blocks back)");
  if (!options.Counts.empty())
    throw Error(name + " cannot be combined with label counts (a repair would move them)");
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
  this->Position.assign(static_cast<std::size_t>(indices), -1);
  this->OwnerPosition.assign(static_cast<std::size_t>(n[0] * n[1] * n[2]), -1);
  for (std::size_t i = 0; i < blocks.size(); ++i) // in run order: the last to cover a site owns it
  {
    const Block& b = blocks[i];
    this->Position[static_cast<std::size_t>(b.Index)] = static_cast<std::int32_t>(i);
    ForEachSite(
      b, n, [&](std::size_t s) { this->OwnerPosition[s] = static_cast<std::int32_t>(i); });
  }
}

bool NetworkGuard::Keeps(
  const Block& block, const Catalog& cat, const std::vector<std::int32_t>& model)
{
  const std::int32_t now = this->Position[static_cast<std::size_t>(block.Index)];
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
  std::vector<std::uint8_t> seen;
  std::vector<std::int64_t> stack;
  auto tally = [&](bool after, std::int64_t& closed, std::int64_t& open)
  {
    auto label = [&](std::int64_t s)
    {
      std::int64_t local = 0;
      return after && inBlock(s, local) ? static_cast<std::int32_t>(cat.Single(local))
                                        : model[static_cast<std::size_t>(s)];
    };
    auto isOpen = [&](std::int64_t s)
    {
      const std::int32_t owner = this->OwnerPosition[static_cast<std::size_t>(s)];
      return (after ? owner > now : owner >= now) || label(s) < 0;
    };
    closed = open = 0;
    Flood(
      this->Rule, n, label, isOpen, [&](const Component& c) { ++(c.Open ? open : closed); }, seen,
      stack);
  };
  std::int64_t closedBefore = 0, openBefore = 0, closed = 0, open = 0;
  tally(false, closedBefore, openBefore);
  tally(true, closed, open);
  const std::int64_t limit = open > 0 ? this->Maximum - 1 : this->Maximum;
  const bool keeps = closed <= std::max(limit, closedBefore);
  if (!keeps)
    ++this->Redone;
  return keeps;
}

namespace
{
/**
 * One repair of @p c: boxes around it grown by 1, 2, 4, ... up to MaximumGrowth sites,
 * AttemptsPerBlock attempts each, until a result has fewer components than @p parts (then
 * @p parts is the new list). Block indices from @p key on.
 */
bool RepairComponent(BlockSolver& solver, SharedModel& shared, const NetworkRule& rule,
  const SynthesisOptions& options, const Component& c, std::int64_t& key,
  SynthesisStatistics& stats, std::vector<Component>& parts)
{
  constexpr std::int64_t MaximumGrowth = 16;
  const Coord n = solver.Size();
  std::vector<double> sparse(static_cast<std::size_t>(rule.Labels()), 1.0);
  for (std::size_t b = 0; b < sparse.size(); ++b)
    if (rule.Sides(static_cast<std::int32_t>(b)) >= 0)
      sparse[b] = 1.0 / 64;
  std::vector<std::int32_t> savedModel, savedLast;
  bool whole = false;
  for (std::int64_t grow = 1; grow <= MaximumGrowth && !whole; grow *= 2)
  {
    Block box;
    box.Index = key++;
    whole = true;
    for (std::size_t a = 0; a < 3; ++a)
    {
      box.Origin[a] = std::max<std::int64_t>(0, c.Low[a] - grow);
      box.Dims[a] = std::min(n[a], c.High[a] + grow + 1) - box.Origin[a];
      whole = whole && box.Dims[a] == n[a];
    }
    savedModel.clear();
    savedLast.clear();
    ForEachSite(box, n,
      [&](std::size_t s)
      {
        savedModel.push_back(shared.Model[s]);
        savedLast.push_back(shared.LastBlock[s]);
      });
    for (int attempt = 0; attempt < options.AttemptsPerBlock; ++attempt)
    {
      Random rng = Random::Derived(options.Seed, static_cast<std::uint64_t>(box.Index),
        static_cast<std::uint64_t>(attempt) + (std::uint64_t(1) << 40));
      ++stats.Attempts;
      // Every other attempt draws the network's labels rarely: the box keeps only the paths
      // its surroundings force, which continue those outside.
      solver.ScaleWeights(attempt % 2 == 1 ? &sparse : nullptr);
      const std::int64_t empty = solver.RunBlock(box, rng, stats.Assignments);
      solver.ScaleWeights(nullptr);
      if (empty >= 0)
        continue; // a failed attempt leaves the model as it was
      std::vector<Component> now = FindComponents(rule, shared.Model, n);
      if (now.size() < parts.size())
      {
        parts = std::move(now);
        return true;
      }
      std::size_t i = 0;
      ForEachSite(box, n,
        [&](std::size_t s)
        {
          shared.Model[s] = savedModel[i];
          shared.LastBlock[s] = savedLast[i++];
        });
    }
  }
  return false;
}
} // namespace

std::string RepairNetwork(BlockSolver& solver, SharedModel& shared, const NetworkRule& rule,
  const SynthesisOptions& options, std::int64_t firstIndex, SynthesisStatistics& stats,
  ConnectedResult& out)
{
  const Coord n = solver.Size();
  std::vector<Component> parts = FindComponents(rule, shared.Model, n);
  out.Before = static_cast<std::int64_t>(parts.size());
  std::int64_t key = firstIndex;
  while (static_cast<std::int64_t>(parts.size()) > out.Maximum)
  {
    // The smallest components first (the first of equal ones): the cheapest to join or remove;
    // one that can be neither gives way to the next.
    std::vector<std::size_t> order(parts.size());
    for (std::size_t i = 0; i < order.size(); ++i)
      order[i] = i;
    std::stable_sort(order.begin(), order.end(),
      [&](std::size_t a, std::size_t b) { return parts[a].Sites < parts[b].Sites; });
    bool repaired = false;
    for (std::size_t i = 0; i < order.size() && !repaired; ++i)
      repaired = RepairComponent(
        solver, shared, rule, options, Component(parts[order[i]]), key, stats, parts);
    if (!repaired)
    {
      const Component& c = parts[order[0]];
      return NetworkName(options.Connected) + " has " + std::to_string(parts.size()) +
        " components, more than " + std::to_string(out.Maximum) +
        ", and none could be joined to another or removed (the smallest: " +
        std::to_string(c.Sites) + " sites at " + Format(c.Low) +
        "). Try another seed, more attempts or a larger maximum";
    }
    ++out.Repairs;
  }
  out.Components = static_cast<std::int64_t>(parts.size());
  return std::string();
}

NetworkRun::NetworkRun(const AdjacencyRules& rules, const SynthesisOptions& options,
  const std::vector<Block>& blocks, BlockSolver& solver)
  : Rule(rules, options.Connected)
{
  if (blocks.size() > 1)
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
