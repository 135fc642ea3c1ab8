// SPDX-License-Identifier: BSD-3-Clause
// The propagation engine's fast path for one-word sets (k <= 64) against the general loop, and
// the trail that a long search forgets (LabelDomains::Forget, BlockSearch::Trim).
#include "Core/Error.h"
#include "Core/Propagation.h"
#include "Core/Random.h"
#include "Discrete/ConsistencyCheck.h"
#include "Discrete/DiscreteSynthesis.h"
#include "Formats/Tileset.h"

#include <cstdint>
#include <string>
#include <vector>

#include <gtest/gtest.h>

using namespace msynth;

namespace
{
/// A chain relation of two direction classes (0: to the right, 1: to the left) over k labels:
/// the pairs of a random table over the first @p used labels; labels from @p used on have no
/// pair at all (propagation removes them first).
class ChainRelation : public CompatibilityRelation
{
public:
  ChainRelation(int k, int used, std::uint64_t seed)
  {
    this->Allocate(k, 2);
    Random rng(seed);
    for (int b = 0; b < used; ++b)
    {
      for (int c = 0; c < used; ++c)
      {
        if (rng.Next() % 3 == 0)
        {
          this->AllowOne(0, b, c);
          this->AllowOne(1, c, b);
        }
      }
    }
    this->Finish();
  }
};

/// Propagates a chain of @p n sites after @p picks assignments; the sets of the first @p used
/// labels per site (or an empty vector when a set emptied).
std::vector<std::uint64_t> RunChain(const CompatibilityRelation& rel, int used, std::int64_t n,
  const std::vector<std::pair<std::int64_t, int>>& picks)
{
  LabelDomains domains;
  domains.Reset(n, rel.NumberOfLabels());
  auto neighbours = [n](std::int64_t v, auto&& visit)
  {
    if (v + 1 < n && !visit(v + 1, 0))
      return;
    if (v > 0)
      visit(v - 1, 1);
  };
  if (domains.Propagate(rel, neighbours) >= 0)
    return {};
  for (const auto& pick : picks)
  {
    if (!domains.Contains(pick.first, pick.second))
      continue;
    domains.Assign(pick.first, pick.second);
    if (domains.Propagate(rel, neighbours) >= 0)
      return {};
  }
  std::vector<std::uint64_t> sets;
  for (std::int64_t s = 0; s < n; ++s)
  {
    std::uint64_t low = domains.Domain(s)[0] & ((std::uint64_t(1) << used) - 1);
    for (int w = 1; w < domains.Words(); ++w)
      EXPECT_EQ(domains.Domain(s)[w], 0u) << "labels without pairs left at site " << s;
    sets.push_back(low);
  }
  return sets;
}
} // namespace

TEST(Propagation, OneWordSetsReachTheSameCatalogAsTheGeneralLoop)
{
  // The same 40 labels with pairs, once in a one-word relation (k = 40) and once in a
  // three-word one (k = 150, labels 40.. without pairs): arc consistency has one fixpoint.
  for (std::uint64_t seed = 1; seed <= 20; ++seed)
  {
    const ChainRelation one(40, 40, seed), three(150, 40, seed);
    ASSERT_EQ(one.Words(), 1);
    ASSERT_EQ(three.Words(), 3);
    Random rng(seed + 100);
    std::vector<std::pair<std::int64_t, int>> picks;
    for (int i = 0; i < 30; ++i)
      picks.push_back(
        { static_cast<std::int64_t>(rng.Next() % 200), static_cast<int>(rng.Next() % 40) });
    EXPECT_EQ(RunChain(one, 40, 200, picks), RunChain(three, 40, 200, picks)) << "seed " << seed;
  }
}

TEST(Propagation, ForgottenTrailCannotBeUndoneTheRestCan)
{
  const ChainRelation rel(8, 8, 3);
  LabelDomains domains;
  const std::int64_t n = 100000;
  domains.Reset(n, 8);
  domains.Record(true);
  std::vector<std::uint64_t> keepLow(1, 0x0f), keepOne(1, 0x03);
  for (std::int64_t s = 0; s < n; ++s)
    domains.Keep(s, keepLow.data()); // 2 words each: 200 000 words
  const std::size_t middle = domains.Mark();
  EXPECT_EQ(middle, std::size_t(2 * n));
  for (std::int64_t s = 0; s < n / 2; ++s)
    domains.Keep(s, keepOne.data());
  const std::size_t end = domains.Mark();
  domains.Forget(middle); // drops the first 200 000 words (the larger part)
  EXPECT_EQ(domains.Mark(), end) << "marks count the forgotten words too";
  domains.Undo(middle);
  EXPECT_EQ(domains.Mark(), middle);
  for (std::int64_t s = 0; s < n; s += 997)
    EXPECT_EQ(domains.Count(s), 4) << s;
  EXPECT_THROW(domains.Undo(0), Error);
}

TEST(Propagation, TrailKeepsAWordOnceBetweenMarks)
{
  // Undo needs only the state at a mark: a word changed again after a mark is not recorded
  // again (Font's whole model recorded 16 M words within 40 choices when each change kept the
  // whole set, and went on without backtracking).
  LabelDomains domains;
  domains.Reset(10, 200); // 4 words a set
  domains.Record(true);
  auto without = [](std::initializer_list<int> labels)
  {
    std::vector<std::uint64_t> mask(4, ~std::uint64_t(0));
    for (const int b : labels)
      mask[ToIndex(b >> 6)] &= ~(std::uint64_t(1) << (b & 63));
    return mask;
  };
  const std::size_t first = domains.Mark();
  domains.Keep(3, without({ 0 }).data());
  domains.Keep(3, without({ 1 }).data());
  domains.Keep(3, without({ 2, 70 }).data());
  EXPECT_EQ(domains.TrailWords(), 4u) << "words 0 and 1 of site 3, each once";
  EXPECT_EQ(domains.Count(3), 196);
  const std::size_t second = domains.Mark();
  domains.Keep(3, without({ 3 }).data());
  domains.Keep(3, without({ 4 }).data());
  EXPECT_EQ(domains.TrailWords(), 6u) << "word 0 again after the new mark, once";
  domains.Undo(second);
  EXPECT_EQ(domains.Count(3), 196);
  EXPECT_FALSE(domains.Contains(3, 2));
  EXPECT_TRUE(domains.Contains(3, 3));
  domains.Keep(3, without({ 5 }).data());
  domains.Undo(second);
  EXPECT_EQ(domains.Count(3), 196) << "the word recorded again after the undo";
  domains.Undo(first);
  EXPECT_EQ(domains.Count(3), 200);
  EXPECT_EQ(domains.TrailWords(), 0u);
}

TEST(Propagation, WholeModelSearchOverATrimmedTrailIsValid)
{
  // A whole model of Lines with backtracking: tens of thousands of choices, so BlockSearch trims
  // its stack and the catalog forgets the trail's start; every undo still finds its records.
  const Tileset lines = ReadTilesetFile(std::string(MSYNTH_DATA) + "/Tilesets/Lines.xml");
  const AdjacencyRules rules = lines.Rules();
  SynthesisOptions o;
  o.Size = { { 300, 300, 1 } };
  o.Seed = 5;
  o.AttemptsPerBlock = 1;
  o.BlocksWhenWholeFails = false;
  const SynthesisResult r = Synthesize(rules, o);
  ASSERT_TRUE(r.Succeeded()) << r.Message;
  EXPECT_GT(r.Statistics.Assignments, 20000);
  EXPECT_TRUE(CheckConsistency(lines.Pairs, r.Model).Consistent);
}

namespace
{
/// A random relation over a grid's four direction classes (0: +x, 1: -x, 2: +y, 3: -y): each
/// pair allowed with probability 1/@p sparsity, stored in both directions.
class GridRelation : public CompatibilityRelation
{
public:
  GridRelation(int k, int sparsity, std::uint64_t seed)
  {
    this->Allocate(k, 4);
    Random rng(seed);
    for (int axis = 0; axis < 2; ++axis)
      for (int b = 0; b < k; ++b)
        for (int c = 0; c < k; ++c)
          if (rng.Next() % static_cast<std::uint64_t>(sparsity) == 0)
          {
            this->AllowOne(2 * axis, b, c);
            this->AllowOne(2 * axis + 1, c, b);
          }
    this->Finish();
  }
};

/// Neighbours on an nx x ny grid (not periodic), in the order +x, -x, +y, -y.
struct GridNeighbours
{
  std::int64_t Nx, Ny;
  template <class Visit>
  void operator()(std::int64_t v, Visit&& visit) const
  {
    const std::int64_t x = v % this->Nx, y = v / this->Nx;
    if (x + 1 < this->Nx && !visit(v + 1, 0))
      return;
    if (x > 0 && !visit(v - 1, 1))
      return;
    if (y + 1 < this->Ny && !visit(v + this->Nx, 2))
      return;
    if (y > 0)
      visit(v - this->Nx, 3);
  }
};

/// The sets and the order of changed sites of @p a and @p b are the same; @p what names the step.
void ExpectSame(const LabelDomains& a, const LabelDomains& b, const std::string& what)
{
  ASSERT_EQ(a.Changed(), b.Changed()) << what;
  ASSERT_EQ(a.Decided(), b.Decided()) << what;
  for (std::int64_t s = 0; s < a.NumberOfSites(); ++s)
  {
    ASSERT_EQ(a.Count(s), b.Count(s)) << what << ", site " << s;
    for (int w = 0; w < a.Words(); ++w)
      ASSERT_EQ(a.Domain(s)[w], b.Domain(s)[w]) << what << ", site " << s;
  }
}

/// Every label left has a support at each neighbour (the sets are arc consistent).
void ExpectArcConsistent(
  const LabelDomains& a, const CompatibilityRelation& rel, const GridNeighbours& grid)
{
  for (std::int64_t v = 0; v < a.NumberOfSites(); ++v)
    grid(v,
      [&](std::int64_t u, int d)
      {
        for (int c = 0; c < a.NumberOfLabels(); ++c)
        {
          if (!a.Contains(u, c))
            continue;
          bool supported = false;
          for (int b = 0; b < a.NumberOfLabels() && !supported; ++b)
            supported = a.Contains(v, b) && rel.Allowed(d, b, c);
          EXPECT_TRUE(supported) << "label " << c << " at " << u << " from " << v;
        }
        return true;
      });
}

/**
 * Random choices with backtracking on a grid, once by removals and once by the unions
 * only: after every Propagate and Undo the same sets in the same order of changes. Counts in
 * @p undos how many undos ran.
 */
void CompareWithUnions(
  const GridRelation& rel, std::int64_t nx, std::int64_t ny, std::uint64_t seed, int& undos)
{
  const GridNeighbours grid{ nx, ny };
  LabelDomains counted, unions;
  unions.AllowRevisionsByRemovals(false);
  counted.Reset(nx * ny, rel.NumberOfLabels());
  unions.Reset(nx * ny, rel.NumberOfLabels());
  counted.Record(true);
  unions.Record(true);
  // A restriction before the first propagation (its site keeps its place first in the queue).
  std::vector<std::uint64_t> half(ToIndex(rel.Words()), 0x5555555555555555ull);
  counted.Keep(nx + 1, half.data());
  unions.Keep(nx + 1, half.data());
  const std::int64_t start = counted.Propagate(rel, grid);
  ASSERT_EQ(start, unions.Propagate(rel, grid));
  EXPECT_TRUE(counted.UsesRevisionsByRemovals());
  EXPECT_FALSE(unions.UsesRevisionsByRemovals());
  ExpectSame(counted, unions, "start");
  ASSERT_LT(start, 0) << "k " << rel.NumberOfLabels() << ": the relation allows no model";
  ExpectArcConsistent(counted, rel, grid);
  Random rng(seed);
  std::vector<std::pair<std::size_t, std::size_t>> marks; // (counted, unions): trails differ
  std::vector<std::uint64_t> others(ToIndex(rel.Words()));
  for (int step = 0; step < 300 && !::testing::Test::HasFatalFailure(); ++step)
  {
    const std::string what = "seed " + std::to_string(seed) + ", step " + std::to_string(step);
    counted.ClearChanged();
    unions.ClearChanged();
    std::int64_t site = -1;
    for (int tries = 0; tries < 200 && site < 0; ++tries)
    {
      const auto s = static_cast<std::int64_t>(rng.Below(static_cast<std::uint64_t>(nx * ny)));
      site = counted.Count(s) > 1 ? s : -1;
    }
    if (site < 0)
      break;
    int label = -1;
    for (int c = static_cast<int>(rng.Below(static_cast<std::uint64_t>(rel.NumberOfLabels())));
         label < 0; c = (c + 1) % rel.NumberOfLabels())
      label = counted.Contains(site, c) ? c : -1;
    marks.emplace_back(counted.Mark(), unions.Mark());
    counted.Assign(site, label);
    unions.Assign(site, label);
    const std::int64_t a = counted.Propagate(rel, grid), b = unions.Propagate(rel, grid);
    ASSERT_EQ(a, b) << what;
    ExpectSame(counted, unions, what);
    if (a < 0 && step % 25 == 0)
      ExpectArcConsistent(counted, rel, grid);
    if (a < 0 && rng.Below(6) != 0)
      continue;
    // Undo to this choice (after a failure) or to an older one, then rule the label out at its
    // site as BlockSearch does when the undo went to this choice.
    ++undos;
    const std::size_t back = a >= 0 ? marks.size() - 1 : ToIndex(rng.Below(marks.size()));
    counted.ClearChanged();
    unions.ClearChanged();
    counted.Undo(marks[back].first);
    unions.Undo(marks[back].second);
    marks.resize(back);
    ExpectSame(counted, unions, what + ", undo");
    if (a >= 0)
    {
      marks.emplace_back(counted.Mark(), unions.Mark());
      std::fill(others.begin(), others.end(), ~std::uint64_t(0));
      others[ToIndex(label >> 6)] &= ~(std::uint64_t(1) << (label & 63));
      counted.ClearChanged();
      unions.ClearChanged();
      counted.Keep(site, others.data());
      unions.Keep(site, others.data());
      const std::int64_t c = counted.Propagate(rel, grid);
      ASSERT_EQ(c, unions.Propagate(rel, grid)) << what;
      ExpectSame(counted, unions, what + ", ruled out");
      if (c >= 0)
      {
        counted.Undo(marks.back().first);
        unions.Undo(marks.back().second);
        ExpectSame(counted, unions, what + ", ruled out and undone");
      }
      marks.pop_back();
    }
  }
  EXPECT_GT(counted.RevisionsByRemovals(), 0) << "the removals were not used";
}
} // namespace

TEST(Propagation, RevisionsByRemovalsGiveTheSetsAndChangesOfTheUnions)
{
  // k > 512 (the unions walk the labels or, sparsest, the lists), sparse relations (so the
  // lists exist), random choices with failures and undos, also far back.
  struct Case
  {
    int K, Sparsity;
  };
  for (const Case c : { Case{ 520, 40 }, Case{ 600, 60 }, Case{ 700, 120 }, Case{ 900, 150 } })
  {
    for (std::uint64_t seed = 1; seed <= 3; ++seed)
    {
      const GridRelation rel(c.K, c.Sparsity, seed * 7 + static_cast<std::uint64_t>(c.K));
      ASSERT_TRUE(rel.HasLists());
      int undos = 0;
      CompareWithUnions(rel, 9, 7, seed, undos);
      ASSERT_FALSE(HasFatalFailure()) << "k " << c.K << ", seed " << seed;
      EXPECT_GT(undos, 0) << "k " << c.K;
    }
  }
}

TEST(Propagation, RevisionsByRemovalsAfterResetsOfOtherSizes)
{
  // One LabelDomains reused for regions of several sizes (as a block solver does), with the
  // Applied kept from before: every region propagates as by the unions.
  const GridRelation rel(600, 50, 11);
  LabelDomains counted, unions;
  unions.AllowRevisionsByRemovals(false);
  for (const std::int64_t nx : { 6, 11, 4, 11 })
  {
    const GridNeighbours grid{ nx, 5 };
    counted.Reset(nx * 5, rel.NumberOfLabels());
    unions.Reset(nx * 5, rel.NumberOfLabels());
    ASSERT_EQ(counted.Propagate(rel, grid), unions.Propagate(rel, grid));
    Random rng(static_cast<std::uint64_t>(nx));
    for (int i = 0; i < 12; ++i)
    {
      const auto s = static_cast<std::int64_t>(rng.Below(static_cast<std::uint64_t>(nx * 5)));
      const int label = counted.Single(s);
      counted.Assign(s, label);
      unions.Assign(s, label);
      const std::int64_t a = counted.Propagate(rel, grid);
      ASSERT_EQ(a, unions.Propagate(rel, grid));
      ExpectSame(counted, unions, "width " + std::to_string(nx));
      if (a >= 0)
        break;
    }
  }
}
