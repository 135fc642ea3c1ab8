// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/**
 * @file Catalog.h
 * @brief The catalog C (dissertation §3.3.2, Algorithms 3.2–3.3) over one box-shaped region of
 * the model: the set of labels still possible at each site, as a bit set of k bits, and its
 * propagation.
 *
 * Propagation is arc consistency on bit sets: when the set at v shrinks, each neighbour u = v + d
 * keeps only the labels some label of v allows there (the union of the rules' compatible sets).
 * Memory is k bits plus a few bytes per site; there are no per-label support counters (AC-4
 * would need 6·k counters per site).
 *
 * Sites outside the region are fixed: Constrain() applies a fixed neighbour's label to a border
 * site of the region.
 */
#include "msynth/AdjacencyRules.h"

#include <array>
#include <cstdint>
#include <vector>

namespace msynth
{

class Catalog
{
public:
  explicit Catalog(const AdjacencyRules& rules);

  /// Makes the region the box [origin, origin + dims) with every label possible everywhere.
  void Reset(const std::array<std::int64_t, 3>& origin, const std::array<std::int64_t, 3>& dims);

  const std::array<std::int64_t, 3>& Origin() const { return this->RegionOrigin; }
  const std::array<std::int64_t, 3>& Dims() const { return this->RegionDims; }
  std::int64_t NumberOfSites() const { return static_cast<std::int64_t>(this->Counts.size()); }
  /// Local index of region coordinates (x fastest).
  std::int64_t Local(std::int64_t x, std::int64_t y, std::int64_t z) const
  {
    return x + this->RegionDims[0] * (y + this->RegionDims[1] * z);
  }
  std::array<std::int64_t, 3> Coordinates(std::int64_t local) const;

  /// Number of labels possible at @p local.
  int Count(std::int64_t local) const { return this->Counts[static_cast<std::size_t>(local)]; }
  const std::uint64_t* Domain(std::int64_t local) const
  {
    return this->Bits.data() + static_cast<std::size_t>(local) * this->W;
  }
  bool Contains(std::int64_t local, int b) const
  {
    return (this->Domain(local)[b >> 6] >> (b & 63)) & 1u;
  }
  /// Sites with exactly one label left.
  std::int64_t Decided() const { return this->DecidedSites; }
  /// The only label left at @p local (Count() must be 1).
  int Single(std::int64_t local) const;

  /// Keeps only label @p b at @p local (an assignment, line 13 of Algorithm 3.1).
  /// Returns false when @p b was not possible there.
  bool Assign(std::int64_t local, int b);
  /// Keeps at @p local only the labels of @p mask (Words() words). False if nothing is left.
  bool Keep(std::int64_t local, const std::uint64_t* mask) { return this->Restrict(local, mask); }
  /// Keeps at @p local only labels allowed next to label @p b of a fixed site outside the
  /// region, reached from that site along direction @p d. Returns false if nothing is left.
  bool Constrain(std::int64_t local, int d, int b);

  /**
   * Propagates every change since the last call (Algorithm 3.2's stack loop). Returns -1 when
   * every set is non-empty, else the local index of a site whose set became empty.
   */
  std::int64_t Propagate();

  /// Sites whose sets changed during the last Propagate(), Assign() or Constrain() calls since
  /// ClearChanged(); used to keep priorities (minimum entropy) up to date.
  const std::vector<std::int64_t>& Changed() const { return this->ChangedSites; }
  void ClearChanged() { this->ChangedSites.clear(); }

private:
  bool Restrict(std::int64_t local, const std::uint64_t* mask);
  void Push(std::int64_t local);

  const AdjacencyRules& Rules;
  int W;
  std::array<std::int64_t, 3> RegionOrigin{ { 0, 0, 0 } };
  std::array<std::int64_t, 3> RegionDims{ { 0, 0, 0 } };
  std::vector<std::uint64_t> Bits;
  std::vector<int> Counts;
  std::vector<std::uint8_t> Queued;
  std::vector<std::int64_t> Stack;
  std::vector<std::int64_t> ChangedSites;
  std::vector<std::uint64_t> Scratch;
  std::int64_t EmptySite = -1;
  std::int64_t DecidedSites = 0;
};

} // namespace msynth
