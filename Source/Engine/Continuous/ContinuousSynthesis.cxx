// SPDX-License-Identifier: BSD-3-Clause
#include "Continuous/ContinuousSynthesis.h"

#include "Continuous/ConstraintPlan.h"
#include "Continuous/ContinuousMirror.h"
#include "Continuous/RunParts.h"
#include "Continuous/SolverParts.h"
#include "Core/BlockDriver.h"
#include "Core/Error.h"
#include "Core/Index.h"
#include "Core/ParallelChunks.h"
#include "Core/Random.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstring>
#include <limits>
#include <memory>
#include <numeric>

namespace msynth
{
namespace
{
/// A double's bits as an integer for the block exchange, and back.
std::int64_t BitsOf(double x)
{
  std::int64_t bits = 0;
  std::memcpy(&bits, &x, sizeof bits);
  return bits;
}
double DoubleOf(std::int64_t bits)
{
  double x = 0;
  std::memcpy(&x, &bits, sizeof x);
  return x;
}

/**
 * One worker of a run of continuous synthesis (D§4.5, Algorithm 4.1; T§4.5.6 for the blocks):
 * its block's vertices and catalog, the attempt with one level of backtracking, and (worker 0,
 * alone) the catalog snapshots. The workers share the model's labels, each writing only its own
 * block's (blocks of a phase never touch); the run over the blocks is the shared BlockDriver.
 */
class ContinuousRun
{
public:
  ContinuousRun(const detail::RunParts& parts, const PlaneArrangement& arrangement,
    const ContinuousSynthesisOptions& options, ContinuousSynthesisResult& result, unsigned worker)
    : Arrangement(arrangement)
    , Options(options)
    , Rules(parts.Rules)
    , Result(result)
    , N(arrangement.NumberOfVertices())
    , K(this->Rules.NumberOfLabels())
    , Words(this->Rules.Words())
    , Worker(worker)
    , Whole(parts.Whole)
    , Halo(parts.Whole || !parts.Parallel ? std::numeric_limits<double>::infinity()
                                          : parts.Layout->CellEdge)
    , Layout(parts.Layout.get())
    , Blocks(this->Whole ? 1 : static_cast<std::int64_t>(parts.Order.size()))
    , Initial(parts.Initial)
    , Weights(parts.Weights)
    , Plan(parts.Plan.get())
    , Ends(parts.Ends.get())
    , Order(parts.Order)
  {
    if (worker == 0)
      result.Labels.assign(ToIndex(this->N), this->Rules.EmptyLabel());
    this->LocalOf.assign(ToIndex(this->N), -1);
    this->Guided = this->Plan->Weighted() || this->Plan->GrowMask() != 0 || this->Ends;
    this->Tally.assign(ToIndex(this->Plan->NumberOfTypes()), 0.0);
  }

  /// The shares of the model as every block of the next phase sees them.
  void SetTally(const std::vector<double>& tally) { this->Tally = tally; }
  const std::vector<double>& PhaseTally() const { return this->Tally; }
  /// Labels withdrawn because their propagation failed, on this worker.
  std::int64_t Backtracks() const { return this->Withdrawn; }

  /// The block labelled @p position-th (blocks spread outward from connectivity seeds).
  std::int64_t BlockAt(std::size_t position) const { return this->Order[position]; }
  /// The vertices of the block labelled @p position-th, ascending.
  std::vector<std::int64_t> VerticesOf(std::size_t position) const
  {
    if (!this->Whole)
      return this->Layout->Vertices(this->BlockAt(position));
    std::vector<std::int64_t> all(ToIndex(this->N));
    std::iota(all.begin(), all.end(), std::int64_t(0));
    return all;
  }
  /// Empties stray solid parts: floating (grounded runs), beyond the seeds (connectivity).
  detail::ConstraintPlan::Removed RemoveStrayParts()
  {
    return this->Plan->RemoveStrayParts(this->Result.Labels, this->Rules.EmptyLabel());
  }
  /// Empties solid parts that keep the types' shares from their targets (proportions).
  detail::ConstraintPlan::Proportioned KeepProportions()
  {
    return this->Plan->KeepProportionateParts(this->Result.Labels, this->Rules.EmptyLabel(),
      static_cast<unsigned>(std::max(0, this->Options.Threads)));
  }
  /// Empties the solid parts holding a corner too close to another plane's feature (slivers).
  std::int64_t RemoveNarrowParts()
  {
    return this->Plan->EmptyPartsAt(this->Result.Labels, this->Rules.EmptyLabel(),
      this->Rules.NarrowCorners(this->Result.Labels));
  }
  /// Redraws blocks before the emptying of parts for the proportions (RedrawForProportions).
  detail::ConstraintPlan::Redrawn RedrawForProportions(BlockDriver& driver)
  {
    detail::ConstraintPlan::BlockRedraw hooks;
    hooks.Blocks = this->Whole ? 1 : this->Layout->NumberOfBlocks();
    hooks.Vertices = [this](std::int64_t b) { return this->Layout->Vertices(b); };
    hooks.Redraw = [this, &driver](std::int64_t b, std::uint64_t key)
    {
      std::fill(this->Tally.begin(), this->Tally.end(), 0.0); // the model's shares steer
      for (const std::int32_t label : this->Result.Labels)
        this->AddShares(this->Tally, label, 1);
      this->Enter(b);
      Random rng = Random::Derived(this->Options.Seed, key, 0x70726f70); // "prop"
      std::int64_t assignments = 0;
      std::vector<double> tally;
      return this->Attempt(b, rng, driver, assignments, tally) < 0;
    };
    hooks.Clean = [this]()
    {
      const auto stray = this->RemoveStrayParts();
      return std::array<std::int64_t, 3>{ { stray.Floating, stray.BeyondSeeds,
        this->RemoveNarrowParts() } };
    };
    hooks.Stopped = [&driver]() { return driver.Stopped(0); };
    return this->Plan->RedrawForProportions(this->Result.Labels, this->Rules.EmptyLabel(),
      static_cast<unsigned>(std::max(0, this->Options.Threads)), hooks);
  }

  bool WholeModel() const { return this->Whole; }
  std::int64_t NumberOfBlocks() const { return this->Blocks; }
  bool Snapshots() const { return this->Options.Snapshots > 0 && this->Options.OnSnapshot; }
  const std::string& LastFailure() const { return this->Failure; }
  /// The arrangement vertex of the current block's local vertex @p local.
  std::int64_t Vertex(std::int64_t local) const { return this->Verts[ToIndex(local)]; }
  void EmptyModel() { this->Result.Labels.assign(ToIndex(this->N), this->Rules.EmptyLabel()); }

  /// Makes block @p b the current one: its vertices and their local numbers.
  void Enter(std::int64_t b)
  {
    for (std::int64_t v : this->Verts) // the worker's previous block
      this->LocalOf[ToIndex(v)] = -1;
    if (this->Whole)
    {
      this->Verts.resize(ToIndex(this->N));
      std::iota(this->Verts.begin(), this->Verts.end(), std::int64_t(0));
    }
    else
    {
      this->Verts = this->Layout->Vertices(b);
    }
    for (std::size_t i = 0; i < this->Verts.size(); ++i)
      this->LocalOf[ToIndex(this->Verts[i])] = static_cast<std::int32_t>(i);
    this->BlockStart = CatalogSnapshot();
    this->BlockTally = this->Tally; // the shares without the block's current labels
    for (std::int64_t v : this->Verts)
      this->AddShares(this->BlockTally, this->Result.Labels[ToIndex(v)], -1);
  }

  /// One attempt at the current block @p b: -1 when solved (its labels are written to the
  /// model, the model's shares with them to @p tally), else the local vertex whose catalog
  /// became empty.
  std::int64_t Attempt(std::int64_t b, Random& rng, BlockDriver& driver, std::int64_t& assignments,
    std::vector<double>& tally);

  /// After the block labelled @p b-th (worker 0, alone): its snapshots are emitted.
  void Leave(std::int64_t b)
  {
    if (this->Whole || !this->Snapshots())
      return;
    // Snapshots 1 .. S-1 show the catalog of block floor(j · blocks / S) after its first
    // propagation; snapshot S the finished model.
    for (std::int64_t j = 1; j < this->Options.Snapshots; ++j)
    {
      if ((j * this->Blocks) / this->Options.Snapshots == b)
      {
        if (this->BlockStart.CatalogSize.empty())
          this->BlockStart = this->Capture(b, false);
        this->Emit(this->BlockStart);
      }
    }
    if (b + 1 == this->Blocks)
      this->Emit(this->Capture(b, false));
  }

  /// The whole model now; @p active: with the current block's catalog; block -1: the catalog
  /// before anything is chosen.
  CatalogSnapshot Capture(std::int64_t block, bool active) const;
  void Emit(CatalogSnapshot s)
  {
    s.Step = this->Step++;
    this->Options.OnSnapshot(s);
  }

private:
  /// The labels of vertices outside the block constrain the block's catalog (then propagated).
  std::int64_t ConstrainFromOutside();
  /// Labels the undecided vertices; a label whose propagation empties a set is removed and
  /// another tried (one level of backtracking). Returns -1, or the emptied local vertex.
  std::int64_t AssignAll(std::int64_t b, Random& rng, BlockDriver& driver, std::int64_t& assigned);
  /// A label for local vertex @p i under the constraints: connectivity (types that grow only
  /// next to themselves, seeds), guide weights and type proportions.
  int Choose(std::int64_t i, Random& rng);
  /// Puts the undecided neighbours of the decided local vertex @p i that its growing types
  /// reach on the growth front.
  void Spread(std::int64_t i, detail::SiteQueue& queue) const;
  /// The model's shares with the block labelled @p labels.
  std::vector<double> Tallied(const std::vector<std::int32_t>& labels) const
  {
    std::vector<double> tally = this->BlockTally;
    for (int label : labels)
      this->AddShares(tally, label, 1);
    return tally;
  }
  void AddShares(std::vector<double>& tally, int label, double sign) const
  {
    if (!this->Plan->Weighted())
      return; // the shares only steer weighted draws (Factor, Mismatch)
    for (int t = 0; t < this->Plan->NumberOfTypes(); ++t)
      tally[ToIndex(t)] += sign * this->Plan->Occupancy(label, t);
  }
  template <typename Visit>
  void ForEachNeighbour(std::int64_t local, Visit&& visit) const
  {
    const std::int64_t v = this->Verts[ToIndex(local)];
    for (const auto* l = this->Arrangement.LinksBegin(v); l != this->Arrangement.LinksEnd(v); ++l)
    {
      if (l->Vertex >= 0)
      {
        const std::int32_t u = this->LocalOf[ToIndex(l->Vertex)];
        if (u >= 0 && !visit(u, l->Direction))
          return;
      }
    }
  }

  const PlaneArrangement& Arrangement;
  const ContinuousSynthesisOptions& Options;
  const ArrangementRules& Rules;
  ContinuousSynthesisResult& Result;
  const std::int64_t N;
  const int K, Words;
  const unsigned Worker;
  const bool Whole;
  /// How far outside its block a block may read labels: a cell's edge where blocks of a phase
  /// run concurrently (BlockLayout), anywhere when one block or one at a time.
  const double Halo;
  const detail::BlockLayout* Layout;
  const std::int64_t Blocks;
  const std::vector<std::uint64_t>& Initial; ///< [vertex][word]: the starting catalog
  const std::vector<double>& Weights;        ///< per label; empty: uniform
  const detail::ConstraintPlan* Plan;
  const detail::RunEnds* Ends;
  const std::vector<std::int64_t>& Order; ///< blocks in the order they are labelled
  bool Guided = false;                    ///< labels drawn by Choose (constraints active)
  std::vector<double> Tally;      ///< solid shares of the model at the phase's start (per type bit)
  std::vector<double> BlockTally; ///< the same without the current block's labels
  std::vector<double> AttemptTally; ///< BlockTally plus the attempt's choices so far
  std::vector<int> Candidates;      ///< scratch of Choose
  std::vector<double> CandidateWeights;
  std::vector<std::int32_t> LocalOf; ///< per vertex: its number in the current block, or -1
  std::vector<std::int64_t> Verts;   ///< the current block's vertices, ascending
  LabelDomains Domains;
  std::vector<CatalogSnapshot> Pending; ///< whole model: the current attempt's snapshots
  CatalogSnapshot BlockStart;           ///< blocks: the block's catalog after propagation
  std::int64_t Step = 0;
  std::int64_t AssignmentsSoFar = 0; ///< label choices of all finished attempts
  std::int64_t Withdrawn = 0;        ///< labels withdrawn (backtracks) on this worker
  std::string Failure;               ///< where the last failed attempt emptied a catalog
};

CatalogSnapshot ContinuousRun::Capture(std::int64_t block, bool active) const
{
  CatalogSnapshot s;
  s.Block = block;
  s.Assignments = this->AssignmentsSoFar;
  s.CatalogSize.assign(ToIndex(this->N), 1);
  s.Labels = this->Result.Labels;
  if (block < 0) // the catalog before anything is chosen
  {
    for (std::int64_t v = 0; v < this->N; ++v)
    {
      int c = 0;
      for (int i = 0; i < this->Words; ++i)
        c += __builtin_popcountll(this->Initial[ToIndex(v) * this->Words + i]);
      s.CatalogSize[ToIndex(v)] = c;
      s.Labels[ToIndex(v)] = CatalogSnapshot::Undecided;
    }
  }
  if (active)
  {
    for (std::size_t i = 0; i < this->Verts.size(); ++i)
    {
      const auto v = ToIndex(this->Verts[i]);
      const int c = this->Domains.Count(static_cast<std::int64_t>(i));
      s.CatalogSize[v] = c;
      s.Labels[v] =
        c == 1 ? this->Domains.Single(static_cast<std::int64_t>(i)) : CatalogSnapshot::Undecided;
    }
  }
  s.Entropy.resize(s.CatalogSize.size());
  for (std::size_t i = 0; i < s.CatalogSize.size(); ++i)
    s.Entropy[i] = s.CatalogSize[i] > 0 ? static_cast<float>(std::log2(s.CatalogSize[i])) : 0.0f;
  return s;
}

std::int64_t ContinuousRun::ConstrainFromOutside()
{
  const auto m = static_cast<std::int64_t>(this->Verts.size());
  std::vector<std::uint64_t> startSets(ToIndex(m) * this->Words);
  for (std::int64_t i = 0; i < m; ++i)
    std::copy_n(this->Initial.data() + ToIndex(this->Verts[ToIndex(i)]) * this->Words, this->Words,
      startSets.data() + ToIndex(i) * this->Words);
  this->Domains.Reset(m, this->K, std::move(startSets));
  bool ok = true;
  for (std::int64_t i = 0; i < m; ++i)
  {
    const std::int64_t v = this->Verts[ToIndex(i)];
    for (const auto* l = this->Arrangement.LinksBegin(v); l != this->Arrangement.LinksEnd(v); ++l)
    {
      if (l->Vertex >= 0 && this->LocalOf[ToIndex(l->Vertex)] < 0)
      {
        // A fixed neighbour w: u is reached from w along the opposite direction.
        ok = this->Domains.Keep(i,
               this->Rules.Compatible(l->Direction ^ 1, this->Result.Labels[ToIndex(l->Vertex)])) &&
          ok;
      }
    }
  }
  auto neighbours = [this](std::int64_t local, auto&& visit)
  { this->ForEachNeighbour(local, visit); };
  return ok ? this->Domains.Propagate(this->Rules, neighbours) : 0;
}

std::int64_t ContinuousRun::AssignAll(
  std::int64_t b, Random& rng, BlockDriver& driver, std::int64_t& assigned)
{
  const auto m = static_cast<std::int64_t>(this->Verts.size());
  auto neighbours = [this](std::int64_t local, auto&& visit)
  { this->ForEachNeighbour(local, visit); };
  int taken = 0;
  std::vector<std::uint64_t> exclude(ToIndex(this->Words));
  detail::SiteQueue queue(this->Options.Order, m, rng);
  for (std::int64_t i = 0; i < m; ++i)
    queue.Update(i, this->Domains.Count(i));
  this->AttemptTally = this->BlockTally;
  if (this->Plan->GrowMask())
  {
    // The growth front: seeds, the ground, and vertices the labels around them reach.
    for (std::int64_t i = 0; i < m; ++i)
    {
      const std::int64_t v = this->Verts[ToIndex(i)];
      std::uint64_t reach = this->Plan->StartTypes(v);
      for (const auto* l = this->Arrangement.LinksBegin(v); l != this->Arrangement.LinksEnd(v); ++l)
      {
        if (l->Vertex >= 0 && this->LocalOf[ToIndex(l->Vertex)] < 0)
          reach |= this->Plan->EdgeTypes(l->Direction ^ 1, this->Result.Labels[ToIndex(l->Vertex)]);
      }
      if (reach & this->Plan->GrowMask())
        queue.SetFront(i, (reach & this->Plan->LeadMask()) != 0);
    }
    for (std::int64_t i = 0; i < m; ++i)
      if (this->Domains.Count(i) == 1)
        this->Spread(i, queue);
  }
  this->Domains.ClearChanged();
  this->Domains.Record(true);
  std::int64_t empty = -1;
  for (;;)
  {
    if (driver.Poll(this->Worker, assigned))
      return 0; // cancelled: the attempt ends here (and no other starts)
    const std::int64_t i = queue.Next();
    if (i < 0)
      return -1;
    for (;;)
    {
      this->Domains.Record(true);
      const int label = this->Guided ? this->Choose(i, rng)
                                     : detail::PickLabel(this->Domains.Domain(i), this->Words,
                                         this->Domains.Count(i), this->Weights, rng);
      this->Domains.Assign(i, label);
      ++assigned;
      empty = this->Domains.Propagate(this->Rules, neighbours);
      if (empty < 0)
        break;
      this->Domains.Undo(0);
      ++this->Withdrawn;
      std::fill(exclude.begin(), exclude.end(), ~std::uint64_t(0));
      exclude[ToIndex(label >> 6)] &= ~(std::uint64_t(1) << (label & 63));
      this->Domains.Keep(i, exclude.data());
      empty = this->Domains.Propagate(this->Rules, neighbours);
      if (empty >= 0 || this->Domains.Count(i) == 1)
        break;
    }
    if (empty < 0 && this->Domains.Count(i) == 1)
      this->AddShares(this->AttemptTally, this->Domains.Single(i), 1);
    for (std::int64_t c : this->Domains.Changed())
    {
      queue.Update(c, this->Domains.Count(c));
      if (empty < 0 && this->Plan->GrowMask() && this->Domains.Count(c) == 1)
        this->Spread(c, queue);
    }
    if (empty < 0 && this->Plan->GrowMask() && this->Domains.Count(i) == 1)
      this->Spread(i, queue);
    this->Domains.ClearChanged();
    if (empty >= 0)
      return empty;
    if (this->Whole && this->Snapshots())
    {
      const int snapshots = this->Options.Snapshots;
      while (
        taken < snapshots && (m - queue.Remaining()) * snapshots >= std::int64_t(taken + 1) * m)
      {
        ++taken;
        this->Pending.push_back(this->Capture(b, true));
      }
    }
  }
}

void ContinuousRun::Spread(std::int64_t i, detail::SiteQueue& queue) const
{
  const int label = this->Domains.Single(i);
  this->ForEachNeighbour(i,
    [&](std::int64_t u, int d)
    {
      const std::uint64_t reach = this->Plan->EdgeTypes(d, label);
      if (this->Domains.Count(u) > 1 && (reach & this->Plan->GrowMask()))
        queue.SetFront(u, (reach & this->Plan->LeadMask()) != 0);
      return true;
    });
}

int ContinuousRun::Choose(std::int64_t i, Random& rng)
{
  const std::int64_t v = this->Verts[ToIndex(i)];
  std::uint64_t forbidden = 0, seeded = 0;
  if (this->Plan->GrowMask())
  {
    // Growing types only next to their group (TVCG §4.6: a type, or the solid as a whole), or
    // where a seed or the ground starts them.
    std::uint64_t reach = this->Plan->StartTypes(v);
    for (const auto* l = this->Arrangement.LinksBegin(v); l != this->Arrangement.LinksEnd(v); ++l)
    {
      if (l->Vertex < 0)
        continue;
      const std::int32_t u = this->LocalOf[ToIndex(l->Vertex)];
      if (u >= 0 && this->Domains.Count(u) != 1)
        continue;
      const int label = u >= 0 ? this->Domains.Single(u) : this->Result.Labels[ToIndex(l->Vertex)];
      reach |= this->Plan->EdgeTypes(l->Direction ^ 1, label);
    }
    forbidden = this->Plan->Unreached(reach);
    seeded = this->Plan->SeedTypes(v);
  }
  auto& c = this->Candidates;
  const std::uint64_t* domain = this->Domains.Domain(i);
  for (int pass = 0; pass < 3; ++pass)
  {
    // Pass 0: a seed's own types; 1: labels the growth allows; 2: any label of the catalog.
    if (pass == 0 && !seeded)
      continue;
    c.clear();
    for (int w = 0; w < this->Words; ++w)
    {
      for (std::uint64_t bits = domain[w]; bits; bits &= bits - 1)
      {
        const int a = w * 64 + __builtin_ctzll(bits);
        const std::uint64_t types = this->Plan->LabelTypes(a);
        if ((pass == 0 && !(types & seeded)) || (pass < 2 && (types & forbidden)))
          continue;
        c.push_back(a);
      }
    }
    if (!c.empty())
      break;
  }
  if (!this->Plan->Weighted() && this->Weights.empty() && !this->Ends)
    return c[ToIndex(rng.Below(c.size()))];
  auto& weight = this->CandidateWeights;
  weight.resize(c.size());
  double total = 0;
  for (std::size_t k = 0; k < c.size(); ++k)
    weight[k] = this->Weights.empty() ? 1.0 : this->Weights[ToIndex(c[k])];
  if (this->Ends)
  {
    // A decided vertex's label, -1 undecided, -2 outside the block where another block of the
    // phase may be labelling (Halo or more away).
    this->Ends->Weigh(v, c, weight,
      [this](std::int64_t u, double distance)
      {
        const std::int32_t l = this->LocalOf[ToIndex(u)];
        return l >= 0 ? (this->Domains.Count(l) == 1 ? this->Domains.Single(l) : -1)
                      : (distance < this->Halo ? this->Result.Labels[ToIndex(u)] : -2);
      });
  }
  // The constraints' factors (guide, proportions, fill) last: the run ends rescale the labels
  // that end a part against those that carry it on, which would undo a type's proportion.
  for (std::size_t k = 0; k < c.size(); ++k)
    weight[k] *= this->Plan->Factor(v, c[k], this->AttemptTally);
  for (double w : weight)
    total += w;
  if (!(total > 0))
    return c[ToIndex(rng.Below(c.size()))];
  const int k =
    DrawWeighted([&c](auto&& visit) { ForEachIndex(static_cast<int>(c.size()), visit); },
      [&weight](int j) { return weight[ToIndex(j)]; }, rng.Uniform());
  return c[ToIndex(k)];
}

std::int64_t ContinuousRun::Attempt(std::int64_t b, Random& rng, BlockDriver& driver,
  std::int64_t& assignments, std::vector<double>& tally)
{
  this->Pending.clear();
  std::int64_t empty = this->ConstrainFromOutside();
  if (!this->Whole && this->Snapshots() && empty < 0)
    this->BlockStart = this->Capture(b, true); // the block's catalog, the rest of the model fixed
  std::int64_t assigned = 0;
  if (empty < 0)
    empty = this->AssignAll(b, rng, driver, assigned);
  assignments += assigned;
  this->AssignmentsSoFar += assigned;
  if (empty >= 0)
  {
    const std::int64_t v = this->Verts[ToIndex(empty)];
    const Point3& p = this->Arrangement.Position(v);
    this->Failure = "no label fits at vertex " + std::to_string(v) + " (" + std::to_string(p[0]) +
      ", " + std::to_string(p[1]) + ", " + std::to_string(p[2]) + ")";
    return empty;
  }
  std::vector<std::int32_t> best(this->Verts.size());
  for (std::size_t i = 0; i < this->Verts.size(); ++i)
    best[i] = this->Domains.Single(static_cast<std::int64_t>(i));
  const int candidates = this->Snapshots() ? 1 : this->Plan->Candidates();
  double bestScore = candidates > 1 ? this->Plan->Mismatch(this->Tallied(best)) : 0;
  for (int c = 1; c < candidates; ++c)
  {
    // Other labellings of the block; the one whose type shares come closest to the targets wins.
    Random other = Random::Derived(rng.Next(), static_cast<std::uint64_t>(c));
    std::int64_t more = 0;
    if (this->ConstrainFromOutside() >= 0 || this->AssignAll(b, other, driver, more) >= 0)
      continue;
    assignments += more;
    this->AssignmentsSoFar += more;
    std::vector<std::int32_t> labels(this->Verts.size());
    for (std::size_t i = 0; i < this->Verts.size(); ++i)
      labels[i] = this->Domains.Single(static_cast<std::int64_t>(i));
    const double score = this->Plan->Mismatch(this->Tallied(labels));
    if (score < bestScore)
    {
      bestScore = score;
      best.swap(labels);
    }
  }
  for (std::size_t i = 0; i < this->Verts.size(); ++i)
    this->Result.Labels[ToIndex(this->Verts[i])] = best[i];
  tally = this->Tallied(best);
  while (this->Whole && this->Snapshots() &&
    static_cast<int>(this->Pending.size()) < this->Options.Snapshots)
    this->Pending.push_back(this->Capture(b, true)); // decided by propagation before the last marks
  for (const auto& s : this->Pending) // only the successful attempt's snapshots are kept
    this->Emit(s);
  return -1;
}

/**
 * Runs the schedule's blocks on the driver's workers (worker 0: @p run, the others made here).
 * The model's type shares move on in block order after each phase, so every block of a phase
 * sees the same shares whatever the number of threads.
 */
SynthesisStatus RunBlocks(const detail::RunParts& parts, ContinuousRun& run,
  const PlaneArrangement& arrangement, const ContinuousSynthesisOptions& options,
  ContinuousSynthesisResult& result, BlockDriver& driver)
{
  std::vector<std::unique_ptr<ContinuousRun>> others;
  for (unsigned w = 1; w < driver.Workers(); ++w)
    others.push_back(std::make_unique<ContinuousRun>(parts, arrangement, options, result, w));
  auto on = [&](unsigned w) -> ContinuousRun& { return w == 0 ? run : *others[w - 1]; };
  const BlockSchedule& schedule = parts.Schedule;
  std::vector<std::vector<double>> tallies(schedule.Size());
  std::vector<double> model = run.PhaseTally();
  BlockClient client;
  client.Enter = [&](unsigned w, std::size_t i) { on(w).Enter(run.BlockAt(i)); };
  client.Attempt = [&](unsigned w, std::size_t i, int, Random& rng, std::int64_t& assignments)
  {
    ContinuousRun& r = on(w);
    const std::int64_t empty = r.Attempt(run.BlockAt(i), rng, driver, assignments, tallies[i]);
    return empty < 0 ? empty : r.Vertex(empty); // the arrangement vertex, for Describe
  };
  client.Describe = [](std::size_t, const BlockOutcome& out, BlockFailure& f)
  { f.EmptyIndex = out.Empty; };
  // Processes: a block travels as its vertices' labels and the model's shares it left.
  client.Pack = [&](std::size_t i, BlockRunner::Bytes& out)
  {
    for (std::int64_t v : run.VerticesOf(i))
      out.Put(result.Labels[ToIndex(v)]);
    out.Put(static_cast<std::int64_t>(tallies[i].size()));
    for (double share : tallies[i])
      out.Put(BitsOf(share));
  };
  client.Unpack = [&](std::size_t i, BlockRunner::Bytes& in, bool remote)
  {
    for (std::int64_t v : run.VerticesOf(i))
    {
      const auto label = static_cast<std::int32_t>(in.Get());
      if (remote)
        result.Labels[ToIndex(v)] = label;
    }
    const std::int64_t shares = in.Get();
    if (shares < 0 || shares > 64)
      throw Error("block exchange: a block's shares are damaged");
    std::vector<double> tally(ToIndex(shares));
    for (double& share : tally)
      share = DoubleOf(in.Get());
    if (remote)
      tallies[i] = std::move(tally);
  };
  client.After = [&](std::size_t i, const BlockOutcome&)
  {
    const std::vector<double>& phase = run.PhaseTally();
    for (std::size_t t = 0; t < tallies[i].size(); ++t)
      model[t] += tallies[i][t] - phase[t];
    if (i + 1 == schedule.Size() || schedule.Phases[i + 1] != schedule.Phases[i])
      for (unsigned w = 0; w < driver.Workers(); ++w)
        on(w).SetTally(model);
    run.Leave(static_cast<std::int64_t>(i));
  };
  const SynthesisStatus status = driver.Run(schedule, client, result.Statistics);
  for (unsigned w = 0; w < driver.Workers(); ++w)
    result.Statistics.Backtracks += on(w).Backtracks();
  return status;
}
} // namespace

ContinuousSynthesisResult SynthesizeContinuous(const PolyhedralAnalysis& analysis,
  const PlaneArrangement& arrangement, const ContinuousSynthesisOptions& options)
{
  if (options.Constraints.ModelCandidates != 1)
    return SynthesizeCandidates(analysis, arrangement, options);
  if (options.MirrorAxes != 0)
    return SynthesizeMirrored(analysis, arrangement, options);
  const auto start = std::chrono::steady_clock::now();
  if (!std::isfinite(options.BlockSize) ||
    !(options.BlockSize < 0 || options.BlockSize == 0 || options.BlockSize >= 1))
    throw Error("continuous synthesis: the block size is measured in plane spacings and must be "
                "0 (the whole model at once), at least 1, or negative (automatic), not " +
      std::to_string(options.BlockSize));
  if (options.Attempts < 1)
    throw Error("continuous synthesis: at least one attempt is needed");
  ContinuousSynthesisResult result;
  SynthesisStatistics& stats = result.Statistics;
  const detail::RunParts parts(analysis, arrangement, options);
  result.BlockSize = parts.BlockSize;
  result.Order = options.Order;
  ContinuousRun run(parts, arrangement, options, result, 0);
  if (run.Snapshots())
    run.Emit(run.Capture(-1, false));

  // Phases of non-touching blocks on threads (snapshots: one thread, the same model); blocks
  // spreading outward from connectivity seeds one after the other.
  BlockRunner::Policy policy;
  policy.Threads = options.Threads;
  policy.Exchange = options.Exchange;
  policy.Serial = run.Snapshots() || !parts.Parallel;
  policy.Progress = options.Progress;
  BlockDriver driver(
    std::move(policy), options.Seed, options.Attempts, parts.Schedule.Size(), start);
  result.Status = RunBlocks(parts, run, arrangement, options, result, driver);
  stats.Phases = 0;
  for (std::size_t i = 0; i < parts.Schedule.Size(); ++i)
    stats.Phases += i == 0 || parts.Schedule.Phases[i] != parts.Schedule.Phases[i - 1] ? 1 : 0;
  if (!driver.End(result.Status, result.Message, stats, run.WholeModel(),
        [&](const BlockFailure&)
        {
          return WholeModelFailure("whole-model synthesis (Algorithm 4.1)", options.Attempts,
            run.LastFailure(), "Try blocks (a block size of a few plane spacings)");
        }))
  {
    run.EmptyModel();
    return result;
  }
  const auto removed = run.RemoveStrayParts();
  result.FloatingPartsRemoved = removed.Floating;
  result.PartsBeyondSeedsRemoved = removed.BeyondSeeds;
  result.NarrowPartsRemoved = run.RemoveNarrowParts();
  // Not on the half of a mirrored model (its seam edges are free until it is reflected).
  if (options.PartOf.empty())
  {
    const auto redrawn = run.RedrawForProportions(driver);
    result.ProportionBlocksRedrawn = redrawn.Blocks;
    result.FloatingPartsRemoved += redrawn.Parts[0];
    result.PartsBeyondSeedsRemoved += redrawn.Parts[1];
    result.NarrowPartsRemoved += redrawn.Parts[2];
    if (driver.Stopped(0)) // cancelled among the redraws: no model, as within the blocks
    {
      result.Status = SynthesisStatus::Cancelled;
      result.Message = "cancelled";
      run.EmptyModel();
      return result;
    }
  }
  const auto proportioned =
    options.PartOf.empty() ? run.KeepProportions() : detail::ConstraintPlan::Proportioned();
  result.ProportionPartsRemoved = proportioned.Removed;
  result.ProportionVolumeRemoved = proportioned.VolumeRemoved;
  result.ProportionsOutside = proportioned.Reason;
  // The arrangement's vertices are the output's points (the mirrored model's: its whole
  // arrangement, which the outermost mirror names).
  result.Message = (options.PartOf.empty()
                       ? std::to_string(arrangement.NumberOfVertices()) + " arrangement vertices, "
                       : std::string()) +
    Summary(stats, run.WholeModel());
  if (options.Constraints.Grounded)
    result.Message +=
      ", " + std::to_string(result.FloatingPartsRemoved) + " floating parts emptied";
  if (result.NarrowPartsRemoved > 0)
    result.Message += ", " + std::to_string(result.NarrowPartsRemoved) +
      " parts emptied for features under a tenth of a spacing";
  if (result.ProportionBlocksRedrawn > 0)
    result.Message += ", " + std::to_string(result.ProportionBlocksRedrawn) +
      " blocks redrawn for the types' proportions";
  if (proportioned.Removed > 0)
    result.Message +=
      ", " + std::to_string(proportioned.Removed) + " parts emptied for the types' proportions";
  if (removed.BeyondSeeds > 0)
    result.Message +=
      ", " + std::to_string(removed.BeyondSeeds) + " parts beyond the seeds emptied";
  return result;
}

} // namespace msynth
