// SPDX-License-Identifier: BSD-3-Clause
// "Generate several, keep the best match" (TVCG §4.7) over whole models, and the match error
// that ranks them.
#include "Continuous/ConstraintPlan.h"
#include "Continuous/ContinuousSynthesis.h"
#include "Core/Error.h"
#include "Core/Index.h"

#include <chrono>
#include <cmath>
#include <limits>
#include <sstream>

namespace msynth
{
namespace detail
{

double ConstraintPlan::MatchError(const std::vector<std::int32_t>& labels) const
{
  const std::size_t nt = this->Types.size();
  std::vector<double> tally(nt, 0.0), fit(nt, 0.0);
  std::vector<float> highest(nt, 0.0f);
  for (const auto& [t, weights] : this->GuideWeights)
    for (float w : *weights)
      highest[ToIndex(t)] = std::max(highest[ToIndex(t)], w);
  for (std::int64_t v = 0; v < this->Arrangement.NumberOfVertices(); ++v)
  {
    const int label = labels[ToIndex(v)];
    for (std::size_t t = 1; t < nt; ++t)
      tally[t] += this->Occupancy(label, static_cast<int>(t));
    if (this->GuideWeights.empty())
      continue;
    const auto cell = ToIndex(this->CellOf(v));
    for (const auto& [t, weights] : this->GuideWeights)
      fit[ToIndex(t)] += this->Occupancy(label, t) * static_cast<double>((*weights)[cell]);
  }
  double error = 0, solid = 0;
  for (std::size_t t = 1; t < nt; ++t)
    solid += tally[t];
  if (this->Proportions && solid > 0)
    for (std::size_t t = 1; t < nt; ++t)
      error += std::abs(tally[t] / solid - this->Target[t]);
  for (const auto& [t, weights] : this->GuideWeights)
  {
    const auto k = ToIndex(t);
    if (tally[k] > 0 && highest[k] > 0)
      error += 1 - fit[k] / (static_cast<double>(highest[k]) * tally[k]);
  }
  // Connectivity of every solid type from seeds: parts beyond the seeds.
  if (const std::int64_t seeds = this->SeedsOfAllSolid())
  {
    std::vector<std::int64_t> component;
    const std::int64_t parts = SolidComponents(
      this->Arrangement, labels, [this](int d, int a) { return this->EdgeTypes(d, a); },
      this->Solid, this->TypesOfLabel, component);
    error += static_cast<double>(std::max<std::int64_t>(parts - seeds, 0));
  }
  return error;
}

} // namespace detail

double MatchError(const PolyhedralAnalysis& analysis, const PlaneArrangement& arrangement,
  const ContinuousConstraints& constraints, const std::vector<std::int32_t>& labels)
{
  if (static_cast<std::int64_t>(labels.size()) != arrangement.NumberOfVertices())
    throw Error("match error: a label per arrangement vertex is needed");
  return detail::ConstraintPlan(analysis, arrangement, constraints, 0).MatchError(labels);
}

ContinuousSynthesisResult SynthesizeCandidates(const PolyhedralAnalysis& analysis,
  const PlaneArrangement& arrangement, const ContinuousSynthesisOptions& options)
{
  const int n = options.Constraints.ModelCandidates;
  if (n < 1 || n > 1000)
    throw Error("continuous synthesis: model candidates must be between 1 and 1000, not " +
      std::to_string(n));
  if (n > 1 && options.Snapshots > 0)
    throw Error("continuous synthesis: catalog snapshots are of one model, not of several model "
                "candidates");
  const auto start = std::chrono::steady_clock::now();
  ContinuousSynthesisResult best;
  double bestError = std::numeric_limits<double>::infinity();
  for (int k = 0; k < n; ++k)
  {
    ContinuousSynthesisOptions o = options;
    o.Constraints.ModelCandidates = 1;
    o.Seed = options.Seed + static_cast<std::uint64_t>(k);
    if (options.Progress)
      o.Progress = [&options, k, n](double f)
      { return options.Progress((static_cast<double>(k) + f) / static_cast<double>(n)); };
    ContinuousSynthesisResult r = SynthesizeContinuous(analysis, arrangement, o);
    if (r.Status == SynthesisStatus::Cancelled)
      return r;
    if (!r.Succeeded())
    {
      if (k == 0)
        best = std::move(r); // kept only if no candidate succeeds
      continue;
    }
    const double error = MatchError(analysis, arrangement, options.Constraints, r.Labels);
    if (error < bestError)
    {
      bestError = error;
      best = std::move(r);
      best.ModelChosen = k;
      best.MatchError = error;
    }
  }
  best.Statistics.Seconds =
    std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (best.Succeeded())
  {
    std::ostringstream text;
    text << ", model " << best.ModelChosen + 1 << " of " << n << " kept (match error "
         << best.MatchError << ")";
    best.Message += text.str();
  }
  return best;
}

} // namespace msynth
