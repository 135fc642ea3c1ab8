// SPDX-License-Identifier: BSD-3-Clause
#include "msynth/DiscreteSynthesis.h"

#include "SymmetryPlan.h"

#include "msynth/Catalog.h"
#include "msynth/Error.h"
#include "msynth/Memory.h"
#include "msynth/Random.h"

#include "ProgressPoll.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstring>
#include <functional>
#include <limits>
#include <memory>
#include <queue>
#include <system_error>
#include <thread>

namespace msynth
{
namespace
{
// ---------------------------------------------------------------------------------------------
// internal
// ---------------------------------------------------------------------------------------------
using Coord = std::array<std::int64_t, 3>;

/// One block of Algorithm 3.4: the box [Origin, Origin + Dims), clipped to the model.
struct Block
{
  std::int64_t Index = 0; ///< position in scan order of the block grid (the seed's sub-key)
  Coord Origin{ { 0, 0, 0 } };
  Coord Dims{ { 0, 0, 0 } };
  int Phase = 0;
};

/// Block origins along one axis: steps of m - overlap until the model is covered.
std::vector<std::int64_t> Starts(std::int64_t n, std::int64_t m, std::int64_t step)
{
  std::vector<std::int64_t> starts{ 0 };
  while (starts.back() + m < n)
  {
    starts.push_back(starts.back() + step);
  }
  return starts;
}

/**
 * The blocks, ordered by phase then position. Along an axis with step s and block size m,
 * blocks c = ceil((m + 1) / s) apart leave at least one site between them, so two blocks
 * whose indices are congruent modulo c on every axis never touch (nor their neighbour
 * layers): a phase may run its blocks in any order, or concurrently.
 */
std::vector<Block> PlanBlocks(const Coord& n, const Coord& m, const Coord& step, int& phases)
{
  std::array<std::vector<std::int64_t>, 3> starts;
  std::array<int, 3> period{ { 1, 1, 1 } };
  for (int a = 0; a < 3; ++a)
  {
    starts[a] = Starts(n[a], m[a], step[a]);
    if (starts[a].size() > 1)
    {
      period[a] = static_cast<int>((m[a] + 1 + step[a] - 1) / step[a]);
    }
  }
  std::vector<Block> blocks;
  std::int64_t index = 0;
  for (std::size_t k = 0; k < starts[2].size(); ++k)
    for (std::size_t j = 0; j < starts[1].size(); ++j)
      for (std::size_t i = 0; i < starts[0].size(); ++i)
      {
        Block b;
        b.Index = index++;
        const std::size_t ijk[3] = { i, j, k };
        for (int a = 0; a < 3; ++a)
        {
          b.Origin[a] = starts[a][ijk[a]];
          b.Dims[a] = std::min(m[a], n[a] - b.Origin[a]);
        }
        b.Phase = static_cast<int>(i % period[0]) +
          period[0] *
            (static_cast<int>(j % period[1]) + period[1] * static_cast<int>(k % period[2]));
        blocks.push_back(b);
      }
  std::stable_sort(
    blocks.begin(), blocks.end(), [](const Block& a, const Block& b) { return a.Phase < b.Phase; });
  phases = period[0] * period[1] * period[2];
  return blocks;
}

std::string Format(const Coord& c)
{
  return "(" + std::to_string(c[0]) + ", " + std::to_string(c[1]) + ", " + std::to_string(c[2]) +
    ")";
}

/// Block size and step per axis from the options (Algorithm 3.5's m and the overlap).
bool BlockGeometry(const SynthesisOptions& options, Coord& m, Coord& step)
{
  bool wholeModel = true;
  for (int a = 0; a < 3; ++a)
  {
    const std::int64_t n = options.Size[a];
    m[a] = options.BlockSize[a] <= 0 ? n : std::min(options.BlockSize[a], n);
    wholeModel = wholeModel && m[a] == n;
    std::int64_t overlap = options.Overlap[a] < 0 ? m[a] / 2 : options.Overlap[a];
    overlap = std::min(overlap, m[a] - 1);
    step[a] = m[a] - overlap;
  }
  return wholeModel;
}

/// Symmetric synthesis: what the half to synthesize is and how it maps onto the full model.
struct MirrorPlan
{
  Coord Full{ { 1, 1, 1 } };
  Coord Half{ { 1, 1, 1 } };
  std::array<bool, 3> Axes{ { false, false, false } };
  std::array<std::vector<int>, 3> F; ///< label index → index of its mirror image, per axis
  std::array<std::vector<std::uint64_t>, 3> ColumnMask; ///< labels allowed on the last layer
  SynthesisOptions HalfOptions;

  /// Index of the mirror image of label index @p b over the axes whose bit is set in @p axes.
  int Image(int b, int axes) const
  {
    for (int a = 0; a < 3; ++a)
      if (axes & (1 << a))
        b = this->F[static_cast<std::size_t>(a)][static_cast<std::size_t>(b)];
    return b;
  }
  /// The site of the full model that mirrors half-model site @p p over the axes of @p axes.
  Coord ImageSite(const Coord& p, int axes) const
  {
    Coord q = p;
    for (int a = 0; a < 3; ++a)
      if (axes & (1 << a))
        q[a] = this->Full[a] - 1 - p[a];
    return q;
  }
  int AxisMask() const
  {
    return (this->Axes[0] ? 1 : 0) | (this->Axes[1] ? 2 : 0) | (this->Axes[2] ? 4 : 0);
  }
};

bool AnyMirror(const SynthesisOptions& options)
{
  return options.Symmetry[0].Enabled || options.Symmetry[1].Enabled || options.Symmetry[2].Enabled;
}

/// Validates the symmetry options against the rules and plans the half to synthesize.
MirrorPlan PlanMirror(const AdjacencyRules& rules, const SynthesisOptions& options)
{
  MirrorPlan plan;
  plan.Full = options.Size;
  plan.HalfOptions = options;
  const int k = rules.NumberOfLabels();
  const auto& values = rules.LabelValues();
  static const char* const axisName = "xyz";
  for (int a = 0; a < 3; ++a)
  {
    const Mirror& mirror = options.Symmetry[static_cast<std::size_t>(a)];
    plan.HalfOptions.Symmetry[static_cast<std::size_t>(a)].Enabled = false;
    if (!mirror.Enabled)
      continue;
    const std::string axis(1, axisName[a]);
    plan.Axes[static_cast<std::size_t>(a)] = true;
    auto& f = plan.F[static_cast<std::size_t>(a)];
    f.resize(static_cast<std::size_t>(k));
    for (int b = 0; b < k; ++b)
      f[static_cast<std::size_t>(b)] = b;
    for (const auto& kv : mirror.Map)
    {
      const int from = rules.IndexOf(kv.first), to = rules.IndexOf(kv.second);
      if (from < 0 || to < 0)
        throw Error("the mirror map along " + axis + " names label " +
          std::to_string(from < 0 ? kv.first : kv.second) +
          ", which does not occur in the example");
      f[static_cast<std::size_t>(from)] = to;
    }
    for (int b = 0; b < k; ++b)
      if (f[static_cast<std::size_t>(f[static_cast<std::size_t>(b)])] != b)
        throw Error("the mirror map along " + axis + " is not its own inverse: label " +
          std::to_string(values[static_cast<std::size_t>(b)]) + " maps to " +
          std::to_string(values[static_cast<std::size_t>(f[static_cast<std::size_t>(b)])]) +
          ", which does not map back");
    // The rules must be symmetric under f (else a mirrored model breaks them).
    for (int axis2 = 0; axis2 < 3; ++axis2)
      for (int b = 0; b < k; ++b)
        for (int c = 0; c < k; ++c)
        {
          const int fb = f[static_cast<std::size_t>(b)], fc = f[static_cast<std::size_t>(c)];
          const bool mirrored =
            axis2 == a ? rules.Allowed(2 * axis2, fc, fb) : rules.Allowed(2 * axis2, fb, fc);
          if (rules.Allowed(2 * axis2, b, c) != mirrored)
            throw Error("the example is not symmetric under the mirror map along " + axis +
              ": label " + std::to_string(values[static_cast<std::size_t>(b)]) + " before " +
              std::to_string(values[static_cast<std::size_t>(c)]) + " along " + axisName[axis2] +
              (rules.Allowed(2 * axis2, b, c) ? " occurs" : " does not occur") +
              " but its mirror image " + (mirrored ? "does" : "does not"));
        }
    // The half, and the labels allowed on its last layer next to their own mirror image.
    const std::int64_t n = options.Size[a];
    plan.Half[a] = (n + 1) / 2;
    auto& mask = plan.ColumnMask[static_cast<std::size_t>(a)];
    mask.assign(static_cast<std::size_t>(rules.Words()), 0);
    bool any = false;
    for (int b = 0; b < k; ++b)
    {
      const bool ok = (n % 2 == 1) ? f[static_cast<std::size_t>(b)] == b
                                   : rules.Allowed(2 * a, b, f[static_cast<std::size_t>(b)]);
      if (ok || n == 1)
      {
        mask[static_cast<std::size_t>(b / 64)] |= std::uint64_t(1) << (b % 64);
        any = true;
      }
    }
    if (!any)
      throw Error("no label can lie on the mirror plane along " + axis +
        (n % 2 == 1 ? " (an odd size puts sites on the plane, and no label is its own mirror image)"
                    : " (no label may be followed by its mirror image)"));
    // Boundary faces: the far face is the mirror image of the near one.
    auto& near = plan.HalfOptions.Boundary[static_cast<std::size_t>(2 * a)];
    auto& far = plan.HalfOptions.Boundary[static_cast<std::size_t>(2 * a + 1)];
    if (near && far && rules.IndexOf(*near) >= 0 && rules.IndexOf(*far) >= 0 &&
      f[static_cast<std::size_t>(rules.IndexOf(*near))] != rules.IndexOf(*far))
      throw Error("with symmetry along " + axis +
        ", the boundary label of the far face must be "
        "the mirror image of the near face's");
    if (!near && far)
      near = values[static_cast<std::size_t>(
        f[static_cast<std::size_t>(rules.IndexOf(*far) < 0 ? 0 : rules.IndexOf(*far))])];
    far.reset();
  }
  for (int a = 0; a < 3; ++a)
    if (!plan.Axes[static_cast<std::size_t>(a)])
      plan.Half[a] = options.Size[a];
  for (int a = 0; a < 3; ++a)
    for (int c = a + 1; c < 3; ++c)
      if (plan.Axes[static_cast<std::size_t>(a)] && plan.Axes[static_cast<std::size_t>(c)])
        for (int b = 0; b < k; ++b)
          if (plan.Image(plan.Image(b, 1 << a), 1 << c) !=
            plan.Image(plan.Image(b, 1 << c), 1 << a))
            throw Error(std::string("the mirror maps along ") + axisName[a] + " and " +
              axisName[c] + " do not commute (label " +
              std::to_string(values[static_cast<std::size_t>(b)]) + ")");
  plan.HalfOptions.Size = plan.Half;
  return plan;
}

/// The model being synthesized, shared by the solvers of all threads. Blocks of one phase
/// never touch, so threads write disjoint sites.
struct SharedModel
{
  std::vector<std::int32_t> Model;     ///< label indices; -1 unassigned
  std::vector<std::int32_t> Fixed;     ///< boundary label indices; -1 free
  std::vector<std::int32_t> LastBlock; ///< block that last changed each site
};

/// The solver state shared by all blocks.
class Solver
{
public:
  /// A solver over @p shared; the first solver of a run sizes it, later ones (one per extra
  /// thread) share it with their own catalog and scratch space.
  Solver(const AdjacencyRules& rules, const SynthesisOptions& options, const MirrorPlan* plan,
    const detail::SymmetryPlan* seams, SharedModel& shared)
    : Rules(rules)
    , Options(options)
    , Cat(rules)
    , Plan(plan)
    , Seams(seams)
    , Model(shared.Model)
    , Fixed(shared.Fixed)
    , LastBlock(shared.LastBlock)
  {
    this->N = options.Size;
    LabelGrid::CheckDimensions(this->N[0], this->N[1], this->N[2]);
    if (seams)
      this->Cat.SetArcs(seams->Relation.get(), &seams->Arcs);
    const auto sites = static_cast<std::size_t>(this->N[0] * this->N[1] * this->N[2]);
    if (this->Model.empty())
    {
      this->Model.assign(sites, -1);
      this->Fixed.assign(sites, -1);
      this->LastBlock.assign(sites, -1);
    }
    const int k = rules.NumberOfLabels();
    this->WLogW.resize(static_cast<std::size_t>(k));
    for (int b = 0; b < k; ++b)
    {
      const double w = this->Weight(b);
      this->WLogW[static_cast<std::size_t>(b)] = w * std::log(w);
    }
    double sum = 0.0, sumWLogW = 0.0;
    for (int b = 0; b < k; ++b)
    {
      sum += this->Weight(b);
      sumWLogW += this->WLogW[static_cast<std::size_t>(b)];
    }
    this->FullEntropy = std::log(sum) - sumWLogW / sum;
    if (options.Guide)
    {
      this->SetUpGuide(*options.Guide);
    }
    if (options.Choice == LabelChoice::Resemblance)
    {
      this->SetUpResemblance();
    }
  }

  /// The example as label indices, and the window offsets, for LabelChoice::Resemblance.
  void SetUpResemblance()
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
  int DecidedLabel(const Coord& q) const
  {
    const Coord& o = this->Cat.Origin();
    const Coord& d = this->Cat.Dims();
    if (q[0] >= o[0] && q[1] >= o[1] && q[2] >= o[2] && q[0] < o[0] + d[0] && q[1] < o[1] + d[1] &&
      q[2] < o[2] + d[2])
    {
      const std::int64_t local = this->Cat.Local(q[0] - o[0], q[1] - o[1], q[2] - o[2]);
      return this->Cat.Count(local) == 1 ? this->Cat.Single(local) : -1;
    }
    return this->Model[static_cast<std::size_t>(this->Index(q))];
  }

  /// L(k) of Eqs. 4-5 for every label of the catalog at @p local (written to @p weights):
  /// the number of example sites holding k whose window is at the minimum distance d0.
  void ResemblanceWeights(std::int64_t local, std::vector<double>& weights)
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
    count.assign(static_cast<std::size_t>(k), 0);
    for (std::int64_t z = 0; z < ed[2]; ++z)
      for (std::int64_t y = 0; y < ed[1]; ++y)
        for (std::int64_t x = 0; x < ed[0]; ++x)
        {
          const int centre = this->ExampleIndex[static_cast<std::size_t>(e.Index(x, y, z))];
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
              this->ExampleIndex[static_cast<std::size_t>(e.Index(ex, ey, ez))] != a.second)
              ++d;
          }
          if (d < d0)
          {
            d0 = d;
            std::fill(count.begin(), count.end(), 0);
          }
          if (d == d0)
            ++count[static_cast<std::size_t>(centre)];
        }
    weights.assign(static_cast<std::size_t>(k), 0.0);
    for (int b = 0; b < k; ++b)
      weights[static_cast<std::size_t>(b)] =
        static_cast<double>(count[static_cast<std::size_t>(b)]);
  }

  /// Dense guide weights [cell][label index] and, per cell, the mask of labels allowed there.
  void SetUpGuide(const GuideVolume& guide)
  {
    const auto& d = guide.Dims;
    if (d[0] < 1 || d[1] < 1 || d[2] < 1 || d[0] > (1 << 20) || d[1] > (1 << 20) ||
      d[2] > (1 << 20))
      throw Error("the guide volume's dimensions must be between 1 and 2^20");
    const std::int64_t cells = d[0] * d[1] * d[2];
    const int k = this->Rules.NumberOfLabels();
    if (cells > (std::int64_t(1) << 28) / k)
      throw Error("the guide volume is too large (cells × labels above 2^28)");
    this->GuideWeights.assign(static_cast<std::size_t>(cells * k), 1.0f);
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
        const float w = kv.second[static_cast<std::size_t>(c)];
        if (!(w >= 0.0f) || !std::isfinite(w))
          throw Error("the guide weight of label " + std::to_string(kv.first) + " in cell " +
            std::to_string(c) + " is negative or not finite");
        this->GuideWeights[static_cast<std::size_t>(c * k + b)] = w;
      }
    }
    const int words = this->Rules.Words();
    this->GuideMasks.assign(static_cast<std::size_t>(cells * words), 0);
    for (std::int64_t c = 0; c < cells; ++c)
      for (int b = 0; b < k; ++b)
        if (this->GuideWeights[static_cast<std::size_t>(c * k + b)] > 0.0f)
          this->GuideMasks[static_cast<std::size_t>(c * words + b / 64)] |= std::uint64_t(1)
            << (b % 64);
  }

  bool HasGuide() const { return !this->GuideWeights.empty(); }

  /// Unary constraints of a free site @p p: the guide (at the site and, with symmetry, at each
  /// of its mirror images for the mirrored label) and the mirror planes' last layers.
  bool KeepSiteConstraints(Catalog& cat, std::int64_t local, const Coord& p)
  {
    const int words = this->Rules.Words();
    if (this->Seams) // its masks hold the seams' unary constraints and the guide at every image
      return !this->Seams->HasMasks() ||
        cat.Keep(local,
          this->Seams->SiteMasks.data() + static_cast<std::size_t>(this->Index(p)) * words);
    if (this->Plan)
    {
      for (int a = 0; a < 3; ++a)
        if (this->Plan->Axes[static_cast<std::size_t>(a)] && p[a] == this->N[a] - 1 &&
          !cat.Keep(local, this->Plan->ColumnMask[static_cast<std::size_t>(a)].data()))
          return false;
    }
    if (!this->HasGuide())
      return true;
    if (!this->Plan)
      return cat.Keep(
        local, this->GuideMasks.data() + static_cast<std::size_t>(this->GuideCell(p)) * words);
    // Label b is allowed when each image of the site allows the image of b.
    std::vector<std::uint64_t>& mask = this->MaskScratch;
    mask.assign(static_cast<std::size_t>(words), 0);
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
        mask[static_cast<std::size_t>(b / 64)] |= std::uint64_t(1) << (b % 64);
    }
    return cat.Keep(local, mask.data());
  }

  /// The guide cell of model site @p p.
  std::int64_t GuideCell(const Coord& p) const
  {
    // The guide spans the full output, also when only a part of it is synthesized.
    return this->Options.Guide->CellOf(
      p, this->Plan ? this->Plan->Full : (this->Seams ? this->Seams->Full : this->N));
  }
  float GuideWeight(std::int64_t cell, int b) const
  {
    return this->GuideWeights[static_cast<std::size_t>(cell * this->Rules.NumberOfLabels() + b)];
  }

  /// The weight of label @p b at a site of guide cell @p cell (the base weight without a guide).
  double SiteWeight(std::int64_t cell, int b) const
  {
    return this->HasGuide() ? this->Weight(b) * this->GuideWeight(cell, b) : this->Weight(b);
  }

  /// The guide cell of a site of the current catalog region.
  std::int64_t GuideCellOfLocal(std::int64_t local) const
  {
    const Coord c = this->Cat.Coordinates(local);
    const Coord& o = this->Cat.Origin();
    return this->GuideCell({ { o[0] + c[0], o[1] + c[1], o[2] + c[2] } });
  }

  double Weight(int b) const
  {
    return this->Options.Choice == LabelChoice::Frequency
      ? this->Rules.Weights()[static_cast<std::size_t>(b)]
      : 1.0;
  }

  std::int64_t Index(const Coord& p) const
  {
    return p[0] + this->N[0] * (p[1] + this->N[1] * p[2]);
  }

  int LabelIndex(Label value, const char* what) const
  {
    const int b = this->Rules.IndexOf(value);
    if (b < 0)
    {
      throw Error(
        std::string(what) + " label " + std::to_string(value) + " does not occur in the example");
    }
    return b;
  }

  /// Boundary layers (Fig. 3.11), with precedence -z, +z, -y, +y, -x, +x.
  void ApplyBoundary()
  {
    static const int precedence[6] = { FaceMinZ, FaceMaxZ, FaceMinY, FaceMaxY, FaceMinX, FaceMaxX };
    for (int f = 5; f >= 0; --f) // lowest precedence first, so higher ones overwrite
    {
      const int face = precedence[f];
      const auto& value = this->Options.Boundary[static_cast<std::size_t>(face)];
      const int axis = face / 2;
      if (!value || this->N[axis] == 1)
      {
        continue;
      }
      const int b = this->LabelIndex(*value, "boundary");
      const std::int64_t layer = (face % 2 == 0) ? 0 : this->N[axis] - 1;
      Coord p;
      for (p[2] = 0; p[2] < this->N[2]; ++p[2])
        for (p[1] = 0; p[1] < this->N[1]; ++p[1])
          for (p[0] = 0; p[0] < this->N[0]; ++p[0])
          {
            if (p[axis] == layer)
            {
              this->Fixed[static_cast<std::size_t>(this->Index(p))] = b;
            }
          }
    }
    for (std::size_t s = 0; s < this->Fixed.size(); ++s)
    {
      if (this->Fixed[s] >= 0)
      {
        this->Model[s] = this->Fixed[s];
      }
    }
    if (this->HasGuide())
    {
      Coord p;
      for (p[2] = 0; p[2] < this->N[2]; ++p[2])
        for (p[1] = 0; p[1] < this->N[1]; ++p[1])
          for (p[0] = 0; p[0] < this->N[0]; ++p[0])
          {
            const int b = this->Fixed[static_cast<std::size_t>(this->Index(p))];
            if (b >= 0 && this->GuideWeight(this->GuideCell(p), b) == 0.0f)
              throw Error("the boundary label " +
                std::to_string(this->Rules.LabelValues()[static_cast<std::size_t>(b)]) +
                " has guide weight 0 at " + Format(p));
          }
    }
  }

  /// The trivial start of Algorithm 3.4 (lines 3-5), checked for consistency.
  int TrivialStart()
  {
    int t = -1;
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
      const int zero = this->Rules.IndexOf(0);
      if (zero >= 0 && this->Rules.SelfAdjacent(zero, this->N))
      {
        t = zero;
      }
      for (int b = 0; t < 0 && b < this->Rules.NumberOfLabels(); ++b)
      {
        if (this->Rules.SelfAdjacent(b, this->N) &&
          (t < 0 ||
            this->Rules.Weights()[static_cast<std::size_t>(b)] >
              this->Rules.Weights()[static_cast<std::size_t>(t)]))
        {
          t = b;
        }
      }
      if (t < 0)
      {
        throw Error("the example has no usable trivial start for block synthesis: no label is "
                    "adjacent to itself along every axis (usually the empty label is). Use "
                    "whole-model synthesis (a block as large as the output) instead");
      }
    }
    for (std::size_t s = 0; s < this->Model.size(); ++s)
    {
      if (this->Fixed[s] < 0)
      {
        this->Model[s] = t;
      }
    }
    // With symmetry, the trivial label must be allowed on the mirror planes.
    if (this->Plan)
      for (int a = 0; a < 3; ++a)
        if (this->Plan->Axes[static_cast<std::size_t>(a)] &&
          !((this->Plan
                ->ColumnMask[static_cast<std::size_t>(a)][static_cast<std::size_t>(t / 64)] >>
              (t % 64)) &
            1u))
          throw Error("the trivial label " +
            std::to_string(this->Rules.LabelValues()[static_cast<std::size_t>(t)]) +
            " cannot lie next to its own mirror image along " +
            std::string("xyz").substr(static_cast<std::size_t>(a), 1));
    // A failed block falls back to the trivial label, so the guide may not forbid it.
    if (this->HasGuide())
    {
      Coord p;
      for (p[2] = 0; p[2] < this->N[2]; ++p[2])
        for (p[1] = 0; p[1] < this->N[1]; ++p[1])
          for (p[0] = 0; p[0] < this->N[0]; ++p[0])
            if (this->Fixed[static_cast<std::size_t>(this->Index(p))] < 0 &&
              this->GuideWeight(this->GuideCell(p), t) == 0.0f)
              throw Error("the guide gives the trivial label " +
                std::to_string(this->Rules.LabelValues()[static_cast<std::size_t>(t)]) +
                " weight 0 at " + Format(p) +
                ", but block synthesis falls back to it where a "
                "block fails. Allow that label everywhere, or use whole-model synthesis");
    }
    // The start must satisfy Eq. 3.3, boundary labels included.
    Coord p;
    for (p[2] = 0; p[2] < this->N[2]; ++p[2])
      for (p[1] = 0; p[1] < this->N[1]; ++p[1])
        for (p[0] = 0; p[0] < this->N[0]; ++p[0])
          for (int axis = 0; axis < 3; ++axis)
          {
            Coord q = p;
            if (++q[axis] >= this->N[axis])
              continue;
            const int b = this->Model[static_cast<std::size_t>(this->Index(p))];
            const int c = this->Model[static_cast<std::size_t>(this->Index(q))];
            if (!this->Rules.Allowed(2 * axis, b, c))
            {
              const auto& v = this->Rules.LabelValues();
              throw Error("no usable trivial start: the initial model of label " +
                std::to_string(v[static_cast<std::size_t>(t)]) +
                " with the boundary labels puts label " +
                std::to_string(v[static_cast<std::size_t>(b)]) + " before " +
                std::to_string(v[static_cast<std::size_t>(c)]) + " along " +
                std::string("xyz").substr(static_cast<std::size_t>(axis), 1) + " at " + Format(p) +
                ", which the example never does");
            }
          }
    if (this->Seams)
      this->CheckStartAgainstSeams(t);
    return t;
  }

  /// The trivial start must also satisfy the symmetry's seams and unary constraints.
  void CheckStartAgainstSeams(int t) const
  {
    const auto& v = this->Rules.LabelValues();
    const SiteArcs& arcs = this->Seams->Arcs;
    const int words = this->Rules.Words();
    for (std::size_t s = 0; s < this->Model.size(); ++s)
    {
      const int b = this->Model[s];
      const std::uint64_t* mask = this->Seams->HasMasks()
        ? this->Seams->SiteMasks.data() + s * static_cast<std::size_t>(words)
        : nullptr;
      bool ok = !mask || ((mask[b / 64] >> (b % 64)) & 1u);
      for (std::int64_t i = arcs.Start[s]; ok && i < arcs.Start[s + 1]; ++i)
        ok = this->Seams->Relation->Allowed(arcs.Class[static_cast<std::size_t>(i)], b,
          this->Model[static_cast<std::size_t>(arcs.Target[static_cast<std::size_t>(i)])]);
      if (!ok)
        throw Error("no usable trivial start: a model of label " +
          std::to_string(v[static_cast<std::size_t>(t)]) +
          " (with the boundary labels) does not meet its own symmetric copies at " +
          Format(this->Coordinates(static_cast<std::int64_t>(s))) +
          "; the trivial label must be its own image under the symmetry's label map");
    }
  }

  Coord Coordinates(std::int64_t index) const
  {
    return { { index % this->N[0], (index / this->N[0]) % this->N[1],
      index / (this->N[0] * this->N[1]) } };
  }

  /// One attempt at a block (lines 9-29 of Algorithm 3.4). Returns -1 on success, else the
  /// model index of the site whose catalog became empty.
  std::int64_t RunBlock(const Block& block, Random& rng, std::int64_t& assignments)
  {
    Catalog& cat = this->Cat;
    cat.Reset(block.Origin, block.Dims);
    this->Pending.clear(); // snapshots of an earlier, failed attempt are dropped
    const Coord& o = block.Origin;
    const Coord& m = block.Dims;
    auto global = [&](std::int64_t local)
    {
      const Coord c = cat.Coordinates(local);
      return this->Index({ { o[0] + c[0], o[1] + c[1], o[2] + c[2] } });
    };
    auto fail = [&](std::int64_t local) { return global(local); };

    // Fixed labels inside the block, and the labels around it (lines 12-17).
    std::vector<std::int64_t> free;
    free.reserve(static_cast<std::size_t>(cat.NumberOfSites()));
    for (std::int64_t local = 0; local < cat.NumberOfSites(); ++local)
    {
      const Coord c = cat.Coordinates(local);
      const Coord p{ { o[0] + c[0], o[1] + c[1], o[2] + c[2] } };
      const int fixed = this->Fixed[static_cast<std::size_t>(this->Index(p))];
      if (fixed >= 0)
      {
        if (!cat.Assign(local, fixed))
          return fail(local);
      }
      else
      {
        free.push_back(local);
        if (!this->KeepSiteConstraints(cat, local, p))
          return fail(local);
      }
      for (int d = 0; d < NumberOfDirections; ++d)
      {
        const int axis = AxisOf(d);
        Coord q = p;
        q[axis] += (d & 1) ? -1 : 1;
        if (q[axis] < 0 || q[axis] >= this->N[axis] ||
          (q[axis] >= o[axis] && q[axis] < o[axis] + m[axis]))
          continue; // outside the model, or inside the block
        const int label = this->Model[static_cast<std::size_t>(this->Index(q))];
        if (label >= 0 && !cat.Constrain(local, Opposite(d), label))
          return fail(local);
      }
      if (this->Seams) // seams to sites outside the block
      {
        const SiteArcs& arcs = this->Seams->Arcs;
        const std::int64_t g = this->Index(p);
        for (std::int64_t i = arcs.Start[static_cast<std::size_t>(g)];
             i < arcs.Start[static_cast<std::size_t>(g + 1)]; ++i)
        {
          const std::int64_t t = arcs.Target[static_cast<std::size_t>(i)];
          const Coord q{ { t % this->N[0], (t / this->N[0]) % this->N[1],
            t / (this->N[0] * this->N[1]) } };
          if (q[0] >= o[0] && q[1] >= o[1] && q[2] >= o[2] && q[0] < o[0] + m[0] &&
            q[1] < o[1] + m[1] && q[2] < o[2] + m[2])
            continue; // inside the block: propagated by the catalog
          const int label = this->Model[static_cast<std::size_t>(t)];
          if (label >= 0 &&
            !cat.Constrain(local, arcs.Class[static_cast<std::size_t>(i)] ^ 1, label))
            return fail(local);
        }
      }
    }
    std::int64_t empty = cat.Propagate();
    if (empty >= 0)
      return fail(empty);

    // Assign the free sites (lines 19-29), in the chosen order.
    auto choose = [&](std::int64_t local)
    {
      // The guide's weights of this site's region multiply the choice's (D§3.5.3).
      const std::int64_t cell = this->HasGuide() ? this->GuideCellOfLocal(local) : 0;
      if (this->Options.Choice == LabelChoice::Resemblance)
      {
        this->ResemblanceWeights(local, this->ChoiceWeights);
        double weightSum = 0.0;
        for (std::size_t b = 0; b < this->ChoiceWeights.size(); ++b)
        {
          if (this->HasGuide())
            this->ChoiceWeights[b] *= this->GuideWeight(cell, static_cast<int>(b));
          weightSum += this->ChoiceWeights[b];
        }
        if (weightSum > 0.0)
        {
          double r = rng.Uniform() * weightSum;
          int last = -1;
          for (int b = 0; b < this->Rules.NumberOfLabels(); ++b)
          {
            const double x = this->ChoiceWeights[static_cast<std::size_t>(b)];
            if (x <= 0.0)
              continue;
            last = b;
            r -= x;
            if (r < 0.0)
              return b;
          }
          return last;
        }
        // No example site matches any possible label (labels only reachable through
        // propagation): fall back to the weighted choice below.
      }
      return DrawLabel(cat.Domain(local), this->Rules.Words(),
        [this, cell](int b) { return this->SiteWeight(cell, b); }, rng.Uniform());
    };
    auto assign = [&](std::int64_t local) -> std::int64_t
    {
      if (cat.Count(local) == 0)
        return local;
      if ((assignments & 1023) == 0 && this->Stopped())
        return local; // cancelled: the attempt ends here (and no other starts)
      if (cat.Count(local) > 1)
      {
        ++assignments;
        cat.Assign(local, choose(local));
        const std::int64_t emptied = cat.Propagate();
        if (emptied < 0)
          this->MaybeCapture(block, assignments);
        return emptied;
      }
      return -1;
    };

    if (this->Options.Order == SiteOrder::MinimumEntropy)
    {
      empty = this->AssignByEntropy(free, rng, assign);
    }
    else
    {
      if (this->Options.Order == SiteOrder::Random)
      {
        for (std::size_t i = free.size(); i > 1; --i)
          std::swap(free[i - 1], free[static_cast<std::size_t>(rng.Below(i))]);
      }
      for (std::int64_t local : free)
      {
        empty = assign(local);
        if (empty >= 0)
          break;
      }
    }
    if (empty >= 0)
      return fail(empty);

    // Success: commit the block.
    for (std::int64_t local = 0; local < cat.NumberOfSites(); ++local)
    {
      const auto s = static_cast<std::size_t>(global(local));
      const int b = cat.Single(local);
      if (this->Model[s] != b)
      {
        this->Model[s] = b;
        this->LastBlock[s] = static_cast<std::int32_t>(block.Index);
      }
    }
    return -1;
  }

  /// Minimum-entropy order with a priority queue (no full scan per step): entries are pushed
  /// when a site's catalog changes and skipped when stale.
  template <typename AssignFn>
  std::int64_t AssignByEntropy(
    const std::vector<std::int64_t>& free, Random& rng, AssignFn&& assign)
  {
    Catalog& cat = this->Cat;
    struct Entry
    {
      double Priority;
      std::int64_t Local;
      int Count;
      bool operator<(const Entry& o) const { return this->Priority > o.Priority; } // min-heap
    };
    std::vector<double> noise(static_cast<std::size_t>(cat.NumberOfSites()), 0.0);
    std::vector<std::uint8_t> isFree(static_cast<std::size_t>(cat.NumberOfSites()), 0);
    for (std::int64_t local : free)
    {
      noise[static_cast<std::size_t>(local)] = 1e-6 * rng.Uniform();
      isFree[static_cast<std::size_t>(local)] = 1;
    }
    auto entropy = [&](std::int64_t local) { return this->Entropy(cat, local); };
    std::priority_queue<Entry> heap;
    for (std::int64_t local : free)
    {
      if (cat.Count(local) > 1)
        heap.push(
          { entropy(local) + noise[static_cast<std::size_t>(local)], local, cat.Count(local) });
    }
    cat.ClearChanged();
    while (!heap.empty())
    {
      const Entry e = heap.top();
      heap.pop();
      if (cat.Count(e.Local) != e.Count || cat.Count(e.Local) <= 1)
        continue; // stale, or decided by propagation
      const std::int64_t empty = assign(e.Local);
      if (empty >= 0)
        return empty;
      for (std::int64_t local : cat.Changed())
      {
        if (isFree[static_cast<std::size_t>(local)] && cat.Count(local) > 1)
          heap.push(
            { entropy(local) + noise[static_cast<std::size_t>(local)], local, cat.Count(local) });
      }
      cat.ClearChanged();
    }
    // Every free site is now decided (a single label) or was never undecided.
    for (std::int64_t local : free)
    {
      if (cat.Count(local) == 0)
        return local;
    }
    return -1;
  }

  // -------------------------------------------------------------------------------------------
  // Catalog snapshots
  bool Snapshots() const { return this->Options.SnapshotsPerBlock > 0 && this->Options.OnSnapshot; }

  /// Entropy of the weighted labels still possible at @p local of the current catalog (the
  /// guide's weights included).
  double Entropy(const Catalog& cat, std::int64_t local) const
  {
    const bool guided = this->HasGuide();
    const std::int64_t cell = guided ? this->GuideCellOfLocal(local) : 0;
    double sum = 0.0, sumWLogW = 0.0;
    const std::uint64_t* dom = cat.Domain(local);
    for (int w = 0; w < this->Rules.Words(); ++w)
      for (std::uint64_t bits = dom[w]; bits; bits &= bits - 1)
      {
        const int b = w * 64 + __builtin_ctzll(bits);
        if (guided)
        {
          const double weight = this->SiteWeight(cell, b);
          sum += weight;
          sumWLogW += weight > 0.0 ? weight * std::log(weight) : 0.0;
        }
        else
        {
          sum += this->Weight(b);
          sumWLogW += this->WLogW[static_cast<std::size_t>(b)];
        }
      }
    return sum > 0.0 ? std::log(sum) - sumWLogW / sum : 0.0;
  }

  /// The whole model now: outside the active block, the model; inside, the catalog.
  CatalogSnapshot Capture(const Block* active, std::int64_t assignments) const
  {
    CatalogSnapshot snap;
    const std::size_t n = this->Model.size();
    snap.CatalogSize.assign(n, 1);
    snap.Entropy.assign(n, 0.0f);
    snap.Labels.resize(n);
    snap.Block = active ? active->Index : -1;
    snap.Assignments = assignments;
    const auto& values = this->Rules.LabelValues();
    const int k = this->Rules.NumberOfLabels();
    for (std::size_t s = 0; s < n; ++s)
    {
      const int b = this->Model[s];
      snap.Labels[s] = b >= 0 ? values[static_cast<std::size_t>(b)] : CatalogSnapshot::Undecided;
      if (b < 0)
      {
        snap.CatalogSize[s] = k; // never constrained yet (whole-model start)
        snap.Entropy[s] = static_cast<float>(this->FullEntropy);
      }
    }
    if (active)
    {
      const Catalog& cat = this->Cat;
      for (std::int64_t local = 0; local < cat.NumberOfSites(); ++local)
      {
        const Coord c = cat.Coordinates(local);
        const auto s = static_cast<std::size_t>(this->Index(
          { { active->Origin[0] + c[0], active->Origin[1] + c[1], active->Origin[2] + c[2] } }));
        const int count = cat.Count(local);
        snap.CatalogSize[s] = count;
        snap.Entropy[s] = static_cast<float>(this->Entropy(cat, local));
        snap.Labels[s] = count == 1 ? values[static_cast<std::size_t>(cat.Single(local))]
                                    : CatalogSnapshot::Undecided;
      }
    }
    return snap;
  }

  /// During an attempt: capture when the block's decided fraction reaches the next milestone.
  void MaybeCapture(const Block& block, std::int64_t assignments)
  {
    if (!this->Snapshots())
      return;
    const int per = this->Options.SnapshotsPerBlock;
    // The last milestone (all decided) is the committed block, captured by CommitSnapshots.
    if (static_cast<int>(this->Pending.size()) >= per - 1)
      return;
    const double fraction = double(this->Cat.Decided()) / double(this->Cat.NumberOfSites());
    while (static_cast<int>(this->Pending.size()) < per - 1 &&
      fraction >= double(this->Pending.size() + 1) / double(per))
    {
      this->Pending.push_back(this->Capture(&block, assignments));
    }
  }

  /// After a block: emit its snapshots (padded to SnapshotsPerBlock with the final state).
  void CommitSnapshots(std::int64_t assignments)
  {
    if (!this->Snapshots())
      return;
    CatalogSnapshot final = this->Capture(nullptr, assignments);
    while (static_cast<int>(this->Pending.size()) < this->Options.SnapshotsPerBlock - 1)
      this->Pending.push_back(final);
    this->Pending.push_back(std::move(final));
    for (auto& snap : this->Pending)
    {
      snap.Step = ++this->Steps;
      this->Options.OnSnapshot(snap);
    }
    this->Pending.clear();
  }

  void StartSnapshots()
  {
    if (!this->Snapshots())
      return;
    CatalogSnapshot start = this->Capture(nullptr, 0);
    start.Step = 0;
    this->Options.OnSnapshot(start);
  }

  const AdjacencyRules& Rules;
  const SynthesisOptions& Options;
  Catalog Cat;
  const MirrorPlan* Plan;                        ///< symmetric synthesis of a half, or nullptr
  const detail::SymmetryPlan* Seams;             ///< translation/rotation: a domain, or nullptr
  std::vector<int> ExampleIndex;                 ///< resemblance: the example as label indices
  std::vector<std::array<int, 3>> WindowOffsets; ///< resemblance: window offsets but the centre
  std::vector<std::int64_t> ResemblanceCounts;
  std::vector<double> ChoiceWeights;
  std::vector<std::uint64_t> MaskScratch;
  std::vector<float> GuideWeights;       ///< [guide cell][label index]; empty: no guide
  std::vector<std::uint64_t> GuideMasks; ///< [guide cell][word]: labels with weight > 0
  std::vector<CatalogSnapshot> Pending; ///< snapshots of the current attempt

  /// Cancellation inside a block: every solver watches Stop; the main one also polls the
  /// caller's progress callback (Poll, with the fraction PollFraction gives), whose false sets
  /// Stop. A long block (Algorithm 3.1 on a large model) so stops within a fraction of a second.
  std::atomic<bool>* Stop = nullptr;
  std::unique_ptr<detail::ProgressPoll> Poll;
  std::function<double()> PollFraction;
  bool Stopped()
  {
    if (this->Poll && !this->Poll->Continue(this->PollFraction()) && this->Stop)
      this->Stop->store(true);
    return this->Stop && this->Stop->load(std::memory_order_relaxed);
  }
  std::int64_t Steps = 0;
  double FullEntropy = 0.0;
  Coord N{ { 1, 1, 1 } };
  std::vector<std::int32_t>& Model;     ///< label indices; -1 unassigned (shared)
  std::vector<std::int32_t>& Fixed;     ///< boundary label indices; -1 free (shared)
  std::vector<std::int32_t>& LastBlock; ///< block that last changed each site (shared)
  std::vector<double> WLogW;
};

} // namespace

// ---------------------------------------------------------------------------------------------
// public API
// ---------------------------------------------------------------------------------------------
std::int64_t CountBlocks(const SynthesisOptions& requested)
{
  LabelGrid::CheckDimensions(requested.Size[0], requested.Size[1], requested.Size[2]);
  SynthesisOptions options = requested;
  for (int a = 0; a < 3; ++a)
  {
    if (requested.Symmetry[static_cast<std::size_t>(a)].Enabled)
      options.Size[a] = (requested.Size[a] + 1) / 2; // the synthesized half
    const Translation& t = requested.Translate[static_cast<std::size_t>(a)];
    if (t.Enabled && t.Period > 0 && t.Period < requested.Size[a])
      options.Size[a] = t.Period; // one period
  }
  if (requested.Rotate.Enabled)
    for (int a = 0; a < 2; ++a)
      options.Size[a] = (requested.Size[a] + 1) / 2; // a quadrant
  Coord m, step;
  BlockGeometry(options, m, step);
  std::int64_t count = 1;
  for (int a = 0; a < 3; ++a)
  {
    count *= static_cast<std::int64_t>(Starts(options.Size[a], m[a], step[a]).size());
  }
  return count;
}

std::int64_t CountSnapshots(const SynthesisOptions& options)
{
  return options.SnapshotsPerBlock > 0 ? 1 + CountBlocks(options) * options.SnapshotsPerBlock : 0;
}

namespace
{
SynthesisResult SynthesizeDirect(const AdjacencyRules& rules, const SynthesisOptions& options,
  const MirrorPlan* plan, const detail::SymmetryPlan* seams)
{
  const auto start = std::chrono::steady_clock::now();
  if (options.AttemptsPerBlock < 1)
  {
    throw Error("attempts per block must be at least 1");
  }
  SharedModel shared;
  Solver solver(rules, options, plan, seams, shared);
  const Coord& n = solver.N;
  Coord m, step;
  const bool wholeModel = BlockGeometry(options, m, step);
  solver.ApplyBoundary();

  SynthesisResult result;
  SynthesisStatistics& stats = result.Statistics;
  if (!wholeModel)
  {
    stats.TrivialLabel = rules.LabelValues()[static_cast<std::size_t>(solver.TrivialStart())];
  }
  const std::vector<Block> blocks = PlanBlocks(n, m, step, stats.Phases);
  stats.Blocks = static_cast<std::int64_t>(blocks.size());

  // One block: its attempts (lines 9-34 of Algorithm 3.4), each from its own generator.
  struct Outcome
  {
    std::int64_t Empty = -1;
    int Attempts = 0;
    std::int64_t Assignments = 0;
    std::vector<std::int32_t> SavedModel, SavedLast; ///< the block before, for soft constraints
  };
  const bool soft = options.Soft.Active();
  if (soft && wholeModel)
    throw Error("soft constraints (Metropolis acceptance of block changes) need block synthesis");
  auto forEachSite = [&](const Block& block, const std::function<void(std::size_t)>& visit)
  {
    Coord p;
    for (p[2] = block.Origin[2]; p[2] < block.Origin[2] + block.Dims[2]; ++p[2])
      for (p[1] = block.Origin[1]; p[1] < block.Origin[1] + block.Dims[1]; ++p[1])
        for (p[0] = block.Origin[0]; p[0] < block.Origin[0] + block.Dims[0]; ++p[0])
          visit(static_cast<std::size_t>(solver.Index(p)));
  };
  auto runBlock = [&options, &forEachSite, soft, &shared](Solver& worker, const Block& block)
  {
    Outcome out;
    if (soft)
      forEachSite(block,
        [&](std::size_t s)
        {
          out.SavedModel.push_back(shared.Model[s]);
          out.SavedLast.push_back(shared.LastBlock[s]);
        });
    for (; out.Attempts < options.AttemptsPerBlock;)
    {
      Random rng = Random::Derived(options.Seed, static_cast<std::uint64_t>(block.Index),
        static_cast<std::uint64_t>(out.Attempts));
      ++out.Attempts;
      out.Empty = worker.RunBlock(block, rng, out.Assignments);
      if (out.Empty < 0 || worker.Stopped())
        break;
    }
    return out;
  };
  // Soft constraints: label counts of the current model and the targets, by label index.
  const int k = rules.NumberOfLabels();
  std::vector<double> target(static_cast<std::size_t>(k), -1.0);
  std::vector<std::int64_t> counts(static_cast<std::size_t>(k), 0);
  double fitness = 0.0;
  const double sites = static_cast<double>(shared.Model.size());
  auto modelGrid = [&]()
  {
    std::vector<Label> values(shared.Model.size());
    for (std::size_t i = 0; i < values.size(); ++i)
      values[i] = rules.LabelValues()[static_cast<std::size_t>(shared.Model[i])];
    return LabelGrid(n, std::move(values));
  };
  if (soft)
  {
    for (const auto& kv : options.Soft.TargetFractions)
    {
      const int b = rules.IndexOf(kv.first);
      if (b < 0)
        throw Error("the soft constraint names label " + std::to_string(kv.first) +
          ", which does not occur in the example");
      if (!(kv.second >= 0.0 && kv.second <= 1.0))
        throw Error(
          "the target fraction of label " + std::to_string(kv.first) + " is not in [0, 1]");
      target[static_cast<std::size_t>(b)] = kv.second;
    }
    if (!(options.Soft.Temperature > 0.0) || !std::isfinite(options.Soft.Temperature))
      throw Error("the soft constraints' temperature must be positive");
    for (std::int32_t b : shared.Model)
      ++counts[static_cast<std::size_t>(b)];
    if (options.Soft.Fitness)
      fitness = options.Soft.Fitness(modelGrid());
  }
  auto energy = [&](int b, std::int64_t count)
  {
    const double t = target[static_cast<std::size_t>(b)];
    return t < 0.0 ? 0.0 : sites * (double(count) / sites - t) * (double(count) / sites - t);
  };
  // Keeps or rolls back a synthesized block (2007 paper §4.2); decided in block order.
  auto decide = [&](const Block& block, const Outcome& out)
  {
    if (!soft || out.Empty >= 0)
      return true;
    std::vector<std::int64_t> delta(static_cast<std::size_t>(k), 0);
    std::size_t i = 0;
    forEachSite(block,
      [&](std::size_t s)
      {
        --delta[static_cast<std::size_t>(out.SavedModel[i++])];
        ++delta[static_cast<std::size_t>(shared.Model[s])];
      });
    double dE = 0.0;
    for (int b = 0; b < k; ++b)
      if (delta[static_cast<std::size_t>(b)] != 0)
        dE += energy(b, counts[static_cast<std::size_t>(b)] + delta[static_cast<std::size_t>(b)]) -
          energy(b, counts[static_cast<std::size_t>(b)]);
    double ratio = std::exp(-dE / options.Soft.Temperature);
    double newFitness = fitness;
    if (options.Soft.Fitness)
    {
      newFitness = options.Soft.Fitness(modelGrid());
      if (!(newFitness > 0.0) || !(fitness > 0.0))
        throw Error("the soft constraints' fitness must be positive");
      ratio *= newFitness / fitness;
    }
    Random rng =
      Random::Derived(options.Seed, static_cast<std::uint64_t>(block.Index), 0x50f7ull << 32);
    if (ratio >= 1.0 || rng.Uniform() < ratio)
    {
      for (int b = 0; b < k; ++b)
        counts[static_cast<std::size_t>(b)] += delta[static_cast<std::size_t>(b)];
      fitness = newFitness;
      return true;
    }
    i = 0;
    forEachSite(block,
      [&](std::size_t s)
      {
        shared.Model[s] = out.SavedModel[i];
        shared.LastBlock[s] = out.SavedLast[i++];
      });
    ++stats.BlocksRejected;
    return false;
  };
  auto record = [&](const Block& block, const Outcome& out)
  {
    stats.Attempts += out.Attempts;
    stats.Assignments += out.Assignments;
    if (out.Empty < 0)
    {
      ++stats.BlocksAccepted;
      return;
    }
    ++stats.BlocksFailed;
    BlockFailure f;
    f.Block = block.Index;
    f.Origin = block.Origin;
    f.EmptySite = { { out.Empty % n[0], (out.Empty / n[0]) % n[1], out.Empty / (n[0] * n[1]) } };
    f.Attempts = out.Attempts;
    stats.Failures.push_back(f);
  };

  // Threads: blocks of a phase never touch, so they run concurrently; each block's result
  // depends only on the seed and its surroundings, which no block of its phase changes. The
  // model is therefore the same for any number of threads. Snapshots need one thread.
  // More threads than cores only costs memory (a solver each): clamp to the cores.
  const unsigned cores = std::max(1u, std::thread::hardware_concurrency());
  unsigned threads =
    options.Threads > 0 ? std::min(static_cast<unsigned>(options.Threads), cores) : cores;
  if (solver.Snapshots() || blocks.size() < 2 || (seams && !seams->Arcs.Empty()))
    threads = 1; // seams link blocks of one phase
  stats.Threads = static_cast<int>(threads);
  // Processes: each runs its share of a phase, then all exchange the blocks' labels.
  const bool distributed = options.Exchange.Active() && !solver.Snapshots() &&
    !(seams && !seams->Arcs.Empty());
  const std::size_t processes =
    distributed ? static_cast<std::size_t>(options.Exchange.Processes) : 1;
  const std::size_t rank = distributed ? static_cast<std::size_t>(options.Exchange.Rank) : 0;
  if (distributed && (options.Exchange.Rank < 0 || options.Exchange.Rank >= options.Exchange.Processes))
    throw Error("block exchange: rank " + std::to_string(options.Exchange.Rank) + " of " +
      std::to_string(options.Exchange.Processes) + " processes");
  stats.Processes = static_cast<int>(processes);
  std::atomic<bool> stop{ false };
  solver.Stop = &stop;
  std::vector<std::unique_ptr<Solver>> workers;
  for (unsigned t = 1; t < threads; ++t)
  {
    workers.push_back(std::make_unique<Solver>(rules, options, plan, seams, shared));
    workers.back()->Stop = &stop;
  }

  // The all-gather of a phase: per block run here, its outcome and its sites' labels; the
  // blocks run elsewhere are written into the model (their previous labels saved first for the
  // soft constraints). Returns whether any process was cancelled.
  auto exchange = [&](std::size_t first, std::size_t last, const std::vector<std::size_t>& mine,
                    std::vector<Outcome>& outcomes, bool cancelledHere)
  {
    std::vector<char> bytes;
    auto put = [&bytes](std::int64_t v)
    {
      char b[8];
      std::memcpy(b, &v, 8);
      bytes.insert(bytes.end(), b, b + 8);
    };
    put(cancelledHere ? 1 : 0);
    for (std::size_t i : mine)
    {
      const Outcome& out = outcomes[i - first];
      put(static_cast<std::int64_t>(i));
      put(out.Empty);
      put(out.Attempts);
      put(out.Assignments);
      forEachSite(blocks[i],
        [&](std::size_t site)
        {
          put(shared.Model[site]);
          put(shared.LastBlock[site]);
        });
    }
    const auto all = options.Exchange.AllGather(bytes);
    if (all.size() != processes)
      throw Error("block exchange: expected results from " + std::to_string(processes) +
        " processes, got " + std::to_string(all.size()));
    bool anyCancelled = false;
    for (std::size_t p = 0; p < all.size(); ++p)
    {
      const std::vector<char>& in = all[p];
      std::size_t at = 0;
      auto get = [&]()
      {
        if (at + 8 > in.size())
          throw Error("block exchange: a truncated result from process " + std::to_string(p));
        std::int64_t v;
        std::memcpy(&v, in.data() + at, 8);
        at += 8;
        return v;
      };
      anyCancelled = get() != 0 || anyCancelled;
      while (at < in.size())
      {
        const auto i = static_cast<std::size_t>(get());
        if (i < first || i >= last)
          throw Error("block exchange: process " + std::to_string(p) +
            " sent a block of another phase");
        Outcome& out = outcomes[i - first];
        out.Empty = get();
        out.Attempts = static_cast<int>(get());
        out.Assignments = get();
        const bool remote = p != rank;
        if (remote && soft)
        {
          out.SavedModel.clear();
          out.SavedLast.clear();
        }
        forEachSite(blocks[i],
          [&](std::size_t site)
          {
            const auto label = static_cast<std::int32_t>(get());
            const auto lastBlock = static_cast<std::int32_t>(get());
            if (!remote)
              return;
            if (soft)
            {
              out.SavedModel.push_back(shared.Model[site]);
              out.SavedLast.push_back(shared.LastBlock[site]);
            }
            shared.Model[site] = label;
            shared.LastBlock[site] = lastBlock;
          });
      }
    }
    return anyCancelled;
  };

  solver.StartSnapshots();
  bool cancelled = false, cancelRequested = false;
  std::size_t done = 0;
  if (options.Progress)
  {
    solver.Poll = std::make_unique<detail::ProgressPoll>(options.Progress);
    solver.PollFraction = [&done, &blocks]() { return double(done) / double(blocks.size()); };
  }
  for (std::size_t first = 0; first < blocks.size() && !cancelled;)
  {
    std::size_t last = first;
    while (last < blocks.size() && blocks[last].Phase == blocks[first].Phase)
      ++last;
    std::vector<Outcome> outcomes(last - first);
    if (threads == 1 && !distributed)
    {
      for (std::size_t i = first; i < last && !cancelled; ++i)
      {
        outcomes[i - first] = runBlock(solver, blocks[i]);
        if (outcomes[i - first].Empty >= 0 || !decide(blocks[i], outcomes[i - first]))
          solver.Pending.clear(); // the block keeps its previous labels: repeat that state
        solver.CommitSnapshots(stats.Assignments + outcomes[i - first].Assignments);
        record(blocks[i], outcomes[i - first]);
        ++done;
        cancelled = stop || (options.Progress && !options.Progress(double(done) / double(blocks.size())));
      }
    }
    else
    {
      // This process's blocks of the phase (all of them without distribution).
      std::vector<std::size_t> mine;
      for (std::size_t i = first; i < last; ++i)
        if ((i - first) % processes == rank)
          mine.push_back(i);
      std::atomic<std::size_t> next{ 0 };
      std::vector<std::thread> pool;
      auto work = [&](Solver& worker)
      {
        for (std::size_t j; (j = next++) < mine.size();)
          outcomes[mine[j] - first] = runBlock(worker, blocks[mine[j]]);
      };
      for (auto& w : workers)
      {
        try
        {
          pool.emplace_back(work, std::ref(*w));
        }
        catch (const std::system_error&)
        {
          break; // no more threads to be had: the others and this one share the blocks
        }
      }
      work(solver);
      for (auto& t : pool)
        t.join();
      if (distributed) // every process stops at the same phase
        cancelled = exchange(first, last, mine, outcomes, cancelRequested);
      for (std::size_t i = first; i < last; ++i)
      {
        decide(blocks[i], outcomes[i - first]); // in block order: deterministic
        record(blocks[i], outcomes[i - first]);
      }
      done += last - first;
      const bool stopHere =
        stop || (options.Progress && !options.Progress(double(done) / double(blocks.size())));
      if (distributed)
        cancelRequested = cancelRequested || stopHere;
      else
        cancelled = stopHere;
    }
    first = last;
  }
  stats.Seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

  if (cancelled)
  {
    result.Success = false;
    result.Message = "cancelled";
    return result;
  }
  if (wholeModel && stats.BlocksFailed > 0)
  {
    // Algorithm 3.1 failed: report it, never return the partial model.
    result.Success = false;
    result.Message = "whole-model synthesis (Algorithm 3.1) failed " +
      std::to_string(options.AttemptsPerBlock) + " time(s); the catalog became empty at site " +
      Format(stats.Failures.front().EmptySite) +
      " in the last attempt. Try another seed, more attempts, or block synthesis";
    return result;
  }
  std::vector<Label> values(solver.Model.size());
  for (std::size_t s = 0; s < values.size(); ++s)
  {
    values[s] = rules.LabelValues()[static_cast<std::size_t>(solver.Model[s])];
  }
  result.Model = LabelGrid(n, std::move(values));
  result.LastBlock = std::move(solver.LastBlock);
  result.Success = true;
  result.Message = wholeModel ? "whole-model synthesis succeeded"
                              : std::to_string(stats.BlocksAccepted) + " of " +
      std::to_string(stats.Blocks) + " blocks synthesized, " + std::to_string(stats.BlocksFailed) +
      " left at their previous labels" +
      (stats.BlocksRejected
          ? ", " + std::to_string(stats.BlocksRejected) + " rolled back by the soft constraints"
          : std::string());
  return result;
}

/**
 * A part of the output (a mirrored half; a period or a quadrant) spread over the whole output:
 * output site q shows part site Source(q) (linear index, x fastest) with its label value mapped
 * by Image(q, value).
 */
struct Unfolding
{
  Coord Full{ { 1, 1, 1 } };
  std::function<std::size_t(const Coord&)> Source;
  std::function<Label(const Coord&, Label)> Image;

  template <class Visit>
  void ForEach(Visit&& visit) const
  {
    Coord q;
    std::size_t i = 0;
    for (q[2] = 0; q[2] < this->Full[2]; ++q[2])
      for (q[1] = 0; q[1] < this->Full[1]; ++q[1])
        for (q[0] = 0; q[0] < this->Full[0]; ++q[0], ++i)
          visit(i, q, this->Source(q));
  }

  CatalogSnapshot Snapshot(const CatalogSnapshot& part) const
  {
    CatalogSnapshot out;
    out.Step = part.Step;
    out.Block = part.Block;
    out.Assignments = part.Assignments;
    const auto n = static_cast<std::size_t>(this->Full[0] * this->Full[1] * this->Full[2]);
    out.CatalogSize.resize(n);
    out.Entropy.resize(n);
    out.Labels.resize(n);
    this->ForEach(
      [&](std::size_t i, const Coord& q, std::size_t j)
      {
        out.CatalogSize[i] = part.CatalogSize[j];
        out.Entropy[i] = part.Entropy[j];
        const Label v = part.Labels[j];
        out.Labels[i] = v == CatalogSnapshot::Undecided ? v : this->Image(q, v);
      });
    return out;
  }

  /// Replaces the part's model and LastBlock in @p r by the whole output's.
  void Apply(SynthesisResult& r) const
  {
    LabelGrid model(this->Full[0], this->Full[1], this->Full[2]);
    std::vector<std::int32_t> lastBlock(static_cast<std::size_t>(model.NumberOfSites()));
    this->ForEach(
      [&](std::size_t i, const Coord& q, std::size_t j)
      {
        model.Data()[i] = this->Image(q, r.Model.Data()[j]);
        lastBlock[i] = r.LastBlock[j];
      });
    r.Model = std::move(model);
    r.LastBlock = std::move(lastBlock);
  }
};

/// Synthesizes @p part (the options of a half, period or quadrant) and spreads it by
/// @p unfolding; the snapshots @p options asks for are spread too.
SynthesisResult SynthesizePart(const AdjacencyRules& rules, const SynthesisOptions& options,
  SynthesisOptions part, const MirrorPlan* mirror, const detail::SymmetryPlan* seams,
  const Unfolding& unfolding)
{
  if (options.OnSnapshot)
    part.OnSnapshot = [&](const CatalogSnapshot& s) { options.OnSnapshot(unfolding.Snapshot(s)); };
  SynthesisResult r = SynthesizeDirect(rules, part, mirror, seams);
  if (r.Success)
    unfolding.Apply(r);
  return r;
}

/// Translation or rotation symmetry: synthesizes the plan's domain with its seams, then repeats
/// (turns) it over the output with the labels mapped.
SynthesisResult SynthesizeSeamSymmetric(
  const AdjacencyRules& rules, const SynthesisOptions& options)
{
  const auto plan = detail::PlanSymmetry(rules, options);
  const auto& values = rules.LabelValues();
  Unfolding unfolding;
  unfolding.Full = plan->Full;
  unfolding.Source = [&plan](const Coord& q) { return static_cast<std::size_t>(plan->Source(q)); };
  unfolding.Image = [&](const Coord& q, Label v)
  { return values[static_cast<std::size_t>(plan->Image(q, rules.IndexOf(v)))]; };
  SynthesisResult r =
    SynthesizePart(rules, options, plan->DomainOptions, nullptr, plan.get(), unfolding);
  if (r.Success)
    r.Message += plan->Rotate ? " (turned copies of a quadrant)" : " (repeated periods)";
  return r;
}

} // namespace

namespace
{
/// Refuses, before anything is allocated, a model whose memory would exceed what is available:
/// per site the model, the last-block record and the caller's copies (about 24 bytes), plus a
/// catalog (two bit sets of the labels and bookkeeping) over each block being solved at once.
void CheckSynthesisMemory(const AdjacencyRules& rules, const SynthesisOptions& o)
{
  std::uint64_t sites = 1, blockSites = 1;
  for (std::size_t a = 0; a < 3; ++a)
  {
    const auto n = static_cast<std::uint64_t>(o.Size[a]);
    sites *= n;
    const auto m = static_cast<std::uint64_t>(o.BlockSize[a]);
    blockSites *= (m == 0 || m > n) ? n : m;
  }
  const auto perCatalogSite = static_cast<std::uint64_t>(rules.Words()) * 16 + 24;
  const std::uint64_t catalogs =
    blockSites * (blockSites < sites ? std::max(1u, std::thread::hardware_concurrency()) : 1u);
  CheckMemory(sites * 24 + catalogs * perCatalogSite,
    "a " + std::to_string(o.Size[0]) + " x " + std::to_string(o.Size[1]) + " x " +
      std::to_string(o.Size[2]) + " model of " + std::to_string(rules.NumberOfLabels()) +
      " labels");
}
} // namespace

SynthesisResult Synthesize(const AdjacencyRules& rules, const SynthesisOptions& options)
{
  LabelGrid::CheckDimensions(options.Size[0], options.Size[1], options.Size[2]);
  CheckSynthesisMemory(rules, options);
  if (AnyMirror(options) && detail::AnySeamSymmetry(options))
    throw Error("mirror symmetry cannot be combined with translation or rotation symmetry");
  if (!AnyMirror(options))
  {
    return detail::AnySeamSymmetry(options) ? SynthesizeSeamSymmetric(rules, options)
                                    : SynthesizeDirect(rules, options, nullptr, nullptr);
  }
  const MirrorPlan plan = PlanMirror(rules, options);
  const auto& values = rules.LabelValues();
  // Output site q folds onto half site p, mirrored over the axes where q lies past the middle.
  auto fold = [&plan](const Coord& q, Coord& p)
  {
    int axes = 0;
    p = q;
    for (int a = 0; a < 3; ++a)
      if (plan.Axes[static_cast<std::size_t>(a)] && q[a] >= plan.Half[a])
      {
        p[a] = plan.Full[a] - 1 - q[a];
        axes |= 1 << a;
      }
    return axes;
  };
  Unfolding unfolding;
  unfolding.Full = plan.Full;
  unfolding.Source = [&](const Coord& q)
  {
    Coord p;
    fold(q, p);
    return static_cast<std::size_t>(p[0] + plan.Half[0] * (p[1] + plan.Half[1] * p[2]));
  };
  unfolding.Image = [&](const Coord& q, Label v)
  {
    Coord p;
    return values[static_cast<std::size_t>(plan.Image(rules.IndexOf(v), fold(q, p)))];
  };
  SynthesisResult r = SynthesizePart(rules, options, plan.HalfOptions, &plan, nullptr, unfolding);
  if (!r.Success)
  {
    return r;
  }
  r.Message += " (mirrored)";
  return r;
}

} // namespace msynth
