// SPDX-License-Identifier: BSD-3-Clause
#include "Core/Error.h"
#include "Formats/SampleList.h"

#include <gtest/gtest.h>

#include <fstream>
#include <string>
#include <sys/stat.h>

using namespace msynth;

namespace
{
std::string Folder(const std::string& name)
{
  const std::string dir = std::string(MSYNTH_TEST_TMP) + "/" + name;
  ::mkdir(dir.c_str(), 0777);
  return dir;
}

void Write(const std::string& path, const std::string& text)
{
  std::ofstream(path) << text;
}
} // namespace

TEST(SampleList, EntriesAttributesAndLayouts)
{
  const std::string dir = Folder("sample-list");
  for (const char* sub : { "/samples", "/tilesets", "/samples/Old" })
    ::mkdir((dir + sub).c_str(), 0777);
  Write(dir + "/samples/Flowers.png", "x");
  Write(dir + "/tilesets/Knots.xml", "x");
  Write(dir + "/samples/Old/data.xml", "x");
  Write(dir + "/samples/castle.txt", "x");
  Write(dir + "/samples.xml", R"(<samples>
  <overlapping name="Flowers" N="3" symmetry="2" ground="-4" periodic="True"/>
  <overlapping name="Chess" periodicInput="False" width="47" height="40" screenshots="1"/>
  <simpletiled name="Knots" subset="Dense" width="24" height="20" periodic="True"/>
  <simpletiled name="Old" blockWidth="8" blockLength="6"/>
  <tiledmodel name="castle.txt" width="40" length="30" height="10" blockWidth="10"/>
  <tiledmodel name="flat.txt" width="12" height="7" limit="5" textOutput="True"/>
  <something name="ignored"/>
</samples>)");
  const auto e = ReadSampleList(dir + "/samples.xml");
  ASSERT_EQ(e.size(), 6u);
  EXPECT_EQ(e[0].Kind, SampleEntry::Overlapping);
  EXPECT_EQ(e[0].File, dir + "/samples/Flowers.png");
  EXPECT_EQ(e[0].N, 3);
  EXPECT_EQ(e[0].Symmetry, 2);
  EXPECT_TRUE(e[0].Ground); // the older lists' pattern index
  EXPECT_TRUE(e[0].Periodic);
  EXPECT_TRUE(e[0].PeriodicInput);
  EXPECT_EQ(e[0].Size, (std::array<std::int64_t, 3>{ { 48, 48, 1 } })); // the default
  EXPECT_EQ(e[0].Screenshots, 2);
  EXPECT_EQ(e[1].N, 2);
  EXPECT_FALSE(e[1].PeriodicInput);
  EXPECT_FALSE(e[1].Ground);
  EXPECT_EQ(e[1].Size, (std::array<std::int64_t, 3>{ { 47, 40, 1 } }));
  EXPECT_EQ(e[1].Screenshots, 1);
  EXPECT_EQ(e[1].File, dir + "/samples/Chess.png"); // missing: the first candidate
  EXPECT_EQ(e[2].Kind, SampleEntry::SimpleTiled);
  EXPECT_EQ(e[2].File, dir + "/tilesets/Knots.xml"); // WaveFunctionCollapse's current layout
  EXPECT_EQ(e[2].Subset, "Dense");
  EXPECT_EQ(e[3].File, dir + "/samples/Old/data.xml");                  // the older layout
  EXPECT_EQ(e[3].Size, (std::array<std::int64_t, 3>{ { 24, 24, 1 } })); // the default
  EXPECT_EQ(e[3].Block, (std::array<std::int64_t, 3>{ { 8, 6, 0 } }));
  EXPECT_EQ(e[4].Kind, SampleEntry::TiledModel);
  EXPECT_EQ(e[4].File, dir + "/samples/castle.txt");
  EXPECT_EQ(e[4].Size, (std::array<std::int64_t, 3>{ { 40, 30, 10 } }));
  EXPECT_EQ(e[4].Screenshots, 1);
  EXPECT_EQ(e[5].Size, (std::array<std::int64_t, 3>{ { 12, 7, 1 } })); // no length: 2D
  EXPECT_EQ(e[5].Line, 7);
  // Ground "True" (the current lists) and "False".
  Write(dir + "/g.xml", R"(<samples><overlapping name="a" ground="True"/>
    <overlapping name="b" ground="False"/></samples>)");
  const auto g = ReadSampleList(dir + "/g.xml");
  EXPECT_TRUE(g[0].Ground);
  EXPECT_FALSE(g[1].Ground);
  // WaveFunctionCollapse's size: both sides, unless width or height is given.
  Write(dir + "/size.xml", R"(<samples><overlapping name="a" size="32"/>
    <overlapping name="b" size="32" height="20"/><simpletiled name="c" size="12"/>
    <simpletiled name="d" size="12" width="30" height="8"/></samples>)");
  const auto sized = ReadSampleList(dir + "/size.xml");
  ASSERT_EQ(sized.size(), 4u);
  EXPECT_EQ(sized[0].Size, (std::array<std::int64_t, 3>{ { 32, 32, 1 } }));
  EXPECT_EQ(sized[1].Size, (std::array<std::int64_t, 3>{ { 32, 20, 1 } }));
  EXPECT_EQ(sized[2].Size, (std::array<std::int64_t, 3>{ { 12, 12, 1 } }));
  EXPECT_EQ(sized[3].Size, (std::array<std::int64_t, 3>{ { 30, 8, 1 } }));
}

TEST(SampleList, MalformedListsAreErrorsNamingTheLine)
{
  const std::string dir = Folder("sample-list-bad");
  const std::pair<const char*, const char*> cases[] = {
    { "<set/>", "root is <samples>" },
    { "<samples>\n<overlapping N=\"3\"/></samples>", "line 2: <overlapping> has no name" },
    { "<samples>\n\n<overlapping name=\"a\" N=\"9\"/></samples>", "line 3: N=\"9\" is not" },
    { "<samples><overlapping name=\"a\" periodic=\"yes\"/></samples>", "True or False" },
    { "<samples><overlapping name=\"a\" width=\"-3\"/></samples>", "width=\"-3\"" },
    { "<samples><simpletiled name=\"a\" size=\"0\"/></samples>", "size=\"0\" is not" },
    { "<samples><tiledmodel name=\"a.txt\"/></samples>", "needs a width" },
    { "<samples><overlapping name=\"a\"", "line 1" },
  };
  for (const auto& c : cases)
  {
    Write(dir + "/bad.xml", c.first);
    try
    {
      ReadSampleList(dir + "/bad.xml");
      ADD_FAILURE() << "no error for " << c.first;
    }
    catch (const Error& e)
    {
      EXPECT_NE(std::string(e.what()).find(c.second), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find("bad.xml"), std::string::npos) << e.what();
    }
  }
  EXPECT_THROW(ReadSampleList(dir + "/missing.xml"), Error);
}
