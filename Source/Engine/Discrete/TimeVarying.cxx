// SPDX-License-Identifier: BSD-3-Clause
#include "Discrete/TimeVarying.h"

#include "Core/BlockDriver.h"
#include "Core/Error.h"
#include "Core/LabelDraw.h"
#include "Core/Memory.h"

#include "Core/Index.h"
#include "Core/Random.h"

#include <algorithm>
#include <chrono>
#include <map>
#include <numeric>
#include <set>
#include <tuple>

namespace msynth
{

namespace
{
constexpr int TimeDirections = 8; // +x -x +y -y +z -z +t -t
constexpr int PlusT = 6;

std::string Format(const Coord4& p)
{
  return "(" + std::to_string(p[0]) + ", " + std::to_string(p[1]) + ", " + std::to_string(p[2]) +
    ") of frame " + std::to_string(p[3]);
}
} // namespace

Coord4 TimeVaryingGrid::Dimensions() const
{
  if (this->Frames.empty())
    throw Error("a time-varying model needs at least one frame");
  const auto& d = this->Frames[0].Dimensions();
  for (std::size_t t = 1; t < this->Frames.size(); ++t)
    if (this->Frames[t].Dimensions() != d)
    {
      const auto& e = this->Frames[t].Dimensions();
      throw Error("frame " + std::to_string(t) + " is " + std::to_string(e[0]) + " x " +
        std::to_string(e[1]) + " x " + std::to_string(e[2]) + " sites, but frame 0 is " +
        std::to_string(d[0]) + " x " + std::to_string(d[1]) + " x " + std::to_string(d[2]));
    }
  return { { d[0], d[1], d[2], static_cast<std::int64_t>(this->Frames.size()) } };
}

TimeVaryingGrid TimeVaryingGrid::FromSlices(const LabelGrid& grid)
{
  TimeVaryingGrid out;
  const auto& d = grid.Dimensions();
  for (std::int64_t z = 0; z < d[2]; ++z)
  {
    LabelGrid slice(d[0], d[1], 1);
    for (std::int64_t y = 0; y < d[1]; ++y)
      for (std::int64_t x = 0; x < d[0]; ++x)
        slice.Set(x, y, 0, grid.At(x, y, z));
    out.Frames.push_back(std::move(slice));
  }
  return out;
}

TimeVaryingRules TimeVaryingRules::FromExample(const TimeVaryingGrid& example)
{
  const Coord4 n = example.Dimensions();
  std::map<Label, std::int64_t> counts;
  for (const auto& frame : example.Frames)
    for (Label v : frame.Data())
      ++counts[v];
  TimeVaryingRules rules;
  for (const auto& kv : counts)
  {
    rules.Values.push_back(kv.first);
    rules.LabelWeights.push_back(static_cast<double>(kv.second));
  }
  rules.Allocate(static_cast<int>(rules.Values.size()), TimeDirections);
  auto allow = [&rules](int axis, Label from, Label to)
  {
    const int b = rules.IndexOf(from), c = rules.IndexOf(to);
    rules.AllowOne(2 * axis, b, c);
    rules.AllowOne(2 * axis + 1, c, b);
  };
  for (std::int64_t t = 0; t < n[3]; ++t)
  {
    const LabelGrid& f = example.Frames[ToIndex(t)];
    for (std::int64_t z = 0; z < n[2]; ++z)
      for (std::int64_t y = 0; y < n[1]; ++y)
        for (std::int64_t x = 0; x < n[0]; ++x)
        {
          const Label v = f.At(x, y, z);
          if (x + 1 < n[0])
            allow(0, v, f.At(x + 1, y, z));
          if (y + 1 < n[1])
            allow(1, v, f.At(x, y + 1, z));
          if (z + 1 < n[2])
            allow(2, v, f.At(x, y, z + 1));
          if (t + 1 < n[3])
            allow(3, v, example.Frames[ToIndex(t + 1)].At(x, y, z));
        }
  }
  rules.Finish();
  return rules;
}

int TimeVaryingRules::IndexOf(Label value) const
{
  return IndexOfLabel(this->Values, value);
}

namespace
{
using Block4 = BoxBlock<4>;

/// Refuses sizes, label choices and orders the time-varying solver does not have.
std::int64_t CheckOptions(const TimeVaryingOptions& options)
{
  const Coord4& n = options.Size;
  std::int64_t total = 1;
  for (int a = 0; a < 4; ++a)
  {
    if (n[a] < 1)
      throw Error("the output size must be at least 1 along every axis, got " +
        std::to_string(n[a]) + " along " + "xyzt"[a]);
    if (n[a] > LabelGrid::MaxSites / total)
      throw Error("the time-varying output exceeds the limit of " +
        std::to_string(LabelGrid::MaxSites) + " sites");
    total *= n[a];
  }
  if (options.Choice == LabelChoice::Resemblance)
    throw Error("resemblance-weighted label choice is not available for time-varying models");
  if (options.Order == SiteOrder::MinimumEntropy)
    throw Error("time-varying synthesis assigns sites in scan-line or random order, not by "
                "minimum entropy");
  if (options.AttemptsPerBlock < 1)
    throw Error("attempts per block must be at least 1");
  return total;
}

/**
 * Refuses, before anything is allocated, a model whose memory would exceed what is available: per
 * site the model, the frames returned and the caller's copies (about 16 bytes); per frame the
 * bookkeeping of a grid and of the caller's image (about 2 KB); and a catalog (two bit sets of
 * the labels and bookkeeping) over a block of @p m sites. A whole 8 x 6 x 6 model of a million
 * frames (288 M sites) peaked at 9 GB before its catalog emptied; this says 13.5 GB at once.
 */
void CheckTimeVaryingMemory(const TimeVaryingRules& rules, const Coord4& n, const Coord4& m)
{
  std::uint64_t sites = 1, blockSites = 1;
  for (int a = 0; a < 4; ++a)
  {
    sites *= static_cast<std::uint64_t>(n[a]);
    blockSites *= static_cast<std::uint64_t>(m[a]);
  }
  const auto perCatalogSite = static_cast<std::uint64_t>(rules.Words()) * 16 + 8;
  CheckMemory(sites * 16 + static_cast<std::uint64_t>(n[3]) * 2048 + blockSites * perCatalogSite,
    "a " + std::to_string(n[0]) + " x " + std::to_string(n[1]) + " x " + std::to_string(n[2]) +
      " model of " + std::to_string(n[3]) + " frames");
}

/// The trivial start (Algorithm 3.4, lines 3-5): a label next to itself along every axis the
/// output extends along, and in time.
int TrivialStart(const TimeVaryingRules& rules, const TimeVaryingOptions& options)
{
  const Coord4& n = options.Size;
  auto usable = [&](int b)
  {
    for (int a = 0; a < 4; ++a)
      if ((n[a] > 1 || (a == 3 && options.Loop)) && !rules.Allowed(2 * a, b, b))
        return false;
    return true;
  };
  if (options.TrivialLabel)
  {
    const int t = rules.IndexOf(*options.TrivialLabel);
    if (t < 0 || !usable(t))
      throw Error("the trivial label " + std::to_string(*options.TrivialLabel) +
        (t < 0 ? " does not occur in the example"
               : " is not next to itself along every axis and in time, so a model of only that "
                 "label is not consistent"));
    return t;
  }
  const int t = ChooseTrivialLabel(rules.NumberOfLabels(), rules.IndexOf(0), usable);
  if (t < 0)
    throw Error("the example has no usable trivial start for block synthesis: no label stays "
                "next to itself along every axis and from frame to frame. Use whole-model "
                "synthesis (a block as large as the output) instead");
  return t;
}

/// The solver of one 4D block: its neighbourhood (eight directions, time wrapping with Loop)
/// and its label choice, on the shared propagation engine.
class TimeVaryingSolver
{
public:
  TimeVaryingSolver(const TimeVaryingRules& rules, const TimeVaryingOptions& options,
    std::vector<std::int32_t>& model, BlockDriver& driver)
    : Rules(rules)
    , Options(options)
    , N(options.Size)
    , Model(model)
    , Driver(driver)
    , SelfInTime(ToIndex(rules.Words()), 0)
  {
    // Labels that may follow themselves in time (the seam of a one-frame loop).
    for (int b = 0; b < rules.NumberOfLabels(); ++b)
      if (rules.Allowed(PlusT, b, b))
        this->SelfInTime[ToIndex(b / 64)] |= std::uint64_t(1) << (b % 64);
    this->LoopSelf = options.Loop && this->N[3] == 1;
    this->LoopSeam = options.Loop && this->N[3] > 1;
  }

  std::int64_t Index(const Coord4& p) const
  {
    return p[0] + this->N[0] * (p[1] + this->N[1] * (p[2] + this->N[2] * p[3]));
  }
  Coord4 Coordinates(std::int64_t index) const
  {
    Coord4 e;
    for (int a = 0; a < 4; ++a)
    {
      e[a] = index % this->N[a];
      index /= this->N[a];
    }
    return e;
  }

  /// One attempt at @p block: -1 on success (the block is written to the model), else the
  /// model index of the site whose catalog became empty.
  std::int64_t Attempt(const Block4& block, Random& rng, std::int64_t& assignments)
  {
    this->Current = &block;
    std::int64_t sites = 1;
    for (int a = 0; a < 4; ++a)
      sites *= block.Dims[a];
    this->Domains.Reset(sites, this->Rules.NumberOfLabels());
    for (std::int64_t local = 0; local < sites; ++local)
      if (!this->ConstrainFromOutside(local))
        return this->Index(this->Coordinates(block, local));
    auto forEach = [this](std::int64_t v, auto&& visit) { this->ForEachNeighbour(v, visit); };
    std::int64_t empty = this->Domains.Propagate(this->Rules, forEach);
    if (empty < 0)
      empty = this->AssignAll(sites, rng, assignments);
    if (empty >= 0)
      return this->Index(this->Coordinates(block, empty));
    for (std::int64_t local = 0; local < sites; ++local)
      this->Model[ToIndex(this->Index(this->Coordinates(block, local)))] =
        this->Domains.Single(local);
    return -1;
  }

private:
  Coord4 Coordinates(const Block4& block, std::int64_t local) const
  {
    Coord4 p;
    for (int a = 0; a < 4; ++a)
    {
      p[a] = block.Origin[a] + local % block.Dims[a];
      local /= block.Dims[a];
    }
    return p;
  }
  std::int64_t LocalOf(const Coord4& p) const
  {
    const Block4& b = *this->Current;
    std::int64_t local = 0;
    for (int a = 3; a >= 0; --a)
    {
      if (p[a] < b.Origin[a] || p[a] >= b.Origin[a] + b.Dims[a])
        return -1;
      local = local * b.Dims[a] + (p[a] - b.Origin[a]);
    }
    return local;
  }
  /// The neighbour of p along direction dir: false on an axis outside the model (time wraps
  /// with Loop).
  bool Neighbour(const Coord4& p, int dir, Coord4& q) const
  {
    const int a = dir / 2;
    q = p;
    q[a] += (dir & 1) ? -1 : 1;
    if (q[a] < 0 || q[a] >= this->N[a])
    {
      if (a != 3 || !this->LoopSeam)
        return false;
      q[a] = (q[a] + this->N[a]) % this->N[a];
    }
    return true;
  }
  template <typename Visit>
  void ForEachNeighbour(std::int64_t v, Visit&& visit) const
  {
    const Coord4 p = this->Coordinates(*this->Current, v);
    for (int dir = 0; dir < TimeDirections; ++dir)
    {
      Coord4 q;
      if (!this->Neighbour(p, dir, q))
        continue;
      const std::int64_t u = this->LocalOf(q);
      if (u >= 0 && u != v && !visit(u, dir))
        return;
    }
  }
  /// The labels around the block (and the loop's self-seam) constrain site @p local.
  bool ConstrainFromOutside(std::int64_t local)
  {
    const Coord4 p = this->Coordinates(*this->Current, local);
    if (this->LoopSelf && !this->Domains.Keep(local, this->SelfInTime.data()))
      return false;
    for (int dir = 0; dir < TimeDirections; ++dir)
    {
      Coord4 q;
      if (!this->Neighbour(p, dir, q) || this->LocalOf(q) >= 0)
        continue;
      const int label = this->Model[ToIndex(this->Index(q))];
      if (label >= 0 && !this->Domains.Keep(local, this->Rules.Compatible(dir ^ 1, label)))
        return false;
    }
    return true;
  }
  /// Lines 19-29 of Algorithm 3.4: assigns the undecided sites in scan-line or random order.
  std::int64_t AssignAll(std::int64_t sites, Random& rng, std::int64_t& assignments)
  {
    auto forEach = [this](std::int64_t v, auto&& visit) { this->ForEachNeighbour(v, visit); };
    this->Order.resize(ToIndex(sites));
    std::iota(this->Order.begin(), this->Order.end(), 0);
    if (this->Options.Order == SiteOrder::Random)
      for (std::size_t i = this->Order.size(); i > 1; --i)
        std::swap(this->Order[i - 1], this->Order[ToIndex(rng.Below(i))]);
    for (std::int64_t local : this->Order)
    {
      if (this->Domains.Count(local) == 0)
        return local;
      if (this->Domains.Count(local) == 1)
        continue;
      if (this->Driver.Poll(0, assignments))
        return local; // cancelled: the attempt ends here (and no other starts)
      const int pick = DrawLabel(
        this->Domains.Domain(local), this->Rules.Words(),
        [&](int b)
        {
          return this->Options.Choice == LabelChoice::Frequency ? this->Rules.Weights()[ToIndex(b)]
                                                                : 1.0;
        },
        rng.Uniform());
      ++assignments;
      this->Domains.Assign(local, pick);
      const std::int64_t empty = this->Domains.Propagate(this->Rules, forEach);
      if (empty >= 0)
        return empty;
    }
    return -1;
  }

  const TimeVaryingRules& Rules;
  const TimeVaryingOptions& Options;
  Coord4 N;
  std::vector<std::int32_t>& Model; ///< label indices
  BlockDriver& Driver;
  std::vector<std::uint64_t> SelfInTime;
  bool LoopSelf = false, LoopSeam = false;
  const Block4* Current = nullptr;
  LabelDomains Domains;
  std::vector<std::int64_t> Order;
};

/// The model's label values as frames.
TimeVaryingGrid Frames(const TimeVaryingRules& rules, const TimeVaryingSolver& solver,
  const std::vector<std::int32_t>& model, const Coord4& n)
{
  TimeVaryingGrid out;
  const auto& values = rules.LabelValues();
  for (std::int64_t t = 0; t < n[3]; ++t)
  {
    LabelGrid frame(n[0], n[1], n[2]);
    for (std::int64_t z = 0; z < n[2]; ++z)
      for (std::int64_t y = 0; y < n[1]; ++y)
        for (std::int64_t x = 0; x < n[0]; ++x)
          frame.Set(x, y, z, values[ToIndex(model[ToIndex(solver.Index({ { x, y, z, t } }))])]);
    out.Frames.push_back(std::move(frame));
  }
  return out;
}
} // namespace

TimeVaryingResult SynthesizeTimeVarying(
  const TimeVaryingRules& rules, const TimeVaryingOptions& options)
{
  const auto start = std::chrono::steady_clock::now();
  const std::int64_t total = CheckOptions(options);
  const Coord4& n = options.Size;
  Coord4 m, step;
  const bool whole = BlockGeometry<4>(n, options.BlockSize, options.Overlap, m, step);
  CheckTimeVaryingMemory(rules, n, m);
  TimeVaryingResult result;
  SynthesisStatistics& stats = result.Statistics;
  std::vector<std::int32_t> model(ToIndex(total), -1);
  if (!whole)
  {
    const int t = TrivialStart(rules, options);
    std::fill(model.begin(), model.end(), t);
    stats.TrivialLabel = rules.LabelValues()[ToIndex(t)];
  }
  // Blocks one after the other in scan order of the block grid (x fastest, time last).
  const std::vector<Block4> blocks =
    PlanBoxBlocks<4>(n, m, step, PhasePolicy::Sequential, stats.Phases);
  BlockRunner::Policy policy;
  policy.Serial = true;
  policy.Progress = options.Progress;
  BlockDriver driver(
    std::move(policy), options.Seed, options.AttemptsPerBlock, blocks.size(), start);
  TimeVaryingSolver solver(rules, options, model, driver);
  BlockClient client;
  client.Attempt = [&](unsigned, std::size_t i, int, Random& rng, std::int64_t& assignments)
  { return solver.Attempt(blocks[i], rng, assignments); };
  client.Describe = [&](std::size_t i, const BlockOutcome& out, BlockFailure& failure)
  {
    const Coord4 e = solver.Coordinates(std::max<std::int64_t>(out.Empty, 0));
    failure.Origin = { { blocks[i].Origin[0], blocks[i].Origin[1], blocks[i].Origin[2] } };
    failure.EmptySite = { { e[0], e[1], e[2] } };
    failure.Frame = e[3];
  };
  result.Status = driver.Run(BlockSchedule::Of(blocks), client, stats);
  if (!driver.End(result.Status, result.Message, stats, whole,
        [&](const BlockFailure& f)
        {
          return WholeModelFailure("whole-model synthesis (Algorithm 3.1)",
            options.AttemptsPerBlock,
            "the catalog became empty at site " +
              Format({ { f.EmptySite[0], f.EmptySite[1], f.EmptySite[2], f.Frame } }),
            "Try another seed, more attempts, or blocks");
        }))
    return result;
  result.Model = Frames(rules, solver, model, n);
  result.Message = Summary(stats, whole);
  return result;
}

ConsistencyReport CheckTimeVarying(
  const TimeVaryingGrid& example, const TimeVaryingGrid& model, bool loop)
{
  const Coord4 e = example.Dimensions(), n = model.Dimensions();
  std::set<std::tuple<int, Label, Label>> allowed;
  for (std::int64_t t = 0; t < e[3]; ++t)
    for (std::int64_t z = 0; z < e[2]; ++z)
      for (std::int64_t y = 0; y < e[1]; ++y)
        for (std::int64_t x = 0; x < e[0]; ++x)
        {
          const LabelGrid& f = example.Frames[ToIndex(t)];
          const Label v = f.At(x, y, z);
          if (x + 1 < e[0])
            allowed.emplace(0, v, f.At(x + 1, y, z));
          if (y + 1 < e[1])
            allowed.emplace(1, v, f.At(x, y + 1, z));
          if (z + 1 < e[2])
            allowed.emplace(2, v, f.At(x, y, z + 1));
          if (t + 1 < e[3])
            allowed.emplace(3, v, example.Frames[ToIndex(t + 1)].At(x, y, z));
        }
  ConsistencyReport report;
  for (std::int64_t t = 0; t < n[3]; ++t)
    for (std::int64_t z = 0; z < n[2]; ++z)
      for (std::int64_t y = 0; y < n[1]; ++y)
        for (std::int64_t x = 0; x < n[0]; ++x)
        {
          const LabelGrid& f = model.Frames[ToIndex(t)];
          const Label v = f.At(x, y, z);
          auto check = [&](int axis, Label to)
          {
            ++report.PairsChecked;
            if (allowed.count(std::make_tuple(axis, v, to)))
              return;
            report.Consistent = false;
            if (++report.Violations <= 10)
            {
              ConsistencyViolation bad;
              bad.Site = { { x, y, z } };
              bad.Time = t;
              bad.Axis = axis;
              bad.From = v;
              bad.To = to;
              report.First.push_back(bad);
            }
          };
          if (x + 1 < n[0])
            check(0, f.At(x + 1, y, z));
          if (y + 1 < n[1])
            check(1, f.At(x, y + 1, z));
          if (z + 1 < n[2])
            check(2, f.At(x, y, z + 1));
          if (t + 1 < n[3] || loop)
            check(3, model.Frames[ToIndex((t + 1) % n[3])].At(x, y, z));
        }
  return report;
}

} // namespace msynth
