// SPDX-License-Identifier: BSD-3-Clause
#include "Fixtures.h"

#include "Discrete/ConsistencyCheck.h"
#include "Discrete/DiscreteSynthesis.h"
#include "Discrete/Infallibility.h"

#include <gtest/gtest.h>

#include <random>

using namespace msynth;
using msynth_test::Grid2D;

namespace
{
AdjacencyRules RulesOf(const LabelGrid& e)
{
  return AdjacencyRules::FromExample(ExampleAnalysis::FromExample(e));
}
} // namespace

TEST(Infallibility, ThesisExamplesE0AndCheckerboardAreProved)
{
  const auto e0 = AnalyzeInfallibility(RulesOf(LabelGrid(3, 3, 3, 0)), { { 10, 10, 10 } });
  EXPECT_TRUE(e0.Proved) << e0.Explanation;
  const auto board = AnalyzeInfallibility(
    RulesOf(Grid2D({ { 0, 1, 0 }, { 1, 0, 1 }, { 0, 1, 0 } })), { { 10, 10, 1 } });
  EXPECT_TRUE(board.Proved) << board.Explanation;
  EXPECT_NE(board.Recommendation.find("Algorithm 3.1"), std::string::npos);
}

TEST(Infallibility, TheFallibleFixtureIsNotProved)
{
  // The example that makes Algorithm 3.1 fail (FallibleExampleFailsWholeButSucceedsInBlocks).
  const LabelGrid e =
    Grid2D({ { 0, 0, 0, 0, 0, 0, 0, 0 }, { 0, 0, 0, 0, 5, 1, 4, 0 }, { 0, 0, 0, 5, 7, 3, 4, 0 },
      { 0, 3, 1, 6, 7, 6, 2, 0 }, { 0, 0, 0, 5, 7, 6, 3, 0 }, { 0, 0, 0, 0, 0, 0, 0, 0 } });
  const auto r = AnalyzeInfallibility(RulesOf(e), { { 24, 24, 1 } });
  EXPECT_FALSE(r.Proved);
  EXPECT_NE(r.Explanation.find("no label fits"), std::string::npos) << r.Explanation;
  EXPECT_NE(r.Recommendation.find("block synthesis"), std::string::npos);
}

TEST(Infallibility, ProvedExamplesNeverFailAlgorithm31)
{
  // Soundness, checked empirically: whatever the analysis proves never fails in practice.
  std::mt19937 rng(31);
  int proved = 0, notProved = 0;
  for (int trial = 0; trial < 300; ++trial)
  {
    const std::int64_t nx = 2 + rng() % 4, ny = 2 + rng() % 4, nz = trial % 3 == 0 ? 2 : 1;
    LabelGrid e(nx, ny, nz);
    const unsigned k = 2 + rng() % 3;
    for (auto& v : e.Data())
      v = static_cast<Label>(rng() % k);
    const std::array<std::int64_t, 3> size{ { 10, 9, nz == 1 ? 1 : 4 } };
    const auto rules = RulesOf(e);
    const auto report = AnalyzeInfallibility(rules, size);
    if (!report.Proved)
    {
      ++notProved;
      continue;
    }
    ++proved;
    for (std::uint64_t seed = 0; seed < 6; ++seed)
    {
      SynthesisOptions o;
      o.Size = size;
      o.Seed = seed;
      o.AttemptsPerBlock = 1;
      o.Order = SiteOrder::ScanLine; // the order of Algorithm 3.6, which the proof follows
      const auto r = Synthesize(rules, o);
      ASSERT_TRUE(r.Succeeded()) << "proved infallible but failed: trial " << trial << ", seed "
                                 << seed;
      EXPECT_TRUE(CheckConsistency(e, r.Model).Consistent);
    }
  }
  EXPECT_GT(proved, 0);
  EXPECT_GT(notProved, 0);
}

TEST(Infallibility, EnumerationLimitIsReported)
{
  LabelGrid e(4, 4, 4);
  std::mt19937 rng(3);
  for (auto& v : e.Data())
    v = static_cast<Label>(rng() % 6);
  const auto r = AnalyzeInfallibility(RulesOf(e), { { 8, 8, 8 } }, 50);
  if (r.Exhausted)
  {
    EXPECT_FALSE(r.Proved);
    EXPECT_NE(r.Explanation.find("stopped after 50"), std::string::npos);
  }
}

TEST(Infallibility, TheLineModelOfFigures31cAnd312IsProved)
{
  // Fig. 3.12 (= Fig. 3.1(c)), reconstructed from the text (the figure itself is an image): a
  // line of 1s in empty space. A 1 above a 1 never occurs, so the region [1 / 1 1] of §3.3.7 is
  // inconsistent, and Eq. 3.11 holds: the 2x2 analysis proves it.
  const LabelGrid line = Grid2D({ { 0, 0, 0, 0, 0 }, { 0, 1, 1, 1, 0 }, { 0, 0, 0, 0, 0 } });
  const auto r = AnalyzeInfallibility(RulesOf(line), { { 30, 30, 1 } });
  EXPECT_TRUE(r.Proved) << r.Explanation;
  EXPECT_EQ(r.Region, (std::array<int, 3>{ { 2, 2, 2 } }));
  EXPECT_GT(r.Configurations, 0);
}

TEST(Infallibility, LargerRegionsProveWhatTwoByTwoCannot)
{
  // §3.3.7 on Fig. 3.4(a): Algorithm 3.6 may fail with 2x2 regions but not with 3x2, because
  // the wider region sees the placed site below-right of p. This four-label example behaves
  // the same way (Fig. 3.4(a) itself is an image missing from the text we have).
  const LabelGrid e = Grid2D({ { 0, 0, 0, 0, 0 }, { 0, 0, 3, 2, 0 }, { 0, 3, 2, 2, 0 },
    { 0, 1, 2, 3, 0 }, { 0, 0, 0, 0, 0 } });
  const auto rules = RulesOf(e);
  const auto twoByTwo = AnalyzeInfallibility(rules, { { 30, 30, 1 } }, 10000000, 2);
  EXPECT_FALSE(twoByTwo.Proved);
  const auto r = AnalyzeInfallibility(rules, { { 30, 30, 1 } });
  ASSERT_TRUE(r.Proved) << r.Explanation;
  EXPECT_EQ(r.Region, (std::array<int, 3>{ { 3, 2, 2 } }));
  EXPECT_NE(r.Explanation.find("3x2"), std::string::npos);
  for (std::uint64_t seed = 0; seed < 40; ++seed)
  {
    SynthesisOptions o;
    o.Size = { { 9 + static_cast<std::int64_t>(seed % 7), 6 + static_cast<std::int64_t>(seed % 5),
      1 } };
    o.Seed = seed;
    o.AttemptsPerBlock = 1;
    o.Order = SiteOrder::ScanLine;
    const auto m = Synthesize(rules, o);
    ASSERT_TRUE(m.Succeeded()) << "proved infallible but failed, seed " << seed;
    EXPECT_TRUE(CheckConsistency(e, m.Model).Consistent);
  }
}

TEST(Infallibility, RegionAnalysisIsSoundAndAgreesWithTheCornersAtTwoByTwo)
{
  // The window-state enumeration with 2x2 regions proves exactly what the corner condition
  // proves; whatever any region proves never fails Algorithm 3.1 in scan-line order.
  std::mt19937 rng(17);
  int larger = 0;
  for (int trial = 0; trial < 400; ++trial)
  {
    const std::int64_t w = 2 + rng() % 4, h = 2 + rng() % 3;
    const unsigned k = 2 + rng() % 4;
    LabelGrid e(w + 2 * (trial % 2), h + 2 * (trial % 2), 1, 0);
    for (std::int64_t y = 0; y < h; ++y)
      for (std::int64_t x = 0; x < w; ++x)
        e.Set(x + trial % 2, y + trial % 2, 0, static_cast<Label>(rng() % k));
    const auto rules = RulesOf(e);
    const auto corners = AnalyzeInfallibility(rules, { { 20, 20, 1 } }, 10000000, 2);
    EXPECT_EQ(AnalyzeRegion2D(rules, { { 0, 1 } }, 2, 2).Proved, corners.Proved) << trial;
    const auto report = AnalyzeInfallibility(rules, { { 20, 20, 1 } });
    if (!report.Proved || corners.Proved)
      continue;
    ++larger;
    for (std::uint64_t seed = 0; seed < 8; ++seed)
      for (const std::array<std::int64_t, 3> size :
        { std::array<std::int64_t, 3>{ { 7, 9, 1 } }, std::array<std::int64_t, 3>{ { 16, 12, 1 } },
          std::array<std::int64_t, 3>{ { 3, 20, 1 } } })
      {
        SynthesisOptions o;
        o.Size = size;
        o.Seed = seed;
        o.AttemptsPerBlock = 1;
        o.Order = SiteOrder::ScanLine;
        const auto m = Synthesize(rules, o);
        ASSERT_TRUE(m.Succeeded()) << "trial " << trial << " proved with region "
                                   << report.Region[0] << "x" << report.Region[1] << " but failed";
        EXPECT_TRUE(CheckConsistency(e, m.Model).Consistent);
      }
  }
  EXPECT_GT(larger, 10);
}
