// SPDX-License-Identifier: BSD-3-Clause
// PLY and STL examples read by our own checked readers: every variant of the formats, and
// malformed files (short, huge counts, every bit flip) as errors naming the file, never crashes.
#include "Core/Error.h"
#include "Formats/MeshFormats.h"

#include <gtest/gtest.h>

#include <cstring>
#include <fstream>
#include <functional>
#include <string>

using namespace msynth;

namespace
{
std::string Temp(const std::string& name)
{
  return std::string(MSYNTH_TEST_TMP) + "/" + name;
}

std::string Put(const std::string& name, const std::string& bytes)
{
  const std::string path = Temp(name);
  std::ofstream(path, std::ios::binary | std::ios::trunc) << bytes;
  return path;
}

// A unit cube: 8 corners, 6 outward quads.
const double Corners[8][3] = { { 0, 0, 0 }, { 1, 0, 0 }, { 1, 1, 0 }, { 0, 1, 0 }, { 0, 0, 1 },
  { 1, 0, 1 }, { 1, 1, 1 }, { 0, 1, 1 } };
const int Quads[6][4] = { { 0, 3, 2, 1 }, { 4, 5, 6, 7 }, { 0, 1, 5, 4 }, { 1, 2, 6, 5 },
  { 2, 3, 7, 6 }, { 3, 0, 4, 7 } };

std::string Binary(const void* data, std::size_t n, bool bigEndian)
{
  std::string s(static_cast<const char*>(data), n);
  if (bigEndian)
    std::reverse(s.begin(), s.end());
  return s;
}

/// The cube as PLY: an extra element before the vertices, an extra vertex property, quads
/// counted by uchar with int indices (the usual layout) or by int with uint indices.
std::string Ply(int format, bool intCounts)
{
  static const char* const names[] = { "ascii", "binary_little_endian", "binary_big_endian" };
  std::string header = std::string("ply\nformat ") + names[format] +
    " 1.0\ncomment made by a test\nelement camera 1\nproperty float focal\n"
    "element vertex 8\nproperty double x\nproperty float y\nproperty float z\nproperty uchar red\n"
    "element face 6\nproperty list " +
    (intCounts ? "int uint" : "uchar int") + " vertex_indices\nend_header\n";
  std::string body;
  const bool big = format == 2;
  if (format == 0)
  {
    body += "35\n";
    for (const auto& c : Corners)
      body +=
        std::to_string(c[0]) + " " + std::to_string(c[1]) + " " + std::to_string(c[2]) + " 200\n";
    for (const auto& q : Quads)
      body += "4 " + std::to_string(q[0]) + " " + std::to_string(q[1]) + " " +
        std::to_string(q[2]) + " " + std::to_string(q[3]) + "\n";
    return header + body;
  }
  const float focal = 35;
  body += Binary(&focal, 4, big);
  for (const auto& c : Corners)
  {
    const double x = c[0];
    const float y = static_cast<float>(c[1]), z = static_cast<float>(c[2]);
    body += Binary(&x, 8, big) + Binary(&y, 4, big) + Binary(&z, 4, big) + std::string(1, '\xc8');
  }
  for (const auto& q : Quads)
  {
    if (intCounts)
    {
      const std::int32_t four = 4;
      body += Binary(&four, 4, big);
    }
    else
      body += std::string(1, '\x04');
    for (int k : q)
    {
      const std::int32_t i = k;
      body += Binary(&i, 4, big);
    }
  }
  return header + body;
}

/// The cube as STL triangles, ascii or binary (optionally with a header starting "solid").
std::string Stl(bool ascii, bool solidHeader = false)
{
  std::string text = "solid cube\n", bin(80, ' ');
  if (solidHeader)
    bin.replace(0, 5, "solid");
  std::uint32_t n = 12;
  bin += std::string(reinterpret_cast<const char*>(&n), 4);
  for (const auto& q : Quads)
    for (const auto& tri :
      { std::array<int, 3>{ { q[0], q[1], q[2] } }, std::array<int, 3>{ { q[0], q[2], q[3] } } })
    {
      text += " facet normal 0 0 0\n  outer loop\n";
      bin += std::string(12, '\0');
      for (int k : tri)
      {
        text += "   vertex " + std::to_string(Corners[k][0]) + " " + std::to_string(Corners[k][1]) +
          " " + std::to_string(Corners[k][2]) + "\n";
        for (double c : Corners[k])
        {
          const float f = static_cast<float>(c);
          bin += std::string(reinterpret_cast<const char*>(&f), 4);
        }
      }
      text += "  endloop\n endfacet\n";
      bin += std::string(2, '\0');
    }
  return ascii ? text + "endsolid cube\n" : bin;
}

void ExpectCube(const PolyhedralExample& e, std::size_t faces)
{
  EXPECT_EQ(e.Points.size(), 8u); // STL's repeated corners merged
  EXPECT_EQ(e.Faces.size(), faces);
  EXPECT_EQ(e.NumberOfObjects(), 1);
  for (const auto& f : e.Faces)
    for (int i : f)
      ASSERT_TRUE(i >= 0 && i < 8);
}

/// Reads @p bytes as @p name; returns the error text ("" when it was read).
std::string ErrorOf(const std::string& name, const std::string& bytes,
  const std::function<PolyhedralExample(const std::string&)>& read)
{
  const std::string path = Put(name, bytes);
  try
  {
    read(path);
  }
  catch (const Error& e)
  {
    EXPECT_NE(std::string(e.what()).find("'" + path + "'"), std::string::npos) << e.what();
    return e.what();
  }
  return "";
}
} // namespace

TEST(MeshFormats, PlyInEveryEncoding)
{
  for (int format = 0; format < 3; ++format)
    for (bool intCounts : { false, true })
    {
      const PolyhedralExample e = ReadPLYExample(Put("cube.ply", Ply(format, intCounts)));
      ExpectCube(e, 6);
      for (std::size_t f = 0; f < 6; ++f)
        for (std::size_t k = 0; k < 4; ++k)
          EXPECT_EQ(e.Points[static_cast<std::size_t>(e.Faces[f][k])],
            (Point3{
              { Corners[Quads[f][k]][0], Corners[Quads[f][k]][1], Corners[Quads[f][k]][2] } }))
            << "format " << format;
    }
}

TEST(MeshFormats, StlAsciiAndBinary)
{
  ExpectCube(ReadSTLExample(Put("cube.stl", Stl(true))), 12);
  ExpectCube(ReadSTLExample(Put("cube.stl", Stl(false))), 12);
  ExpectCube(ReadSTLExample(Put("cube.stl", Stl(false, true))), 12); // binary saying "solid"
}

TEST(MeshFormats, MalformedFilesAreErrors)
{
  const auto ply = [](const std::string& p) { return ReadPLYExample(p); };
  const auto stl = [](const std::string& p) { return ReadSTLExample(p); };
  EXPECT_NE(
    ErrorOf("a.ply",
      "ply\nformat ascii 1.0\nelement vertex 1000000000000\nproperty float x\nend_header\n0\n", ply)
      .find("declares 1000000000000 vertex elements"),
    std::string::npos);
  EXPECT_NE(ErrorOf("b.ply",
              "ply\nformat binary_little_endian 1.0\nelement vertex 1\nproperty float x\n", ply)
              .find("no 'end_header'"),
    std::string::npos);
  EXPECT_NE(ErrorOf("c.ply",
              "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
              "property float z\nelement face 1\nproperty list uchar int vertex_indices\n"
              "end_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 7\n",
              ply)
              .find("vertex index 7.000000 is not one of 0..2"),
    std::string::npos);
  EXPECT_NE(
    ErrorOf("d.ply", "ply\nformat ascii 1.0\nelement vertex 1\nproperty quux x\nend_header\n", ply)
      .find("unknown type 'quux'"),
    std::string::npos);
  EXPECT_NE(
    ErrorOf("e.ply",
      "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nend_header\n\x01\x1b", ply)
      .find("'?"
            "?' is not a number"),
    std::string::npos);
  // The 84-byte STL declaring about 1.9e9 triangles, and short files.
  std::string header(80, ' ');
  const std::uint32_t many = 1900000000;
  EXPECT_NE(ErrorOf("f.stl", header + std::string(reinterpret_cast<const char*>(&many), 4), stl)
              .find("declares 1900000000 triangles but holds 0"),
    std::string::npos);
  EXPECT_NE(ErrorOf("g.stl", std::string(57, 'x'), stl).find("less than a binary header"),
    std::string::npos);
  EXPECT_NE(
    ErrorOf("h.stl", "solid x\n facet normal 0 0 1\n", stl).find("no polygons"), std::string::npos);
  EXPECT_NE(ErrorOf("i.ply", std::string(57, '\0'), ply).find("does not start with 'ply'"),
    std::string::npos);
}

TEST(MeshFormats, EveryBitFlipIsReadOrAnError)
{
  // No crash and no unbounded allocation whatever one bit a valid file has wrong (the sanitizer
  // build runs this too).
  for (const auto& [name, bytes] : { std::make_pair(std::string("flip.ply"), Ply(1, false)),
         std::make_pair(std::string("flip-ascii.ply"), Ply(0, false)),
         std::make_pair(std::string("flip.stl"), Stl(false)),
         std::make_pair(std::string("flip-ascii.stl"), Stl(true)) })
    for (std::size_t i = 0; i < bytes.size(); ++i)
    {
      std::string bad = bytes;
      bad[i] = static_cast<char>(bad[i] ^ (1 << (i % 8)));
      const bool isPly = name.find(".ply") != std::string::npos;
      ErrorOf(name, bad,
        isPly ? std::function<PolyhedralExample(const std::string&)>(ReadPLYExample)
              : std::function<PolyhedralExample(const std::string&)>(ReadSTLExample));
    }
}
