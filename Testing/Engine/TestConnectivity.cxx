// SPDX-License-Identifier: BSD-3-Clause
// Connected networks (SynthesisOptions::Connected, Discrete/Connectivity.h): models whole and in
// blocks, on a path tileset whose tiles say which sides connect and on a label grid, are
// verified here by a union-find of the test's own (over the tileset's sides as read) and by
// CheckConsistency against the tileset's pairs; the tiles' sides turn with their orientation;
// requests the solver cannot keep are one line before any work.
#include "Core/Error.h"
#include "Discrete/ConsistencyCheck.h"
#include "Discrete/DiscreteSynthesis.h"
#include "Formats/Tileset.h"

#include "Fixtures.h"

#include <gtest/gtest.h>

#include <chrono>
#include <numeric>
#include <set>
#include <sstream>
#include <string>
#include <vector>

using namespace msynth;

namespace
{
// Paths of lines, corners and T junctions over empty space; a path leaves a line through its
// ends, a corner through its right and top sides, a T through its right, top and left sides
// (orientation 0). Every rule joins sides of the same kind.
const char* const PathsXml = R"(<set>
  <tiles>
    <tile name="empty" symmetry="X" weight="3" connects=""/>
    <tile name="line" symmetry="I" connects="right left"/>
    <tile name="corner" symmetry="L" connects="right top"/>
    <tile name="t" symmetry="T" weight="0.2" connects="right top left"/>
  </tiles>
  <neighbors>
    <neighbor left="empty" right="empty"/>
    <neighbor left="line" right="line"/>
    <neighbor left="line 1" right="line 1"/>
    <neighbor left="line 1" right="empty"/>
    <neighbor left="line" right="corner 1"/>
    <neighbor left="corner" right="line"/>
    <neighbor left="corner" right="corner 1"/>
    <neighbor left="empty" right="corner"/>
    <neighbor left="line 1" right="corner"/>
    <neighbor left="t" right="t"/>
    <neighbor left="t" right="line"/>
    <neighbor left="line" right="t"/>
    <neighbor left="t" right="corner 1"/>
    <neighbor left="corner" right="t"/>
    <neighbor left="t 1" right="empty"/>
    <neighbor left="empty" right="t 3"/>
    <neighbor left="t 1" right="line 1"/>
    <neighbor left="line 1" right="t 3"/>
    <neighbor left="t 1" right="corner"/>
    <neighbor left="corner 1" right="t 3"/>
    <neighbor left="t 1" right="t 3"/>
    <neighbor left="t 2" right="t"/>
    <neighbor left="t" right="t 2"/>
  </neighbors>
</set>)";

Tileset Paths(const std::string& xml = PathsXml)
{
  std::istringstream in(xml);
  return ReadTileset(in, "paths.xml");
}

/// The bundled Paths set (Utilities/make-path-tilesets.py): as the one above with crossings,
/// every pair of tile sides of one kind allowed.
Tileset BundledPaths()
{
  return ReadTilesetFile(std::string(MSYNTH_DATA) + "/Tilesets/Paths.xml");
}

/// The network of every label but empty (0), with the tileset's sides.
ConnectedNetwork Network(const Tileset& set, std::int64_t maximum = 1)
{
  ConnectedNetwork c;
  c.Name = "paths";
  c.Maximum = maximum;
  for (int b = 1; b < set.NumberOfLabels(); ++b)
  {
    c.Values.push_back(b);
    c.Sides[b] = static_cast<std::uint8_t>(set.LabelSides[static_cast<std::size_t>(b)]);
  }
  return c;
}

/// Per site of @p model, the root of its component (-1: not in the network), the sites with a
/// mask in @p sides (bits +x -x +y -y +z -z; -1: not in the network) joined where both facing
/// sides connect: a union-find of the test's own.
std::vector<std::int64_t> Roots(const LabelGrid& model, const std::vector<int>& sides)
{
  const auto d = model.Dimensions();
  const std::int64_t n = d[0] * d[1] * d[2];
  std::vector<std::int64_t> parent(static_cast<std::size_t>(n));
  std::iota(parent.begin(), parent.end(), 0);
  auto find = [&](std::int64_t i)
  {
    while (parent[static_cast<std::size_t>(i)] != i)
      i = parent[static_cast<std::size_t>(i)];
    return i;
  };
  auto mask = [&](std::int64_t i)
  {
    const Label v = model.Data()[static_cast<std::size_t>(i)];
    return v >= 0 && v < static_cast<Label>(sides.size()) ? sides[static_cast<std::size_t>(v)] : -1;
  };
  const std::int64_t stride[3] = { 1, d[0], d[0] * d[1] };
  for (std::int64_t i = 0; i < n; ++i)
    for (int a = 0; a < 3; ++a)
    {
      const std::int64_t along = (i / stride[a]) % d[static_cast<std::size_t>(a)];
      if (along + 1 < d[static_cast<std::size_t>(a)] && mask(i) >= 0 && mask(i + stride[a]) >= 0 &&
        ((mask(i) >> (2 * a)) & 1) && ((mask(i + stride[a]) >> (2 * a + 1)) & 1))
        parent[static_cast<std::size_t>(find(i))] = find(i + stride[a]);
    }
  std::vector<std::int64_t> roots(static_cast<std::size_t>(n), -1);
  for (std::int64_t i = 0; i < n; ++i)
    if (mask(i) >= 0)
      roots[static_cast<std::size_t>(i)] = find(i);
  return roots;
}

/// The number of components of the network (see Roots).
std::int64_t Components(const LabelGrid& model, const std::vector<int>& sides)
{
  const std::vector<std::int64_t> roots = Roots(model, sides);
  std::int64_t count = 0;
  for (std::size_t i = 0; i < roots.size(); ++i)
    count += roots[i] == static_cast<std::int64_t>(i) ? 1 : 0;
  return count;
}

std::vector<int> SidesOf(const Tileset& set)
{
  std::vector<int> sides = set.LabelSides;
  sides[0] = -1; // empty is not in the network
  return sides;
}

SynthesisOptions Options(const Tileset& set, std::array<std::int64_t, 3> block, std::uint64_t seed)
{
  SynthesisOptions o;
  o.Size = { { 40, 40, 1 } };
  o.BlockSize = block;
  o.Seed = seed;
  o.Connected = Network(set);
  return o;
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

TEST(Connectivity, TileSidesTurnWithTheirOrientation)
{
  const Tileset set = Paths();
  ASSERT_EQ(set.LabelSides.size(), 11u); // empty, line 0-1, corner 0-3, t 0-3
  EXPECT_EQ(set.LabelSides[0], 0);
  EXPECT_EQ(set.LabelSides[1], 1 | 2);     // line 0: right, left
  EXPECT_EQ(set.LabelSides[2], 4 | 8);     // line 1: top, bottom
  EXPECT_EQ(set.LabelSides[3], 1 | 4);     // corner 0: right, top
  EXPECT_EQ(set.LabelSides[4], 4 | 2);     // corner 1: top, left
  EXPECT_EQ(set.LabelSides[5], 2 | 8);     // corner 2: left, bottom
  EXPECT_EQ(set.LabelSides[6], 8 | 1);     // corner 3: bottom, right
  EXPECT_EQ(set.LabelSides[7], 1 | 4 | 2); // t 0: right, top, left
  EXPECT_EQ(set.LabelSides[8], 4 | 2 | 8); // t 1: top, left, bottom
}

TEST(Connectivity, SidesThatBreakTheSymmetryAreOneLine)
{
  std::string xml = PathsXml;
  xml.replace(xml.find("connects=\"\""), 11, "connects=\"right\"");
  try
  {
    Paths(xml);
    FAIL() << "an X tile connecting through one side was read";
  }
  catch (const Error& e)
  {
    EXPECT_NE(std::string(e.what()).find("do not have its symmetry X"), std::string::npos)
      << e.what();
  }
  xml = PathsXml;
  xml.replace(xml.find("connects=\"right left\""), 21, "connects=\"right up\"");
  EXPECT_THROW(Paths(xml), Error);
}

TEST(Connectivity, OneNetworkWholeAndInBlocks)
{
  const Tileset set = BundledPaths();
  const AdjacencyRules rules = set.Rules();
  for (const auto& block :
    { std::array<std::int64_t, 3>{ { 0, 0, 0 } }, std::array<std::int64_t, 3>{ { 12, 12, 1 } } })
    for (std::uint64_t seed : { 1u, 2u, 3u })
    {
      SynthesisOptions plain = Options(set, block, seed);
      plain.Connected = ConnectedNetwork();
      const SynthesisResult before = Synthesize(rules, plain);
      const SynthesisResult r = Synthesize(rules, Options(set, block, seed));
      ASSERT_TRUE(r.Succeeded()) << r.Message;
      EXPECT_TRUE(CheckConsistency(set.Pairs, r.Model).Consistent);
      EXPECT_EQ(Components(r.Model, SidesOf(set)), 1) << "seed " << seed;
      EXPECT_EQ(r.Connected.Components, 1);
      EXPECT_TRUE(r.Connected.Requested);
      if (block[0] == 0) // whole: the repairs start from the plain model
      {
        EXPECT_EQ(r.Connected.Before, Components(before.Model, SidesOf(set)));
        EXPECT_GT(r.Connected.Before, 1) << "the test should start from several components";
      }
    }
}

TEST(Connectivity, APathJoinsItsSitesWholeAndInBlocks)
{
  const Tileset set = BundledPaths();
  const AdjacencyRules rules = set.Rules();
  const std::vector<std::array<std::int64_t, 3>> sites{ { { 0, 0, 0 } }, { { 39, 39, 0 } },
    { { 3, 30, 0 } }, { { 35, 4, 0 } } };
  for (const auto& block :
    { std::array<std::int64_t, 3>{ { 0, 0, 0 } }, std::array<std::int64_t, 3>{ { 12, 12, 1 } } })
    for (std::uint64_t seed : { 1u, 2u })
    {
      SynthesisOptions o = Options(set, block, seed);
      o.Connected.Maximum = 1000;
      o.Connected.PathSites = sites;
      const SynthesisResult r = Synthesize(rules, o);
      ASSERT_TRUE(r.Succeeded()) << r.Message;
      EXPECT_TRUE(CheckConsistency(set.Pairs, r.Model).Consistent);
      const std::vector<std::int64_t> roots = Roots(r.Model, SidesOf(set));
      std::set<std::int64_t> joined;
      for (const auto& p : sites)
        joined.insert(roots[static_cast<std::size_t>(p[0] + 40 * p[1])]);
      EXPECT_EQ(joined, std::set<std::int64_t>{ roots[0] }) << "seed " << seed;
      EXPECT_GE(roots[0], 0);
      EXPECT_EQ(r.Connected.PathSites, 4);
    }
  SynthesisOptions o = Options(set, { { 0, 0, 0 } }, 1);
  o.Connected.PathSites = { { { 40, 0, 0 } } };
  EXPECT_NE(ErrorOf(rules, o).find("outside the model"), std::string::npos);
  o.Connected.PathSites.clear();
  o.Connected.PathLabels = { 0 };
  EXPECT_NE(ErrorOf(rules, o).find("cannot carry"), std::string::npos);
}

TEST(Connectivity, AtMostNComponentsAndTheSameModelForAnyThreadCount)
{
  const Tileset set = BundledPaths();
  const AdjacencyRules rules = set.Rules();
  SynthesisOptions o = Options(set, { { 12, 12, 1 } }, 7);
  o.Connected.Maximum = 3;
  o.Threads = 1;
  const SynthesisResult one = Synthesize(rules, o);
  o.Threads = 2;
  const SynthesisResult two = Synthesize(rules, o);
  ASSERT_TRUE(one.Succeeded()) << one.Message;
  EXPECT_LE(Components(one.Model, SidesOf(set)), 3);
  EXPECT_EQ(one.Model.Data(), two.Model.Data());
}

TEST(Connectivity, FaceNeighboursWithoutSides)
{
  // The village's walls and roofs (labels 2, 3) in blocks: one building complex.
  const LabelGrid example = msynth_test::Village();
  const AdjacencyRules rules = AdjacencyRules::FromExample(ExampleAnalysis::FromExample(example));
  SynthesisOptions o;
  o.Size = { { 24, 24, 5 } };
  o.BlockSize = { { 12, 12, 5 } };
  o.Boundary[4] = 1; // ground along -z
  o.Seed = 3;
  o.Connected.Values = { 2, 3 };
  const SynthesisResult r = Synthesize(rules, o);
  ASSERT_TRUE(r.Succeeded()) << r.Message;
  EXPECT_TRUE(CheckConsistency(example, r.Model).Consistent);
  EXPECT_EQ(Components(r.Model, { -1, -1, 63, 63 }), 1);
}

TEST(Connectivity, RequestsItCannotKeepAreOneLine)
{
  const Tileset set = Paths();
  const AdjacencyRules rules = set.Rules();
  SynthesisOptions o = Options(set, { { 0, 0, 0 } }, 1);
  o.Connected.Values.push_back(99);
  EXPECT_NE(ErrorOf(rules, o).find("label 99 does not occur"), std::string::npos);
  o = Options(set, { { 0, 0, 0 } }, 1);
  o.Connected.Maximum = 0;
  EXPECT_NE(ErrorOf(rules, o).find("at least 1"), std::string::npos);
  o = Options(set, { { 0, 0, 0 } }, 1);
  o.Symmetry[0].Enabled = true;
  EXPECT_NE(ErrorOf(rules, o).find("symmetry"), std::string::npos);
  o = Options(set, { { 10, 10, 1 } }, 1);
  try
  {
    SynthesizeRegion(rules, o, { { 0, 0, 0 } }, { { 10, 10, 1 } });
    FAIL() << "a region kept a network";
  }
  catch (const Error& e)
  {
    EXPECT_NE(std::string(e.what()).find("connected network"), std::string::npos) << e.what();
  }
}

TEST(Connectivity, AnImpossibleNetworkFailsWithOneLine)
{
  // A checkerboard: every site of label 0 is alone among its face neighbours, whatever a repair
  // draws, so 0 cannot form one component.
  const LabelGrid example =
    msynth_test::Grid2D({ { 0, 1, 0, 1 }, { 1, 0, 1, 0 }, { 0, 1, 0, 1 }, { 1, 0, 1, 0 } });
  const AdjacencyRules rules = AdjacencyRules::FromExample(ExampleAnalysis::FromExample(example));
  {
    SynthesisOptions o;
    o.Size = { { 12, 12, 1 } };
    o.AttemptsPerBlock = 2;
    o.BlocksWhenWholeFails = false;
    o.Connected.Values = { 0 };
    o.Connected.Name = "0";
    const SynthesisResult r = Synthesize(rules, o);
    EXPECT_FALSE(r.Succeeded());
    EXPECT_NE(r.Message.find("the network of 0 has 72 components, more than 1"), std::string::npos)
      << r.Message;
    EXPECT_EQ(r.Message.find('\n'), std::string::npos);
  }
  {
    // With every attempt a box may take, the repairs run out of work first (at most 64 box
    // attempts per component at the start): one line, not hours of boxes.
    SynthesisOptions o;
    o.Size = { { 16, 16, 1 } };
    o.BlocksWhenWholeFails = false;
    o.Connected.Values = { 0 };
    o.Connected.Name = "0";
    SynthesisResult r = Synthesize(rules, o);
    EXPECT_FALSE(r.Succeeded());
    EXPECT_NE(r.Message.find("the repairs stopped after"), std::string::npos) << r.Message;
    const std::size_t at = r.Message.find("after ") + 6;
    EXPECT_LE(std::stoll(r.Message.substr(at)), 64 * (1 + 128)) << r.Message;
    EXPECT_EQ(r.Message.find('\n'), std::string::npos);
  }
}

TEST(Connectivity, TheSecondsIncludeTheRepairs)
{
  // The repairs of a whole model's network run after its one block; the synthesis' Seconds
  // (statistics.json, "synthesis ... s") stopped before them: 0.00 s of 0.03 s on the bundled
  // Circuits (every tile but substrate, label 0, in the network) at 96².
  const Tileset set = ReadTilesetFile(std::string(MSYNTH_DATA) + "/Tilesets/Circuits.xml");
  const AdjacencyRules rules = set.Rules();
  SynthesisOptions o = Options(set, { { 0, 0, 0 } }, 1);
  o.Size = { { 96, 96, 1 } };
  const auto start = std::chrono::steady_clock::now();
  const SynthesisResult r = Synthesize(rules, o);
  const double wall =
    std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  ASSERT_TRUE(r.Succeeded()) << r.Message;
  EXPECT_GT(r.Connected.Before, 100);
  EXPECT_EQ(r.Connected.Components, 1);
  EXPECT_GE(r.Statistics.Seconds, 0.5 * wall) << r.Statistics.Seconds << " s of " << wall;
  EXPECT_LE(r.Statistics.Seconds, wall);
}
