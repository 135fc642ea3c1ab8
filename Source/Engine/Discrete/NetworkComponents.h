// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/**
 * @file NetworkComponents.h
 * @brief The components of a connected network (internal to Discrete/Connectivity.cxx and
 * Discrete/NetworkRepair.cxx): the flood over face neighbours joined through connecting sides.
 */
#include "Core/Index.h"
#include "Discrete/Connectivity.h"

#include <algorithm>
#include <cstdint>
#include <string>
#include <vector>

namespace msynth
{
namespace detail
{

/// A component of the network found by Flood.
struct Component
{
  std::int64_t Sites = 0;
  bool Open = false;
  Coord Low{ { 0, 0, 0 } }, High{ { 0, 0, 0 } }; ///< bounding box, inclusive
};

/**
 * The components of the network over @p n sites whose label index at site s is label(s);
 * open(s) says whether a later block writes s. Calls @p found for each, in the order of their
 * first site.
 */
template <class LabelFn, class OpenFn, class FoundFn>
void Flood(const NetworkRule& rule, const Coord& n, LabelFn&& label, OpenFn&& open, FoundFn&& found,
  std::vector<std::int32_t>& seen, std::vector<std::int64_t>& stack)
{
  const std::int64_t total = n[0] * n[1] * n[2];
  const std::int64_t stride[3] = { 1, n[0], n[0] * n[1] };
  seen.assign(ToIndex(total), 0);
  std::int32_t number = 0; // seen: the component's number + 1
  for (std::int64_t first = 0; first < total; ++first)
  {
    if (seen[ToIndex(first)] || rule.Sides(label(first)) < 0)
      continue;
    Component c;
    c.Low = { { first % n[0], (first / n[0]) % n[1], first / (n[0] * n[1]) } };
    c.High = c.Low;
    seen[ToIndex(first)] = ++number;
    stack.assign(1, first);
    while (!stack.empty())
    {
      const std::int64_t s = stack.back();
      stack.pop_back();
      ++c.Sites;
      const Coord p{ { s % n[0], (s / n[0]) % n[1], s / (n[0] * n[1]) } };
      for (std::size_t a = 0; a < 3; ++a)
      {
        c.Low[a] = std::min(c.Low[a], p[a]);
        c.High[a] = std::max(c.High[a], p[a]);
      }
      c.Open = c.Open || open(s);
      const int sides = rule.Sides(label(s));
      for (int d = 0; d < 6; ++d)
      {
        const std::size_t a = ToIndex(d / 2);
        const bool up = d % 2 == 0;
        if (!((sides >> d) & 1) || (up ? p[a] + 1 >= n[a] : p[a] == 0))
          continue;
        const std::int64_t q = s + (up ? stride[a] : -stride[a]);
        if (open(q))
          c.Open = true; // the side faces a site still to be written
        const int other = rule.Sides(label(q));
        if (other < 0 || !((other >> (d ^ 1)) & 1) || seen[ToIndex(q)])
          continue;
        seen[ToIndex(q)] = number;
        stack.push_back(q);
      }
    }
    found(c);
  }
}

/**
 * Visits each site of the model (@p n sites) face next to @p box and outside it, as
 * visit(site, toward, inside): toward is the side (bit 2a: toward +a, 2a+1: toward -a) that
 * faces the box, inside the box's site there.
 */
template <class Visit>
void ForEachRingSite(const Block& box, const Coord& n, Visit&& visit)
{
  const std::int64_t stride[3] = { 1, n[0], n[0] * n[1] };
  const Coord& o = box.Origin;
  Coord p;
  for (p[2] = std::max<std::int64_t>(0, o[2] - 1); p[2] < std::min(n[2], o[2] + box.Dims[2] + 1);
       ++p[2])
    for (p[1] = std::max<std::int64_t>(0, o[1] - 1); p[1] < std::min(n[1], o[1] + box.Dims[1] + 1);
         ++p[1])
      for (p[0] = std::max<std::int64_t>(0, o[0] - 1);
           p[0] < std::min(n[0], o[0] + box.Dims[0] + 1); ++p[0])
      {
        int outside = 0, toward = 0;
        for (std::size_t a = 0; a < 3; ++a)
          if (p[a] < o[a] || p[a] >= o[a] + box.Dims[a])
          {
            ++outside;
            toward = 2 * static_cast<int>(a) + (p[a] < o[a] ? 0 : 1);
          }
        if (outside != 1)
          continue; // inside the box, or only next to an edge or corner of it
        const std::int64_t s = p[0] + n[0] * (p[1] + n[1] * p[2]);
        visit(s, toward, s + (toward % 2 == 0 ? 1 : -1) * stride[toward / 2]);
      }
}

/// The components of @p model; @p ids (when given) receives each site's component number + 1
/// (0: not in the network).
std::vector<Component> FindComponents(const NetworkRule& rule,
  const std::vector<std::int32_t>& model, const Coord& n, std::vector<std::int32_t>* ids = nullptr);

/// "the network of LABELS", for messages.
std::string NetworkName(const ConnectedNetwork& network);

} // namespace detail
} // namespace msynth
