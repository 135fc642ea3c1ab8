// SPDX-License-Identifier: BSD-3-Clause
// The one block driver (Core/BlockDriver.h), the one label draw (Core/LabelDraw.h), the one
// mirror fold (Core/MirrorFold.h) and the one list parser (Core/TextLists.h).
#include "Core/BlockDriver.h"
#include "Core/Error.h"
#include "Core/LabelDraw.h"
#include "Core/MirrorFold.h"
#include "Core/TextLists.h"

#include <gtest/gtest.h>

#include <map>
#include <mutex>
#include <set>
#include <vector>

using namespace msynth;

namespace
{
BlockClient Recording(
  std::map<std::size_t, std::vector<std::uint64_t>>& draws, std::mutex& lock, int solvedAtAttempt)
{
  BlockClient client;
  client.Attempt = [&draws, &lock, solvedAtAttempt](
                     unsigned, std::size_t i, int attempt, Random& rng, std::int64_t& assignments)
  {
    ++assignments;
    std::lock_guard<std::mutex> guard(lock);
    draws[i].push_back(rng.Next());
    return attempt >= solvedAtAttempt ? std::int64_t(-1) : std::int64_t(100 + i);
  };
  client.Describe = [](std::size_t i, const BlockOutcome& out, BlockFailure& f)
  { f.EmptyIndex = out.Empty + static_cast<std::int64_t>(i) * 0; };
  return client;
}
} // namespace

TEST(BlockDriver, AttemptsDrawFromTheBlockKeyAndStopAtTheFirstSuccess)
{
  BlockRunner::Policy policy;
  policy.Threads = 2;
  BlockDriver driver(policy, 42, 5, 4);
  BlockSchedule schedule;
  schedule.Phases = { 0, 0, 1, 1 };
  schedule.Keys = { 7, 3, 11, 5 };
  std::map<std::size_t, std::vector<std::uint64_t>> draws;
  std::mutex lock;
  SynthesisStatistics stats;
  ASSERT_EQ(driver.Run(schedule, Recording(draws, lock, 2), stats), SynthesisStatus::Succeeded);
  EXPECT_EQ(stats.Blocks, 4);
  EXPECT_EQ(stats.BlocksAccepted, 4);
  EXPECT_EQ(stats.Attempts, 12); // three attempts a block: 0 and 1 fail, 2 succeeds
  EXPECT_EQ(stats.Assignments, 12);
  for (std::size_t i = 0; i < 4; ++i)
  {
    ASSERT_EQ(draws[i].size(), 3u);
    for (int a = 0; a < 3; ++a)
      EXPECT_EQ(draws[i][static_cast<std::size_t>(a)],
        Random::Derived(42, schedule.Keys[i], static_cast<std::uint64_t>(a)).Next());
  }
}

TEST(BlockDriver, FailedBlocksAreRecordedByKeyAndASecondPassHasItsOwnStreams)
{
  BlockDriver driver(BlockRunner::Policy(), 9, 2, 3);
  std::map<std::size_t, std::vector<std::uint64_t>> draws;
  std::mutex lock;
  SynthesisStatistics stats;
  const BlockSchedule schedule = BlockSchedule::InSequence({ 4, 8, 15 });
  EXPECT_EQ(schedule.Phases, (std::vector<int>{ 0, 1, 2 }));
  ASSERT_EQ(driver.Run(schedule, Recording(draws, lock, 99), stats), SynthesisStatus::Succeeded);
  ASSERT_EQ(stats.Failures.size(), 3u);
  EXPECT_EQ(stats.BlocksFailed, 3);
  EXPECT_EQ(stats.Failures[1].Block, 8);
  EXPECT_EQ(stats.Failures[1].Attempts, 2);
  EXPECT_EQ(stats.Failures[1].EmptyIndex, 101);

  draws.clear();
  BlockPass pass;
  pass.AttemptOffset = 2;
  pass.Attempts = 1;
  pass.Serial = true;
  SynthesisStatistics second;
  driver.Run(BlockSchedule::InSequence({ 8 }), Recording(draws, lock, 0), second, pass);
  EXPECT_EQ(second.BlocksAccepted, 1);
  ASSERT_EQ(draws[0].size(), 1u);
  EXPECT_EQ(draws[0][0], Random::Derived(9, 8, 2).Next());
}

TEST(BlockDriver, EndGivesOneMessagePerOutcome)
{
  BlockDriver driver(BlockRunner::Policy(), 1, 1, 1);
  SynthesisStatistics stats;
  stats.BlocksFailed = 1;
  stats.Failures.push_back(BlockFailure());
  SynthesisStatus status = SynthesisStatus::Cancelled;
  std::string message;
  auto why = [](const BlockFailure&) { return std::string("why"); };
  EXPECT_FALSE(driver.End(status, message, stats, true, why));
  EXPECT_EQ(message, "cancelled");
  status = SynthesisStatus::Succeeded;
  EXPECT_FALSE(driver.End(status, message, stats, true, why));
  EXPECT_EQ(status, SynthesisStatus::Failed);
  EXPECT_EQ(message, "why");
  status = SynthesisStatus::Succeeded;
  EXPECT_TRUE(driver.End(status, message, stats, false, why)); // blocks keep earlier labels
  EXPECT_GE(stats.Seconds, 0.0);
  EXPECT_EQ(WholeModelFailure("whole-model synthesis", 3, "it emptied at (1, 2, 3)", "Try again"),
    "whole-model synthesis failed in all 3 attempts; in the last, it emptied at (1, 2, 3). Try "
    "again");
}

TEST(BlockDriver, GeometryHonoursTheOverlapOnEveryAxis)
{
  std::array<std::int64_t, 4> m{}, step{};
  EXPECT_FALSE(
    BlockGeometry<4>({ { 10, 10, 10, 4 } }, { { 4, 4, 0, 2 } }, { { -1, 1, -1, 0 } }, m, step));
  EXPECT_EQ(m, (std::array<std::int64_t, 4>{ { 4, 4, 10, 2 } }));
  EXPECT_EQ(step, (std::array<std::int64_t, 4>{ { 2, 3, 5, 2 } }));
  std::array<std::int64_t, 3> m3{}, s3{};
  EXPECT_TRUE(BlockGeometry<3>({ { 5, 5, 5 } }, { { 0, 9, 5 } }, { { 9, 9, 9 } }, m3, s3));
  EXPECT_EQ(s3, (std::array<std::int64_t, 3>{ { 1, 1, 1 } })); // overlap at most the block less one
}

TEST(LabelDraw, WeightedDrawWalksTheCandidatesInOrder)
{
  const std::uint64_t domain[2] = { 0b1011, 1 }; // labels 0, 1, 3, 64
  auto weight = [](int b) { return b == 1 ? 0.0 : 1.0; };
  EXPECT_EQ(DrawLabel(domain, 2, weight, 0.0), 0);
  EXPECT_EQ(DrawLabel(domain, 2, weight, 0.34), 3);
  EXPECT_EQ(DrawLabel(domain, 2, weight, 0.99), 64);
  EXPECT_EQ(DrawLabel(domain, 2, weight, 1.0), 64); // the remainder: last of positive weight
  const std::uint64_t none[1] = { 0 };
  EXPECT_EQ(DrawLabel(none, 1, weight, 0.5), -1);
  EXPECT_EQ(NthLabel(domain, 2, 2), 3);
  EXPECT_EQ(NthLabel(domain, 2, 3), 64);
  EXPECT_EQ(NthLabel(domain, 2, 4), -1);
  // Zero weights are never drawn, also when rounding leaves a remainder.
  auto zeroLast = [](int b) { return b == 64 ? 0.0 : 1.0; };
  EXPECT_EQ(DrawLabel(domain, 2, zeroLast, 1.0), 3);
}

TEST(MirrorFold, SitesPastThePartAreReflected)
{
  std::array<std::int64_t, 3> p{};
  EXPECT_EQ(FoldMirror({ { 4, 1, 0 } }, { { 5, 4, 1 } }, { { 3, 2, 1 } }, 3, p), 1);
  EXPECT_EQ(p, (std::array<std::int64_t, 3>{ { 0, 1, 0 } }));
  EXPECT_EQ(
    FoldMirror({ { 4, 3, 0 } }, { { 5, 4, 1 } }, { { 3, 2, 1 } }, 1, p), 1); // y not mirrored
  EXPECT_EQ(p, (std::array<std::int64_t, 3>{ { 0, 3, 0 } }));
}

TEST(TextLists, OneParserForEveryList)
{
  EXPECT_EQ(SplitText("a,,b,", ','), (std::vector<std::string>{ "a", "", "b", "" }));
  EXPECT_EQ(SplitText(" a b :c", ':', true), (std::vector<std::string>{ "ab", "c" }));
  long long v = 0;
  EXPECT_TRUE(ParseInteger("-12", -20, 20, v));
  EXPECT_EQ(v, -12);
  EXPECT_FALSE(ParseInteger("12x", 0, 20, v));
  EXPECT_FALSE(ParseInteger("21", 0, 20, v));
  EXPECT_FALSE(ParseInteger("", 0, 20, v));
  EXPECT_FALSE(ParseInteger("-", -5, 20, v));
  EXPECT_FALSE(ParseInteger("99999999999999999999", 0, 20, v));

  const auto swaps = ParseLabelPairs("1:2; 3 : 4,5:6", true, "MirrorSwaps");
  EXPECT_EQ(
    swaps, (std::map<Label, Label>{ { 1, 2 }, { 2, 1 }, { 3, 4 }, { 4, 3 }, { 5, 6 }, { 6, 5 } }));
  EXPECT_EQ(ParseLabelPairs("1:2", false, "map"), (std::map<Label, Label>{ { 1, 2 } }));
  EXPECT_TRUE(ParseLabelPairs("", false, "map").empty());
  for (const char* bad : { "1:", "1:2:3", "a:b", "12", "1:2,3", "9999999999:1" })
  {
    try
    {
      ParseLabelPairs(bad, false, "RotationMap");
      ADD_FAILURE() << bad;
    }
    catch (const Error& e)
    {
      EXPECT_NE(std::string(e.what()).find("RotationMap: '"), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find("is not a pair 'a:b' of labels"), std::string::npos);
    }
  }
  EXPECT_EQ(ParseLabelValues("3:0.25,4:1", "--target"),
    (std::map<Label, double>{ { 3, 0.25 }, { 4, 1.0 } }));
  EXPECT_THROW(ParseLabelValues("3:x", "--target"), Error);
  EXPECT_THROW(ParseLabelValues("3:inf", "--target"), Error);
  EXPECT_THROW(ParseLabelValues("road:0.5", "--target"), Error);
}
