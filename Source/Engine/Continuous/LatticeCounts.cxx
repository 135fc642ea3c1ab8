// SPDX-License-Identifier: BSD-3-Clause
#include "Continuous/LatticeCounts.h"

#include "Core/Index.h"
#include "Core/ParallelChunks.h"

#include <algorithm>
#include <cmath>

namespace msynth
{

std::vector<double> LatticeOccurrences(const PolyhedralExample& example,
  const PolyhedralAnalysis& analysis, const ArrangementParameters& output)
{
  ArrangementParameters p = output;
  const int dims = analysis.Planar() ? 2 : 3;
  for (int c = 0; c < 3; ++c)
  {
    // The output's exact origin is the example's lowest corner (DefaultArrangementParameters).
    p.BoxLow[c] = 0;
    p.BoxHigh[c] = c < dims
      ? static_cast<std::int64_t>(
          std::floor((analysis.High()[ToIndex(c)] - analysis.Low()[ToIndex(c)]) / p.Quantum + 0.5))
      : 0;
  }
  const PlaneArrangement lattice(analysis.Families(), p);
  const NeighbourhoodProbe probe(example, analysis.Families(), analysis.FamilyUnitNormals(),
    analysis.AnalysisOptions().AngleTolerance);
  const std::int64_t n = lattice.NumberOfVertices();
  std::vector<int> label(ToIndex(n), -1);
  constexpr std::int64_t chunk = 1024;
  RunChunks(ToIndex((n + chunk - 1) / chunk), output.Threads,
    [&](std::size_t c)
    {
      const std::int64_t first = static_cast<std::int64_t>(c) * chunk;
      for (std::int64_t v = first; v < std::min(n, first + chunk); ++v)
        label[ToIndex(v)] = analysis.Find(probe.LabelAt(lattice.Position(v)));
    });
  std::vector<double> counts(ToIndex(analysis.NumberOfLabels()), 0.0);
  for (const int id : label)
    if (id >= 0)
      counts[ToIndex(id)] += 1;
  return counts;
}

} // namespace msynth
