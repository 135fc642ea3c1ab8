// SPDX-License-Identifier: BSD-3-Clause
#include "Discrete/BlockSolver.h"

// The start of Algorithm 3.4 (lines 3-5): a consistent model the blocks then modify. The
// dissertation fills the model with one trivial label adjacent to itself along every axis. Where
// no such label may lie everywhere (a ground row that only one label may hold, a guide, an image
// sample whose patterns all differ from row to row), the start is layered instead: one label per
// layer along an axis, each adjacent to itself along the other axes, consecutive layers allowed
// in order (and the last before the first where the output repeats along that axis).

#include "Core/Error.h"
#include "Core/Index.h"

#include <algorithm>
#include <map>

namespace msynth
{
namespace detail
{
namespace
{
bool Has(const std::uint64_t* set, int b)
{
  return (set[b / 64] >> (b % 64)) & 1u;
}
} // namespace

/// The labels site @p s may hold in any model: its boundary label, else those the guide and
/// the symmetry's unary constraints allow there.
void BlockSolver::SiteMask(std::size_t s, std::uint64_t* out) const
{
  const int words = this->Rules.Words();
  const int k = this->Rules.NumberOfLabels();
  std::fill(out, out + words, std::uint64_t(0));
  if (this->Fixed[s] >= 0)
  {
    out[this->Fixed[s] / 64] |= std::uint64_t(1) << (this->Fixed[s] % 64);
    return;
  }
  for (int b = 0; b < k; ++b)
    out[b / 64] |= std::uint64_t(1) << (b % 64);
  if (this->HasGuide())
  {
    const std::uint64_t* g = this->GuideMasks.data() +
      ToIndex(this->GuideCell(this->Coordinates(static_cast<std::int64_t>(s)))) * ToIndex(words);
    for (int w = 0; w < words; ++w)
      out[w] &= g[w];
  }
  if (this->Seams && this->Seams->HasMasks())
  {
    const std::uint64_t* m = this->Seams->SiteMasks.data() + s * ToIndex(words);
    for (int w = 0; w < words; ++w)
      out[w] &= m[w];
  }
}

/// Per layer along @p axis, the labels every site of the layer may hold that are adjacent to
/// themselves along the other axes of the output.
std::vector<std::uint64_t> BlockSolver::LayerMasks(int axis) const
{
  const int words = this->Rules.Words();
  const int k = this->Rules.NumberOfLabels();
  std::vector<std::uint64_t> layers(ToIndex(this->N[axis] * words), ~0ull);
  std::vector<std::uint64_t> site(ToIndex(words));
  for (std::size_t s = 0; s < this->Model.size(); ++s)
  {
    this->SiteMask(s, site.data());
    const Coord p = this->Coordinates(static_cast<std::int64_t>(s));
    std::uint64_t* layer = layers.data() + p[axis] * words;
    for (int w = 0; w < words; ++w)
      layer[w] &= site[ToIndex(w)];
  }
  for (int b = 0; b < k; ++b)
  {
    bool selfAdjacent = true;
    for (int a = 0; a < 3; ++a)
      if (a != axis && this->N[a] > 1 && !this->Rules.Allowed(2 * a, b, b))
        selfAdjacent = false;
    if (!selfAdjacent)
      for (std::int64_t i = 0; i < this->N[axis]; ++i)
        layers[ToIndex(i * words + b / 64)] &= ~(std::uint64_t(1) << (b % 64));
  }
  return layers;
}

/// A layered start along @p axis (one label per layer), or an empty vector when there is none.
/// Among the choices it keeps a layer's label for the next layer where it can, so the start
/// changes as few times as the constraints need.
std::vector<int> BlockSolver::LayeredStart(int axis) const
{
  const int words = this->Rules.Words();
  const std::int64_t n = this->N[axis];
  const std::vector<std::uint64_t> allowed = this->LayerMasks(axis);
  const bool wrap = this->Seams && this->Seams->Period[ToIndex(axis)] > 0;
  const int forward = 2 * axis;
  std::vector<std::uint64_t> reach(allowed.size(), 0), next(ToIndex(words));
  // Candidate labels of the first layer: all of them, or one at a time when the last layer
  // must come back to it.
  std::vector<int> firsts;
  for (int b = 0; b < this->Rules.NumberOfLabels(); ++b)
    if (Has(allowed.data(), b))
      firsts.push_back(b);
  if (!wrap)
    firsts.assign(1, -1);
  for (const int first : firsts)
  {
    std::fill(reach.begin(), reach.end(), 0);
    if (first < 0)
      std::copy(allowed.begin(), allowed.begin() + words, reach.begin());
    else
      reach[ToIndex(first / 64)] = std::uint64_t(1) << (first % 64);
    bool empty = false;
    for (std::int64_t i = 1; i < n && !empty; ++i)
    {
      this->Rules.UnionOf(forward, reach.data() + (i - 1) * words, next.data());
      empty = true;
      for (int w = 0; w < words; ++w)
      {
        const auto j = ToIndex(i * words + w);
        reach[j] = next[ToIndex(w)] & allowed[j];
        empty = empty && reach[j] == 0;
      }
    }
    if (empty)
      continue;
    // Back from the last layer: a label reached there (that leads back to the first), then in
    // each earlier layer one allowed before the next, the same label where possible.
    std::vector<int> layers(ToIndex(n), -1);
    const std::uint64_t* last = reach.data() + (n - 1) * words;
    for (int b = 0; b < this->Rules.NumberOfLabels() && layers.back() < 0; ++b)
      if (Has(last, b) && (first < 0 || this->Rules.Allowed(forward, b, first)))
        layers.back() = b;
    if (layers.back() < 0)
      continue;
    for (std::int64_t i = n - 2; i >= 0; --i)
    {
      const int above = layers[ToIndex(i + 1)];
      const std::uint64_t* here = reach.data() + i * words;
      int pick = Has(here, above) && this->Rules.Allowed(forward, above, above) ? above : -1;
      for (int b = 0; b < this->Rules.NumberOfLabels() && pick < 0; ++b)
        if (Has(here, b) && this->Rules.Allowed(forward, b, above))
          pick = b;
      layers[ToIndex(i)] = pick;
    }
    return layers;
  }
  return {};
}

/// The trivial start of Algorithm 3.4 (lines 3-5), checked for consistency. Returns the label
/// most sites start with.
int BlockSolver::TrivialStart()
{
  int t = -1;
  std::vector<int> layers;
  int layerAxis = -1;
  if (this->Options.Start)
    return this->GivenStart(*this->Options.Start);
  if (this->Options.TrivialLabel)
  {
    t = this->LabelIndex(*this->Options.TrivialLabel, "trivial");
    if (!this->Rules.SelfAdjacent(t, this->N))
    {
      throw Error("the trivial label " + std::to_string(*this->Options.TrivialLabel) +
        " is not adjacent to itself along every axis of the output, so a model of only that "
        "label is not consistent");
    }
  }
  else
  {
    // A label every free site may hold, else layers (not for mirrored halves, whose mirror
    // planes constrain single labels).
    std::vector<std::uint64_t> everywhere(ToIndex(this->Rules.Words()), ~0ull);
    std::vector<std::uint64_t> site(everywhere.size());
    for (std::size_t s = 0; s < this->Model.size(); ++s)
      if (this->Fixed[s] < 0)
      {
        this->SiteMask(s, site.data());
        for (std::size_t w = 0; w < site.size(); ++w)
          everywhere[w] &= site[w];
      }
    t = ChooseTrivialLabel(this->Rules.NumberOfLabels(), this->Rules.IndexOf(0),
      [&](int b) { return Has(everywhere.data(), b) && this->Rules.SelfAdjacent(b, this->N); });
    for (int a = 2; t < 0 && !this->Plan && a >= 0 && layers.empty(); --a)
      if (this->N[a] > 1)
      {
        layers = this->LayeredStart(a);
        layerAxis = a;
      }
    if (t < 0 && layers.empty())
    {
      t = ChooseTrivialLabel(this->Rules.NumberOfLabels(), this->Rules.IndexOf(0),
        [this](int b) { return this->Rules.SelfAdjacent(b, this->N); });
      if (t < 0)
        throw Error("the example has no usable trivial start for block synthesis: no label is "
                    "adjacent to itself along every axis (usually the empty label is), and no "
                    "layers of such labels fit the boundary, guide and symmetry. Use "
                    "whole-model synthesis (a block as large as the output) instead");
    }
  }
  std::map<int, std::int64_t> counts;
  for (std::size_t s = 0; s < this->Model.size(); ++s)
  {
    if (this->Fixed[s] >= 0)
      continue;
    this->Model[s] = layers.empty()
      ? t
      : layers[ToIndex(this->Coordinates(static_cast<std::int64_t>(s))[ToIndex(layerAxis)])];
    ++counts[this->Model[s]];
  }
  if (!layers.empty())
    t = std::max_element(counts.begin(), counts.end(),
      [](const auto& a, const auto& b) {
        return a.second < b.second;
      })->first;
  this->CheckStart(t,
    layers.empty() ? std::string("a model of label ")
                   : "a model layered along " + std::string("xyz").substr(ToIndex(layerAxis), 1) +
        " starting with label ");
  return t;
}

/// SynthesisOptions::Start, checked like a trivial one. Returns its commonest label.
int BlockSolver::GivenStart(const LabelGrid& start)
{
  if (this->Plan || (this->Seams && this->Seams->Rotate))
    throw Error("a start model cannot be combined with mirror or rotation symmetry");
  if (start.Dimensions() != this->N)
    throw Error("the start model has " + Format(start.Dimensions()) + " sites, the output " +
      Format(this->N));
  std::map<int, std::int64_t> counts;
  for (std::size_t s = 0; s < this->Model.size(); ++s)
  {
    if (this->Fixed[s] >= 0)
      continue;
    this->Model[s] = this->LabelIndex(start.Data()[s], "start");
    ++counts[this->Model[s]];
  }
  const int t = counts.empty() ? this->Model.front()
                               : std::max_element(counts.begin(), counts.end(),
                                   [](const auto& a, const auto& b) { return a.second < b.second; })
                                   ->first;
  this->CheckStart(t, "the start model, mostly label ");
  return t;
}

/// The start must satisfy the mirror planes, the guide, Eq. 3.3 and the symmetry's seams.
void BlockSolver::CheckStart(int t, const std::string& what) const
{
  const auto& v = this->Rules.LabelValues();
  const std::string start = what + std::to_string(v[ToIndex(t)]);
  // With symmetry, the trivial label must be allowed on the mirror planes.
  if (this->Plan)
    for (int a = 0; a < 3; ++a)
      if (this->Plan->Axes[ToIndex(a)] && !Has(this->Plan->ColumnMask[ToIndex(a)].data(), t))
        throw Error("the trivial label " + std::to_string(v[ToIndex(t)]) +
          " cannot lie next to its own mirror image along " +
          std::string("xyz").substr(ToIndex(a), 1));
  // A failed block keeps the start's labels, so the guide may not forbid them.
  if (this->HasGuide())
    for (std::size_t s = 0; s < this->Model.size(); ++s)
    {
      const Coord p = this->Coordinates(static_cast<std::int64_t>(s));
      const int b = this->Model[s];
      if (this->Fixed[s] < 0 && this->GuideWeight(this->GuideCell(p), b) == 0.0f)
        throw Error("the guide gives the trivial label " + std::to_string(v[ToIndex(b)]) +
          " weight 0 at " + Format(p) +
          ", but block synthesis falls back to it where a "
          "block fails. Allow that label everywhere, or use whole-model synthesis");
    }
  // The start must satisfy Eq. 3.3, boundary labels included.
  this->ForEachAdjacentPair(
    [&](const Coord& p, const Coord& q, int axis)
    {
      const int b = this->Model[ToIndex(this->Index(p))];
      const int c = this->Model[ToIndex(this->Index(q))];
      if (!this->Rules.Allowed(2 * axis, b, c))
        throw Error("no usable trivial start: " + start + " with the boundary labels puts label " +
          std::to_string(v[ToIndex(b)]) + " before " + std::to_string(v[ToIndex(c)]) + " along " +
          std::string("xyz").substr(ToIndex(axis), 1) + " at " + Format(p) +
          ", which the example never does");
    });
  if (this->Seams)
    this->CheckStartAgainstSeams(start);
}

/// The trivial start must also satisfy the symmetry's seams and unary constraints.
void BlockSolver::CheckStartAgainstSeams(const std::string& start) const
{
  const SiteArcs& arcs = this->Seams->Arcs;
  const int words = this->Rules.Words();
  for (std::size_t s = 0; s < this->Model.size(); ++s)
  {
    const int b = this->Model[s];
    const std::uint64_t* mask =
      this->Seams->HasMasks() ? this->Seams->SiteMasks.data() + s * ToIndex(words) : nullptr;
    bool ok = !mask || Has(mask, b);
    for (std::int64_t i = arcs.Start[s]; ok && i < arcs.Start[s + 1]; ++i)
      ok = this->Seams->Relation->Allowed(
        arcs.Class[ToIndex(i)], b, this->Model[ToIndex(arcs.Target[ToIndex(i)])]);
    if (!ok)
      throw Error("no usable trivial start: " + start +
        " (with the boundary labels) does not meet its own symmetric copies at " +
        Format(this->Coordinates(static_cast<std::int64_t>(s))) +
        "; the trivial label must be its own image under the symmetry's label map");
  }
}

} // namespace detail
} // namespace msynth
