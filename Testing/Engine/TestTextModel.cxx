// SPDX-License-Identifier: BSD-3-Clause
#include "Core/Error.h"
#include "Formats/TextModel.h"

#include <gtest/gtest.h>

#include <sstream>

using namespace msynth;

namespace
{
// The shape of the original program's example files (samples/castle.txt and the others): a
// dimensions line with trailing blanks, slices separated by blank lines, and an <Objects>
// trailer with a scene line, free-text entry lines, names containing '$', an entry without
// pieces, blank lines between entries and no newline after the last '#'.
const char* const Castle = "Example model created by hand.  Do not insert or delete lines.\n"
                           "\n"
                           "x, y, and z extents\n"
                           "2 3 2             \n"
                           "\n"
                           "1 1 1\n"
                           "1 1 1\n"
                           "\n"
                           "0 2 0\n"
                           "0 3 4\n"
                           "\n"
                           "<Objects>\n"
                           "3D Studio Scenes\\castle.max\n"
                           "somethin'\n"
                           "$castle9\n"
                           "$snow9\n"
                           "#\n"
                           "1\n"
                           "$backa$\n"
                           "$wall\n"
                           "#\n"
                           "\n"
                           "tree20\n"
                           "#\n"
                           "44 $ignored on the entry line\n"
                           "$roof\n"
                           "#";

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

TextModel Read(const std::string& text)
{
  std::istringstream in(text);
  return ReadTextModel(in, "x.txt", 1000);
}
} // namespace

TEST(TextModel, ReadsSlicesForZForXForY)
{
  const TextModel m = Read(Castle);
  EXPECT_EQ(m.Header[0], "Example model created by hand.  Do not insert or delete lines.");
  EXPECT_EQ(m.Header[2], "x, y, and z extents");
  EXPECT_EQ(m.Grid.Dimensions(), (std::array<std::int64_t, 3>{ { 2, 3, 2 } }));
  // Slice z = 1: row x = 0 is "0 2 0", row x = 1 is "0 3 4" (values along y).
  EXPECT_EQ(m.Grid.At(0, 1, 1), 2);
  EXPECT_EQ(m.Grid.At(1, 1, 1), 3);
  EXPECT_EQ(m.Grid.At(1, 2, 1), 4);
  EXPECT_EQ(m.Grid.At(1, 2, 0), 1);
}

TEST(TextModel, ReadsTheObjectsTrailerAsEntriesOfLabelsOneTwoThree)
{
  const TextModel m = Read(Castle);
  ASSERT_TRUE(m.HasObjects);
  EXPECT_TRUE(m.ObjectsProblem.empty()) << m.ObjectsProblem;
  EXPECT_EQ(m.Scene, "3D Studio Scenes\\castle.max");
  ASSERT_EQ(m.Objects.size(), 4u);
  EXPECT_EQ(m.Objects[0].Text, "somethin'");
  EXPECT_EQ(m.Objects[1].Text, "1");
  EXPECT_EQ(m.Objects[2].Text, "tree20");
  EXPECT_TRUE(m.Objects[2].Pieces.empty());
  EXPECT_EQ(m.Objects[3].Text, "44 $ignored on the entry line");
  EXPECT_EQ(m.Pieces.at(1), (std::vector<std::string>{ "castle9", "snow9" }));
  EXPECT_EQ(m.Pieces.at(2), (std::vector<std::string>{ "backa$", "wall" }));
  EXPECT_EQ(m.Pieces.count(3), 0u); // an entry without pieces
  EXPECT_EQ(m.Pieces.at(4), (std::vector<std::string>{ "roof" }));
  EXPECT_EQ(m.Pieces.count(0), 0u); // label 0 (empty) has no entry
}

TEST(TextModel, ValuesMayBeLaidOutFreelyAsTheOriginalProgramReadsThem)
{
  // The original reads a stream of numbers: one line, CRLF line ends and tabs all work.
  const TextModel flat = Read("a\r\nb\r\nc\r\n2 3 2\r\n1 1 1 1 1 1\t0 2 0 0 3 4\r\n");
  EXPECT_EQ(flat.Grid, Read(Castle).Grid);
  EXPECT_EQ(flat.Header[1], "b");
  EXPECT_TRUE(flat.Trailer.empty());
  EXPECT_FALSE(flat.HasObjects);
}

TEST(TextModel, OtherTrailersAreKeptVerbatim)
{
  const TextModel m = Read("a\nb\nc\n1 1 1\n5\n\nnotes: made for a test\n  second line\n");
  EXPECT_EQ(m.Trailer, "notes: made for a test\n  second line\n");
  EXPECT_FALSE(m.HasObjects);
  EXPECT_TRUE(m.Pieces.empty());
  EXPECT_TRUE(m.ObjectsProblem.empty());
}

TEST(TextModel, AnObjectsSectionOfAnotherShapeIsKeptAndExplained)
{
  const TextModel m = Read("a\nb\nc\n1 1 1\n4\n<Objects>\nscene\n4\nwall\n#\n");
  EXPECT_TRUE(m.HasObjects);
  EXPECT_TRUE(m.Pieces.empty());
  EXPECT_EQ(m.Trailer, "<Objects>\nscene\n4\nwall\n#\n");
  EXPECT_NE(m.ObjectsProblem.find("line 9: expected a piece name starting with '$' or '#' to end "
                                  "the entry of label 1"),
    std::string::npos)
    << m.ObjectsProblem;
}

TEST(TextModel, WritesAsTheOriginalProgramAndReadsBackIdentically)
{
  TextModel m = Read(Castle);
  m.Header = GeneratedTextModelHeader();
  std::ostringstream out;
  WriteTextModel(out, m);
  const std::string text = out.str();
  // The original's layout: "%2d " per value, a blank line after the dimensions and each slice,
  // then the trailer unchanged (its loaders find the grid after "x, y, and z extents").
  EXPECT_NE(text.find("x, y, and z extents\n2 3 2\n\n 1  1  1 \n 1  1  1 \n\n 0  2  0 \n"
                      " 0  3  4 \n\n<Objects>\n3D Studio Scenes\\castle.max\n"),
    std::string::npos)
    << text;
  EXPECT_EQ(text.back(), '#'); // the trailer's missing last newline is not added
  EXPECT_EQ(text.substr(text.find("<Objects>")), Read(Castle).Trailer);
  const TextModel n = Read(text);
  EXPECT_EQ(n.Grid, m.Grid);
  EXPECT_EQ(n.Header, m.Header);
  EXPECT_EQ(n.Trailer, m.Trailer);
  EXPECT_EQ(n.Pieces, m.Pieces);
  std::ostringstream again;
  WriteTextModel(again, n);
  EXPECT_EQ(again.str(), text);
}

TEST(TextModel, MalformedFilesNameTheLineAndProblem)
{
  EXPECT_NE(ErrorOf("a\nb\n").find("line 3: the file ends inside its three header lines"),
    std::string::npos);
  EXPECT_NE(ErrorOf("a\nb\nc\n2 3\n").find("the file ends before the dimensions 'X Y Z' (found 2"),
    std::string::npos);
  EXPECT_NE(ErrorOf("a\nb\nc\n2 x 3\n").find("line 4: 'x' is not an integer"), std::string::npos);
  EXPECT_NE(ErrorOf("a\nb\nc\n2 0 3\n").find("at least 1"), std::string::npos);
  EXPECT_NE(ErrorOf("a\nb\nc\n100000 100000 100000\n").find("exceed the limit of 1000 sites"),
    std::string::npos);
  EXPECT_NE(ErrorOf("a\nb\nc\n2 2 2\n1 1\n1 1\n")
              .find("the file ends in slice 1 after 0 of its 4 values (expected 2 slices of 2 "
                    "rows of 2 values)"),
    std::string::npos);
  // A short row shifts the values: the trailer's first word is then read as a value.
  EXPECT_NE(ErrorOf("a\nb\nc\n2 2 1\n1 1\n1\n<Objects>\n")
              .find("line 7: '<Objects>' is not an "
                    "integer"),
    std::string::npos);
  EXPECT_NE(
    ErrorOf("a\nb\nc\n1 1 1\n99999999999\n").find("out of the 32-bit range"), std::string::npos);
  EXPECT_NE(ErrorOf("a\nb\nc\n1 1 1\n\x01\x1b[2J\n")
              .find("'?"
                    "?[2J' is not an integer"),
    std::string::npos);
  EXPECT_THROW(ReadTextModelFile("/no/such/file.txt", 10), Error);
}
