// SPDX-License-Identifier: BSD-3-Clause
// Formats/GltfFile: the .glb container read back here byte by byte (header, chunk lengths, the
// binary chunk's positions turned to y up), the colours made linear, and the errors that name
// the file. The full reading back (VTK's glTF reader, the Khronos validator) is in
// Testing/Python/test_gltf*.py.
#include "Core/Error.h"
#include "Core/LabelColor.h"
#include "Formats/GltfFile.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace
{
std::string Bytes(const std::string& path)
{
  std::ifstream in(path, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

std::uint32_t Word(const std::string& bytes, std::size_t at)
{
  std::uint32_t w = 0;
  std::memcpy(&w, bytes.data() + at, 4);
  return w;
}

msynth::GltfPart Square(const std::string& name)
{
  msynth::GltfPart part;
  part.Name = name;
  part.Color = { 1.0, 0.5, 0.0, 1.0 };
  part.Positions = { 0, 0, 0, 1, 0, 0, 1, 1, 2, 0, 1, 2 };
  part.Triangles = { 0, 1, 2, 0, 2, 3 };
  return part;
}
} // namespace

TEST(GltfFile, ContainerChunksAndTurnedPositions)
{
  const std::string path = std::string(MSYNTH_TEST_TMP) + "/engine-square.glb";
  msynth::WriteGlbFile(path, { Square("label 7") }, "test");
  const std::string bytes = Bytes(path);
  ASSERT_GE(bytes.size(), 28u);
  EXPECT_EQ(bytes.substr(0, 4), "glTF");
  EXPECT_EQ(Word(bytes, 4), 2u);
  EXPECT_EQ(Word(bytes, 8), bytes.size());
  const std::uint32_t json = Word(bytes, 12);
  EXPECT_EQ(Word(bytes, 16), 0x4E4F534Au); // JSON
  EXPECT_EQ(json % 4, 0u);
  const std::string text = bytes.substr(20, json);
  EXPECT_NE(text.find("\"label 7\""), std::string::npos);
  EXPECT_NE(text.find("\"generator\":\"test\""), std::string::npos);
  // The binary chunk: 4 positions (48 bytes) then 6 indices (24 bytes).
  const std::size_t bin = 20 + json;
  ASSERT_EQ(Word(bytes, bin + 4), 0x004E4942u); // BIN
  EXPECT_GE(Word(bytes, bin), 72u);
  float p[12];
  std::memcpy(p, bytes.data() + bin + 8, sizeof(p));
  // Vertex 2 (1, 1, 2) in the model's z-up frame is (1, 2, -1) in glTF's y-up frame.
  EXPECT_EQ(p[6], 1.0f);
  EXPECT_EQ(p[7], 2.0f);
  EXPECT_EQ(p[8], -1.0f);
  std::uint32_t indices[6];
  std::memcpy(indices, bytes.data() + bin + 8 + 48, sizeof(indices));
  EXPECT_EQ(indices[4], 2u);
  EXPECT_EQ(indices[5], 3u);
  // sRGB 0.5 is linear 0.214 (the sRGB curve), 1 stays 1, 0 stays 0.
  EXPECT_NE(text.find("\"baseColorFactor\":[1.0,0.21404114"), std::string::npos) << text;
}

TEST(GltfFile, InconsistentPartsAndUnwritablePathsNameTheFile)
{
  const std::string path = std::string(MSYNTH_TEST_TMP) + "/engine-bad.glb";
  msynth::GltfPart bad = Square("label 1");
  bad.Triangles.back() = 4; // one past the 4 vertices
  try
  {
    msynth::WriteGlbFile(path, { bad }, "test");
    FAIL() << "an index out of range was accepted";
  }
  catch (const msynth::Error& e)
  {
    EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("index 4"), std::string::npos) << e.what();
  }
  EXPECT_FALSE(std::ifstream(path).good()); // nothing written
  const std::string unwritable = std::string(MSYNTH_TEST_TMP) + "/no-such-folder/x.glb";
  EXPECT_THROW(msynth::WriteGlbFile(unwritable, { Square("a") }, "test"), msynth::Error);
}

TEST(LabelColor, PaletteAndDistinctColoursBeyondIt)
{
  const auto sand = msynth::LabelColor(1);
  EXPECT_DOUBLE_EQ(sand[0], 0.80);
  EXPECT_DOUBLE_EQ(sand[2], 0.50);
  EXPECT_EQ(msynth::LabelColor(0), msynth::LabelColor(12));
  for (int a = 13; a < 80; ++a)
    for (int b = a + 1; b < 80; ++b)
      EXPECT_NE(msynth::LabelColor(a), msynth::LabelColor(b)) << a << " " << b;
}
