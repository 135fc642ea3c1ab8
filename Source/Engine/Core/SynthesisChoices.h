// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/**
 * @file SynthesisChoices.h
 * @brief The choices every label solver shares: how a label is drawn at a site and in which
 * order the sites of a block are decided (discrete, time-varying and continuous synthesis).
 */

namespace msynth
{

/// How a label is drawn from the catalog at a site.
enum class LabelChoice
{
  Uniform,   ///< every possible label equally likely (the dissertation)
  Frequency, ///< weighted by the label's frequency in the example
  /// Resemblance (2007 paper, Eqs. 2–6): label k is weighted by L(k), the number of example
  /// sites holding k whose (2w+1)³ window is at the minimum perceptual distance d0 from the
  /// model's window around the site. The distance counts the pieces that differ where both
  /// windows have one (inside the example, decided in the model). Needs
  /// SynthesisOptions::Example.
  Resemblance
};

/// The order in which sites of a block are assigned.
enum class SiteOrder
{
  ScanLine,      ///< x fastest, then y, then z (the dissertation)
  Random,        ///< a seeded random permutation
  MinimumEntropy ///< the site with the fewest (entropy-weighted) choices first, ties at random
};

} // namespace msynth
