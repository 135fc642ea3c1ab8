// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/**
 * @file MirrorPlan.h
 * @brief Reflection symmetry (D§3.5.2), internal: the half of the output to synthesize and how
 * it maps onto the whole, checked against the example's rules.
 */
#include "Core/Index.h"
#include "Discrete/AdjacencyRules.h"
#include "Discrete/DiscreteSynthesis.h"

#include <array>
#include <cstdint>
#include <vector>

namespace msynth
{
namespace detail
{

using Coord = std::array<std::int64_t, 3>;

/// Symmetric synthesis: what the half to synthesize is and how it maps onto the full model.
struct MirrorPlan
{
  Coord Full{ { 1, 1, 1 } };
  Coord Half{ { 1, 1, 1 } };
  std::array<bool, 3> Axes{ { false, false, false } };
  std::array<std::vector<int>, 3> F; ///< label index → index of its mirror image, per axis
  std::array<std::vector<std::uint64_t>, 3> ColumnMask; ///< labels allowed on the last layer
  SynthesisOptions HalfOptions;

  /// Index of the mirror image of label index @p b over the axes whose bit is set in @p axes.
  int Image(int b, int axes) const
  {
    for (int a = 0; a < 3; ++a)
      if (axes & (1 << a))
        b = this->F[ToIndex(a)][ToIndex(b)];
    return b;
  }
  /// The site of the full model that mirrors half-model site @p p over the axes of @p axes.
  Coord ImageSite(const Coord& p, int axes) const
  {
    Coord q = p;
    for (int a = 0; a < 3; ++a)
      if (axes & (1 << a))
        q[a] = this->Full[a] - 1 - p[a];
    return q;
  }
  int AxisMask() const
  {
    return (this->Axes[0] ? 1 : 0) | (this->Axes[1] ? 2 : 0) | (this->Axes[2] ? 4 : 0);
  }
};

/// Whether any axis has mirror symmetry.
bool AnyMirror(const SynthesisOptions& options);

/// Validates the symmetry options against the rules and plans the half to synthesize.
MirrorPlan PlanMirror(const AdjacencyRules& rules, const SynthesisOptions& options);

} // namespace detail
} // namespace msynth
