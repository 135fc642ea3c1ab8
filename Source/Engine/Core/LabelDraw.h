// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/**
 * @file LabelDraw.h
 * @brief The one label draw of every solver: a candidate chosen with probability proportional
 * to its weight (Algorithm 3.4 line 22's random choice, weighted by frequency, resemblance
 * (M07 Eqs. 4-6), a guide (D§3.5.3) or the continuous constraints (T§4.6)), and the uniform
 * draw of the n-th label of a catalog set.
 */
#include <cstdint>

namespace msynth
{

/// Calls @p visit(label) for each label of the set @p domain (@p words 64-bit words) in index
/// order while it returns true.
template <class Visit>
void ForEachLabel(const std::uint64_t* domain, int words, Visit&& visit)
{
  for (int w = 0; w < words; ++w)
    for (std::uint64_t bits = domain[w]; bits; bits &= bits - 1)
      if (!visit(w * 64 + __builtin_ctzll(bits)))
        return;
}

/// Calls @p visit(i) for i = 0, 1, ..., n - 1 while it returns true.
template <class Visit>
void ForEachIndex(int n, Visit&& visit)
{
  for (int i = 0; i < n; ++i)
    if (!visit(i))
      return;
}

/**
 * One of the candidates that @p each visits (each(visit) calls visit(c) in order while it
 * returns true), drawn with probability proportional to weight(c) from @p u uniform in [0, 1):
 * the candidates are walked subtracting their weights from u · (sum of weights). When rounding
 * leaves a remainder, the last candidate of positive weight (or, with none, the last one) is
 * returned; -1 when there is no candidate.
 */
template <class Each, class Weight>
int DrawWeighted(Each&& each, Weight&& weight, double u)
{
  double total = 0.0;
  each(
    [&](int c)
    {
      total += weight(c);
      return true;
    });
  double r = u * total;
  int chosen = -1, last = -1, lastPositive = -1;
  each(
    [&](int c)
    {
      const double x = weight(c);
      last = c;
      if (x > 0.0)
        lastPositive = c;
      r -= x;
      if (r < 0.0)
      {
        chosen = c;
        return false;
      }
      return true;
    });
  return chosen >= 0 ? chosen : (lastPositive >= 0 ? lastPositive : last);
}

/// A label of the set @p domain drawn with probability proportional to weight(label) from
/// @p u (DrawWeighted over the set's labels in index order); -1 for an empty set.
template <class Weight>
int DrawLabel(const std::uint64_t* domain, int words, Weight&& weight, double u)
{
  return DrawWeighted([&](auto&& visit) { ForEachLabel(domain, words, visit); }, weight, u);
}

/// The label of rank @p r (0-based, in index order) of the set @p domain; -1 when it has fewer.
inline int NthLabel(const std::uint64_t* domain, int words, std::uint64_t r)
{
  int found = -1;
  ForEachLabel(domain, words,
    [&](int b)
    {
      if (r-- != 0)
        return true;
      found = b;
      return false;
    });
  return found;
}

} // namespace msynth
