// SPDX-License-Identifier: BSD-3-Clause
// Time-varying (4D) models, dissertation §3.5.4. Every output is checked by CheckTimeVarying,
// which recomputes the allowed pairs (in space and in time) from the example frames, and the
// rolling ball's motion is checked here from its definition.
#include "Core/Error.h"
#include "Discrete/TimeVarying.h"

#include <gtest/gtest.h>

#include <random>

using namespace msynth;

namespace
{
constexpr Label Empty = 0, In = 1, Out = 2;

/// Fig. 3.27 in one dimension of space: a ball emerges from a cell's left edge (In) and leaves
/// through its right edge a frame later (Out) while the next cell shows it emerging (In).
TimeVaryingGrid RollingBall()
{
  TimeVaryingGrid e;
  for (std::int64_t t = 0; t < 8; ++t)
  {
    LabelGrid frame(6, 1, 1, Empty);
    if (t < 6)
      frame.Set(t, 0, 0, In);
    if (t >= 1 && t - 1 < 6)
      frame.Set(t - 1, 0, 0, Out);
    e.Frames.push_back(frame);
  }
  return e;
}

/// Every ball came from the left (or from outside) and leaves in the next frame. Returns the
/// number of balls seen.
int ExpectBallsRoll(const TimeVaryingGrid& m, bool loop)
{
  const Coord4 n = m.Dimensions();
  int balls = 0;
  for (std::int64_t t = 0; t < n[3]; ++t)
    for (std::int64_t x = 0; x < n[0]; ++x)
    {
      const Label v = m.Frames[static_cast<std::size_t>(t)].At(x, 0, 0);
      if (v != In)
        continue;
      ++balls;
      if (x > 0)
      {
        EXPECT_EQ(m.Frames[static_cast<std::size_t>(t)].At(x - 1, 0, 0), Out) << x << " " << t;
      }
      if (t + 1 < n[3] || loop)
      {
        EXPECT_EQ(m.Frames[static_cast<std::size_t>((t + 1) % n[3])].At(x, 0, 0), Out)
          << x << " " << t;
      }
    }
  return balls;
}
} // namespace

TEST(TimeVarying, RollingBallOfFigure327)
{
  const TimeVaryingGrid e = RollingBall();
  const auto rules = TimeVaryingRules::FromExample(e);
  EXPECT_EQ(rules.NumberOfLabels(), 3);
  int balls = 0;
  for (const bool blocks : { false, true })
    for (std::uint64_t seed = 0; seed < 5; ++seed)
    {
      TimeVaryingOptions o;
      o.Size = { { 16, 1, 1, 20 } };
      o.Seed = seed;
      if (blocks)
        o.BlockSize = { { 6, 1, 1, 6 } };
      const auto r = SynthesizeTimeVarying(rules, o);
      ASSERT_TRUE(r.Succeeded()) << r.Message;
      const auto report = CheckTimeVarying(e, r.Model);
      EXPECT_TRUE(report.Consistent) << (report.First.empty() ? "" : report.First[0].Describe());
      balls += ExpectBallsRoll(r.Model, false);
    }
  EXPECT_GT(balls, 5);
}

TEST(TimeVarying, BlocksHonourTheOverlap)
{
  const TimeVaryingGrid e = RollingBall();
  const auto rules = TimeVaryingRules::FromExample(e);
  TimeVaryingOptions o;
  o.Size = { { 16, 1, 1, 20 } };
  o.BlockSize = { { 6, 1, 1, 6 } };
  o.Seed = 3;
  const auto half = SynthesizeTimeVarying(rules, o);
  ASSERT_TRUE(half.Succeeded()) << half.Message;
  EXPECT_EQ(half.Statistics.Blocks, 5 * 6); // steps of 3: x at 0 3 6 9 12 (until 6 covers 16)
  o.Overlap = { { 1, 0, 0, 2 } };
  const auto r = SynthesizeTimeVarying(rules, o);
  ASSERT_TRUE(r.Succeeded()) << r.Message;
  EXPECT_EQ(r.Statistics.Blocks, 3 * 5); // x at 0 5 10, t at 0 4 8 12 16
  const auto report = CheckTimeVarying(e, r.Model);
  EXPECT_TRUE(report.Consistent) << (report.First.empty() ? "" : report.First[0].Describe());
}

TEST(TimeVarying, LoopingAnimationJoinsTheLastFrameToTheFirst)
{
  const TimeVaryingGrid e = RollingBall();
  const auto rules = TimeVaryingRules::FromExample(e);
  int successes = 0, balls = 0;
  for (std::uint64_t seed = 0; seed < 6; ++seed)
  {
    TimeVaryingOptions o;
    o.Size = { { 12, 1, 1, 10 } };
    o.Seed = seed;
    o.Loop = true;
    const auto r = SynthesizeTimeVarying(rules, o);
    if (!r.Succeeded())
    {
      EXPECT_TRUE(r.Model.Frames.empty());
      continue;
    }
    ++successes;
    EXPECT_TRUE(CheckTimeVarying(e, r.Model, true).Consistent);
    balls += ExpectBallsRoll(r.Model, true);
  }
  EXPECT_GT(successes, 0);
  EXPECT_GT(balls, 0);
  // The checker sees a broken seam: the example's first six frames end with a ball in the
  // last cell, which is empty in the first frame.
  TimeVaryingGrid broken = RollingBall();
  broken.Frames.resize(6);
  EXPECT_TRUE(CheckTimeVarying(e, broken, false).Consistent);
  EXPECT_FALSE(CheckTimeVarying(e, broken, true).Consistent);
}

TEST(TimeVarying, RandomExamplesGiveConsistentModelsOrReportedFailures)
{
  std::mt19937 rng(4);
  int successes = 0;
  for (int trial = 0; trial < 30; ++trial)
  {
    TimeVaryingGrid e;
    const std::int64_t nt = 2 + rng() % 3;
    for (std::int64_t t = 0; t < nt; ++t)
    {
      LabelGrid frame(4, 4, 2, 0);
      for (std::int64_t z = 0; z < 2; ++z)
        for (std::int64_t y = 1; y < 3; ++y)
          for (std::int64_t x = 1; x < 3; ++x)
            frame.Set(x, y, z, static_cast<Label>(rng() % 4));
      e.Frames.push_back(frame);
    }
    const auto rules = TimeVaryingRules::FromExample(e);
    TimeVaryingOptions o;
    o.Size = { { 7, 6, 3, 5 } };
    o.Seed = static_cast<std::uint64_t>(trial);
    o.Order = trial % 2 ? SiteOrder::Random : SiteOrder::ScanLine;
    if (trial % 3 == 0)
      o.BlockSize = { { 4, 4, 3, 3 } };
    const auto r = SynthesizeTimeVarying(rules, o);
    if (!r.Succeeded())
    {
      EXPECT_TRUE(r.Model.Frames.empty()) << "a failure returned a model";
      continue;
    }
    ++successes;
    EXPECT_EQ(r.Model.Dimensions(), (Coord4{ { 7, 6, 3, 5 } }));
    const auto report = CheckTimeVarying(e, r.Model);
    EXPECT_TRUE(report.Consistent) << trial << ": " << report.First[0].Describe();
  }
  EXPECT_GT(successes, 15);
}

TEST(TimeVarying, SameSeedSameAnimation)
{
  const auto rules = TimeVaryingRules::FromExample(RollingBall());
  TimeVaryingOptions o;
  o.Size = { { 10, 1, 1, 12 } };
  o.Seed = 8;
  o.BlockSize = { { 5, 1, 1, 5 } };
  const auto a = SynthesizeTimeVarying(rules, o);
  const auto b = SynthesizeTimeVarying(rules, o);
  ASSERT_TRUE(a.Succeeded() && b.Succeeded());
  for (std::size_t t = 0; t < a.Model.Frames.size(); ++t)
    EXPECT_EQ(a.Model.Frames[t], b.Model.Frames[t]);
}

TEST(TimeVarying, BadInputIsRefused)
{
  TimeVaryingGrid uneven;
  uneven.Frames.push_back(LabelGrid(3, 3, 1, 0));
  uneven.Frames.push_back(LabelGrid(3, 2, 1, 0));
  EXPECT_THROW(TimeVaryingRules::FromExample(uneven), Error);
  EXPECT_THROW(TimeVaryingRules::FromExample(TimeVaryingGrid{}), Error);
  const auto rules = TimeVaryingRules::FromExample(RollingBall());
  TimeVaryingOptions o;
  o.Size = { { 4, 1, 1, 0 } };
  EXPECT_THROW(SynthesizeTimeVarying(rules, o), Error);
  o.Size = { { 4, 1, 1, 4 } };
  o.Order = SiteOrder::MinimumEntropy;
  EXPECT_THROW(SynthesizeTimeVarying(rules, o), Error);
  o.Order = SiteOrder::ScanLine;
  o.Choice = LabelChoice::Resemblance;
  EXPECT_THROW(SynthesizeTimeVarying(rules, o), Error);
}

TEST(TimeVarying, ProgressCancelsWithAStatusAndNoModel)
{
  const TimeVaryingGrid e = RollingBall();
  const auto rules = TimeVaryingRules::FromExample(e);
  TimeVaryingOptions o;
  o.Size = { { 16, 1, 1, 20 } };
  o.BlockSize = { { 6, 1, 1, 6 } };
  int calls = 0;
  o.Progress = [&calls](double) { return ++calls < 3; };
  const auto r = SynthesizeTimeVarying(rules, o);
  EXPECT_EQ(r.Status, SynthesisStatus::Cancelled);
  EXPECT_TRUE(r.Model.Frames.empty());
  EXPECT_EQ(calls, 3);
  EXPECT_EQ(r.Statistics.Blocks, 30); // 5 blocks along x (step 3), 6 along time
  EXPECT_EQ(r.Statistics.BlocksAccepted + r.Statistics.BlocksFailed, 3);
}
