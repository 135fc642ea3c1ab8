// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file PeriodCheck.cxx
 * @brief CheckTranslationPeriods (Discrete/DiscreteSynthesis.h): a world that repeats every P
 * sites along an axis needs a row of labels that closes after P steps, a closed walk of length P
 * in the graph of the rules along that axis. A closed walk stays in one strongly connected part,
 * and its length is a multiple of that part's period (the gcd of its cycles' lengths): when no
 * part's period divides P, no model exists (WaveFunctionCollapse's Chess, N = 2, at size 47:
 * its rows alternate, period 2). Said at once, rather than as a catalog emptied in every attempt.
 */
#include "Core/Error.h"
#include "Core/Index.h"
#include "Discrete/DiscreteSynthesis.h"

#include <numeric>
#include <string>
#include <vector>

namespace msynth
{
namespace
{
/// The labels allowed after each label along direction @p d.
std::vector<std::vector<int>> Successors(const AdjacencyRules& rules, int d)
{
  const int k = rules.NumberOfLabels();
  std::vector<std::vector<int>> next(ToIndex(k));
  for (int b = 0; b < k; ++b)
  {
    const std::uint64_t* row = rules.Compatible(d, b);
    for (int w = 0; w < rules.Words(); ++w)
      for (std::uint64_t bits = row[w]; bits; bits &= bits - 1)
      {
        int c = 64 * w;
        for (std::uint64_t low = bits & (~bits + 1); low > 1; low >>= 1)
          ++c;
        if (c < k)
          next[ToIndex(b)].push_back(c);
      }
  }
  return next;
}

/// Strongly connected parts of @p next (Tarjan, iterative): each label's part index.
std::vector<int> Parts(const std::vector<std::vector<int>>& next)
{
  const std::size_t k = next.size();
  std::vector<int> index(k, -1), low(k, 0), part(k, -1), stack;
  std::vector<char> on(k, 0);
  int counter = 0, parts = 0;
  std::vector<std::pair<std::size_t, std::size_t>> call; // (label, next successor)
  for (std::size_t root = 0; root < k; ++root)
  {
    if (index[root] >= 0)
      continue;
    call.emplace_back(root, 0);
    while (!call.empty())
    {
      auto& [v, i] = call.back();
      if (i == 0 && index[v] < 0)
      {
        index[v] = low[v] = counter++;
        stack.push_back(static_cast<int>(v));
        on[v] = 1;
      }
      if (i < next[v].size())
      {
        const std::size_t w = ToIndex(next[v][i++]);
        if (index[w] < 0)
          call.emplace_back(w, 0);
        else if (on[w])
          low[v] = std::min(low[v], index[w]);
        continue;
      }
      if (low[v] == index[v])
      {
        int w;
        do
        {
          w = stack.back();
          stack.pop_back();
          on[ToIndex(w)] = 0;
          part[ToIndex(w)] = parts;
        } while (ToIndex(w) != v);
        ++parts;
      }
      const std::size_t done = v;
      call.pop_back();
      if (!call.empty())
        low[call.back().first] = std::min(low[call.back().first], low[done]);
    }
  }
  return part;
}

/// The periods of the parts of @p next that hold a cycle (gcd of level differences along their
/// inner edges, levels from a breadth-first search inside the part).
std::vector<std::int64_t> Periods(const std::vector<std::vector<int>>& next)
{
  const std::vector<int> part = Parts(next);
  std::vector<std::int64_t> level(next.size(), -1), period;
  for (std::size_t root = 0; root < next.size(); ++root)
  {
    if (level[root] >= 0)
      continue;
    std::int64_t g = 0;
    std::vector<std::size_t> queue{ root };
    level[root] = 0;
    for (std::size_t q = 0; q < queue.size(); ++q)
    {
      const std::size_t v = queue[q];
      for (int c : next[v])
      {
        const std::size_t w = ToIndex(c);
        if (part[w] != part[v])
          continue;
        if (level[w] < 0)
        {
          level[w] = level[v] + 1;
          queue.push_back(w);
        }
        else
          g = std::gcd(g, std::abs(level[v] + 1 - level[w]));
      }
    }
    if (g > 0)
      period.push_back(g);
  }
  return period;
}
} // namespace

void CheckTranslationPeriods(const AdjacencyRules& rules, const SynthesisOptions& options)
{
  static const char* const names[3] = { "x", "y", "z" };
  for (std::size_t a = 0; a < 3; ++a)
  {
    const Translation& t = options.Translate[a];
    const std::int64_t p = t.Period > 0 ? t.Period : options.Size[a];
    if (!t.Enabled || !t.Map.empty() || rules.NumberOfLabels() == 0)
      continue;
    const std::vector<std::int64_t> periods = Periods(Successors(rules, 2 * static_cast<int>(a)));
    std::int64_t least = 0;
    bool fits = periods.empty(); // no cycle at all: the solver says so itself
    for (std::int64_t d : periods)
    {
      fits = fits || p % d == 0;
      least = least == 0 ? d : std::min(least, d);
    }
    if (fits)
      continue;
    const std::string axis = names[a];
    throw Error("the example repeats every " + std::to_string(least) + " sites along " + axis +
      " (its rows along " + axis + " close only after a multiple of " + std::to_string(least) +
      " sites), so a model that repeats every " + std::to_string(p) + " sites along " + axis +
      " cannot exist: use a multiple of " + std::to_string(least) + " (" +
      std::to_string(p + least - p % least) + ") or no --translate " + axis);
  }
}

} // namespace msynth
