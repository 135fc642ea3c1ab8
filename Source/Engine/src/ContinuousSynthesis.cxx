// SPDX-License-Identifier: BSD-3-Clause
#include "msynth/ContinuousSynthesis.h"

#include "msynth/Error.h"

#include "ProgressPoll.h"
#include "msynth/Random.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <map>
#include <set>
#include <tuple>

namespace msynth
{

ArrangementRules::ArrangementRules(
  const PolyhedralAnalysis& analysis, const PlaneArrangement& arrangement)
  : Arrangement(arrangement)
{
  const PlaneFamilySet& set = arrangement.Families();
  if (set.AllNormals() != analysis.Families().AllNormals())
  {
    throw Error("the plane arrangement was built for other plane families than the example's");
  }
  const int k = analysis.NumberOfLabels();
  const int directions = arrangement.NumberOfDirections();
  this->Allocate(k, std::max(directions, 1));
  this->Empty = analysis.Find(NeighbourhoodLabel::Constant(0));
  if (this->Empty < 0)
  {
    throw Error("the example has no empty space around it");
  }
  for (const auto& info : analysis.Labels())
  {
    std::uint64_t mask = 0;
    for (int f : info.Label.Families)
    {
      mask |= std::uint64_t(1) << f;
    }
    this->LabelFamilies.push_back(mask);
  }
  std::map<NeighbourhoodLabel, int> ids;
  const int emptyId = ids.emplace(NeighbourhoodLabel::Constant(0), 0).first->second;
  this->Evaluations.resize(static_cast<std::size_t>(directions) * k);
  for (int d = 0; d < directions; ++d)
  {
    for (int a = 0; a < k; ++a)
    {
      const NeighbourhoodLabel e = analysis.Label(a).Label.Evaluate(set, arrangement.Direction(d));
      const int id = ids.emplace(e, static_cast<int>(ids.size())).first->second;
      this->Evaluations[static_cast<std::size_t>(d) * k + a] = id;
    }
  }
  const int w = this->Words();
  this->EmptyToward.assign(static_cast<std::size_t>(directions) * w, 0);
  std::vector<std::vector<int>> bucket(ids.size());
  for (int d = 0; d < directions; ++d)
  {
    // Labels b at the far end of an edge along d see it along the opposite class d ^ 1.
    for (auto& b : bucket)
    {
      b.clear();
    }
    for (int b = 0; b < k; ++b)
    {
      bucket[static_cast<std::size_t>(this->EvaluationId(d ^ 1, b))].push_back(b);
    }
    for (int a = 0; a < k; ++a)
    {
      const int id = this->EvaluationId(d, a);
      for (int b : bucket[static_cast<std::size_t>(id)])
      {
        this->AllowOne(d, a, b);
      }
      if (id == emptyId)
      {
        this->EmptyToward[static_cast<std::size_t>(d) * w + (a >> 6)] |= std::uint64_t(1) << (a & 63);
      }
    }
  }
  this->Finish();
}

void ArrangementRules::InitialDomain(std::int64_t v, std::uint64_t* out) const
{
  const int w = this->Words();
  std::fill(out, out + w, 0);
  const std::uint64_t mask = this->Arrangement.FamilyMask(v);
  for (int a = 0; a < this->NumberOfLabels(); ++a)
  {
    if ((this->LabelFamilies[static_cast<std::size_t>(a)] & ~mask) == 0)
    {
      out[a >> 6] |= std::uint64_t(1) << (a & 63);
    }
  }
  for (const auto* l = this->Arrangement.LinksBegin(v); l != this->Arrangement.LinksEnd(v); ++l)
  {
    if (l->Vertex < 0)
    {
      const std::uint64_t* e = this->EmptyToward.data() + static_cast<std::size_t>(l->Direction) * w;
      for (int i = 0; i < w; ++i)
      {
        out[i] &= e[i];
      }
    }
  }
}

int ArrangementRules::InitialCount(std::int64_t v) const
{
  std::vector<std::uint64_t> bits(static_cast<std::size_t>(this->Words()));
  this->InitialDomain(v, bits.data());
  int n = 0;
  for (auto b : bits)
  {
    n += __builtin_popcountll(b);
  }
  return n;
}

namespace
{

/// Vertices grouped into overlapping blocks: cells of half the block edge, a block is 2×2×2 cells.
struct BlockLayout
{
  std::array<std::int64_t, 3> Cells{ { 1, 1, 1 } };
  std::vector<std::vector<std::int64_t>> CellVertices;
  std::array<std::int64_t, 3> Blocks{ { 1, 1, 1 } };

  BlockLayout(const PlaneArrangement& arrangement, double edge)
  {
    const auto& p = arrangement.Parameters();
    const int dims = arrangement.Planar() ? 2 : 3;
    const double half = edge / 2;
    std::array<double, 3> lo{};
    for (int c = 0; c < 3; ++c)
    {
      lo[static_cast<std::size_t>(c)] = p.Origin[static_cast<std::size_t>(c)] +
        p.Quantum * static_cast<double>(p.BoxLow[c]);
      if (c < dims && edge > 0)
      {
        const double extent = p.Quantum * static_cast<double>(p.BoxHigh[c] - p.BoxLow[c]);
        this->Cells[static_cast<std::size_t>(c)] =
          std::max<std::int64_t>(1, static_cast<std::int64_t>(std::ceil(extent / half - 1e-9)));
        this->Blocks[static_cast<std::size_t>(c)] =
          std::max<std::int64_t>(1, this->Cells[static_cast<std::size_t>(c)] - 1);
      }
    }
    this->CellVertices.resize(static_cast<std::size_t>(this->Cells[0] * this->Cells[1] * this->Cells[2]));
    for (std::int64_t v = 0; v < arrangement.NumberOfVertices(); ++v)
    {
      std::array<std::int64_t, 3> cell{ { 0, 0, 0 } };
      for (int c = 0; c < dims; ++c)
      {
        if (edge > 0)
        {
          const double t = (arrangement.Position(v)[static_cast<std::size_t>(c)] - lo[static_cast<std::size_t>(c)]) / half;
          cell[static_cast<std::size_t>(c)] = std::clamp<std::int64_t>(
            static_cast<std::int64_t>(std::floor(t)), 0, this->Cells[static_cast<std::size_t>(c)] - 1);
        }
      }
      this->CellVertices[static_cast<std::size_t>(cell[0] + this->Cells[0] * (cell[1] + this->Cells[1] * cell[2]))].push_back(v);
    }
  }

  std::int64_t NumberOfBlocks() const { return this->Blocks[0] * this->Blocks[1] * this->Blocks[2]; }

  /// Vertices of block @p b in ascending (scan) order.
  std::vector<std::int64_t> Vertices(std::int64_t b) const
  {
    const std::int64_t bx = b % this->Blocks[0], by = (b / this->Blocks[0]) % this->Blocks[1],
                       bz = b / (this->Blocks[0] * this->Blocks[1]);
    std::vector<std::int64_t> out;
    for (std::int64_t z = bz; z < std::min(bz + 2, this->Cells[2]); ++z)
    {
      for (std::int64_t y = by; y < std::min(by + 2, this->Cells[1]); ++y)
      {
        for (std::int64_t x = bx; x < std::min(bx + 2, this->Cells[0]); ++x)
        {
          const auto& c = this->CellVertices[static_cast<std::size_t>(x + this->Cells[0] * (y + this->Cells[1] * z))];
          out.insert(out.end(), c.begin(), c.end());
        }
      }
    }
    std::sort(out.begin(), out.end());
    return out;
  }
};

/// A label of @p domain: uniformly, or proportionally to @p weights when not empty.
int PickLabel(const std::uint64_t* domain, int words, int count, const std::vector<double>& weights,
  Random& rng)
{
  if (weights.empty())
  {
    auto r = static_cast<int>(rng.Below(static_cast<std::uint64_t>(count)));
    for (int w = 0; w < words; ++w)
    {
      for (std::uint64_t bits = domain[w]; bits; bits &= bits - 1)
      {
        if (r-- == 0)
        {
          return w * 64 + __builtin_ctzll(bits);
        }
      }
    }
    return -1;
  }
  double total = 0;
  int last = -1;
  for (int w = 0; w < words; ++w)
  {
    for (std::uint64_t bits = domain[w]; bits; bits &= bits - 1)
    {
      total += weights[static_cast<std::size_t>(w * 64 + __builtin_ctzll(bits))];
    }
  }
  double r = rng.Uniform() * total;
  for (int w = 0; w < words; ++w)
  {
    for (std::uint64_t bits = domain[w]; bits; bits &= bits - 1)
    {
      last = w * 64 + __builtin_ctzll(bits);
      r -= weights[static_cast<std::size_t>(last)];
      if (r < 0)
      {
        return last;
      }
    }
  }
  return last;
}

/// The undecided vertices of a block in the order they are labelled.
class SiteQueue
{
public:
  SiteQueue(SiteOrder order, std::int64_t n, Random& rng)
    : Order(order)
    , Counts(static_cast<std::size_t>(n), 0)
    , Key(static_cast<std::size_t>(n))
  {
    for (std::int64_t i = 0; i < n; ++i)
    {
      this->Key[static_cast<std::size_t>(i)] = order == SiteOrder::ScanLine ? static_cast<std::uint64_t>(i) : rng.Next();
    }
  }

  void Update(std::int64_t i, int count)
  {
    auto& old = this->Counts[static_cast<std::size_t>(i)];
    if (old > 1)
    {
      this->Pending.erase({ this->Order == SiteOrder::MinimumEntropy ? old : 0, this->Key[static_cast<std::size_t>(i)], i });
    }
    old = count;
    if (count > 1)
    {
      this->Pending.insert({ this->Order == SiteOrder::MinimumEntropy ? count : 0, this->Key[static_cast<std::size_t>(i)], i });
    }
  }

  /// The next undecided vertex, or -1.
  std::int64_t Next() const
  {
    return this->Pending.empty() ? -1 : std::get<2>(*this->Pending.begin());
  }
  std::int64_t Remaining() const { return static_cast<std::int64_t>(this->Pending.size()); }

private:
  SiteOrder Order;
  std::vector<int> Counts;
  std::vector<std::uint64_t> Key;
  std::set<std::tuple<int, std::uint64_t, std::int64_t>> Pending;
};

} // namespace

ContinuousSynthesisResult SynthesizeContinuous(const PolyhedralAnalysis& analysis,
  const PlaneArrangement& arrangement, const ContinuousSynthesisOptions& options)
{
  const auto start = std::chrono::steady_clock::now();
  const ArrangementRules rules(analysis, arrangement);
  const std::int64_t n = arrangement.NumberOfVertices();
  const int k = rules.NumberOfLabels();
  const int words = rules.Words();
  if (!std::isfinite(options.BlockSize) || !(options.BlockSize == 0 || options.BlockSize >= 1))
  {
    throw Error("continuous synthesis: the block size is measured in plane spacings and must be "
                "0 (the whole model at once) or at least 1, not " +
      std::to_string(options.BlockSize));
  }
  if (options.Attempts < 1)
  {
    throw Error("continuous synthesis: at least one attempt is needed");
  }
  ContinuousSynthesisResult result;
  result.Labels.assign(static_cast<std::size_t>(n), rules.EmptyLabel());

  double reference = 0;
  for (int f = 0; f < arrangement.Families().Size(); ++f)
  {
    reference = std::max(reference, arrangement.Parameters().Spacing(arrangement.Families(), f));
  }
  const bool whole = options.BlockSize == 0;
  detail::ProgressPoll poll(options.Progress);
  const BlockLayout layout(arrangement, whole ? 0.0 : options.BlockSize * reference);
  const std::int64_t blocks = whole ? 1 : layout.NumberOfBlocks();
  result.Blocks = blocks;

  std::vector<std::uint64_t> initial(static_cast<std::size_t>(n) * words);
  for (std::int64_t v = 0; v < n; ++v)
  {
    rules.InitialDomain(v, initial.data() + static_cast<std::size_t>(v) * words);
  }

  std::vector<double> weights;
  if (options.Choice == LabelChoice::Frequency)
  {
    for (const auto& info : analysis.Labels())
    {
      weights.push_back(static_cast<double>(std::max<std::int64_t>(info.Occurrences, 1)));
    }
  }
  else if (options.Choice != LabelChoice::Uniform)
  {
    throw Error("continuous synthesis: only uniform and frequency-weighted label choice are available");
  }
  std::vector<std::int32_t> localOf(static_cast<std::size_t>(n), -1);
  LabelDomains domains;
  std::int64_t step = 0;
  const auto capture = [&](std::int64_t block, const std::vector<std::int64_t>* active)
  {
    ContinuousSnapshot s;
    s.Block = block;
    s.Assignments = result.Assignments;
    s.CatalogSize.assign(static_cast<std::size_t>(n), 1);
    s.Labels = result.Labels;
    if (block < 0) // the catalog before anything is chosen
    {
      for (std::int64_t v = 0; v < n; ++v)
      {
        int c = 0;
        for (int i = 0; i < words; ++i)
        {
          c += __builtin_popcountll(initial[static_cast<std::size_t>(v) * words + i]);
        }
        s.CatalogSize[static_cast<std::size_t>(v)] = c;
        s.Labels[static_cast<std::size_t>(v)] = -1;
      }
    }
    if (active)
    {
      for (std::size_t i = 0; i < active->size(); ++i)
      {
        const auto v = static_cast<std::size_t>((*active)[i]);
        const int c = domains.Count(static_cast<std::int64_t>(i));
        s.CatalogSize[v] = c;
        s.Labels[v] = c == 1 ? domains.Single(static_cast<std::int64_t>(i)) : -1;
      }
    }
    s.Entropy.resize(s.CatalogSize.size());
    for (std::size_t i = 0; i < s.CatalogSize.size(); ++i)
    {
      s.Entropy[i] = s.CatalogSize[i] > 0 ? static_cast<float>(std::log2(s.CatalogSize[i])) : 0.0f;
    }
    return s;
  };
  const auto emit = [&](ContinuousSnapshot s)
  {
    s.Step = step++;
    options.OnSnapshot(s);
  };
  if (options.Snapshots > 0 && options.OnSnapshot)
  {
    emit(capture(-1, nullptr));
  }

  std::string lastFailure;
  for (std::int64_t b = 0; b < blocks; ++b)
  {
    std::vector<std::int64_t> verts;
    if (whole)
    {
      verts.resize(static_cast<std::size_t>(n));
      for (std::int64_t v = 0; v < n; ++v)
      {
        verts[static_cast<std::size_t>(v)] = v;
      }
    }
    else
    {
      verts = layout.Vertices(b);
    }
    const auto m = static_cast<std::int64_t>(verts.size());
    for (std::int64_t i = 0; i < m; ++i)
    {
      localOf[static_cast<std::size_t>(verts[static_cast<std::size_t>(i)])] = static_cast<std::int32_t>(i);
    }
    const auto neighbours = [&](std::int64_t local, auto&& visit)
    {
      const std::int64_t v = verts[static_cast<std::size_t>(local)];
      for (const auto* l = arrangement.LinksBegin(v); l != arrangement.LinksEnd(v); ++l)
      {
        if (l->Vertex >= 0)
        {
          const std::int32_t u = localOf[static_cast<std::size_t>(l->Vertex)];
          if (u >= 0 && !visit(u, l->Direction))
          {
            return;
          }
        }
      }
    };
    bool solved = false;
    std::vector<ContinuousSnapshot> pending;
    ContinuousSnapshot blockStart;
    for (int attempt = 0; attempt < options.Attempts && !solved; ++attempt)
    {
      ++result.Attempts;
      pending.clear();
      Random rng = Random::Derived(options.Seed, static_cast<std::uint64_t>(b), static_cast<std::uint64_t>(attempt));
      std::vector<std::uint64_t> startSets(static_cast<std::size_t>(m) * words);
      for (std::int64_t i = 0; i < m; ++i)
      {
        std::copy_n(initial.data() + static_cast<std::size_t>(verts[static_cast<std::size_t>(i)]) * words, words,
          startSets.data() + static_cast<std::size_t>(i) * words);
      }
      domains.Reset(m, k, std::move(startSets));
      bool ok = true;
      for (std::int64_t i = 0; i < m && ok; ++i)
      {
        const std::int64_t v = verts[static_cast<std::size_t>(i)];
        for (const auto* l = arrangement.LinksBegin(v); l != arrangement.LinksEnd(v); ++l)
        {
          if (l->Vertex >= 0 && localOf[static_cast<std::size_t>(l->Vertex)] < 0)
          {
            // A fixed neighbour w: u is reached from w along the opposite direction.
            ok = domains.Keep(i, rules.Compatible(l->Direction ^ 1,
                                   result.Labels[static_cast<std::size_t>(l->Vertex)])) &&
              ok;
          }
        }
      }
      std::int64_t empty = ok ? domains.Propagate(rules, neighbours) : 0;
      if (!whole && options.Snapshots > 0 && options.OnSnapshot && empty < 0)
      {
        blockStart = capture(b, &verts); // the block's catalog, the rest of the model fixed
      }
      std::int64_t assigned = 0;
      int taken = 0;
      std::vector<std::uint64_t> exclude(static_cast<std::size_t>(words));
      SiteQueue queue(options.Order, m, rng);
      for (std::int64_t i = 0; i < m; ++i)
      {
        queue.Update(i, domains.Count(i));
      }
      domains.ClearChanged();
      // A label whose propagation empties a set is removed and another tried (one level of
      // backtracking); the attempt fails only when no label is left at the vertex.
      domains.Record(true);
      while (empty < 0)
      {
        // Cancellation inside a block.
        if ((assigned & 1023) == 0 &&
          !poll.Continue(static_cast<double>(b) / static_cast<double>(blocks)))
        {
          throw Error("continuous synthesis was cancelled");
        }
        const std::int64_t i = queue.Next();
        if (i < 0)
        {
          break;
        }
        for (;;)
        {
          domains.Record(true);
          const int label = PickLabel(domains.Domain(i), words, domains.Count(i), weights, rng);
          domains.Assign(i, label);
          ++assigned;
          empty = domains.Propagate(rules, neighbours);
          if (empty < 0)
          {
            break;
          }
          domains.Undo(0);
          ++result.Backtracks;
          std::fill(exclude.begin(), exclude.end(), ~std::uint64_t(0));
          exclude[static_cast<std::size_t>(label >> 6)] &= ~(std::uint64_t(1) << (label & 63));
          domains.Keep(i, exclude.data());
          empty = domains.Propagate(rules, neighbours);
          if (empty >= 0 || domains.Count(i) == 1)
          {
            break;
          }
        }
        for (std::int64_t c : domains.Changed())
        {
          queue.Update(c, domains.Count(c));
        }
        domains.ClearChanged();
        if (whole && options.Snapshots > 0 && options.OnSnapshot && empty < 0)
        {
          while (taken < options.Snapshots &&
            (m - queue.Remaining()) * options.Snapshots >= static_cast<std::int64_t>(taken + 1) * m)
          {
            ++taken;
            pending.push_back(capture(b, &verts));
          }
        }
      }
      result.Assignments += assigned;
      if (empty >= 0)
      {
        ++result.FailedAttempts;
        const Point3& p = arrangement.Position(verts[static_cast<std::size_t>(empty)]);
        lastFailure = "no label fits at vertex " + std::to_string(verts[static_cast<std::size_t>(empty)]) +
          " (" + std::to_string(p[0]) + ", " + std::to_string(p[1]) + ", " + std::to_string(p[2]) + ")";
        continue;
      }
      solved = true;
      for (std::int64_t i = 0; i < m; ++i)
      {
        result.Labels[static_cast<std::size_t>(verts[static_cast<std::size_t>(i)])] = domains.Single(i);
      }
      while (whole && options.Snapshots > 0 && options.OnSnapshot &&
        static_cast<int>(pending.size()) < options.Snapshots)
      {
        pending.push_back(capture(b, &verts)); // decided by propagation before the last marks
      }
      for (const auto& s : pending) // only the successful attempt's snapshots are kept
      {
        emit(s);
      }
    }
    if (!solved)
    {
      ++result.FailedBlocks;
    }
    for (std::int64_t v : verts)
    {
      localOf[static_cast<std::size_t>(v)] = -1;
    }
    if (!whole && options.Snapshots > 0 && options.OnSnapshot)
    {
      // Snapshots 1 .. S-1 show the catalog of block floor(j · blocks / S) after its first
      // propagation; snapshot S the finished model.
      for (std::int64_t j = 1; j < options.Snapshots; ++j)
      {
        if ((j * blocks) / options.Snapshots == b)
        {
          if (blockStart.CatalogSize.empty())
          {
            blockStart = capture(b, nullptr);
          }
          emit(blockStart);
        }
      }
      if (b + 1 == blocks)
      {
        emit(capture(b, nullptr));
      }
    }
    if (options.Progress && !options.Progress(static_cast<double>(b + 1) / static_cast<double>(blocks)))
    {
      throw Error("continuous synthesis was cancelled");
    }
    if (whole && !solved)
    {
      result.Success = false;
      result.Message = "whole-model synthesis failed in all " + std::to_string(options.Attempts) +
        " attempts (last: " + lastFailure + "); try blocks (a block size of a few plane spacings)";
      result.Labels.assign(static_cast<std::size_t>(n), rules.EmptyLabel());
      result.Seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      return result;
    }
  }
  result.Success = true;
  result.Message = std::to_string(n) + " vertices, " + std::to_string(blocks) + " blocks, " +
    std::to_string(result.FailedBlocks) + " left unchanged after failing";
  result.Seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

std::string CheckArrangementLabels(const PolyhedralAnalysis& analysis,
  const PlaneArrangement& arrangement, const std::vector<std::int32_t>& labels)
{
  const PlaneFamilySet& set = arrangement.Families();
  const std::int64_t n = arrangement.NumberOfVertices();
  if (static_cast<std::int64_t>(labels.size()) != n)
  {
    return "there are " + std::to_string(labels.size()) + " labels for " + std::to_string(n) + " vertices";
  }
  const NeighbourhoodLabel empty = NeighbourhoodLabel::Constant(0);
  for (std::int64_t v = 0; v < n; ++v)
  {
    const int a = labels[static_cast<std::size_t>(v)];
    if (a < 0 || a >= analysis.NumberOfLabels())
    {
      return "vertex " + std::to_string(v) + " has no example label";
    }
    const NeighbourhoodLabel& la = analysis.Label(a).Label;
    for (int f : la.Families)
    {
      if (!((arrangement.FamilyMask(v) >> f) & 1u))
      {
        return "vertex " + std::to_string(v) + " has a label on a plane that does not pass through it";
      }
    }
    for (const auto* l = arrangement.LinksBegin(v); l != arrangement.LinksEnd(v); ++l)
    {
      const IntVec3& d = arrangement.Direction(l->Direction);
      const NeighbourhoodLabel here = la.Evaluate(set, d);
      if (l->Vertex < 0)
      {
        if (here != empty)
        {
          return "vertex " + std::to_string(v) + " is not empty toward the outside of the box";
        }
        continue;
      }
      const NeighbourhoodLabel& lb = analysis.Label(labels[static_cast<std::size_t>(l->Vertex)]).Label;
      if (here != lb.Evaluate(set, { -d[0], -d[1], -d[2] }))
      {
        return "vertices " + std::to_string(v) + " and " + std::to_string(l->Vertex) +
          " disagree about the edge between them";
      }
    }
  }
  return {};
}

} // namespace msynth
