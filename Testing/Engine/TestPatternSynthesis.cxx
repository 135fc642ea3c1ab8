// SPDX-License-Identifier: BSD-3-Clause
// Factor-graph pattern synthesis (Yeh et al. 2012): shapes, learning, BLOCKSS and the
// baselines, zoning, fixed sites, mirroring, 3D, and the quality measures. Every synthesized
// pattern is checked by PatternQuality's CheckPatternPairs, which recomputes the pairs from the
// exemplars with its own code.
#include "Core/Error.h"
#include "Patterns/FactorGraph.h"
#include "Patterns/PatternQuality.h"
#include "Patterns/PatternSynthesis.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

using namespace msynth;

namespace
{

/// A 2D grid from text art (top row first), label = index of the character in @p chars.
LabelGrid Art(const std::vector<std::string>& rows, const std::string& chars)
{
  const auto ny = static_cast<std::int64_t>(rows.size());
  const auto nx = static_cast<std::int64_t>(rows[0].size());
  LabelGrid g(nx, ny, 1);
  for (std::int64_t y = 0; y < ny; ++y)
    for (std::int64_t x = 0; x < nx; ++x)
      g.Set(x, y, 0,
        static_cast<Label>(
          chars.find(rows[static_cast<std::size_t>(ny - 1 - y)][static_cast<std::size_t>(x)])));
  return g;
}

const std::string FacadeTiles = ".-#TW_Dd=";
// A rectangular facade with windows of four tiles and a door (cf. Data/Patterns).
LabelGrid Facade()
{
  return Art({ "............", "............", "------------", "############", "#T##T##T##T#",
               "#W##W##W##W#", "#W##W##W##W#", "#_##_##_##_#", "############", "#T##D##T##T#",
               "#W##d##W##W#", "#W##d##W##W#", "#_##d##_##_#", "============" },
    FacadeTiles);
}

PatternOptions Options(std::int64_t nx, std::int64_t ny, const std::string& soft = "")
{
  PatternOptions o;
  o.Size = { { nx, ny, 1 } };
  o.SoftFactors = ParseStencils(soft);
  o.Seed = 7;
  o.BurnIn = 1;
  return o;
}

void ExpectValid(const std::vector<LabelGrid>& exemplars, const PatternResult& r)
{
  ASSERT_FALSE(r.Samples.empty());
  for (const PatternSample& s : r.Samples)
  {
    const auto problems = CheckPatternPairs(exemplars, s.Labels);
    EXPECT_TRUE(problems.empty()) << problems.front();
  }
}

} // namespace

TEST(PatternShapes, ParsesNamesBoxesAndStencils)
{
  const Stencil h = ParseStencil("4H");
  EXPECT_EQ(h.Offsets.size(), 4u);
  EXPECT_EQ(h.Extent, (std::array<int, 3>{ { 4, 1, 1 } }));
  EXPECT_EQ(ParseStencil("3v").Extent, (std::array<int, 3>{ { 1, 3, 1 } }));
  EXPECT_EQ(ParseStencil("2D").Extent, (std::array<int, 3>{ { 1, 1, 2 } }));
  EXPECT_EQ(ParseStencil("3x3").Offsets.size(), 9u);
  EXPECT_EQ(ParseStencil("2x2x2").Extent, (std::array<int, 3>{ { 2, 2, 2 } }));
  // Offsets are normalised so the lowest corner is the anchor.
  const Stencil l = ParseStencil("0:0+-1:0+0:1");
  EXPECT_EQ(l.Extent, (std::array<int, 3>{ { 2, 2, 1 } }));
  EXPECT_EQ(l.Offsets.front(), (std::array<int, 3>{ { 0, 0, 0 } }));
  EXPECT_EQ(ParseStencils("2H,2V,,4H").size(), 3u);
  for (const char* bad : { "", "H", "0H", "65H", "3x", "axb", "0:0+0:0", "1:2:3:4", "9x9" })
    EXPECT_THROW(ParseStencil(bad), Error) << bad;
  EXPECT_EQ(BlockScheme(1, false).size(), 1u);
  EXPECT_EQ(BlockScheme(6, false).size(), 9u);
  EXPECT_EQ(BlockScheme(6, true).size(), 14u);
  EXPECT_THROW(BlockScheme(7, false), Error);
}

TEST(PatternFactors, LearnsPairsConfigurationsAndBlocks)
{
  const FactorModel m =
    LearnFactors({ Facade() }, ParseStencils("4V"), { ParseStencil("1x1"), ParseStencil("2x2") });
  EXPECT_EQ(m.NumberOfTiles(), 9);
  const int wall = m.TileIndex(2), top = m.TileIndex(3), middle = m.TileIndex(4);
  EXPECT_TRUE(m.Allowed(1, middle, top));  // a middle below a window top
  EXPECT_FALSE(m.Allowed(1, top, middle)); // never above it
  EXPECT_TRUE(m.Allowed(0, wall, top));
  EXPECT_FALSE(m.AxisSeen[2]);
  EXPECT_EQ(m.BlockTiles[0].size(), 9u); // nine distinct single tiles
  EXPECT_EQ(m.Observed[0][0].size(), CountConfigurations({ Facade() }, ParseStencil("4V")).size());
}

TEST(PatternSynthesis, BlockssSatisfiesTheHardFactorsAndIsDeterministic)
{
  const std::vector<LabelGrid> ex{ Facade() };
  PatternOptions o = Options(24, 13, "4H,4V");
  o.Samples = 3;
  const PatternResult r = SynthesizePattern(ex, o);
  ASSERT_EQ(r.Samples.size(), 3u);
  ExpectValid(ex, r);
  EXPECT_GT(r.WalkMoves, 0);
  EXPECT_GT(r.AnnealingMoves, 0);
  // Samples move on from each other (the moves between samples, see PatternSynthesis.h).
  EXPECT_NE(r.Samples[0].Labels, r.Samples[2].Labels);
  // The log probability is the soft factors' count, recomputed independently.
  for (const PatternSample& s : r.Samples)
    EXPECT_NEAR(s.LogProbability,
      PatternLogProbability(ex, s.Labels, ParseStencils("4H,4V"), o.Epsilon), 1e-9);
  const PatternResult again = SynthesizePattern(ex, o);
  for (std::size_t i = 0; i < r.Samples.size(); ++i)
    EXPECT_EQ(r.Samples[i].Labels, again.Samples[i].Labels);
  o.Seed = 8;
  EXPECT_NE(SynthesizePattern(ex, o).Samples[0].Labels, r.Samples[0].Labels);
}

TEST(PatternSynthesis, BaselinesSatisfyTheHardFactors)
{
  const std::vector<LabelGrid> ex{ Facade() };
  PatternOptions o = Options(10, 8);
  o.Method = PatternMethod::MetropolisHastings;
  ExpectValid(ex, SynthesizePattern(ex, o));
  o.Method = PatternMethod::ConstraintSolver;
  o.Samples = 2;
  const PatternResult csp = SynthesizePattern(ex, o);
  ASSERT_EQ(csp.Samples.size(), 2u);
  ExpectValid(ex, csp);
}

// An L-shaped facade: a tower beside a wider block.
static LabelGrid LShapedFacade()
{
  return Art(
    { "...............", "-------........", "#######........", "#T##T##........", "#W##W##........",
      "#W##W##........", "#_##_##........", "#######--------", "###############", "#T##T##T##T##T#",
      "#W##W##W##W##W#", "#W##W##W##W##W#", "#_##_##_##_##_#", "###############", "#T##D##T##T##D#",
      "#W##d##W##W##d#", "#W##d##W##W##d#", "#_##d##_##_##d#", "===============" },
    FacadeTiles);
}

TEST(PatternSynthesis, ZonesAndFixedSitesHold)
{
  const std::vector<LabelGrid> ex{ Facade(), LShapedFacade() };
  for (PatternMethod method : { PatternMethod::BlockSS, PatternMethod::ConstraintSolver })
  {
    PatternOptions o = Options(16, 14, "4V");
    o.Method = method;
    // An L: sky (zone 1) over the right half of the top six rows; a plinth row (zone 2).
    o.SiteZone.assign(16 * 14, 0);
    for (int y = 0; y < 14; ++y)
      for (int x = 0; x < 16; ++x)
        o.SiteZone[static_cast<std::size_t>(x + 16 * y)] = y == 0 ? 2 : (y >= 8 && x >= 8) ? 1 : 0;
    o.ZoneTiles[1] = { 0 };
    o.ZoneTiles[2] = { 8 };
    o.ZoneTiles[0] = { 1, 2, 3, 4, 5, 6, 7, 0 };
    o.Fixed.assign(16 * 14, -1);
    o.Fixed[static_cast<std::size_t>(3 + 16 * 1)] = 7; // a door at (3, 1)
    const PatternResult r = SynthesizePattern(ex, o);
    ExpectValid(ex, r);
    const LabelGrid& m = r.Samples[0].Labels;
    EXPECT_EQ(m.At(3, 1, 0), 7);
    for (int y = 0; y < 14; ++y)
      for (int x = 0; x < 16; ++x)
      {
        if (y == 0)
        {
          EXPECT_EQ(m.At(x, y, 0), 8);
        }
        else if (y >= 8 && x >= 8)
        {
          EXPECT_EQ(m.At(x, y, 0), 0);
        }
      }
  }
}

TEST(PatternSynthesis, ZonesTakeTheirStyleFromTheirExemplars)
{
  // Checkerboard and stripes share their pairs but not their 2 x 2 configurations.
  const LabelGrid checker = Art({ "abab", "baba", "abab", "baba" }, "ab");
  const LabelGrid stripes = Art({ "aaaa", "bbbb", "aaaa", "bbbb" }, "ab");
  PatternOptions o = Options(12, 8, "2x2");
  o.SiteZone.assign(96, 0);
  for (int y = 0; y < 8; ++y)
    for (int x = 0; x < 12; ++x)
      o.SiteZone[static_cast<std::size_t>(x + 12 * y)] = x < 6 ? 1 : 2;
  o.ZoneExemplars[1] = { 0 };
  o.ZoneExemplars[2] = { 1 };
  const PatternResult r = SynthesizePattern({ checker, stripes }, o);
  ExpectValid({ checker, stripes }, r);
  const PatternSample& s = r.Samples[0];
  // SatisfiedSoft recomputed: the 2 x 2 window at each anchor against its zone's exemplar.
  const Stencil square = ParseStencil("2x2");
  const auto seen = [&](const LabelGrid& e) { return CountConfigurations({ e }, square); };
  const ConfigurationHistogram left = seen(checker), right = seen(stripes);
  int satisfiedLeft = 0, satisfiedRight = 0;
  for (int y = 0; y + 1 < 8; ++y)
    for (int x = 0; x + 1 < 12; ++x)
    {
      std::vector<Label> c;
      for (const auto& off : square.Offsets) // the stencil's order, as CountConfigurations
        c.push_back(s.Labels.At(x + off[0], y + off[1], 0));
      const bool ok = (x < 6 ? left : right).count(c) > 0;
      EXPECT_EQ(s.SatisfiedSoft[static_cast<std::size_t>(x + 12 * y)], ok ? 1 : 0) << x << "," << y;
      (x < 6 ? satisfiedLeft : satisfiedRight) += ok ? 1 : 0;
    }
  // Each half mostly looks like its own exemplar.
  EXPECT_GT(satisfiedLeft, 25);  // of 42 anchors
  EXPECT_GT(satisfiedRight, 20); // of 35
}

TEST(PatternSynthesis, TilesetRulesAloneOrBesideExemplars)
{
  // Pipes: 0 empty, 1 horizontal, 2 vertical; a pipe must continue or meet the border.
  LabelPairs rules;
  rules[0] = { { 0, 0 }, { 0, 2 }, { 2, 0 }, { 2, 2 }, { 1, 1 } };
  rules[1] = { { 0, 0 }, { 0, 1 }, { 1, 0 }, { 1, 1 }, { 2, 2 } };
  PatternOptions o = Options(12, 9);
  o.ExtraPairs = rules;
  const PatternResult r = SynthesizePattern({}, o);
  ASSERT_EQ(r.Samples.size(), 1u);
  EXPECT_TRUE(CheckPatternPairs({}, r.Samples[0].Labels, 10, rules).empty());
  EXPECT_FALSE(CheckPatternPairs({}, r.Samples[0].Labels).empty()); // no rules: no pair known
  // Beside an exemplar, the rules add pairs (and tiles) the exemplar never shows.
  const LabelGrid empty = Art({ "...", "..." }, ".");
  const PatternResult both = SynthesizePattern({ empty }, o);
  EXPECT_TRUE(CheckPatternPairs({ empty }, both.Samples[0].Labels, 10, rules).empty());
  EXPECT_THROW(SynthesizePattern({}, Options(4, 4)), Error); // nothing to learn from
}

TEST(PatternSynthesis, MirroredOutputsAreSymmetric)
{
  const std::string tiles = ".=_[]1234o()";
  const LabelGrid border =
    Art({ "1==========2", "[(o)....(o)]", "[..........]", "[o........o]", "[..........]",
          "[..........]", "[o........o]", "[..........]", "[(o)....(o)]", "3__________4" },
      tiles);
  const std::vector<LabelGrid> ex{ border };
  for (std::int64_t width : { 14, 15 })
  {
    PatternOptions o = Options(width, 10, "3x3");
    o.Mirror[0] = true;
    o.MirrorMap = { { 3, 4 }, { 4, 3 }, { 5, 6 }, { 6, 5 }, { 7, 8 }, { 8, 7 }, { 10, 11 },
      { 11, 10 } };
    // The frame's ring is the border; the inside anything.
    o.SiteZone.assign(static_cast<std::size_t>(width * 10), 0);
    for (std::int64_t y = 0; y < 10; ++y)
      for (std::int64_t x = 0; x < width; ++x)
        if (x == 0 || y == 0 || x == width - 1 || y == 9)
          o.SiteZone[static_cast<std::size_t>(x + width * y)] = 1;
    o.ZoneTiles[1] = { 1, 2, 3, 4, 5, 6, 7, 8 };
    o.ZoneTiles[0] = { 0, 9, 10, 11 };
    const PatternResult r = SynthesizePattern(ex, o);
    ExpectValid(ex, r);
    const LabelGrid& m = r.Samples[0].Labels;
    for (std::int64_t y = 0; y < 10; ++y)
      for (std::int64_t x = 0; x < width; ++x)
      {
        const Label a = m.At(x, y, 0), b = m.At(width - 1 - x, y, 0);
        const auto it = o.MirrorMap.find(a);
        EXPECT_EQ(it == o.MirrorMap.end() ? a : it->second, b) << x << "," << y;
      }
  }
}

TEST(PatternSynthesis, ThreeDimensionalPatterns)
{
  // Floors (1) under air (0) with pillars (2) two sites high.
  LabelGrid ex(6, 6, 4, 0);
  for (int y = 0; y < 6; ++y)
    for (int x = 0; x < 6; ++x)
    {
      ex.Set(x, y, 0, 1);
      if (x % 3 == 1 && y % 3 == 1)
      {
        ex.Set(x, y, 1, 2);
        ex.Set(x, y, 2, 2);
      }
    }
  PatternOptions o;
  o.Size = { { 10, 10, 4 } };
  o.SoftFactors = ParseStencils("3D,2x2x2");
  o.BurnIn = 0;
  const PatternResult r = SynthesizePattern({ ex }, o);
  ExpectValid({ ex }, r);
  o.Size = { { 10, 10, 4 } };
  EXPECT_THROW(SynthesizePattern({ Facade() }, o), Error); // 2D exemplars, 3D output
}

TEST(PatternSynthesis, BadOptionsAreClearErrors)
{
  const std::vector<LabelGrid> ex{ Facade() };
  PatternOptions o = Options(8, 8);
  o.ZoneTiles[0] = { 42 };
  o.SiteZone.assign(64, 0);
  EXPECT_THROW(SynthesizePattern(ex, o), Error);
  o = Options(8, 8);
  o.SiteZone.assign(10, 0);
  EXPECT_THROW(SynthesizePattern(ex, o), Error);
  o = Options(8, 8);
  o.ZoneExemplars[0] = { 3 };
  o.SiteZone.assign(64, 0);
  EXPECT_THROW(SynthesizePattern(ex, o), Error);
  o = Options(8, 8);
  o.Mirror[0] = true;
  o.MirrorMap = { { 3, 4 } }; // not an involution
  EXPECT_THROW(SynthesizePattern(ex, o), Error);
  // Two fixed sites no pair allows: the moves run out with a message, not a hang.
  o = Options(6, 6);
  o.Fixed.assign(36, -1);
  o.Fixed[0] = 0; // sky
  o.Fixed[1] = 8; // plinth right of sky: never in the exemplar
  o.MaxMoves = 20000;
  try
  {
    SynthesizePattern(ex, o);
    ADD_FAILURE() << "no error";
  }
  catch (const Error& e)
  {
    EXPECT_NE(std::string(e.what()).find("hard factors"), std::string::npos) << e.what();
  }
}

namespace
{
/// Components of the sites holding @p road in @p g (face neighbours), by a flood of the test's.
int RoadComponents(const LabelGrid& g, Label road)
{
  const std::int64_t nx = g.Size(0), ny = g.Size(1);
  std::vector<char> seen(static_cast<std::size_t>(nx * ny), 0);
  int count = 0;
  for (std::int64_t start = 0; start < nx * ny; ++start)
  {
    if (seen[static_cast<std::size_t>(start)] || g.Data()[static_cast<std::size_t>(start)] != road)
      continue;
    ++count;
    std::vector<std::int64_t> stack{ start };
    seen[static_cast<std::size_t>(start)] = 1;
    while (!stack.empty())
    {
      const std::int64_t s = stack.back();
      stack.pop_back();
      const std::int64_t x = s % nx, y = s / nx;
      const std::int64_t next[4][2] = { { x + 1, y }, { x - 1, y }, { x, y + 1 }, { x, y - 1 } };
      for (const auto& q : next)
      {
        const std::int64_t i = q[0] + nx * q[1];
        if (q[0] < 0 || q[0] >= nx || q[1] < 0 || q[1] >= ny || seen[static_cast<std::size_t>(i)] ||
          g.Data()[static_cast<std::size_t>(i)] != road)
          continue;
        seen[static_cast<std::size_t>(i)] = 1;
        stack.push_back(i);
      }
    }
  }
  return count;
}
} // namespace

TEST(PatternSynthesis, ConnectedNetworkIsOneComponentInEverySample)
{
  const std::vector<LabelGrid> ex{ Art(
    { "..........", ".###..##..", ".#......#.", ".#..###.#.", "....#.....", ".........." }, ".#") };
  // (Metropolis-Hastings on this exemplar, whose pairs allow anything, percolates: a network
  // of half the sites that boxes seldom mend; test_pattern_connected runs it on the city.)
  for (PatternMethod method : { PatternMethod::BlockSS, PatternMethod::ConstraintSolver })
  {
    PatternOptions o = Options(30, 24);
    o.Method = method;
    o.Samples = 2;
    const PatternResult plain = SynthesizePattern(ex, o);
    o.Connected.Values = { 1 };
    o.Connected.Name = "road";
    const PatternResult r = SynthesizePattern(ex, o);
    ExpectValid(ex, r);
    EXPECT_GT(RoadComponents(plain.Samples[0].Labels, 1), 1) << "the plain run has one already";
    for (const PatternSample& s : r.Samples)
    {
      EXPECT_EQ(RoadComponents(s.Labels, 1), 1);
      EXPECT_TRUE(s.Connected.Requested);
      EXPECT_EQ(s.Connected.Components, 1);
    }
    const PatternResult again = SynthesizePattern(ex, o);
    EXPECT_EQ(again.Samples.back().Labels.Data(), r.Samples.back().Labels.Data());
  }
  PatternOptions o = Options(12, 12);
  o.Connected.Values = { 5 };
  EXPECT_THROW(SynthesizePattern(ex, o), Error); // no exemplar holds 5
  o.Connected.Values = { 1 };
  o.Mirror[0] = true;
  EXPECT_THROW(SynthesizePattern(ex, o), Error);
}

TEST(PatternQuality, KLDivergenceAndSmoothing)
{
  const LabelGrid f = Facade();
  const Stencil v = ParseStencil("4V");
  // The exemplar against itself: only the smoothing separates them.
  const double self = PatternKL({ f }, f, v);
  EXPECT_GE(self, 0.0);
  EXPECT_LT(self, 0.05);
  // A facade with elongated windows shows configurations the exemplar does not.
  const LabelGrid tall =
    Art({ "............", "------------", "#T##T##T##T#", "#W##W##W##W#", "#W##W##W##W#",
          "#W##W##W##W#", "#W##W##W##W#", "#_##_##_##_#", "#T##D##T##T#", "#W##d##W##W#",
          "#W##d##W##W#", "#_##d##_##_#", "============" },
      FacadeTiles);
  EXPECT_GT(PatternKL({ f }, tall, v), self + 0.1);
  // By hand: model {A: 1}, exemplar {A: 1, B: 1}: f̂(A) = 2 / 4, D = log 2.
  ConfigurationHistogram model{ { { 1 }, 1 } }, exemplar{ { { 1 }, 1 }, { { 2 }, 1 } };
  EXPECT_NEAR(KLDivergence(model, exemplar), std::log(2.0), 1e-12);
  EXPECT_TRUE(CheckPatternPairs({ f }, f).empty());
  EXPECT_FALSE(CheckPatternPairs({ f }, tall).empty()); // window tops under the cornice
}
