// SPDX-License-Identifier: BSD-3-Clause
#include "Discrete/BlockSolver.h"

// The label weights of the discrete solver: the resemblance of M07§3 (Eqs. 2-6), the guide of
// D§3.5.3, and the unary site constraints (guide, mirror planes, symmetry seams).

#include "Core/Error.h"
#include "Core/Index.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace msynth
{
namespace detail
{

/// The example as label indices, and the window offsets, for LabelChoice::Resemblance.
void BlockSolver::SetUpResemblance()
{
  if (!this->Options.Example)
    throw Error("resemblance-weighted label choice needs the example grid");
  const int w = this->Options.ResemblanceWindow;
  if (w < 0 || w > 8)
    throw Error("the resemblance window half-width must be between 0 and 8");
  const LabelGrid& e = *this->Options.Example;
  this->ExampleIndex.resize(e.Data().size());
  for (std::size_t i = 0; i < e.Data().size(); ++i)
  {
    const int b = this->Rules.IndexOf(e.Data()[i]);
    if (b < 0)
      throw Error("the example given for resemblance has label " + std::to_string(e.Data()[i]) +
        ", which the rules do not know");
    this->ExampleIndex[i] = b;
  }
  this->WindowOffsets.clear();
  for (int z = -w; z <= w; ++z)
    for (int y = -w; y <= w; ++y)
      for (int x = -w; x <= w; ++x)
        if (x || y || z)
          this->WindowOffsets.push_back({ { x, y, z } });
}

/// The decided label index at model site @p q during the current block (-1: undecided).
int BlockSolver::DecidedLabel(const Coord& q) const
{
  const Coord& o = this->Cat.Origin();
  const Coord& d = this->Cat.Dims();
  if (q[0] >= o[0] && q[1] >= o[1] && q[2] >= o[2] && q[0] < o[0] + d[0] && q[1] < o[1] + d[1] &&
    q[2] < o[2] + d[2])
  {
    const std::int64_t local = this->Cat.Local(q[0] - o[0], q[1] - o[1], q[2] - o[2]);
    return this->Cat.Count(local) == 1 ? this->Cat.Single(local) : -1;
  }
  return this->Model[ToIndex(this->Index(q))];
}

/// L(k) of Eqs. 4-5 for every label of the catalog at @p local (written to @p weights):
/// the number of example sites holding k whose window is at the minimum distance d0.
void BlockSolver::ResemblanceWeights(std::int64_t local, std::vector<double>& weights)
{
  const LabelGrid& e = *this->Options.Example;
  const auto& ed = e.Dimensions();
  const Coord c = this->Cat.Coordinates(local);
  const Coord& o = this->Cat.Origin();
  const Coord v{ { o[0] + c[0], o[1] + c[1], o[2] + c[2] } };
  // The decided labels around v (the window of M').
  std::vector<std::pair<std::size_t, int>> around; // (offset index, label)
  for (std::size_t i = 0; i < this->WindowOffsets.size(); ++i)
  {
    const auto& q = this->WindowOffsets[i];
    const Coord p{ { v[0] + q[0], v[1] + q[1], v[2] + q[2] } };
    if (p[0] < 0 || p[1] < 0 || p[2] < 0 || p[0] >= this->N[0] || p[1] >= this->N[1] ||
      p[2] >= this->N[2])
      continue;
    const int b = this->DecidedLabel(p);
    if (b >= 0)
      around.emplace_back(i, b);
  }
  // d(v', k) = |P_v'| - overlap(v') - [E(v') = k]; d0 = the minimum over v' and possible k.
  const int k = this->Rules.NumberOfLabels();
  std::int64_t d0 = std::numeric_limits<std::int64_t>::max();
  std::vector<std::int64_t>& count = this->ResemblanceCounts;
  count.assign(ToIndex(k), 0);
  for (std::int64_t z = 0; z < ed[2]; ++z)
    for (std::int64_t y = 0; y < ed[1]; ++y)
      for (std::int64_t x = 0; x < ed[0]; ++x)
      {
        const int centre = this->ExampleIndex[ToIndex(e.Index(x, y, z))];
        if (!this->Cat.Contains(local, centre))
          continue; // (v, k) not in the catalog: L(k) = 0 (Eq. 5)
        // Perceptual distance over the positions both windows define (inside E, decided in
        // M): the pieces that differ. (Eqs. 2-3 read literally count every example piece the
        // model lacks, which favours example windows clipped by its border and, there, empty
        // space; see Documentation/architecture.md.)
        std::int64_t d = 0;
        for (const auto& a : around)
        {
          const auto& q = this->WindowOffsets[a.first];
          const std::int64_t ex = x + q[0], ey = y + q[1], ez = z + q[2];
          if (e.Contains(ex, ey, ez) &&
            this->ExampleIndex[ToIndex(e.Index(ex, ey, ez))] != a.second)
            ++d;
        }
        if (d < d0)
        {
          d0 = d;
          std::fill(count.begin(), count.end(), 0);
        }
        if (d == d0)
          ++count[ToIndex(centre)];
      }
  weights.assign(ToIndex(k), 0.0);
  for (int b = 0; b < k; ++b)
    weights[ToIndex(b)] = static_cast<double>(count[ToIndex(b)]);
}

/// Dense guide weights [cell][label index] and, per cell, the mask of labels allowed there.
void BlockSolver::SetUpGuide(const GuideVolume& guide)
{
  const auto& d = guide.Dims;
  if (d[0] < 1 || d[1] < 1 || d[2] < 1 || d[0] > (1 << 20) || d[1] > (1 << 20) || d[2] > (1 << 20))
    throw Error("the guide volume's dimensions must be between 1 and 2^20");
  const std::int64_t cells = d[0] * d[1] * d[2];
  const int k = this->Rules.NumberOfLabels();
  if (cells > (std::int64_t(1) << 28) / k)
    throw Error("the guide volume is too large (cells × labels above 2^28)");
  this->GuideWeights.assign(ToIndex(cells * k), 1.0f);
  for (const auto& kv : guide.Weights)
  {
    const int b = this->Rules.IndexOf(kv.first);
    if (b < 0)
      throw Error("the guide gives weights for label " + std::to_string(kv.first) +
        ", which does not occur in the example");
    if (static_cast<std::int64_t>(kv.second.size()) != cells)
      throw Error("the guide weights of label " + std::to_string(kv.first) + " have " +
        std::to_string(kv.second.size()) + " values for " + std::to_string(cells) + " cells");
    for (std::int64_t c = 0; c < cells; ++c)
    {
      const float w = kv.second[ToIndex(c)];
      if (!(w >= 0.0f) || !std::isfinite(w))
        throw Error("the guide weight of label " + std::to_string(kv.first) + " in cell " +
          std::to_string(c) + " is negative or not finite");
      this->GuideWeights[ToIndex(c * k + b)] = w;
    }
  }
  const int words = this->Rules.Words();
  this->GuideMasks.assign(ToIndex(cells * words), 0);
  for (std::int64_t c = 0; c < cells; ++c)
    for (int b = 0; b < k; ++b)
      if (this->GuideWeights[ToIndex(c * k + b)] > 0.0f)
        this->GuideMasks[ToIndex(c * words + b / 64)] |= std::uint64_t(1) << (b % 64);
}

/// Unary constraints of a free site @p p: the guide (at the site and, with symmetry, at each
/// of its mirror images for the mirrored label) and the mirror planes' last layers.
bool BlockSolver::KeepSiteConstraints(Catalog& cat, std::int64_t local, const Coord& p)
{
  const int words = this->Rules.Words();
  if (this->Seams) // its masks hold the seams' unary constraints and the guide at every image
    return !this->Seams->HasMasks() ||
      cat.Keep(local, this->Seams->SiteMasks.data() + ToIndex(this->Index(p)) * words);
  if (this->Plan)
  {
    for (int a = 0; a < 3; ++a)
      if (this->Plan->Axes[ToIndex(a)] && p[a] == this->N[a] - 1 &&
        !cat.Keep(local, this->Plan->ColumnMask[ToIndex(a)].data()))
        return false;
  }
  if (!this->HasGuide())
    return true;
  if (!this->Plan)
    return cat.Keep(local, this->GuideMasks.data() + ToIndex(this->GuideCell(p)) * words);
  // Label b is allowed when each image of the site allows the image of b.
  std::vector<std::uint64_t>& mask = this->MaskScratch;
  mask.assign(ToIndex(words), 0);
  const int axes = this->Plan->AxisMask();
  for (int b = 0; b < this->Rules.NumberOfLabels(); ++b)
  {
    bool ok = true;
    for (int subset = 0; subset <= axes && ok; ++subset)
    {
      if ((subset & axes) != subset)
        continue;
      const std::int64_t cell = this->GuideCell(this->Plan->ImageSite(p, subset));
      ok = this->GuideWeight(cell, this->Plan->Image(b, subset)) > 0.0f;
    }
    if (ok)
      mask[ToIndex(b / 64)] |= std::uint64_t(1) << (b % 64);
  }
  return cat.Keep(local, mask.data());
}

} // namespace detail
} // namespace msynth
