// SPDX-License-Identifier: BSD-3-Clause
#include "Core/Error.h"
#include "Formats/VoxModel.h"

#include <gtest/gtest.h>

#include <sstream>

#include <random>

using namespace msynth;

namespace
{
void U32(std::vector<std::uint8_t>& b, std::uint32_t v)
{
  for (int i = 0; i < 4; ++i)
    b.push_back(static_cast<std::uint8_t>(v >> (8 * i)));
}
void Chunk(std::vector<std::uint8_t>& b, const char* id, const std::vector<std::uint8_t>& content,
  const std::vector<std::uint8_t>& children = {})
{
  b.insert(b.end(), id, id + 4);
  U32(b, static_cast<std::uint32_t>(content.size()));
  U32(b, static_cast<std::uint32_t>(children.size()));
  b.insert(b.end(), content.begin(), content.end());
  b.insert(b.end(), children.begin(), children.end());
}
/// A 3 x 2 x 2 model with voxels (0,0,0)=5, (2,1,1)=7, (1,0,1)=255 and optionally a palette.
std::vector<std::uint8_t> Sample(bool palette)
{
  std::vector<std::uint8_t> size, xyzi, rgba, children, file;
  U32(size, 3);
  U32(size, 2);
  U32(size, 2);
  U32(xyzi, 3);
  for (std::uint8_t v : { 0, 0, 0, 5, 2, 1, 1, 7, 1, 0, 1, 255 })
    xyzi.push_back(v);
  Chunk(children, "SIZE", size);
  Chunk(children, "XYZI", xyzi);
  if (palette)
  {
    for (int i = 0; i < 256; ++i)
      for (int c = 0; c < 4; ++c)
        rgba.push_back(static_cast<std::uint8_t>(i + c));
    Chunk(children, "RGBA", rgba);
  }
  file = { 'V', 'O', 'X', ' ' };
  U32(file, 150);
  Chunk(file, "MAIN", {}, children);
  return file;
}
/// A DICT of the scene chunks: a count, then key and value as (length, bytes) strings.
std::vector<std::uint8_t> Dict(const std::vector<std::pair<std::string, std::string>>& entries)
{
  std::vector<std::uint8_t> b;
  U32(b, static_cast<std::uint32_t>(entries.size()));
  for (const auto& [key, value] : entries)
    for (const std::string* text : { &key, &value })
    {
      U32(b, static_cast<std::uint32_t>(text->size()));
      b.insert(b.end(), text->begin(), text->end());
    }
  return b;
}

/// A file laid out as MagicaVoxel 0.99.7 saves it (version 200): the models first (SIZE, XYZI,
/// each), then the scene graph (nTRN, nGRP, nSHP with DICT attributes and frames), eight LAYR,
/// RGBA, IMAP, a MATL per palette entry, render objects (rOBJ), cameras (rCAM) and NOTE.
std::vector<std::uint8_t> SavedByMagicaVoxel()
{
  std::vector<std::uint8_t> children, content;
  for (int model = 0; model < 2; ++model)
  {
    content.clear();
    for (std::uint32_t n : { 3u, 2u, 2u })
      U32(content, n);
    Chunk(children, "SIZE", content);
    content.clear();
    const std::vector<std::uint8_t> voxels = model == 0
      ? std::vector<std::uint8_t>{ 0, 0, 0, 5, 2, 1, 1, 7 }
      : std::vector<std::uint8_t>{ 1, 1, 1, 9 };
    U32(content, static_cast<std::uint32_t>(voxels.size() / 4));
    content.insert(content.end(), voxels.begin(), voxels.end());
    Chunk(children, "XYZI", content);
  }
  auto node =
    [](std::uint32_t id, const std::vector<std::pair<std::string, std::string>>& attributes)
  {
    std::vector<std::uint8_t> b;
    U32(b, id);
    const auto dict = Dict(attributes);
    b.insert(b.end(), dict.begin(), dict.end());
    return b;
  };
  content = node(0, {}); // the root transform: child 1, no layer, one frame
  for (std::uint32_t v : { 1u, 0xffffffffu, 0xffffffffu, 1u })
    U32(content, v);
  auto frame = Dict({ { "_t", "0 0 1" } });
  content.insert(content.end(), frame.begin(), frame.end());
  Chunk(children, "nTRN", content);
  content = node(1, {}); // a group of two shapes' transforms
  U32(content, 2);
  U32(content, 2);
  U32(content, 4);
  Chunk(children, "nGRP", content);
  for (std::uint32_t t : { 2u, 4u })
  {
    content = node(t, { { "_name", "house" }, { "_hidden", "0" } });
    for (std::uint32_t v : { t + 1, 0xffffffffu, 0u, 1u })
      U32(content, v);
    frame = Dict({ { "_t", t == 2 ? "0 0 0" : "8 0 0" }, { "_r", "4" } });
    content.insert(content.end(), frame.begin(), frame.end());
    Chunk(children, "nTRN", content);
    content = node(t + 1, {});
    U32(content, 1); // one model
    U32(content, t == 2 ? 0 : 1);
    frame = Dict({ { "_f", "0" } });
    content.insert(content.end(), frame.begin(), frame.end());
    Chunk(children, "nSHP", content);
  }
  for (std::uint32_t layer = 0; layer < 8; ++layer)
  {
    content = node(layer, { { "_name", "layer" } });
    U32(content, 0xffffffffu);
    Chunk(children, "LAYR", content);
  }
  content.clear();
  for (int i = 0; i < 256; ++i)
    for (int c = 0; c < 4; ++c)
      content.push_back(static_cast<std::uint8_t>(255 - i));
  Chunk(children, "RGBA", content);
  content.clear();
  for (int i = 0; i < 256; ++i)
    content.push_back(static_cast<std::uint8_t>(i));
  Chunk(children, "IMAP", content);
  for (std::uint32_t m = 0; m < 256; ++m)
    Chunk(children, "MATL", node(m, { { "_type", "_diffuse" }, { "_weight", "1" } }));
  Chunk(children, "rOBJ", Dict({ { "_type", "_bloom" }, { "_mix", "0.5" } }));
  Chunk(children, "rCAM", node(0, { { "_mode", "pers" }, { "_focus", "0 0 0" } }));
  content.clear();
  U32(content, 1);
  U32(content, 4);
  for (char c : std::string("note"))
    content.push_back(static_cast<std::uint8_t>(c));
  Chunk(children, "NOTE", content);
  std::vector<std::uint8_t> file = { 'V', 'O', 'X', ' ' };
  U32(file, 200);
  Chunk(file, "MAIN", {}, children);
  return file;
}
} // namespace

TEST(VoxModel, FilesAsMagicaVoxelSavesThemRead)
{
  // Version 200 with the scene graph, layers, materials, render settings and a second model:
  // the first model and the palette are read, everything else is skipped.
  const VoxModel m = ReadVoxModel(SavedByMagicaVoxel(), "scene.vox", 1000);
  EXPECT_EQ(m.NumberOfModels, 2);
  EXPECT_EQ(m.Grid.Dimensions(), (std::array<std::int64_t, 3>{ { 3, 2, 2 } }));
  EXPECT_EQ(m.Grid.At(0, 0, 0), 5);
  EXPECT_EQ(m.Grid.At(2, 1, 1), 7);
  EXPECT_EQ(m.Grid.At(1, 0, 0), 0);
  EXPECT_EQ(m.Palette[5], (std::array<std::uint8_t, 4>{ { 251, 251, 251, 251 } }));
}

TEST(VoxModel, PaletteIndexIsTheLabel)
{
  const VoxModel m = ReadVoxModel(Sample(true), "s.vox", 1000);
  EXPECT_EQ(m.Grid.Dimensions(), (std::array<std::int64_t, 3>{ { 3, 2, 2 } }));
  EXPECT_EQ(m.Grid.At(0, 0, 0), 5);
  EXPECT_EQ(m.Grid.At(2, 1, 1), 7);
  EXPECT_EQ(m.Grid.At(1, 0, 1), 255);
  EXPECT_EQ(m.Grid.At(1, 1, 0), 0); // empty
  // Chunk entry i is the colour of palette index i + 1.
  EXPECT_EQ(m.Palette[1], (std::array<std::uint8_t, 4>{ { 0, 1, 2, 3 } }));
  EXPECT_EQ(m.Palette[5], (std::array<std::uint8_t, 4>{ { 4, 5, 6, 7 } }));
  // Without RGBA: the format's default palette (index 1 is opaque white, ABGR 0xffffffff).
  const VoxModel d = ReadVoxModel(Sample(false), "d.vox", 1000);
  EXPECT_EQ(d.Palette[1], (std::array<std::uint8_t, 4>{ { 255, 255, 255, 255 } }));
  EXPECT_EQ(d.Palette[255], (std::array<std::uint8_t, 4>{ { 0x11, 0x11, 0x11, 0xff } }));
}

TEST(VoxModel, EveryTruncationAndCorruptionIsAnErrorNeverACrash)
{
  const std::vector<std::uint8_t> good = Sample(true);
  for (std::size_t cut = 0; cut < good.size(); ++cut)
  {
    const std::vector<std::uint8_t> part(
      good.begin(), good.begin() + static_cast<std::ptrdiff_t>(cut));
    EXPECT_THROW(ReadVoxModel(part, "cut.vox", 1000), Error) << "cut at " << cut;
  }
  // Random byte flips: either a clean error or a model within the declared size (fuzz).
  std::mt19937 rng(5);
  for (int trial = 0; trial < 2000; ++trial)
  {
    std::vector<std::uint8_t> bad = good;
    for (int flips = 0; flips < 3; ++flips)
      bad[rng() % bad.size()] = static_cast<std::uint8_t>(rng());
    try
    {
      const VoxModel m = ReadVoxModel(bad, "fuzz.vox", 1 << 20);
      EXPECT_LE(m.Grid.NumberOfSites(), 1 << 20);
    }
    catch (const Error& e)
    {
      EXPECT_NE(std::string(e.what()).find("fuzz.vox"), std::string::npos);
    }
  }
  EXPECT_THROW(ReadVoxModel(good, "small.vox", 11), Error); // 12 sites over a limit of 11
  EXPECT_THROW(ReadVoxModelFile("/no/such.vox", 100), Error);
}

TEST(VoxModel, WrittenModelsReadBackWithTheirPalette)
{
  msynth::VoxModel m;
  m.Grid = msynth::LabelGrid(5, 4, 3, 0);
  for (std::int64_t z = 0; z < 3; ++z)
    for (std::int64_t y = 0; y < 4; ++y)
      for (std::int64_t x = 0; x < 5; ++x)
        m.Grid.Set(x, y, z, static_cast<msynth::Label>((x * 7 + y * 3 + z * 51) % 256));
  m.Palette.resize(256);
  for (std::size_t i = 0; i < 256; ++i)
    m.Palette[i] = { { static_cast<std::uint8_t>(i), static_cast<std::uint8_t>(255 - i),
      static_cast<std::uint8_t>(i * 3), 255 } };
  std::ostringstream out;
  msynth::WriteVoxModel(out, m, "m.vox");
  const std::string bytes = out.str();
  const msynth::VoxModel back =
    msynth::ReadVoxModel(std::vector<std::uint8_t>(bytes.begin(), bytes.end()), "m.vox", 1000);
  EXPECT_EQ(back.Grid, m.Grid);
  for (std::size_t i = 1; i < 256; ++i) // index 0 is empty space, not a colour
    EXPECT_EQ(back.Palette[i], m.Palette[i]) << i;
  // Without a palette MagicaVoxel's default is used (no RGBA chunk).
  m.Palette.clear();
  std::ostringstream plain;
  msynth::WriteVoxModel(plain, m, "m.vox");
  EXPECT_EQ(plain.str().find("RGBA"), std::string::npos);
  // What MagicaVoxel cannot hold is an error naming the file.
  m.Grid.Set(1, 1, 1, 300);
  std::ostringstream bad;
  EXPECT_THROW(msynth::WriteVoxModel(bad, m, "m.vox"), msynth::Error);
  msynth::VoxModel big;
  big.Grid = msynth::LabelGrid(257, 1, 1, 1);
  try
  {
    msynth::WriteVoxModel(bad, big, "big.vox");
    ADD_FAILURE() << "a 257-voxel model was written";
  }
  catch (const msynth::Error& e)
  {
    EXPECT_NE(
      std::string(e.what()).find("'big.vox': cannot hold a 257 x 1 x 1 model"), std::string::npos);
  }
}
