// SPDX-License-Identifier: BSD-3-Clause
// Discrete model synthesis (D ch. 3): Algorithms 3.1 and 3.4 as one run of blocks over the
// shared block machinery (Core/BlockSynthesis.h), each block solved by a BlockSolver
// (Discrete/BlockSolver.h); soft constraints (M07§4.2, Discrete/SoftConstraints.h) decide which
// blocks are kept; symmetric outputs (D§3.5.2) synthesize a part and unfold it.
#include "Discrete/DiscreteSynthesis.h"

#include "Core/BlockDriver.h"
#include "Core/Error.h"
#include "Core/Index.h"
#include "Core/Memory.h"
#include "Core/MirrorFold.h"
#include "Core/Random.h"
#include "Core/WorldSchedule.h"
#include "Discrete/BlockSolver.h"
#include "Discrete/Connectivity.h"
#include "Discrete/LabelCounts.h"
#include "Discrete/MirrorPlan.h"
#include "Discrete/SoftConstraints.h"
#include "Discrete/SymmetryPlan.h"
#include "Discrete/WindowRun.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <functional>
#include <memory>
#include <set>
#include <thread>

namespace msynth
{
using namespace detail;

namespace
{
/// The solvers of a run: worker 0's, and one more per extra thread over the same model.
struct Workers
{
  /// Worker 0 (@p first) and one more per extra thread of @p driver (made by @p another),
  /// each attached to it, over @p cone's window when given.
  Workers(BlockSolver& first, BlockDriver& driver, const RegionCone* cone,
    const std::function<std::unique_ptr<BlockSolver>()>& another)
    : First(&first)
    , Offset(cone ? cone->WindowLow : Coord{ { 0, 0, 0 } })
  {
    first.Attach(&driver, 0);
    for (unsigned w = 1; w < driver.Workers(); ++w)
    {
      this->Extra.push_back(another());
      this->Extra.back()->Attach(&driver, w);
    }
  }

  std::vector<std::unique_ptr<BlockSolver>> Extra;
  BlockSolver* First = nullptr;
  Coord Offset; ///< where their model lies in the world (a window's low corner; else 0)
  BlockSolver& operator[](unsigned w) { return w == 0 ? *this->First : *this->Extra[w - 1]; }
  /// Adds every worker's backtracks to @p stats; returns their attempts that missed the counts.
  std::int64_t Totals(SynthesisStatistics& stats) const
  {
    stats.Backtracks = this->First->Backtracks();
    std::int64_t misses = this->First->CountMisses();
    for (const auto& extra : this->Extra)
    {
      stats.Backtracks += extra->Backtracks();
      misses += extra->CountMisses();
    }
    return misses;
  }
};

/// The blocks as the driver's client: attempts (with @p orders alternating per attempt when
/// given), keep or roll back, snapshots, failures, and the labels exchanged between processes.
BlockClient MakeClient(const std::vector<Block>& blocks, Workers& workers, SoftConstraints& soft,
  SharedModel& shared, SynthesisStatistics& stats, std::vector<SiteOrder> orders = {})
{
  BlockSolver& solver = workers[0];
  const Coord n = solver.Size();
  BlockClient client;
  client.Enter = [&blocks, &soft](unsigned, std::size_t i) { soft.Save(i, blocks[i]); };
  const int attempts = solver.Attempts();
  client.Attempt = [&blocks, &workers, orders, attempts](
                     unsigned w, std::size_t i, int attempt, Random& rng, std::int64_t& assignments)
  {
    BlockSolver& worker = workers[w];
    worker.SetFinalAttempt(attempt + 1 >= attempts);
    if (!orders.empty())
      worker.SetOrder(orders[ToIndex(attempt) % orders.size()]);
    return worker.RunBlock(blocks[i], rng, assignments);
  };
  client.After = [&blocks, &soft, &solver, &stats](std::size_t i, const BlockOutcome& out)
  {
    const bool kept = out.Solved() && soft.Decide(i, blocks[i]);
    if (!kept)
      solver.DropSnapshots(); // the block keeps its previous labels: repeat that state
    solver.CommitSnapshots(stats.Assignments + out.Assignments);
  };
  client.Describe = [&blocks, n, off = workers.Offset](
                      std::size_t i, const BlockOutcome& out, BlockFailure& f)
  {
    // In the world's coordinates, as a region's or a stream's failures are reported.
    const Coord e{ { out.Empty % n[0], (out.Empty / n[0]) % n[1], out.Empty / (n[0] * n[1]) } };
    for (std::size_t a = 0; a < 3; ++a)
    {
      f.Origin[a] = blocks[i].Origin[a] + off[a];
      f.EmptySite[a] = e[a] + off[a];
    }
  };
  client.Pack = [&blocks, &shared, n](std::size_t i, BlockRunner::Bytes& out)
  {
    ForEachSite(blocks[i], n,
      [&](std::size_t s)
      {
        out.Put(shared.Model[s]);
        out.Put(shared.LastBlock[s]);
      });
  };
  client.Unpack = [&blocks, &shared, &soft, n](std::size_t i, BlockRunner::Bytes& in, bool remote)
  {
    if (remote)
      soft.Save(i, blocks[i]); // the labels before the block, as where it ran
    ForEachSite(blocks[i], n,
      [&](std::size_t s)
      {
        const auto label = static_cast<std::int32_t>(in.Get());
        const auto lastBlock = static_cast<std::int32_t>(in.Get());
        if (remote)
        {
          shared.Model[s] = label;
          shared.LastBlock[s] = lastBlock;
        }
      });
  };
  return client;
}

/**
 * One pass of second tries at failed blocks (SynthesisOptions::RepairFailedBlocks): a pass over
 * the phases after every earlier one, running those of @p candidates (in phase order) still
 * failed, with attempt streams after the first try's and earlier passes', twice the attempts,
 * and site orders alternating. Those that succeed leave the failures. Part of the schedule:
 * blocks of a phase never touch, so the model does not depend on threads, and a region's cone
 * takes these passes in (Core/WorldSchedule.h).
 */
SynthesisStatus RepairFailedBlocks(const SynthesisOptions& options,
  const std::vector<Block>& candidates, BlockDriver& driver, Workers& workers,
  SoftConstraints& soft, SharedModel& shared, SynthesisStatistics& stats, int round)
{
  std::set<std::int64_t> failed;
  for (const BlockFailure& f : stats.Failures)
    failed.insert(f.Block);
  std::vector<Block> again;
  for (const Block& b : candidates)
    if (failed.count(b.Index))
      again.push_back(b);
  // Alternating the order the first pass did not use with minimum entropy or scan line: a
  // block one order cannot finish the other often can (entropy order closes the loops of
  // WaveFunctionCollapse's Castle set, scan line those of its Knots "CE" subset).
  const SiteOrder order = workers[0].Order();
  BlockPass pass;
  pass.AttemptOffset = options.AttemptsPerBlock * (1 + 2 * round);
  pass.Attempts = 2 * options.AttemptsPerBlock;
  pass.Later = true;
  SynthesisStatistics second;
  for (unsigned w = 0; w < driver.Workers(); ++w)
    workers[w].SetRepairing(true); // every block has run: keep the others' own counts
  const BlockClient client = MakeClient(again, workers, soft, shared, second,
    order == SiteOrder::MinimumEntropy
      ? std::vector<SiteOrder>{ SiteOrder::ScanLine, SiteOrder::MinimumEntropy }
      : std::vector<SiteOrder>{ SiteOrder::MinimumEntropy, order });
  const SynthesisStatus status = driver.Run(BlockSchedule::Of(again), client, second, pass);
  for (unsigned w = 0; w < driver.Workers(); ++w)
  {
    workers[w].SetOrder(order);
    workers[w].SetRepairing(false);
  }
  stats.BlocksRepaired += second.BlocksAccepted;
  stats.BlocksAccepted += second.BlocksAccepted;
  stats.BlocksFailed -= second.BlocksAccepted;
  stats.Attempts += second.Attempts;
  stats.Assignments += second.Assignments;
  std::set<std::int64_t> tried;
  for (const Block& b : again)
    tried.insert(b.Index);
  std::vector<BlockFailure> still; // failures this pass could not reach (outside a region's cone)
  for (const BlockFailure& f : stats.Failures)
    if (!tried.count(f.Block))
      still.push_back(f);
  still.insert(still.end(), second.Failures.begin(), second.Failures.end());
  stats.Failures = std::move(still);
  return status;
}

/**
 * A region's start must be the world's start there: a start that varies along an axis (layers)
 * depends on where the window lies along it, unless the window spans the world on that axis.
 * @throw Error otherwise.
 */
void CheckStartInWindow(
  const RegionCone& cone, const std::vector<std::int32_t>& start, const Coord& n)
{
  for (std::size_t a = 0; a < 3; ++a)
  {
    if (cone.WindowLow[a] == 0 && cone.WindowHigh[a] == cone.World[a])
      continue;
    const std::int64_t stride = a == 0 ? 1 : (a == 1 ? n[0] : n[0] * n[1]);
    for (std::size_t s = 0; s < start.size(); ++s)
    {
      const auto along = (static_cast<std::int64_t>(s) / stride) % n[a];
      if (along + 1 < n[a] && start[s] != start[s + ToIndex(stride)])
        throw Error(std::string("a region of this world cannot be computed alone: its start is "
                                "layered along ") +
          "xyz"[a] + " (no label tiles space), so it depends on where the region lies; compute " +
          "the whole world");
    }
  }
}

/// The blocks of @p cone's pass @p pass in its window's coordinates (keys and phases the
/// world's).
std::vector<Block> WindowBlocks(const RegionCone& cone, std::size_t pass = 0)
{
  std::vector<Block> blocks = cone.Passes[pass];
  for (Block& b : blocks)
    for (std::size_t a = 0; a < 3; ++a)
      b.Origin[a] -= cone.WindowLow[a];
  return blocks;
}

/// The blocks the repair pass @p round may run in @p cone's window (into @p scratch).
const std::vector<Block>& RepairCandidates(
  const RegionCone& cone, int round, std::vector<Block>& scratch)
{
  scratch = WindowBlocks(cone, ToIndex(round + 1));
  return scratch;
}

/// After block synthesis from an undecided start: false, with @p result failed and a message
/// naming the first undecided site, when a site was left undecided (its blocks all failed).
bool AllDecided(const std::vector<std::int32_t>& model, const Coord& n, SynthesisResult& result)
{
  const auto first = std::find(model.begin(), model.end(), -1);
  if (first == model.end())
    return true;
  const auto s = static_cast<std::int64_t>(first - model.begin());
  result.Status = SynthesisStatus::Failed;
  result.Message = "block synthesis from an undecided start left " +
    std::to_string(std::count(model.begin(), model.end(), -1)) + " sites undecided, the first at " +
    Format({ { s % n[0], (s / n[0]) % n[1], s / (n[0] * n[1]) } }) +
    " (every block over them failed). Try another seed, larger blocks, or the trivial start";
  return false;
}

/**
 * The start of block synthesis (Algorithm 3.4, lines 3-5) on @p solver's model, checked, and the
 * pins applied after it; records it in @p stats. Returns whether the start is undecided (the
 * free sites stay -1, which blocks read as free).
 */
bool StartBlocks(const AdjacencyRules& rules, const SynthesisOptions& options, BlockSolver& solver,
  const SharedModel& shared, const RegionCone* cone, bool wholeModel, SynthesisStatistics& stats)
{
  const bool undecided = !wholeModel && options.StartFrom == BlockStart::Undecided;
  if (!wholeModel)
    stats.StartFrom = undecided ? "undecided" : "trivial";
  if (!wholeModel && !undecided)
    stats.TrivialLabel = rules.LabelValues()[ToIndex(solver.TrivialStart())];
  if (cone && !undecided)
    CheckStartInWindow(*cone, shared.Model, solver.Size());
  solver.ApplyPins(); // after the start's own checks: the pins are placed into it later
  return undecided;
}

/// The runner's policy: snapshots need one thread; seams link blocks of one phase; a fitness
/// function sees the whole model, so its decisions must follow every block in order.
BlockRunner::Policy PolicyOf(
  const SynthesisOptions& options, const BlockSolver& solver, const SymmetryPlan* seams)
{
  BlockRunner::Policy policy;
  policy.Threads = options.Threads;
  policy.Exchange = options.Exchange;
  policy.Serial = solver.Snapshots() || (seams && !seams->Arcs.Empty()) ||
    static_cast<bool>(options.Soft.Fitness) || options.Connected.Active();
  policy.Progress = options.Progress;
  return policy;
}

/// The values of the labels of @p shared (every site decided) as @p r's model.
void ModelFromShared(
  const AdjacencyRules& rules, SharedModel& shared, const Coord& n, SynthesisResult& r)
{
  std::vector<Label> values(shared.Model.size());
  for (std::size_t s = 0; s < values.size(); ++s)
    values[s] = rules.LabelValues()[ToIndex(shared.Model[s])];
  r.Model = LabelGrid(n, std::move(values));
  r.LastBlock = std::move(shared.LastBlock);
}
} // namespace

SynthesisResult detail::SynthesizeDirect(const AdjacencyRules& rules,
  const SynthesisOptions& options, const MirrorPlan* plan, const SymmetryPlan* seams,
  const WindowRun* run)
{
  const RegionCone* cone = run ? run->Cone : nullptr;
  const auto start = std::chrono::steady_clock::now();
  if (options.AttemptsPerBlock < 1)
    throw Error("attempts per block must be at least 1");
  SharedModel shared;
  BlockSolver solver(rules, options, plan, seams, shared);
  const Coord n = solver.Size();
  Coord m, step;
  const bool wholeModel =
    cone ? cone->Whole : BlockGeometry<3>(n, options.BlockSize, options.Overlap, m, step);
  solver.ApplyBoundary();

  SynthesisResult result;
  SynthesisStatistics& stats = result.Statistics;
  const bool undecided = StartBlocks(rules, options, solver, shared, cone, wholeModel, stats);
  const std::vector<Block> blocks = cone
    ? WindowBlocks(*cone)
    : PlanBoxBlocks<3>(n, m, step, PhasePolicy::NonTouching, stats.Phases);
  if (cone)
    stats.Phases = cone->Phases;
  std::vector<Block> repairScratch;
  if (options.Soft.Active() && wholeModel)
    throw Error("soft constraints (Metropolis acceptance of block changes) need block synthesis");
  SoftConstraints soft(rules, options, shared, n, blocks.size(), stats);

  BlockRunner::Policy policy = PolicyOf(options, solver, seams);
  std::size_t most = blocks.size(); // the workers a later pass may use too
  for (std::size_t p = 1; cone && p < cone->Passes.size(); ++p)
    most = std::max(most, cone->Passes[p].size());
  BlockDriver driver(std::move(policy), options.Seed, options.AttemptsPerBlock, most, start);
  Workers workers(solver, driver, cone,
    [&] { return std::make_unique<BlockSolver>(rules, options, plan, seams, shared); });

  if (!wholeModel && options.Pins)
  {
    if (cone) // the world's block size
      BlockGeometry<3>(cone->World, options.BlockSize, options.Overlap, m, step);
    solver.PlacePins(m, options.Seed, stats.Assignments, cone, run ? run->Scales : nullptr);
  }
  const auto budget = options.Counts.empty()
    ? nullptr
    : std::make_unique<CountBudget>(
        rules, options, cone ? CountedBlocks(*cone) : blocks, n, shared.Fixed, cone);
  for (unsigned w = 0; budget && w < driver.Workers(); ++w)
    workers[w].UseCounts(budget.get());
  const auto network = options.Connected.Active() && (options.Connected.Open || !(run && run->Keep))
    ? std::make_unique<NetworkRun>(rules, options, blocks, solver, cone) // one thread (PolicyOf)
    : nullptr;
  solver.StartSnapshots();
  if (run && run->Carry)
    run->Carry(shared);
  if (run && run->Failures)
    stats.Failures = *run->Failures;
  result.Status =
    driver.Run(BlockSchedule::Of(blocks), MakeClient(blocks, workers, soft, shared, stats), stats);
  // Passes of second tries over the phases: a block next to one repaired in a pass meets new
  // surroundings in the next.
  const bool repair =
    !wholeModel && options.RepairFailedBlocks && !solver.Snapshots() && !options.Soft.Active();
  for (int round = 0; repair && round < RepairPasses &&
       result.Status == SynthesisStatus::Succeeded && !stats.Failures.empty();
       ++round)
  {
    const std::vector<Block>& candidates =
      cone ? RepairCandidates(*cone, round, repairScratch) : blocks;
    result.Status =
      RepairFailedBlocks(options, candidates, driver, workers, soft, shared, stats, round);
  }
  const std::int64_t misses = workers.Totals(stats);
  if (!driver.End(result.Status, result.Message, stats, wholeModel,
        [&](const BlockFailure& f)
        {
          return WholeModelFailure("whole-model synthesis (Algorithm 3.1)",
            options.AttemptsPerBlock, "the catalog became empty at site " + Format(f.EmptySite),
            "Try another seed, more attempts, or block synthesis");
        }))
    return CountsKept(options, std::move(result), misses, false);
  result.Message = Summary(stats, wholeModel);
  if (run && run->Failures)
    *run->Failures = stats.Failures;
  if (run && run->Keep)
  {
    *run->Keep = std::move(shared);
    return result;
  }
  if (undecided && !AllDecided(shared.Model, n, result))
    return result;
  const bool kept = !network || network->Keep(options, solver, shared, blocks, result);
  if (stats.Seconds = driver.Seconds(); !kept) // the network's repairs are synthesis too
    return result;
  ModelFromShared(rules, shared, n, result);
  return budget ? CountsKept(options, std::move(result), misses, true) : result;
}

namespace
{

/**
 * A part of the output (a mirrored half; a period or a quadrant) spread over the whole output:
 * output site q shows part site Source(q) (linear index, x fastest) with its label value mapped
 * by Image(q, value).
 */
struct Unfolding
{
  Coord Full{ { 1, 1, 1 } };
  std::function<std::size_t(const Coord&)> Source;
  std::function<Label(const Coord&, Label)> Image;

  template <class Visit>
  void ForEach(Visit&& visit) const
  {
    Coord q;
    std::size_t i = 0;
    for (q[2] = 0; q[2] < this->Full[2]; ++q[2])
      for (q[1] = 0; q[1] < this->Full[1]; ++q[1])
        for (q[0] = 0; q[0] < this->Full[0]; ++q[0], ++i)
          visit(i, q, this->Source(q));
  }

  CatalogSnapshot Snapshot(const CatalogSnapshot& part) const
  {
    CatalogSnapshot out;
    out.Step = part.Step;
    out.Block = part.Block;
    out.Assignments = part.Assignments;
    const auto n = ToIndex(this->Full[0] * this->Full[1] * this->Full[2]);
    out.CatalogSize.resize(n);
    out.Entropy.resize(n);
    out.Labels.resize(n);
    this->ForEach(
      [&](std::size_t i, const Coord& q, std::size_t j)
      {
        out.CatalogSize[i] = part.CatalogSize[j];
        out.Entropy[i] = part.Entropy[j];
        const Label v = part.Labels[j];
        out.Labels[i] = v == CatalogSnapshot::Undecided ? v : this->Image(q, v);
      });
    return out;
  }

  /// Replaces the part's model and LastBlock in @p r by the whole output's.
  void Apply(SynthesisResult& r) const
  {
    LabelGrid model(this->Full[0], this->Full[1], this->Full[2]);
    std::vector<std::int32_t> lastBlock(ToIndex(model.NumberOfSites()));
    this->ForEach(
      [&](std::size_t i, const Coord& q, std::size_t j)
      {
        model.Data()[i] = this->Image(q, r.Model.Data()[j]);
        lastBlock[i] = r.LastBlock[j];
      });
    r.Model = std::move(model);
    r.LastBlock = std::move(lastBlock);
  }
};

/// Synthesizes @p part (the options of a half, period or quadrant) and spreads it by
/// @p unfolding; the snapshots @p options asks for are spread too.
SynthesisResult SynthesizePart(const AdjacencyRules& rules, const SynthesisOptions& options,
  SynthesisOptions part, const MirrorPlan* mirror, const SymmetryPlan* seams,
  const Unfolding& unfolding)
{
  if (options.OnSnapshot)
    part.OnSnapshot = [&](const CatalogSnapshot& s) { options.OnSnapshot(unfolding.Snapshot(s)); };
  SynthesisResult r = SynthesizeDirect(rules, part, mirror, seams);
  if (r.Succeeded())
    unfolding.Apply(r);
  return r;
}

/// Translation or rotation symmetry: synthesizes the plan's domain with its seams, then repeats
/// (turns) it over the output with the labels mapped.
SynthesisResult SynthesizeSeamSymmetric(
  const AdjacencyRules& rules, const SynthesisOptions& options)
{
  const auto plan = PlanSymmetry(rules, options);
  const auto& values = rules.LabelValues();
  Unfolding unfolding;
  unfolding.Full = plan->Full;
  unfolding.Source = [&plan](const Coord& q) { return ToIndex(plan->Source(q)); };
  unfolding.Image = [&](const Coord& q, Label v)
  { return values[ToIndex(plan->Image(q, rules.IndexOf(v)))]; };
  SynthesisResult r =
    SynthesizePart(rules, options, plan->DomainOptions, nullptr, plan.get(), unfolding);
  if (r.Succeeded())
    r.Message += plan->Rotate ? " (turned copies of a quadrant)" : " (repeated periods)";
  return r;
}

/// Refuses, before anything is allocated, a model whose memory would exceed what is available:
/// per site the model, the last-block record and the caller's copies (about 24 bytes), plus a
/// catalog (two bit sets of the labels and bookkeeping) over each block being solved at once.
} // namespace

void detail::CheckSynthesisMemory(const AdjacencyRules& rules, const SynthesisOptions& o)
{
  std::uint64_t sites = 1, blockSites = 1;
  for (std::size_t a = 0; a < 3; ++a)
  {
    const auto n = static_cast<std::uint64_t>(o.Size[a]);
    sites *= n;
    const auto m = static_cast<std::uint64_t>(o.BlockSize[a]);
    blockSites *= (m == 0 || m > n) ? n : m;
  }
  const auto perCatalogSite = static_cast<std::uint64_t>(rules.Words()) * 16 + 24;
  const std::uint64_t catalogs =
    blockSites * (blockSites < sites ? std::max(1u, std::thread::hardware_concurrency()) : 1u);
  CheckMemory(sites * 24 + catalogs * perCatalogSite,
    "a " + std::to_string(o.Size[0]) + " x " + std::to_string(o.Size[1]) + " x " +
      std::to_string(o.Size[2]) + " model of " + std::to_string(rules.NumberOfLabels()) +
      " labels");
}

std::int64_t CountBlocks(const SynthesisOptions& requested)
{
  LabelGrid::CheckDimensions(requested.Size[0], requested.Size[1], requested.Size[2]);
  SynthesisOptions options = requested;
  for (int a = 0; a < 3; ++a)
  {
    if (requested.Symmetry[ToIndex(a)].Enabled)
      options.Size[a] = (requested.Size[a] + 1) / 2; // the synthesized half
    const Translation& t = requested.Translate[ToIndex(a)];
    if (t.Enabled && t.Period > 0 && t.Period < requested.Size[a])
      options.Size[a] = t.Period; // one period
  }
  if (requested.Rotate.Enabled)
    for (int a = 0; a < 2; ++a)
      options.Size[a] = (requested.Size[a] + 1) / 2; // a quadrant
  Coord m, step;
  BlockGeometry<3>(options.Size, options.BlockSize, options.Overlap, m, step);
  std::int64_t count = 1;
  for (int a = 0; a < 3; ++a)
  {
    count *= static_cast<std::int64_t>(BlockStarts(options.Size[a], m[a], step[a]).size());
  }
  return count;
}

std::int64_t CountSnapshots(const SynthesisOptions& options)
{
  return options.SnapshotsPerBlock > 0 ? 1 + CountBlocks(options) * options.SnapshotsPerBlock : 0;
}

namespace
{
SynthesisResult SynthesizeWithStart(const AdjacencyRules& rules, const SynthesisOptions& options);

/// The blocks a failed whole-model run falls back to (FallbackBlockEdge per axis, at most the
/// output); false when they would be the whole output again.
bool FallbackBlocks(const SynthesisOptions& options, Coord& block)
{
  bool smaller = false;
  for (std::size_t a = 0; a < 3; ++a)
  {
    block[a] = std::min(options.Size[a], FallbackBlockEdge);
    smaller |= block[a] < options.Size[a];
  }
  return smaller;
}
} // namespace

void CheckAxesWithoutPairs(const AdjacencyRules& rules, const SynthesisOptions& options)
{
  static const char* const names[3] = { "x", "y", "z" };
  for (int a = 0; a < 3; ++a)
  {
    if (options.Size[ToIndex(a)] <= 1 || rules.NumberOfLabels() == 0)
      continue;
    const std::uint64_t* any = rules.CompatibleWithAny(2 * a);
    bool none = true;
    for (int w = 0; w < rules.Words() && none; ++w)
      none = any[w] == 0;
    if (!none)
      continue;
    std::string size;
    for (int b = 0; b < 3; ++b)
      size +=
        (b ? " " : "") + (b == a ? std::string("1") : std::to_string(options.Size[ToIndex(b)]));
    throw Error(std::string("no two labels may be neighbours along ") + names[a] +
      " (the rules are flat along it: a 2D tileset or example), so a model " +
      std::to_string(options.Size[ToIndex(a)]) + " sites long along " + names[a] +
      " cannot exist; ask for one site along it (size " + size + ")");
  }
}

SynthesisResult Synthesize(const AdjacencyRules& rules, const SynthesisOptions& given)
{
  std::optional<SynthesisOptions> placed; // a placed pin grid, spread over the output
  if (given.Pins && given.PinsOrigin)
  {
    placed = given;
    placed->Pins = PinsOfBox(given, { { 0, 0, 0 } }, given.Size);
    placed->PinsOrigin.reset();
  }
  const SynthesisOptions& options = placed ? *placed : given;
  CheckAxesWithoutPairs(rules, options);
  CheckTranslationPeriods(rules, options);
  CheckCountRequest(rules, options);
  CheckConnectedRequest(rules, options);
  SynthesisResult r = SynthesizeWithStart(rules, options);
  Coord m, step, block;
  if (r.Status != SynthesisStatus::Failed || !options.BlocksWhenWholeFails ||
    options.SnapshotsPerBlock > 0 ||
    !BlockGeometry<3>(options.Size, options.BlockSize, options.Overlap, m, step) ||
    !FallbackBlocks(options, block))
    return r;
  SynthesisOptions blocks = options;
  blocks.BlockSize = block;
  blocks.Overlap = { { -1, -1, -1 } };
  SynthesisResult second;
  try
  {
    second = SynthesizeWithStart(rules, blocks);
  }
  catch (const Error&)
  {
    // Blocks cannot start here (no trivial start): the whole model's failure is the answer,
    // without advice to use blocks.
    const std::string advice = ", more attempts, or block synthesis";
    const auto at = r.Message.rfind(advice);
    if (at != std::string::npos)
      r.Message.replace(
        at, advice.size(), " or more attempts (block synthesis cannot start with this example)");
    return r;
  }
  if (!second.Succeeded())
    return second.Status == SynthesisStatus::Cancelled ? second : r;
  second.Message = r.Message.substr(0, r.Message.find(';')) + ", so the model was synthesized in " +
    std::to_string(block[0]) + " x " + std::to_string(block[1]) + " x " + std::to_string(block[2]) +
    " blocks instead: " + second.Message;
  return second;
}

namespace
{
SynthesisResult SynthesizeWithStart(const AdjacencyRules& rules, const SynthesisOptions& options)
{
  LabelGrid::CheckDimensions(options.Size[0], options.Size[1], options.Size[2]);
  CheckSynthesisMemory(rules, options);
  if (options.StartFrom == BlockStart::Automatic && options.UndecidedFirst)
  {
    SynthesisResult r = SynthesizeWithStart(rules, UndecidedWorld(options));
    if (r.Status != SynthesisStatus::Failed)
      return r;
    SynthesisOptions given = options;
    given.UndecidedFirst = false;
    SynthesisResult second = SynthesizeWithStart(rules, given);
    second.Message += " (from the given start: the undecided start failed, " + r.Message + ")";
    return second;
  }
  if (options.StartFrom == BlockStart::Automatic)
  {
    std::optional<SynthesisResult> done;
    SynthesisOptions chosen = options;
    chosen.StartFrom = ChooseBlockStart(rules, options, &done);
    if (done)
      return std::move(*done);
    SynthesisResult r = SynthesizeWithStart(rules, chosen);
    if (chosen.StartFrom != BlockStart::WholeModel || r.Status != SynthesisStatus::Failed)
      return r;
    chosen.StartFrom =
      BlockStart::Trivial; // the output's whole run failed where the probe's did not
    SynthesisResult trivial = SynthesizeWithStart(rules, chosen);
    trivial.Message += " (" + r.Message + ")";
    return trivial;
  }
  if (options.StartFrom == BlockStart::WholeModel)
    return SynthesizeFromWholeModel(rules, options);
  if (AnyMirror(options) && AnySeamSymmetry(options))
    throw Error("mirror symmetry cannot be combined with translation or rotation symmetry");
  if (!AnyMirror(options))
  {
    return AnySeamSymmetry(options) ? SynthesizeSeamSymmetric(rules, options)
                                    : SynthesizeDirect(rules, options, nullptr, nullptr);
  }
  const MirrorPlan plan = PlanMirror(rules, options);
  const auto& values = rules.LabelValues();
  // Output site q folds onto half site p, mirrored over the axes where q lies past the middle.
  auto fold = [&plan](const Coord& q, Coord& p)
  { return FoldMirror(q, plan.Full, plan.Half, plan.AxisMask(), p); };
  Unfolding unfolding;
  unfolding.Full = plan.Full;
  unfolding.Source = [&](const Coord& q)
  {
    Coord p;
    fold(q, p);
    return ToIndex(p[0] + plan.Half[0] * (p[1] + plan.Half[1] * p[2]));
  };
  unfolding.Image = [&](const Coord& q, Label v)
  {
    Coord p;
    return values[ToIndex(plan.Image(rules.IndexOf(v), fold(q, p)))];
  };
  SynthesisResult r = SynthesizePart(rules, options, plan.HalfOptions, &plan, nullptr, unfolding);
  if (!r.Succeeded())
  {
    return r;
  }
  r.Message += " (mirrored)";
  return r;
}
} // namespace

void StartFromWholeModel(const AdjacencyRules& rules, SynthesisOptions& options)
{
  bool blocks = false;
  for (std::size_t a = 0; a < 3; ++a)
    blocks |= options.BlockSize[a] > 0 && options.BlockSize[a] < options.Size[a];
  bool symmetric = options.Rotate.Enabled;
  for (std::size_t a = 0; a < 3; ++a)
    symmetric |= options.Symmetry[a].Enabled || options.Translate[a].Enabled;
  if (!blocks || symmetric || options.Start)
    return;
  for (int b = 0; b < rules.NumberOfLabels(); ++b)
    if (rules.SelfAdjacent(b, options.Size))
      return;
  SynthesisOptions whole = options;
  whole.BlockSize = { { 0, 0, 0 } };
  whole.OnSnapshot = nullptr;
  whole.SnapshotsPerBlock = 0;
  whole.Exchange = BlockExchange();
  const SynthesisResult start = Synthesize(rules, whole);
  if (start.Succeeded())
    options.Start = start.Model;
}

} // namespace msynth
