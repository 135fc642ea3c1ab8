// SPDX-License-Identifier: BSD-3-Clause
// D§3.3.8: converting a fallible example to an infallible one (Discrete/InfallibleRefinement).
#include "Fixtures.h"

#include "Core/Error.h"
#include "Discrete/ConsistencyCheck.h"
#include "Discrete/InfallibleRefinement.h"

#include <gtest/gtest.h>

#include <set>

using namespace msynth;
using msynth_test::Grid2D;

namespace
{
// Data/Examples/Fallible-Fig3.5a.vti and Fallible-Fig3.6a.vti (Utilities/make-test-data.py).
LabelGrid Fig35a()
{
  return Grid2D({ { 0, 0, 0, 0, 0, 0, 0, 0, 0, 0 }, { 0, 3, 4, 5, 0, 0, 7, 4, 5, 0 },
    { 0, 2, 0, 6, 0, 0, 2, 1, 6, 0 }, { 8, 8, 8, 8, 8, 8, 8, 8, 8, 8 } });
}
LabelGrid Fig36a()
{
  return Grid2D({ { 0, 0, 0, 0, 0, 0, 0 }, { 0, 0, 4, 1, 5, 0, 0 }, { 0, 0, 2, 3, 2, 0, 0 },
    { 6, 6, 6, 6, 6, 6, 6 } });
}
const std::array<std::int64_t, 3> Plane{ { 64, 64, 1 } };

std::vector<std::pair<Label, Label>> Renamed(const LabelMap& f)
{
  std::vector<std::pair<Label, Label>> out;
  for (const auto& p : f)
    if (p.first != p.second)
      out.push_back(p);
  return out;
}
} // namespace

TEST(InfallibleRefinement, Figure35aBecomesFigure315)
{
  // Eq. 3.12: E_I is E with the one 0 between a 2 and its 6 made a 9.
  const LabelGrid e = Fig35a();
  const auto r = FindInfallibleRefinement(e, Plane);
  ASSERT_TRUE(r.Found) << r.Summary;
  EXPECT_FALSE(r.Steps.front().Proved); // E itself is not proved
  EXPECT_TRUE(r.Report.Proved);
  EXPECT_EQ(Renamed(r.Map), (std::vector<std::pair<Label, Label>>{ { 9, 0 } }));
  EXPECT_EQ(MapLabels(r.Refined, r.Map), e); // f(E_I) = E
  int changed = 0;
  for (std::size_t i = 0; i < e.Data().size(); ++i)
    changed += e.Data()[i] != r.Refined.Data()[i];
  EXPECT_EQ(changed, 1);
  EXPECT_EQ(r.Refined.At(2, 1, 0), 9);
  EXPECT_TRUE(r.Check.Holds);
  EXPECT_GE(r.Check.Sizes, 9);
  EXPECT_NE(r.Summary.find("label 0 by -x=2"), std::string::npos) << r.Summary;
}

TEST(InfallibleRefinement, Figure36aIsConverted)
{
  const LabelGrid e = Fig36a();
  const auto r = FindInfallibleRefinement(e, Plane);
  ASSERT_TRUE(r.Found) << r.Summary;
  EXPECT_FALSE(r.Steps.front().Proved);
  const auto renamed = Renamed(r.Map);
  ASSERT_EQ(renamed.size(), 1u);
  EXPECT_EQ(renamed[0].second, 2); // the two ends of a pair become two labels
  EXPECT_EQ(MapLabels(r.Refined, r.Map), e);
  EXPECT_NE(r.Refined.At(2, 1, 0), r.Refined.At(4, 1, 0));
}

TEST(InfallibleRefinement, WholeRunsOnTheRefinementNeverFail)
{
  // Algorithm 3.1 on E_I with one attempt and no backtracking, over 20 seeds and sizes; each
  // model mapped back is consistent with the ORIGINAL example by the independent check.
  for (const LabelGrid& e : { Fig35a(), Fig36a() })
  {
    std::set<Label> seen;
    for (std::uint64_t seed = 0; seed < 20; ++seed)
    {
      SynthesisOptions o;
      o.Size = { { 12 + static_cast<std::int64_t>(seed % 9),
        8 + static_cast<std::int64_t>(seed % 5), 1 } };
      o.Seed = seed;
      const SynthesisResult m = SynthesizeViaInfallible(e, o);
      ASSERT_TRUE(m.Succeeded()) << "seed " << seed << ": " << m.Message;
      EXPECT_EQ(m.Statistics.BlocksFailed, 0);
      const auto check = CheckConsistency(e, m.Model);
      EXPECT_TRUE(check.Consistent) << "seed " << seed;
      seen.insert(m.Model.Data().begin(), m.Model.Data().end());
      EXPECT_NE(m.Message.find("infallible refinement"), std::string::npos);
    }
    EXPECT_TRUE(seen.count(2)) << "no structure was ever made";
    for (Label v : seen)
      EXPECT_LT(v, 9) << "a label of E_I was not mapped back";
  }
}

TEST(InfallibleRefinement, Equation313CheckFindsLostModels)
{
  // A line of 1s whose first 1 is split off: "0 1 0" is consistent with E but has no
  // counterpart, also away from the faces.
  const LabelGrid e = Grid2D({ { 0, 0, 0, 0, 0 }, { 0, 1, 1, 1, 0 }, { 0, 0, 0, 0, 0 } });
  LabelGrid split = e;
  split.Set(1, 1, 0, 2);
  const LabelMap f{ { 0, 0 }, { 1, 1 }, { 2, 1 } };
  const auto framed = CheckEquation313(e, split, f, Plane, 1);
  EXPECT_FALSE(framed.Holds);
  EXPECT_NE(framed.Text.find("no counterpart"), std::string::npos);
  // The identity keeps every model.
  const auto same = CheckEquation313(e, e, { { 0, 0 }, { 1, 1 } }, Plane, 0);
  EXPECT_TRUE(same.Holds);
  EXPECT_GE(same.Sizes, 9) << same.Text;
  // Fig. 3.15's refinement keeps every model away from the faces, not at them (a structure cut
  // by a face: "2 0 0" in one row).
  const auto r = FindInfallibleRefinement(Fig35a(), Plane);
  EXPECT_TRUE(CheckEquation313(Fig35a(), r.Refined, r.Map, Plane, 1).Holds);
  EXPECT_FALSE(CheckEquation313(Fig35a(), r.Refined, r.Map, Plane, 0).Holds);
}

TEST(InfallibleRefinement, ProvedExamplesAreTheirOwnRefinement)
{
  const LabelGrid board = Grid2D({ { 0, 1, 0 }, { 1, 0, 1 }, { 0, 1, 0 } });
  const auto r = FindInfallibleRefinement(board, Plane);
  ASSERT_TRUE(r.Found);
  EXPECT_EQ(r.Steps.size(), 1u);
  EXPECT_EQ(r.Refined, board);
  EXPECT_TRUE(Renamed(r.Map).empty());
}

TEST(InfallibleRefinement, NotFoundIsReportedAndRefused)
{
  // The fixture Algorithm 3.1 fails on (TestInfallibility): no split of this search proves it.
  const LabelGrid e =
    Grid2D({ { 0, 0, 0, 0, 0, 0, 0, 0 }, { 0, 0, 0, 0, 5, 1, 4, 0 }, { 0, 0, 0, 5, 7, 3, 4, 0 },
      { 0, 3, 1, 6, 7, 6, 2, 0 }, { 0, 0, 0, 5, 7, 6, 3, 0 }, { 0, 0, 0, 0, 0, 0, 0, 0 } });
  RefinementOptions some;
  some.MaxCandidates = 30;
  const auto r = FindInfallibleRefinement(e, { { 24, 24, 1 } }, some);
  EXPECT_FALSE(r.Found);
  EXPECT_EQ(r.Steps.size(), 31u);
  EXPECT_NE(r.Summary.find("no refinement"), std::string::npos);
  SynthesisOptions o;
  o.Size = { { 24, 24, 1 } };
  try
  {
    some.MaxCandidates = 5;
    SynthesizeViaInfallible(e, o, some);
    ADD_FAILURE() << "no error";
  }
  catch (const Error& error)
  {
    EXPECT_NE(std::string(error.what()).find("no infallible refinement"), std::string::npos);
  }
}

TEST(InfallibleRefinement, OptionsOfBlocksOrOtherOrdersAreRefused)
{
  SynthesisOptions blocks;
  blocks.Size = { { 20, 20, 1 } };
  blocks.BlockSize = { { 8, 8, 1 } };
  EXPECT_THROW(SynthesizeViaInfallible(Fig35a(), blocks), Error);
  SynthesisOptions random;
  random.Size = { { 20, 20, 1 } };
  random.Order = SiteOrder::Random;
  EXPECT_THROW(SynthesizeViaInfallible(Fig35a(), random), Error);
  EXPECT_THROW(MapLabels(LabelGrid(2, 2, 1, 42), { { 0, 0 } }), Error);
}

TEST(InfallibleRefinement, TheSearchIsDeterministic)
{
  const auto a = FindInfallibleRefinement(Fig36a(), Plane);
  const auto b = FindInfallibleRefinement(Fig36a(), Plane);
  EXPECT_EQ(a.Refined, b.Refined);
  EXPECT_EQ(a.Map, b.Map);
  ASSERT_EQ(a.Steps.size(), b.Steps.size());
  for (std::size_t i = 0; i < a.Steps.size(); ++i)
    EXPECT_EQ(a.Steps[i].Split, b.Steps[i].Split);
}
