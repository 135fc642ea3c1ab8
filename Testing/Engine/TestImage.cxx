// SPDX-License-Identifier: BSD-3-Clause
// Pictures: PNG written and read back, BMP as older tilesets have them, and every damaged file
// an error naming it (never a crash: the sanitizer build runs these too).
#include "Core/Error.h"
#include "Formats/Image.h"

#include <gtest/gtest.h>

#include <fstream>
#include <iterator>
#include <string>
#include <vector>

using namespace msynth;

namespace
{
std::string Temp(const std::string& name)
{
  return std::string(MSYNTH_TEST_TMP) + "/" + name;
}

RgbaImage Pattern(int w, int h, bool opaque)
{
  RgbaImage image;
  image.Width = w;
  image.Height = h;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      for (int c : { 3 * x + y, 5 * y, x * y, opaque ? 255 : 40 + x })
        image.Pixels.push_back(static_cast<std::uint8_t>(c));
  return image;
}

std::vector<char> Bytes(const std::string& path)
{
  std::ifstream in(path, std::ios::binary);
  return std::vector<char>(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

void Put(const std::string& path, const std::vector<char>& bytes)
{
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
}

std::string ErrorOf(const std::string& path)
{
  try
  {
    ReadImage(path);
  }
  catch (const Error& e)
  {
    return e.what();
  }
  return "";
}

/// A BMP file written here byte by byte: bottom-up rows padded to 4 bytes.
std::vector<char> Bmp(const RgbaImage& image, int bits)
{
  const int stride = ((image.Width * bits + 31) / 32) * 4;
  const int table = bits == 8 ? 4 * 256 : 0;
  const int offset = 54 + table;
  std::vector<char> b(static_cast<std::size_t>(offset + stride * image.Height), 0);
  auto put = [&b](int at, std::uint32_t v, int n)
  {
    for (int i = 0; i < n; ++i)
      b[static_cast<std::size_t>(at + i)] = static_cast<char>((v >> (8 * i)) & 255);
  };
  b[0] = 'B';
  b[1] = 'M';
  put(2, static_cast<std::uint32_t>(b.size()), 4);
  put(10, static_cast<std::uint32_t>(offset), 4);
  put(14, 40, 4);
  put(18, static_cast<std::uint32_t>(image.Width), 4);
  put(22, static_cast<std::uint32_t>(image.Height), 4);
  put(26, 1, 2);
  put(28, static_cast<std::uint32_t>(bits), 2);
  for (int i = 0; i < 256 && bits == 8; ++i) // grey ramp
    put(54 + 4 * i, static_cast<std::uint32_t>(i * 0x010101), 4);
  for (int y = 0; y < image.Height; ++y)
    for (int x = 0; x < image.Width; ++x)
    {
      const std::uint8_t* p = image.At(x, image.Height - 1 - y);
      const int at = offset + y * stride + x * (bits / 8);
      if (bits == 8)
        b[static_cast<std::size_t>(at)] = static_cast<char>(p[0]);
      else
        for (int c = 0; c < 3; ++c)
          b[static_cast<std::size_t>(at + c)] = static_cast<char>(p[2 - c]);
    }
  return b;
}
} // namespace

TEST(Image, PngRoundTrips)
{
  for (bool opaque : { true, false })
  {
    const RgbaImage image = Pattern(13, 7, opaque);
    const std::string path = Temp(opaque ? "opaque.png" : "alpha.png");
    WritePng(path, image, 6);
    const RgbaImage back = ReadPng(path);
    EXPECT_EQ(back.Width, 13);
    EXPECT_EQ(back.Height, 7);
    EXPECT_EQ(back.Pixels, image.Pixels);
  }
}

TEST(Image, LargePicturesAreWrittenInStripsAndReadBack)
{
  // Several strips of about 1 MB each, deflated apart and joined; every filter type is useful
  // somewhere (flat rows, horizontal ramps, vertical repeats, noise).
  for (const bool opaque : { true, false })
  {
    RgbaImage image;
    image.Width = 700;
    image.Height = 1100;
    std::uint32_t state = 7;
    for (int y = 0; y < image.Height; ++y)
      for (int x = 0; x < image.Width; ++x)
      {
        state = state * 1664525u + 1013904223u;
        const int band = (y / 100) % 4;
        const std::uint8_t v = band == 0 ? 40
          : band == 1                    ? static_cast<std::uint8_t>(x)
          : band == 2                    ? static_cast<std::uint8_t>(x % 16 * 9)
                                         : static_cast<std::uint8_t>(state >> 24);
        for (const int c : { static_cast<int>(v), v / 2, 255 - v, opaque ? 255 : (x + y) % 256 })
          image.Pixels.push_back(static_cast<std::uint8_t>(c));
      }
    const std::string path = Temp(opaque ? "large-opaque.png" : "large-alpha.png");
    WritePng(path, image);
    const RgbaImage back = ReadPng(path); // libpng checks every chunk's CRC and the Adler-32
    EXPECT_EQ(back.Width, image.Width);
    EXPECT_EQ(back.Height, image.Height);
    EXPECT_TRUE(back.Pixels == image.Pixels);
    // Rows given by a function (bottom-first storage, as VTK's) give the same file.
    const std::string again = Temp("again.png");
    WritePng(again, image.Width, image.Height, [&image](int y) { return image.At(0, y); });
    EXPECT_EQ(Bytes(path), Bytes(again));
  }
  EXPECT_THROW(WritePng(Temp("empty.png"), RgbaImage()), Error);
}

TEST(Image, FewColoursAreWrittenAsAPalette)
{
  // Tile pictures have a few colours: an indexed PNG (colour type 3, PLTE, tRNS for the
  // translucent ones) that reads back to the same pixels; 257 colours fall back to RGB(A).
  for (const int colours : { 1, 3, 256, 257 })
    for (const bool opaque : { true, false })
    {
      RgbaImage image;
      image.Width = 300;
      image.Height = 40;
      for (int y = 0; y < image.Height; ++y)
        for (int x = 0; x < image.Width; ++x)
        {
          const int c = (x / 3 + 7 * y) % colours;
          for (const int v :
            { c % 256, (c * 7 + c / 256) % 256, 255 - c % 256, opaque || c % 5 ? 255 : c % 200 })
            image.Pixels.push_back(static_cast<std::uint8_t>(v));
        }
      const std::string path = Temp("palette.png");
      WritePng(path, image);
      const std::vector<char> file = Bytes(path);
      const std::string bytes(file.begin(), file.end());
      ASSERT_GT(bytes.size(), 33u);
      EXPECT_EQ(static_cast<int>(bytes[25]), colours <= 256 ? 3 : (opaque ? 2 : 6)) << colours;
      EXPECT_EQ(bytes.find("tRNS") != std::string::npos, colours <= 256 && !opaque) << colours;
      const RgbaImage back = ReadPng(path);
      EXPECT_TRUE(back.Pixels == image.Pixels) << colours << " " << opaque;
    }
}

TEST(Image, WrittenPicturesSayMsynthWroteThem)
{
  // So that `msynth check` can tell a picture it wrote from a sample given in its place.
  const std::string path = Temp("written.png");
  WritePng(path, Pattern(8, 8, true));
  EXPECT_TRUE(IsWrittenPng(path));
  EXPECT_EQ(ReadPng(path).Pixels, Pattern(8, 8, true).Pixels);
  std::vector<char> bytes = Bytes(path);
  const std::string text(bytes.begin(), bytes.end());
  const std::size_t at = text.find("Software");
  ASSERT_NE(at, std::string::npos);
  bytes[at + 9] = 'x'; // another program's text (its CRC no longer matters: not read)
  Put(Temp("other.png"), bytes);
  EXPECT_FALSE(IsWrittenPng(Temp("other.png")));
  const std::vector<char> whole = Bytes(path);
  for (const std::size_t n : { std::size_t(0), std::size_t(8), std::size_t(20) })
  {
    Put(Temp("cut.png"),
      std::vector<char>(whole.begin(), whole.begin() + static_cast<std::ptrdiff_t>(n)));
    EXPECT_FALSE(IsWrittenPng(Temp("cut.png"))) << n;
  }
  EXPECT_FALSE(IsWrittenPng(Temp("no-such.png")));
}

TEST(Image, BmpIsReadAsOlderTilesetsHaveIt)
{
  const RgbaImage image = Pattern(5, 3, true);
  Put(Temp("tile.bmp"), Bmp(image, 24));
  EXPECT_EQ(ReadImage(Temp("tile.bmp")).Pixels, image.Pixels);
  Put(Temp("grey.bmp"), Bmp(image, 8));
  const RgbaImage grey = ReadImage(Temp("grey.bmp"));
  for (int y = 0; y < 3; ++y)
    for (int x = 0; x < 5; ++x)
      EXPECT_EQ(grey.At(x, y)[1], image.At(x, y)[0]); // the ramp maps index i to (i, i, i)
}

TEST(Image, DamagedFilesAreErrorsNamingTheFile)
{
  const std::string good = Temp("good.png");
  WritePng(good, Pattern(16, 16, false), 6);
  const std::vector<char> png = Bytes(good);
  // Truncations into the pixel data, including the 60 bytes that crashed VTK's PNG reader (a
  // file missing only its end marker still holds the whole picture and is read).
  for (std::size_t n : { std::size_t(0), std::size_t(8), std::size_t(33), std::size_t(60),
         png.size() / 2, png.size() - 13 })
  {
    const std::string path = Temp("cut.png");
    Put(path, std::vector<char>(png.begin(), png.begin() + static_cast<std::ptrdiff_t>(n)));
    EXPECT_NE(ErrorOf(path).find("'" + path + "'"), std::string::npos) << n << " bytes";
  }
  // Every single-bit flip is either read (then with its size) or an error naming the file.
  for (std::size_t i = 0; i < png.size(); ++i)
  {
    std::vector<char> bad = png;
    bad[i] = static_cast<char>(bad[i] ^ (1 << (i % 8)));
    const std::string path = Temp("flip.png");
    Put(path, bad);
    try
    {
      const RgbaImage image = ReadImage(path);
      EXPECT_EQ(image.Pixels.size(), 4u * static_cast<std::size_t>(image.Width) * image.Height);
    }
    catch (const Error& e)
    {
      EXPECT_NE(std::string(e.what()).find("'" + path + "'"), std::string::npos) << e.what();
    }
  }
  // BMP: truncated pixels, an absurd size, a colour outside the table, another format.
  std::vector<char> bmp = Bmp(Pattern(5, 3, true), 24);
  Put(Temp("cut.bmp"), std::vector<char>(bmp.begin(), bmp.end() - 7));
  EXPECT_NE(ErrorOf(Temp("cut.bmp")).find("is truncated"), std::string::npos);
  std::vector<char> huge = bmp;
  huge[21] = 0x7f; // width 2^31 - ...
  Put(Temp("huge.bmp"), huge);
  EXPECT_NE(ErrorOf(Temp("huge.bmp")).find("pixels a side"), std::string::npos);
  std::vector<char> grey = Bmp(Pattern(5, 3, true), 8);
  grey[46] = 2; // a table of two colours, indices up to 255
  Put(Temp("table.bmp"), grey);
  EXPECT_NE(ErrorOf(Temp("table.bmp")).find("beyond its table"), std::string::npos);
  Put(Temp("text.bmp"), std::vector<char>(100, 'x'));
  EXPECT_NE(ErrorOf(Temp("text.bmp")).find("no 'BM' signature"), std::string::npos);
  EXPECT_NE(ErrorOf(Temp("missing.png")).find("no such image file"), std::string::npos);
}
