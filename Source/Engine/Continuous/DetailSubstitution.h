// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/**
 * @file DetailSubstitution.h
 * @brief Bounding volumes and algebraic constraints (TVCG §4.8): synthesize with a simple
 * bounding volume in place of a detailed object (a box cut into triangular prisms scales
 * uniformly in two directions, one cut by a plane through three of its corners in all three),
 * then substitute the detailed mesh back into every part of that object type in the output,
 * scaled and moved onto the part's bounding box.
 */
#include "Continuous/ContinuousMesh.h"
#include "Formats/PolyhedralExample.h"

#include <array>
#include <vector>

namespace msynth
{

struct DetailPlacement
{
  Point3 Low{}, High{};          ///< the part's bounding box in the output
  std::array<double, 3> Scale{}; ///< per axis, from the example's bounding volume
  /// The largest relative difference between the scales (0: scaled uniformly in all three
  /// directions; in 2D, x and y).
  double Anisotropy = 0;
};

struct DetailResult
{
  ContinuousMesh Mesh;
  std::vector<DetailPlacement> Placements;
};

/**
 * Replaces every connected part of the object types @p types in @p model (3D) by @p detail, a
 * mesh authored in the example's coordinates inside the bounding volume's box [@p low, @p high]:
 * each part gets a copy mapped from that box onto its own bounding box, of type types[0].
 * Several types make one bounding volume of several pieces (a box cut into two prisms, each
 * piece its own type so that the cut is a face synthesis keeps): faces between them go with
 * the part. The part's faces toward empty space are removed; faces it shares with other object
 * types stay, as those types' faces toward empty space. @throw Error for a 2D model, no type,
 * an empty box or a detail without polygons.
 */
DetailResult SubstituteDetail(const ContinuousMesh& model, const std::vector<int>& types,
  const PolyhedralExample& detail, const Point3& low, const Point3& high);

} // namespace msynth
