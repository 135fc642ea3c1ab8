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
    domains.Keep(s, keepLow.data()); // 3 words each: 300 000 words
  const std::size_t middle = domains.Mark();
  EXPECT_EQ(middle, std::size_t(3 * n));
  for (std::int64_t s = 0; s < n / 2; ++s)
    domains.Keep(s, keepOne.data());
  const std::size_t end = domains.Mark();
  domains.Forget(middle); // drops the first 300 000 words (the larger part)
  EXPECT_EQ(domains.Mark(), end) << "marks count the forgotten words too";
  domains.Undo(middle);
  EXPECT_EQ(domains.Mark(), middle);
  for (std::int64_t s = 0; s < n; s += 997)
    EXPECT_EQ(domains.Count(s), 4) << s;
  EXPECT_THROW(domains.Undo(0), Error);
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
