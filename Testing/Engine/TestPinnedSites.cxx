// SPDX-License-Identifier: BSD-3-Clause
// Pinned sites (SynthesisOptions::Pins): completing a partial model. Every model is verified by
// CheckConsistency (the pairs recomputed from the example), and every pin is looked up in it.
#include "Core/Error.h"
#include "Discrete/ConsistencyCheck.h"
#include "Discrete/DiscreteSynthesis.h"

#include "Fixtures.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

using namespace msynth;

using msynth_test::Village;

namespace
{
struct Pin
{
  std::int64_t X, Y, Z;
  Label Value;
};

SynthesisOptions WithPins(const std::vector<Pin>& pins, std::array<std::int64_t, 3> block)
{
  SynthesisOptions o;
  o.Size = { { 24, 24, 5 } };
  o.BlockSize = block;
  o.Seed = 11;
  LabelGrid grid(24, 24, 5, FreeSite);
  for (const Pin& p : pins)
    grid.Set(p.X, p.Y, p.Z, p.Value);
  o.Pins = std::move(grid);
  return o;
}

std::string ErrorOf(const SynthesisOptions& o)
{
  try
  {
    const LabelGrid example = Village();
    Synthesize(AdjacencyRules::FromExample(ExampleAnalysis::FromExample(example)), o);
  }
  catch (const Error& e)
  {
    return e.what();
  }
  return "";
}
} // namespace

// Roofs pinned where the trivial start has empty sky: whole-model synthesis starts its catalog
// from them; block synthesis places each with a block around it first, and no block moves them.
TEST(PinnedSites, PinsAreKeptWholeAndInBlocksOnAnyThreads)
{
  const LabelGrid example = Village();
  const AdjacencyRules rules = AdjacencyRules::FromExample(ExampleAnalysis::FromExample(example));
  const std::vector<Pin> pins = { { 5, 5, 3, 3 }, { 17, 6, 3, 3 }, { 12, 19, 1, 2 }, { 0, 0, 0, 1 },
    { 20, 20, 4, 0 } };
  for (const auto& block :
    { std::array<std::int64_t, 3>{ { 0, 0, 0 } }, std::array<std::int64_t, 3>{ { 12, 12, 5 } } })
  {
    LabelGrid first;
    for (int threads : { 1, 2 })
    {
      SynthesisOptions o = WithPins(pins, block);
      o.Boundary[4] = 1; // ground along -z, so that the trivial start is ground under sky
      o.Threads = threads;
      const SynthesisResult r = Synthesize(rules, o);
      ASSERT_TRUE(r.Succeeded()) << r.Message;
      const ConsistencyReport report = CheckConsistency(example, r.Model);
      EXPECT_TRUE(report.Consistent) << (report.First.empty() ? "" : report.First[0].Describe());
      for (const Pin& p : pins)
        EXPECT_EQ(r.Model.At(p.X, p.Y, p.Z), p.Value) << p.X << " " << p.Y << " " << p.Z;
      if (threads == 1)
        first = r.Model;
      else
        EXPECT_TRUE(r.Model.Data() == first.Data()) << "the same model on any thread count";
    }
  }
}

// Pins that cannot hold are one line before any work: next to each other, through propagation,
// with a label the example lacks, against the boundary, or with the wrong size.
TEST(PinnedSites, ContradictionsAreOneLineBeforeAnyWork)
{
  const std::array<std::int64_t, 3> whole{ { 0, 0, 0 } };
  EXPECT_EQ(ErrorOf(WithPins({ { 5, 5, 1, 1 }, { 5, 5, 2, 3 } }, whole)),
    "the labels 1 at (5, 5, 1) and 3 at (5, 5, 2) cannot meet: the example never puts them next "
    "to each other along z");
  // Ground at z = 0 and z = 2: nothing lies both on ground and under it.
  EXPECT_EQ(ErrorOf(WithPins({ { 5, 5, 0, 1 }, { 5, 5, 2, 1 } }, whole)),
    "the pinned sites cannot all hold: with them, no label fits site (5, 5, 1)");
  EXPECT_EQ(ErrorOf(WithPins({ { 3, 4, 2, 7 } }, whole)),
    "site (3, 4, 2) is pinned to label 7, which does not occur in the example");
  SynthesisOptions boundary = WithPins({ { 3, 4, 0, 2 } }, whole);
  boundary.Boundary[4] = 1; // ground along -z
  EXPECT_EQ(
    ErrorOf(boundary), "site (3, 4, 0) is pinned to label 2, but the boundary there is label 1");
  SynthesisOptions small = WithPins({}, whole);
  small.Pins = LabelGrid(4, 4, 5, FreeSite);
  EXPECT_EQ(ErrorOf(small),
    "the pinned sites cover 4 x 4 x 5 sites, the output 24 x 24 x 5: "
    "expected a grid of the output's size");
  SynthesisOptions mirrored = WithPins({ { 5, 5, 3, 3 } }, whole);
  mirrored.Symmetry[0].Enabled = true;
  EXPECT_NE(ErrorOf(mirrored).find("cannot be combined with mirror"), std::string::npos);
}
