// SPDX-License-Identifier: BSD-3-Clause
// Constraints together (issue 44: pins, label counts and a connected network in one run): a
// town of roads, houses and grass is synthesized with its roads one network, a number of houses
// and pinned sites, whole and in blocks; every model is verified here by a union-find, a count
// and a look at every pin of the test's own, and by CheckConsistency (the pairs recomputed from
// the example). An open network with counts and pins gives regions and streams equal to the
// whole run; combinations that cannot work are one line.
#include "Core/Error.h"
#include "Core/WorldSchedule.h"
#include "Discrete/ConsistencyCheck.h"
#include "Discrete/DiscreteSynthesis.h"

#include "Fixtures.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <numeric>
#include <string>
#include <vector>

using namespace msynth;

namespace
{
constexpr Label Grass = 0, Road = 1, House = 2;

/// A small town: roads (1) that cross and end, houses (2) beside them, grass (0).
LabelGrid Town()
{
  return msynth_test::Grid2D({
    { 0, 0, 2, 1, 0, 0, 0, 0 },
    { 0, 0, 2, 1, 2, 2, 0, 0 },
    { 1, 1, 1, 1, 1, 1, 1, 1 },
    { 0, 2, 0, 1, 0, 0, 2, 0 },
    { 0, 2, 0, 1, 0, 0, 2, 0 },
    { 0, 0, 0, 1, 1, 1, 1, 1 },
    { 0, 2, 2, 1, 0, 2, 0, 1 },
    { 0, 0, 0, 1, 0, 0, 0, 1 },
  });
}

struct Pin
{
  std::int64_t X, Y;
  Label Value;
};

/// Roads pinned near the four corners (the network must join them) and two houses.
const std::vector<Pin> TownPins = { { 3, 3, Road }, { 28, 3, Road }, { 3, 28, Road },
  { 28, 28, Road }, { 16, 10, House }, { 10, 20, House } };

LabelCount Count(Label value, std::int64_t low, std::int64_t high)
{
  LabelCount c;
  c.Values = { value };
  c.Name = std::to_string(value);
  c.Minimum = low;
  c.Maximum = high;
  return c;
}

SynthesisOptions TownOptions(std::array<std::int64_t, 3> block, std::uint64_t seed)
{
  SynthesisOptions o;
  o.Size = { { 32, 32, 1 } };
  o.BlockSize = block;
  o.Seed = seed;
  LabelGrid pins(32, 32, 1, FreeSite);
  for (const Pin& p : TownPins)
    pins.Set(p.X, p.Y, 0, p.Value);
  o.Pins = std::move(pins);
  o.Connected.Values = { Road };
  o.Connected.Name = "roads";
  o.Counts = { Count(House, 60, 100) };
  return o;
}

/// The components of the sites of @p model holding @p value, face neighbours joined: a
/// union-find of the test's own.
std::int64_t Components(const LabelGrid& model, Label value)
{
  const auto d = model.Dimensions();
  const std::int64_t n = d[0] * d[1] * d[2];
  std::vector<std::int64_t> parent(static_cast<std::size_t>(n));
  std::iota(parent.begin(), parent.end(), 0);
  const auto find = [&](std::int64_t i)
  {
    while (parent[static_cast<std::size_t>(i)] != i)
      i = parent[static_cast<std::size_t>(i)];
    return i;
  };
  const auto on = [&](std::int64_t i)
  { return model.Data()[static_cast<std::size_t>(i)] == value; };
  const std::int64_t stride[3] = { 1, d[0], d[0] * d[1] };
  for (std::int64_t i = 0; i < n; ++i)
    for (std::size_t a = 0; a < 3; ++a)
      if ((i / stride[a]) % d[a] + 1 < d[a] && on(i) && on(i + stride[a]))
        parent[static_cast<std::size_t>(find(i))] = find(i + stride[a]);
  std::int64_t count = 0;
  for (std::int64_t i = 0; i < n; ++i)
    count += on(i) && find(i) == i ? 1 : 0;
  return count;
}

std::int64_t Sites(const LabelGrid& model, Label value)
{
  return static_cast<std::int64_t>(std::count(model.Data().begin(), model.Data().end(), value));
}

std::string ErrorOf(const AdjacencyRules& rules, const SynthesisOptions& o)
{
  try
  {
    Synthesize(rules, o);
  }
  catch (const Error& e)
  {
    return e.what();
  }
  return "";
}
} // namespace

// The done-when of issue 44 on a small town: one road network through four pinned road sites,
// 60 to 100 houses (unsteered the town holds far more), two pinned houses; whole and in blocks,
// on seeds, 1 and 2 threads giving the same model.
TEST(ConstraintsCompose, NetworkCountsAndPinsHoldTogether)
{
  const LabelGrid example = Town();
  const AdjacencyRules rules = AdjacencyRules::FromExample(ExampleAnalysis::FromExample(example));
  for (const auto& block :
    { std::array<std::int64_t, 3>{ { 0, 0, 0 } }, std::array<std::int64_t, 3>{ { 16, 16, 1 } } })
    for (std::uint64_t seed : { 1u, 2u, 3u })
    {
      SynthesisOptions o = TownOptions(block, seed);
      const SynthesisResult r = Synthesize(rules, o);
      ASSERT_TRUE(r.Succeeded()) << "block " << block[0] << ", seed " << seed << ": " << r.Message;
      EXPECT_TRUE(CheckConsistency(example, r.Model).Consistent);
      EXPECT_EQ(Components(r.Model, Road), 1) << "block " << block[0] << ", seed " << seed;
      const std::int64_t houses = Sites(r.Model, House);
      EXPECT_GE(houses, 60) << "block " << block[0] << ", seed " << seed;
      EXPECT_LE(houses, 100) << "block " << block[0] << ", seed " << seed;
      ASSERT_EQ(r.Counts.size(), 1u);
      EXPECT_EQ(r.Counts[0].Achieved, houses);
      EXPECT_EQ(r.Connected.Components, 1);
      for (const Pin& p : TownPins)
        EXPECT_EQ(r.Model.At(p.X, p.Y, 0), p.Value) << "pin (" << p.X << ", " << p.Y << ")";
      if (block[0] > 0 && seed == 1)
      {
        o.Threads = 2;
        EXPECT_EQ(Synthesize(rules, o).Model.Data(), r.Model.Data());
      }
    }
}

// The network's own labels counted: the roads one network of 380 to 460 sites (unsteered the
// town holds about 460 to 500; the repairs that join them must keep the count), whole and in
// blocks.
TEST(ConstraintsCompose, ACountOfTheNetworksOwnLabelsHolds)
{
  const LabelGrid example = Town();
  const AdjacencyRules rules = AdjacencyRules::FromExample(ExampleAnalysis::FromExample(example));
  for (const auto& block :
    { std::array<std::int64_t, 3>{ { 0, 0, 0 } }, std::array<std::int64_t, 3>{ { 16, 16, 1 } } })
    for (std::uint64_t seed : { 1u, 2u })
    {
      SynthesisOptions o = TownOptions(block, seed);
      o.Counts = { Count(Road, 380, 460) };
      const SynthesisResult r = Synthesize(rules, o);
      ASSERT_TRUE(r.Succeeded()) << "block " << block[0] << ", seed " << seed << ": " << r.Message;
      EXPECT_TRUE(CheckConsistency(example, r.Model).Consistent);
      EXPECT_EQ(Components(r.Model, Road), 1);
      EXPECT_GE(Sites(r.Model, Road), 380);
      EXPECT_LE(Sites(r.Model, Road), 460);
    }
}

// Pinned roads farther apart than a count of roads can join: the run fails in one line that
// says the counts turned the repairs down, not with a model that misses one of them.
TEST(ConstraintsCompose, ANetworkTheCountsCannotCarryFailsInOneLine)
{
  const LabelGrid example = Town();
  const AdjacencyRules rules = AdjacencyRules::FromExample(ExampleAnalysis::FromExample(example));
  SynthesisOptions o = TownOptions({ { 0, 0, 0 } }, 1);
  o.Counts = { Count(Road, 0, 20) };
  const SynthesisResult r = Synthesize(rules, o);
  ASSERT_FALSE(r.Succeeded());
  EXPECT_EQ(r.Message.find('\n'), std::string::npos) << r.Message;
  EXPECT_NE(r.Message.find("the network of roads"), std::string::npos) << r.Message;
  EXPECT_NE(r.Message.find("label counts"), std::string::npos) << r.Message;
}

// An open network (the meaning in a world) with counts and pins: every block keeps all three by
// what it reads, so regions equal the same sites of the whole run and a stream equals it.
TEST(ConstraintsCompose, OpenNetworkCountsAndPinsInRegionsAndStreams)
{
  const LabelGrid example = Town();
  const AdjacencyRules rules = AdjacencyRules::FromExample(ExampleAnalysis::FromExample(example));
  SynthesisOptions o = TownOptions({ { 16, 16, 1 } }, 2);
  o.Size = { { 48, 40, 1 } };
  LabelGrid pins(48, 40, 1, FreeSite);
  for (const Pin& p : TownPins)
    pins.Set(p.X + 8, p.Y + 4, 0, p.Value);
  o.Pins = std::move(pins);
  o.Connected.Open = true;
  o.Counts = { Count(House, 150, 260) };
  const SynthesisResult whole = Synthesize(rules, o);
  ASSERT_TRUE(whole.Succeeded()) << whole.Message;
  EXPECT_TRUE(CheckConsistency(example, whole.Model).Consistent);
  EXPECT_GE(Sites(whole.Model, House), 150);
  EXPECT_LE(Sites(whole.Model, House), 260);
  for (const Pin& p : TownPins)
    EXPECT_EQ(whole.Model.At(p.X + 8, p.Y + 4, 0), p.Value);
  for (const auto& [lo, hi] : { std::pair<WorldBox, WorldBox>{ { { 0, 0, 0 } }, { { 20, 14, 1 } } },
         { { { 9, 5, 0 } }, { { 41, 30, 1 } } }, { { { 30, 20, 0 } }, { { 48, 40, 1 } } } })
  {
    const SynthesisResult region = SynthesizeRegion(rules, o, lo, hi);
    ASSERT_TRUE(region.Succeeded()) << region.Message;
    for (std::int64_t y = lo[1]; y < hi[1]; ++y)
      for (std::int64_t x = lo[0]; x < hi[0]; ++x)
        ASSERT_EQ(region.Model.At(x - lo[0], y - lo[1], 0), whole.Model.At(x, y, 0))
          << "(" << x << ", " << y << ")";
  }
  LabelGrid streamed(48, 40, 1, -2);
  const SynthesisResult r = SynthesizeStreamed(rules, o, PlanStream(o, 8),
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

// What cannot work is one line before any work: a network kept by repairs of the whole model
// (not open, or with a path) in a region, a network or counts with soft constraints or symmetry.
TEST(ConstraintsCompose, RefusedCombinationsSayWhyInOneLine)
{
  const LabelGrid example = Town();
  const AdjacencyRules rules = AdjacencyRules::FromExample(ExampleAnalysis::FromExample(example));
  SynthesisOptions o = TownOptions({ { 16, 16, 1 } }, 1);
  try
  {
    SynthesizeRegion(rules, o, { { 0, 0, 0 } }, { { 16, 16, 1 } });
    FAIL() << "a region kept a closed network";
  }
  catch (const Error& e)
  {
    const std::string what = e.what();
    EXPECT_NE(what.find("connected network but an open one"), std::string::npos) << what;
    EXPECT_EQ(what.find('\n'), std::string::npos);
  }
  o.Soft.TargetFractions[House] = 0.2;
  o.Counts.clear();
  EXPECT_NE(ErrorOf(rules, o).find("cannot be combined with soft constraints"), std::string::npos);
  o = TownOptions({ { 0, 0, 0 } }, 1);
  o.Symmetry[0].Enabled = true;
  EXPECT_NE(ErrorOf(rules, o).find("cannot be combined with symmetry"), std::string::npos);
}
