// SPDX-License-Identifier: BSD-3-Clause
// Proportions that hold below the level of a part (issue 29): where emptying whole parts cannot
// bring the object types' shares within the tolerance, or would leave most of the box bare,
// blocks of the model are synthesized again (the rest fixed) and a redraw is kept when it brings
// the shares nearer the targets, or keeps more solid in proportion.
#include "Continuous/ConstraintPlan.h"
#include "Core/Index.h"

#include <algorithm>
#include <limits>
#include <utility>

namespace msynth
{
namespace detail
{

namespace
{
using Proportioned = ConstraintPlan::Proportioned;

/// Whether @p a is nearer the targets than @p b: the largest relative deviation, then the sum.
bool Nearer(const Proportioned& a, const Proportioned& b)
{
  return a.Worst < b.Worst - 1e-12 || (a.Worst <= b.Worst + 1e-12 && a.Sum < b.Sum - 1e-12);
}

/// The rounds of redraws of one run: the model, the shares its emptying would leave, the tally.
struct RedrawRun
{
  const ConstraintPlan& Plan;
  std::vector<std::int32_t>& Labels;
  const int EmptyLabel;
  const unsigned Threads;
  const ConstraintPlan::BlockRedraw& Blocks;
  ConstraintPlan::Redrawn Out;
  Proportioned Now;
  std::vector<std::int32_t> Scratch, Kept;
  std::vector<std::pair<double, std::int64_t>> Ranked;

  /// The shares the emptying of whole parts would leave (on a copy: the model keeps its parts).
  Proportioned Assess()
  {
    this->Scratch = this->Labels;
    return this->Plan.KeepProportionateParts(this->Scratch, this->EmptyLabel, this->Threads);
  }

  /// Redraws the blocks @p group (generator keys @p key(b)) and keeps them when
  /// @p better(trial, now), else restores the model.
  template <typename Key, typename Better>
  bool Try(const std::vector<std::int64_t>& group, const Key& key, const Better& better)
  {
    ++this->Out.Tried;
    this->Kept = this->Labels;
    std::int64_t redrawn = 0;
    for (const std::int64_t b : group)
      redrawn += this->Blocks.Redraw(b, key(b)) ? 1 : 0;
    if (redrawn == 0)
      return false;
    const std::array<std::int64_t, 3> emptied = this->Blocks.Clean();
    const Proportioned trial = this->Assess();
    if (!better(trial, this->Now))
    {
      this->Labels.swap(this->Kept);
      return false;
    }
    this->Now = trial;
    this->Out.Blocks += redrawn;
    for (std::size_t i = 0; i < emptied.size(); ++i)
      this->Out.Parts[i] += emptied[i];
    return true;
  }

  /// Rounds over the blocks ranked by @p rank (smaller first, ties: the first block; a block
  /// ranked at infinity is not tried) while @p go, each round ending at its first kept redraw.
  /// A redraw is of one block, or in a model of many blocks of a group of the next ranked ones
  /// (ConstraintPlan::RedrawGroup): one block moves a large model's shares too little.
  template <typename Go, typename Rank, typename Better>
  void Rounds(std::uint64_t phase, const Go& go, const Rank& rank, const Better& better)
  {
    const auto blocks = static_cast<std::uint64_t>(this->Blocks.Blocks);
    const std::size_t size = this->Blocks.Blocks < ConstraintPlan::RedrawGroupsFrom
      ? 1
      : ToIndex(this->Blocks.Blocks / ConstraintPlan::RedrawGroup);
    std::vector<std::int64_t> group;
    for (std::uint64_t round = 0; go() && this->Out.Tried < ConstraintPlan::RedrawBudget; ++round)
    {
      this->Ranked.clear();
      for (std::int64_t b = 0; b < this->Blocks.Blocks; ++b)
      {
        const double r = rank(this->Blocks.Vertices(b));
        if (r < std::numeric_limits<double>::infinity())
          this->Ranked.emplace_back(r, b);
      }
      std::sort(this->Ranked.begin(), this->Ranked.end());
      bool done = false;
      for (std::size_t k = 0;
           k * size < this->Ranked.size() && k < ToIndex(ConstraintPlan::RedrawBlocks) && !done;
           ++k)
      {
        group.clear();
        for (std::size_t i = k * size; i < std::min(this->Ranked.size(), (k + 1) * size); ++i)
          group.push_back(this->Ranked[i].second);
        for (std::uint64_t attempt = 0;
             attempt < 2 && !done && this->Out.Tried < ConstraintPlan::RedrawBudget; ++attempt)
        {
          if (this->Blocks.Stopped())
            return;
          const auto key = [&](std::int64_t b)
          {
            const std::uint64_t place = round * blocks + static_cast<std::uint64_t>(b);
            return (phase << 63) | (place * 2 + attempt);
          };
          done = this->Try(group, key, better);
        }
      }
      if (!done)
        return;
    }
  }
};
} // namespace

ConstraintPlan::Redrawn ConstraintPlan::RedrawForProportions(std::vector<std::int32_t>& labels,
  int emptyLabel, unsigned threads, const BlockRedraw& blocks) const
{
  if (!this->Proportions || !this->GuideWeights.empty() || blocks.Blocks < 2)
    return Redrawn();
  RedrawRun run{ *this, labels, emptyLabel, threads, blocks, {}, {}, {}, {}, {} };
  run.Now = run.Assess();
  const std::size_t nt = this->Types.size();
  if (run.Now.Worst > ProportionTolerance)
  {
    // Shares out of reach of the emptying: the blocks holding most of the type furthest above
    // its target are redrawn, kept when the shares left come nearer the targets.
    int excess = -1;
    const auto go = [&]()
    {
      excess = -1;
      double most = 0;
      for (std::size_t t = 1; t < nt && t < run.Now.Shares.size(); ++t)
      {
        const double target = this->Target[t];
        const double above = target > 0 ? run.Now.Shares[t] / target - 1 : run.Now.Shares[t];
        if (above > most)
        {
          most = above;
          excess = static_cast<int>(t);
        }
      }
      return run.Now.Worst > RedrawTarget && excess >= 0;
    };
    const auto holding = [&](const std::vector<std::int64_t>& vertices)
    {
      double held = 0;
      for (const std::int64_t v : vertices)
        held += this->Occupancy(labels[ToIndex(v)], excess);
      return held > 0 ? -held : std::numeric_limits<double>::infinity();
    };
    run.Rounds(0, go, holding, Nearer);
  }
  if (run.Now.Worst <= RedrawTarget)
  {
    // Shares within reach, but the emptying would leave much of the box bare: the blocks holding
    // least solid (on the ground, when grounded) are redrawn, kept when the emptying then keeps
    // more solid with every share still within RedrawTarget.
    const auto bare = [&](const std::vector<std::int64_t>& vertices)
    {
      double held = 0;
      bool ground = !this->Constraints.Grounded;
      for (const std::int64_t v : vertices)
      {
        ground = ground || this->OnGround(v);
        for (std::size_t t = 1; t < nt; ++t)
          held += this->Occupancy(labels[ToIndex(v)], static_cast<int>(t));
      }
      return ground ? held : std::numeric_limits<double>::infinity();
    };
    run.Rounds(
      1, [&]() { return run.Now.VolumeRemoved > RefillAbove; }, bare,
      [](const Proportioned& trial, const Proportioned& now)
      { return trial.Worst <= RedrawTarget && trial.Kept > now.Kept * (1 + 1e-9); });
  }
  return run.Out;
}

} // namespace detail
} // namespace msynth
