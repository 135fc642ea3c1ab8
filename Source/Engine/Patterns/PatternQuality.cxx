// SPDX-License-Identifier: BSD-3-Clause
#include "Patterns/PatternQuality.h"
#include "Core/Index.h"

#include <cmath>
#include <limits>
#include <set>
#include <utility>

namespace msynth
{

ConfigurationHistogram CountConfigurations(
  const std::vector<LabelGrid>& grids, const Stencil& shape)
{
  ConfigurationHistogram histogram;
  std::vector<Label> config(shape.Offsets.size());
  for (const LabelGrid& g : grids)
  {
    const auto& d = g.Dimensions();
    for (std::int64_t z = 0; z + shape.Extent[2] <= d[2]; ++z)
      for (std::int64_t y = 0; y + shape.Extent[1] <= d[1]; ++y)
        for (std::int64_t x = 0; x + shape.Extent[0] <= d[0]; ++x)
        {
          for (std::size_t k = 0; k < shape.Offsets.size(); ++k)
            config[k] =
              g.At(x + shape.Offsets[k][0], y + shape.Offsets[k][1], z + shape.Offsets[k][2]);
          ++histogram[config];
        }
  }
  return histogram;
}

double KLDivergence(const ConfigurationHistogram& model, const ConfigurationHistogram& exemplars)
{
  std::int64_t modelTotal = 0, exemplarTotal = 0;
  for (const auto& entry : model)
    modelTotal += entry.second;
  if (modelTotal == 0)
    return 0.0;
  for (const auto& entry : exemplars)
    exemplarTotal += entry.second;
  std::size_t unionSize = exemplars.size();
  for (const auto& entry : model)
    if (!exemplars.count(entry.first))
      ++unionSize;
  const double denominator =
    static_cast<double>(exemplarTotal + static_cast<std::int64_t>(unionSize));
  double kl = 0.0;
  for (const auto& [config, count] : model)
  {
    const auto it = exemplars.find(config);
    const double f = static_cast<double>(count) / static_cast<double>(modelTotal);
    const double g =
      (static_cast<double>(it == exemplars.end() ? 0 : it->second) + 1.0) / denominator;
    kl += f * std::log(f / g);
  }
  return kl;
}

double PatternKL(
  const std::vector<LabelGrid>& exemplars, const LabelGrid& model, const Stencil& shape)
{
  return KLDivergence(CountConfigurations({ model }, shape), CountConfigurations(exemplars, shape));
}

double PatternLogProbability(const std::vector<LabelGrid>& exemplars, const LabelGrid& model,
  const std::vector<Stencil>& softShapes, double epsilon)
{
  if (!CheckPatternPairs(exemplars, model, 1).empty())
    return -std::numeric_limits<double>::infinity();
  std::int64_t satisfied = 0;
  for (const Stencil& s : softShapes)
  {
    const ConfigurationHistogram seen = CountConfigurations(exemplars, s);
    for (const auto& [config, count] : CountConfigurations({ model }, s))
      if (seen.count(config))
        satisfied += count;
  }
  return static_cast<double>(satisfied) * std::log1p(epsilon);
}

std::vector<std::string> CheckPatternPairs(const std::vector<LabelGrid>& exemplars,
  const LabelGrid& model, std::size_t limit, const LabelPairs& extra)
{
  std::set<std::pair<Label, Label>> seen[3];
  for (int a = 0; a < 3; ++a)
    seen[a].insert(extra[ToIndex(a)].begin(), extra[ToIndex(a)].end());
  for (const LabelGrid& g : exemplars)
    for (std::int64_t z = 0; z < g.Size(2); ++z)
      for (std::int64_t y = 0; y < g.Size(1); ++y)
        for (std::int64_t x = 0; x < g.Size(0); ++x)
        {
          if (x + 1 < g.Size(0))
            seen[0].emplace(g.At(x, y, z), g.At(x + 1, y, z));
          if (y + 1 < g.Size(1))
            seen[1].emplace(g.At(x, y, z), g.At(x, y + 1, z));
          if (z + 1 < g.Size(2))
            seen[2].emplace(g.At(x, y, z), g.At(x, y, z + 1));
        }
  std::vector<std::string> problems;
  for (std::int64_t z = 0; z < model.Size(2); ++z)
    for (std::int64_t y = 0; y < model.Size(1); ++y)
      for (std::int64_t x = 0; x < model.Size(0); ++x)
        for (int a = 0; a < 3; ++a)
        {
          const std::int64_t q[3] = { x + (a == 0), y + (a == 1), z + (a == 2) };
          if (!model.Contains(q[0], q[1], q[2]))
            continue;
          const Label b = model.At(x, y, z), c = model.At(q[0], q[1], q[2]);
          if (seen[a].count({ b, c }))
            continue;
          if (problems.size() < limit)
            problems.push_back("site (" + std::to_string(x) + ", " + std::to_string(y) + ", " +
              std::to_string(z) + "): label " + std::to_string(c) + " after " + std::to_string(b) +
              " along " + "xyz"[a] + " occurs in no exemplar");
          else
            return problems;
        }
  return problems;
}

} // namespace msynth
