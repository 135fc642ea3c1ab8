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
#include "msynth/AdjacencyRules.h"
#include "msynth/Propagation.h"

#include <array>
#include <cstdint>
#include <vector>

namespace msynth
{

class Catalog : public LabelDomains
{
public:
  explicit Catalog(const AdjacencyRules& rules)
    : Rules(rules)
  {
  }

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
  /// region, reached from that site along direction @p d. Returns false if nothing is left.
  bool Constrain(std::int64_t local, int d, int b)
  {
    return this->Keep(local, this->Rules.Compatible(d, b));
  }

  /**
   * Propagates every change since the last call (Algorithm 3.2's stack loop). Returns -1 when
   * every set is non-empty, else the local index of a site whose set became empty.
   */
  std::int64_t Propagate();

private:
  const AdjacencyRules& Rules;
  std::array<std::int64_t, 3> RegionOrigin{ { 0, 0, 0 } };
  std::array<std::int64_t, 3> RegionDims{ { 0, 0, 0 } };
};


} // namespace msynth
