// SPDX-License-Identifier: BSD-3-Clause
#include "Core/Error.h"
#include "Core/LabelGrid.h"

#include <gtest/gtest.h>

using msynth::LabelGrid;

TEST(LabelGrid, IndexesXFastestLikeVTK)
{
  LabelGrid g(3, 2, 2, 7);
  EXPECT_EQ(g.NumberOfSites(), 12);
  EXPECT_EQ(g.Index(1, 0, 0), 1);
  EXPECT_EQ(g.Index(0, 1, 0), 3);
  EXPECT_EQ(g.Index(0, 0, 1), 6);
  g.Set(2, 1, 1, 4);
  EXPECT_EQ(g.Data()[11], 4);
  EXPECT_EQ(g.At(0, 0, 0), 7);
  EXPECT_TRUE(g.Contains(2, 1, 1));
  EXPECT_FALSE(g.Contains(3, 0, 0));
  EXPECT_FALSE(g.Contains(0, -1, 0));
  EXPECT_FALSE(g.Is2D());
  EXPECT_TRUE(LabelGrid(4, 4, 1).Is2D());
}

TEST(LabelGrid, RejectsBadDimensions)
{
  EXPECT_THROW(LabelGrid(0, 1, 1), msynth::Error);
  EXPECT_THROW(LabelGrid(1, -3, 1), msynth::Error);
  // Too large, and a product that would overflow 64 bits: refused before allocating.
  EXPECT_THROW(LabelGrid(1 << 20, 1 << 20, 1), msynth::Error);
  EXPECT_THROW(
    LabelGrid(std::int64_t(1) << 40, std::int64_t(1) << 40, std::int64_t(1) << 40), msynth::Error);
}

TEST(LabelGrid, RejectsMismatchedData)
{
  EXPECT_THROW(LabelGrid({ { 2, 2, 1 } }, std::vector<msynth::Label>(3)), msynth::Error);
  EXPECT_NO_THROW(LabelGrid({ { 2, 2, 1 } }, std::vector<msynth::Label>(4)));
}
