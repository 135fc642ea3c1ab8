// SPDX-License-Identifier: BSD-3-Clause
// Proportions that hold below the level of a part (issue 29): where emptying whole parts cannot
// bring the object types' shares within the tolerance, blocks of the model are synthesized again
// (the rest fixed) and a redraw is kept when it brings the shares nearer the targets.
#include "Continuous/ConstraintPlan.h"
#include "Core/Index.h"

#include <algorithm>
#include <utility>

namespace msynth
{
namespace detail
{

namespace
{
/// Whether @p a is nearer the targets than @p b: the largest relative deviation, then the sum.
bool Nearer(const ConstraintPlan::Proportioned& a, const ConstraintPlan::Proportioned& b)
{
  return a.Worst < b.Worst - 1e-12 || (a.Worst <= b.Worst + 1e-12 && a.Sum < b.Sum - 1e-12);
}
} // namespace

ConstraintPlan::Redrawn ConstraintPlan::RedrawForProportions(std::vector<std::int32_t>& labels,
  int emptyLabel, unsigned threads, const BlockRedraw& blocks) const
{
  Redrawn out;
  if (!this->Proportions || !this->GuideWeights.empty() || blocks.Blocks < 2)
    return out;
  // The shares the emptying of whole parts would leave (on a copy: the model keeps its parts).
  std::vector<std::int32_t> scratch;
  const auto assess = [&]()
  {
    scratch = labels;
    return this->KeepProportionateParts(scratch, emptyLabel, threads);
  };
  Proportioned now = assess();
  if (now.Worst <= ProportionTolerance)
    return out; // emptying parts suffices: the model is left as it is
  const std::size_t nt = this->Types.size();
  std::vector<std::int32_t> kept;
  std::vector<std::pair<double, std::int64_t>> rank;
  for (std::uint64_t round = 0; now.Worst > RedrawTarget && out.Tried < RedrawBudget; ++round)
  {
    // The type furthest above its target, and the blocks holding most of it (ties: the first).
    int excess = -1;
    double most = 0;
    for (std::size_t t = 1; t < nt && t < now.Shares.size(); ++t)
    {
      const double target = this->Target[t];
      const double above = target > 0 ? now.Shares[t] / target - 1 : now.Shares[t];
      if (above > most)
      {
        most = above;
        excess = static_cast<int>(t);
      }
    }
    if (excess < 0)
      break;
    rank.clear();
    for (std::int64_t b = 0; b < blocks.Blocks; ++b)
    {
      double held = 0;
      for (const std::int64_t v : blocks.Vertices(b))
        held += this->Occupancy(labels[ToIndex(v)], excess);
      if (held > 0)
        rank.emplace_back(-held, b);
    }
    std::sort(rank.begin(), rank.end());
    bool better = false;
    for (std::size_t k = 0; k < rank.size() && k < ToIndex(RedrawBlocks) && !better; ++k)
    {
      for (std::uint64_t attempt = 0; attempt < 2 && !better && out.Tried < RedrawBudget; ++attempt)
      {
        if (blocks.Stopped())
          return out;
        ++out.Tried;
        kept = labels;
        const std::int64_t b = rank[k].second;
        const std::uint64_t place =
          round * static_cast<std::uint64_t>(blocks.Blocks) + static_cast<std::uint64_t>(b);
        if (!blocks.Redraw(b, place * 2 + attempt))
          continue;
        const std::array<std::int64_t, 3> emptied = blocks.Clean();
        const Proportioned trial = assess();
        if (Nearer(trial, now))
        {
          now = trial;
          better = true;
          ++out.Blocks;
          for (std::size_t i = 0; i < emptied.size(); ++i)
            out.Parts[i] += emptied[i];
        }
        else
        {
          labels.swap(kept);
        }
      }
    }
    if (!better)
      break;
  }
  return out;
}

} // namespace detail
} // namespace msynth
