// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/**
 * @file PatternQuality.h
 * @brief How much a pattern looks like its exemplars (Yeh et al. 2012, §7), and the independent
 * check of its hard factors. Works on label values with ordered containers and shares no code
 * with the samplers (nor with FactorGraph's learning), so it can check them.
 *
 * Histograms f_s (Eq. 4) count each configuration of shape s at every anchor where s fits. The
 * KL divergence of a model to its exemplars is D(f_model ‖ f_exemplars) = Σ_c f_model(c)
 * log(f_model(c) / f̂(c)) (natural log) over the configurations c the model shows, where f̂
 * smooths the exemplars' counts by adding one to every configuration either shows (Laplace):
 * f̂(c) = (F(c) + 1) / (Σ F + |U|), U the union of both supports. It is 0 when the model shows
 * only exemplar configurations in the same proportions, and grows with configurations the
 * exemplars never show (elongated doors, repeated windows).
 */
#include "Core/LabelGrid.h"
#include "Patterns/FactorGraph.h"

#include <cstdint>
#include <map>
#include <string>
#include <vector>

namespace msynth
{

/// F_s: configuration (label values in the shape's offset order) → count.
using ConfigurationHistogram = std::map<std::vector<Label>, std::int64_t>;

/// F_s over every anchor where @p shape fits in each grid of @p grids.
ConfigurationHistogram CountConfigurations(
  const std::vector<LabelGrid>& grids, const Stencil& shape);

/// D(f_model ‖ f̂_exemplars) as above; 0 when the model has no configuration.
double KLDivergence(const ConfigurationHistogram& model, const ConfigurationHistogram& exemplars);

/// The KL divergence of @p model to @p exemplars for @p shape.
double PatternKL(
  const std::vector<LabelGrid>& exemplars, const LabelGrid& model, const Stencil& shape);

/**
 * The unnormalised log probability of Eq. 3 with hard pairs and soft factors of @p softShapes
 * learned from all of @p exemplars: (number of soft factors whose configuration an exemplar
 * shows) · log(1 + ε), or -infinity when a hard pair does not occur in any exemplar.
 */
double PatternLogProbability(const std::vector<LabelGrid>& exemplars, const LabelGrid& model,
  const std::vector<Stencil>& softShapes, double epsilon);

/**
 * The hard factors (§5.1) checked from scratch: every pair of neighbours along each axis must
 * occur along that axis in an exemplar, or be one of @p extra (a tileset's rules). Returns one
 * line per violation (at most @p limit).
 */
std::vector<std::string> CheckPatternPairs(const std::vector<LabelGrid>& exemplars,
  const LabelGrid& model, std::size_t limit = 10, const LabelPairs& extra = LabelPairs());

} // namespace msynth
