// SPDX-License-Identifier: BSD-3-Clause
// The network's components kept up to date box by box (Discrete/NetworkParts.h), as the repairs of
// a connected network use them: after every rewritten box, the proposed counts and, once applied,
// the components' sites, sizes and boxes are compared with a flood of the whole model
// (FindComponents) and a count of the test's own, on random models in 2D and 3D with a label that
// connects through two sides only, listed path sites and a path label.
#include "Discrete/BlockSolver.h"
#include "Discrete/Connectivity.h"
#include "Discrete/NetworkComponents.h"
#include "Discrete/NetworkParts.h"

#include <gtest/gtest.h>

#include <limits>
#include <map>
#include <random>
#include <vector>

using namespace msynth;
using detail::Block;
using detail::Coord;

namespace
{
struct Truth
{
  std::vector<detail::Component> Parts;
  std::vector<std::int32_t> Ids;
  std::int64_t Outside = 0, PathParts = 0, PathLabelSites = 0;
};

/// The whole model flooded again, and the path's figures counted directly.
Truth Recount(const detail::NetworkRule& rule, const std::vector<std::int32_t>& model,
  const Coord& n, const std::vector<std::int64_t>& listed, std::int32_t pathLabel)
{
  Truth t;
  t.Parts = detail::FindComponents(rule, model, n, &t.Ids);
  std::vector<char> holds(t.Parts.size(), 0);
  for (std::size_t s = 0; s < model.size(); ++s)
  {
    t.PathLabelSites += model[s] == pathLabel ? 1 : 0;
    if (t.Ids[s] != 0 && model[s] == pathLabel)
      holds[ToIndex(t.Ids[s] - 1)] = 1;
  }
  for (std::int64_t s : listed)
  {
    if (t.Ids[ToIndex(s)] == 0)
      ++t.Outside;
    else
      holds[ToIndex(t.Ids[ToIndex(s)] - 1)] = 1;
  }
  for (char h : holds)
    t.PathParts += h;
  return t;
}

void RunBoxes(const Coord& n, std::uint32_t seed)
{
  // Labels 0 (space), 1 (joins through every side), 2 (joins through its x sides only; the path
  // label). Every pair is allowed: the components come from the sides alone.
  std::array<std::vector<std::pair<int, int>>, 3> pairs;
  for (auto& axis : pairs)
    for (int b = 0; b < 3; ++b)
      for (int c = 0; c < 3; ++c)
        axis.emplace_back(b, c);
  const AdjacencyRules rules = AdjacencyRules::FromPairs({ 0, 1, 2 }, { 1, 1, 1 }, pairs);
  ConnectedNetwork network;
  network.Values = { 1, 2 };
  network.Sides[2] = 3; // toward +x and -x
  network.PathLabels = { 2 };
  const detail::NetworkRule rule(rules, network);

  std::mt19937 rng(seed);
  const std::int64_t total = n[0] * n[1] * n[2];
  auto draw = [&]()
  {
    const int r = static_cast<int>(rng() % 100);
    return r < 45 ? 0 : (r < 85 ? 1 : 2);
  };
  std::vector<std::int32_t> model(ToIndex(total));
  for (auto& b : model)
    b = draw();
  const std::vector<std::int64_t> listed = { 0, total / 3, total / 2, total - 1 };
  detail::NetworkParts parts(rule, model, n, listed);

  int exact = 0, applied = 0;
  for (int round = 0; round < 400; ++round)
  {
    Block box;
    box.Index = round;
    for (std::size_t a = 0; a < 3; ++a)
    {
      box.Dims[a] = 1 +
        static_cast<std::int64_t>(
          rng() % static_cast<std::uint32_t>(std::min<std::int64_t>(n[a], 8)));
      box.Origin[a] =
        static_cast<std::int64_t>(rng() % static_cast<std::uint32_t>(n[a] - box.Dims[a] + 1));
    }
    std::vector<std::int32_t> before;
    detail::ForEachSite(box, n,
      [&](std::size_t s)
      {
        before.push_back(model[s]);
        model[s] = draw();
      });
    const detail::NetworkParts::Outcome o = parts.Propose(box, before);
    const Truth t = Recount(rule, model, n, listed, 2);
    if (o.Components != std::numeric_limits<std::int64_t>::max())
    {
      ++exact;
      ASSERT_EQ(o.Components, static_cast<std::int64_t>(t.Parts.size())) << "round " << round;
      ASSERT_EQ(o.PathParts, t.PathParts) << "round " << round;
    }
    ASSERT_EQ(o.PathSitesOutside, t.Outside) << "round " << round;
    ASSERT_EQ(o.PathLabelSites, t.PathLabelSites) << "round " << round;
    if (o.Components == std::numeric_limits<std::int64_t>::max() || rng() % 3 == 0)
    {
      std::size_t i = 0; // not taken: the model goes back
      detail::ForEachSite(box, n, [&](std::size_t s) { model[s] = before[i++]; });
      continue;
    }
    parts.Apply();
    ++applied;
    // The same partition of the sites, the same sizes, and boxes that hold their components.
    ASSERT_EQ(parts.Count(), static_cast<std::int64_t>(t.Parts.size()));
    ASSERT_EQ(parts.BySize().size(), t.Parts.size());
    ASSERT_EQ(parts.PathParts(), t.PathParts);
    std::map<std::int32_t, std::int32_t> toTruth, fromTruth;
    for (std::int64_t s = 0; s < total; ++s)
    {
      const std::int32_t mine = parts.Ids()[ToIndex(s)], theirs = t.Ids[ToIndex(s)];
      ASSERT_EQ(mine == 0, theirs == 0) << "site " << s << ", round " << round;
      if (mine == 0)
        continue;
      ASSERT_EQ(toTruth.emplace(mine, theirs).first->second, theirs) << "site " << s;
      ASSERT_EQ(fromTruth.emplace(theirs, mine).first->second, mine) << "site " << s;
      const detail::Component& c = parts.Parts()[ToIndex(mine - 1)];
      const Coord p{ { s % n[0], (s / n[0]) % n[1], s / (n[0] * n[1]) } };
      for (std::size_t a = 0; a < 3; ++a)
        ASSERT_TRUE(c.Low[a] <= p[a] && p[a] <= c.High[a]) << "site " << s << " outside its box";
    }
    for (const auto& [mine, theirs] : toTruth)
      ASSERT_EQ(parts.Parts()[ToIndex(mine - 1)].Sites, t.Parts[ToIndex(theirs - 1)].Sites);
  }
  EXPECT_GT(exact, 300); // the walk's bound rarely cuts a proposal short at these sizes
  EXPECT_GT(applied, 150);
}
} // namespace

TEST(NetworkParts, FollowTheWholeModelsComponentsIn2D)
{
  RunBoxes({ { 48, 40, 1 } }, 1);
}

TEST(NetworkParts, FollowTheWholeModelsComponentsIn3D)
{
  RunBoxes({ { 16, 14, 6 } }, 2);
}
