// SPDX-License-Identifier: BSD-3-Clause
#include "Discrete/SoftConstraints.h"

#include "Core/Error.h"
#include "Core/Index.h"
#include "Core/Random.h"

#include <cmath>
#include <string>

namespace msynth
{
namespace detail
{

SoftConstraints::SoftConstraints(const AdjacencyRules& rules, const SynthesisOptions& options,
  SharedModel& shared, const Coord& n, std::size_t blocks, SynthesisStatistics& stats)
  : Rules(rules)
  , Options(options.Soft)
  , Seed(options.Seed)
  , Shared(shared)
  , N(n)
  , Stats(stats)
{
  if (!this->Options.Active())
    return;
  const int k = rules.NumberOfLabels();
  this->Target.assign(ToIndex(k), -1.0);
  this->Counts.assign(ToIndex(k), 0);
  this->Saved.resize(blocks);
  for (const auto& kv : this->Options.TargetFractions)
  {
    const int b = rules.IndexOf(kv.first);
    if (b < 0)
      throw Error("the soft constraint names label " + std::to_string(kv.first) +
        ", which does not occur in the example");
    if (!(kv.second >= 0.0 && kv.second <= 1.0))
      throw Error("the target fraction of label " + std::to_string(kv.first) + " is not in [0, 1]");
    this->Target[ToIndex(b)] = kv.second;
  }
  if (!(this->Options.Temperature > 0.0) || !std::isfinite(this->Options.Temperature))
    throw Error("the soft constraints' temperature must be positive");
  for (std::int32_t b : shared.Model)
    ++this->Counts[ToIndex(b)];
  if (this->Options.Fitness)
    this->Fitness = this->Options.Fitness(this->ModelGrid());
}

void SoftConstraints::Save(std::size_t i, const Block& block)
{
  if (!this->Options.Active())
    return;
  auto& saved = this->Saved[i];
  saved.clear();
  ForEachSite(block, this->N,
    [&](std::size_t s)
    {
      saved.push_back(this->Shared.Model[s]);
      saved.push_back(this->Shared.LastBlock[s]);
    });
}

bool SoftConstraints::Decide(std::size_t i, const Block& block)
{
  if (!this->Options.Active())
    return true;
  const int k = this->Rules.NumberOfLabels();
  std::vector<std::int64_t> delta(ToIndex(k), 0);
  const std::vector<std::int32_t>& saved = this->Saved[i];
  std::size_t at = 0;
  ForEachSite(block, this->N,
    [&](std::size_t s)
    {
      --delta[ToIndex(saved[at])];
      ++delta[ToIndex(this->Shared.Model[s])];
      at += 2;
    });
  double dE = 0.0;
  for (int b = 0; b < k; ++b)
  {
    const auto c = this->Counts[ToIndex(b)];
    const auto d = delta[ToIndex(b)];
    if (d != 0)
      dE += this->Energy(b, c + d) - this->Energy(b, c);
  }
  double ratio = std::exp(-dE / this->Options.Temperature);
  double fitness = this->Fitness;
  if (this->Options.Fitness)
  {
    fitness = this->Options.Fitness(this->ModelGrid());
    if (!(fitness > 0.0) || !(this->Fitness > 0.0))
      throw Error("the soft constraints' fitness must be positive");
    ratio *= fitness / this->Fitness;
  }
  Random rng =
    Random::Derived(this->Seed, static_cast<std::uint64_t>(block.Index), 0x50f7ull << 32);
  if (ratio >= 1.0 || rng.Uniform() < ratio)
  {
    for (int b = 0; b < k; ++b)
      this->Counts[ToIndex(b)] += delta[ToIndex(b)];
    this->Fitness = fitness;
    return true;
  }
  at = 0;
  ForEachSite(block, this->N,
    [&](std::size_t s)
    {
      this->Shared.Model[s] = saved[at++];
      this->Shared.LastBlock[s] = saved[at++];
    });
  ++this->Stats.BlocksRejected;
  return false;
}

double SoftConstraints::Energy(int b, std::int64_t count) const
{
  const double t = this->Target[ToIndex(b)];
  const auto sites = static_cast<double>(this->Shared.Model.size());
  return t < 0.0 ? 0.0 : sites * (double(count) / sites - t) * (double(count) / sites - t);
}

LabelGrid SoftConstraints::ModelGrid() const
{
  std::vector<Label> values(this->Shared.Model.size());
  for (std::size_t i = 0; i < values.size(); ++i)
    values[i] = this->Rules.LabelValues()[ToIndex(this->Shared.Model[i])];
  return LabelGrid(this->N, std::move(values));
}

} // namespace detail
} // namespace msynth
