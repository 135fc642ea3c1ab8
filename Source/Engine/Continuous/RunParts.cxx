// SPDX-License-Identifier: BSD-3-Clause
#include "Continuous/RunParts.h"

#include "Continuous/ContinuousMirror.h"
#include "Core/Error.h"
#include "Core/Index.h"
#include "Core/ParallelChunks.h"

#include <algorithm>
#include <numeric>

namespace msynth
{
namespace detail
{

RunParts::RunParts(const PolyhedralAnalysis& analysis, const PlaneArrangement& arrangement,
  const ContinuousSynthesisOptions& options)
  : Rules(analysis, arrangement)
{
  const std::int64_t n = arrangement.NumberOfVertices();
  const int words = this->Rules.Words();
  this->Plan =
    std::make_unique<ConstraintPlan>(analysis, arrangement, options.Constraints, options.Seed);
  if (!options.Runs.empty())
    this->Ends = std::make_unique<RunEnds>(options.Runs, arrangement, *this->Plan);
  double reference = 0;
  for (int f = 0; f < arrangement.Families().Size(); ++f)
    reference = std::max(reference, arrangement.Parameters().Spacing(arrangement.Families(), f));
  this->BlockSize =
    options.BlockSize < 0 ? AutomaticBlockSize(options.Runs, reference) : options.BlockSize;
  this->Whole = this->BlockSize == 0;
  // Blocks spread outward from connectivity seeds one after the other; else non-touching
  // blocks run in phases, concurrently.
  this->Parallel = this->Plan->Seeds().empty();
  this->Layout =
    std::make_unique<BlockLayout>(arrangement, this->Whole ? 0.0 : this->BlockSize * reference,
      this->Parallel ? PhasePolicy::NonTouching : PhasePolicy::Sequential);
  this->Initial.resize(ToIndex(n) * words);
  int seams = 0;
  for (const ArrangementMirror* plan : options.PartOf)
    seams |= 1 << plan->Axis;
  // Each vertex's starting catalog on its own (threads: chunks of vertices, the same catalogs).
  const auto eachVertex = [&](const auto& work)
  {
    constexpr std::int64_t chunk = 8192;
    RunChunks(ToIndex((n + chunk - 1) / chunk), static_cast<unsigned>(std::max(0, options.Threads)),
      [&](std::size_t c)
      {
        const std::int64_t first = static_cast<std::int64_t>(c) * chunk;
        for (std::int64_t v = first; v < std::min(n, first + chunk); ++v)
          work(v, this->Initial.data() + ToIndex(v) * words);
      });
  };
  eachVertex(
    [&](std::int64_t v, std::uint64_t* domain) { this->Rules.InitialDomain(v, domain, seams); });
  if (!options.PartOf.empty())
    RestrictToMirrorImages(options.PartOf, arrangement, this->Initial);
  if (options.Choice != LabelChoice::Frequency && options.Choice != LabelChoice::Uniform)
    throw Error(
      "continuous synthesis: only uniform and frequency-weighted label choice are available");
  const bool given = options.LabelWeights.size() == analysis.Labels().size();
  const std::size_t k = options.Choice == LabelChoice::Frequency ? analysis.Labels().size() : 0;
  for (std::size_t id = 0; id < k; ++id) // lattice counts (LatticeCounts.h) or sampled ones
    this->Weights.push_back(std::max(1.0,
      given ? options.LabelWeights[id] : static_cast<double>(analysis.Labels()[id].Occurrences)));
  if (options.Constraints.RestrictsCatalog())
    eachVertex([&](std::int64_t v, std::uint64_t* domain) { this->Plan->Restrict(v, domain); });
  if (this->Parallel)
  {
    this->Order.resize(this->Layout->Grid.size());
    std::iota(this->Order.begin(), this->Order.end(), std::int64_t(0));
  }
  else
  {
    this->Order = this->Layout->OrderFrom(this->Plan->Seeds());
  }
  for (std::size_t i = 0; i < this->Order.size(); ++i)
  {
    const auto& block = this->Layout->Grid[ToIndex(this->Order[i])];
    this->Schedule.Phases.push_back(this->Parallel ? block.Phase : static_cast<int>(i));
    this->Schedule.Keys.push_back(static_cast<std::uint64_t>(block.Index));
  }
}

} // namespace detail
} // namespace msynth
