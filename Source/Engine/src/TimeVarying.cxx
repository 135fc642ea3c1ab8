// SPDX-License-Identifier: BSD-3-Clause
#include "msynth/TimeVarying.h"

#include "msynth/Error.h"

#include "ProgressPoll.h"
#include "msynth/Random.h"

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
    const LabelGrid& f = example.Frames[static_cast<std::size_t>(t)];
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
            allow(3, v, example.Frames[static_cast<std::size_t>(t + 1)].At(x, y, z));
        }
  }
  rules.Finish();
  return rules;
}

int TimeVaryingRules::IndexOf(Label value) const
{
  const auto it = std::lower_bound(this->Values.begin(), this->Values.end(), value);
  return it != this->Values.end() && *it == value ? static_cast<int>(it - this->Values.begin())
                                                  : -1;
}

TimeVaryingResult SynthesizeTimeVarying(
  const TimeVaryingRules& rules, const TimeVaryingOptions& options)
{
  const auto start = std::chrono::steady_clock::now();
  detail::ProgressPoll poll(options.Progress); // cancellation inside a block
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
  const int k = rules.NumberOfLabels();
  const int words = rules.Words();

  Coord4 m, step;
  bool whole = true;
  for (int a = 0; a < 4; ++a)
  {
    m[a] = options.BlockSize[a] <= 0 ? n[a] : std::min(options.BlockSize[a], n[a]);
    whole = whole && m[a] == n[a];
    step[a] = std::max<std::int64_t>(1, m[a] - m[a] / 2);
  }
  auto index = [&n](const Coord4& p) { return p[0] + n[0] * (p[1] + n[1] * (p[2] + n[2] * p[3])); };
  // Labels that may follow themselves in time (the seam of a one-frame loop).
  std::vector<std::uint64_t> selfInTime(static_cast<std::size_t>(words), 0);
  for (int b = 0; b < k; ++b)
    if (rules.Allowed(PlusT, b, b))
      selfInTime[static_cast<std::size_t>(b / 64)] |= std::uint64_t(1) << (b % 64);
  const bool loopSelf = options.Loop && n[3] == 1;
  const bool loopSeam = options.Loop && n[3] > 1;

  TimeVaryingResult result;
  SynthesisStatistics& stats = result.Statistics;
  std::vector<std::int32_t> model(static_cast<std::size_t>(total), -1);
  if (!whole)
  {
    // The trivial start: a label next to itself along every axis the output extends along.
    auto usable = [&](int b)
    {
      for (int a = 0; a < 4; ++a)
        if ((n[a] > 1 || (a == 3 && options.Loop)) && !rules.Allowed(2 * a, b, b))
          return false;
      return true;
    };
    int t = -1;
    if (options.TrivialLabel)
    {
      t = rules.IndexOf(*options.TrivialLabel);
      if (t < 0 || !usable(t))
        throw Error("the trivial label " + std::to_string(*options.TrivialLabel) +
          (t < 0 ? " does not occur in the example"
                 : " is not next to itself along every axis and in time, so a model of only that "
                   "label is not consistent"));
    }
    else
    {
      const int zero = rules.IndexOf(0);
      if (zero >= 0 && usable(zero))
        t = zero;
      for (int b = 0; t < 0 && b < k; ++b)
        if (usable(b))
          t = b;
      if (t < 0)
        throw Error("the example has no usable trivial start for block synthesis: no label stays "
                    "next to itself along every axis and from frame to frame. Use whole-model "
                    "synthesis (a block as large as the output) instead");
    }
    std::fill(model.begin(), model.end(), t);
    stats.TrivialLabel = rules.LabelValues()[static_cast<std::size_t>(t)];
  }

  // Blocks in scan order of the block grid (x fastest, time last).
  std::array<std::vector<std::int64_t>, 4> starts;
  for (int a = 0; a < 4; ++a)
  {
    starts[static_cast<std::size_t>(a)] = { 0 };
    while (starts[static_cast<std::size_t>(a)].back() + m[a] < n[a])
      starts[static_cast<std::size_t>(a)].push_back(starts[static_cast<std::size_t>(a)].back() + step[a]);
  }
  std::vector<Coord4> origins;
  for (std::int64_t t : starts[3])
    for (std::int64_t z : starts[2])
      for (std::int64_t y : starts[1])
        for (std::int64_t x : starts[0])
          origins.push_back({ { x, y, z, t } });
  stats.Blocks = static_cast<std::int64_t>(origins.size());

  LabelDomains domains;
  std::vector<std::int64_t> order;
  for (std::size_t bi = 0; bi < origins.size(); ++bi)
  {
    Coord4 o = origins[bi], d;
    std::int64_t sites = 1;
    for (int a = 0; a < 4; ++a)
    {
      d[a] = std::min(m[a], n[a] - o[a]);
      sites *= d[a];
    }
    auto coordinates = [&d, &o](std::int64_t local)
    {
      Coord4 p;
      for (int a = 0; a < 4; ++a)
      {
        p[a] = o[a] + local % d[a];
        local /= d[a];
      }
      return p;
    };
    auto localOf = [&d, &o](const Coord4& p) -> std::int64_t
    {
      std::int64_t local = 0;
      for (int a = 3; a >= 0; --a)
      {
        if (p[a] < o[a] || p[a] >= o[a] + d[a])
          return -1;
        local = local * d[a] + (p[a] - o[a]);
      }
      return local;
    };
    // The neighbour of p along direction dir: -1 on an axis outside the model (time wraps with
    // Loop).
    auto neighbour = [&n, loopSeam](Coord4 p, int dir, Coord4& q)
    {
      const int a = dir / 2;
      q = p;
      q[a] += (dir & 1) ? -1 : 1;
      if (q[a] < 0 || q[a] >= n[a])
      {
        if (a != 3 || !loopSeam)
          return false;
        q[a] = (q[a] + n[a]) % n[a];
      }
      return true;
    };
    std::int64_t emptied = -1;
    int attempt = 0;
    for (; attempt < options.AttemptsPerBlock; ++attempt)
    {
      ++stats.Attempts;
      Random rng = Random::Derived(options.Seed, bi, static_cast<std::uint64_t>(attempt));
      domains.Reset(sites, k);
      bool ok = true;
      for (std::int64_t local = 0; local < sites && ok; ++local)
      {
        const Coord4 p = coordinates(local);
        if (loopSelf)
          ok = domains.Keep(local, selfInTime.data());
        for (int dir = 0; dir < TimeDirections && ok; ++dir)
        {
          Coord4 q;
          if (!neighbour(p, dir, q) || localOf(q) >= 0)
            continue;
          const int label = model[static_cast<std::size_t>(index(q))];
          if (label >= 0)
            ok = domains.Keep(local, rules.Compatible(dir ^ 1, label));
        }
        if (!ok)
          emptied = index(p);
      }
      auto forEach = [&](std::int64_t v, auto&& visit)
      {
        const Coord4 p = coordinates(v);
        for (int dir = 0; dir < TimeDirections; ++dir)
        {
          Coord4 q;
          if (!neighbour(p, dir, q))
            continue;
          const std::int64_t u = localOf(q);
          if (u >= 0 && u != v && !visit(u, dir))
            return;
        }
      };
      std::int64_t empty = -1;
      if (ok)
      {
        empty = domains.Propagate(rules, forEach);
      }
      if (ok && empty < 0)
      {
        order.resize(static_cast<std::size_t>(sites));
        std::iota(order.begin(), order.end(), 0);
        if (options.Order == SiteOrder::Random)
          for (std::size_t i = order.size(); i > 1; --i)
            std::swap(order[i - 1], order[static_cast<std::size_t>(rng.Below(i))]);
        for (std::int64_t local : order)
        {
          if (domains.Count(local) == 0)
          {
            empty = local;
            break;
          }
          if (domains.Count(local) == 1)
            continue;
          if ((stats.Assignments & 1023) == 0 &&
            !poll.Continue(static_cast<double>(bi) / static_cast<double>(origins.size())))
          {
            result.Message = "cancelled";
            return result;
          }
          const int pick = DrawLabel(domains.Domain(local), words,
            [&](int b)
            {
              return options.Choice == LabelChoice::Frequency
                ? rules.Weights()[static_cast<std::size_t>(b)]
                : 1.0;
            },
            rng.Uniform());
          ++stats.Assignments;
          domains.Assign(local, pick);
          empty = domains.Propagate(rules, forEach);
          if (empty >= 0)
            break;
        }
      }
      if (ok && empty < 0)
      {
        for (std::int64_t local = 0; local < sites; ++local)
          model[static_cast<std::size_t>(index(coordinates(local)))] = domains.Single(local);
        break;
      }
      if (ok)
        emptied = index(coordinates(empty));
    }
    if (attempt == options.AttemptsPerBlock)
    {
      Coord4 e;
      std::int64_t rest = std::max<std::int64_t>(emptied, 0);
      for (int a = 0; a < 4; ++a)
      {
        e[a] = rest % n[a];
        rest /= n[a];
      }
      if (whole)
      {
        result.Message = "whole-model synthesis (Algorithm 3.1) failed " +
          std::to_string(options.AttemptsPerBlock) + " time(s); the catalog became empty at site " +
          Format(e) + " in the last attempt. Try another seed, more attempts, or blocks";
        stats.Seconds =
          std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        return result;
      }
      ++stats.BlocksFailed;
      BlockFailure failure;
      failure.Block = static_cast<std::int64_t>(bi);
      failure.Origin = { { o[0], o[1], o[2] } };
      failure.EmptySite = { { e[0], e[1], e[2] } };
      failure.Attempts = options.AttemptsPerBlock;
      stats.Failures.push_back(failure);
    }
    else
      ++stats.BlocksAccepted;
    if (options.Progress &&
      !options.Progress(static_cast<double>(bi + 1) / static_cast<double>(origins.size())))
    {
      result.Message = "cancelled";
      return result;
    }
  }
  // Frames of label values.
  const auto& values = rules.LabelValues();
  for (std::int64_t t = 0; t < n[3]; ++t)
  {
    LabelGrid frame(n[0], n[1], n[2]);
    for (std::int64_t z = 0; z < n[2]; ++z)
      for (std::int64_t y = 0; y < n[1]; ++y)
        for (std::int64_t x = 0; x < n[0]; ++x)
          frame.Set(x, y, z,
            values[static_cast<std::size_t>(model[static_cast<std::size_t>(index({ { x, y, z, t } }))])]);
    result.Model.Frames.push_back(std::move(frame));
  }
  result.Success = true;
  result.Message = whole ? "whole-model synthesis succeeded"
                         : std::to_string(stats.BlocksAccepted) + " of " +
      std::to_string(stats.Blocks) + " blocks synthesized, " + std::to_string(stats.BlocksFailed) +
      " left at their previous labels";
  stats.Seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
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
          const LabelGrid& f = example.Frames[static_cast<std::size_t>(t)];
          const Label v = f.At(x, y, z);
          if (x + 1 < e[0])
            allowed.emplace(0, v, f.At(x + 1, y, z));
          if (y + 1 < e[1])
            allowed.emplace(1, v, f.At(x, y + 1, z));
          if (z + 1 < e[2])
            allowed.emplace(2, v, f.At(x, y, z + 1));
          if (t + 1 < e[3])
            allowed.emplace(3, v, example.Frames[static_cast<std::size_t>(t + 1)].At(x, y, z));
        }
  ConsistencyReport report;
  for (std::int64_t t = 0; t < n[3]; ++t)
    for (std::int64_t z = 0; z < n[2]; ++z)
      for (std::int64_t y = 0; y < n[1]; ++y)
        for (std::int64_t x = 0; x < n[0]; ++x)
        {
          const LabelGrid& f = model.Frames[static_cast<std::size_t>(t)];
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
            check(3, model.Frames[static_cast<std::size_t>((t + 1) % n[3])].At(x, y, z));
        }
  return report;
}

} // namespace msynth
