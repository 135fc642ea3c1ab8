// SPDX-License-Identifier: BSD-3-Clause
#include "Discrete/Connectivity.h"

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
  std::vector<std::int32_t>& seen, std::vector<std::int64_t>& stack)
{
  const std::int64_t total = n[0] * n[1] * n[2];
  const std::int64_t stride[3] = { 1, n[0], n[0] * n[1] };
  seen.assign(ToIndex(total), 0);
  std::int32_t number = 0; // seen: the component's number + 1
  for (std::int64_t first = 0; first < total; ++first)
  {
    if (seen[ToIndex(first)] || rule.Sides(label(first)) < 0)
      continue;
    Component c;
    c.Low = { { first % n[0], (first / n[0]) % n[1], first / (n[0] * n[1]) } };
    c.High = c.Low;
    seen[ToIndex(first)] = ++number;
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
        const std::size_t a = ToIndex(d / 2);
        const bool up = d % 2 == 0;
        if (!((sides >> d) & 1) || (up ? p[a] + 1 >= n[a] : p[a] == 0))
          continue;
        const std::int64_t q = s + (up ? stride[a] : -stride[a]);
        if (open(q))
          c.Open = true; // the side faces a site still to be written
        const int other = rule.Sides(label(q));
        if (other < 0 || !((other >> (d ^ 1)) & 1) || seen[ToIndex(q)])
          continue;
        seen[ToIndex(q)] = number;
        stack.push_back(q);
      }
    }
    found(c);
  }
}

/// The components of @p model; @p ids (when given) receives each site's component number + 1
/// (0: not in the network).
std::vector<Component> FindComponents(const NetworkRule& rule,
  const std::vector<std::int32_t>& model, const Coord& n, std::vector<std::int32_t>* ids = nullptr)
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
  if (!options.Counts.empty())
    throw Error(name + " cannot be combined with label counts (a repair would move them)");
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
  for (std::size_t i = 0; i < blocks.size(); ++i) // in run order: the last to cover a site owns it
  {
    const Block& b = blocks[i];
    this->Position[ToIndex(b.Index)] = static_cast<std::int32_t>(i);
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

bool NetworkGuard::Keeps(
  const Block& block, const Catalog& cat, const std::vector<std::int32_t>& model)
{
  if (this->Open)
    return this->KeepsOpen(block, cat, model);
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
  std::vector<std::int32_t> seen;
  std::vector<std::int64_t> stack;
  auto tally = [&](bool after, std::int64_t& closed, std::int64_t& open)
  {
    auto label = [&](std::int64_t s)
    {
      std::int64_t local = 0;
      return after && inBlock(s, local) ? static_cast<std::int32_t>(cat.Single(local))
                                        : model[ToIndex(s)];
    };
    auto isOpen = [&](std::int64_t s)
    {
      const std::int32_t owner = this->OwnerPosition[ToIndex(s)];
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
 * How far a model is from what the network asks, compared lexicographically (smaller is nearer):
 * listed path sites outside the network, components holding path sites, all components.
 */
using Shortfall = std::array<std::int64_t, 3>;

/// The repairs' state: the model, the components, the path and scratch space.
struct Repair
{
  BlockSolver& Solver;
  SharedModel& Shared;
  const NetworkRule& Rule;
  const SynthesisOptions& Options;
  SynthesisStatistics& Stats;
  std::int64_t Key = 0;          ///< the next box's block index
  std::vector<Component> Parts;  ///< the components now
  std::vector<std::int32_t> Ids; ///< per site, its component's number + 1 (0: none)
  std::vector<double> Sparse;    ///< the network's labels' weights scaled down
  std::vector<std::int32_t> SavedModel, SavedLast;
  std::vector<std::int64_t> PathSites; ///< the listed path sites' model indices
  std::vector<char> PathLabel;         ///< per label index, whether it is a path label
  std::int64_t PathLabelSites = 0;     ///< sites holding path labels before the repairs
  std::vector<char> PathPart;          ///< per component, whether it holds a path site
  Shortfall Now{ { 0, 0, 0 } };

  Repair(BlockSolver& solver, SharedModel& shared, const NetworkRule& rule,
    const SynthesisOptions& options, SynthesisStatistics& stats)
    : Solver(solver)
    , Shared(shared)
    , Rule(rule)
    , Options(options)
    , Stats(stats)
  {
    this->Parts = FindComponents(rule, shared.Model, solver.Size(), &this->Ids);
    this->Sparse.assign(ToIndex(rule.Labels()), 1.0);
    for (std::size_t b = 0; b < this->Sparse.size(); ++b)
      if (rule.Sides(static_cast<std::int32_t>(b)) >= 0)
        this->Sparse[b] = 1.0 / 64;
    const Coord n = solver.Size();
    for (const Coord& p : options.Connected.PathSites)
      this->PathSites.push_back(p[0] + n[0] * (p[1] + n[1] * p[2]));
    this->PathLabel.assign(ToIndex(rule.Labels()), 0);
    for (int b = 0; b < rule.Labels(); ++b)
      this->PathLabel[ToIndex(b)] = rule.OnPath(b) ? 1 : 0;
    this->PathLabelSites = this->CountPathLabelSites(shared.Model);
    this->Now = this->Measure(this->Parts, this->Ids, this->PathPart);
  }

  std::int64_t CountPathLabelSites(const std::vector<std::int32_t>& model) const
  {
    std::int64_t count = 0;
    for (std::int32_t b : model)
      count += b >= 0 && this->PathLabel[ToIndex(b)] ? 1 : 0;
    return count;
  }

  /// The shortfall of @p parts (site numbers @p ids); @p pathPart marks the components holding
  /// path sites.
  Shortfall Measure(const std::vector<Component>& parts, const std::vector<std::int32_t>& ids,
    std::vector<char>& pathPart) const
  {
    pathPart.assign(parts.size(), 0);
    Shortfall f{ { 0, 0, static_cast<std::int64_t>(parts.size()) } };
    for (std::int64_t s : this->PathSites)
    {
      const std::int32_t id = ids[ToIndex(s)];
      if (id == 0)
        ++f[0];
      else
        pathPart[ToIndex(id - 1)] = 1;
    }
    if (!this->Options.Connected.PathLabels.empty())
      for (std::size_t s = 0; s < ids.size(); ++s)
      {
        const std::int32_t b = this->Shared.Model[s];
        if (b >= 0 && this->PathLabel[ToIndex(b)] && ids[s] != 0)
          pathPart[ToIndex(ids[s] - 1)] = 1;
      }
    for (char c : pathPart)
      f[1] += c;
    return f;
  }

  /// Whether the model has what the network asks.
  bool Done() const
  {
    return this->Now[0] == 0 && this->Now[1] <= 1 &&
      this->Now[2] <= this->Options.Connected.Maximum;
  }

  /**
   * The box [@p lo - @p grow, @p hi + @p grow] synthesized again, AttemptsPerBlock attempts
   * (each drawn with @p steer's weights when given, else every other one drawing the network's
   * labels rarely, so the box keeps only the paths its surroundings force), until one leaves a
   * smaller shortfall (and no fewer sites of the path's labels). Returns whether one did.
   */
  bool TryBox(
    const Coord& lo, const Coord& hi, std::int64_t grow, const BlockSolver::SiteBias* steer = nullptr)
  {
    const Coord n = this->Solver.Size();
    Block box;
    box.Index = this->Key++;
    for (std::size_t a = 0; a < 3; ++a)
    {
      box.Origin[a] = std::max<std::int64_t>(0, lo[a] - grow);
      box.Dims[a] = std::min(n[a], hi[a] + grow + 1) - box.Origin[a];
    }
    this->SavedModel.clear();
    this->SavedLast.clear();
    ForEachSite(box, n,
      [&](std::size_t s)
      {
        this->SavedModel.push_back(this->Shared.Model[s]);
        this->SavedLast.push_back(this->Shared.LastBlock[s]);
      });
    for (int attempt = 0; attempt < this->Options.AttemptsPerBlock; ++attempt)
    {
      Random rng = Random::Derived(this->Options.Seed, static_cast<std::uint64_t>(box.Index),
        static_cast<std::uint64_t>(attempt) + (std::uint64_t(1) << 40));
      ++this->Stats.Attempts;
      this->Solver.ScaleWeights(attempt % 2 == 1 && !steer ? &this->Sparse : nullptr);
      this->Solver.BiasWeights(steer);
      const std::int64_t empty = this->Solver.RunBlock(box, rng, this->Stats.Assignments);
      this->Solver.ScaleWeights(nullptr);
      this->Solver.BiasWeights(nullptr);
      if (empty >= 0)
        continue; // a failed attempt leaves the model as it was
      std::vector<std::int32_t> ids;
      std::vector<char> pathPart;
      std::vector<Component> now = FindComponents(this->Rule, this->Shared.Model, n, &ids);
      const Shortfall f = this->Measure(now, ids, pathPart);
      if (f < this->Now && this->CountPathLabelSites(this->Shared.Model) >= this->PathLabelSites)
      {
        this->Parts = std::move(now);
        this->Ids = std::move(ids);
        this->PathPart = std::move(pathPart);
        this->Now = f;
        return true;
      }
      std::size_t i = 0;
      ForEachSite(box, n,
        [&](std::size_t s)
        {
          this->Shared.Model[s] = this->SavedModel[i];
          this->Shared.LastBlock[s] = this->SavedLast[i++];
        });
    }
    return false;
  }

  /**
   * The nearest site of another component to component @p c (number @p c + 1) by face steps
   * (at most MaximumGap), with @p toPath one that holds path sites: the breadth-first search's
   * steps from a site of @p c to it, both ends included, in @p gap (empty when none is that near).
   */
  void Gap(std::int32_t c, bool toPath, std::vector<std::int64_t>& gap) const
  {
    constexpr std::int32_t MaximumGap = 16;
    const Coord n = this->Solver.Size();
    const std::int64_t stride[3] = { 1, n[0], n[0] * n[1] };
    std::vector<std::int64_t> parent(this->Ids.size(), -1), front, next;
    gap.clear();
    for (std::size_t s = 0; s < this->Ids.size(); ++s)
      if (this->Ids[s] == c + 1)
      {
        parent[s] = static_cast<std::int64_t>(s); // a root of the search
        front.push_back(static_cast<std::int64_t>(s));
      }
    for (std::int32_t step = 0; step < MaximumGap && !front.empty(); ++step)
    {
      next.clear();
      for (std::int64_t s : front)
        for (int d = 0; d < 6; ++d)
        {
          const auto a = ToIndex(d / 2);
          const std::int64_t along = (s / stride[a]) % n[a];
          if (d % 2 == 0 ? along + 1 >= n[a] : along == 0)
            continue;
          const std::int64_t q = s + (d % 2 == 0 ? stride[a] : -stride[a]);
          if (parent[ToIndex(q)] >= 0)
            continue;
          parent[ToIndex(q)] = s;
          const std::int32_t id = this->Ids[ToIndex(q)];
          if (id != 0 && id != c + 1 && (!toPath || this->PathPart[ToIndex(id - 1)]))
          {
            for (std::int64_t t = q;; t = parent[ToIndex(t)])
            {
              gap.push_back(t);
              if (parent[ToIndex(t)] == t)
                break;
            }
            std::reverse(gap.begin(), gap.end());
            return;
          }
          next.push_back(q);
        }
      front.swap(next);
    }
  }

  /// The side bit (Sides) of site @p s that faces its neighbour @p t.
  int Facing(std::int64_t s, std::int64_t t) const
  {
    const Coord p = this->At(s), q = this->At(t);
    for (std::size_t a = 0; a < 3; ++a)
      if (p[a] != q[a])
        return 1 << (2 * static_cast<int>(a) + (q[a] > p[a] ? 0 : 1));
    return 0;
  }

  /**
   * The weights that steer a box along @p gap (from one component to another): at each site of
   * the gap a label that connects toward its neighbours on the gap (at the ends, also through
   * the sides the site's label connects through now) is drawn Prefer times as often, less 8
   * times for each further side; every other site keeps its label Keep times as often.
   */
  BlockSolver::SiteBias Steer(const std::vector<std::int64_t>& gap) const
  {
    constexpr double Prefer = 1.0e4, Keep = 1.0e3;
    std::vector<std::pair<std::int64_t, int>> need; // (site, the sides it must connect through)
    for (std::size_t i = 0; i < gap.size(); ++i)
    {
      const std::int64_t s = gap[i];
      int sides = i == 0 || i + 1 == gap.size() ? std::max(this->Rule.Sides(this->Shared.Model[ToIndex(s)]), 0) : 0;
      if (i > 0)
        sides |= this->Facing(s, gap[i - 1]);
      if (i + 1 < gap.size())
        sides |= this->Facing(s, gap[i + 1]);
      need.emplace_back(s, sides);
    }
    return [this, need](std::int64_t site, int b)
    {
      for (const auto& [s, sides] : need)
        if (s == site)
        {
          const int has = this->Rule.Sides(b);
          if (has < 0 || (has & sides) != sides)
            return 1.0;
          double w = Prefer;
          for (int extra = has & ~sides; extra != 0; extra &= extra - 1)
            w /= 8.0;
          return w;
        }
      return this->Shared.Model[ToIndex(site)] == b ? Keep : 1.0;
    };
  }

  Coord At(std::int64_t s) const
  {
    const Coord n = this->Solver.Size();
    return Coord{ { s % n[0], (s / n[0]) % n[1], s / (n[0] * n[1]) } };
  }

  /// Joins component @p c to its nearest neighbour (with @p toPath, one holding path sites)
  /// through boxes over the gap between them, first steered along it (Steer) grown by 1 and 2
  /// sites, then drawn freely grown by 1, 2, 4; else removes it (or joins it) through boxes
  /// around it grown by 1, 2, ..., 16 sites.
  bool Fix(std::size_t c, bool toPath)
  {
    std::vector<std::int64_t> gap;
    this->Gap(static_cast<std::int32_t>(c), toPath, gap);
    if (!gap.empty())
    {
      const Coord p = this->At(gap.front()), q = this->At(gap.back());
      Coord lo, hi;
      for (std::size_t a = 0; a < 3; ++a)
      {
        lo[a] = std::min(p[a], q[a]);
        hi[a] = std::max(p[a], q[a]);
      }
      for (const std::int64_t s : gap)
        for (std::size_t a = 0; a < 3; ++a)
        {
          lo[a] = std::min(lo[a], this->At(s)[a]);
          hi[a] = std::max(hi[a], this->At(s)[a]);
        }
      const BlockSolver::SiteBias steer = this->Steer(gap);
      for (std::int64_t grow = 1; grow <= 2; grow *= 2)
        if (this->TryBox(lo, hi, grow, &steer))
          return true;
      for (std::int64_t grow = 1; grow <= 4; grow *= 2)
        if (this->TryBox(lo, hi, grow))
          return true;
    }
    const Component part = this->Parts[c];
    for (std::int64_t grow = 1; grow <= 16; grow *= 2)
      if (this->TryBox(part.Low, part.High, grow))
        return true;
    return false;
  }

  /// One step nearer: a listed path site brought into the network, else a component holding
  /// path sites joined to another such, else any component joined or removed (smallest first).
  bool Step()
  {
    for (std::int64_t s : this->PathSites)
      if (this->Ids[ToIndex(s)] == 0)
      {
        const Coord p = this->At(s);
        for (std::int64_t grow = 1; grow <= 8; grow *= 2)
          if (this->TryBox(p, p, grow))
            return true;
      }
    std::vector<std::size_t> order(this->Parts.size());
    for (std::size_t i = 0; i < order.size(); ++i)
      order[i] = i;
    std::stable_sort(order.begin(), order.end(),
      [&](std::size_t a, std::size_t b) { return this->Parts[a].Sites < this->Parts[b].Sites; });
    if (this->Now[1] > 1)
      for (std::size_t c : order)
        if (this->PathPart[c] && this->Fix(c, true))
          return true;
    for (std::size_t c : order)
      if (this->Fix(c, false))
        return true;
    return false;
  }

  /// Why the network cannot be kept, in one line.
  std::string Failure() const
  {
    const std::string name = NetworkName(this->Options.Connected);
    if (this->Now[0] > 0 || this->Now[1] > 1)
      return name + " does not join the path: " +
        (this->Now[0] > 0 ? std::to_string(this->Now[0]) + " of its sites hold no network label"
                          : "its sites lie in " + std::to_string(this->Now[1]) + " components") +
        ", and no repair brought them nearer. Try another seed, more attempts or nearer sites";
    std::size_t smallest = 0;
    for (std::size_t c = 1; c < this->Parts.size(); ++c)
      if (this->Parts[c].Sites < this->Parts[smallest].Sites)
        smallest = c;
    const Component& c = this->Parts[smallest];
    return name + " has " + std::to_string(this->Parts.size()) + " components, more than " +
      std::to_string(this->Options.Connected.Maximum) +
      ", and none could be joined to another or removed (the smallest: " + std::to_string(c.Sites) +
      " sites at " + Format(c.Low) + "). Try another seed, more attempts or a larger maximum";
  }
};
} // namespace

std::string RepairNetwork(BlockSolver& solver, SharedModel& shared, const NetworkRule& rule,
  const SynthesisOptions& options, std::int64_t firstIndex, SynthesisStatistics& stats,
  ConnectedResult& out)
{
  Repair repair(solver, shared, rule, options, stats);
  repair.Key = firstIndex;
  out.Before = static_cast<std::int64_t>(repair.Parts.size());
  out.PathComponentsBefore = repair.Now[1];
  while (!repair.Done())
  {
    if (!repair.Step())
      return repair.Failure();
    ++out.Repairs;
  }
  out.Components = static_cast<std::int64_t>(repair.Parts.size());
  out.PathSites =
    static_cast<std::int64_t>(repair.PathSites.size()) + repair.CountPathLabelSites(shared.Model);
  return std::string();
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
