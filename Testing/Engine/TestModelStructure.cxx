// SPDX-License-Identifier: BSD-3-Clause
// What a person sees in a continuous model (ModelStructure.h): parts, their footprints,
// heights and what they front, measured on boxes whose answers are known; the comparison with
// the example; the example's label counts at its own lattice (LatticeCounts.h); and its runs
// and their chances of ending (RunEnds.h).
#include "Continuous/ContinuousMesh.h"
#include "Continuous/ContinuousSynthesis.h"
#include "Continuous/LatticeCounts.h"
#include "Continuous/ModelStructure.h"
#include "Continuous/PlaneArrangement.h"
#include "Continuous/RunEnds.h"
#include "Core/Error.h"
#include "Formats/PolyhedralExample.h"

#include "Fixtures.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <sstream>
#include <string>

using namespace msynth;

namespace
{
/// An OBJ object: the axis-aligned box [x0, x1] x [y0, y1] x [z0, z1].
std::string Box(const std::string& name, double x0, double y0, double z0, double x1, double y1,
  double z1, int& points)
{
  std::ostringstream s;
  s << "o " << name << "\n";
  for (int k = 0; k < 8; ++k)
    s << "v " << (k & 1 ? x1 : x0) << " " << (k & 2 ? y1 : y0) << " " << (k & 4 ? z1 : z0) << "\n";
  const int b = points + 1;
  const int faces[6][4] = { { 0, 2, 3, 1 }, { 4, 5, 7, 6 }, { 0, 1, 5, 4 }, { 2, 6, 7, 3 },
    { 0, 4, 6, 2 }, { 1, 3, 7, 5 } };
  for (const auto& f : faces)
    s << "f " << b + f[0] << " " << b + f[1] << " " << b + f[2] << " " << b + f[3] << "\n";
  points += 8;
  return s.str();
}

PolyhedralExample Model(const std::string& text)
{
  std::istringstream in(text);
  PolyhedralExample model = ReadOBJExample(in, "test.obj");
  ValidateExample(model);
  return model;
}

/// Three houses (4 x 2 x 2, 1 x 1 x 1, 2 x 1 x 1) and a T of roads (10 along x, 4.5 more along
/// y from its middle): the first house 0.5 from the road, the others 1.5.
PolyhedralExample Street()
{
  int points = 0;
  std::string text = Box("house", 0, 0, 0, 4, 2, 2, points);
  text += Box("house.001", 6, 0, 0, 7, 1, 1, points);
  text += Box("house.002", 7, 5, 0, 9, 6, 1, points);
  text += Box("road", 0, 2.5, 0, 10, 3.5, 0.5, points);
  text += Box("road.001", 4.5, 3.5, 0, 5.5, 8, 0.5, points);
  return Model(text);
}
} // namespace

TEST(ModelStructure, PartsTheirSizesAndWhatTheyFront)
{
  const ModelStructure s = MeasureStructure(Street(), 0.25, 1.0);
  ASSERT_EQ(s.Types.size(), 2u);
  const TypeStructure* house = s.Find(1);
  const TypeStructure* road = s.Find(2);
  ASSERT_TRUE(house && road);
  ASSERT_EQ(house->Parts.size(), 3u);
  EXPECT_NEAR(house->Parts[0].Footprint, 8.0, 1e-9); // the largest first
  EXPECT_NEAR(house->Parts[0].Height, 2.0, 1e-9);
  EXPECT_NEAR(house->Parts[1].Footprint, 2.0, 1e-9);
  EXPECT_NEAR(house->Parts[2].Footprint, 1.0, 1e-9);
  EXPECT_NEAR(house->MedianFootprint, 2.0, 1e-9);
  EXPECT_NEAR(house->Volume, 19.0, 1e-9);
  ASSERT_EQ(road->Parts.size(), 1u); // the two road objects touch
  EXPECT_NEAR(road->Parts[0].Span, 10.0, 1e-9);
  EXPECT_NEAR(road->Parts[0].Footprint, 10.0 * 5.5, 1e-9);
  EXPECT_NEAR(road->Parts[0].Ground, 10.0 + 4.5, 1e-9);
  EXPECT_NEAR(s.GroundArea, 10.0 * 8.0, 1e-9);
  EXPECT_NEAR(house->PartsPer100, 100.0 * 3 / 80.0, 1e-9);
  // Within a reach of 1 one house of three fronts the road; within 2 all do.
  EXPECT_NEAR(house->Fronting.at(2), 1.0 / 3, 1e-9);
  EXPECT_NEAR(road->Fronting.at(1), 1.0, 1e-9);
  EXPECT_NEAR(MeasureStructure(Street(), 0.25, 2.0).Find(1)->Fronting.at(2), 1.0, 1e-9);
}

TEST(ModelStructure, TouchingObjectsOfOneTypeAreOnePart)
{
  int points = 0;
  std::string text = Box("road", 0, 0, 0, 2, 2, 0.5, points);
  text += Box("road.001", 2, 0, 0, 4, 2, 0.5, points);
  text += Box("road.002", 2, 2, 0, 4, 4, 0.5, points);
  const ModelStructure s = MeasureStructure(Model(text), 0.25, 1.0);
  ASSERT_EQ(s.Types.size(), 1u);
  ASSERT_EQ(s.Types[0].Parts.size(), 1u);
  EXPECT_NEAR(s.Types[0].Parts[0].Footprint, 16.0, 1e-9);
  EXPECT_NEAR(s.Types[0].Volume, 6.0, 1e-9);
}

TEST(ModelStructure, AModelLikeItsExampleResemblesItAndSmallPartsDoNot)
{
  const std::map<int, std::string> names{ { 1, "house" }, { 2, "road" } };
  const ModelStructure example = MeasureStructure(Street(), 0.25, 1.0);
  for (const auto& item : CompareStructure(example, example, names))
    EXPECT_TRUE(item.Passes) << item.Measure;
  // Houses a quarter of the size, the road in three pieces: footprints and the network fail.
  int points = 0;
  std::string text = Box("house", 0, 0, 0, 2, 1, 2, points);
  text += Box("house.001", 6, 0, 0, 6.5, 0.5, 1, points);
  text += Box("house.002", 7, 5, 0, 8, 5.5, 1, points);
  for (int k = 0; k < 3; ++k)
    text += Box("road" + std::string(k ? ".00" + std::to_string(k) : ""), 3.5 * k, 2.5, 0,
      3.5 * k + 2.5, 3.5, 0.5, points);
  const ModelStructure model = MeasureStructure(Model(text), 0.25, 1.0);
  std::map<std::string, bool> passes;
  for (const auto& item : CompareStructure(example, model, names))
    passes[item.Measure] = item.Passes;
  EXPECT_FALSE(passes.at("house: median footprint (square units)"));
  EXPECT_FALSE(passes.at("road: volume share in networks (parts spanning half the example's)"));
  EXPECT_TRUE(passes.at("house: parts per 100 square units of ground"));
  // One house in its own box: its density is not compared, nor is a solid block a network.
  int one = 0;
  const ModelStructure house =
    MeasureStructure(Model(Box("house", 0, 0, 0, 4, 2, 2, one)), 0.25, 1);
  const auto items = CompareStructure(house, model, names);
  ASSERT_EQ(items.size(), 1u);
  EXPECT_EQ(items[0].Measure, "house: median footprint (square units)");
  EXPECT_THROW(MeasureStructure(Street(), 0, 1), Error);
}

TEST(LatticeCounts, LabelsCountOncePerVertexOfTheExamplesOwnLattice)
{
  // A 4 x 1 x 1 bar with planes a unit apart (the default would be 4 across x): each of its four
  // edges along x holds three lattice vertices between its corners, each corner one, so an edge
  // label along x counts 3 where the analysis samples it once.
  int points = 0;
  PolyhedralExample bar = Model(Box("bar", 0, 0, 0, 4, 1, 1, points));
  const PolyhedralAnalysis analysis = PolyhedralAnalysis::Analyze(bar);
  const ArrangementParameters p =
    DefaultArrangementParameters(bar, analysis, { 12, 12, 12 }, 0, { 1, 1, 1 });
  const std::vector<double> counts = LatticeOccurrences(bar, analysis, p);
  ASSERT_EQ(counts.size(), static_cast<std::size_t>(analysis.NumberOfLabels()));
  double total = 0;
  int edgesAlongX = 0;
  for (int id = 0; id < analysis.NumberOfLabels(); ++id)
  {
    total += counts[static_cast<std::size_t>(id)];
    if (analysis.Label(id).Kind == FeatureKind::Edge && counts[static_cast<std::size_t>(id)] == 3)
      ++edgesAlongX;
  }
  EXPECT_EQ(total, 5 * 2 * 2); // every vertex of the 5 x 2 x 2 lattice has a label
  EXPECT_EQ(edgesAlongX, 4);
}

TEST(RunEnds, TheExamplesRunsAndTheirChancesOfEnding)
{
  // Rows of a quarter unit along x: the first house's 64 are 4 long and start at the example's
  // edge (cut: it may go on beyond), the second's 16 are 1, the third's 16 are 2.
  const ExampleRuns runs = MeasureRuns(Street(), 0.25);
  const TypeRuns& house = runs.at(1)[0];
  EXPECT_EQ(house.Complete.size(), 16u + 16u);
  EXPECT_EQ(house.Cut.size(), 64u);
  EXPECT_NEAR(house.EndChance(2, 1), 16.0 / (16 + 64), 1e-12);
  EXPECT_NEAR(house.EndChance(3, 1), 0.0, 1e-12); // no house ends at 3: it goes on
  EXPECT_NEAR(house.EndChance(4, 1), 0.0, 1e-12); // the one 4 long may go on past the edge
  EXPECT_NEAR(house.EndChance(9, 1), 1.0, 1e-12); // longer than any the example shows: it ends
  // The road along x crosses the whole example (cut); its branch along y is 1 across.
  const TypeRuns& road = runs.at(2)[0];
  EXPECT_EQ(road.Cut.size(), 4u * 2u);
  EXPECT_NEAR(road.EndChance(5, 1), 0.0, 1e-12);
  // A gabled roof narrows toward its ridge: only the walls are followed.
  const auto houses = msynth_test::LoadPolyhedra("house.obj");
  const ExampleRuns upright = MeasureRuns(houses.Example, 0.25);
  EXPECT_EQ(upright.size(), 1u);
  EXPECT_EQ(upright.count(1), 1u);
}

TEST(RunEnds, APartFitsWhereTheExamplesRunsFitAndBlocksHoldTheLongest)
{
  // The street's houses along x: 16 complete rows 1 long, 16 complete 2 long, 64 cut at 4.
  const ExampleRuns runs = MeasureRuns(Street(), 0.25);
  const TypeRuns& house = runs.at(1)[0];
  // In a room of 1 only the 16 rows 1 long fit, among the complete rows and the cut ones
  // longer than the room (which go on past the example's edge: they need more).
  EXPECT_NEAR(house.FitChance(1, 0.25), 16.0 / (32 + 64), 1e-12);
  EXPECT_NEAR(house.FitChance(2, 0.25), 32.0 / (32 + 64), 1e-12);
  EXPECT_NEAR(house.FitChance(0.5, 0.25), 0.0, 1e-12); // no house is that narrow
  EXPECT_NEAR(house.FitChance(4, 0.25), 1.0, 1e-12);   // the cut rows may end at 4 as well
  EXPECT_LT(TypeRuns{}.FitChance(3, 1), 0);            // nothing to tell
  EXPECT_NEAR(house.Longest(), 4.0, 1e-12);
  // Blocks twice the longest complete run (the street's: 2), at least 4 spacings.
  EXPECT_EQ(AutomaticBlockSize(runs, 1.0), 4.0);
  EXPECT_EQ(AutomaticBlockSize(runs, 0.25), 16.0);
  EXPECT_EQ(AutomaticBlockSize({}, 1.0), 4.0);
}

TEST(RunEnds, BarsComeOutAsLongAsTheExamplesWithItsChances)
{
  // Bars 5 and 6 long along x (planes a unit apart across x): drawn with the same odds at each
  // vertex, most bars end after a unit or two; with the example's chances, at 5 or 6.
  int points = 0;
  std::string text = Box("bar", 0, 0, 0, 6, 1, 1, points);
  text += Box("bar.001", 1, 2, 0, 6, 3, 1, points);
  text += Box("bar.002", 0, 4, 0, 5, 5, 1, points);
  const PolyhedralExample bars = Model(text);
  const PolyhedralAnalysis analysis = PolyhedralAnalysis::Analyze(bars);
  const PlaneArrangement arrangement(
    analysis.Families(), DefaultArrangementParameters(bars, analysis, { 24, 12, 1 }, 0, {}));
  auto medianLength = [&](bool sizes)
  {
    ContinuousSynthesisOptions o;
    o.Seed = 4;
    o.BlockSize = 0;
    if (sizes)
      o.Runs = MeasureRuns(bars, 0.25);
    const auto result = SynthesizeContinuous(analysis, arrangement, o);
    EXPECT_TRUE(result.Succeeded()) << result.Message;
    const ContinuousMesh mesh = ExtractMesh(analysis, arrangement, result.Labels);
    EXPECT_TRUE(CheckContinuousModel(analysis, mesh, {}).Valid);
    std::vector<double> lengths = MeasureRuns(MeshToModel(mesh, {}), 0.25).at(1)[0].Complete;
    EXPECT_FALSE(lengths.empty());
    std::sort(lengths.begin(), lengths.end());
    return lengths.empty() ? 0.0 : lengths[lengths.size() / 2];
  };
  const double memoryless = medianLength(false);
  const double sized = medianLength(true);
  EXPECT_LE(memoryless, 3.0);
  EXPECT_GE(sized, 4.5);
  EXPECT_LE(sized, 6.5);
}
