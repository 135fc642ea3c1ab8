// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/**
 * @file LatticeCounts.h
 * @brief How often each label of the example occurs at the vertices of the example's own plane
 * arrangement: the weights of a frequency-weighted draw that keep the example's sizes.
 *
 * The analysis samples each vertex, edge piece and face of the example once, whatever its size,
 * so a wall six spacings long and one a spacing long count alike. Drawn by those counts (or
 * uniformly), a wall's face label and the corner that ends it are about as likely at each
 * vertex along a line, and walls end after a spacing or two: the parts of a model come out a
 * fraction of the example's. Counted instead at the vertices of the arrangement the output is
 * built on (the same families, spacings and offsets), laid over the example's box, a face holds
 * as many vertices as its area in spacings, so a draw by these counts continues a wall as often
 * as the example's walls continue and ends it as often as they end.
 */
#include "Continuous/PlaneArrangement.h"
#include "Continuous/PolyhedralAnalysis.h"

#include <vector>

namespace msynth
{

/**
 * Per label of @p analysis (its ids), the vertices of the arrangement of @p output's families,
 * spacings and offsets over the box of @p example whose neighbourhood in the example is that
 * label. Threads: @p output's. @throw Error as PlaneArrangement does (too many vertices).
 */
std::vector<double> LatticeOccurrences(const PolyhedralExample& example,
  const PolyhedralAnalysis& analysis, const ArrangementParameters& output);

} // namespace msynth
