// SPDX-License-Identifier: BSD-3-Clause
// The same inputs and seed give the same labels: hashes of the models of eighteen
// configurations (discrete, time-varying, continuous and pattern synthesis), stored here. A change
// of any solver's behaviour (intended or not) changes a hash; restructuring code must not. When a
// behaviour change is intended, say so in the commit and update the hash with the value the failure
// prints.
#include "Continuous/ContinuousMesh.h"
#include "Continuous/ContinuousSynthesis.h"
#include "Discrete/AdjacencyRules.h"
#include "Discrete/DiscreteSynthesis.h"
#include "Discrete/ExampleAnalysis.h"
#include "Discrete/TimeVarying.h"
#include "Formats/TextModel.h"
#include "Formats/Tileset.h"
#include "Patterns/PatternQuality.h"
#include "Patterns/PatternSynthesis.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <map>
#include <string>
#include <vector>

using namespace msynth;

namespace
{
std::string Data(const std::string& relative)
{
  return std::string(MSYNTH_DATA) + "/" + relative;
}

/// FNV-1a over the values, as 16 hexadecimal digits.
template <typename Values>
std::string Hash(const Values& values)
{
  std::uint64_t h = 1469598103934665603ull;
  for (auto v : values)
  {
    const auto u = static_cast<std::uint32_t>(v);
    for (int b = 0; b < 4; ++b)
    {
      h ^= (u >> (8 * b)) & 255u;
      h *= 1099511628211ull;
    }
  }
  char text[17];
  std::snprintf(text, sizeof text, "%016llx", static_cast<unsigned long long>(h));
  return text;
}

const LabelGrid& Village()
{
  static const LabelGrid v = ReadTextModelFile(Data("Examples/Village.txt"), 1 << 20).Grid;
  return v;
}

std::string Discrete(SynthesisOptions o, const LabelGrid& example = Village())
{
  o.Example = &example;
  const SynthesisResult r =
    Synthesize(AdjacencyRules::FromExample(ExampleAnalysis::FromExample(example)), o);
  EXPECT_TRUE(r.Succeeded()) << r.Message;
  return Hash(r.Model.Data());
}

/// Every configuration's hash as stored; a failure prints the line to store.
void ExpectHashes(
  const std::map<std::string, std::string>& got, const std::map<std::string, std::string>& expected)
{
  for (const auto& [name, hash] : got)
  {
    const auto it = expected.find(name);
    EXPECT_TRUE(it != expected.end() && it->second == hash)
      << "    { \"" << name << "\", \"" << hash << "\" },";
  }
}

SynthesisOptions VillageOptions(std::int64_t n, std::int64_t block)
{
  SynthesisOptions o;
  o.Size = { { n, n, 5 } };
  if (block)
    o.BlockSize = { { block, block, 5 } };
  o.Boundary[FaceMinZ] = 1;
  o.Seed = 11;
  return o;
}

/// A 2D grid from text art (top row first), label = index of the character in @p chars.
LabelGrid Art(const std::vector<std::string>& rows, const std::string& chars)
{
  const auto ny = static_cast<std::int64_t>(rows.size());
  const auto nx = static_cast<std::int64_t>(rows[0].size());
  LabelGrid g(nx, ny, 1);
  for (std::int64_t y = 0; y < ny; ++y)
    for (std::int64_t x = 0; x < nx; ++x)
      g.Set(x, y, 0,
        static_cast<Label>(
          chars.find(rows[static_cast<std::size_t>(ny - 1 - y)][static_cast<std::size_t>(x)])));
  return g;
}

/// Every sample of a pattern run, in order, as one hash; each is checked against the exemplars'
/// pairs by PatternQuality, which does not share the solver's code.
std::string Pattern(const std::vector<LabelGrid>& exemplars, const PatternOptions& o)
{
  const PatternResult r = SynthesizePattern(exemplars, o);
  std::vector<Label> all;
  for (const PatternSample& s : r.Samples)
  {
    const auto problems = CheckPatternPairs(exemplars, s.Labels);
    EXPECT_TRUE(problems.empty()) << problems.front();
    all.insert(all.end(), s.Labels.Data().begin(), s.Labels.Data().end());
  }
  EXPECT_EQ(r.Samples.size(), static_cast<std::size_t>(o.Samples));
  return Hash(all);
}

PatternOptions SmallPattern(std::int64_t nx, std::int64_t ny, const std::string& soft)
{
  PatternOptions o;
  o.Size = { { nx, ny, 1 } };
  o.SoftFactors = ParseStencils(soft);
  o.Seed = 7;
  o.BurnIn = 1;
  o.Samples = 2;
  return o;
}
} // namespace

TEST(OutputHashes, DiscreteConfigurations)
{
  std::map<std::string, std::string> got;
  got["whole model"] = Discrete(VillageOptions(24, 0));
  got["blocks"] = Discrete(VillageOptions(40, 10));
  {
    SynthesisOptions o = VillageOptions(40, 10);
    o.Threads = 2;
    got["blocks, 2 threads"] = Discrete(o);
  }
  {
    SynthesisOptions o = VillageOptions(30, 10);
    o.Order = SiteOrder::MinimumEntropy;
    o.Choice = LabelChoice::Frequency;
    got["entropy order, frequency"] = Discrete(o);
  }
  {
    SynthesisOptions o = VillageOptions(20, 0);
    o.Choice = LabelChoice::Resemblance;
    got["resemblance"] = Discrete(o);
  }
  {
    SynthesisOptions o = VillageOptions(30, 10);
    o.Symmetry[0].Enabled = true;
    got["mirror x"] = Discrete(o);
  }
  {
    SynthesisOptions o = VillageOptions(30, 10);
    o.Boundary = {};
    o.Translate[0].Enabled = o.Translate[1].Enabled = true;
    got["translation (tileable)"] = Discrete(o);
  }
  {
    SynthesisOptions o = VillageOptions(30, 10);
    GuideVolume g;
    g.Dims = { { 2, 1, 1 } };
    g.Weights[2] = { 0.0f, 3.0f };
    g.Weights[3] = { 0.0f, 3.0f };
    o.Guide = g;
    got["guide"] = Discrete(o);
  }
  {
    SynthesisOptions o = VillageOptions(40, 10);
    o.Soft.TargetFractions[2] = 0.2;
    got["soft constraint"] = Discrete(o);
  }
  {
    const Tileset t = ReadTilesetFile(Data("Tilesets/Lines.xml"));
    SynthesisOptions o;
    o.Size = { { 16, 16, 1 } };
    o.Seed = 4;
    o.Rotate.Enabled = true;
    o.Rotate.Map = t.TurnMap();
    const SynthesisResult r = Synthesize(t.Rules(), o);
    EXPECT_TRUE(r.Succeeded()) << r.Message;
    got["tileset, rotation"] = Hash(r.Model.Data());
  }
  const std::map<std::string, std::string> expected = {
    { "blocks", "e828281039733461" },
    { "blocks, 2 threads", "e828281039733461" },
    { "entropy order, frequency", "03b3ed502cc4e113" },
    { "guide", "e85c7ab609ce2a13" },
    { "mirror x", "d445252d36e62843" },
    { "resemblance", "49a04552b9867723" },
    { "soft constraint", "41227582726751a0" },
    { "tileset, rotation", "143d35ee984b5263" },
    { "translation (tileable)", "0489373d9cc17bf2" },
    { "whole model", "0ea5ad63dafc7712" },
  };
  ExpectHashes(got, expected);
}

TEST(OutputHashes, TimeVaryingAndContinuous)
{
  std::map<std::string, std::string> got;
  {
    // A ball rolling along x: frames are z slices of a 6 x 1 x 6 grid.
    LabelGrid slices(6, 1, 6, 0);
    for (std::int64_t t = 0; t < 6; ++t)
      slices.Set(t, 0, t, 1);
    const TimeVaryingGrid example = TimeVaryingGrid::FromSlices(slices);
    TimeVaryingOptions o;
    o.Size = { { 12, 1, 1, 10 } };
    o.Seed = 5;
    o.Loop = false;
    const TimeVaryingResult r = SynthesizeTimeVarying(TimeVaryingRules::FromExample(example), o);
    EXPECT_TRUE(r.Succeeded()) << r.Message;
    std::vector<Label> all;
    for (const auto& f : r.Model.Frames)
      all.insert(all.end(), f.Data().begin(), f.Data().end());
    got["time-varying"] = Hash(all);
  }
  {
    PolyhedralExample e = ReadOBJExample(Data("Continuous/house.obj"));
    ValidateExample(e);
    const PolyhedralAnalysis a = PolyhedralAnalysis::Analyze(e);
    const ArrangementParameters p = DefaultArrangementParameters(e, a, { 18, 18, 8 }, 0, {});
    const PlaneArrangement arrangement(a.Families(), p);
    ContinuousSynthesisOptions o;
    o.Seed = 7;
    o.BlockSize = 4;
    const ContinuousSynthesisResult r = SynthesizeContinuous(a, arrangement, o);
    EXPECT_TRUE(r.Succeeded()) << r.Message;
    got["continuous house, blocks"] = Hash(r.Labels);
    o.Constraints.KeepProportions = false; // the uniform draw of the dissertation
    got["continuous house, blocks, uniform"] = Hash(SynthesizeContinuous(a, arrangement, o).Labels);
    o.Constraints.Grounded = true;
    o.Constraints.Thickness.push_back({ 1, FamilyAlongAxis(a.Families(), 2), 1, {} });
    got["continuous house, grounded, walls one spacing high"] =
      Hash(SynthesizeContinuous(a, arrangement, o).Labels);
    // Several blocks per phase (16 blocks, 9 phases), run on two threads.
    const PlaneArrangement larger(
      a.Families(), DefaultArrangementParameters(e, a, { 32, 32, 8 }, 0, {}));
    ContinuousSynthesisOptions phased;
    phased.Seed = 7;
    phased.BlockSize = 4;
    phased.Threads = 2;
    phased.Constraints.Grounded = true;
    got["continuous house, grounded, blocks in phases"] =
      Hash(SynthesizeContinuous(a, larger, phased).Labels);
  }
  const std::map<std::string, std::string> expected = {
    { "continuous house, blocks", "563513aa0e02963b" },
    { "continuous house, blocks, uniform", "9a403552fe60dd2b" },
    { "continuous house, grounded, walls one spacing high", "85ae7bd83af329ac" },
    { "continuous house, grounded, blocks in phases", "e3cc41e42fda359c" },
    { "time-varying", "f1eeebd4ae9d53c2" },
  };
  ExpectHashes(got, expected);
}

TEST(OutputHashes, PatternConfigurations)
{
  // A rectangular facade with windows and a door (cf. Data/Patterns/Facade).
  const std::vector<LabelGrid> facade{ Art(
    { "............", "............", "------------", "############", "#T##T##T##T#",
      "#W##W##W##W#", "#W##W##W##W#", "#_##_##_##_#", "############", "#T##D##T##T#",
      "#W##d##W##W#", "#W##d##W##W#", "#_##d##_##_#", "============" },
    ".-#TW_Dd=") };
  // A framed border (cf. Data/Patterns/Border): corners, edges and curls that mirror in x.
  const std::vector<LabelGrid> border{ Art(
    { "1==========2", "[(o)....(o)]", "[..........]", "[o........o]", "[..........]",
      "[..........]", "[o........o]", "[..........]", "[(o)....(o)]", "3__________4" },
    ".=_[]1234o()") };
  std::map<std::string, std::string> got;
  got["pattern BLOCKSS, 4H 4V"] = Pattern(facade, SmallPattern(16, 13, "4H,4V"));
  {
    PatternOptions o = SmallPattern(12, 10, "");
    o.Method = PatternMethod::ConstraintSolver;
    got["pattern constraint solver"] = Pattern(facade, o);
  }
  {
    PatternOptions o = SmallPattern(10, 8, "");
    o.Method = PatternMethod::MetropolisHastings;
    o.Samples = 1;
    got["pattern Metropolis-Hastings"] = Pattern(facade, o);
  }
  {
    PatternOptions o = SmallPattern(15, 10, "3x3");
    o.Samples = 1;
    o.Mirror[0] = true;
    o.MirrorMap = { { 3, 4 }, { 4, 3 }, { 5, 6 }, { 6, 5 }, { 7, 8 }, { 8, 7 }, { 10, 11 },
      { 11, 10 } };
    // The ring is the frame (zone 1), the inside anything else (zone 0).
    o.SiteZone.assign(15 * 10, 0);
    for (std::int64_t y = 0; y < 10; ++y)
      for (std::int64_t x = 0; x < 15; ++x)
        if (x == 0 || y == 0 || x == 14 || y == 9)
          o.SiteZone[static_cast<std::size_t>(x + 15 * y)] = 1;
    o.ZoneTiles[1] = { 1, 2, 3, 4, 5, 6, 7, 8 };
    o.ZoneTiles[0] = { 0, 9, 10, 11 };
    got["pattern mirrored x, zones"] = Pattern(border, o);
  }
  const std::map<std::string, std::string> expected = {
    { "pattern BLOCKSS, 4H 4V", "29e562f9eb86d646" },
    { "pattern Metropolis-Hastings", "bee838d5f25909d3" },
    { "pattern constraint solver", "7ff06c42ea8886c7" },
    { "pattern mirrored x, zones", "636243cbdb45a425" },
  };
  ExpectHashes(got, expected);
}
