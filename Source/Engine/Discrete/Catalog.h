// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/**
 * @file Catalog.h
 * @brief The catalog C (dissertation §3.3.2, Algorithms 3.2–3.3) over one box-shaped region of
 * the model: the set of labels still possible at each site, as a bit set of k bits, and its
 * propagation.
 *
 * The bit sets and their propagation are the shared engine of Propagation.h (LabelDomains);
 * this class adds the box-shaped region and its six axis neighbours.
 *
 * Sites outside the region are fixed: Constrain() applies a fixed neighbour's label to a border
 * site of the region.
 */
#include "Core/Propagation.h"
#include "Discrete/AdjacencyRules.h"

#include <array>
#include <cstdint>
#include <vector>

namespace msynth
{

/**
 * Extra constraints between sites that are not axis neighbours (the seams of translation and
 * rotation symmetry, dissertation §3.5.2), over a box of sites indexed x fastest: site s is
 * linked to Target[i] for Start[s] <= i < Start[s + 1], with direction class Class[i] (>= 6) of
 * the relation given to Catalog::SetArcs. Every arc is stored in both directions, the second
 * with class Class ^ 1.
 */
struct SiteArcs
{
  std::array<std::int64_t, 3> Dims{ { 0, 0, 0 } };
  std::vector<std::int64_t> Start;
  std::vector<std::int64_t> Target;
  std::vector<int> Class;
  bool Empty() const { return this->Target.empty(); }
};

class Catalog : public LabelDomains
{
public:
  explicit Catalog(const AdjacencyRules& rules)
    : Rules(rules)
    , Relation(&rules)
  {
  }

  /// Adds @p arcs (not owned) to the neighbourhood; @p relation (not owned) has the six axis
  /// classes of the rules and the arcs' classes.
  void SetArcs(const CompatibilityRelation* relation, const SiteArcs* arcs)
  {
    this->Relation = relation;
    this->Arcs = arcs;
  }
  const CompatibilityRelation& Relations() const { return *this->Relation; }

  /// Makes the region the box [origin, origin + dims) with every label possible everywhere.
  void Reset(const std::array<std::int64_t, 3>& origin, const std::array<std::int64_t, 3>& dims);

  const std::array<std::int64_t, 3>& Origin() const { return this->RegionOrigin; }
  const std::array<std::int64_t, 3>& Dims() const { return this->RegionDims; }
  /// Local index of region coordinates (x fastest).
  std::int64_t Local(std::int64_t x, std::int64_t y, std::int64_t z) const
  {
    return x + this->RegionDims[0] * (y + this->RegionDims[1] * z);
  }
  std::array<std::int64_t, 3> Coordinates(std::int64_t local) const;

  /// Keeps at @p local only labels allowed next to label @p b of a fixed site outside the
  /// region, reached from that site along direction @p d (an axis direction or an arc class).
  /// Returns false if nothing is left.
  bool Constrain(std::int64_t local, int d, int b)
  {
    return this->Keep(local, this->Relation->Compatible(d, b));
  }

  /**
   * Propagates every change since the last call (Algorithm 3.2's stack loop). Returns -1 when
   * every set is non-empty, else the local index of a site whose set became empty.
   */
  std::int64_t Propagate();

private:
  const AdjacencyRules& Rules;
  const CompatibilityRelation* Relation;
  const SiteArcs* Arcs = nullptr;
  std::array<std::int64_t, 3> RegionOrigin{ { 0, 0, 0 } };
  std::array<std::int64_t, 3> RegionDims{ { 0, 0, 0 } };
  /// Per site, bit d set when the neighbour along direction d is inside the region (so that
  /// propagation finds a site's neighbours without dividing its index).
  std::vector<std::uint8_t> Inside;
};

} // namespace msynth
