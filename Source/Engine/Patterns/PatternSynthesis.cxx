// SPDX-License-Identifier: BSD-3-Clause
#include "Patterns/PatternSynthesis.h"

#include "Core/Error.h"
#include "Core/Index.h"
#include "Core/Memory.h"
#include "Core/MirrorFold.h"
#include "Core/Random.h"
#include "Core/TextLists.h"
#include "Discrete/Connectivity.h"
#include "Discrete/DiscreteSynthesis.h"
#include "Patterns/BlockSampler.h"

#include <algorithm>
#include <chrono>
#include <climits>
#include <cmath>
#include <cstdint>
#include <memory>
#include <optional>

namespace msynth
{

namespace
{

using detail::PatternProblem;

void CheckOptions(const FactorModel& m, const PatternOptions& o)
{
  for (int a = 0; a < 3; ++a)
  {
    if (o.Size[ToIndex(a)] < 1)
      throw Error("the output size must be at least 1 along every axis");
    if (o.Size[ToIndex(a)] > 1 && !m.AxisSeen[ToIndex(a)])
      throw Error(std::string("the output extends along ") + "xyz"[a] +
        " but no exemplar does, so no pair along it is known" +
        (a == 2 ? " (a 3D output needs 3D exemplars)" : ""));
  }
  LabelGrid::CheckDimensions(o.Size[0], o.Size[1], o.Size[2]);
  if (!(o.Epsilon >= 0) || !std::isfinite(o.Epsilon))
    throw Error("epsilon must be a finite number at least 0");
  if (!(o.Temperature > 0) || !std::isfinite(o.Temperature))
    throw Error("the temperature must be a finite number above 0");
  for (double p : { o.WalkProbability, o.FlipProbability })
    if (!(p >= 0 && p <= 1))
      throw Error("p_walk and p_flip must be probabilities (0 to 1)");
  if (o.Samples < 1 || o.BurnIn < 0)
    throw Error("at least one sample is needed, and the burn-in cannot be negative");
  bool mirrored = false;
  for (int a = 0; a < 3; ++a)
    if (o.Mirror[ToIndex(a)])
    {
      mirrored = true;
      if (o.Size[ToIndex(a)] < 2)
        throw Error(std::string("mirroring along ") + "xyz"[a] + " needs at least 2 sites");
    }
  if (!mirrored)
    return;
  if (o.Connected.Active())
    throw Error("a connected network cannot be combined with mirroring (only half the output is "
                "synthesized)");
  const int t = m.NumberOfTiles();
  std::vector<std::int32_t> f(ToIndex(t));
  for (int b = 0; b < t; ++b)
  {
    const auto it = o.MirrorMap.find(m.Tiles[ToIndex(b)]);
    f[ToIndex(b)] = it == o.MirrorMap.end() ? b : m.TileIndex(it->second);
    if (f[ToIndex(b)] < 0)
      throw Error("the mirror map sends label " + std::to_string(it->first) + " to " +
        std::to_string(it->second) + ", which no exemplar holds");
  }
  for (int b = 0; b < t; ++b)
    if (f[ToIndex(f[ToIndex(b)])] != b)
      throw Error(
        "the mirror map is not its own inverse at label " + std::to_string(m.Tiles[ToIndex(b)]));
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < t; ++b)
      for (int c = 0; c < t; ++c)
      {
        const bool along = o.Mirror[ToIndex(a)];
        const int fb = f[ToIndex(b)], fc = f[ToIndex(c)];
        if (m.Allowed(a, b, c) != (along ? m.Allowed(a, fc, fb) : m.Allowed(a, fb, fc)))
          throw Error(std::string("the mirror map does not keep the exemplars' pairs along ") +
            "xyz"[a] + " (labels " + std::to_string(m.Tiles[ToIndex(b)]) + ", " +
            std::to_string(m.Tiles[ToIndex(c)]) + ")");
      }
}

/// The lower half (rounded up) along mirrored axes.
std::array<std::int64_t, 3> SolvedSize(const PatternOptions& o)
{
  std::array<std::int64_t, 3> s = o.Size;
  for (std::size_t a = 0; a < 3; ++a)
    if (o.Mirror[a])
      s[a] = (s[a] + 1) / 2;
  return s;
}

/// The full pattern from the synthesized part (mirrored along the options' axes).
template <typename T, typename Map>
std::vector<T> Unfold(const std::vector<T>& part, const std::array<std::int64_t, 3>& partSize,
  const PatternOptions& o, Map&& map)
{
  const auto& full = o.Size;
  const int axes = (o.Mirror[0] ? 1 : 0) | (o.Mirror[1] ? 2 : 0) | (o.Mirror[2] ? 4 : 0);
  std::vector<T> out(ToIndex(full[0] * full[1] * full[2]));
  std::array<std::int64_t, 3> q, p;
  std::size_t i = 0;
  for (q[2] = 0; q[2] < full[2]; ++q[2])
    for (q[1] = 0; q[1] < full[1]; ++q[1])
      for (q[0] = 0; q[0] < full[0]; ++q[0], ++i)
      {
        const int flips =
          __builtin_popcount(static_cast<unsigned>(FoldMirror(q, full, partSize, axes, p)));
        T v = part[ToIndex(p[0] + partSize[0] * (p[1] + partSize[1] * p[2]))];
        for (int k = 0; k < flips; ++k)
          v = map(v);
        out[i] = v;
      }
  return out;
}

PatternSample MakeSample(const PatternProblem& scorer, const FactorModel& m,
  const PatternOptions& o, std::vector<std::int32_t> tiles, std::vector<std::int64_t> last)
{
  PatternSample s;
  const std::int64_t soft = scorer.CountSoft(tiles, &s.SatisfiedSoft);
  s.LogProbability = static_cast<double>(soft) * std::log1p(o.Epsilon);
  std::vector<Label> values(tiles.size());
  for (std::size_t i = 0; i < tiles.size(); ++i)
    values[i] = m.Tiles[ToIndex(tiles[i])];
  s.Labels = LabelGrid(o.Size, std::move(values));
  s.LastChange = std::move(last);
  return s;
}

/// @p network without the labels no exemplar (or tileset rule) holds: a tileset's names may
/// cover more tiles than the exemplars use (a path label among them has no site to join).
/// @throw Error when none is left.
ConnectedNetwork HeldNetwork(const FactorModel& m, const ConnectedNetwork& network)
{
  ConnectedNetwork held = network;
  held.Values.clear();
  for (Label v : network.Values)
    if (m.TileIndex(v) >= 0)
      held.Values.push_back(v);
  if (network.Active() && held.Values.empty())
    throw Error("the network of " + network.Name + ": none of its labels occurs in the exemplars");
  held.PathLabels.clear(); // one that is no network label stays, for the repairs' refusal
  for (Label v : network.PathLabels)
    if (m.TileIndex(v) >= 0 ||
      std::find(network.Values.begin(), network.Values.end(), v) == network.Values.end())
      held.PathLabels.push_back(v);
  return held;
}

/**
 * Refuses, with one line, a path without a network, and a listed path site outside the output
 * or whose zone, fixed label or seam allows none of the network's tiles (the repairs could
 * never bring it in).
 */
void CheckPatternPath(const FactorModel& m, const PatternProblem& problem, const PatternOptions& o)
{
  const ConnectedNetwork& network = o.Connected;
  if (!network.HasPath())
    return;
  if (!network.Active())
    throw Error("a path (--path) needs a network of labels to carry it (--connected LABELS)");
  const auto& n = o.Size;
  for (const auto& p : network.PathSites)
  {
    for (std::size_t a = 0; a < 3; ++a)
      if (p[a] < 0 || p[a] >= n[a])
        throw Error("the path's site " + detail::Format(p) + " is outside the output (" +
          std::to_string(n[0]) + " x " + std::to_string(n[1]) + " x " + std::to_string(n[2]) +
          " sites)");
    const std::int64_t s = p[0] + n[0] * (p[1] + n[1] * p[2]);
    bool any = false;
    for (Label v : network.Values)
      any = any || (m.TileIndex(v) >= 0 && problem.AllowedAt(s, m.TileIndex(v)));
    if (!any)
      throw Error("the path's site " + detail::Format(p) + " cannot hold " + network.Name +
        " (its zone or fixed label allows none of them)");
  }
}

/// The discrete solver's rules from the hard pairs.
AdjacencyRules PairRules(const FactorModel& m)
{
  std::array<std::vector<std::pair<int, int>>, 3> pairs;
  const int t = m.NumberOfTiles();
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < t; ++b)
      for (int c = 0; c < t; ++c)
        if (m.Allowed(a, b, c))
          pairs[ToIndex(a)].emplace_back(b, c);
  return AdjacencyRules::FromPairs(m.Tiles, std::vector<double>(ToIndex(t), 1.0), pairs);
}

/// Discrete synthesis options for @p problem's sites: zones, fixed sites and seams as a guide of
/// zero weights; with @p mirror the options' mirrors as reflection symmetry (over the output).
SynthesisOptions SolverOptions(
  const FactorModel& m, const PatternProblem& problem, const PatternOptions& o, bool mirror)
{
  SynthesisOptions so;
  so.Size = problem.Size;
  so.Order = SiteOrder::Random; // as §8.1 randomised MINION's variable order
  so.AttemptsPerBlock = 20;
  so.Threads = 1;
  const int t = m.NumberOfTiles();
  if (problem.ClassTiles.size() > 1 || problem.ClassTiles[0].size() != ToIndex(t))
  {
    GuideVolume guide;
    guide.Dims = problem.Size;
    for (int b = 0; b < t; ++b)
    {
      std::vector<float> w(ToIndex(problem.N), 1.0f);
      for (std::int64_t p = 0; p < problem.N; ++p)
        if (!problem.AllowedAt(p, b))
          w[ToIndex(p)] = 0.0f;
      guide.Weights[m.Tiles[ToIndex(b)]] = std::move(w);
    }
    so.Guide = std::move(guide);
  }
  if (mirror)
    for (std::size_t a = 0; a < 3; ++a)
      if (o.Mirror[a])
      {
        so.Symmetry[a].Enabled = true;
        so.Symmetry[a].Map = o.MirrorMap;
      }
  so.Progress = o.Progress;
  return so;
}

/// One run of the discrete solver as tile indices (its network's figures in @p connected, when
/// given); empty when cancelled.
std::vector<std::int32_t> SolveOnce(const FactorModel& m, const AdjacencyRules& rules,
  SynthesisOptions& so, std::uint64_t seed, PatternResult& result,
  ConnectedResult* connected = nullptr)
{
  so.Seed = seed;
  SynthesisResult r = Synthesize(rules, so);
  result.Moves += r.Statistics.Assignments;
  if (connected)
    *connected = r.Connected;
  if (r.Status == SynthesisStatus::Cancelled)
  {
    result.Status = SynthesisStatus::Cancelled;
    return {};
  }
  if (!r.Succeeded())
    throw Error("the constraint solver found no pattern: " + r.Message);
  std::vector<std::int32_t> tiles(r.Model.Data().size());
  for (std::size_t i = 0; i < tiles.size(); ++i)
    tiles[i] = m.TileIndex(r.Model.Data()[i]);
  return tiles;
}

/// §8.1's pure constraint solver: discrete model synthesis on the hard pairs, one run a sample.
void RunConstraintSolver(const FactorModel& m, const PatternProblem& scorer,
  const PatternOptions& o, PatternResult& result)
{
  const auto start = std::chrono::steady_clock::now();
  const AdjacencyRules rules = PairRules(m);
  SynthesisOptions so = SolverOptions(m, scorer, o, true);
  so.Connected = HeldNetwork(m, o.Connected);
  for (int n = 0; n < o.Samples; ++n)
  {
    ConnectedResult connected;
    std::vector<std::int32_t> tiles = SolveOnce(m, rules, so,
      Random::Derived(o.Seed, 0xc5b, static_cast<std::uint64_t>(n)).Next(), result, &connected);
    if (result.Status == SynthesisStatus::Cancelled)
      return;
    std::vector<std::int64_t> last(tiles.size(), 0);
    PatternSample s = MakeSample(scorer, m, o, std::move(tiles), std::move(last));
    s.Connected = connected;
    s.Moves = result.Moves;
    s.Seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (n == 0)
    {
      result.FirstValidMoves = s.Moves;
      result.FirstValidSeconds = s.Seconds;
    }
    result.Samples.push_back(std::move(s));
  }
}

/**
 * A connected network's repairs of BLOCKSS and MH samples (PatternOptions::Connected): the
 * discrete solver on the hard pairs, with the site classes as its guide, re-solves boxes over
 * and around the surplus components (detail::RepairNetwork) of each kept sample.
 */
class NetworkRepair
{
public:
  NetworkRepair(const FactorModel& m, const PatternProblem& problem, const PatternOptions& o)
    : Rules(PairRules(m))
    , Options(SolverOptions(m, problem, o, false))
  {
    this->Options.Connected = HeldNetwork(m, o.Connected);
    this->Options.AttemptsPerBlock = 10;
    detail::CheckConnectedRequest(this->Rules, this->Options);
    this->Rule = std::make_unique<detail::NetworkRule>(this->Rules, this->Options.Connected);
    this->Solver = std::make_unique<detail::BlockSolver>(
      this->Rules, this->Options, nullptr, nullptr, this->Shared);
  }

  /// Mends sample @p tiles (tile indices, the same as the pair rules' label indices) until
  /// the network has at most Maximum components; its figures into @p out. Returns why not
  /// when no surplus component could be joined or removed (@p tiles partly mended).
  std::string Mend(std::vector<std::int32_t>& tiles, PatternResult& result, ConnectedResult& out)
  {
    const auto start = std::chrono::steady_clock::now();
    this->Options.Seed = Random::Derived(this->Seed, 0xc011, this->Mended++).Next();
    this->Shared.Model = tiles;
    std::fill(this->Shared.LastBlock.begin(), this->Shared.LastBlock.end(), -1);
    out.Requested = true;
    out.Maximum = this->Options.Connected.Maximum;
    out.Name = this->Options.Connected.Name;
    SynthesisStatistics stats;
    const std::string failure =
      detail::RepairNetwork(*this->Solver, this->Shared, *this->Rule, this->Options, 0, stats, out);
    result.NetworkAssignments += stats.Assignments;
    result.NetworkSeconds +=
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    tiles = this->Shared.Model;
    return failure;
  }

  std::uint64_t Seed = 0;

private:
  AdjacencyRules Rules;
  SynthesisOptions Options;
  detail::SharedModel Shared;
  std::unique_ptr<detail::NetworkRule> Rule;
  std::unique_ptr<detail::BlockSolver> Solver;
  std::uint64_t Mended = 0;
};

} // namespace

std::map<std::int32_t, std::vector<std::int32_t>> ParseZoneLists(
  const std::string& text, const std::string& what)
{
  constexpr long long low = INT32_MIN, high = INT32_MAX;
  std::map<std::int32_t, std::vector<std::int32_t>> lists;
  for (const std::string& item : SplitText(text, ';', true))
  {
    if (item.empty())
      continue;
    const std::size_t colon = item.find(':');
    long long zone = 0;
    if (colon == std::string::npos || !ParseInteger(item.substr(0, colon), low, high, zone))
      throw Error(what + ": '" + item + "' is not 'zone:a,b,...'");
    auto& values = lists[static_cast<std::int32_t>(zone)];
    for (const std::string& v : SplitText(item.substr(colon + 1), ','))
    {
      long long value = 0;
      if (!ParseInteger(v, low, high, value))
        throw Error(what + ": '" + item + "' is not 'zone:a,b,...' ('" + v + "' is not a number)");
      values.push_back(static_cast<std::int32_t>(value));
    }
  }
  return lists;
}

std::map<Label, Label> ParseMirrorSwaps(const std::string& text)
{
  return ParseLabelPairs(text, true, "mirror swaps");
}

PatternResult SynthesizePattern(
  const std::vector<LabelGrid>& exemplars, const PatternOptions& options)
{
  const auto start = std::chrono::steady_clock::now();
  const bool threeD = options.Size[2] > 1;
  const std::vector<Stencil> blocks =
    options.Blocks.empty() ? BlockScheme(6, threeD) : options.Blocks;
  const FactorModel model =
    LearnFactors(exemplars, options.SoftFactors, blocks, options.ExtraPairs);
  CheckOptions(model, options);
  {
    // Per factor: validity, slice, satisfaction (bytes), stamp (4) and set position (8); per
    // site: tiles, classes, groups, last change; each sample kept: labels, two fields.
    const auto sites =
      static_cast<std::uint64_t>(options.Size[0] * options.Size[1] * options.Size[2]);
    const std::uint64_t factors = sites * (3 + options.SoftFactors.size());
    CheckMemory(factors * 15 + sites * (24 + 16 * static_cast<std::uint64_t>(options.Samples)),
      "A pattern of " + std::to_string(sites) + " sites");
  }

  PatternResult result;
  result.Tiles = model.NumberOfTiles();
  for (const auto& b : model.BlockTiles)
    result.ReplacementBlocks += static_cast<std::int64_t>(b.size());
  // The whole output, for scoring samples (and for the constraint solver's guide).
  const PatternProblem scorer(model, options, options.Size, false);
  result.HardFactors = scorer.HardCount;
  result.SoftFactors = scorer.SoftCount;
  CheckPatternPath(model, scorer, options);

  if (options.Method == PatternMethod::ConstraintSolver)
    RunConstraintSolver(model, scorer, options, result);
  else
  {
    const std::array<std::int64_t, 3> part = SolvedSize(options);
    const bool mirrored = part != options.Size;
    std::optional<PatternProblem> half;
    if (mirrored)
      half.emplace(model, options, part, true);
    const PatternProblem& problem = mirrored ? *half : scorer;
    std::vector<std::int32_t> mirror(ToIndex(model.NumberOfTiles()));
    for (int b = 0; b < model.NumberOfTiles(); ++b)
    {
      const auto it = options.MirrorMap.find(model.Tiles[ToIndex(b)]);
      mirror[ToIndex(b)] = it == options.MirrorMap.end() ? b : model.TileIndex(it->second);
    }
    std::vector<std::int32_t> initial;
    if (options.Start == PatternStart::Solver && options.Method == PatternMethod::BlockSS)
    {
      SynthesisOptions so = SolverOptions(model, problem, options, false);
      initial = SolveOnce(
        model, PairRules(model), so, Random::Derived(options.Seed, 0x57a27).Next(), result);
      if (result.Status == SynthesisStatus::Cancelled)
        return result;
    }
    std::unique_ptr<NetworkRepair> network;
    ConnectedResult connected; // the last repair's figures, for the sample taken next
    detail::SampleRepair repair;
    if (options.Connected.Active())
    {
      network = std::make_unique<NetworkRepair>(model, problem, options);
      network->Seed = options.Seed;
      repair = [&](std::vector<std::int32_t>& tiles)
      { return network->Mend(tiles, result, connected); };
    }
    detail::RunSampler(
      problem, options, initial, result,
      [&](const std::vector<std::int32_t>& tiles, const std::vector<std::int64_t>& last,
        double seconds)
      {
        std::vector<std::int32_t> fullTiles = mirrored
          ? Unfold(tiles, part, options, [&](std::int32_t b) { return mirror[ToIndex(b)]; })
          : tiles;
        std::vector<std::int64_t> fullLast =
          mirrored ? Unfold(last, part, options, [](std::int64_t v) { return v; }) : last;
        PatternSample s =
          MakeSample(scorer, model, options, std::move(fullTiles), std::move(fullLast));
        s.Moves = result.Moves;
        s.Seconds = seconds;
        s.Connected = connected;
        result.Samples.push_back(std::move(s));
      },
      repair);
  }
  result.Seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

} // namespace msynth
