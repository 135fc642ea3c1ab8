// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/**
 * @file FeatureWidth.h
 * @brief The narrowest feature of a continuous model, measured on its polygons alone (no plane
 * arrangement, no labels, no solver): slivers of near-coincident planes show up here.
 *
 * A corner of the model is a point where the boundary's planes have full rank (three
 * independent normals in 3D; two boundary directions in 2D). The width of the model at a corner
 * is its distance to the nearest part of the boundary (a polygon in 3D, a boundary segment in 2D)
 * whose plane (line) does not pass through the corner: a short edge, a thin face, a narrow gap
 * between two solids or a thin wall all bring such a part close to a corner. Parts in a plane
 * through the corner are its own faces (or coplanar neighbours, whose own corners measure them).
 */
#include "Continuous/ContinuousMesh.h"

namespace msynth
{

/// Outputs must have no feature narrower than this fraction of the smallest plane spacing.
constexpr double MinimumFeatureFraction = 0.1;

struct FeatureWidth
{
  /// The narrowest width found, or the search radius when nothing is narrower.
  double Width = 0;
  Point3 Where{};           ///< the corner where it was found (when Found)
  bool Found = false;       ///< whether a width under the radius was found
  std::int64_t Corners = 0; ///< corners measured
};

/**
 * The narrowest feature of @p mesh up to @p radius (> 0; e.g. the smallest plane spacing).
 * Distances under 10⁻⁹ of the model's diagonal count as touching (exact coincidences are not
 * features). Polygons of (near) zero area are skipped. Linear in the polygons (a uniform grid).
 */
FeatureWidth SmallestFeature(const ContinuousMesh& mesh, double radius);

} // namespace msynth
