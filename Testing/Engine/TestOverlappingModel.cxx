// SPDX-License-Identifier: BSD-3-Clause
#include "Core/Error.h"
#include "Discrete/DiscreteSynthesis.h"
#include "Discrete/OverlappingModel.h"

#include <gtest/gtest.h>

#include <map>
#include <set>
#include <string>
#include <vector>

using namespace msynth;

namespace
{
/// A picture from rows of characters, top first; each character is one colour.
RgbaImage Picture(const std::vector<std::string>& rows)
{
  static const std::map<char, std::array<std::uint8_t, 4>> colours{ { '.',
                                                                      { { 120, 180, 255, 255 } } },
    { '#', { { 90, 60, 30, 255 } } }, { '|', { { 30, 160, 40, 255 } } },
    { 'o', { { 240, 40, 60, 255 } } }, { 'a', { { 0, 0, 0, 255 } } },
    { 'b', { { 255, 255, 255, 255 } } }, { 'c', { { 255, 0, 0, 255 } } },
    { 'd', { { 0, 255, 0, 255 } } }, { 'e', { { 0, 0, 255, 255 } } }, { 'f', { { 9, 9, 9, 255 } } },
    { 'g', { { 1, 2, 3, 255 } } }, { 'h', { { 4, 5, 6, 255 } } }, { 'i', { { 7, 8, 9, 255 } } } };
  RgbaImage image;
  image.Width = static_cast<int>(rows[0].size());
  image.Height = static_cast<int>(rows.size());
  for (const auto& row : rows)
    for (const char c : row)
    {
      const auto& rgba = colours.at(c);
      image.Pixels.insert(image.Pixels.end(), rgba.begin(), rgba.end());
    }
  return image;
}

/// Sky, flowers on stems, and ground along the bottom: a sample for the ground option.
const std::vector<std::string> Meadow{
  "................",
  "................",
  "...o........o...",
  "...|...o....|...",
  "...|...|....|...",
  "################",
  "################",
};

RgbaImage SynthesizePicture(const PatternSet& set, const RgbaImage& sample, SynthesisOptions o,
  bool periodic, int width, int height)
{
  const Periodic both{ { periodic, periodic } };
  o.Size = set.SitesFor(width, height, both);
  if (periodic)
    o.Translate[0].Enabled = o.Translate[1].Enabled = true;
  set.Configure(o, both);
  const SynthesisResult r = Synthesize(set.Rules(), o);
  EXPECT_TRUE(r.Succeeded()) << r.Message;
  EXPECT_EQ(r.Statistics.BlocksFailed, 0);
  // Valid is not enough: a picture of one pattern passes the check. Most patterns appear.
  const std::set<Label> used(r.Model.Data().begin(), r.Model.Data().end());
  EXPECT_GE(static_cast<int>(used.size()), set.NumberOfPatterns() / 2);
  const RgbaImage picture = set.Compose(r.Model, both);
  EXPECT_EQ(picture.Width, width);
  EXPECT_EQ(picture.Height, height);
  const auto problems = CheckPicture(sample, set.Options, picture, both);
  EXPECT_TRUE(problems.empty()) << problems.front();
  return picture;
}
} // namespace

TEST(OverlappingModel, PatternsCountsAndPairs)
{
  // A 2 x 2 checkerboard: two 2 x 2 patterns with wrapping, each twice (16 times with all
  // symmetries), each the other's neighbour along both axes.
  const RgbaImage board = Picture({ "ab", "ba" });
  OverlappingOptions o;
  o.N = 2;
  o.Symmetry = 1;
  PatternSet set = ExtractPatterns(board, o, "board");
  ASSERT_EQ(set.NumberOfPatterns(), 2);
  EXPECT_EQ(set.Counts, (std::vector<double>{ 2, 2 }));
  const std::vector<std::pair<int, int>> cross{ { 0, 1 }, { 1, 0 } };
  EXPECT_EQ(set.Pairs[0], cross);
  EXPECT_EQ(set.Pairs[1], cross);
  o.Symmetry = 8;
  set = ExtractPatterns(board, o, "board");
  EXPECT_EQ(set.Counts, (std::vector<double>{ 16, 16 }));
  // Without wrapping only the one window inside.
  o.PeriodicInput = false;
  o.Symmetry = 1;
  EXPECT_EQ(ExtractPatterns(board, o, "board").NumberOfPatterns(), 1);
}

TEST(OverlappingModel, DihedralImagesInWaveFunctionCollapseOrder)
{
  // One 3 x 3 window of nine colours: its eight images are eight patterns, numbered identity,
  // mirror, quarter turn (counter-clockwise: the top-right corner comes to the top left), ...
  const RgbaImage nine = Picture({ "abc", "def", "ghi" });
  OverlappingOptions o;
  o.PeriodicInput = false;
  const PatternSet set = ExtractPatterns(nine, o, "nine");
  ASSERT_EQ(set.NumberOfPatterns(), 8);
  const auto colour = [&](int t, int x, int y) { return set.Colours[set.At(t, x, y)][2]; };
  EXPECT_EQ(colour(0, 0, 0), 0); // a: black
  EXPECT_EQ(colour(1, 0, 0), 0); // mirrored: c, red (blue 0) ...
  EXPECT_EQ(set.At(1, 0, 0), 2); // colour index 2 is c
  EXPECT_EQ(set.At(2, 0, 0), 2); // turned: c at the top left
  EXPECT_EQ(set.At(2, 0, 2), 0); // a at the bottom left
  EXPECT_EQ(set.At(3, 0, 0), 8); // the turn mirrored: i at the top left
  EXPECT_EQ(set.At(4, 0, 0), 8); // half turn: i at the top left
  EXPECT_EQ(set.At(6, 0, 0), 6); // three quarters: g at the top left
  EXPECT_EQ(set.At(7, 0, 0), 0); // its mirror: a (the transpose)
  EXPECT_EQ(set.At(7, 1, 0), 3); // d right of a in the transpose
  (void)colour;
}

TEST(OverlappingModel, BadOptionsAreErrors)
{
  const RgbaImage board = Picture({ "ab", "ba" });
  OverlappingOptions o;
  o.N = 3;
  EXPECT_THROW(ExtractPatterns(board, o, "board"), Error); // larger than the sample
  o.N = 0;
  EXPECT_THROW(ExtractPatterns(board, o, "board"), Error);
  o.N = 2;
  o.Symmetry = 9;
  EXPECT_THROW(ExtractPatterns(board, o, "board"), Error);
  o.Symmetry = 1;
  RgbaImage huge;
  huge.Width = 2048;
  huge.Height = 1024;
  huge.Pixels.assign(static_cast<std::size_t>(4 * huge.Width * huge.Height), 0);
  EXPECT_THROW(ExtractPatterns(huge, o, "huge"), Error); // over 2^20 pixels
  // Every pixel a colour of its own: more patterns than allowed, refused while counting.
  RgbaImage noisy;
  noisy.Width = noisy.Height = 128;
  for (int i = 0; i < 128 * 128; ++i)
    for (const int c : { i & 255, i >> 8, 7, 255 })
      noisy.Pixels.push_back(static_cast<std::uint8_t>(c));
  o.N = 2;
  EXPECT_THROW(ExtractPatterns(noisy, o, "noisy"), Error);
  const PatternSet set = ExtractPatterns(board, o, "board");
  EXPECT_THROW(set.SitesFor(1, 5, { { false, false } }), Error);
  LabelGrid bad(2, 2, 1, 7);
  EXPECT_THROW(set.Compose(bad, { { true, true } }), Error);
}

TEST(OverlappingModel, PicturesFromBlocksAndWholeModel)
{
  const RgbaImage sample = Picture(Meadow);
  OverlappingOptions po;
  po.Symmetry = 2;
  const PatternSet set = ExtractPatterns(sample, po, "meadow");
  for (std::uint64_t seed = 1; seed <= 3; ++seed)
  {
    SynthesisOptions o;
    o.Seed = seed;
    o.Choice = LabelChoice::Frequency;
    o.Order = SiteOrder::MinimumEntropy;
    SynthesizePicture(set, sample, o, false, 40, 24);
    o.BlockSize = { { 12, 12, 1 } };
    SynthesizePicture(set, sample, o, false, 48, 30);
  }
}

TEST(OverlappingModel, GroundAndPeriodicOutput)
{
  const RgbaImage sample = Picture(Meadow);
  OverlappingOptions po;
  po.Symmetry = 2;
  po.Ground = true;
  const PatternSet set = ExtractPatterns(sample, po, "meadow");
  for (std::uint64_t seed = 1; seed <= 3; ++seed)
  {
    SynthesisOptions o;
    o.Seed = seed;
    o.Choice = LabelChoice::Frequency;
    const RgbaImage periodic = SynthesizePicture(set, sample, o, true, 32, 20);
    // The bottom row of pixels is the sample's: ground.
    for (int x = 0; x < periodic.Width; ++x)
      EXPECT_EQ(periodic.At(x, periodic.Height - 1)[2], 30);
    o.BlockSize = { { 10, 10, 1 } }; // blocks start from layers: ground, then sky above
    SynthesizePicture(set, sample, o, true, 40, 20);
    SynthesizePicture(set, sample, o, false, 40, 20);
  }
}

TEST(OverlappingModel, CheckerFindsWrongPictures)
{
  const RgbaImage sample = Picture(Meadow);
  OverlappingOptions po;
  po.Symmetry = 2;
  const PatternSet set = ExtractPatterns(sample, po, "meadow");
  SynthesisOptions o;
  o.Seed = 5;
  const Periodic bounded{ { false, false } }, repeating{ { true, true } };
  o.Size = set.SitesFor(30, 20, bounded);
  const SynthesisResult r = Synthesize(set.Rules(), o);
  ASSERT_TRUE(r.Succeeded());
  RgbaImage picture = set.Compose(r.Model, bounded);
  ASSERT_TRUE(CheckPicture(sample, po, picture, bounded).empty());
  // A flower in the ground is in no window of the sample.
  picture.Pixels[static_cast<std::size_t>(4 * (19 * 30 + 7))] = 240;
  picture.Pixels[static_cast<std::size_t>(4 * (19 * 30 + 7) + 1)] = 40;
  picture.Pixels[static_cast<std::size_t>(4 * (19 * 30 + 7) + 2)] = 60;
  EXPECT_FALSE(CheckPicture(sample, po, picture, bounded).empty());
  // Turned windows are not in a sample read without symmetry.
  const RgbaImage turned = Picture({ "ab.", "...", "..." });
  OverlappingOptions one;
  one.Symmetry = 1;
  EXPECT_FALSE(CheckPicture(Picture({ "a..", "b..", "..." }), one, turned, repeating).empty());
  one.Symmetry = 8;
  EXPECT_TRUE(CheckPicture(Picture({ "a..", "b..", "..." }), one, turned, repeating).empty());
}
