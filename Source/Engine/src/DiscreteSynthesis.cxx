// SPDX-License-Identifier: BSD-3-Clause
#include "msynth/DiscreteSynthesis.h"

#include "msynth/Catalog.h"
#include "msynth/Error.h"
#include "msynth/Random.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <queue>

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

/// The solver state shared by all blocks.
class Solver
{
public:
  Solver(const AdjacencyRules& rules, const SynthesisOptions& options)
    : Rules(rules)
    , Options(options)
    , Cat(rules)
  {
    this->N = options.Size;
    LabelGrid::CheckDimensions(this->N[0], this->N[1], this->N[2]);
    const auto sites = static_cast<std::size_t>(this->N[0] * this->N[1] * this->N[2]);
    this->Model.assign(sites, -1);
    this->Fixed.assign(sites, -1);
    this->LastBlock.assign(sites, -1);
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
    this->GuideDims = d;
  }

  bool HasGuide() const { return !this->GuideWeights.empty(); }

  /// The guide cell of model site @p p.
  std::int64_t GuideCell(const Coord& p) const
  {
    std::int64_t c[3];
    for (int a = 0; a < 3; ++a)
    {
      // floor((p + 1/2) · D / N) in integers: (2p + 1) · D / (2N).
      c[a] =
        std::min(this->GuideDims[a] - 1, ((2 * p[a] + 1) * this->GuideDims[a]) / (2 * this->N[a]));
    }
    return c[0] + this->GuideDims[0] * (c[1] + this->GuideDims[1] * c[2]);
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
    return t;
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
        if (this->HasGuide() &&
          !cat.Keep(local,
            this->GuideMasks.data() +
              static_cast<std::size_t>(this->GuideCell(p)) * this->Rules.Words()))
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
    }
    std::int64_t empty = cat.Propagate();
    if (empty >= 0)
      return fail(empty);

    // Assign the free sites (lines 19-29), in the chosen order.
    auto choose = [&](std::int64_t local)
    {
      double total = 0.0;
      const std::uint64_t* dom = cat.Domain(local);
      for (int w = 0; w < this->Rules.Words(); ++w)
        for (std::uint64_t bits = dom[w]; bits; bits &= bits - 1)
          total += this->Weight(w * 64 + __builtin_ctzll(bits));
      double r = rng.Uniform() * total;
      int last = -1;
      for (int w = 0; w < this->Rules.Words(); ++w)
        for (std::uint64_t bits = dom[w]; bits; bits &= bits - 1)
        {
          last = w * 64 + __builtin_ctzll(bits);
          r -= this->Weight(last);
          if (r < 0.0)
            return last;
        }
      return last; // rounding: the last possible label
    };
    auto assign = [&](std::int64_t local) -> std::int64_t
    {
      if (cat.Count(local) == 0)
        return local;
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
  std::vector<float> GuideWeights;       ///< [guide cell][label index]; empty: no guide
  std::vector<std::uint64_t> GuideMasks; ///< [guide cell][word]: labels with weight > 0
  Coord GuideDims{ { 1, 1, 1 } };
  std::vector<CatalogSnapshot> Pending; ///< snapshots of the current attempt
  std::int64_t Steps = 0;
  double FullEntropy = 0.0;
  Coord N{ { 1, 1, 1 } };
  std::vector<std::int32_t> Model; ///< label indices; -1 unassigned
  std::vector<std::int32_t> Fixed; ///< boundary label indices; -1 free
  std::vector<std::int32_t> LastBlock;
  std::vector<double> WLogW;
};

} // namespace

// ---------------------------------------------------------------------------------------------
// public API
// ---------------------------------------------------------------------------------------------
std::int64_t CountBlocks(const SynthesisOptions& options)
{
  LabelGrid::CheckDimensions(options.Size[0], options.Size[1], options.Size[2]);
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

SynthesisResult Synthesize(const AdjacencyRules& rules, const SynthesisOptions& options)
{
  const auto start = std::chrono::steady_clock::now();
  if (options.AttemptsPerBlock < 1)
  {
    throw Error("attempts per block must be at least 1");
  }
  Solver solver(rules, options);
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

  solver.StartSnapshots();
  bool cancelled = false;
  for (std::size_t i = 0; i < blocks.size() && !cancelled; ++i)
  {
    const Block& block = blocks[i];
    std::int64_t empty = -1;
    int attempt = 0;
    for (; attempt < options.AttemptsPerBlock; ++attempt)
    {
      Random rng = Random::Derived(
        options.Seed, static_cast<std::uint64_t>(block.Index), static_cast<std::uint64_t>(attempt));
      ++stats.Attempts;
      empty = solver.RunBlock(block, rng, stats.Assignments);
      if (empty < 0)
        break;
    }
    if (empty >= 0)
    {
      solver.Pending.clear(); // the block keeps its previous labels: repeat that state
    }
    solver.CommitSnapshots(stats.Assignments);
    if (empty < 0)
    {
      ++stats.BlocksAccepted;
    }
    else
    {
      ++stats.BlocksFailed;
      BlockFailure f;
      f.Block = block.Index;
      f.Origin = block.Origin;
      f.EmptySite = { { empty % n[0], (empty / n[0]) % n[1], empty / (n[0] * n[1]) } };
      f.Attempts = attempt;
      stats.Failures.push_back(f);
    }
    if (options.Progress && !options.Progress(double(i + 1) / double(blocks.size())))
    {
      cancelled = true;
    }
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
      " left at their previous labels";
  return result;
}

} // namespace msynth
