// SPDX-License-Identifier: BSD-3-Clause
#include "Discrete/BlockSolver.h"

#include "Core/LabelDraw.h"

#include "Core/Error.h"
#include "Core/Index.h"
#include "Discrete/Connectivity.h"

#include <algorithm>
#include <cmath>
#include <queue>

namespace msynth
{
namespace detail
{

BlockSolver::BlockSolver(const AdjacencyRules& rules, const SynthesisOptions& options,
  const MirrorPlan* plan, const SymmetryPlan* seams, SharedModel& shared)
  : Rules(rules)
  , Options(options)
  , Cat(rules)
  , Plan(plan)
  , Seams(seams)
  , Model(shared.Model)
  , Fixed(shared.Fixed)
  , LastBlock(shared.LastBlock)
{
  this->N = options.Size;
  this->SiteOrderNow = options.Order;
  LabelGrid::CheckDimensions(this->N[0], this->N[1], this->N[2]);
  if (seams)
    this->Cat.SetArcs(seams->Relation.get(), &seams->Arcs);
  const auto sites = ToIndex(this->N[0] * this->N[1] * this->N[2]);
  if (this->Model.empty())
  {
    this->Model.assign(sites, -1);
    this->Fixed.assign(sites, -1);
    this->LastBlock.assign(sites, -1);
  }
  const int k = rules.NumberOfLabels();
  this->WLogW.resize(ToIndex(k));
  for (int b = 0; b < k; ++b)
  {
    const double w = this->Weight(b);
    this->WLogW[ToIndex(b)] = w * std::log(w);
  }
  double sum = 0.0, sumWLogW = 0.0;
  for (int b = 0; b < k; ++b)
  {
    sum += this->Weight(b);
    sumWLogW += this->WLogW[ToIndex(b)];
  }
  this->FullEntropy = std::log(sum) - sumWLogW / sum;
  if (options.Guide)
  {
    this->SetUpGuide(*options.Guide);
  }
  if (options.Choice == LabelChoice::Resemblance)
  {
    this->SetUpResemblance();
  }
}

int BlockSolver::LabelIndex(Label value, const char* what) const
{
  const int b = this->Rules.IndexOf(value);
  if (b < 0)
  {
    throw Error(
      std::string(what) + " label " + std::to_string(value) + " does not occur in the example");
  }
  return b;
}

/// Boundary layers (Fig. 3.11), with precedence -z, +z, -y, +y, -x, +x.
void BlockSolver::ApplyBoundary()
{
  static const int precedence[6] = { FaceMinZ, FaceMaxZ, FaceMinY, FaceMaxY, FaceMinX, FaceMaxX };
  for (int f = 5; f >= 0; --f) // lowest precedence first, so higher ones overwrite
  {
    const int face = precedence[f];
    const auto& value = this->Options.Boundary[ToIndex(face)];
    const int axis = face / 2;
    if (!value || this->N[axis] == 1)
    {
      continue;
    }
    const int b = this->LabelIndex(*value, "boundary");
    const std::int64_t layer = (face % 2 == 0) ? 0 : this->N[axis] - 1;
    Coord p;
    for (p[2] = 0; p[2] < this->N[2]; ++p[2])
      for (p[1] = 0; p[1] < this->N[1]; ++p[1])
        for (p[0] = 0; p[0] < this->N[0]; ++p[0])
        {
          if (p[axis] == layer)
          {
            this->Fixed[ToIndex(this->Index(p))] = b;
          }
        }
  }
  for (std::size_t s = 0; s < this->Fixed.size(); ++s)
  {
    if (this->Fixed[s] >= 0)
    {
      this->Model[s] = this->Fixed[s];
    }
  }
  if (this->HasGuide())
  {
    Coord p;
    for (p[2] = 0; p[2] < this->N[2]; ++p[2])
      for (p[1] = 0; p[1] < this->N[1]; ++p[1])
        for (p[0] = 0; p[0] < this->N[0]; ++p[0])
        {
          const int b = this->Fixed[ToIndex(this->Index(p))];
          if (b >= 0 && this->GuideWeight(this->GuideCell(p), b) == 0.0f)
            throw Error("the boundary label " +
              std::to_string(this->Rules.LabelValues()[ToIndex(b)]) + " has guide weight 0 at " +
              Format(p));
        }
  }
}

std::int64_t BlockSolver::ConstrainBlock(const Block& block, std::vector<std::int64_t>& free)
{
  Catalog& cat = this->Cat;
  const Coord& o = block.Origin;
  const Coord& m = block.Dims;
  free.clear();
  free.reserve(ToIndex(cat.NumberOfSites()));
  for (std::int64_t local = 0; local < cat.NumberOfSites(); ++local)
  {
    const Coord c = cat.Coordinates(local);
    const Coord p{ { o[0] + c[0], o[1] + c[1], o[2] + c[2] } };
    const int fixed = this->Fixed[ToIndex(this->Index(p))];
    if (fixed >= 0)
    {
      if (!cat.Assign(local, fixed))
        return local;
    }
    else
    {
      free.push_back(local);
      if (!this->KeepSiteConstraints(cat, local, p))
        return local;
    }
    for (int d = 0; d < NumberOfDirections; ++d)
    {
      const int axis = AxisOf(d);
      Coord q = p;
      q[axis] += (d & 1) ? -1 : 1;
      if (q[axis] < 0 || q[axis] >= this->N[axis] ||
        (q[axis] >= o[axis] && q[axis] < o[axis] + m[axis]))
        continue; // outside the model, or inside the block
      const int label = this->Model[ToIndex(this->Index(q))];
      if (label >= 0 && !cat.Constrain(local, Opposite(d), label))
        return local;
    }
    if (this->Seams && !this->ConstrainAcrossSeams(block, local, p))
      return local;
  }
  return cat.Propagate();
}

bool BlockSolver::ConstrainAcrossSeams(const Block& block, std::int64_t local, const Coord& p)
{
  const Coord& o = block.Origin;
  const Coord& m = block.Dims;
  const SiteArcs& arcs = this->Seams->Arcs;
  const std::int64_t g = this->Index(p);
  for (std::int64_t i = arcs.Start[ToIndex(g)]; i < arcs.Start[ToIndex(g + 1)]; ++i)
  {
    const std::int64_t t = arcs.Target[ToIndex(i)];
    const Coord q = this->Coordinates(t);
    if (q[0] >= o[0] && q[1] >= o[1] && q[2] >= o[2] && q[0] < o[0] + m[0] && q[1] < o[1] + m[1] &&
      q[2] < o[2] + m[2])
      continue; // inside the block: propagated by the catalog
    const int label = this->Model[ToIndex(t)];
    if (label >= 0 && !this->Cat.Constrain(local, arcs.Class[ToIndex(i)] ^ 1, label))
      return false;
  }
  return true;
}

int BlockSolver::ChooseLabel(std::int64_t local, Random& rng)
{
  if (this->Budget && this->Own[ToIndex(local)])
    return this->ChooseCounted(local, rng);
  // The guide's weights of this site's region multiply the choice's (D§3.5.3).
  const std::int64_t cell = this->HasGuide() ? this->GuideCellOfLocal(local) : 0;
  if (this->Options.Choice == LabelChoice::Resemblance)
  {
    this->ResemblanceWeights(local, this->ChoiceWeights);
    double weightSum = 0.0;
    for (std::size_t b = 0; b < this->ChoiceWeights.size(); ++b)
    {
      if (this->HasGuide())
        this->ChoiceWeights[b] *= this->GuideWeight(cell, static_cast<int>(b));
      weightSum += this->ChoiceWeights[b];
    }
    if (weightSum > 0.0)
    {
      return DrawWeighted([this](auto&& visit)
        { ForEachIndex(this->Rules.NumberOfLabels(), visit); },
        [this](int b) { return this->ChoiceWeights[ToIndex(b)]; }, rng.Uniform());
    }
    // No example site matches any possible label (labels only reachable through
    // propagation): fall back to the weighted choice below.
  }
  if (this->Bias)
  {
    const Coord c = this->Cat.Coordinates(local);
    const Coord& o = this->Cat.Origin();
    const std::int64_t site = this->Index({ { o[0] + c[0], o[1] + c[1], o[2] + c[2] } });
    return DrawLabel(
      this->Cat.Domain(local), this->Rules.Words(),
      [this, cell, site](int b)
      {
        const double w = this->SiteWeight(cell, b) * (*this->Bias)(site, b);
        return this->Scale ? w * (*this->Scale)[ToIndex(b)] : w;
      },
      rng.Uniform());
  }
  if (this->Scale)
    return DrawLabel(
      this->Cat.Domain(local), this->Rules.Words(),
      [this, cell](int b) { return this->SiteWeight(cell, b) * (*this->Scale)[ToIndex(b)]; },
      rng.Uniform());
  return DrawLabel(
    this->Cat.Domain(local), this->Rules.Words(),
    [this, cell](int b) { return this->SiteWeight(cell, b); }, rng.Uniform());
}

std::int64_t BlockSolver::RunBlock(const Block& block, Random& rng, std::int64_t& assignments)
{
  Catalog& cat = this->Cat;
  cat.Reset(block.Origin, block.Dims);
  this->Pending.clear(); // snapshots of an earlier, failed attempt are dropped
  const Coord& o = block.Origin;
  auto global = [&](std::int64_t local)
  {
    const Coord c = cat.Coordinates(local);
    return this->Index({ { o[0] + c[0], o[1] + c[1], o[2] + c[2] } });
  };

  // Fixed labels inside the block, and the labels around it (lines 12-17).
  std::vector<std::int64_t>& free = this->FreeSites;
  std::int64_t empty = this->ConstrainBlock(block, free);
  if (empty >= 0)
    return global(empty);
  if (this->Budget)
    this->StartCounts(block);

  // Assign the free sites (lines 19-29), in the chosen order, with bounded chronological
  // backtracking (BlockSearch.cxx): a choice that empties a catalog is undone and ruled out there.
  BlockSearch search(*this, block, rng, assignments);
  if (this->SiteOrderNow == SiteOrder::MinimumEntropy)
  {
    empty =
      this->AssignByEntropy(free, rng, [&](std::int64_t local) { return search.Assign(local); });
  }
  else
  {
    if (this->SiteOrderNow == SiteOrder::Random)
    {
      for (std::size_t i = free.size(); i > 1; --i)
        std::swap(free[i - 1], free[ToIndex(rng.Below(i))]);
    }
    // Where to resume after a backtrack (none without backtracking).
    std::vector<std::int64_t>& position = this->Position;
    if (this->Options.BacktracksPerAttempt > 0)
    {
      position.assign(ToIndex(cat.NumberOfSites()), -1);
      for (std::size_t i = 0; i < free.size(); ++i)
        position[ToIndex(free[i])] = static_cast<std::int64_t>(i);
    }
    for (std::size_t i = 0; i < free.size();)
    {
      empty = search.Assign(free[i]);
      if (empty >= 0)
        break;
      if (!this->Budget)
        cat.ClearChanged(); // nobody reads them here: a whole model would keep every change
      // After a backtrack, go on from the site whose choice was ruled out: every later site is
      // as it was before that choice.
      i = search.Resume() >= 0 ? ToIndex(position[ToIndex(search.Resume())]) : i + 1;
    }
  }
  if (empty >= 0)
    return global(empty);
  if (this->Budget && !this->CountsKept(block))
    return global(0); // solved, but the label counts missed: another attempt
  if (this->Network && !this->FinalAttempt && !this->Repairing &&
    !this->Network->Keeps(block, cat, this->Model))
    return global(0); // solved, but it closes a component of the network off: another attempt

  // Success: commit the block.
  for (std::int64_t local = 0; local < cat.NumberOfSites(); ++local)
  {
    const auto s = ToIndex(global(local));
    const int b = cat.Single(local);
    if (this->Model[s] != b)
    {
      this->Model[s] = b;
      this->LastBlock[s] = static_cast<std::int32_t>(block.Index);
    }
  }
  return -1;
}

/// Minimum-entropy order with a priority queue (no full scan per step): entries are pushed
/// when a site's catalog changes and skipped when stale.
template <typename AssignFn>
std::int64_t BlockSolver::AssignByEntropy(
  const std::vector<std::int64_t>& free, Random& rng, AssignFn&& assign)
{
  Catalog& cat = this->Cat;
  struct Entry
  {
    double Priority;
    std::int64_t Local;
    int Count;
    bool operator<(const Entry& o) const { return this->Priority > o.Priority; } // min-heap
  };
  std::vector<double> noise(ToIndex(cat.NumberOfSites()), 0.0);
  std::vector<std::uint8_t> isFree(ToIndex(cat.NumberOfSites()), 0);
  for (std::int64_t local : free)
  {
    noise[ToIndex(local)] = 1e-6 * rng.Uniform();
    isFree[ToIndex(local)] = 1;
  }
  std::vector<std::uint32_t> pushed(ToIndex(cat.NumberOfSites()), 0);
  std::uint32_t step = 0;
  auto entropy = [&](std::int64_t local) { return this->Entropy(cat, local); };
  std::priority_queue<Entry> heap;
  for (std::int64_t local : free)
  {
    if (cat.Count(local) > 1)
      heap.push({ entropy(local) + noise[ToIndex(local)], local, cat.Count(local) });
  }
  cat.ClearChanged();
  while (!heap.empty())
  {
    const Entry e = heap.top();
    heap.pop();
    if (cat.Count(e.Local) != e.Count || cat.Count(e.Local) <= 1)
      continue; // stale, or decided by propagation
    const std::int64_t empty = assign(e.Local);
    if (empty >= 0)
      return empty;
    ++step;
    for (std::int64_t local : cat.Changed())
    {
      // A site changed several times in one propagation is pushed once (the same entry).
      if (isFree[ToIndex(local)] && cat.Count(local) > 1 && pushed[ToIndex(local)] != step)
      {
        pushed[ToIndex(local)] = step;
        heap.push({ entropy(local) + noise[ToIndex(local)], local, cat.Count(local) });
      }
    }
    if (this->Budget)
      this->SyncCounts(); // before the changes are dropped
    cat.ClearChanged();
  }
  // Every free site is now decided (a single label) or was never undecided.
  for (std::int64_t local : free)
  {
    if (cat.Count(local) == 0)
      return local;
  }
  return -1;
}

/// Entropy of the weighted labels still possible at @p local of the current catalog (the
/// guide's weights included).
double BlockSolver::Entropy(const Catalog& cat, std::int64_t local) const
{
  const bool guided = this->HasGuide();
  const std::int64_t cell = guided ? this->GuideCellOfLocal(local) : 0;
  double sum = 0.0, sumWLogW = 0.0;
  const std::uint64_t* dom = cat.Domain(local);
  for (int w = 0; w < this->Rules.Words(); ++w)
    for (std::uint64_t bits = dom[w]; bits; bits &= bits - 1)
    {
      const int b = w * 64 + __builtin_ctzll(bits);
      if (guided)
      {
        const double weight = this->SiteWeight(cell, b);
        sum += weight;
        sumWLogW += weight > 0.0 ? weight * std::log(weight) : 0.0;
      }
      else
      {
        sum += this->Weight(b);
        sumWLogW += this->WLogW[ToIndex(b)];
      }
    }
  return sum > 0.0 ? std::log(sum) - sumWLogW / sum : 0.0;
}

/// The whole model now: outside the active block, the model; inside, the catalog.
CatalogSnapshot BlockSolver::Capture(const Block* active, std::int64_t assignments) const
{
  CatalogSnapshot snap;
  const std::size_t n = this->Model.size();
  snap.CatalogSize.assign(n, 1);
  snap.Entropy.assign(n, 0.0f);
  snap.Labels.resize(n);
  snap.Block = active ? active->Index : -1;
  snap.Assignments = assignments;
  const auto& values = this->Rules.LabelValues();
  const int k = this->Rules.NumberOfLabels();
  for (std::size_t s = 0; s < n; ++s)
  {
    const int b = this->Model[s];
    snap.Labels[s] = b >= 0 ? values[ToIndex(b)] : CatalogSnapshot::Undecided;
    if (b < 0)
    {
      snap.CatalogSize[s] = k; // never constrained yet (whole-model start)
      snap.Entropy[s] = static_cast<float>(this->FullEntropy);
    }
  }
  if (active)
  {
    const Catalog& cat = this->Cat;
    for (std::int64_t local = 0; local < cat.NumberOfSites(); ++local)
    {
      const Coord c = cat.Coordinates(local);
      const auto s = ToIndex(this->Index(
        { { active->Origin[0] + c[0], active->Origin[1] + c[1], active->Origin[2] + c[2] } }));
      const int count = cat.Count(local);
      snap.CatalogSize[s] = count;
      snap.Entropy[s] = static_cast<float>(this->Entropy(cat, local));
      snap.Labels[s] = count == 1 ? values[ToIndex(cat.Single(local))] : CatalogSnapshot::Undecided;
    }
  }
  return snap;
}

/// During an attempt: capture when the block's decided fraction reaches the next milestone.
void BlockSolver::MaybeCapture(const Block& block, std::int64_t assignments)
{
  if (!this->Snapshots())
    return;
  const int per = this->Options.SnapshotsPerBlock;
  // The last milestone (all decided) is the committed block, captured by CommitSnapshots.
  if (static_cast<int>(this->Pending.size()) >= per - 1)
    return;
  const double fraction = double(this->Cat.Decided()) / double(this->Cat.NumberOfSites());
  while (static_cast<int>(this->Pending.size()) < per - 1 &&
    fraction >= double(this->Pending.size() + 1) / double(per))
  {
    this->Pending.push_back(this->Capture(&block, assignments));
  }
}

/// After a block: emit its snapshots (padded to SnapshotsPerBlock with the final state).
void BlockSolver::CommitSnapshots(std::int64_t assignments)
{
  if (!this->Snapshots())
    return;
  CatalogSnapshot final = this->Capture(nullptr, assignments);
  while (static_cast<int>(this->Pending.size()) < this->Options.SnapshotsPerBlock - 1)
    this->Pending.push_back(final);
  this->Pending.push_back(std::move(final));
  for (auto& snap : this->Pending)
  {
    snap.Step = ++this->Steps;
    this->Options.OnSnapshot(snap);
  }
  this->Pending.clear();
}

void BlockSolver::StartSnapshots()
{
  if (!this->Snapshots())
    return;
  CatalogSnapshot start = this->Capture(nullptr, 0);
  start.Step = 0;
  this->Options.OnSnapshot(start);
}

} // namespace detail
} // namespace msynth
