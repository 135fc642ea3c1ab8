// SPDX-License-Identifier: BSD-3-Clause
// The repairs of a connected network after the blocks (Connectivity.h: RepairNetwork): boxes
// over the gaps between components steered along them, free boxes, boxes around a component.
#include "Discrete/Connectivity.h"
#include "Discrete/NetworkComponents.h"
#include "Discrete/NetworkParts.h"

#include "Core/Index.h"
#include "Core/Random.h"

#include <algorithm>
#include <array>

namespace msynth
{
namespace detail
{
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
  static constexpr int SteeredAttempts = 3; ///< attempts of a box steered along a gap
  /// The repairs' work is bounded (a network the rules cannot make ends in one line, not hours
  /// later): at most this many box attempts per component and listed path site at the start.
  static constexpr std::int64_t AttemptsPerPart = 64;
  BlockSolver& Solver;
  SharedModel& Shared;
  const NetworkRule& Rule;
  const SynthesisOptions& Options;
  SynthesisStatistics& Stats;
  std::int64_t Key = 0;       ///< the next box's block index
  std::vector<double> Sparse; ///< the network's labels' weights scaled down
  std::vector<std::int32_t> SavedModel, SavedLast;
  std::vector<std::int64_t> PathSites; ///< the listed path sites' model indices
  NetworkParts Net;                    ///< the components now
  std::int64_t PathLabelSites = 0;     ///< sites holding path labels before the repairs
  Shortfall Now{ { 0, 0, 0 } };
  std::int64_t Tried = 0;        ///< box attempts so far
  std::int64_t MissesBefore = 0; ///< the solver's count misses before the repairs
  std::int64_t LimitsBefore = 0; ///< the solver's count limits before the repairs
  std::int64_t MayTry = 0;       ///< box attempts allowed (AttemptsPerPart)

  Repair(BlockSolver& solver, SharedModel& shared, const NetworkRule& rule,
    const SynthesisOptions& options, SynthesisStatistics& stats)
    : Solver(solver)
    , Shared(shared)
    , Rule(rule)
    , Options(options)
    , Stats(stats)
    , PathSites(Listed(options, solver.Size()))
    , Net(rule, shared.Model, solver.Size(), this->PathSites)
  {
    this->Sparse.assign(ToIndex(rule.Labels()), 1.0);
    for (std::size_t b = 0; b < this->Sparse.size(); ++b)
      if (rule.Sides(static_cast<std::int32_t>(b)) >= 0)
        this->Sparse[b] = 1.0 / 64;
    this->MayTry =
      AttemptsPerPart * (1 + this->Net.Count() + static_cast<std::int64_t>(this->PathSites.size()));
    this->PathLabelSites = this->Net.PathLabelSites();
    this->Now = { { this->Net.PathSitesOutside(), this->Net.PathParts(), this->Net.Count() } };
  }

  static std::vector<std::int64_t> Listed(const SynthesisOptions& options, const Coord& n)
  {
    std::vector<std::int64_t> sites;
    for (const Coord& p : options.Connected.PathSites)
      sites.push_back(p[0] + n[0] * (p[1] + n[1] * p[2]));
    return sites;
  }

  /// Whether the model has what the network asks.
  bool Done() const
  {
    return this->Now[0] == 0 && this->Now[1] <= 1 &&
      this->Now[2] <= this->Options.Connected.Maximum;
  }

  /// Whether the repairs have made all the box attempts they may (AttemptsPerPart).
  bool OutOfWork() const { return this->Tried >= this->MayTry; }

  /**
   * The box [@p lo - @p grow, @p hi + @p grow] synthesized again, AttemptsPerBlock attempts
   * (each drawn with @p steer's weights when given, else every other one drawing the network's
   * labels rarely, so the box keeps only the paths its surroundings force), until one leaves a
   * smaller shortfall (and no fewer sites of the path's labels). Returns whether one did.
   */
  bool TryBox(const Coord& lo, const Coord& hi, std::int64_t grow,
    const BlockSolver::SiteBias* steer = nullptr)
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
    // A steered box finds a join in its first attempts when the pairs allow one along its gap.
    const int attempts = steer ? std::min(this->Options.AttemptsPerBlock, SteeredAttempts)
                               : this->Options.AttemptsPerBlock;
    for (int attempt = 0; attempt < attempts; ++attempt)
    {
      if (this->OutOfWork())
        return false;
      ++this->Tried;
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
      const NetworkParts::Outcome o = this->Net.Propose(box, this->SavedModel);
      const Shortfall f{ { o.PathSitesOutside, o.PathParts, o.Components } };
      if (f < this->Now && o.PathLabelSites >= this->PathLabelSites)
      {
        this->Net.Apply();
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
    constexpr std::int64_t MaximumGap = 16;
    const Coord n = this->Solver.Size();
    const std::int64_t stride[3] = { 1, n[0], n[0] * n[1] };
    const std::vector<std::int32_t>& ids = this->Net.Ids();
    const Component& part = this->Net.Parts()[ToIndex(c)];
    // The search stays within MaximumGap steps of the component's box.
    Coord lo, d;
    for (std::size_t a = 0; a < 3; ++a)
    {
      lo[a] = std::max<std::int64_t>(0, part.Low[a] - MaximumGap);
      d[a] = std::min(n[a], part.High[a] + MaximumGap + 1) - lo[a];
    }
    const auto local = [&](std::int64_t s)
    {
      const Coord p = this->At(s);
      return ToIndex((p[0] - lo[0]) + d[0] * ((p[1] - lo[1]) + d[1] * (p[2] - lo[2])));
    };
    std::vector<std::int64_t> parent(ToIndex(d[0] * d[1] * d[2]), -1), front, next;
    gap.clear();
    for (std::int64_t z = part.Low[2]; z <= part.High[2]; ++z)
      for (std::int64_t y = part.Low[1]; y <= part.High[1]; ++y)
        for (std::int64_t x = part.Low[0]; x <= part.High[0]; ++x)
        {
          const std::int64_t s = x + n[0] * (y + n[1] * z);
          if (ids[ToIndex(s)] == c + 1)
          {
            parent[local(s)] = s; // a root of the search
            front.push_back(s);
          }
        }
    for (std::int64_t step = 0; step < MaximumGap && !front.empty(); ++step)
    {
      next.clear();
      for (std::int64_t s : front)
        for (int e = 0; e < 6; ++e)
        {
          const auto a = ToIndex(e / 2);
          const std::int64_t along = (s / stride[a]) % n[a];
          if (e % 2 == 0 ? along + 1 >= n[a] : along == 0)
            continue;
          const std::int64_t q = s + (e % 2 == 0 ? stride[a] : -stride[a]);
          if (parent[local(q)] >= 0)
            continue;
          parent[local(q)] = s;
          const std::int32_t id = ids[ToIndex(q)];
          if (id != 0 && id != c + 1 && (!toPath || this->Net.HoldsPath(id - 1)))
          {
            for (std::int64_t t = q;; t = parent[local(t)])
            {
              gap.push_back(t);
              if (parent[local(t)] == t)
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

  /// Whether a network label connects through the sides site @p s connects through now and
  /// @p side too (else no gap can leave it there).
  bool Joinable(std::int64_t s, int side) const
  {
    const int need = std::max(this->Rule.Sides(this->Shared.Model[ToIndex(s)]), 0) | side;
    for (int b = 0; b < this->Rule.Labels(); ++b)
    {
      const int has = this->Rule.Sides(b);
      if (has >= 0 && (has & need) == need)
        return true;
    }
    return false;
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
      int sides = i == 0 || i + 1 == gap.size()
        ? std::max(this->Rule.Sides(this->Shared.Model[ToIndex(s)]), 0)
        : 0;
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

  /**
   * Straight gaps from component @p c (number @p c + 1) to another (with @p toPath, one holding
   * path sites): from a site of @p c along an axis over sites of no component to a site of the
   * other, at most MaximumGap steps, where a network label could connect each end toward the
   * gap (Joinable); the shortest first (ties in site order), at most MaximumStraight, each as
   * its sites in order.
   */
  std::vector<std::vector<std::int64_t>> StraightGaps(std::int32_t c, bool toPath) const
  {
    constexpr std::int64_t MaximumGap = 16;
    constexpr std::size_t MaximumStraight = 8;
    const Coord n = this->Solver.Size();
    const std::int64_t stride[3] = { 1, n[0], n[0] * n[1] };
    std::vector<std::vector<std::int64_t>> found;
    const std::vector<std::int32_t>& ids = this->Net.Ids();
    const Component& part = this->Net.Parts()[ToIndex(c)];
    for (std::int64_t z = part.Low[2]; z <= part.High[2]; ++z)
      for (std::int64_t y = part.Low[1]; y <= part.High[1]; ++y)
        for (std::int64_t x = part.Low[0]; x <= part.High[0]; ++x)
        {
          const std::int64_t s = x + n[0] * (y + n[1] * z);
          if (ids[ToIndex(s)] != c + 1)
            continue;
          const Coord p{ { x, y, z } };
          for (int d = 0; d < 6; ++d)
          {
            const auto a = ToIndex(d / 2);
            const std::int64_t step = d % 2 == 0 ? 1 : -1;
            for (std::int64_t k = 1; k <= MaximumGap; ++k)
            {
              const std::int64_t along = p[a] + step * k;
              if (along < 0 || along >= n[a])
                break;
              const std::int32_t id = ids[ToIndex(s + step * k * stride[a])];
              if (id == 0)
                continue;
              const std::int64_t q = s + step * k * stride[a];
              if (id != c + 1 && (!toPath || this->Net.HoldsPath(id - 1)) &&
                this->Joinable(s, 1 << d) && this->Joinable(q, 1 << (d ^ 1)))
              {
                std::vector<std::int64_t> gap;
                for (std::int64_t j = 0; j <= k; ++j)
                  gap.push_back(s + step * j * stride[a]);
                found.push_back(std::move(gap));
              }
              break;
            }
          }
        }
    std::stable_sort(found.begin(), found.end(),
      [](const std::vector<std::int64_t>& a, const std::vector<std::int64_t>& b)
      { return a.size() < b.size(); });
    if (found.size() > MaximumStraight)
      found.resize(MaximumStraight);
    return found;
  }

  /// The box [@p lo, @p hi] around the sites of @p gap.
  void Bounds(const std::vector<std::int64_t>& gap, Coord& lo, Coord& hi) const
  {
    lo = hi = this->At(gap.front());
    for (const std::int64_t s : gap)
      for (std::size_t a = 0; a < 3; ++a)
      {
        lo[a] = std::min(lo[a], this->At(s)[a]);
        hi[a] = std::max(hi[a], this->At(s)[a]);
      }
  }

  /**
   * Joins component @p c to another (with @p toPath, one holding path sites) through boxes over
   * a gap between them drawn steered along it (Steer), grown by 1 and then 2 sites: the straight
   * gaps (StraightGaps; the exemplars' pairs may forbid a road at one place and not at the
   * next), then the gap to the nearest other component (Gap); then boxes over that gap drawn
   * freely, grown by 1, 2, 4; else removes it (or joins it) through boxes around it grown by
   * 1, 2, ..., 16 sites.
   */
  bool Fix(std::size_t c, bool toPath)
  {
    if (this->OutOfWork())
      return false;
    std::vector<std::vector<std::int64_t>> gaps =
      this->StraightGaps(static_cast<std::int32_t>(c), toPath);
    std::vector<std::int64_t> nearest;
    this->Gap(static_cast<std::int32_t>(c), toPath, nearest);
    if (!nearest.empty())
      gaps.push_back(nearest);
    Coord lo, hi;
    for (std::int64_t grow = 1; grow <= 2; grow *= 2)
      for (const std::vector<std::int64_t>& gap : gaps)
      {
        this->Bounds(gap, lo, hi);
        const BlockSolver::SiteBias steer = this->Steer(gap);
        if (this->TryBox(lo, hi, grow, &steer))
          return true;
      }
    if (!nearest.empty())
    {
      this->Bounds(nearest, lo, hi);
      for (std::int64_t grow = 1; grow <= 4; grow *= 2)
        if (this->TryBox(lo, hi, grow))
          return true;
    }
    const Component part = this->Net.Parts()[c];
    for (std::int64_t grow = 1; grow <= 16; grow *= 2)
      if (this->TryBox(part.Low, part.High, grow))
        return true;
    return false;
  }

  /// One step nearer: a listed path site brought into the network, else a component holding
  /// path sites joined to another such, else any component joined or removed (smallest first).
  bool Step()
  {
    if (this->OutOfWork())
      return false;
    for (std::int64_t s : this->PathSites)
      if (this->Net.Ids()[ToIndex(s)] == 0)
      {
        const Coord p = this->At(s);
        for (std::int64_t grow = 1; grow <= 8; grow *= 2)
          if (this->TryBox(p, p, grow))
            return true;
      }
    // Smallest first; a repair that succeeds changes the components, so the walk stops there.
    if (this->Now[1] > 1)
      for (const auto& [sites, c] : this->Net.BySize())
        if (this->Net.HoldsPath(c) && this->Fix(ToIndex(c), true))
          return true;
    for (const auto& [sites, c] : this->Net.BySize())
      if (this->Fix(ToIndex(c), false))
        return true;
    return false;
  }

  /// Why the network cannot be kept, in one line.
  std::string Failure() const
  {
    const std::string name = NetworkName(this->Options.Connected);
    std::string counts; // what the label counts held back (BlockSolver::SetCountsOfModel)
    if (!this->Options.Counts.empty())
      counts = " (the label counts held back " +
        std::to_string(this->Solver.CountLimits() - this->LimitsBefore) +
        " box attempts at a range's end and turned down " +
        std::to_string(this->Solver.CountMisses() - this->MissesBefore) +
        " solved ones; wider counts leave the repairs room)";
    const std::string tried =
      (this->OutOfWork()
          ? "the repairs stopped after " + std::to_string(this->Tried) + " box attempts (" +
            std::to_string(AttemptsPerPart) + " per component and path site at the start)"
          : "no repair brought them nearer") +
      counts;
    if (this->Now[0] > 0 || this->Now[1] > 1)
      return name + " does not join the path: " +
        (this->Now[0] > 0 ? std::to_string(this->Now[0]) + " of its sites hold no network label"
                          : "its sites lie in " + std::to_string(this->Now[1]) + " components") +
        ", and " + tried + ". Try another seed, more attempts or nearer sites";
    const Component& c = this->Net.Parts()[ToIndex(this->Net.BySize().begin()->second)];
    return name + " has " + std::to_string(this->Net.Count()) + " components, more than " +
      std::to_string(this->Options.Connected.Maximum) +
      (this->OutOfWork() ? ", and " + tried
                         : ", and none could be joined to another or removed" + counts) +
      " (the smallest: " + std::to_string(c.Sites) + (c.Sites == 1 ? " site at " : " sites at ") +
      Format(c.Low) + "). Try another seed, more attempts or a larger maximum";
  }
};
} // namespace

std::string RepairNetwork(BlockSolver& solver, SharedModel& shared, const NetworkRule& rule,
  const SynthesisOptions& options, std::int64_t firstIndex, SynthesisStatistics& stats,
  ConnectedResult& out)
{
  Repair repair(solver, shared, rule, options, stats);
  repair.Key = firstIndex;
  // With label counts every box keeps the model's counts in their ranges (the blocks kept
  // them; a count's labels are not drawn where the range leaves the box none): the network,
  // the counts and the pins (fixed labels in every box) hold together.
  repair.MissesBefore = solver.CountMisses();
  repair.LimitsBefore = solver.CountLimits();
  solver.SetCountsOfModel(true);
  struct Restore
  {
    BlockSolver& Solver;
    ~Restore() { this->Solver.SetCountsOfModel(false); }
  } restore{ solver };
  out.Before = repair.Net.Count();
  out.PathComponentsBefore = repair.Now[1];
  while (!repair.Done())
  {
    if (!repair.Step())
      return repair.Failure();
    ++out.Repairs;
  }
  out.Components = repair.Net.Count();
  out.PathSites = static_cast<std::int64_t>(repair.PathSites.size()) + repair.Net.PathLabelSites();
  return std::string();
}

} // namespace detail
} // namespace msynth
