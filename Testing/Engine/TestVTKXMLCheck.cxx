// SPDX-License-Identifier: BSD-3-Clause
#include "Core/Error.h"
#include "Formats/VTKXMLCheck.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>
#include <iterator>
#include <string>

using namespace msynth;

namespace
{
/// A one-piece image file whose piece has extent @p extent and one ascii Int32 array of
/// @p values.
std::string WriteImage(
  const std::string& name, const std::string& extent, const std::string& values)
{
  const std::string path = ::testing::TempDir() + name;
  std::ofstream(path)
    << "<?xml version=\"1.0\"?>\n"
       "<VTKFile type=\"ImageData\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
       "  <ImageData WholeExtent=\""
    << extent
    << "\" Origin=\"0 0 0\" Spacing=\"1 1 1\">\n"
       "    <Piece Extent=\""
    << extent
    << "\">\n"
       "      <PointData>\n"
       "        <DataArray type=\"Int32\" Name=\"Label\" format=\"ascii\">"
    << values
    << "</DataArray>\n"
       "      </PointData>\n"
       "    </Piece>\n"
       "  </ImageData>\n"
       "</VTKFile>\n";
  return path;
}
} // namespace

TEST(VTKXMLCheck, AWellFormedImagePasses)
{
  EXPECT_NO_THROW(CheckVTKXMLFile(WriteImage("ok.vti", "0 1 0 1 0 0", "1 2 3 4")));
}

TEST(VTKXMLCheck, ExtentsBeyondAnyCountAreLeftToTheReaderWithoutOverflow)
{
  // Extents that saturate 64-bit integers (sscanf gives LLONG_MAX / LLONG_MIN): the piece's
  // size cannot be counted, so its arrays are not size-checked; the arithmetic must not
  // overflow on the way (a fuzzing find; the sanitizer build traps signed overflow).
  for (const char* extent : { "0 99999999999999999999999 0 1 0 0",
         "-99999999999999999999999 0 0 1 0 0", "-9223372036854775808 9223372036854775807 0 0 0 0" })
  {
    try
    {
      CheckVTKXMLFile(WriteImage("huge.vti", extent, "1"));
    }
    catch (const Error& e)
    {
      EXPECT_NE(std::string(e.what()).find("huge.vti"), std::string::npos) << e.what();
    }
  }
}

TEST(VTKXMLCheck, AWholeExtentItsPiecesDoNotHoldIsRefused)
{
  // VTK's reader allocates the WholeExtent before it reads the pieces: 10^10 points for a
  // piece of four was a SIGABRT in every command that read a guide.
  std::string path = WriteImage("whole.vti", "0 1 0 1 0 0", "1 2 3 4");
  {
    std::ifstream in(path);
    std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    text.replace(
      text.find("WholeExtent=\"0 1 0 1 0 0\""), 25, "WholeExtent=\"0 100000 0 100000 0 0\"");
    std::ofstream(path) << text;
  }
  try
  {
    CheckVTKXMLFile(path);
    FAIL() << "a WholeExtent larger than its pieces must be refused";
  }
  catch (const Error& e)
  {
    const std::string what = e.what();
    EXPECT_NE(what.find("whole.vti"), std::string::npos) << what;
    EXPECT_NE(what.find("10000200001 points, but its pieces hold 4"), std::string::npos) << what;
  }
  // A reversed axis, in the WholeExtent or a piece's Extent.
  try
  {
    CheckVTKXMLFile(WriteImage("reversed.vti", "0 1 0 1 5 0", "1 2 3 4"));
    FAIL() << "a reversed extent must be refused";
  }
  catch (const Error& e)
  {
    EXPECT_NE(
      std::string(e.what()).find("reversed WholeExtent '0 1 0 1 5 0' (axis z"), std::string::npos)
      << e.what();
  }
}

TEST(ErrorMessages, AreOneLineOfValidUtf8)
{
  // Text quoted from a damaged file reaches the message as is; control characters and bytes
  // that are no UTF-8 become '?', while the engine's own symbols (≥, ×, °) stay.
  EXPECT_EQ(Printable("a\nb\x1b[31m"), "a?b?[31m");
  EXPECT_EQ(Printable("≥ 2 × 3°"), "≥ 2 × 3°");
  EXPECT_EQ(Printable("\xd6\xd6\xff\x7f ok \xe2\x89"), "???? ok ??");
  EXPECT_EQ(Printable("\xc0\xaf"), "??"); // an overlong '/', no valid start byte
  EXPECT_EQ(std::string(Error("x \xff y").what()), "x ? y");
}
