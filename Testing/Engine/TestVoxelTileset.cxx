// SPDX-License-Identifier: BSD-3-Clause
// MarkovJunior voxel tilesets: symmetry counts, the rules' images as the format states them, the
// independent check against the reader's pairs, synthesis, and MagicaVoxel scenes.
#include "Core/Error.h"
#include "Discrete/DiscreteSynthesis.h"
#include "Formats/VoxModel.h"
#include "Formats/VoxelTileset.h"

#include <gtest/gtest.h>

#include <fstream>
#include <functional>
#include <set>
#include <sstream>
#include <sys/stat.h>

using namespace msynth;

namespace
{
std::string Folder(const std::string& name)
{
  const std::string dir = std::string(MSYNTH_TEST_TMP) + "/voxel-tilesets/" + name;
  ::mkdir((std::string(MSYNTH_TEST_TMP) + "/voxel-tilesets").c_str(), 0755);
  ::mkdir(dir.c_str(), 0755);
  return dir;
}

/// Writes a tile of palette indices (0 empty) drawn by @p draw.
void WriteTile(
  const std::string& path, int s, int sz, const std::function<int(int, int, int)>& draw)
{
  VoxModel m;
  m.Grid = LabelGrid(s, s, sz, 0);
  for (int z = 0; z < sz; ++z)
    for (int y = 0; y < s; ++y)
      for (int x = 0; x < s; ++x)
        m.Grid.Set(x, y, z, draw(x, y, z));
  m.Palette.assign(256, { { 0, 0, 0, 255 } });
  for (int i = 1; i < 256; ++i)
    m.Palette[static_cast<std::size_t>(i)] = { { static_cast<std::uint8_t>(40 * i),
      static_cast<std::uint8_t>(255 - 30 * i), static_cast<std::uint8_t>(17 * i), 255 } };
  WriteVoxModelFile(path, m);
}

/// Own drawings, 3 voxels a side: Nook (no symmetry: three arms of different colours from a
/// corner, x longest), Rod (a bar along x), Solid (full), Void (empty); 2D: Hook (an L).
void DrawTiles(const std::string& dir, int sz)
{
  WriteTile(dir + "/Nook.vox", 3, sz,
    [](int x, int y, int z)
    {
      if (y == 0 && z == 0 && x < 2)
        return 1;
      if (x == 0 && z == 0 && y == 1)
        return 2;
      return x == 0 && y == 0 && z == 1 ? 3 : 0;
    });
  WriteTile(
    dir + "/Rod.vox", 3, sz, [sz](int, int y, int z) { return y == 1 && z == sz / 2 ? 4 : 0; });
  WriteTile(dir + "/Solid.vox", 3, sz, [](int, int, int) { return 5; });
  WriteTile(dir + "/Void.vox", 3, sz, [](int, int, int) { return 0; });
}

std::string WriteSet(const std::string& name, const std::string& xml, int sz = 3)
{
  const std::string dir = Folder(name);
  DrawTiles(dir, sz);
  const std::string path = dir + ".xml";
  std::ofstream(path) << xml;
  return path;
}

const char* const Tiles = "<tiles> <tile name=\"Void\" weight=\"2.5\"/> <tile name=\"Nook\"/> "
                          "<tile name=\"Rod\"/> <tile name=\"Solid\" legend=\"ignored\"/> </tiles>";

std::string Xml(bool full, const std::string& rules)
{
  return std::string("<tileset") + (full ? " fullSymmetry=\"True\"" : "") + ">\n" + Tiles +
    "\n<neighbors>\n" + rules + "\n</neighbors>\n</tileset>\n";
}

int LabelOf(const Tileset& t, const VoxelBlock& v)
{
  for (int b = 0; b < t.NumberOfLabels(); ++b)
    if (t.LabelVoxels[static_cast<std::size_t>(b)] == v.Voxels)
      return b;
  return -1;
}

VoxelBlock TileBlock(const Tileset& t, const std::string& name)
{
  for (const auto& tile : t.Tiles)
    if (tile.Name == name)
      return { t.VoxelSize, t.LabelVoxels[static_cast<std::size_t>(tile.FirstLabel)] };
  return {};
}

std::set<std::pair<int, int>> PairSet(const Tileset& t, std::size_t axis)
{
  return { t.Pairs[axis].begin(), t.Pairs[axis].end() };
}

CubeSymmetry Diagonal(int x, int y, int z)
{
  CubeSymmetry s;
  s.M = { { { { x, 0, 0 } }, { { 0, y, 0 } }, { { 0, 0, z } } } };
  return s;
}

/// A two-cell model of labels @p a, @p b along @p axis, composed and checked independently.
bool CheckerAccepts(const std::string& path, const Tileset& t, int a, int b, int axis)
{
  LabelGrid labels(axis == 0 ? 2 : 1, axis == 1 ? 2 : 1, axis == 2 ? 2 : 1, a);
  labels.Set(axis == 0, axis == 1, axis == 2, b);
  std::vector<std::array<std::uint8_t, 4>> palette;
  const LabelGrid voxels = ComposeVoxels(t, labels, palette);
  return CheckVoxelModel(path, "", voxels, palette).Valid;
}
} // namespace

TEST(VoxelTileset, SymmetryGroups)
{
  EXPECT_EQ(SymmetryGroup(false).size(), 8u);
  EXPECT_EQ(SymmetryGroup(true).size(), 48u);
  for (std::size_t i = 0; i < 8; ++i)
    EXPECT_EQ(SymmetryGroup(true)[i], SymmetryGroup(false)[i]);
  EXPECT_EQ(SymmetryGroup(true)[0], CubeSymmetry());
  // The configuration turned about z puts +x at +y; about y, +x at +z; the mirror, at -x.
  EXPECT_EQ(CubeSymmetry::QuarterTurn(2).MapsAxis(0), 2);
  EXPECT_EQ(CubeSymmetry::QuarterTurn(1).MapsAxis(0), 3);
  EXPECT_EQ(CubeSymmetry::MirrorX().MapsAxis(0), -1);
  CubeSymmetry zzx;
  ASSERT_TRUE(ParseTurns("zzx", zzx)); // about x first, then z twice
  const CubeSymmetry z = CubeSymmetry::QuarterTurn(2);
  EXPECT_EQ(zzx, CubeSymmetry::Then(CubeSymmetry::Then(CubeSymmetry::QuarterTurn(0), z), z));
  CubeSymmetry bad;
  EXPECT_FALSE(ParseTurns("zq", bad));
}

TEST(VoxelTileset, TurnsAreTheFormatsSourceLookups)
{
  VoxelBlock b;
  b.Size = { { 3, 3, 3 } };
  for (std::uint32_t i = 0; i < 27; ++i)
    b.Voxels.push_back(i + 1);
  const auto at = [](const VoxelBlock& v, int x, int y, int z)
  { return v.Voxels[static_cast<std::size_t>(x + 3 * (y + 3 * z))]; };
  const VoxelBlock zt = TransformVoxels(b, CubeSymmetry::QuarterTurn(2));
  const VoxelBlock yt = TransformVoxels(b, CubeSymmetry::QuarterTurn(1));
  const VoxelBlock xt = TransformVoxels(b, CubeSymmetry::QuarterTurn(0));
  const VoxelBlock m = TransformVoxels(b, CubeSymmetry::MirrorX());
  for (int z = 0; z < 3; ++z)
    for (int y = 0; y < 3; ++y)
      for (int x = 0; x < 3; ++x)
      {
        EXPECT_EQ(at(zt, x, y, z), at(b, y, 2 - x, z));
        EXPECT_EQ(at(yt, x, y, z), at(b, z, y, 2 - x));
        EXPECT_EQ(at(xt, x, y, z), at(b, x, z, 2 - y));
        EXPECT_EQ(at(m, x, y, z), at(b, 2 - x, y, z));
      }
}

TEST(VoxelTileset, VariantCounts)
{
  const Tileset square = ReadTilesetFile(WriteSet("Counts", Xml(false, "")));
  const Tileset cube = ReadTilesetFile(WriteSet("CountsFull", Xml(true, "")));
  const int expectSquare[] = { 1, 8, 2, 1 }, expectCube[] = { 1, 48, 3, 1 };
  for (std::size_t i = 0; i < 4; ++i)
  {
    EXPECT_EQ(square.Tiles[i].Orientations, expectSquare[i]) << square.Tiles[i].Name;
    EXPECT_EQ(cube.Tiles[i].Orientations, expectCube[i]) << cube.Tiles[i].Name;
  }
  EXPECT_EQ(square.NumberOfLabels(), 12);
  EXPECT_EQ(cube.NumberOfLabels(), 53);
  EXPECT_TRUE(square.Voxel);
  EXPECT_EQ(square.VoxelSize, (std::array<int, 3>{ { 3, 3, 3 } }));
  // Weights go to every image of the tile; other attributes are ignored.
  EXPECT_DOUBLE_EQ(square.Tiles[0].Weight, 2.5);
}

TEST(VoxelTileset, SquareRulesAreTheImagesTheFormatLists)
{
  // One left/right rule with a turn prefix, one top/bottom rule; text between elements.
  const Tileset t = ReadTilesetFile(WriteSet("Square",
    Xml(false,
      "<neighbor left=\"z Nook\" right=\"Rod\"/> ~ text\n"
      "<neighbor top=\"Nook\" bottom=\"zz Nook\"/> 12")));
  const CubeSymmetry z = CubeSymmetry::QuarterTurn(2), mx = Diagonal(-1, 1, 1),
                     my = Diagonal(1, -1, 1);
  const VoxelBlock a = TransformVoxels(TileBlock(t, "Nook"), z), b = TileBlock(t, "Rod");
  const auto L = [&t](const VoxelBlock& v, const CubeSymmetry& s)
  { return LabelOf(t, TransformVoxels(v, s)); };
  const CubeSymmetry id, mxy = CubeSymmetry::Then(mx, my);
  std::set<std::pair<int, int>> x{ { L(a, id), L(b, id) }, { L(a, my), L(b, my) },
    { L(b, mx), L(a, mx) }, { L(b, mxy), L(a, mxy) } };
  const VoxelBlock za = TransformVoxels(a, z), zb = TransformVoxels(b, z);
  std::set<std::pair<int, int>> y{ { L(za, id), L(zb, id) }, { L(za, mx), L(zb, mx) },
    { L(zb, my), L(za, my) }, { L(zb, mxy), L(za, mxy) } };
  std::set<std::pair<int, int>> up;
  const VoxelBlock top = TileBlock(t, "Nook"),
                   bottom = TransformVoxels(TransformVoxels(TileBlock(t, "Nook"), z), z);
  for (const CubeSymmetry& g : SymmetryGroup(false))
    up.insert({ L(bottom, g), L(top, g) });
  EXPECT_EQ(PairSet(t, 0), x);
  EXPECT_EQ(PairSet(t, 1), y);
  EXPECT_EQ(PairSet(t, 2), up);
}

TEST(VoxelTileset, IndependentCheckAgreesWithTheRulesOnEveryPair)
{
  for (const bool full : { false, true })
  {
    const std::string path = WriteSet(full ? "AgreeFull" : "Agree",
      Xml(full,
        full ? "<neighbor left=\"Void\" right=\"zzx Nook\"/><neighbor left=\"y Rod\" "
               "right=\"Nook\"/><neighbor left=\"Solid\" right=\"Solid\"/>"
             : "<neighbor left=\"Void\" right=\"z Nook\"/><neighbor left=\"Rod\" right=\"Rod\"/>"
               "<neighbor top=\"zzz Nook\" bottom=\"Solid\"/>"));
    const Tileset t = ReadTilesetFile(path);
    int accepted = 0;
    // Every pair of the tile images whose first tile is Void, Rod or Solid, and Nook's first
    // eight images, on every axis: the checker accepts exactly the rules' pairs.
    for (int a = 0; a < t.NumberOfLabels(); ++a)
    {
      if (t.LabelTile[static_cast<std::size_t>(a)] == 1 &&
        t.LabelOrientation[static_cast<std::size_t>(a)] >= 8)
        continue;
      for (int b = 0; b < t.NumberOfLabels(); ++b)
        for (int axis = 0; axis < 3; ++axis)
        {
          const auto& p = t.Pairs[static_cast<std::size_t>(axis)];
          const bool allowed = std::find(p.begin(), p.end(), std::make_pair(a, b)) != p.end();
          ASSERT_EQ(CheckerAccepts(path, t, a, b, axis), allowed)
            << (full ? "full " : "square ") << t.LabelName(a) << " then " << t.LabelName(b)
            << " along axis " << axis;
          accepted += allowed;
        }
    }
    EXPECT_GT(accepted, 8);
  }
}

TEST(VoxelTileset, SynthesizedModelsPassTheIndependentCheck)
{
  const std::string path = WriteSet("Synth",
    Xml(true,
      "<neighbor left=\"Void\" right=\"Void\"/><neighbor left=\"Void\" right=\"Rod\"/>"
      "<neighbor left=\"Rod\" right=\"Rod\"/><neighbor left=\"y Rod\" right=\"Void\"/>"));
  const Tileset t = ReadTilesetFile(path);
  for (const bool blocks : { false, true })
  {
    SynthesisOptions o;
    o.Size = { { 6, 5, 4 } };
    if (blocks)
      o.BlockSize = { { 3, 3, 3 } };
    o.Seed = 7;
    const SynthesisResult r = Synthesize(t.Rules(), o);
    ASSERT_TRUE(r.Succeeded()) << r.Message;
    std::vector<std::array<std::uint8_t, 4>> palette;
    LabelGrid voxels = ComposeVoxels(t, r.Model, palette);
    EXPECT_EQ(voxels.Dimensions(), (std::array<std::int64_t, 3>{ { 18, 15, 12 } }));
    const VoxelCheckReport report = CheckVoxelModel(path, "", voxels, palette);
    EXPECT_TRUE(report.Valid) << (report.First.empty() ? "" : report.First[0]);
    EXPECT_EQ(report.Cells, 120);
    // A rod cut short is no tile image.
    for (std::int64_t x = 0; x < 3; ++x)
      voxels.Set(x, 1, 1, 4);
    voxels.Set(1, 1, 1, 0);
    const VoxelCheckReport broken = CheckVoxelModel(path, "", voxels, palette);
    EXPECT_FALSE(broken.Valid);
    ASSERT_FALSE(broken.First.empty());
    EXPECT_NE(broken.First[0].find("(0, 0, 0)"), std::string::npos) << broken.First[0];
  }
}

TEST(VoxelTileset, TwoDimensionalSetsAndTheTilesFolder)
{
  const std::string dir = Folder("Flat");
  const std::string tiles = Folder("FlatTiles");
  DrawTiles(tiles, 1);
  const std::string path = dir + ".xml";
  std::ofstream(path) << Xml(false, "<neighbor left=\"Nook\" right=\"z Rod\"/>");
  // --tiles: as given, or relative to the XML's folder.
  const Tileset t = ReadTilesetFile(path, "", "FlatTiles");
  EXPECT_EQ(t.VoxelSize, (std::array<int, 3>{ { 3, 3, 1 } }));
  EXPECT_EQ(t.Tiles[1].Orientations, 8);
  EXPECT_EQ(t.Tiles[2].Orientations, 2);
  EXPECT_TRUE(t.Pairs[2].empty());
  EXPECT_EQ(t.TilesFolder, std::string(MSYNTH_TEST_TMP) + "/voxel-tilesets/FlatTiles");
  const Tileset same = ReadTilesetFile(path, "", tiles);
  EXPECT_EQ(same.Pairs, t.Pairs);
}

TEST(VoxelTileset, ErrorsNameTheFileAndTheProblem)
{
  const auto error = [](const std::string& path, const std::string& tiles = "")
  {
    try
    {
      ReadTilesetFile(path, "", tiles);
    }
    catch (const Error& e)
    {
      return std::string(e.what());
    }
    return std::string();
  };
  const std::string missing =
    WriteSet("Missing", "<tileset><tiles><tile name=\"Gone\"/></tiles></tileset>");
  EXPECT_NE(error(missing).find("Gone.vox"), std::string::npos) << error(missing);
  EXPECT_NE(error(WriteSet("BadTurn", Xml(true, "<neighbor left=\"q Rod\" right=\"Rod\"/>")))
              .find("quarter turns"),
    std::string::npos);
  EXPECT_NE(error(WriteSet("NoSide", Xml(false, "<neighbor left=\"Rod\" top=\"Rod\"/>")))
              .find("either left and right or top and bottom"),
    std::string::npos);
  EXPECT_NE(
    error(WriteSet("Unknown", Xml(false, "<neighbor left=\"Rod\" right=\"Nope\"/>"))).find("Nope"),
    std::string::npos);
  // A turn about x of an asymmetric tile without fullSymmetry is none of its images.
  EXPECT_NE(error(WriteSet("XTurn", Xml(false, "<neighbor left=\"x Nook\" right=\"Rod\"/>")))
              .find("need fullSymmetry"),
    std::string::npos);
  // ... but a symmetric one is fine.
  EXPECT_EQ(
    error(WriteSet("XTurnSym", Xml(false, "<neighbor left=\"x Solid\" right=\"Rod\"/>"))), "");
  const std::string flat = WriteSet("FlatFull", Xml(true, ""), 1);
  EXPECT_NE(error(flat).find("with fullSymmetry tiles are cubes"), std::string::npos)
    << error(flat);
}

TEST(VoxelTileset, ScenesOfManyModelsRoundTrip)
{
  VoxModel m;
  m.Grid = LabelGrid(300, 20, 260, 0);
  std::uint64_t h = 1;
  for (std::int64_t z = 0; z < 260; ++z)
    for (std::int64_t y = 0; y < 20; ++y)
      for (std::int64_t x = 0; x < 300; ++x)
      {
        h = h * 6364136223846793005ull + 1442695040888963407ull;
        if ((h >> 60) < 3)
          m.Grid.Set(x, y, z, static_cast<Label>(1 + (h >> 33) % 255));
      }
  m.Grid.Set(299, 19, 259, 9); // the far corner is set, so the extent is the grid's
  m.Grid.Set(0, 0, 0, 3);
  m.Palette.assign(256, { { 1, 2, 3, 255 } });
  m.Palette[0] = { { 0, 0, 0, 0 } };
  std::ostringstream out;
  WriteVoxScene(out, m, "scene.vox");
  const std::string s = out.str();
  const std::vector<std::uint8_t> bytes(s.begin(), s.end());
  const VoxModel back = ReadVoxScene(bytes, "scene.vox", std::int64_t(1) << 26);
  EXPECT_EQ(back.NumberOfModels, 4);
  EXPECT_EQ(back.Grid.Dimensions(), m.Grid.Dimensions());
  EXPECT_TRUE(back.Grid.Data() == m.Grid.Data());
  EXPECT_EQ(back.Palette[5], m.Palette[5]);
  // The first model alone, as the label-grid reader reads it.
  const VoxModel first = ReadVoxModel(bytes, "scene.vox", std::int64_t(1) << 26);
  EXPECT_EQ(first.Grid.Dimensions(), (std::array<std::int64_t, 3>{ { 256, 20, 256 } }));
  EXPECT_EQ(first.Grid.At(0, 0, 0), 3);
  // A one-model file without a scene reads as that model.
  std::ostringstream one;
  VoxModel small;
  small.Grid = LabelGrid(4, 3, 2, 0);
  small.Grid.Set(3, 2, 1, 7);
  WriteVoxModel(one, small, "one.vox");
  const std::string o = one.str();
  const VoxModel single =
    ReadVoxScene(std::vector<std::uint8_t>(o.begin(), o.end()), "one.vox", 100);
  EXPECT_EQ(single.Grid.At(3, 2, 1), 7);
  // A cut file is an error, never an over-read.
  for (std::size_t cut : { std::size_t(8), bytes.size() / 2, bytes.size() - 3 })
    EXPECT_THROW(ReadVoxScene(std::vector<std::uint8_t>(bytes.begin(), bytes.begin() + cut),
                   "cut.vox", std::int64_t(1) << 26),
      Error);
}

TEST(VoxelTileset, TurnMapTurnsEachImageAboutZ)
{
  for (const bool full : { false, true })
  {
    const Tileset t = ReadTilesetFile(WriteSet(full ? "TurnFull" : "Turn", Xml(full, "")));
    const auto turn = t.TurnMap();
    ASSERT_EQ(static_cast<int>(turn.size()), t.NumberOfLabels());
    for (int b = 0; b < t.NumberOfLabels(); ++b)
    {
      const VoxelBlock turned = TransformVoxels(
        { t.VoxelSize, t.LabelVoxels[static_cast<std::size_t>(b)] }, CubeSymmetry::QuarterTurn(2));
      EXPECT_EQ(t.LabelVoxels[static_cast<std::size_t>(turn.at(b))], turned.Voxels) << b;
    }
  }
  // A rotation-symmetric model of a voxel set: the solver's --rotate with this map.
  const Tileset t = ReadTilesetFile(WriteSet("TurnSynth",
    Xml(false,
      "<neighbor left=\"Void\" right=\"Void\"/><neighbor left=\"Rod\" right=\"Rod\"/>"
      "<neighbor left=\"z Rod\" right=\"Void\"/><neighbor top=\"Void\" bottom=\"Void\"/>"
      "<neighbor top=\"Rod\" bottom=\"Rod\"/>")));
  SynthesisOptions o;
  o.Size = { { 6, 6, 2 } };
  o.Rotate.Enabled = true;
  o.Rotate.Map = t.TurnMap();
  o.Seed = 3;
  const SynthesisResult r = Synthesize(t.Rules(), o);
  ASSERT_TRUE(r.Succeeded()) << r.Message;
  for (std::int64_t z = 0; z < 2; ++z)
    for (std::int64_t y = 0; y < 6; ++y)
      for (std::int64_t x = 0; x < 6; ++x) // site (x, y) turned a quarter is (5 - y, x)
        EXPECT_EQ(r.Model.At(5 - y, x, z), o.Rotate.Map.at(r.Model.At(x, y, z)));
}

TEST(VoxelTileset, MirrorMapsMirrorEachImage)
{
  for (const bool full : { false, true })
  {
    const Tileset t = ReadTilesetFile(WriteSet(full ? "MirrorFull" : "Mirror", Xml(full, "")));
    for (int axis = 0; axis < (full ? 3 : 2); ++axis)
    {
      const auto map = t.MirrorMap(axis);
      CubeSymmetry mirror;
      mirror.M[static_cast<std::size_t>(axis)][static_cast<std::size_t>(axis)] = -1;
      for (int b = 0; b < t.NumberOfLabels(); ++b)
        EXPECT_EQ(t.LabelVoxels[static_cast<std::size_t>(map.at(b))],
          TransformVoxels({ t.VoxelSize, t.LabelVoxels[static_cast<std::size_t>(b)] }, mirror)
            .Voxels)
          << axis << " " << b;
    }
  }
  // Without fullSymmetry a mirror in z exists only when every image is its own.
  EXPECT_THROW(ReadTilesetFile(WriteSet("MirrorZ", Xml(false, ""))).MirrorMap(2), Error);
  // A model mirror-symmetric in x and y, synthesized with the maps.
  const Tileset t = ReadTilesetFile(WriteSet("MirrorSynth",
    Xml(true,
      "<neighbor left=\"Void\" right=\"Void\"/><neighbor left=\"Void\" right=\"Rod\"/>"
      "<neighbor left=\"Rod\" right=\"Rod\"/><neighbor left=\"y Rod\" right=\"Void\"/>")));
  SynthesisOptions o;
  o.Size = { { 6, 5, 4 } };
  o.Seed = 2;
  for (std::size_t a = 0; a < 2; ++a)
  {
    o.Symmetry[a].Enabled = true;
    o.Symmetry[a].Map = t.MirrorMap(static_cast<int>(a));
  }
  const SynthesisResult r = Synthesize(t.Rules(), o);
  ASSERT_TRUE(r.Succeeded()) << r.Message;
  std::vector<std::array<std::uint8_t, 4>> palette;
  const LabelGrid v = ComposeVoxels(t, r.Model, palette);
  const auto& d = v.Dimensions();
  for (std::int64_t z = 0; z < d[2]; ++z)
    for (std::int64_t y = 0; y < d[1]; ++y)
      for (std::int64_t x = 0; x < d[0]; ++x)
      {
        ASSERT_EQ(v.At(x, y, z), v.At(d[0] - 1 - x, y, z));
        ASSERT_EQ(v.At(x, y, z), v.At(x, d[1] - 1 - y, z));
      }
}
