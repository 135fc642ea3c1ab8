// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/**
 * @file ContinuousMirror.h
 * @brief Reflection symmetry of continuous models (the papers' open item, TVCG §7): the output
 * is its own mirror image across a plane of the arrangement near the middle of the box.
 *
 * The reflection R across the seam X_axis = M (exact units; M on a plane of the family normal to
 * the axis, the last such plane at or before the middle of the box) must map the arrangement onto
 * itself: every family's reflected normal is a family's normal (up to sign) with the same
 * spacing, and reflected planes are planes. Labels map to their mirror images (the cones
 * reflected, the object types kept); a label whose image is not among the example's cannot be
 * used where its image would be needed.
 *
 * The half box up to the seam is synthesized: vertices on the seam hold labels that are their own
 * mirror images, and their edges across the seam need not be empty (the far side is the mirror
 * of the near side, so those edges agree). The other half is the reflection; beyond twice the
 * seam the box stays empty.
 */
#include "Continuous/ContinuousSynthesis.h"
#include "Continuous/PlaneArrangement.h"
#include "Continuous/PolyhedralAnalysis.h"

#include <cstdint>
#include <vector>

namespace msynth
{

struct ArrangementMirror
{
  int Axis = 0;
  int Family = 0;               ///< the plane family normal to the axis
  std::int64_t Seam = 0;        ///< M, in exact units along the axis
  std::vector<int> FamilyImage; ///< family → family of its reflected normal
  std::vector<char> Flipped;    ///< the reflected normal is minus that family's normal
  std::vector<int> LabelImage;  ///< label → its mirror image's id, −1 when the example lacks it
};

/**
 * The reflection of @p arrangement's planes across the axis (0, 1, 2).
 * @throw Error when the plane families or their planes are not symmetric, or no plane of the
 * axis' family lies in the box.
 */
ArrangementMirror PlanArrangementMirror(
  const PolyhedralAnalysis& analysis, const ArrangementParameters& parameters, int axis);

/// The mirror image of @p label under the plan's family map.
NeighbourhoodLabel MirrorLabel(
  const PlaneFamilySet& families, const NeighbourhoodLabel& label, const ArrangementMirror& plan);

/**
 * The part of a model mirrored across the plans' axes: keeps in each vertex's catalog
 * (@p catalogs, one bit set per vertex, (labels + 63) / 64 words each) only labels whose images
 * under every combination of the reflections the example has, and on a plan's seam only labels
 * that are their own image under that reflection.
 */
void RestrictToMirrorImages(const std::vector<const ArrangementMirror*>& plans,
  const PlaneArrangement& part, std::vector<std::uint64_t>& catalogs);

/**
 * Continuous synthesis with reflection symmetry (options.MirrorAxes): the half box up to the seam
 * of the lowest axis labelled (recursively mirrored across the other axes) with the seams'
 * rules, then reflected onto @p arrangement (the whole box). Called by SynthesizeContinuous.
 * @throw Error as PlanArrangementMirror, or with snapshots.
 */
ContinuousSynthesisResult SynthesizeMirrored(const PolyhedralAnalysis& analysis,
  const PlaneArrangement& arrangement, const ContinuousSynthesisOptions& options);

} // namespace msynth
