// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file SeamMeasure.cxx
 * @brief Window statistics along block borders (SeamMeasure.h): windows counted with ordered
 * containers over label values, sharing nothing with the solver but the block lattice.
 */
#include "Discrete/SeamMeasure.h"

#include "Core/BlockDriver.h"
#include "Core/BlockSynthesis.h"
#include "Core/Error.h"
#include "Core/Index.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <string>

namespace msynth
{
namespace
{
using Histogram = std::map<std::vector<Label>, std::int64_t>;

/// ½ Σ |p(c) − q(c)| of two histograms' frequencies (0 when either is empty).
double Distance(const Histogram& p, const Histogram& q)
{
  std::int64_t np = 0, nq = 0;
  for (const auto& c : p)
    np += c.second;
  for (const auto& c : q)
    nq += c.second;
  if (np == 0 || nq == 0)
    return 0.0;
  double sum = 0.0;
  for (const auto& c : p)
  {
    const auto other = q.find(c.first);
    const double f =
      other == q.end() ? 0.0 : static_cast<double>(other->second) / static_cast<double>(nq);
    sum += std::fabs(static_cast<double>(c.second) / static_cast<double>(np) - f);
  }
  for (const auto& c : q)
    if (p.find(c.first) == p.end())
      sum += static_cast<double>(c.second) / static_cast<double>(nq);
  return 0.5 * sum;
}

/// The share of @p h's most frequent configuration (0 when empty).
double TopShare(const Histogram& h)
{
  std::int64_t total = 0, most = 0;
  for (const auto& c : h)
  {
    total += c.second;
    most = std::max(most, c.second);
  }
  return total > 0 ? static_cast<double>(most) / static_cast<double>(total) : 0.0;
}

/// Whether a window over sites [@p lo, @p lo + @p w) holds a site on either side of a plane.
bool Touches(const std::vector<std::int64_t>& planes, std::int64_t lo, std::int64_t w)
{
  for (std::int64_t p : planes)
    if (lo <= p && p - 1 <= lo + w - 1)
      return true;
  return false;
}

/// The window of @p grid at @p anchor, @p w[a] sites along each axis.
std::vector<Label> WindowAt(const LabelGrid& grid, const std::array<std::int64_t, 3>& anchor,
  const std::array<std::int64_t, 3>& w)
{
  std::vector<Label> c;
  c.reserve(ToIndex(w[0] * w[1] * w[2]));
  for (std::int64_t z = 0; z < w[2]; ++z)
    for (std::int64_t y = 0; y < w[1]; ++y)
      for (std::int64_t x = 0; x < w[0]; ++x)
        c.push_back(grid.At(anchor[0] + x, anchor[1] + y, anchor[2] + z));
  return c;
}
} // namespace

std::array<std::vector<std::int64_t>, 3> BlockBorderPlanes(const std::array<std::int64_t, 3>& size,
  const std::array<std::int64_t, 3>& block, const std::array<std::int64_t, 3>& overlap)
{
  std::array<std::int64_t, 3> m{}, step{};
  BlockGeometry<3>(size, block, overlap, m, step);
  std::array<std::vector<std::int64_t>, 3> planes;
  for (std::size_t a = 0; a < 3; ++a)
  {
    if (m[a] >= size[a])
      continue;
    for (std::int64_t o : BlockStarts(size[a], m[a], step[a]))
      for (std::int64_t p : { o, o + m[a] })
        if (p > 0 && p < size[a])
          planes[a].push_back(p);
    std::sort(planes[a].begin(), planes[a].end());
    planes[a].erase(std::unique(planes[a].begin(), planes[a].end()), planes[a].end());
  }
  return planes;
}

SeamMeasure MeasureSeams(const LabelGrid& model,
  const std::array<std::vector<std::int64_t>, 3>& planes, int window, const LabelGrid* whole)
{
  const auto& n = model.Dimensions();
  std::array<std::int64_t, 3> w{};
  for (std::size_t a = 0; a < 3; ++a)
  {
    w[a] = n[a] == 1 ? 1 : window;
    if (window < 1 || w[a] > n[a])
      throw Error("a seam window of " + std::to_string(window) +
        " sites per axis does not fit in the model (" + std::to_string(n[0]) + " x " +
        std::to_string(n[1]) + " x " + std::to_string(n[2]) + ")");
  }
  if (whole && whole->Dimensions() != n)
    throw Error("the whole run to compare seams with is " + std::to_string(whole->Size(0)) + " x " +
      std::to_string(whole->Size(1)) + " x " + std::to_string(whole->Size(2)) +
      ", not the model's size");
  Histogram border, interior, wholeBorder, wholeInterior, wholeAll;
  std::array<std::int64_t, 3> at{};
  for (at[2] = 0; at[2] + w[2] <= n[2]; ++at[2])
    for (at[1] = 0; at[1] + w[1] <= n[1]; ++at[1])
      for (at[0] = 0; at[0] + w[0] <= n[0]; ++at[0])
      {
        bool touches = false;
        for (std::size_t a = 0; a < 3; ++a)
          touches = touches || Touches(planes[a], at[a], w[a]);
        ++(touches ? border : interior)[WindowAt(model, at, w)];
        if (!whole)
          continue;
        const std::vector<Label> c = WindowAt(*whole, at, w);
        ++wholeAll[c];
        ++(touches ? wholeBorder : wholeInterior)[c];
      }
  SeamMeasure s;
  s.Window = window;
  for (const auto& c : border)
    s.BorderWindows += c.second;
  for (const auto& c : interior)
    s.InteriorWindows += c.second;
  s.BorderVsInterior = Distance(border, interior);
  s.BorderTop = TopShare(border);
  s.InteriorTop = TopShare(interior);
  if (whole)
  {
    s.HasWhole = true;
    s.WholeBorderVsInterior = Distance(wholeBorder, wholeInterior);
    s.BorderVsWhole = Distance(border, wholeAll);
    s.InteriorVsWhole = Distance(interior, wholeAll);
    s.WholeBorderTop = TopShare(wholeBorder);
  }
  return s;
}

} // namespace msynth
