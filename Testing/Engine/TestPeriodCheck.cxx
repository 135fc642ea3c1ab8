// SPDX-License-Identifier: BSD-3-Clause
// Requests that cannot exist say why (issue 44, item 5), and sets without a trivial start still
// get blocks: a checkerboard repeats every 2 sites, so an odd periodic size is refused with the
// period (CheckTranslationPeriods) instead of failing every attempt; its blocks, which no
// single label can ring, start undecided rather than stopping at "no usable trivial start".
#include "Core/Error.h"
#include "Discrete/ConsistencyCheck.h"
#include "Discrete/DiscreteSynthesis.h"
#include "Discrete/ExampleAnalysis.h"

#include "Fixtures.h"

#include <gtest/gtest.h>

#include <string>

using namespace msynth;

using msynth_test::Grid2D;

namespace
{
LabelGrid Checkerboard()
{
  return Grid2D({ { 0, 1, 0, 1 }, { 1, 0, 1, 0 }, { 0, 1, 0, 1 }, { 1, 0, 1, 0 } });
}

SynthesisOptions Periodic(std::int64_t n)
{
  SynthesisOptions o;
  o.Size = { { n, 6, 1 } };
  o.Translate[0].Enabled = true;
  o.Seed = 3;
  return o;
}
} // namespace

TEST(PeriodCheck, AnOddPeriodOfATwoPeriodicExampleIsRefusedWithItsReason)
{
  const LabelGrid example = Checkerboard();
  const auto rules = AdjacencyRules::FromExample(ExampleAnalysis::FromExample(example));
  try
  {
    Synthesize(rules, Periodic(7));
    FAIL() << "a 7-periodic checkerboard does not exist";
  }
  catch (const Error& e)
  {
    const std::string m = e.what();
    EXPECT_NE(m.find("repeats every 2 sites along x"), std::string::npos) << m;
    EXPECT_NE(m.find("use a multiple of 2 (8)"), std::string::npos) << m;
  }
  SynthesisOptions period = Periodic(12);
  period.Translate[0].Period = 5; // the period, not the size, must close
  EXPECT_THROW(Synthesize(rules, period), Error);
  const SynthesisResult r = Synthesize(rules, Periodic(8));
  ASSERT_TRUE(r.Succeeded()) << r.Message;
  EXPECT_TRUE(CheckConsistency(example, r.Model).Consistent);
}

TEST(PeriodCheck, BlocksOfASetWithoutATrivialStartStartUndecided)
{
  const LabelGrid example = Checkerboard();
  const auto rules = AdjacencyRules::FromExample(ExampleAnalysis::FromExample(example));
  SynthesisOptions o;
  o.Size = { { 12, 12, 1 } };
  o.BlockSize = { { 6, 6, 1 } };
  o.Seed = 1;
  o.StartFrom = BlockStart::Trivial; // no label tiles space: said so
  EXPECT_THROW(Synthesize(rules, o), Error);
  o.StartFrom = BlockStart::Automatic;
  const SynthesisResult r = Synthesize(rules, o);
  ASSERT_TRUE(r.Succeeded()) << r.Message;
  EXPECT_EQ(r.Statistics.StartFrom, "undecided");
  EXPECT_TRUE(CheckConsistency(example, r.Model).Consistent);
}
