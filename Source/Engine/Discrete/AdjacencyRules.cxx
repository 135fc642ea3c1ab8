// SPDX-License-Identifier: BSD-3-Clause
#include "Discrete/AdjacencyRules.h"

#include "Core/Error.h"

#include <algorithm>
#include <cmath>

namespace msynth
{

void AdjacencyRules::Allow(int axis, int b, int c)
{
  // c may follow b along +axis, so b may precede c along -axis.
  this->AllowOne(2 * axis, b, c);
  this->AllowOne(2 * axis + 1, c, b);
}

AdjacencyRules AdjacencyRules::FromExample(const ExampleAnalysis& analysis)
{
  AdjacencyRules rules;
  rules.Allocate(analysis.NumberOfLabels());
  rules.Values = analysis.Labels();
  rules.LabelWeights.reserve(analysis.LabelCounts().size());
  for (auto n : analysis.LabelCounts())
  {
    rules.LabelWeights.push_back(static_cast<double>(n));
  }
  for (int axis = 0; axis < 3; ++axis)
  {
    for (const auto& t : analysis.Transitions(axis))
    {
      rules.Allow(axis, t.From, t.To);
    }
  }
  rules.Finish();
  return rules;
}

AdjacencyRules AdjacencyRules::FromPairs(std::vector<Label> values, std::vector<double> weights,
  const std::array<std::vector<std::pair<int, int>>, 3>& pairs)
{
  AdjacencyRules rules;
  const int k = static_cast<int>(values.size());
  rules.Allocate(k);
  if (weights.size() != values.size())
  {
    throw Error("adjacency rules: " + std::to_string(values.size()) + " labels but " +
      std::to_string(weights.size()) + " weights");
  }
  for (std::size_t i = 1; i < values.size(); ++i)
  {
    if (values[i - 1] >= values[i])
    {
      throw Error("adjacency rules: label values must be given in ascending order, once each");
    }
  }
  for (std::size_t i = 0; i < weights.size(); ++i)
  {
    if (!(weights[i] > 0.0) || !std::isfinite(weights[i]))
    {
      throw Error("adjacency rules: label " + std::to_string(values[i]) +
        " has a weight that is not positive and finite");
    }
  }
  for (int axis = 0; axis < 3; ++axis)
  {
    for (const auto& p : pairs[axis])
    {
      if (p.first < 0 || p.first >= k || p.second < 0 || p.second >= k)
      {
        throw Error("adjacency rules: pair (" + std::to_string(p.first) + ", " +
          std::to_string(p.second) + ") names a label index outside 0.." + std::to_string(k - 1));
      }
      rules.Allow(axis, p.first, p.second);
    }
  }
  rules.Values = std::move(values);
  rules.LabelWeights = std::move(weights);
  rules.Finish();
  return rules;
}

int AdjacencyRules::IndexOf(Label value) const
{
  return IndexOfLabel(this->Values, value);
}

bool AdjacencyRules::SelfAdjacent(int b, const std::array<std::int64_t, 3>& outputSize) const
{
  for (int axis = 0; axis < 3; ++axis)
  {
    if (outputSize[axis] > 1 && !this->Allowed(2 * axis, b, b))
    {
      return false;
    }
  }
  return true;
}

} // namespace msynth
