// SPDX-License-Identifier: BSD-3-Clause
#include "Core/Index.h"
#include "Discrete/BlockSolver.h"

// One block attempt's assignments with bounded chronological backtracking (BlockSolver.h).

namespace msynth
{
namespace detail
{

BlockSearch::BlockSearch(
  BlockSolver& solver, const Block& block, Random& rng, std::int64_t& assignments)
  : Solver(solver)
  , Current(block)
  , Rng(rng)
  , Assignments(assignments)
  , Others(ToIndex(solver.Rules.Words()))
  , Budget(solver.Options.BacktracksPerAttempt)
  , Searching(solver.Options.BacktracksPerAttempt > 0)
{
  this->Solver.Cat.Record(this->Searching);
}

BlockSearch::~BlockSearch()
{
  this->Solver.Cat.Record(false);
}

std::int64_t BlockSearch::Assign(std::int64_t local)
{
  Catalog& cat = this->Solver.Cat;
  this->ResumeAt = -1;
  if (cat.Count(local) == 0)
    return local;
  if (this->Solver.Poll(this->Assignments))
    return local; // cancelled: the attempt ends here (and no other starts)
  if (cat.Count(local) == 1)
    return -1;
  ++this->Assignments;
  std::size_t mark = cat.Mark();
  int label = this->Solver.ChooseLabel(local, this->Rng);
  cat.Assign(local, label);
  std::int64_t empty = cat.Propagate();
  if (empty < 0)
  {
    if (this->Searching && cat.TrailWords() > MaximumTrailWords)
    {
      // Too long a trail to keep: go on as Algorithm 3.4 does, without undoing.
      this->Searching = false;
      this->Stack.clear();
      cat.Record(false);
    }
    if (this->Searching)
    {
      this->Stack.push_back({ local, label, mark });
      this->Trim();
    }
    this->Solver.MaybeCapture(this->Current, this->Assignments);
    return -1;
  }
  while (this->Searching && this->Budget > 0)
  {
    --this->Budget;
    ++this->Solver.Backtracked;
    cat.Undo(mark);
    std::fill(this->Others.begin(), this->Others.end(), ~std::uint64_t(0));
    this->Others[ToIndex(label >> 6)] &= ~(std::uint64_t(1) << (label & 63));
    cat.Keep(local, this->Others.data());
    empty = cat.Propagate();
    if (empty < 0)
    {
      this->ResumeAt = local;
      return -1;
    }
    if (this->Stack.empty())
      break;
    const Decision d = this->Stack.back();
    this->Stack.pop_back();
    local = d.Local;
    label = d.Label;
    mark = d.Mark;
  }
  return empty;
}

void BlockSearch::Trim()
{
  // Each undo spends one unit of the budget, so no undo reaches further back than the last
  // Budget choices: older choices and their trail can go (amortized: when twice as many).
  const std::size_t keep = ToIndex(this->Budget) + 1;
  if (this->Stack.size() < 2 * keep + 1024)
    return;
  this->Stack.erase(this->Stack.begin(), this->Stack.end() - static_cast<std::ptrdiff_t>(keep));
  this->Solver.Cat.Forget(this->Stack.front().Mark);
}

} // namespace detail
} // namespace msynth
