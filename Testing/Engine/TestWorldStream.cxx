// SPDX-License-Identifier: BSD-3-Clause
// Streamed worlds (SynthesizeStreamed): the slabs a wavefront of blocks hands out equal the same
// sites of a whole run (label grids and tilesets, failed and repaired blocks, any thread count,
// any slab thickness), a resumed stream equals the rest of a fresh one, and the slabs pass the
// example's pairs, seams included.
#include "Core/Error.h"
#include "Core/Index.h"
#include "Core/WorldSchedule.h"
#include "Discrete/ConsistencyCheck.h"
#include "Discrete/DiscreteSynthesis.h"
#include "Discrete/ExampleAnalysis.h"
#include "Formats/Tileset.h"

#include "Fixtures.h"

#include <gtest/gtest.h>

#include <array>
#include <set>

using namespace msynth;

namespace
{
Tileset LinesTileset()
{
  return ReadTilesetFile(std::string(MSYNTH_DATA) + "/Tilesets/Lines.xml");
}

/// Lines over 70 x 150 in 6 x 6 blocks of one attempt without backtracking: blocks fail, so the
/// repair passes do work.
SynthesisOptions FailingBlocks()
{
  SynthesisOptions o;
  o.Size = { { 70, 150, 1 } };
  o.BlockSize = { { 6, 6, 1 } };
  o.AttemptsPerBlock = 1;
  o.BacktracksPerAttempt = 0;
  return o;
}

/// The slabs of a streamed run from @p first, pasted into a model of the world's size (sites of
/// earlier slabs stay -2); fails the test when the stream fails.
LabelGrid Stream(const AdjacencyRules& rules, const SynthesisOptions& o, std::int64_t thickness,
  int first = 0, SynthesisResult* result = nullptr,
  std::vector<std::vector<BlockFailure>>* handed = nullptr,
  const std::vector<BlockFailure>& kept = {})
{
  const StreamLayout layout = PlanStream(o, thickness);
  LabelGrid world(o.Size[0], o.Size[1], o.Size[2], -2);
  int expected = first;
  const SynthesisResult r = SynthesizeStreamed(
    rules, o, layout,
    [&](StreamChunk&& c)
    {
      EXPECT_EQ(c.Index, expected++);
      if (handed)
        handed->push_back(c.Failures);
      for (std::int64_t z = c.Low[2]; z < c.High[2]; ++z)
        for (std::int64_t y = c.Low[1]; y < c.High[1]; ++y)
          for (std::int64_t x = c.Low[0]; x < c.High[0]; ++x)
            world.Set(x, y, z, c.Model.At(x - c.Low[0], y - c.Low[1], z - c.Low[2]));
      return true;
    },
    first, kept);
  EXPECT_TRUE(r.Succeeded()) << r.Message;
  EXPECT_EQ(expected, layout.Chunks);
  if (result)
    *result = r;
  return world;
}
} // namespace

TEST(WorldStream, SlabsEqualTheWholeRun)
{
  const LabelGrid village = msynth_test::Village();
  const auto rules = AdjacencyRules::FromExample(ExampleAnalysis::FromExample(village));
  SynthesisOptions o;
  o.Size = { { 30, 52, 5 } };
  o.BlockSize = { { 8, 8, 5 } };
  for (std::uint64_t seed : { 1, 2 })
    for (int threads : { 1, 2 })
    {
      o.Seed = seed;
      o.Threads = threads;
      const SynthesisResult whole = Synthesize(rules, o);
      ASSERT_TRUE(whole.Succeeded()) << whole.Message;
      for (std::int64_t thickness : { 5, 16, 52 })
        EXPECT_EQ(Stream(rules, o, thickness).Data(), whole.Model.Data())
          << "seed " << seed << ", " << threads << " threads, slabs of " << thickness;
    }
}

TEST(WorldStream, FailedAndRepairedBlocksStreamAsInTheWholeRun)
{
  const Tileset lines = LinesTileset();
  const AdjacencyRules rules = lines.Rules();
  SynthesisOptions o = FailingBlocks();
  o.Seed = 11;
  const SynthesisResult whole = Synthesize(rules, o);
  ASSERT_TRUE(whole.Succeeded()) << whole.Message;
  EXPECT_GT(whole.Statistics.BlocksRepaired, 0) << whole.Message;
  SynthesisResult streamed;
  const LabelGrid world = Stream(rules, o, 20, 0, &streamed);
  EXPECT_EQ(world.Data(), whole.Model.Data());
  EXPECT_TRUE(CheckConsistency(lines.Pairs, world).Consistent);
  EXPECT_EQ(streamed.Statistics.Blocks, whole.Statistics.Blocks);
  EXPECT_EQ(streamed.Statistics.BlocksRepaired, whole.Statistics.BlocksRepaired);
  EXPECT_EQ(streamed.Statistics.BlocksFailed, whole.Statistics.BlocksFailed);
  EXPECT_EQ(streamed.Statistics.Failures.size(), whole.Statistics.Failures.size());

  // Resumed at slab 4: the blocks its cone needs run again, and slabs 4.. equal the whole run.
  const LabelGrid rest = Stream(rules, o, 20, 4);
  for (std::int64_t y = 79; y < o.Size[1]; ++y) // from the layer it shares with slab 3
    for (std::int64_t x = 0; x < o.Size[0]; ++x)
      ASSERT_EQ(rest.At(x, y, 0), whole.Model.At(x, y, 0)) << x << " " << y;
  EXPECT_EQ(rest.At(0, 78, 0), -2);
}

TEST(WorldStream, AResumedStreamReportsTheWorldsFailures)
{
  // Issue 48, item 7: a resumed stream runs first passes of blocks below its first slab whose
  // repairs it does not need; it reported them as failed. Each slab hands out the failed blocks
  // that start in it, and a resumed run takes those of the slabs it keeps.
  const Tileset lines = LinesTileset();
  const AdjacencyRules rules = lines.Rules();
  SynthesisOptions o = FailingBlocks();
  auto origins = [](const std::vector<BlockFailure>& failures)
  {
    std::set<std::array<std::int64_t, 4>> keys;
    for (const BlockFailure& f : failures)
      keys.insert({ { f.Block, f.Origin[0], f.Origin[1], f.Origin[2] } });
    return keys;
  };
  int withFailures = 0;
  for (std::uint64_t seed : { 11, 12, 13, 14 })
  {
    o.Seed = seed;
    const SynthesisResult whole = Synthesize(rules, o);
    ASSERT_TRUE(whole.Succeeded()) << whole.Message;
    SynthesisResult streamed;
    std::vector<std::vector<BlockFailure>> handed;
    Stream(rules, o, 20, 0, &streamed, &handed);
    EXPECT_EQ(origins(streamed.Statistics.Failures), origins(whole.Statistics.Failures));
    std::vector<BlockFailure> all;
    for (const auto& slab : handed)
      all.insert(all.end(), slab.begin(), slab.end());
    EXPECT_EQ(origins(all), origins(whole.Statistics.Failures)) << "each failure in one slab";
    withFailures += whole.Statistics.BlocksFailed > 0;
    for (int first : { 2, 4, 6 })
    {
      std::vector<BlockFailure> kept;
      for (int j = 0; j < first; ++j)
        for (BlockFailure f : handed[ToIndex(j)])
        {
          f.Block = -1; // as read back from a file: recomputed from the origin
          kept.push_back(f);
        }
      SynthesisResult resumed;
      const LabelGrid rest = Stream(rules, o, 20, first, &resumed, nullptr, kept);
      for (std::int64_t y = 20 * first; y < o.Size[1]; ++y)
        for (std::int64_t x = 0; x < o.Size[0]; ++x)
          ASSERT_EQ(rest.At(x, y, 0), whole.Model.At(x, y, 0))
            << x << " " << y << ", seed " << seed << ", resumed at slab " << first;
      EXPECT_EQ(resumed.Statistics.BlocksFailed, whole.Statistics.BlocksFailed)
        << "seed " << seed << ", resumed at slab " << first;
      EXPECT_EQ(origins(resumed.Statistics.Failures), origins(whole.Statistics.Failures))
        << "seed " << seed << ", resumed at slab " << first;
    }
  }
  EXPECT_GT(withFailures, 0) << "no seed left a block failed: the test checks too little";
}

TEST(WorldStream, TheUndecidedStartStreams)
{
  const LabelGrid village = msynth_test::Village();
  const auto rules = AdjacencyRules::FromExample(ExampleAnalysis::FromExample(village));
  SynthesisOptions o;
  o.Size = { { 24, 60, 5 } };
  o.BlockSize = { { 12, 12, 5 } };
  o.StartFrom = BlockStart::Undecided;
  o.Seed = 3;
  const SynthesisResult whole = Synthesize(rules, o);
  ASSERT_TRUE(whole.Succeeded()) << whole.Message;
  EXPECT_EQ(Stream(rules, o, 10).Data(), whole.Model.Data());
}

TEST(WorldStream, LayoutsAndRefusals)
{
  SynthesisOptions o;
  o.Size = { { 100, 40, 1 } };
  o.BlockSize = { { 10, 10, 1 } };
  StreamLayout layout = PlanStream(o, 30);
  EXPECT_EQ(layout.Axis, 0); // the axis with the most blocks
  EXPECT_EQ(layout.Chunks, 4);
  WorldBox lo, hi;
  layout.Box(3, lo, hi);
  EXPECT_EQ(lo, (WorldBox{ { 90, 0, 0 } }));
  EXPECT_EQ(hi, (WorldBox{ { 100, 40, 1 } }));
  o.Size = { { 100, 100, 1 } };
  EXPECT_EQ(PlanStream(o, 30).Axis, 1); // a tie goes to the higher axis
  o.BlockSize = { { 0, 0, 0 } };
  EXPECT_THROW(PlanStream(o), Error); // one block is the whole world
  o.BlockSize = { { 10, 10, 1 } };
  o.Symmetry[0].Enabled = true;
  EXPECT_THROW(PlanStream(o), Error);
}

// Pins stream as they run in regions (WindowRun.h): each window first grows to hold the pin
// placements it meets, so the slabs equal the whole run with the same pins, which they keep.
TEST(WorldStream, PinsStreamAsInTheWholeRun)
{
  const Tileset lines = LinesTileset();
  const AdjacencyRules rules = lines.Rules();
  SynthesisOptions source;
  source.Size = { { 32, 32, 1 } };
  source.Seed = 99;
  const SynthesisResult drawn = Synthesize(rules, source);
  ASSERT_TRUE(drawn.Succeeded()) << drawn.Message;
  // Patches of a model placed in a 50 x 45 pin grid at (20, 15): (source corner, size, target).
  LabelGrid pins(50, 45, 1, FreeSite);
  const std::array<std::array<std::int64_t, 6>, 3> patches{ { { { 10, 10, 6, 6, 0, 0 } },
    { { 3, 20, 3, 8, 20, 25 } }, { { 5, 5, 1, 1, 49, 44 } } } };
  for (const auto& p : patches)
    for (std::int64_t y = 0; y < p[3]; ++y)
      for (std::int64_t x = 0; x < p[2]; ++x)
        pins.Set(p[4] + x, p[5] + y, 0, drawn.Model.At(p[0] + x, p[1] + y, 0));
  SynthesisOptions o;
  o.Size = { { 96, 80, 1 } };
  o.BlockSize = { { 16, 16, 1 } };
  o.Pins = pins;
  o.PinsOrigin = WorldBox{ { 20, 15, 0 } };
  for (std::uint64_t seed : { 3, 4 })
  {
    o.Seed = seed;
    const SynthesisResult whole = Synthesize(rules, o);
    ASSERT_TRUE(whole.Succeeded()) << whole.Message;
    for (std::int64_t thickness : { 7, 30 })
    {
      const LabelGrid world = Stream(rules, o, thickness);
      EXPECT_EQ(world.Data(), whole.Model.Data()) << "seed " << seed << ", slabs of " << thickness;
      EXPECT_TRUE(CheckConsistency(lines.Pairs, world).Consistent);
      for (std::int64_t y = 0; y < 45; ++y) // every pin kept, counted here
        for (std::int64_t x = 0; x < 50; ++x)
        {
          if (pins.At(x, y, 0) != FreeSite)
          {
            ASSERT_EQ(world.At(x + 20, y + 15, 0), pins.At(x, y, 0)) << x << " " << y;
          }
        }
    }
  }
}

// An open network (LABELS:open) is kept by each block on what it reads: regions and streams of a
// world with one equal the whole run, and it closes fewer components off than a run without it.
TEST(WorldStream, OpenNetworksStreamAndRegionAsInTheWholeRun)
{
  const Tileset lines = LinesTileset();
  const AdjacencyRules rules = lines.Rules();
  SynthesisOptions o;
  o.Size = { { 96, 80, 1 } };
  o.BlockSize = { { 16, 16, 1 } };
  o.Seed = 1;
  for (const Label v : { 1, 2, 3, 4, 5, 6 }) // the tiles line and corner, every orientation
  {
    o.Connected.Values.push_back(v);
    if (lines.LabelSides[static_cast<std::size_t>(v)] >= 0)
      o.Connected.Sides[v] =
        static_cast<std::uint8_t>(lines.LabelSides[static_cast<std::size_t>(v)]);
  }
  o.Connected.Open = true;
  const SynthesisResult whole = Synthesize(rules, o);
  ASSERT_TRUE(whole.Succeeded()) << whole.Message;
  EXPECT_GT(whole.Connected.Redone, 0);
  o.Threads = 1; // the same model on one thread (networks run their blocks on one anyway)
  EXPECT_EQ(Synthesize(rules, o).Model.Data(), whole.Model.Data());
  o.Threads = 0;
  EXPECT_EQ(Stream(rules, o, 20).Data(), whole.Model.Data());
  const WorldBox lo{ { 30, 20, 0 } }, hi{ { 70, 60, 1 } };
  const SynthesisResult region = SynthesizeRegion(rules, o, lo, hi);
  ASSERT_TRUE(region.Succeeded()) << region.Message;
  for (std::int64_t y = lo[1]; y < hi[1]; ++y)
    for (std::int64_t x = lo[0]; x < hi[0]; ++x)
      ASSERT_EQ(region.Model.At(x - lo[0], y - lo[1], 0), whole.Model.At(x, y, 0));
  o.Connected.Open = false; // a bounded network needs the whole world
  EXPECT_THROW(SynthesizeRegion(rules, o, lo, hi), Error);
}
