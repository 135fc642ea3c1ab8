// SPDX-License-Identifier: BSD-3-Clause
#include "msynth/DiscreteSynthesis.h"
#include "msynth/Error.h"
#include "msynth/Tileset.h"

#include <gtest/gtest.h>

#include <set>
#include <sstream>

using namespace msynth;

namespace
{
const char* const Tiny = R"(<?xml version="1.0"?>
<!-- a tiny tileset: empty space, a line (I) and a corner (L) -->
<set unique="False">
  <tiles>
    <tile name="empty" symmetry="X"/>
    <tile name="line" symmetry="I" weight="2.0"/>
    <tile name="corner" symmetry="L" weight="0.5"/>
  </tiles>
  <neighbors>
    <neighbor left="empty" right="empty"/>
    <neighbor left="line 1" right="empty"/>
    <neighbor left="line" right="line"/>
    <neighbor left="line" right="corner 1"/>
  </neighbors>
  <subsets>
    <subset name="lines"><tile name="empty"/><tile name="line"/></subset>
  </subsets>
</set>
)";

Tileset Read(const std::string& text, const std::string& subset = "")
{
  std::istringstream in(text);
  return ReadTileset(in, "tiny.xml", subset);
}

std::string ErrorOf(const std::string& text, const std::string& subset = "")
{
  try
  {
    Read(text, subset);
  }
  catch (const Error& e)
  {
    return e.what();
  }
  return "";
}

int MirrorOf(const Tileset& t, int label)
{
  const auto& tile =
    t.Tiles[static_cast<std::size_t>(t.LabelTile[static_cast<std::size_t>(label)])];
  return tile.FirstLabel +
    TransformOrientation(tile.Symmetry, t.LabelOrientation[static_cast<std::size_t>(label)], true);
}
int Turn(const Tileset& t, int label)
{
  const auto& tile =
    t.Tiles[static_cast<std::size_t>(t.LabelTile[static_cast<std::size_t>(label)])];
  return tile.FirstLabel +
    TransformOrientation(tile.Symmetry, t.LabelOrientation[static_cast<std::size_t>(label)], false);
}
} // namespace

TEST(Tileset, SymmetryClassesAreDihedralActions)
{
  for (char c : { 'X', 'I', '\\', 'L', 'T', 'F' })
  {
    const int n = OrientationCount(c);
    std::set<int> reached;
    for (int i = 0; i < n; ++i)
    {
      int r = i;
      for (int k = 0; k < 4; ++k)
        r = TransformOrientation(c, r, false);
      EXPECT_EQ(r, i) << c << ": four quarter turns";
      EXPECT_EQ(TransformOrientation(c, TransformOrientation(c, i, true), true), i)
        << c << ": mirror twice";
      // m r = r^-1 m
      const int mr = TransformOrientation(c, TransformOrientation(c, i, false), true);
      int rinvm = TransformOrientation(c, i, true);
      for (int k = 0; k < 3; ++k)
        rinvm = TransformOrientation(c, rinvm, false);
      EXPECT_EQ(mr, rinvm) << c;
      int o = 0;
      for (int k = 0; k < i % 4; ++k)
        o = TransformOrientation(c, o, false);
      if (i >= 4)
        o = TransformOrientation(c, o, true);
      reached.insert(o);
    }
    EXPECT_EQ(static_cast<int>(reached.size()), n) << c << ": orientations reached from 0";
  }
  EXPECT_EQ(OrientationCount('Q'), 0);
}

TEST(Tileset, NeighborsExpandToAllRotationsAndReflections)
{
  const Tileset t = Read(Tiny);
  ASSERT_EQ(t.NumberOfLabels(), 7); // empty, line 0-1, corner 0-3
  EXPECT_EQ(t.LabelName(0), "empty");
  EXPECT_EQ(t.LabelName(2), "line 1");
  EXPECT_EQ(t.LabelName(6), "corner 3");
  const std::set<std::pair<int, int>> x(t.Pairs[0].begin(), t.Pairs[0].end());
  const std::set<std::pair<int, int>> y(t.Pairs[1].begin(), t.Pairs[1].end());
  // By hand: a horizontal line continues along x, a vertical one (orientation 1) along y; the
  // vertical line has empty on both sides; the horizontal line has empty above and below.
  EXPECT_TRUE(x.count({ 1, 1 }) && y.count({ 2, 2 }));
  EXPECT_TRUE(x.count({ 2, 0 }) && x.count({ 0, 2 }));
  EXPECT_TRUE(y.count({ 1, 0 }) && y.count({ 0, 1 }));
  EXPECT_FALSE(x.count({ 2, 2 })); // vertical lines are not side by side
  // Structure: the mirror image of each x-pair is an x-pair; each turned a quarter is a y-pair.
  for (const auto& p : x)
  {
    EXPECT_TRUE(x.count({ MirrorOf(t, p.second), MirrorOf(t, p.first) }));
    EXPECT_TRUE(y.count({ Turn(t, p.first), Turn(t, p.second) }));
  }
  EXPECT_TRUE(t.Pairs[2].empty());
  EXPECT_EQ(t.Tiles[1].Weight, 2.0);
  // A subset keeps its tiles and drops rules that name others.
  const Tileset lines = Read(Tiny, "lines");
  EXPECT_EQ(lines.NumberOfLabels(), 3);
}

TEST(Tileset, SynthesisUsesOnlyExpandedPairs)
{
  const Tileset t = Read(Tiny, "lines");
  const std::set<std::pair<int, int>> x(t.Pairs[0].begin(), t.Pairs[0].end());
  const std::set<std::pair<int, int>> y(t.Pairs[1].begin(), t.Pairs[1].end());
  SynthesisOptions o;
  o.Size = { { 24, 20, 1 } };
  o.Choice = LabelChoice::Frequency;
  for (std::uint64_t seed = 0; seed < 5; ++seed)
  {
    o.Seed = seed;
    const auto r = Synthesize(t.Rules(), o);
    ASSERT_TRUE(r.Success) << r.Message;
    for (std::int64_t yy = 0; yy < 20; ++yy)
      for (std::int64_t xx = 0; xx < 24; ++xx)
      {
        if (xx + 1 < 24)
        {
          EXPECT_TRUE(x.count({ r.Model.At(xx, yy, 0), r.Model.At(xx + 1, yy, 0) }));
        }
        if (yy + 1 < 20)
        {
          EXPECT_TRUE(y.count({ r.Model.At(xx, yy, 0), r.Model.At(xx, yy + 1, 0) }));
        }
      }
  }
}

TEST(Tileset, MalformedTilesetsNameTheLineAndProblem)
{
  EXPECT_NE(ErrorOf("<set><tiles></set>").find("closing tag </set> does not match <tiles>"),
    std::string::npos);
  EXPECT_NE(
    ErrorOf("<set>\n<tiles>\n").find("line 2: the file ends inside <tiles>"), std::string::npos);
  EXPECT_NE(ErrorOf("<tiles/>").find("not <set>"), std::string::npos);
  EXPECT_NE(ErrorOf("<set/>").find("has no <tiles>"), std::string::npos);
  EXPECT_NE(ErrorOf("<set><tiles>\n<tile name=\"a\" symmetry=\"Q\"/></tiles></set>")
              .find("line 2: tile 'a' has symmetry 'Q'"),
    std::string::npos);
  EXPECT_NE(ErrorOf("<set><tiles><tile name=\"a\" weight=\"-1\"/></tiles></set>")
              .find("weights are positive"),
    std::string::npos);
  EXPECT_NE(ErrorOf("<set><tiles><tile name=\"a\"/></tiles><neighbors><neighbor left=\"a\" "
                    "right=\"b\"/></neighbors></set>")
              .find("tile 'b', which is not defined"),
    std::string::npos);
  EXPECT_NE(ErrorOf("<set><tiles><tile name=\"a\" symmetry=\"I\"/></tiles><neighbors><neighbor "
                    "left=\"a 2\" right=\"a\"/></neighbors></set>")
              .find("has no orientation 2"),
    std::string::npos);
  EXPECT_NE(ErrorOf(Tiny, "nope").find("no subset named 'nope'"), std::string::npos);
  EXPECT_NE(ErrorOf("<set><tiles><tile name=\"a\" weight=\"1></tiles></set>")
              .find("unterminated attribute"),
    std::string::npos);
  EXPECT_THROW(ReadTilesetFile("/no/such.xml"), Error);
}
