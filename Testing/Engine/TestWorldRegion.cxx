// SPDX-License-Identifier: BSD-3-Clause
// A world as a function of its inputs (Core/WorldSchedule.h, SynthesizeRegion): the world's
// block lattice equals the block grid of whole runs, and a region computed alone from its
// dependency cone equals the same sites of a whole run, checked against the example's pairs.
#include "Core/BlockDriver.h"
#include "Core/Error.h"
#include "Core/WorldSchedule.h"
#include "Discrete/ConsistencyCheck.h"
#include "Discrete/DiscreteSynthesis.h"
#include "Discrete/ExampleAnalysis.h"
#include "Formats/Tileset.h"

#include "Fixtures.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <set>

using namespace msynth;

namespace
{
/// The sites [lo, hi) of @p grid.
LabelGrid Crop(const LabelGrid& grid, const WorldBox& lo, const WorldBox& hi)
{
  LabelGrid out(hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]);
  for (std::int64_t z = lo[2]; z < hi[2]; ++z)
    for (std::int64_t y = lo[1]; y < hi[1]; ++y)
      for (std::int64_t x = lo[0]; x < hi[0]; ++x)
        out.Set(x - lo[0], y - lo[1], z - lo[2], grid.At(x, y, z));
  return out;
}
} // namespace

TEST(WorldRegion, TheLatticeIsTheBlockGridOfWholeRuns)
{
  for (const WorldBox n :
    { WorldBox{ { 37, 21, 5 } }, WorldBox{ { 8, 8, 1 } }, WorldBox{ { 64, 3, 9 } } })
    for (const WorldBox m : { WorldBox{ { 8, 8, 5 } }, WorldBox{ { 5, 3, 2 } } })
      for (const std::int64_t overlap : { -1, 0, 2 })
      {
        WorldBox size = m, step{};
        WorldBox mm{};
        BlockGeometry<3>(n, size, { { overlap, overlap, overlap } }, mm, step);
        int phases = 0;
        const auto whole = PlanBoxBlocks<3>(n, mm, step, PhasePolicy::NonTouching, phases);
        const WorldLattice lattice(n, mm, step);
        EXPECT_EQ(lattice.Phases(), phases);
        std::vector<BoxBlock<3>> listed;
        for (int p = 0; p < lattice.Phases(); ++p)
          lattice.Meeting(p, { { 0, 0, 0 } }, n, listed);
        ASSERT_EQ(listed.size(), whole.size());
        for (std::size_t i = 0; i < whole.size(); ++i)
        {
          EXPECT_EQ(listed[i].Index, whole[i].Index);
          EXPECT_EQ(listed[i].Origin, whole[i].Origin);
          EXPECT_EQ(listed[i].Dims, whole[i].Dims);
          EXPECT_EQ(listed[i].Phase, whole[i].Phase);
        }
        // The cone of the whole world is every block.
        EXPECT_EQ(PlanRegion(lattice, { { 0, 0, 0 } }, n).Blocks.size(), whole.size());
      }
}

TEST(WorldRegion, TheConeOfARegionOfAFlatWorldIsAFewBlocksWideWhateverTheWorldsSize)
{
  // 16 x 16 x 4 blocks over 8 layers: three block origins along z, thousands along x and y.
  // Walking the 27 phases backwards, the cone grows along an axis each time that axis' digit
  // of the phase changes; with z's digit changing fastest, x and y grow 9 and 3 times a pass.
  // (With x's digit fastest, x grew 27 times a pass: 1000 sites wide at 4 passes.)
  const WorldBox m{ { 16, 16, 4 } }, lo{ { 980, 1000, 0 } }, hi{ { 1013, 1033, 2 } };
  for (const int passes : { 1, 4 })
  {
    std::vector<std::size_t> blocks;
    for (const std::int64_t side : { 2000, 6000 })
    {
      const WorldBox n{ { side, side, 8 } };
      WorldBox mm{}, step{};
      BlockGeometry<3>(n, m, { { -1, -1, -1 } }, mm, step);
      const WorldLattice lattice(n, mm, step);
      const RegionCone cone = PlanRegion(lattice, lo, hi, passes);
      for (int a = 0; a < 2; ++a)
        EXPECT_LE(cone.WindowHigh[ToIndex(a)] - cone.WindowLow[ToIndex(a)], passes == 1 ? 260 : 960)
          << "axis " << a << ", " << passes << " passes, world " << side;
      std::size_t count = 0;
      for (const auto& pass : cone.Passes)
        count += pass.size();
      blocks.push_back(count);
    }
    EXPECT_EQ(blocks[0], blocks[1]) << "the cone does not depend on the world's size";
  }
}

TEST(WorldRegion, ARegionAloneEqualsTheSameSitesOfAWholeRun)
{
  const LabelGrid village = msynth_test::Village();
  const auto rules = AdjacencyRules::FromExample(ExampleAnalysis::FromExample(village));
  SynthesisOptions o;
  o.Size = { { 40, 36, 5 } };
  o.BlockSize = { { 8, 8, 5 } };
  o.RepairFailedBlocks = false;
  o.Threads = 2;
  for (std::uint64_t seed : { 1, 2 })
  {
    o.Seed = seed;
    const SynthesisResult whole = Synthesize(rules, o);
    ASSERT_TRUE(whole.Succeeded()) << whole.Message;
    for (const auto& [lo, hi] :
      { std::pair<WorldBox, WorldBox>{ { { 13, 9, 0 } }, { { 25, 20, 5 } } },
        { { { 0, 0, 0 } }, { { 7, 40 - 4, 5 } } }, { { { 30, 30, 2 } }, { { 40, 36, 4 } } } })
    {
      o.Threads = seed == 1 ? 1 : 2;
      const SynthesisResult region = SynthesizeRegion(rules, o, lo, hi);
      ASSERT_TRUE(region.Succeeded()) << region.Message;
      EXPECT_EQ(region.Model.Data(), Crop(whole.Model, lo, hi).Data()) << region.Message;
      EXPECT_TRUE(CheckConsistency(village, region.Model).Consistent);
      EXPECT_LE(region.Statistics.Blocks, whole.Statistics.Blocks);
    }
  }
}

TEST(WorldRegion, ATilesetRegionEqualsTheWholeRunAndAFarRegionOfAHugeWorldIsCheap)
{
  const Tileset lines = ReadTilesetFile(std::string(MSYNTH_DATA) + "/Tilesets/Lines.xml");
  const AdjacencyRules rules = lines.Rules();
  SynthesisOptions o;
  o.Size = { { 96, 80, 1 } };
  o.BlockSize = { { 16, 16, 1 } };
  o.RepairFailedBlocks = false;
  o.Seed = 7;
  const SynthesisResult whole = Synthesize(rules, o);
  ASSERT_TRUE(whole.Succeeded()) << whole.Message;
  const WorldBox lo{ { 40, 33, 0 } }, hi{ { 61, 50, 1 } };
  const SynthesisResult region = SynthesizeRegion(rules, o, lo, hi);
  ASSERT_TRUE(region.Succeeded()) << region.Message;
  EXPECT_EQ(region.Model.Data(), Crop(whole.Model, lo, hi).Data());
  EXPECT_TRUE(CheckConsistency(lines.Pairs, region.Model).Consistent);

  // A 64 x 64 region deep inside a world of 10^6 x 10^6 sites.
  o.Size = { { 1000000, 1000000, 1 } };
  const auto start = std::chrono::steady_clock::now();
  const SynthesisResult far =
    SynthesizeRegion(rules, o, { { 654321, 123456, 0 } }, { { 654321 + 64, 123456 + 64, 1 } });
  const double seconds =
    std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  ASSERT_TRUE(far.Succeeded()) << far.Message;
  EXPECT_TRUE(CheckConsistency(lines.Pairs, far.Model).Consistent);
  EXPECT_LT(far.Statistics.Blocks, 2000) << far.Message;
  EXPECT_LT(seconds, 30.0);
  std::set<Label> distinct(far.Model.Data().begin(), far.Model.Data().end());
  EXPECT_GT(distinct.size(), 2u); // not blank
}

TEST(WorldRegion, RepairPassesArePartOfTheSchedule)
{
  // Few attempts and no backtracking make blocks fail, so the repair passes do work.
  const Tileset lines = ReadTilesetFile(std::string(MSYNTH_DATA) + "/Tilesets/Lines.xml");
  const AdjacencyRules rules = lines.Rules();
  SynthesisOptions o;
  o.Size = { { 90, 70, 1 } };
  o.BlockSize = { { 6, 6, 1 } };
  o.AttemptsPerBlock = 1;
  o.BacktracksPerAttempt = 0;
  o.Seed = 11;
  o.Threads = 1;
  const SynthesisResult whole = Synthesize(rules, o);
  ASSERT_TRUE(whole.Succeeded()) << whole.Message;
  EXPECT_GT(whole.Statistics.BlocksRepaired, 0) << whole.Message;
  EXPECT_TRUE(CheckConsistency(lines.Pairs, whole.Model).Consistent);
  o.Threads = 2;
  EXPECT_EQ(Synthesize(rules, o).Model.Data(), whole.Model.Data()); // any thread count
  for (const auto& [lo, hi] :
    { std::pair<WorldBox, WorldBox>{ { { 30, 20, 0 } }, { { 55, 41, 1 } } },
      { { { 0, 50, 0 } }, { { 17, 70, 1 } } } })
  {
    const SynthesisResult region = SynthesizeRegion(rules, o, lo, hi);
    ASSERT_TRUE(region.Succeeded()) << region.Message;
    EXPECT_EQ(region.Model.Data(), Crop(whole.Model, lo, hi).Data()) << region.Message;
  }
}

TEST(WorldRegion, ALayeredStartIsRefusedWhereItWouldShift)
{
  // Stripes 1 2 1 2 along x: no label sits next to itself along x, so the start is layers along
  // x, which a window not starting at the world's x = 0 would shift.
  LabelGrid stripes(6, 4, 1, 0);
  for (std::int64_t y = 0; y < 4; ++y)
    for (std::int64_t x = 0; x < 6; ++x)
      stripes.Set(x, y, 0, 1 + x % 2);
  const auto rules = AdjacencyRules::FromExample(ExampleAnalysis::FromExample(stripes));
  SynthesisOptions o;
  o.Size = { { 200, 40, 1 } };
  o.BlockSize = { { 8, 8, 1 } };
  try
  {
    SynthesizeRegion(rules, o, { { 150, 10, 0 } }, { { 170, 20, 1 } });
    ADD_FAILURE() << "a shifted layered start was accepted";
  }
  catch (const Error& e)
  {
    EXPECT_NE(std::string(e.what()).find("layered along x"), std::string::npos) << e.what();
  }
  // A window spanning the world along x keeps the layers: the region equals the whole run.
  const SynthesisResult whole = Synthesize(rules, o);
  ASSERT_TRUE(whole.Succeeded()) << whole.Message;
  o.Size = { { 40, 400, 1 } };
  const SynthesisResult tall = Synthesize(rules, o);
  ASSERT_TRUE(tall.Succeeded()) << tall.Message;
  const SynthesisResult region = SynthesizeRegion(rules, o, { { 0, 300, 0 } }, { { 40, 330, 1 } });
  ASSERT_TRUE(region.Succeeded()) << region.Message;
  EXPECT_EQ(region.Model.Data(), Crop(tall.Model, { { 0, 300, 0 } }, { { 40, 330, 1 } }).Data());
}

TEST(WorldRegion, OptionsThatNeedTheWholeWorldAreRefused)
{
  const LabelGrid village = msynth_test::Village();
  const auto rules = AdjacencyRules::FromExample(ExampleAnalysis::FromExample(village));
  SynthesisOptions o;
  o.Size = { { 20, 20, 5 } };
  o.BlockSize = { { 8, 8, 5 } };
  o.Symmetry[0].Enabled = true;
  EXPECT_THROW(SynthesizeRegion(rules, o, { { 0, 0, 0 } }, { { 4, 4, 5 } }), Error);
  o.Symmetry[0].Enabled = false;
  EXPECT_THROW(SynthesizeRegion(rules, o, { { 0, 0, 0 } }, { { 21, 4, 5 } }), Error);
  EXPECT_THROW(SynthesizeRegion(rules, o, { { 3, 0, 0 } }, { { 3, 4, 5 } }), Error);
}

TEST(WorldRegion, TheFirstPassAloneServesRegionsNoFailedBlockCovers)
{
  // Blocks fail here and there; regions over none of them take the first pass's narrower cone,
  // the others the repair passes' too: both equal the whole run.
  const Tileset lines = ReadTilesetFile(std::string(MSYNTH_DATA) + "/Tilesets/Lines.xml");
  const AdjacencyRules rules = lines.Rules();
  SynthesisOptions o;
  o.Size = { { 96, 96, 1 } };
  o.BlockSize = { { 6, 6, 1 } };
  o.AttemptsPerBlock = 1;
  o.BacktracksPerAttempt = 0;
  o.Seed = 5;
  const SynthesisResult whole = Synthesize(rules, o);
  ASSERT_TRUE(whole.Succeeded()) << whole.Message;
  ASSERT_GT(whole.Statistics.BlocksRepaired, 0) << whole.Message;
  int shortcut = 0, full = 0;
  for (std::int64_t y = 0; y < 96; y += 24)
    for (std::int64_t x = 0; x < 96; x += 32)
    {
      const WorldBox lo{ { x, y, 0 } }, hi{ { x + 32, y + 24, 1 } };
      const SynthesisResult region = SynthesizeRegion(rules, o, lo, hi);
      ASSERT_TRUE(region.Succeeded()) << region.Message;
      EXPECT_EQ(region.Model.Data(), Crop(whole.Model, lo, hi).Data()) << x << " " << y;
      (region.Message.find("no repair pass was needed") != std::string::npos ? shortcut : full)++;
    }
  EXPECT_GT(full, 0);
  // Smaller regions are more often clear of failed blocks.
  for (std::int64_t y = 0; y < 96; y += 16)
    for (std::int64_t x = 0; x < 96; x += 16)
    {
      const WorldBox lo{ { x, y, 0 } }, hi{ { x + 8, y + 8, 1 } };
      const SynthesisResult region = SynthesizeRegion(rules, o, lo, hi);
      ASSERT_TRUE(region.Succeeded()) << region.Message;
      EXPECT_EQ(region.Model.Data(), Crop(whole.Model, lo, hi).Data()) << x << " " << y;
      (region.Message.find("no repair pass was needed") != std::string::npos ? shortcut : full)++;
    }
  EXPECT_GT(shortcut, 0);
}

TEST(WorldRegion, WholeModelStartModifiesAWholeSolutionAndNoRegionTakesIt)
{
  // Rows along x of one label: a row of label 1 must reach both faces, so no block narrower than
  // the model can draw one over the trivial start of 0s; over a whole-model start it keeps them.
  const std::array<std::vector<std::pair<int, int>>, 3> pairs{ { { { 0, 0 }, { 1, 1 } },
    { { 0, 0 }, { 0, 1 }, { 1, 0 }, { 1, 1 } }, { { 0, 0 }, { 0, 1 }, { 1, 0 }, { 1, 1 } } } };
  const auto rules = AdjacencyRules::FromPairs({ 0, 1 }, { 1.0, 1.0 }, pairs);
  SynthesisOptions o;
  o.Size = { { 24, 12, 4 } };
  o.BlockSize = { { 8, 6, 4 } };
  o.Seed = 5;
  o.StartFrom = BlockStart::Trivial;
  const SynthesisResult trivial = Synthesize(rules, o);
  ASSERT_TRUE(trivial.Succeeded()) << trivial.Message;
  EXPECT_EQ(std::count(trivial.Model.Data().begin(), trivial.Model.Data().end(), 1), 0);
  o.StartFrom = BlockStart::WholeModel;
  const SynthesisResult r = Synthesize(rules, o);
  ASSERT_TRUE(r.Succeeded()) << r.Message;
  EXPECT_EQ(r.Statistics.StartFrom, "whole");
  EXPECT_GT(r.Statistics.Blocks, 1);
  std::int64_t ones = 0;
  for (std::int64_t z = 0; z < 4; ++z)
    for (std::int64_t y = 0; y < 12; ++y)
      for (std::int64_t x = 0; x < 24; ++x)
      {
        ones += r.Model.At(x, y, z) == 1;
        EXPECT_EQ(r.Model.At(x, y, z), r.Model.At(0, y, z)); // every row one label
      }
  EXPECT_GT(ones, 0);
  EXPECT_LT(ones, 24 * 12 * 4);
  EXPECT_EQ(Synthesize(rules, o).Model.Data(), r.Model.Data()); // deterministic
  EXPECT_THROW(SynthesizeRegion(rules, o, { { 0, 0, 0 } }, { { 8, 6, 4 } }), Error);
  o.BlockSize = { { 0, 0, 0 } }; // no blocks: an ordinary whole run
  const SynthesisResult whole = Synthesize(rules, o);
  ASSERT_TRUE(whole.Succeeded()) << whole.Message;
  EXPECT_EQ(whole.Statistics.StartFrom, "");
}

namespace
{
/// Pins cut from a model of @p rules: patches of it placed at sites of a grid whose site 0 lies
/// at @p origin in the world, FreeSite elsewhere.
LabelGrid PinPatches(const AdjacencyRules& rules, const WorldBox& size)
{
  SynthesisOptions o;
  o.Size = { { 32, 32, 1 } };
  o.Seed = 99;
  const SynthesisResult source = Synthesize(rules, o);
  LabelGrid pins(size[0], size[1], size[2], FreeSite);
  // (source corner, size, target corner in the pin grid)
  const std::array<std::array<std::int64_t, 6>, 3> patches{ { { { 10, 10, 6, 6, 0, 0 } },
    { { 3, 20, 3, 8, 20, 25 } }, { { 5, 5, 1, 1, size[0] - 1, size[1] - 1 } } } };
  for (const auto& p : patches)
    for (std::int64_t y = 0; y < p[3]; ++y)
      for (std::int64_t x = 0; x < p[2]; ++x)
        pins.Set(p[4] + x, p[5] + y, 0, source.Model.At(p[0] + x, p[1] + y, 0));
  return pins;
}

/// Whether every pin of @p pins (placed at @p origin) inside [@p lo, @p hi) holds in @p region.
bool PinsKept(const LabelGrid& pins, const WorldBox& origin, const LabelGrid& region,
  const WorldBox& lo, const WorldBox& hi)
{
  const auto& d = pins.Dimensions();
  for (std::int64_t y = 0; y < d[1]; ++y)
    for (std::int64_t x = 0; x < d[0]; ++x)
    {
      const std::int64_t wx = x + origin[0], wy = y + origin[1];
      if (pins.At(x, y, 0) == FreeSite || wx < lo[0] || wx >= hi[0] || wy < lo[1] || wy >= hi[1])
        continue;
      if (region.At(wx - lo[0], wy - lo[1], 0) != pins.At(x, y, 0))
        return false;
    }
  return true;
}
} // namespace

// Regions of a world take the pins that fall in them (a pin grid placed by its origin): each
// region equals the same sites of the whole run with the same pins, keeps its pins and is
// consistent; the placed grid gives the whole run a world-sized grid gives.
TEST(WorldRegion, RegionsTakeThePinsThatFallInThem)
{
  const Tileset lines = ReadTilesetFile(std::string(MSYNTH_DATA) + "/Tilesets/Lines.xml");
  const AdjacencyRules rules = lines.Rules();
  const WorldBox origin{ { 20, 15, 0 } };
  const LabelGrid pins = PinPatches(rules, { { 50, 45, 1 } });
  SynthesisOptions o;
  o.Size = { { 96, 80, 1 } };
  o.BlockSize = { { 16, 16, 1 } };
  o.Pins = pins;
  o.PinsOrigin = origin;
  for (std::uint64_t seed : { 3, 4 })
  {
    o.Seed = seed;
    const SynthesisResult whole = Synthesize(rules, o);
    ASSERT_TRUE(whole.Succeeded()) << whole.Message;
    ASSERT_TRUE(PinsKept(pins, origin, whole.Model, { { 0, 0, 0 } }, o.Size));
    SynthesisOptions spread = o; // the same pins as a grid of the world's size
    spread.PinsOrigin.reset();
    spread.Pins = LabelGrid(96, 80, 1, FreeSite);
    for (std::int64_t y = 0; y < 45; ++y)
      for (std::int64_t x = 0; x < 50; ++x)
        spread.Pins->Set(x + origin[0], y + origin[1], 0, pins.At(x, y, 0));
    EXPECT_EQ(Synthesize(rules, spread).Model.Data(), whole.Model.Data());
    for (const auto& [lo, hi] :
      { std::pair<WorldBox, WorldBox>{ { { 0, 0, 0 } }, { { 30, 24, 1 } } },
        { { { 38, 36, 0 } }, { { 58, 52, 1 } } }, { { { 60, 50, 0 } }, { { 96, 80, 1 } } },
        { { { 80, 0, 0 } }, { { 96, 10, 1 } } } })
    {
      const SynthesisResult region = SynthesizeRegion(rules, o, lo, hi);
      ASSERT_TRUE(region.Succeeded()) << region.Message;
      EXPECT_EQ(region.Model.Data(), Crop(whole.Model, lo, hi).Data()) << region.Message;
      EXPECT_TRUE(PinsKept(pins, origin, region.Model, lo, hi));
      EXPECT_TRUE(CheckConsistency(lines.Pairs, region.Model).Consistent);
    }
  }
  // A region around pins deep inside a world of 10^6 x 10^6 sites keeps them, cheaply.
  o.Size = { { 1000000, 1000000, 1 } };
  o.PinsOrigin = WorldBox{ { 500000, 400000, 0 } };
  const WorldBox lo{ { 499990, 399990, 0 } }, hi{ { 500060, 400060, 1 } };
  const SynthesisResult far = SynthesizeRegion(rules, o, lo, hi);
  ASSERT_TRUE(far.Succeeded()) << far.Message;
  EXPECT_TRUE(PinsKept(pins, *o.PinsOrigin, far.Model, lo, hi));
  EXPECT_TRUE(CheckConsistency(lines.Pairs, far.Model).Consistent);
  EXPECT_LT(far.Statistics.Blocks, 2000) << far.Message;
  // A pin grid outside the world is one line.
  o.PinsOrigin = WorldBox{ { 999990, 0, 0 } };
  EXPECT_THROW(SynthesizeRegion(rules, o, lo, hi), Error);
}
