// SPDX-License-Identifier: BSD-3-Clause
#include "Fixtures.h"

#include "msynth/ConsistencyCheck.h"
#include "msynth/DiscreteSynthesis.h"
#include "msynth/Infallibility.h"

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
      ASSERT_TRUE(r.Success) << "proved infallible but failed: trial " << trial << ", seed "
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
