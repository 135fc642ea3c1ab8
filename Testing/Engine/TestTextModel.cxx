// SPDX-License-Identifier: BSD-3-Clause
#include "msynth/Error.h"
#include "msynth/TextModel.h"

#include <gtest/gtest.h>

#include <sstream>

using namespace msynth;

namespace
{
const char* const Example = "A small house\nmade by hand\nfor tests\n2 3 2\n"
                            "1 1 1\n1 1 1\n\n"
                            "0 2 0\n0 3 0\n"
                            "<Objects>\n2\n$wall_a\n$wall_b\n#\n3\n$roof\n#\n";

std::string ErrorOf(const std::string& text, std::int64_t maxSites = 1000)
{
  std::istringstream in(text);
  try
  {
    ReadTextModel(in, "x.txt", maxSites);
  }
  catch (const Error& e)
  {
    return e.what();
  }
  return "";
}
} // namespace

TEST(TextModel, ReadsSlicesForZForXForY)
{
  std::istringstream in(Example);
  const TextModel m = ReadTextModel(in, "x.txt", 1000);
  EXPECT_EQ(m.Header[0], "A small house");
  EXPECT_EQ(m.Grid.Dimensions(), (std::array<std::int64_t, 3>{ { 2, 3, 2 } }));
  // Slice z = 1: row x = 0 is "0 2 0", row x = 1 is "0 3 0" (values along y).
  EXPECT_EQ(m.Grid.At(0, 1, 1), 2);
  EXPECT_EQ(m.Grid.At(1, 1, 1), 3);
  EXPECT_EQ(m.Grid.At(1, 2, 0), 1);
  EXPECT_EQ(m.Pieces.at(2), (std::vector<std::string>{ "wall_a", "wall_b" }));
  EXPECT_EQ(m.Pieces.at(3), (std::vector<std::string>{ "roof" }));
}

TEST(TextModel, RoundTrips)
{
  std::istringstream in(Example);
  const TextModel m = ReadTextModel(in, "x.txt", 1000);
  std::ostringstream out;
  WriteTextModel(out, m);
  std::istringstream again(out.str());
  const TextModel n = ReadTextModel(again, "y.txt", 1000);
  EXPECT_EQ(n.Grid, m.Grid);
  EXPECT_EQ(n.Pieces, m.Pieces);
  EXPECT_EQ(n.Header, m.Header);
}

TEST(TextModel, MalformedFilesNameTheLineAndProblem)
{
  EXPECT_NE(ErrorOf("a\nb\n").find("line 2: the file ends inside its three header lines"),
    std::string::npos);
  EXPECT_NE(ErrorOf("a\nb\nc\n2 3\n").find("line 4: expected the dimensions"), std::string::npos);
  EXPECT_NE(ErrorOf("a\nb\nc\n2 x 3\n").find("'x' is not an integer"), std::string::npos);
  EXPECT_NE(ErrorOf("a\nb\nc\n2 0 3\n").find("at least 1"), std::string::npos);
  EXPECT_NE(ErrorOf("a\nb\nc\n100000 100000 100000\n").find("exceed the limit of 1000 sites"),
    std::string::npos);
  EXPECT_NE(ErrorOf("a\nb\nc\n2 2 1\n1 1\n1\n")
              .find("line 6: row 1 of slice 0 has 1 values, expected Y = 2"),
    std::string::npos);
  EXPECT_NE(
    ErrorOf("a\nb\nc\n2 2 2\n1 1\n1 1\n").find("the file ends in slice 1"), std::string::npos);
  EXPECT_NE(ErrorOf("a\nb\nc\n1 1 1\n5\nextra\n").find("unexpected content after the last slice"),
    std::string::npos);
  EXPECT_NE(ErrorOf("a\nb\nc\n1 1 1\n5\n<Objects>\n5\nwall\n#\n").find("starting with '$'"),
    std::string::npos);
  EXPECT_NE(
    ErrorOf("a\nb\nc\n1 1 1\n5\n<Objects>\n5\n$wall\n").find("no closing '#'"), std::string::npos);
  EXPECT_NE(
    ErrorOf("a\nb\nc\n1 1 1\n99999999999\n").find("out of the 32-bit range"), std::string::npos);
  EXPECT_NE(
    ErrorOf("a\nb\nc\n2 1 1\n1\n\n1\n").find("row 1 of slice 0 has 0 values"), std::string::npos);
  EXPECT_THROW(ReadTextModelFile("/no/such/file.txt", 10), Error);
}
