// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/**
 * @file ContinuousConstraints.h
 * @brief The geometric constraints of continuous model synthesis beyond adjacency (TVCG 2010
 * §3.3, §4.5–4.7): dimensional constraints, connectivity (growth from seeds), grounded outputs,
 * large-scale guides and object-type proportions.
 *
 * All of them act on the label solver in one of three ways, so the adjacency constraint and its
 * propagation are unchanged:
 * - **removing labels** from a vertex's catalog before anything is chosen (dimensional
 *   constraints, ground rules, guide zeros), the removal then propagating as usual;
 * - **the order** vertices are labelled in and which labels may start an object there
 *   (connectivity: an object type grows only next to itself, from seeds);
 * - **the weight** of each label when one is drawn (guide weights, type proportions).
 *
 * None of them removes the empty label, so the empty model stays a consistent start for blocks.
 */
#include "Continuous/PlaneArrangement.h"
#include "Continuous/PolyhedralAnalysis.h"

#include <array>
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace msynth
{

/**
 * Dimensional constraint (TVCG §4.5, Fig. 6): objects of @p Type are exactly @p Spacings plane
 * spacings thick across the planes of family @p Family. With one spacing, every label in which
 * the type passes through a plane of the family is removed (the type is on both sides of the
 * plane next to the vertex); with N spacings the planes are grouped into slabs of N (counted
 * from the lowest plane in the output box): the type may not pass through a slab's outer planes
 * and may not end on its inner ones, so it fills whole slabs — N spacings, aligned.
 */
struct ThicknessConstraint
{
  int Type = 1;
  int Family = 0;
  int Spacings = 1;
  /**
   * A width instead (roads, pipes): with further families here, the type is one spacing thick
   * across at least one of Family and these at every point; it may run along any of them, but
   * never fills the whole neighbourhood of a vertex on all of them in their directions (no
   * two-by-two block). Spacings must be 1.
   */
  std::vector<int> OrFamilies;
  /**
   * Whole slabs instead of one: the type may pass through the slabs' outer planes too, so it is
   * N, 2N, 3N ... spacings thick, aligned to the slabs ("TYPE:AXIS:N+"). With N = 2 across x and
   * y, walls are never one spacing thin and the gaps between them never one spacing narrow:
   * together with the overhang rule, a roof cannot rest on a row of thin posts.
   */
  bool Multiples = false;
};

/**
 * Connectivity constraint (TVCG §4.6): labels holding @p Type are only chosen at vertices next
 * to that type (an edge of an already labelled neighbour touches it), so objects grow from
 * seeds; vertices next to the grown objects are labelled first. @p Seeds random vertices (from
 * the run's seed) start an object each; 0 seeds leaves the type unconstrained. Type 0 means
 * every solid type together. In a grounded run the seeds are on the ground, and objects of
 * the seeded types start only there (the other types anywhere on the ground).
 */
struct ConnectivityConstraint
{
  int Type = 0;
  int Seeds = 1;
};

/**
 * Large-scale constraints (TVCG §4.7): a guide grid stretched over the output box, with a
 * weight per object type and cell (x fastest). A vertex at world position p reads the cell
 * floor((p − low) / (high − low) · Dims) of the box [low, high]. A weight of zero removes every
 * label holding that type there; others multiply the probability of such labels. Types without
 * weights have weight 1.
 */
struct ContinuousGuide
{
  std::array<std::int64_t, 3> Dims{ { 1, 1, 1 } };
  std::map<int, std::vector<float>> Weights; ///< object type (≥ 1) → weight per cell
};

struct ContinuousConstraints
{
  /**
   * Grounded output: the labels the example has on its ground (its lowest plane along z; y in
   * 2D) are the only ones allowed on the output's ground and, when the example has them nowhere
   * else, are not allowed above it (no wall bottoms in the air, no roofs lying on the ground);
   * solid objects grow from the ground (connectivity with the ground as seeds), and any solid
   * part that ends up not connected to the ground is emptied (which keeps the model consistent).
   */
  bool Grounded = false;
  std::vector<ThicknessConstraint> Thickness;
  /**
   * Object types whose undersides (the type above, empty space below, along the ground's
   * normal: z, or y in 2D) are at most one plane spacing wide across the horizontal axes: they
   * reach at most one spacing past whatever holds them up, as the eaves of a roof, and never
   * span between thin columns. Labels with such a face across a block two spacings wide are
   * removed at vertices on planes across every axis.
   */
  std::vector<int> Overhang;
  std::vector<ConnectivityConstraint> Connected;
  std::optional<ContinuousGuide> Guide;
  /**
   * Object-type proportions: labels holding a type are favoured while the type's share of the
   * solid volume synthesized so far is below its target, and disfavoured above it. Targets are
   * the example's volume fractions, replaced per type by TargetFractions (fractions of the solid
   * volume); off with KeepProportions false and no targets. Examples with one object type and
   * no guide weights draw as before (uniformly or by frequency).
   */
  bool KeepProportions = true;
  std::map<int, double> TargetFractions;
  /// With proportions steered: labellings tried per block (each a full solve of the block), the
  /// one whose shares come closest to the targets kept ("generate several, keep the best match",
  /// §4.7, block by block).
  int BlockCandidates = 1;
  /// "Generate several, keep the best match" (§4.7) for whole models: this many models are
  /// synthesized, with seeds Seed, Seed + 1, ..., and the one with the smallest MatchError kept.
  int ModelCandidates = 1;

  bool RestrictsCatalog() const
  {
    return this->Grounded || !this->Thickness.empty() || !this->Overhang.empty() ||
      this->Guide.has_value();
  }
};

/// The family whose normal is parallel to coordinate axis @p axis (0, 1, 2), or −1.
int FamilyAlongAxis(const PlaneFamilySet& families, int axis);

/**
 * Parses "TYPE:AXIS:N" (AXIS x, y, z or hK for the K-th plane family, N ≥ 1 spacings; ":N"
 * may be left out for 1; "N+" for whole multiples of N), or a width "TYPE:AXES" with two or more
 * axes ("xy", "h1h2": one spacing thick across at least one of them). TYPE is a number or an
 * object type's name in @p typeNames.
 * @throw Error naming the text.
 */
ThicknessConstraint ParseThickness(const std::string& text, const PlaneFamilySet& families,
  const std::map<int, std::string>& typeNames);
/// Parses "TYPE[:SEEDS]" (TYPE a number, a name, or "solid" for 0). @throw Error.
ConnectivityConstraint ParseConnected(
  const std::string& text, const std::map<int, std::string>& typeNames);
/// The object type named @p text (a number, or a name in @p typeNames). @throw Error.
int ParseObjectType(const std::string& text, const std::map<int, std::string>& typeNames);

/**
 * Measures of a labelled arrangement that a user sees, recomputed from the labels alone:
 * connected solid parts (vertices joined along edges that touch solid), how many touch the
 * ground plane, and per object type the solid share (each vertex counts the fraction of its
 * label's cones holding the type).
 */
struct ArrangementMeasures
{
  std::int64_t Components = 0;         ///< connected solid parts
  std::int64_t GroundedComponents = 0; ///< of which touch the bottom of the box
  std::map<int, double> TypeShares;    ///< object type → share of the solid
};
ArrangementMeasures MeasureArrangement(const PolyhedralAnalysis& analysis,
  const PlaneArrangement& arrangement, const std::vector<std::int32_t>& labels);

/**
 * How far a labelled arrangement is from what @p constraints ask, recomputed from the labels
 * (0: exactly): the sum of
 * - with proportions kept or targets given, |share − target| over the solid types;
 * - per type with guide weights, the part of its volume away from the guide's favoured places:
 *   1 − Σ occupancy · weight / (largest weight · Σ occupancy);
 * - with connectivity from seeds for every solid type, the solid parts beyond the seeds' count.
 */
double MatchError(const PolyhedralAnalysis& analysis, const PlaneArrangement& arrangement,
  const ContinuousConstraints& constraints, const std::vector<std::int32_t>& labels);

} // namespace msynth
