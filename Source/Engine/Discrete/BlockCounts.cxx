// SPDX-License-Identifier: BSD-3-Clause
#include "Discrete/BlockSolver.h"

#include "Core/Index.h"
#include "Core/LabelDraw.h"
#include "Discrete/LabelCounts.h"

#include <algorithm>
#include <map>

// Label counts in one block attempt (SynthesisOptions::Counts, Discrete/LabelCounts.h): the
// block's own sites, the steered choice there, and the check of the solved block.

namespace msynth
{
namespace detail
{

void BlockSolver::StartCounts(const Block& block)
{
  const Catalog& cat = this->Cat;
  const Coord& o = block.Origin;
  this->OwnBlock = block.Index;
  this->Have.assign(this->Budget->Labels().size(), 0);
  this->Left = 0;
  this->Own.assign(ToIndex(cat.NumberOfSites()), 0);
  this->Tally.assign(ToIndex(cat.NumberOfSites()), -2);
  for (std::int64_t local = 0; local < cat.NumberOfSites(); ++local)
  {
    const Coord c = cat.Coordinates(local);
    const auto s = ToIndex(this->Index({ { o[0] + c[0], o[1] + c[1], o[2] + c[2] } }));
    if (!this->CountsOfModel && this->Budget->Owner(s) != block.Index)
      continue;
    this->Own[ToIndex(local)] = 1 + this->Budget->Slot(s);
    ++this->Left; // undecided until tallied
  }
  if (this->CountsOfModel)
  {
    // A network repair's box over a finished model: the box may hold what the model's ranges
    // leave to it once the sites outside it are counted, and at least keeps what it holds when
    // a count is already outside its range (it moves no count farther out).
    const std::size_t counted = this->Budget->Labels().size();
    std::vector<std::int64_t> total(counted, 0), inside(counted, 0);
    for (std::size_t s = 0; s < this->Model.size(); ++s)
      if (const std::int32_t b = this->Model[s]; b >= 0)
        if (const int c = this->Budget->Position(b, this->Budget->Slot(s)); c >= 0)
          ++total[ToIndex(c)];
    ForEachSite(block, this->N,
      [&](std::size_t s)
      {
        if (const std::int32_t b = this->Model[s]; b >= 0)
          if (const int c = this->Budget->Position(b, this->Budget->Slot(s)); c >= 0)
            ++inside[ToIndex(c)];
      });
    this->BoxMin.assign(counted, 0);
    this->BoxMax.assign(counted, 0);
    for (std::size_t c = 0; c < counted; ++c)
    {
      const std::int64_t outside = total[c] - inside[c];
      this->BoxMin[c] = std::min(this->Budget->RangeMinimum(c) - outside, inside[c]);
      this->BoxMax[c] = std::max(this->Budget->RangeMaximum(c) - outside, inside[c]);
    }
  }
  this->LimitedNow = false;
  this->ChangedSeen = 0;
  for (std::int64_t local = 0; local < cat.NumberOfSites(); ++local)
    this->TallySite(local);
  this->Offered.assign(this->Have.size(), 0);
  this->Choices = 0;
}

void BlockSolver::TallySite(std::int64_t local)
{
  const auto i = ToIndex(local);
  if (!this->Own[i])
    return;
  const int now = this->Cat.Count(local) == 1
    ? this->Budget->Position(this->Cat.Single(local), this->Own[i] - 1)
    : -2;
  int& was = this->Tally[i];
  if (now == was)
    return;
  if (was >= 0)
    --this->Have[ToIndex(was)];
  if (was == -2)
    --this->Left;
  if (now >= 0)
    ++this->Have[ToIndex(now)];
  if (now == -2)
    ++this->Left;
  was = now;
}

void BlockSolver::SyncCounts()
{
  const std::vector<std::int64_t>& changed = this->Cat.Changed();
  if (this->ChangedSeen > changed.size())
    this->ChangedSeen = 0; // cleared since
  for (std::size_t i = this->ChangedSeen; i < changed.size(); ++i)
    this->TallySite(changed[i]);
  this->ChangedSeen = changed.size();
}

void BlockSolver::CountedWeights(std::int64_t local, std::vector<double>& weight)
{
  const int words = this->Rules.Words();
  const std::uint64_t* domain = this->Cat.Domain(local);
  const std::int64_t cell = this->HasGuide() ? this->GuideCellOfLocal(local) : 0;
  weight.assign(ToIndex(this->Rules.NumberOfLabels()), 0.0);
  double sum = 0.0;
  if (this->Options.Choice == LabelChoice::Resemblance)
  {
    this->ResemblanceWeights(local, this->ChoiceWeights);
    ForEachLabel(domain, words,
      [&](int b)
      {
        const auto i = ToIndex(b);
        weight[i] = this->ChoiceWeights[i] * (this->HasGuide() ? this->GuideWeight(cell, b) : 1.0);
        sum += weight[i];
        return true;
      });
  }
  if (!(sum > 0.0))
    ForEachLabel(domain, words,
      [&](int b)
      {
        weight[ToIndex(b)] = this->SiteWeight(cell, b);
        return true;
      });
  // A network repair's steering (BiasWeights, ScaleWeights) multiplies the weights, as in
  // ChooseLabel.
  if (this->Bias || this->Scale)
  {
    const Coord c = this->Cat.Coordinates(local);
    const Coord& o = this->Cat.Origin();
    const std::int64_t site = this->Index({ { o[0] + c[0], o[1] + c[1], o[2] + c[2] } });
    ForEachLabel(domain, words,
      [&](int b)
      {
        double& w = weight[ToIndex(b)];
        w *= (this->Bias ? (*this->Bias)(site, b) : 1.0) *
          (this->Scale ? (*this->Scale)[ToIndex(b)] : 1.0);
        return true;
      });
  }
}

int BlockSolver::ChooseCounted(std::int64_t local, Random& rng)
{
  const int words = this->Rules.Words();
  const std::uint64_t* domain = this->Cat.Domain(local);
  const std::int32_t slot = this->Own[ToIndex(local)] - 1;
  this->SyncCounts();
  std::vector<double>& weight = this->Steer;
  this->CountedWeights(local, weight);
  // Each counted label's probability is moved into [need, room] / (own sites left where it may
  // go): up to the
  // rate that reaches its minimum (a quarter faster), down to
  // the rate that keeps its maximum, and to 0 once the maximum is reached. Have and Left count
  // the sites propagation decided too (SyncCounts).
  const double left = static_cast<double>(std::max<std::int64_t>(1, this->Left));
  ++this->Choices;
  const std::vector<int>& labels = this->Budget->Labels();
  for (std::size_t c = 0; c < labels.size(); ++c)
  {
    // The count's labels in the domain move together: their summed weight is scaled.
    double mine = 0.0, total = 0.0;
    ForEachLabel(domain, words,
      [&](int a)
      {
        const double w = weight[ToIndex(a)];
        total += w;
        if (this->Budget->Position(a, slot) == static_cast<int>(c))
          mine += w;
        return true;
      });
    bool present = false;
    ForEachLabel(domain, words,
      [&](int a)
      {
        present |= this->Budget->Position(a, slot) == static_cast<int>(c);
        return !present;
      });
    if (!present)
      continue;
    // The own sites left where the count's labels may still go, estimated from the share of
    // this attempt's choices that offered them.
    ++this->Offered[c];
    const double open =
      left * static_cast<double>(this->Offered[c]) / static_cast<double>(this->Choices);
    const std::int64_t need = this->ShareMinimum(c) - this->Have[c];
    const std::int64_t room = this->ShareMaximum(c) - this->Have[c];
    const double others = total - mine;
    const double share = total > 0.0 ? mine / total : 0.0;
    const auto scale = [&](double factor, double otherwise)
    {
      ForEachLabel(domain, words,
        [&](int a)
        {
          double& w = weight[ToIndex(a)];
          w = this->Budget->Position(a, slot) == static_cast<int>(c)
            ? (mine > 0.0 ? w * factor : factor)
            : w * otherwise;
          return true;
        });
    };
    if (room <= 0)
    {
      if (this->CountsOfModel && mine > 0.0 && !this->LimitedNow)
      {
        this->LimitedNow = true; // a repair box wanted more of the count's labels
        ++this->Limits;
      }
      scale(0.0, 1.0);
      continue;
    }
    if (this->CountsOfModel && this->Bias)
      continue; // a repair box steered along a gap: its bias keeps the rest, CountsKept checks
    const double low = 1.25 * static_cast<double>(need) / open;
    const double high = static_cast<double>(room) / open;
    const double target = share < low ? low : (share > high ? high : share);
    if (target >= 1.0 || !(others > 0.0))
      scale(1.0, 0.0); // only the count's labels
    else if (target != share)
    {
      const double wanted = target * others / (1.0 - target);
      scale(mine > 0.0 ? wanted / mine : wanted, 1.0);
    }
  }
  return DrawLabel(
    domain, words, [&](int b) { return weight[ToIndex(b)]; }, rng.Uniform());
}

std::int64_t BlockSolver::ShareMinimum(std::size_t c) const
{
  return this->CountsOfModel ? this->BoxMin[c] : this->Budget->Minimum(this->OwnBlock, c);
}

std::int64_t BlockSolver::ShareMaximum(std::size_t c) const
{
  return this->CountsOfModel ? this->BoxMax[c] : this->Budget->Maximum(this->OwnBlock, c);
}

bool BlockSolver::CountsKept(const Block& block)
{
  const Catalog& cat = this->Cat;
  const Coord& o = block.Origin;
  const std::size_t counted = this->Budget->Labels().size();
  std::vector<std::int64_t> own(counted, 0);
  std::map<std::int64_t, std::vector<std::int64_t>> others; // repairing: change per owner
  for (std::int64_t local = 0; local < cat.NumberOfSites(); ++local)
  {
    const Coord c = cat.Coordinates(local);
    const auto s = ToIndex(this->Index({ { o[0] + c[0], o[1] + c[1], o[2] + c[2] } }));
    const std::int32_t slot = this->Budget->Slot(s);
    const int now = this->Budget->Position(cat.Single(local), slot);
    const std::int64_t owner = this->Budget->Owner(s);
    if (owner == block.Index || this->CountsOfModel) // a network repair's box: all its own
    {
      if (now >= 0)
        ++own[ToIndex(now)];
      continue;
    }
    if (!this->Repairing)
      continue; // a later block of the run owns the site and will write it
    const int was = this->Model[s] >= 0 ? this->Budget->Position(this->Model[s], slot) : -1;
    if (now == was)
      continue;
    auto& change = others[owner];
    change.resize(counted, 0);
    if (now >= 0)
      ++change[ToIndex(now)];
    if (was >= 0)
      --change[ToIndex(was)];
  }
  bool kept = true;
  for (std::size_t c = 0; c < counted; ++c)
    kept = kept && own[c] >= this->ShareMinimum(c) && own[c] <= this->ShareMaximum(c);
  for (const auto& kv : others)
    kept = kept &&
      std::all_of(kv.second.begin(), kv.second.end(), [](std::int64_t d) { return d == 0; });
  if (!kept)
    ++this->Misses;
  return kept;
}

} // namespace detail
} // namespace msynth
