// SPDX-License-Identifier: BSD-3-Clause
// Eq. 3.2 is checked against a brute-force recomputation that shares nothing with the engine:
// for every label pair and axis, scan the example for an occurrence.
#include "Core/Error.h"
#include "Discrete/ExampleAnalysis.h"

#include "Fixtures.h"

#include <gtest/gtest.h>

#include <random>
#include <set>

using msynth::ExampleAnalysis;
using msynth::Label;
using msynth::LabelGrid;

using msynth_test::Grid2D;

namespace
{

/// Brute force: the number of sites x with E(x) = b and E(x + d) = c.
std::int64_t CountPairs(const LabelGrid& e, int axis, Label b, Label c)
{
  std::int64_t n = 0;
  const auto& d = e.Dimensions();
  for (std::int64_t z = 0; z < d[2]; ++z)
    for (std::int64_t y = 0; y < d[1]; ++y)
      for (std::int64_t x = 0; x < d[0]; ++x)
      {
        std::int64_t q[3] = { x, y, z };
        q[axis] += 1;
        if (e.Contains(q[0], q[1], q[2]) && e.At(x, y, z) == b && e.At(q[0], q[1], q[2]) == c)
        {
          ++n;
        }
      }
  return n;
}

void ExpectMatchesBruteForce(const LabelGrid& e, const ExampleAnalysis& a)
{
  std::set<Label> distinct(e.Data().begin(), e.Data().end());
  ASSERT_EQ(static_cast<std::size_t>(a.NumberOfLabels()), distinct.size());
  std::size_t i = 0;
  for (Label b : distinct)
  {
    EXPECT_EQ(a.Labels()[i], b);
    EXPECT_EQ(a.IndexOf(b), static_cast<int>(i));
    std::int64_t count = 0;
    for (Label v : e.Data())
    {
      count += v == b;
    }
    EXPECT_EQ(a.LabelCounts()[i], count);
    ++i;
  }
  for (int axis = 0; axis < 3; ++axis)
  {
    std::size_t allowed = 0;
    for (Label b : distinct)
    {
      for (Label c : distinct)
      {
        const std::int64_t n = CountPairs(e, axis, b, c);
        EXPECT_EQ(a.PairCount(axis, a.IndexOf(b), a.IndexOf(c)), n)
          << "axis " << axis << " pair " << b << "," << c;
        EXPECT_EQ(a.Allowed(axis, a.IndexOf(b), a.IndexOf(c)), n > 0);
        allowed += n > 0;
      }
    }
    EXPECT_EQ(a.Transitions(axis).size(), allowed);
  }
}
} // namespace

TEST(ExampleAnalysis, OnlyEmptyExampleAllowsOnlyItself)
{
  // E0 of §3.2: a model of only empty space.
  const LabelGrid e(3, 3, 3, 0);
  const auto a = ExampleAnalysis::FromExample(e);
  EXPECT_EQ(a.NumberOfLabels(), 1);
  for (int axis = 0; axis < 3; ++axis)
  {
    ASSERT_EQ(a.Transitions(axis).size(), 1u);
    EXPECT_EQ(a.Transitions(axis)[0], (ExampleAnalysis::Transition{ 0, 0, 18 }));
  }
}

TEST(ExampleAnalysis, CheckerboardAlternates)
{
  const LabelGrid e = Grid2D({ { 0, 1, 0 }, { 1, 0, 1 }, { 0, 1, 0 } });
  const auto a = ExampleAnalysis::FromExample(e);
  ASSERT_EQ(a.NumberOfLabels(), 2);
  for (int axis = 0; axis < 2; ++axis)
  {
    EXPECT_FALSE(a.Allowed(axis, 0, 0));
    EXPECT_FALSE(a.Allowed(axis, 1, 1));
    EXPECT_TRUE(a.Allowed(axis, 0, 1));
    EXPECT_TRUE(a.Allowed(axis, 1, 0));
  }
  EXPECT_TRUE(a.Transitions(msynth::AxisZ).empty()); // a 2D example has no z pairs
  ExpectMatchesBruteForce(e, a);
}

TEST(ExampleAnalysis, DirectionMatters)
{
  // Ground (1) under a wall (2) under a roof (3), in empty space (0): Ty is not symmetric.
  const LabelGrid e = Grid2D({ { 0, 0, 0, 0 }, { 0, 3, 3, 0 }, { 0, 2, 2, 0 }, { 1, 1, 1, 1 } });
  const auto a = ExampleAnalysis::FromExample(e);
  const int ground = a.IndexOf(1), wall = a.IndexOf(2), roof = a.IndexOf(3), empty = a.IndexOf(0);
  EXPECT_TRUE(a.Allowed(msynth::AxisY, ground, wall));
  EXPECT_FALSE(a.Allowed(msynth::AxisY, wall, ground));
  EXPECT_TRUE(a.Allowed(msynth::AxisY, wall, roof));
  EXPECT_TRUE(a.Allowed(msynth::AxisY, roof, empty));
  EXPECT_FALSE(a.Allowed(msynth::AxisY, empty, roof));
  EXPECT_EQ(a.PairCount(msynth::AxisX, wall, wall), 1);
  EXPECT_EQ(a.PairCount(msynth::AxisX, ground, ground), 3);
  ExpectMatchesBruteForce(e, a);
}

TEST(ExampleAnalysis, ArbitraryLabelValuesMapToSortedIndices)
{
  const LabelGrid e = Grid2D({ { 100, -5 }, { 7, 100 } });
  const auto a = ExampleAnalysis::FromExample(e);
  EXPECT_EQ(a.Labels(), (std::vector<Label>{ -5, 7, 100 }));
  EXPECT_EQ(a.IndexOf(7), 1);
  EXPECT_EQ(a.IndexOf(8), -1);
  ExpectMatchesBruteForce(e, a);
}

TEST(ExampleAnalysis, RandomExamplesMatchBruteForce)
{
  std::mt19937 rng(12345);
  for (int trial = 0; trial < 40; ++trial)
  {
    const std::int64_t nx = 1 + rng() % 6, ny = 1 + rng() % 6, nz = 1 + rng() % 4;
    const int k = 1 + static_cast<int>(rng() % 5);
    LabelGrid e(nx, ny, nz);
    for (auto& v : e.Data())
    {
      v = static_cast<Label>(rng() % static_cast<unsigned>(k)) * 3 - 2;
    }
    ExpectMatchesBruteForce(e, ExampleAnalysis::FromExample(e));
  }
}

TEST(ExampleAnalysis, EmptyExampleIsAnError)
{
  EXPECT_THROW(ExampleAnalysis::FromExample(LabelGrid()), msynth::Error);
}
