// SPDX-License-Identifier: BSD-3-Clause
// Label counts (SynthesisOptions::Counts): every model of a matrix (whole and in blocks, seeds,
// 1 and 2 threads) is verified by counting its labels here and by CheckConsistency (the pairs
// recomputed from the example); impossible counts are one line before any work.
#include "Core/Error.h"
#include "Core/WorldSchedule.h"
#include "Discrete/ConsistencyCheck.h"
#include "Discrete/DiscreteSynthesis.h"

#include "Fixtures.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <vector>

using namespace msynth;

using msynth_test::Village;

namespace
{
LabelCount Count(Label value, std::int64_t low, std::int64_t high)
{
  LabelCount c;
  c.Values = { value };
  c.Name = std::to_string(value);
  c.Minimum = low;
  c.Maximum = high;
  return c;
}

SynthesisOptions Options(std::array<std::int64_t, 3> block, std::uint64_t seed, int threads)
{
  SynthesisOptions o;
  o.Size = { { 24, 24, 5 } };
  o.BlockSize = block;
  o.Seed = seed;
  o.Threads = threads;
  o.Boundary[4] = 1; // ground along -z
  return o;
}

std::int64_t Sites(const LabelGrid& model, Label value)
{
  return static_cast<std::int64_t>(std::count(model.Data().begin(), model.Data().end(), value));
}

std::string ErrorOf(const SynthesisOptions& o)
{
  try
  {
    const LabelGrid example = Village();
    Synthesize(AdjacencyRules::FromExample(ExampleAnalysis::FromExample(example)), o);
  }
  catch (const Error& e)
  {
    return e.what();
  }
  return "";
}
} // namespace

// Walls (2) and roofs (3) within ranges far from what the solver makes unsteered, whole and in
// blocks, on seeds and thread counts; the same model for 1 and 2 threads.
TEST(LabelCounts, CountsHoldOnEveryRunOfTheMatrix)
{
  const LabelGrid example = Village();
  const AdjacencyRules rules = AdjacencyRules::FromExample(ExampleAnalysis::FromExample(example));
  const std::vector<LabelCount> counts = { Count(2, 60, 90), Count(3, 40, 60), Count(0, 0, 2300) };
  for (const auto& block :
    { std::array<std::int64_t, 3>{ { 0, 0, 0 } }, std::array<std::int64_t, 3>{ { 12, 12, 5 } } })
    for (std::uint64_t seed : { 1u, 2u, 3u })
    {
      LabelGrid first;
      for (int threads : { 1, 2 })
      {
        SynthesisOptions o = Options(block, seed, threads);
        o.Counts = counts;
        const SynthesisResult r = Synthesize(rules, o);
        ASSERT_TRUE(r.Succeeded()) << r.Message;
        const ConsistencyReport report = CheckConsistency(example, r.Model);
        EXPECT_TRUE(report.Consistent) << (report.First.empty() ? "" : report.First[0].Describe());
        ASSERT_EQ(r.Counts.size(), counts.size());
        for (std::size_t c = 0; c < counts.size(); ++c)
        {
          const std::int64_t n = Sites(r.Model, counts[c].Values[0]);
          EXPECT_GE(n, counts[c].Minimum) << "label " << counts[c].Name << ", seed " << seed;
          EXPECT_LE(n, counts[c].Maximum) << "label " << counts[c].Name << ", seed " << seed;
          EXPECT_EQ(r.Counts[c].Achieved, n);
        }
        if (threads == 1)
          first = r.Model;
        else
          EXPECT_TRUE(r.Model.Data() == first.Data()) << "the same model on any thread count";
      }
    }
}

// Without counts nothing changes (TestOutputHashes pins the models); a count of 0 to the whole
// output changes nothing either but is reported.
TEST(LabelCounts, ResultsReportTheCounts)
{
  const LabelGrid example = Village();
  const AdjacencyRules rules = AdjacencyRules::FromExample(ExampleAnalysis::FromExample(example));
  SynthesisOptions o = Options({ { 12, 12, 5 } }, 4, 1);
  const SynthesisResult plain = Synthesize(rules, o);
  ASSERT_TRUE(plain.Succeeded());
  EXPECT_TRUE(plain.Counts.empty());
  o.Counts = { Count(3, 0, 2880) };
  const SynthesisResult counted = Synthesize(rules, o);
  ASSERT_TRUE(counted.Succeeded()) << counted.Message;
  ASSERT_EQ(counted.Counts.size(), 1u);
  EXPECT_EQ(counted.Counts[0].Achieved, Sites(counted.Model, 3));
}

// Impossible counts and options that cannot keep counts are one line before any work.
TEST(LabelCounts, ImpossibleCountsAreOneLineBeforeAnyWork)
{
  const std::array<std::int64_t, 3> whole{ { 0, 0, 0 } };
  SynthesisOptions o = Options(whole, 1, 1);
  o.Counts = { Count(7, 0, 5) };
  EXPECT_EQ(ErrorOf(o), "the count of label 7: label 7 does not occur in the example");
  o.Counts = { Count(2, 3000, 3000) };
  EXPECT_EQ(
    ErrorOf(o), "the count of label 2 asks for at least 3000 sites, but the output has 2880");
  o.Counts = { Count(2, 2000, 2880), Count(3, 1000, 2880) };
  EXPECT_EQ(
    ErrorOf(o), "the label counts ask for at least 3000 sites together, but the output has 2880");
  o.Counts = { Count(0, 0, 10), Count(1, 0, 10), Count(2, 0, 10), Count(3, 0, 10) };
  EXPECT_EQ(
    ErrorOf(o), "the label counts allow at most 40 sites together, but the output has 2880");
  o.Counts = { Count(2, 5, 3) };
  EXPECT_EQ(ErrorOf(o), "the count of label 2 asks for 5 to 3 sites (need 0 <= MIN <= MAX)");
  o.Counts = { Count(2, 0, 5), Count(2, 0, 5) };
  EXPECT_EQ(ErrorOf(o), "the count of label 2: label 2 is counted twice");
  // The ground boundary leaves 2304 sites.
  o.Counts = { Count(2, 2500, 2880) };
  EXPECT_EQ(ErrorOf(o),
    "label 2 can hold at most 2304 sites (the others are boundary labels or pins), fewer than its "
    "minimum 2500");
  // The ground boundary already holds 576 sites of label 1.
  o.Counts = { Count(1, 0, 100) };
  EXPECT_EQ(ErrorOf(o),
    "the boundary labels and pins already place 576 sites of label 1, more than its maximum 100");
  o.Counts = { Count(3, 0, 10) };
  o.Symmetry[0].Enabled = true;
  EXPECT_EQ(ErrorOf(o),
    "label counts cannot be combined with symmetry (only a part of the output is synthesized)");
}

// Counts of a world are shared over its blocks by position alone (LabelCounts.h): regions equal
// the same sites of the whole run, a stream equals the whole run, and the whole world's total,
// counted here, is in range; a guide region's count needs the whole world (a guide), refused.
TEST(LabelCounts, RegionsAndStreamsOfAWorldKeepTheWholeRunsCounts)
{
  const LabelGrid example = Village();
  const AdjacencyRules rules = AdjacencyRules::FromExample(ExampleAnalysis::FromExample(example));
  SynthesisOptions o = Options({ { 12, 12, 5 } }, 1, 1);
  o.Size = { { 48, 36, 5 } };
  o.Counts = { Count(2, 240, 360), Count(3, 160, 240) };
  for (std::uint64_t seed : { 1u, 2u })
  {
    o.Seed = seed;
    const SynthesisResult whole = Synthesize(rules, o);
    ASSERT_TRUE(whole.Succeeded()) << whole.Message;
    EXPECT_GE(Sites(whole.Model, 2), 240);
    EXPECT_LE(Sites(whole.Model, 2), 360);
    EXPECT_GE(Sites(whole.Model, 3), 160);
    EXPECT_LE(Sites(whole.Model, 3), 240);
    for (const auto& [lo, hi] :
      { std::pair<WorldBox, WorldBox>{ { { 0, 0, 0 } }, { { 20, 14, 5 } } },
        { { { 17, 9, 0 } }, { { 41, 30, 5 } } }, { { { 30, 20, 0 } }, { { 48, 36, 5 } } } })
    {
      const SynthesisResult region = SynthesizeRegion(rules, o, lo, hi);
      ASSERT_TRUE(region.Succeeded()) << region.Message;
      for (std::int64_t z = lo[2]; z < hi[2]; ++z)
        for (std::int64_t y = lo[1]; y < hi[1]; ++y)
          for (std::int64_t x = lo[0]; x < hi[0]; ++x)
            ASSERT_EQ(region.Model.At(x - lo[0], y - lo[1], z - lo[2]), whole.Model.At(x, y, z));
    }
    LabelGrid streamed(48, 36, 5, -2);
    const SynthesisResult r = SynthesizeStreamed(rules, o, PlanStream(o, 7),
      [&](StreamChunk&& c)
      {
        for (std::int64_t z = c.Low[2]; z < c.High[2]; ++z)
          for (std::int64_t y = c.Low[1]; y < c.High[1]; ++y)
            for (std::int64_t x = c.Low[0]; x < c.High[0]; ++x)
              streamed.Set(x, y, z, c.Model.At(x - c.Low[0], y - c.Low[1], z - c.Low[2]));
        return true;
      });
    ASSERT_TRUE(r.Succeeded()) << r.Message;
    EXPECT_EQ(streamed.Data(), whole.Model.Data());
  }
  GuideVolume halves;
  halves.Dims = { { 2, 1, 1 } };
  halves.Regions = { 0, 1 };
  o.Guide = halves;
  o.Counts[0].Region = 1;
  EXPECT_THROW(SynthesizeRegion(rules, o, { { 0, 0, 0 } }, { { 12, 12, 5 } }), Error);
}

namespace
{
/// A guide of two regions over the village's box: x < 12 is region 0, x >= 12 region 1.
GuideVolume TwoRegions()
{
  GuideVolume g;
  g.Dims = { { 2, 1, 1 } };
  g.Regions = { 0, 1 };
  return g;
}

LabelCount InRegion(LabelCount c, std::int32_t region)
{
  c.Region = region;
  return c;
}

/// The sites of @p model holding @p value in the half x < 12 (@p left) or x >= 12, counted here.
std::int64_t SitesInHalf(const LabelGrid& model, Label value, bool left)
{
  std::int64_t n = 0;
  const auto& d = model.Dimensions();
  for (std::int64_t z = 0; z < d[2]; ++z)
    for (std::int64_t y = 0; y < d[1]; ++y)
      for (std::int64_t x = 0; x < d[0]; ++x)
        n += (x < 12) == left && model.At(x, y, z) == value ? 1 : 0;
  return n;
}
} // namespace

// Counts per guide region: roofs (3) many in the left half and few in the right one, walls (2)
// only counted on the right; whole and in blocks, on seeds; counted here by halves.
TEST(LabelCounts, CountsPerGuideRegionHold)
{
  const LabelGrid example = Village();
  const AdjacencyRules rules = AdjacencyRules::FromExample(ExampleAnalysis::FromExample(example));
  const std::vector<LabelCount> counts = { InRegion(Count(3, 150, 220), 0),
    InRegion(Count(3, 50, 100), 1), InRegion(Count(2, 60, 110), 1) };
  for (const auto& block :
    { std::array<std::int64_t, 3>{ { 0, 0, 0 } }, std::array<std::int64_t, 3>{ { 12, 12, 5 } } })
    for (std::uint64_t seed : { 1u, 2u, 3u })
    {
      SynthesisOptions o = Options(block, seed, 2);
      o.Boundary[4].reset(); // as the command runs it (the ranges are measured without ground)
      o.Guide = TwoRegions();
      o.Counts = counts;
      const SynthesisResult r = Synthesize(rules, o);
      ASSERT_TRUE(r.Succeeded()) << r.Message;
      const ConsistencyReport report = CheckConsistency(example, r.Model);
      EXPECT_TRUE(report.Consistent);
      ASSERT_EQ(r.Counts.size(), counts.size());
      for (std::size_t c = 0; c < counts.size(); ++c)
      {
        const std::int64_t n = SitesInHalf(r.Model, counts[c].Values[0], counts[c].Region == 0);
        EXPECT_GE(n, counts[c].Minimum) << "count " << c << ", seed " << seed;
        EXPECT_LE(n, counts[c].Maximum) << "count " << c << ", seed " << seed;
        EXPECT_EQ(r.Counts[c].Achieved, n);
      }
    }
}

// Counts of regions the guide does not have, or cannot hold, are one line before any work.
TEST(LabelCounts, ImpossibleRegionCountsAreOneLineBeforeAnyWork)
{
  SynthesisOptions o = Options({ { 0, 0, 0 } }, 1, 1);
  o.Counts = { InRegion(Count(3, 0, 5), 0) };
  EXPECT_EQ(ErrorOf(o),
    "the count of label 3 in guide region 0 needs a guide with regions (an integer point array "
    "Region)");
  o.Guide = TwoRegions();
  o.Counts = { InRegion(Count(3, 0, 5), 4) };
  EXPECT_EQ(ErrorOf(o),
    "the count of label 3 in guide region 4: the guide's region 4 holds no site of the output");
  o.Counts = { InRegion(Count(3, 1500, 1500), 1) };
  EXPECT_EQ(ErrorOf(o),
    "the count of label 3 in guide region 1 asks for at least 1500 sites, but the region has "
    "1440");
  o.Counts = { InRegion(Count(3, 800, 1440), 1), InRegion(Count(2, 800, 1440), 1) };
  EXPECT_EQ(ErrorOf(o),
    "the label counts ask for at least 1600 sites together, but guide region 1 has 1440");
  o.Counts = { Count(3, 0, 100), InRegion(Count(3, 0, 5), 1) };
  EXPECT_EQ(ErrorOf(o),
    "the count of label 3 in guide region 1: label 3 is counted both in the whole output and in "
    "a guide region");
  // The ground boundary's 288 sites of label 1 in region 0 already pass its maximum.
  o.Counts = { InRegion(Count(1, 0, 100), 0) };
  EXPECT_EQ(ErrorOf(o),
    "the boundary labels and pins already place 288 sites of label 1 in guide region 0, more "
    "than its maximum 100");
}
