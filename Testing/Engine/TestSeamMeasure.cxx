// SPDX-License-Identifier: BSD-3-Clause
// The seam measure (Discrete/SeamMeasure.h, issue 44 item 4) on hand-built grids: where the
// block borders lie, a model whose borders hold another label than its interior (a seam), a
// model without one, and the whole run's own variation at the same places.
#include "Core/Error.h"
#include "Discrete/SeamMeasure.h"

#include <gtest/gtest.h>

using namespace msynth;

namespace
{
using Planes = std::array<std::vector<std::int64_t>, 3>;

/// A 12 x 12 grid of label 0 whose sites on either side of the planes @p lines (x and y) hold 1.
LabelGrid Lined(const std::vector<std::int64_t>& lines)
{
  LabelGrid g(12, 12, 1);
  for (std::int64_t y = 0; y < 12; ++y)
    for (std::int64_t x = 0; x < 12; ++x)
      for (std::int64_t p : lines)
        if (x == p - 1 || x == p || y == p - 1 || y == p)
          g.Set(x, y, 0, 1);
  return g;
}
} // namespace

TEST(SeamMeasure, BordersAreTheBlocksRingPlanes)
{
  // 12 sites in blocks of 6 overlapping by 3: origins 0, 3, 6; rings before each origin and
  // after each end, inside the grid: 3, 6, 9 (12 is the world's face).
  const Planes p = BlockBorderPlanes({ { 12, 12, 1 } }, { { 6, 6, 1 } }, { { -1, -1, -1 } });
  EXPECT_EQ(p[0], (std::vector<std::int64_t>{ 3, 6, 9 }));
  EXPECT_EQ(p[1], (std::vector<std::int64_t>{ 3, 6, 9 }));
  EXPECT_TRUE(p[2].empty()); // a flat axis, one block
  const Planes q = BlockBorderPlanes({ { 62, 62, 1 } }, { { 32, 32, 1 } }, { { -1, -1, -1 } });
  EXPECT_EQ(q[0], (std::vector<std::int64_t>{ 16, 32, 48 })); // origins 0, 16, 32 (clipped)
}

TEST(SeamMeasure, LinesAlongTheBordersAreASeam)
{
  const Planes planes = { { { 6 }, { 6 }, {} } };
  const LabelGrid seam = Lined({ 6 });
  const SeamMeasure s = MeasureSeams(seam, planes, 1);
  EXPECT_EQ(s.BorderWindows, 12 * 12 - 10 * 10);
  EXPECT_EQ(s.InteriorWindows, 10 * 10);
  EXPECT_DOUBLE_EQ(s.BorderVsInterior, 1.0); // only 1 on the borders, only 0 inside
  EXPECT_DOUBLE_EQ(s.BorderTop, 1.0);
  // The same lines away from the borders: both sets hold both labels.
  const LabelGrid elsewhere = Lined({ 3 });
  const SeamMeasure t = MeasureSeams(seam, planes, 1, &elsewhere);
  ASSERT_TRUE(t.HasWhole);
  EXPECT_LT(t.WholeBorderVsInterior, 0.5);
  EXPECT_GT(t.Excess(), 0.5);
  EXPECT_GT(t.BorderVsWhole, t.InteriorVsWhole);
  // The model against itself as the whole run: no excess.
  EXPECT_DOUBLE_EQ(MeasureSeams(seam, planes, 2, &seam).Excess(), 0.0);
}

TEST(SeamMeasure, AUniformModelHasNone)
{
  const LabelGrid flat(12, 12, 1);
  const SeamMeasure s = MeasureSeams(flat, { { { 3, 6, 9 }, { 6 }, {} } }, 2, &flat);
  EXPECT_DOUBLE_EQ(s.BorderVsInterior, 0.0);
  EXPECT_DOUBLE_EQ(s.Excess(), 0.0);
  EXPECT_GT(s.BorderWindows, 0);
}

TEST(SeamMeasure, RefusesWindowsAndWholeRunsThatDoNotFit)
{
  const LabelGrid g(4, 4, 1), other(5, 4, 1);
  EXPECT_THROW(MeasureSeams(g, {}, 5), Error);
  EXPECT_THROW(MeasureSeams(g, {}, 0), Error);
  EXPECT_THROW(MeasureSeams(g, {}, 2, &other), Error);
}
