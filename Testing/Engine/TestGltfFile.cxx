// SPDX-License-Identifier: BSD-3-Clause
// Formats/GltfFile: the .glb container read back here byte by byte (header, chunk lengths, the
// binary chunk's positions turned to y up), the colours made linear, and the errors that name
// the file. The full reading back (VTK's glTF reader, the Khronos validator) is in
// Testing/Python/test_gltf*.py.
#include "Core/Error.h"
#include "Core/LabelColor.h"
#include "Formats/GltfFile.h"

#include <gtest/gtest.h>

#include <array>
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

namespace
{
/// The area of @p part's triangles and whether each triangle's normals are its winding's.
double TriangleArea(const msynth::GltfPart& part, bool& normalsAgree)
{
  double area = 0;
  normalsAgree = part.Normals.size() == part.Positions.size();
  for (std::size_t t = 0; t + 2 < part.Triangles.size(); t += 3)
  {
    const float* a = &part.Positions[3 * part.Triangles[t]];
    const float* b = &part.Positions[3 * part.Triangles[t + 1]];
    const float* c = &part.Positions[3 * part.Triangles[t + 2]];
    const double u[3] = { b[0] - a[0], b[1] - a[1], b[2] - a[2] };
    const double v[3] = { c[0] - a[0], c[1] - a[1], c[2] - a[2] };
    const double n[3] = { u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2],
      u[0] * v[1] - u[1] * v[0] };
    const double length = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    EXPECT_GT(length, 1e-9) << "triangle " << t / 3 << " is degenerate";
    area += length / 2;
    for (std::size_t k = 0; k < 3 && normalsAgree; ++k)
    {
      const float* m = &part.Normals[3 * part.Triangles[t + k]];
      normalsAgree = std::fabs(m[0] - n[0] / length) < 1e-6 &&
        std::fabs(m[1] - n[1] / length) < 1e-6 && std::fabs(m[2] - n[2] / length) < 1e-6;
    }
  }
  return area;
}
} // namespace

// Flat polygons: a convex one fanned from its first corner, one with a straight corner fanned
// around its centre (no degenerate triangle), a concave one cut into ears; normals from the
// winding; vertices shared by coplanar polygons only.
TEST(GltfFile, FlatPolygonsWithoutDegenerateTriangles)
{
  const std::vector<std::array<double, 3>> points = {
    { 0, 0, 0 }, { 2, 0, 0 }, { 2, 2, 0 }, { 0, 2, 0 }, // 0-3: a square in z = 0
    { 1, 0, 0 },                                        // 4: the middle of its lower side
    { 2, 0, 1 }, { 0, 0, 1 },                           // 5, 6: a wall on y = 0
    { 3, 0, 0 }, { 3, 1, 0 }, { 1, 1, 0 }, { 1, 3, 0 }, { 0, 3, 0 } // an L with 0
  };
  bool agree = false;
  {
    msynth::GltfPart part; // the square, facing +z, and the wall below y = 0 facing -y
    msynth::AppendFlatPolygons(part, points, { { 0, 1, 2, 3 }, { 0, 1, 5, 6 } });
    EXPECT_EQ(part.Triangles.size(), 12u);
    EXPECT_EQ(part.Positions.size(), 3 * 8u); // points 0 and 1 once per plane
    EXPECT_NEAR(TriangleArea(part, agree), 6.0, 1e-6);
    EXPECT_TRUE(agree);
    EXPECT_EQ(part.Normals[2], 1.0f);   // the square's first corner faces +z
    EXPECT_EQ(part.Normals[13], -1.0f); // the wall's first corner (point 0 again) faces -y
  }
  {
    msynth::GltfPart part; // the square keeping point 4 on its side: 5 triangles round its centre
    msynth::AppendFlatPolygons(part, points, { { 0, 4, 1, 2, 3 } });
    EXPECT_EQ(part.Triangles.size(), 15u);
    EXPECT_EQ(part.Positions.size(), 3 * 6u);
    EXPECT_NEAR(TriangleArea(part, agree), 4.0, 1e-6);
    EXPECT_TRUE(agree);
  }
  {
    msynth::GltfPart part; // an L of 6 corners (area 5): 4 ears
    msynth::AppendFlatPolygons(part, points, { { 0, 7, 8, 9, 10, 11 } });
    EXPECT_EQ(part.Triangles.size(), 12u);
    EXPECT_NEAR(TriangleArea(part, agree), 5.0, 1e-6);
    EXPECT_TRUE(agree);
  }
  {
    msynth::GltfPart part; // no area, too few corners: nothing
    msynth::AppendFlatPolygons(part, points, { { 0, 4, 1 }, { 0, 1 } });
    EXPECT_TRUE(part.Triangles.empty());
    EXPECT_THROW(msynth::AppendFlatPolygons(part, points, { { 0, 1, 99 } }), msynth::Error);
  }
}

// Normals go into the file as a NORMAL accessor, turned to y up with the positions; a part's
// material is double-sided when asked.
TEST(GltfFile, NormalsTurnedAndDoubleSided)
{
  const std::string path = std::string(MSYNTH_TEST_TMP) + "/engine-normals.glb";
  msynth::GltfPart part;
  part.Name = "roof";
  part.Color = { 0.65, 0.2, 0.12, 1.0 };
  part.DoubleSided = true;
  msynth::AppendFlatPolygons(part, { { 0, 0, 0 }, { 1, 0, 0 }, { 0, 0, 1 } }, { { 0, 1, 2 } });
  ASSERT_EQ(part.Normals.size(), 9u);
  EXPECT_EQ(part.Normals[1], -1.0f); // facing -y in the model's frame
  msynth::WriteGlbFile(path, { part }, "test");
  const std::string bytes = Bytes(path);
  const std::uint32_t json = Word(bytes, 12);
  const std::string text = bytes.substr(20, json);
  EXPECT_NE(text.find("\"NORMAL\":1"), std::string::npos) << text;
  EXPECT_NE(text.find("\"doubleSided\":true"), std::string::npos) << text;
  // The binary chunk: 3 positions (36 bytes), then 3 normals: -y is glTF's +z.
  float n[3];
  std::memcpy(n, bytes.data() + 20 + json + 8 + 36, sizeof(n));
  EXPECT_EQ(n[0], 0.0f);
  EXPECT_EQ(n[1], 0.0f);
  EXPECT_EQ(n[2], 1.0f);
  msynth::GltfPart bad = part;
  bad.Normals.pop_back();
  EXPECT_THROW(msynth::WriteGlbFile(path, { bad }, "test"), msynth::Error);
}
