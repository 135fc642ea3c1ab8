// SPDX-License-Identifier: BSD-3-Clause
#include "Core/Error.h"
#include "VDB/VDBFile.h"

#include "Fixtures.h"

#include <gtest/gtest.h>

#include <sys/resource.h>

#include <csignal>
#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <functional>
#include <iterator>
#include <sstream>

namespace vdb = msynth::vdb;

namespace
{
std::string Tmp(const std::string& name)
{
  return std::string(MSYNTH_TEST_TMP) + "/" + name;
}

std::string ErrorOf(const std::function<void()>& f)
{
  try
  {
    f();
  }
  catch (const msynth::Error& e)
  {
    return e.what();
  }
  return "";
}

vdb::GridHeader Header(const std::string& name, vdb::ValueType type)
{
  vdb::GridHeader h;
  h.Name = name;
  h.Type = type;
  h.IndexMin = { { -2, 5, 0 } };
  h.Dims = { { 4, 3, 2 } };
  h.Origin = { { 1.5, -2.0, 0.25 } };
  h.Spacing = { { 0.5, 0.5, 2.0 } };
  return h;
}

/// One of our own label files, as bytes.
std::string LabelFileBytes()
{
  std::vector<std::int32_t> labels(16 * 16 * 4);
  for (std::size_t i = 0; i < labels.size(); ++i)
    labels[i] = static_cast<std::int32_t>((i * 7) % 5);
  vdb::GridHeader h = Header("Label", vdb::ValueType::Int32);
  h.Dims = { { 16, 16, 4 } };
  const std::string good = Tmp("layout-good.vdb");
  vdb::WriteFile(good, { vdb::DenseGridView{ h, labels.data() } }, { { "note", "kept" } });
  std::ifstream in(good, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

void PutU32(std::string& bytes, std::size_t at, std::uint32_t v)
{
  for (std::size_t k = 0; k < 4; ++k)
    bytes[at + k] = static_cast<char>((v >> (8 * k)) & 255);
}

/// The error of reading @p bytes as a file, and the seconds it took.
std::pair<std::string, double> ReadBytes(const std::string& bytes, const std::string& name)
{
  const std::string path = Tmp(name);
  std::ofstream(path, std::ios::binary | std::ios::trunc) << bytes;
  const auto start = std::chrono::steady_clock::now();
  const std::string e = ErrorOf([&] { vdb::ReadFile(path); });
  return { e, std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() };
}
} // namespace

TEST(VDBFile, RoundTripsLabelsFieldsAndMetadataExactly)
{
  std::vector<std::int32_t> labels(24, 0);
  std::vector<float> field(24), vec(72);
  for (int i = 0; i < 24; ++i)
  {
    labels[static_cast<std::size_t>(i)] = (i % 3 == 0) ? 0 : i * 7 - 40; // zeros are background
    field[static_cast<std::size_t>(i)] = 0.125f * static_cast<float>(i) - 1.0f;
    for (int c = 0; c < 3; ++c)
    {
      vec[static_cast<std::size_t>(3 * i + c)] = static_cast<float>(i * 10 + c);
    }
  }
  vdb::DenseGridView l{ Header("Label", vdb::ValueType::Int32), labels.data() };
  l.Header.Metadata["meaning"] = "labels";
  vdb::DenseGridView f{ Header("Entropy", vdb::ValueType::Float), field.data() };
  f.Header.GridClass = "fog volume";
  vdb::DenseGridView v{ Header("Velocity", vdb::ValueType::Vec3Float), vec.data() };
  const std::string path = Tmp("roundtrip.vdb");
  vdb::WriteFile(path, { l, f, v }, { { "seed", "42" }, { "example", "tiny.vti" } });

  vdb::MetadataMap fileMeta;
  auto summaries = vdb::ListGrids(path, &fileMeta);
  // OpenVDB does not keep the order grids were given in: compare by name.
  auto byName = [](const auto& a, const auto& b) { return a.Name < b.Name; };
  std::sort(summaries.begin(), summaries.end(), byName); // Entropy, Label, Velocity
  ASSERT_EQ(summaries.size(), 3u);
  EXPECT_EQ(fileMeta.at("seed"), "42");
  EXPECT_EQ(fileMeta.at("example"), "tiny.vti");
  EXPECT_EQ(fileMeta.at("generator").rfind("ModelSynth ", 0), 0u);
  EXPECT_EQ(summaries[1].TypeName, "int32");
  EXPECT_EQ(summaries[1].Metadata.at("meaning"), "labels");
  EXPECT_EQ(summaries[0].GridClass, "fog volume");
  EXPECT_EQ(summaries[2].TypeName, "vec3s");
  // Sparse: only non-background labels are active (16 of 24).
  EXPECT_EQ(summaries[1].ActiveVoxelCount, 16);

  auto contents = vdb::ReadFile(path);
  std::sort(contents.Grids.begin(), contents.Grids.end(),
    [](const auto& a, const auto& b) { return a.Header.Name < b.Header.Name; });
  ASSERT_EQ(contents.Grids.size(), 3u);
  for (const auto& g : contents.Grids)
  {
    EXPECT_EQ(g.Header.IndexMin, (std::array<std::int32_t, 3>{ { -2, 5, 0 } }));
    EXPECT_EQ(g.Header.Dims, (std::array<std::int64_t, 3>{ { 4, 3, 2 } }));
    EXPECT_EQ(g.Header.Origin, (std::array<double, 3>{ { 1.5, -2.0, 0.25 } }));
    EXPECT_EQ(g.Header.Spacing, (std::array<double, 3>{ { 0.5, 0.5, 2.0 } }));
  }
  EXPECT_EQ(contents.Grids[1].Ints, labels);
  EXPECT_EQ(contents.Grids[0].Floats, field);
  EXPECT_EQ(contents.Grids[0].Header.GridClass, "fog volume");
  EXPECT_EQ(contents.Grids[2].Floats, vec);

  vdb::ReadOptions only;
  only.GridNames = { "Entropy" };
  EXPECT_EQ(vdb::ReadFile(path, only).Grids.size(), 1u);
  only.GridNames = { "Nope" };
  EXPECT_NE(
    ErrorOf([&] { vdb::ReadFile(path, only); }).find("no grid named 'Nope'"), std::string::npos);
}

TEST(VDBFile, BackgroundAndEmptyBordersSurviveRoundTrip)
{
  // All-background grid with a non-zero background: the stored extent restores the box.
  std::vector<std::int32_t> labels(8, 3);
  vdb::DenseGridView l{ Header("Label", vdb::ValueType::Int32), labels.data() };
  l.Header.Dims = { { 2, 2, 2 } };
  l.Header.Background = 3;
  const std::string path = Tmp("background.vdb");
  vdb::WriteFile(path, { l }, {});
  const auto g = vdb::ReadFile(path).Grids.at(0);
  EXPECT_EQ(g.Ints, labels);
  EXPECT_EQ(g.Header.Background, 3.0);
  EXPECT_EQ(vdb::ListGrids(path).at(0).ActiveVoxelCount, 0);
}

TEST(VDBFile, RefusesExtentsOverTheVoxelLimit)
{
  std::vector<float> field(24, 1.0f);
  const std::string path = Tmp("limit.vdb");
  vdb::WriteFile(path, { { Header("f", vdb::ValueType::Float), field.data() } }, {});
  vdb::ReadOptions small;
  small.MaxVoxels = 23;
  const std::string error = ErrorOf([&] { vdb::ReadFile(path, small); });
  EXPECT_NE(error.find(path), std::string::npos) << error;
  EXPECT_NE(error.find("limit of 23 voxels"), std::string::npos) << error;
}

TEST(VDBFile, BadFilesGiveErrorsNamingTheFile)
{
  const std::string missing = Tmp("missing.vdb");
  std::remove(missing.c_str());
  EXPECT_NE(ErrorOf([&] { vdb::ReadFile(missing); }).find("'" + missing + "'"), std::string::npos);

  const std::string text = Tmp("not-a-vdb.vdb");
  std::ofstream(text) << "this is not an OpenVDB file\n";
  const std::string e1 = ErrorOf([&] { vdb::ReadFile(text); });
  EXPECT_NE(e1.find("'" + text + "'"), std::string::npos) << e1;
  EXPECT_NE(e1.find("not a readable OpenVDB file"), std::string::npos) << e1;

  // A valid file cut short at several places: every cut is an error, never a crash.
  std::vector<float> field(24);
  for (std::size_t i = 0; i < field.size(); ++i)
  {
    field[i] = static_cast<float>(i) + 1.0f;
  }
  const std::string good = Tmp("good.vdb");
  vdb::WriteFile(good, { { Header("f", vdb::ValueType::Float), field.data() } }, {});
  std::ifstream in(good, std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  for (std::size_t cut = 0; cut < bytes.size(); cut += (cut < 64 ? 1 : 37))
  {
    const std::string truncated = Tmp("truncated.vdb");
    std::ofstream(truncated, std::ios::binary) << bytes.substr(0, cut);
    const std::string e = ErrorOf([&] { vdb::ReadFile(truncated); });
    EXPECT_NE(e.find("'" + truncated + "'"), std::string::npos) << "cut at " << cut << ": " << e;
  }
}

TEST(VDBFile, FailedWritesLeaveNoPartialFile)
{
  std::vector<float> field(24, 2.0f);
  vdb::DenseGridView ok{ Header("f", vdb::ValueType::Float), field.data() };

  // Unwritable destination: error naming it, nothing created.
  const std::string nowhere = Tmp("no-such-folder/out.vdb");
  EXPECT_NE(ErrorOf([&] { vdb::WriteFile(nowhere, { ok }, {}); }).find(nowhere), std::string::npos);

  // An invalid grid after a good one: the existing file is left untouched.
  const std::string path = Tmp("kept.vdb");
  vdb::WriteFile(path, { ok }, { { "version", "old" } });
  vdb::DenseGridView bad = ok;
  bad.Header.Name = "bad";
  bad.Header.Spacing = { { 1.0, 0.0, 1.0 } };
  const std::string e = ErrorOf(
    [&] {
      vdb::WriteFile(path, { ok, bad }, { { "version", "new" } });
    });
  EXPECT_NE(e.find("spacing"), std::string::npos) << e;
  vdb::MetadataMap meta;
  vdb::ListGrids(path, &meta);
  EXPECT_EQ(meta.at("version"), "old");

  // Duplicate names are refused.
  EXPECT_NE(ErrorOf(
              [&] {
                vdb::WriteFile(path, { ok, ok }, {});
              })
              .find("two grids"),
    std::string::npos);
}

TEST(VDBFile, DamagedFilesNeverCrashTheReader)
{
  // Four bytes set to 0xff anywhere in one of our own files (a negative chunk size made
  // OpenVDB overflow its buffer): the file is read, or refused naming it; the library reads in
  // a child process, so even its crash is only an error here.
  const std::string bytes = LabelFileBytes();
  ASSERT_GT(bytes.size(), 100u);
  int refused = 0;
  for (std::size_t i = 0; i + 4 <= bytes.size(); i += 131) // a fork each: about 160 reads
  {
    std::string bad = bytes;
    for (std::size_t k = 0; k < 4; ++k)
      bad[i + k] = static_cast<char>(0xff);
    const std::string path = Tmp("damaged.vdb");
    std::ofstream(path, std::ios::binary | std::ios::trunc) << bad;
    const std::string e = ErrorOf([&] { vdb::ReadFile(path); });
    if (!e.empty())
    {
      ++refused;
      EXPECT_NE(e.find("'" + path + "'"), std::string::npos) << e;
    }
  }
  EXPECT_GT(refused, 0);
}

TEST(VDBFile, AFullDiskIsSeenAndLeavesNothing)
{
  // Files may not grow past 4 KB (RLIMIT_FSIZE; writes past it fail as on a full disk): a
  // 40 KB grid's write fails naming the file and the system's reason, and leaves nothing.
  std::vector<float> noise(20 * 20 * 20);
  for (std::size_t i = 0; i < noise.size(); ++i)
    noise[i] = static_cast<float>((i * 2654435761u) % 1000) + 0.5f;
  vdb::GridHeader h = Header("noise", vdb::ValueType::Float);
  h.Dims = { { 20, 20, 20 } };
  const vdb::DenseGridView view{ h, noise.data() };
  const std::string path = Tmp("full-disk.vdb");
  std::remove(path.c_str());
  std::string e;
  {
    const msynth_test::FileSizeLimit limit(4096);
    e = ErrorOf([&] { vdb::WriteFile(path, { view }, {}); });
  }
  EXPECT_NE(e.find("'" + path + "': could not be written: File too large"), std::string::npos) << e;
  std::ifstream left(path);
  EXPECT_FALSE(left.good());
}

namespace
{
/// Value of a dense grid at the voxel nearest to world point @p p.
float ValueAt(const vdb::DenseGrid& g, const std::array<double, 3>& p)
{
  std::array<std::int64_t, 3> i{};
  for (int a = 0; a < 3; ++a)
  {
    i[static_cast<std::size_t>(a)] =
      std::llround((p[static_cast<std::size_t>(a)] - g.Header.Origin[static_cast<std::size_t>(a)]) /
        g.Header.Spacing[static_cast<std::size_t>(a)]) -
      g.Header.IndexMin[static_cast<std::size_t>(a)];
    if (i[static_cast<std::size_t>(a)] < 0 ||
      i[static_cast<std::size_t>(a)] >= g.Header.Dims[static_cast<std::size_t>(a)])
    {
      return g.Header.Background; // outside the stored extent: the background
    }
  }
  return g
    .Floats[static_cast<std::size_t>(i[0] + g.Header.Dims[0] * (i[1] + g.Header.Dims[1] * i[2]))];
}
} // namespace

TEST(VDBFile, MeshLevelSetsHaveTheRightSignsAndClasses)
{
  // A 2 x 2 x 2 box (outward quads) and an L-shaped prism, as two surfaces.
  const std::vector<std::array<double, 3>> points{ { 0, 0, 0 }, { 2, 0, 0 }, { 2, 2, 0 },
    { 0, 2, 0 }, { 0, 0, 2 }, { 2, 0, 2 }, { 2, 2, 2 }, { 0, 2, 2 } };
  const std::vector<std::vector<std::int32_t>> box{ { 0, 3, 2, 1 }, { 4, 5, 6, 7 }, { 0, 1, 5, 4 },
    { 1, 2, 6, 5 }, { 2, 3, 7, 6 }, { 3, 0, 4, 7 } };
  vdb::MeshGridView surface;
  surface.Name = "surface";
  surface.Points = &points;
  surface.Polygons = &box;
  surface.VoxelSize = 0.1;
  surface.HalfWidth = 3;
  surface.FogName = "density";
  surface.Metadata["object_type"] = "all";
  const std::string path = Tmp("levelset.vdb");
  vdb::WriteFile(path, {}, { surface }, { { "example", "box" } });

  vdb::MetadataMap fileMeta;
  const auto grids = vdb::ListGrids(path, &fileMeta);
  ASSERT_EQ(grids.size(), 2u);
  EXPECT_EQ(grids[0].Name, "surface");
  EXPECT_EQ(grids[0].GridClass, "level set");
  EXPECT_EQ(grids[0].Metadata.at("object_type"), "all");
  EXPECT_EQ(grids[1].Name, "density");
  EXPECT_EQ(grids[1].GridClass, "fog volume");
  EXPECT_EQ(fileMeta.at("example"), "box");

  const auto contents = vdb::ReadFile(path);
  const vdb::DenseGrid& sdf = contents.Grids[0];
  const vdb::DenseGrid& fog = contents.Grids[1];
  // Signed distance: negative inside, positive outside, about the distance near the surface.
  EXPECT_LT(ValueAt(sdf, { 1, 1, 1 }), 0.0f); // deep inside (an inactive interior tile)
  EXPECT_NEAR(ValueAt(sdf, { 0.1, 1, 1 }), -0.1f, 0.02f);
  EXPECT_NEAR(ValueAt(sdf, { -0.2, 1, 1 }), 0.2f, 0.02f);
  EXPECT_NEAR(ValueAt(sdf, { 1, 1, 2.2 }), 0.2f, 0.02f);
  EXPECT_GT(ValueAt(sdf, { 3, 3, 3 }), 0.0f); // far outside: the positive background
  // Fog: 1 inside, 0 outside.
  EXPECT_NEAR(ValueAt(fog, { 1, 1, 1 }), 1.0f, 1e-6f);
  EXPECT_NEAR(ValueAt(fog, { -0.5, 1, 1 }), 0.0f, 1e-6f);

  // Bad meshes are refused before anything is written.
  std::remove(path.c_str());
  std::vector<std::vector<std::int32_t>> bad{ { 0, 1, 99 } };
  surface.Polygons = &bad;
  EXPECT_NE(ErrorOf([&] { vdb::WriteFile(path, {}, { surface }, {}); }).find("out of range"),
    std::string::npos);
  surface.Polygons = &box;
  surface.VoxelSize = 0;
  EXPECT_NE(ErrorOf([&] { vdb::WriteFile(path, {}, { surface }, {}); }).find("voxel size"),
    std::string::npos);
  EXPECT_FALSE(std::ifstream(path).good());
}

// Lengths and counts in a file are checked against the bytes left before OpenVDB allocates them:
// a grid name claiming 1.7 GB was allocated and filled (6 s, 1.6 GB) before "truncated", and a
// negative grid count ended in the C++ library's "vector::reserve".
TEST(VDBFile, LengthsAndCountsAreCheckedBeforeOpenVDBAllocates)
{
  const std::string bytes = LabelFileBytes();
  const std::size_t name = bytes.find(std::string("\x05\0\0\0Label", 9));
  ASSERT_NE(name, std::string::npos);
  std::string longName = bytes;
  PutU32(longName, name, 1700000000u);
  const auto [e1, s1] = ReadBytes(longName, "long-name.vdb");
  EXPECT_NE(e1.find("'" + Tmp("long-name.vdb") +
              "': is corrupt: the name of grid 1 claims "
              "1700000000 bytes"),
    std::string::npos)
    << e1;
  EXPECT_LT(s1, 2.0);

  std::string negative = bytes;
  PutU32(negative, name - 4, 0xfffffff0u); // the grid count before the first descriptor
  const auto [e2, s2] = ReadBytes(negative, "negative-count.vdb");
  EXPECT_NE(e2.find("is corrupt: it claims -16 grids"), std::string::npos) << e2;
  EXPECT_EQ(e2.find("vector"), std::string::npos) << e2;

  // The file's metadata entry "note": its value's size.
  const std::size_t note = bytes.find(std::string("\x04\0\0\0note", 8));
  ASSERT_NE(note, std::string::npos);
  const std::size_t size = note + 8 + 4 + std::string("string").size();
  std::string bigValue = bytes;
  PutU32(bigValue, size, 0x7fffffffu);
  const auto [e3, s3] = ReadBytes(bigValue, "big-value.vdb");
  EXPECT_NE(e3.find("metadata 'note' of the file claims 2147483647 bytes"), std::string::npos)
    << e3;
}

// Whatever a damaged file does to the reading child (OpenVDB's warnings, glibc's "malloc():
// corrupted top size" after a flipped bit in a Blosc chunk), nothing of it reaches our stderr:
// the parent's one error says what failed.
TEST(VDBFile, NothingTheReadingProcessPrintsReachesTheUser)
{
  const std::string bytes = LabelFileBytes();
  const std::string log = Tmp("child-stderr.txt");
  std::fflush(stderr);
  const int saved = ::dup(2);
  const int sink = ::open(log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  ASSERT_GE(sink, 0);
  ::dup2(sink, 2);
  for (std::size_t i = 100; i < bytes.size(); i += 61) // one bit in each stretch of the data
  {
    std::string bad = bytes;
    bad[i] = static_cast<char>(bad[i] ^ (1 << (i % 8)));
    ReadBytes(bad, "flipped.vdb");
  }
  // The tree's buffer count after the transform (its type name and 18 doubles): 2 made OpenVDB
  // print "WARNING: multi-buffer trees are no longer supported".
  const std::size_t map = bytes.find("ScaleTranslateMap");
  ASSERT_NE(map, std::string::npos);
  const std::size_t buffers = map + 17 + 18 * 8;
  ASSERT_EQ(bytes.substr(buffers, 4), std::string("\x01\0\0\0", 4));
  std::string twoBuffers = bytes;
  PutU32(twoBuffers, buffers, 2);
  ReadBytes(twoBuffers, "two-buffers.vdb");
  std::fflush(stderr);
  ::dup2(saved, 2);
  ::close(saved);
  ::close(sink);
  std::ifstream in(log);
  const std::string printed((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_EQ(printed, "");
}
