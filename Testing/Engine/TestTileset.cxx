// SPDX-License-Identifier: BSD-3-Clause
#include "Core/Error.h"
#include "Discrete/ConsistencyCheck.h"
#include "Discrete/DiscreteSynthesis.h"
#include "Formats/TilePictures.h"
#include "Formats/Tileset.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <functional>
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
    ASSERT_TRUE(r.Succeeded()) << r.Message;
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
  EXPECT_NE(
    ErrorOf("<set><tiles><tile name=\"a\" symmetry=\"I\"/></tiles><neighbors><neighbor "
            "left=\"a 8\" right=\"a\"/></neighbors></set>")
      .find("'a 8': the number after a tile name is one of the 8 rotations and reflections, "
            "0 to 7"),
    std::string::npos);
  EXPECT_NE(ErrorOf("<set size=\"0\"><tiles><tile name=\"a\"/></tiles></set>")
              .find("<set size=\"0\">: the tile size is a whole number of pixels"),
    std::string::npos);
  EXPECT_NE(ErrorOf(Tiny, "nope").find("no subset named 'nope'"), std::string::npos);
  EXPECT_NE(ErrorOf("<set><tiles><tile name=\"a\" weight=\"1></tiles></set>")
              .find("unterminated attribute"),
    std::string::npos);
  EXPECT_THROW(ReadTilesetFile("/no/such.xml"), Error);
}

TEST(Tileset, NeighborNumbersAreDihedralElementsAsWaveFunctionCollapseReadsThem)
{
  // WaveFunctionCollapse's action[first][k] for each class, written out by hand from its
  // rotation a and reflection b: k = 0..3 are a^k(0), k = 4..7 are b(a^(k-4)(0)).
  const std::pair<char, std::array<int, 8>> expected[] = {
    { 'X', { { 0, 0, 0, 0, 0, 0, 0, 0 } } },
    { 'I', { { 0, 1, 0, 1, 0, 1, 0, 1 } } },
    { '\\', { { 0, 1, 0, 1, 1, 0, 1, 0 } } },
    { 'L', { { 0, 1, 2, 3, 1, 0, 3, 2 } } },
    { 'T', { { 0, 1, 2, 3, 0, 3, 2, 1 } } },
    { 'F', { { 0, 1, 2, 3, 4, 5, 6, 7 } } },
  };
  for (const auto& [symmetry, orientation] : expected)
    for (int k = 0; k < 8; ++k)
    {
      EXPECT_EQ(DihedralAction(symmetry, 0, k), orientation[static_cast<std::size_t>(k)])
        << symmetry << " " << k;
      // "a k" left of an X tile: exactly the pairs of "a <orientation>" left of it.
      const std::string head = std::string("<set><tiles><tile name=\"a\" symmetry=\"") +
        (symmetry == '\\' ? "\\" : std::string(1, symmetry)) +
        "\"/><tile name=\"e\"/></tiles><neighbors><neighbor left=\"a ";
      const std::string tail = "\" right=\"e\"/></neighbors></set>";
      const Tileset byElement = Read(head + std::to_string(k) + tail);
      const Tileset byOrientation =
        Read(head + std::to_string(orientation[static_cast<std::size_t>(k)]) + tail);
      EXPECT_EQ(byElement.Pairs, byOrientation.Pairs) << symmetry << " " << k;
      const int e = byElement.Tiles[1].FirstLabel;
      const std::set<std::pair<int, int>> x(byElement.Pairs[0].begin(), byElement.Pairs[0].end());
      EXPECT_TRUE(x.count({ orientation[static_cast<std::size_t>(k)], e })) << symmetry << " " << k;
    }
  // The published sets' "b_i 3" for a tile of class I: orientation 1, not an error.
  const Tileset t = Read("<set><tiles><tile name=\"b_i\" symmetry=\"I\"/><tile name=\"b\"/></tiles>"
                         "<neighbors><neighbor left=\"b_i 3\" right=\"b\"/></neighbors></set>");
  EXPECT_TRUE(std::count(t.Pairs[0].begin(), t.Pairs[0].end(), std::make_pair(1, 2)) == 1);
}

TEST(Tileset, ImagesAreFoundInBothPublishedLayouts)
{
  EXPECT_EQ(TilesetImageFolder("tilesets/Castle.xml"), "tilesets/Castle");
  EXPECT_EQ(TilesetImageFolder("/a/b.c/Summer.xml"), "/a/b.c/Summer");
  EXPECT_EQ(TilesetImageFolder("samples/Circles/data.xml"), "samples/Circles");
  EXPECT_EQ(TilesetImageFolder("data.xml"), ".");
  const Tileset t = Read("<set size=\"3\" unique=\"True\"><tiles><tile name=\"a\" symmetry=\"L\"/>"
                         "</tiles></set>");
  EXPECT_EQ(t.TileSize, 3);
  EXPECT_TRUE(t.Unique);
  EXPECT_EQ(TileImageFile("/no/Set.xml", t, t.Tiles[0], 2), "/no/Set/a 2.png");
}

namespace
{
/// WaveFunctionCollapse's own construction of the propagator (SimpleTiledModel), written out
/// independently of ReadTileset: per class a rotation a and a reflection b, action[t][k], and
/// four entries per direction for each neighbor rule. Returns the pairs along x (left, right)
/// and y (lower, upper), with WFC's image y (downwards) turned to ours (upwards).
std::array<std::set<std::pair<int, int>>, 2> WfcPairs(const std::vector<char>& classes,
  const std::vector<std::array<int, 4>>& rules) // (left tile, left k, right tile, right k)
{
  std::vector<std::array<int, 8>> action;
  std::vector<int> first;
  for (char c : classes)
  {
    std::function<int(int)> a = [](int i) { return i; }, b = a;
    int cardinality = 1;
    if (c == 'L')
    {
      cardinality = 4;
      a = [](int i) { return (i + 1) % 4; };
      b = [](int i) { return i % 2 == 0 ? i + 1 : i - 1; };
    }
    else if (c == 'T')
    {
      cardinality = 4;
      a = [](int i) { return (i + 1) % 4; };
      b = [](int i) { return i % 2 == 0 ? i : 4 - i; };
    }
    else if (c == 'I')
    {
      cardinality = 2;
      a = [](int i) { return 1 - i; };
    }
    else if (c == '\\')
    {
      cardinality = 2;
      a = [](int i) { return 1 - i; };
      b = [](int i) { return 1 - i; };
    }
    else if (c == 'F')
    {
      cardinality = 8;
      a = [](int i) { return i < 4 ? (i + 1) % 4 : 4 + (i - 1) % 4; };
      b = [](int i) { return i < 4 ? i + 4 : i - 4; };
    }
    const int base = static_cast<int>(action.size());
    first.push_back(base);
    for (int t = 0; t < cardinality; ++t)
      action.push_back({ { base + t, base + a(t), base + a(a(t)), base + a(a(a(t))), base + b(t),
        base + b(a(t)), base + b(a(a(t))), base + b(a(a(a(t)))) } });
  }
  const auto act = [&](int t, int k)
  { return action[static_cast<std::size_t>(t)][static_cast<std::size_t>(k)]; };
  std::array<std::set<std::pair<int, int>>, 2> pairs;
  for (const auto& r : rules)
  {
    const int L = act(first[static_cast<std::size_t>(r[0])], r[1]), D = act(L, 1);
    const int R = act(first[static_cast<std::size_t>(r[2])], r[3]), U = act(R, 1);
    // propagator[0][A][B]: B may stand left of A; propagator[1][A][B]: B may stand below A.
    pairs[0].insert({ L, R });
    pairs[0].insert({ act(L, 6), act(R, 6) });
    pairs[0].insert({ act(R, 4), act(L, 4) });
    pairs[0].insert({ act(R, 2), act(L, 2) });
    pairs[1].insert({ D, U });
    pairs[1].insert({ act(U, 6), act(D, 6) });
    pairs[1].insert({ act(D, 4), act(U, 4) });
    pairs[1].insert({ act(U, 2), act(D, 2) });
  }
  return pairs;
}
} // namespace

TEST(Tileset, PairsEqualWaveFunctionCollapsesPropagator)
{
  const std::vector<char> classes = { 'X', 'I', '\\', 'L', 'T', 'F' };
  std::uint64_t state = 12345;
  const auto next = [&state](int n)
  {
    state = state * 6364136223846793005ULL + 1442695040888963407ULL;
    return static_cast<int>((state >> 33) % static_cast<std::uint64_t>(n));
  };
  for (int trial = 0; trial < 40; ++trial)
  {
    std::string xml = "<set><tiles>";
    for (std::size_t i = 0; i < classes.size(); ++i)
      xml += "<tile name=\"t" + std::to_string(i) + "\" symmetry=\"" +
        (classes[i] == '\\' ? std::string("\\") : std::string(1, classes[i])) + "\"/>";
    xml += "</tiles><neighbors>";
    std::vector<std::array<int, 4>> rules;
    for (int r = 0; r < 1 + trial % 5; ++r)
    {
      const std::array<int, 4> rule{ { next(6), next(8), next(6), next(8) } };
      rules.push_back(rule);
      xml += "<neighbor left=\"t" + std::to_string(rule[0]) + " " + std::to_string(rule[1]) +
        "\" right=\"t" + std::to_string(rule[2]) + " " + std::to_string(rule[3]) + "\"/>";
    }
    xml += "</neighbors></set>";
    const Tileset t = Read(xml);
    const auto expected = WfcPairs(classes, rules);
    for (std::size_t axis = 0; axis < 2; ++axis)
    {
      const std::set<std::pair<int, int>> got(t.Pairs[axis].begin(), t.Pairs[axis].end());
      EXPECT_EQ(got, expected[axis]) << "axis " << axis << " of " << xml;
    }
  }
}

TEST(Tileset, NoFailedBlocksWithBacktracking)
{
  // Lines may not end, so lines entering a block from its neighbours must meet inside it: a
  // constraint arc consistency does not see. Without undoing choices many blocks fail (and
  // keep their previous labels); with the default backtracking none does.
  const Tileset lines = ReadTilesetFile(std::string(MSYNTH_DATA) + "/Tilesets/Lines.xml");
  const AdjacencyRules rules = lines.Rules();
  std::int64_t failedWithout = 0, repairedWithout = 0;
  for (std::uint64_t seed = 1; seed <= 4; ++seed)
  {
    SynthesisOptions o;
    o.Size = { { 96, 96, 1 } };
    o.BlockSize = { { 32, 32, 1 } };
    o.Order = SiteOrder::MinimumEntropy;
    o.Choice = LabelChoice::Frequency;
    o.Seed = seed;
    const SynthesisResult r = Synthesize(rules, o);
    ASSERT_TRUE(r.Succeeded()) << r.Message;
    EXPECT_EQ(r.Statistics.BlocksFailed, 0) << "seed " << seed;
    EXPECT_GT(r.Statistics.Backtracks, 0);
    const ConsistencyReport report = CheckConsistency(lines.Pairs, r.Model);
    EXPECT_TRUE(report.Consistent);
    o.BacktracksPerAttempt = 0; // the dissertation's Algorithm 3.4 ...
    o.RepairFailedBlocks = false;
    const SynthesisResult plain = Synthesize(rules, o);
    EXPECT_TRUE(CheckConsistency(lines.Pairs, plain.Model).Consistent);
    EXPECT_EQ(plain.Statistics.Backtracks, 0);
    EXPECT_EQ(plain.Statistics.BlocksRepaired, 0);
    EXPECT_EQ(
      static_cast<std::int64_t>(plain.Statistics.Failures.size()), plain.Statistics.BlocksFailed);
    failedWithout += plain.Statistics.BlocksFailed;
    o.RepairFailedBlocks = true; // ... with a second try at its failed blocks
    const SynthesisResult repaired = Synthesize(rules, o);
    EXPECT_TRUE(CheckConsistency(lines.Pairs, repaired.Model).Consistent);
    EXPECT_EQ(repaired.Statistics.BlocksRepaired + repaired.Statistics.BlocksFailed,
      plain.Statistics.BlocksFailed);
    EXPECT_EQ(repaired.Statistics.BlocksAccepted + repaired.Statistics.BlocksFailed,
      repaired.Statistics.Blocks);
    repairedWithout += repaired.Statistics.BlocksRepaired;
  }
  EXPECT_GT(failedWithout, 0);
  EXPECT_GT(repairedWithout, 0);
}

TEST(Tileset, APictureOfTilesReadsBackAsItsLabels)
{
  // Lines: a model composed row by row (ComposeTileRow, as picture.png is written) and read back
  // by PinsFromPicture gives the labels again; transparent cells are free; a changed pixel is
  // an error naming the cell's site; a size that is not whole tiles is refused.
  const std::string file = std::string(MSYNTH_DATA) + "/Tilesets/Lines.xml";
  const Tileset lines = ReadTilesetFile(file);
  const std::vector<TilePicture> tiles = LoadTilePictures(file, lines);
  ASSERT_EQ(static_cast<int>(tiles.size()), lines.NumberOfLabels());
  const int t = tiles.front().Size, nx = 5, ny = 3;
  std::vector<std::int32_t> labels(static_cast<std::size_t>(nx * ny));
  for (std::size_t i = 0; i < labels.size(); ++i)
    labels[i] = static_cast<std::int32_t>((i * 5 + 1) % tiles.size());
  RgbaImage picture;
  picture.Width = nx * t;
  picture.Height = ny * t;
  picture.Pixels.resize(static_cast<std::size_t>(picture.Width * picture.Height * 4));
  for (int y = 0; y < picture.Height; ++y) // rows from the top; sites from the bottom
  {
    const int fromBottom = picture.Height - 1 - y;
    ComposeTileRow(labels.data() + (fromBottom / t) * nx, nx, tiles, fromBottom % t,
      picture.Pixels.data() + static_cast<std::size_t>(y) * picture.Width * 4);
  }
  for (int y = 0; y < t; ++y) // site (1, ny - 1) transparent: free
    std::fill_n(picture.Pixels.begin() + 4 * (y * picture.Width + t), 4 * t, std::uint8_t(0));
  const LabelGrid pins = PinsFromPicture(picture, "drawn.png", tiles);
  ASSERT_EQ(pins.Size(0), nx);
  ASSERT_EQ(pins.Size(1), ny);
  for (int y = 0; y < ny; ++y)
    for (int x = 0; x < nx; ++x)
      EXPECT_EQ(pins.At(x, y, 0), x == 1 && y == ny - 1 ? -1 : labels[y * nx + x]) << x << y;
  picture.Pixels[4 * (static_cast<std::size_t>(t + 2) * picture.Width + 3 * t + 1)] ^= 0x55;
  try
  {
    PinsFromPicture(picture, "drawn.png", tiles);
    ADD_FAILURE() << "a changed pixel was accepted";
  }
  catch (const Error& e)
  {
    EXPECT_NE(std::string(e.what()).find("site (3, 1)"), std::string::npos) << e.what();
  }
  picture.Width -= 1;
  EXPECT_THROW(PinsFromPicture(picture, "drawn.png", tiles), Error);
}
