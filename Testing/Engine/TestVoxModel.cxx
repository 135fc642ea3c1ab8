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
} // namespace

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
