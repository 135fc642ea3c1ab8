// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/**
 * @file PlaneArrangement.h
 * @brief The arrangement of evenly spaced parallel planes that continuous model synthesis
 * labels (dissertation §4.5.1–4.5.2, §4.5.7).
 *
 * Family i (normal n_i, an exact integer vector from the example analysis) has the planes
 * n_i·X = Offset_i + c·Spacing_i, c ∈ Z, where X are exact coordinates: world = Origin +
 * Quantum·X. Offsets and spacings are integers, so every vertex (a point where planes with
 * independent normals meet) is an exact rational point, and a fourth plane through a vertex is
 * detected exactly (128-bit integers, overflow checked). Only vertices in the closed output box
 * are kept. Edges join consecutive vertices along every line through a vertex; an edge that
 * leaves the box is kept as a link to "outside" (-1), which the solver requires to be empty.
 *
 * Planar examples (all z = 0) give the 2D variant: line families in the plane z = 0, vertices
 * where two lines meet.
 */
#include "Continuous/Neighbourhood.h"
#include "Core/Index.h"
#include "Formats/PolyhedralExample.h"

#include <cstdint>
#include <vector>

namespace msynth
{

class PolyhedralAnalysis;
namespace detail
{
class ArrangementBuilder;
}

struct ArrangementParameters
{
  Point3 Origin{};    ///< world position of the exact coordinates (0, 0, 0)
  double Quantum = 1; ///< world length of one exact unit
  IntVec3 BoxLow{};   ///< closed output box in exact units (z is 0..0 when planar)
  IntVec3 BoxHigh{};
  std::vector<std::int64_t> Offsets;  ///< per family, in units of n_i·X
  std::vector<std::int64_t> Spacings; ///< per family, > 0
  bool Planar = false;
  std::int64_t MaxVertices = 20000000; ///< larger arrangements are refused with an Error
  /// Threads that build it (0: one per core). The arrangement is the same for any count.
  unsigned Threads = 0;

  /// World distance between neighbouring planes of @p family.
  double Spacing(const PlaneFamilySet& families, int family) const;
};

/**
 * Parameters for an output box of @p size (world units, from the example's lowest corner) and
 * plane spacings derived from the example: per family, the largest spacing (approximate GCD)
 * that puts a plane on every example face of the family and on the example's extremes along its
 * normal. With @p spacing > 0 the arrangement is scaled by one factor (exactly: the quantum is
 * scaled, the integer spacings and offsets kept, so planes that met in the example still meet)
 * so that the smallest world spacing equals it.
 * Per-family @p spacings (world units, one per family) override both when not empty.
 * @throw Error on a non-positive or non-finite size or spacing, or a box too large for exact
 * coordinates.
 */
ArrangementParameters DefaultArrangementParameters(const PolyhedralExample& example,
  const PolyhedralAnalysis& analysis, const Point3& size, double spacing,
  const std::vector<double>& spacings);

class PlaneArrangement
{
public:
  struct Link
  {
    std::int32_t Vertex;    ///< neighbour along the direction, -1 when the edge leaves the box
    std::int32_t Direction; ///< direction class (Direction(d)); d ^ 1 is the opposite one
  };

  /// Builds the arrangement. @throw Error when it would exceed MaxVertices or exact integers.
  PlaneArrangement(const PlaneFamilySet& families, ArrangementParameters parameters);

  const ArrangementParameters& Parameters() const { return this->Params; }
  const PlaneFamilySet& Families() const { return this->Set; }
  bool Planar() const { return this->Params.Planar; }

  std::int64_t NumberOfVertices() const
  {
    return static_cast<std::int64_t>(this->Positions.size());
  }
  /// World position (rounded from the exact rational point).
  const Point3& Position(std::int64_t v) const { return this->Positions[ToIndex(v)]; }
  /// Bit i set when a plane of family i passes through vertex @p v.
  std::uint64_t FamilyMask(std::int64_t v) const { return this->Masks[ToIndex(v)]; }
  std::vector<int> FamiliesThrough(std::int64_t v) const;

  /// Direction classes: every line direction (primitive integer vector) both ways.
  int NumberOfDirections() const { return static_cast<int>(this->Directions.size()); }
  const IntVec3& Direction(int d) const { return this->Directions[ToIndex(d)]; }

  const Link* LinksBegin(std::int64_t v) const
  {
    return this->Links.data() + this->LinkStart[ToIndex(v)];
  }
  const Link* LinksEnd(std::int64_t v) const
  {
    return this->Links.data() + this->LinkStart[ToIndex(v) + 1];
  }

  /// Edges between two vertices (each once), and edges leaving the box.
  std::int64_t NumberOfEdges() const { return this->InnerEdges; }
  std::int64_t NumberOfBoundaryEdges() const { return this->OuterEdges; }
  /// Bytes held by the arrangement.
  std::size_t MemoryBytes() const;

private:
  friend class detail::ArrangementBuilder; // fills the vertices, directions and links
  PlaneFamilySet Set;
  ArrangementParameters Params;
  std::vector<IntVec3> Directions;
  std::vector<Point3> Positions;
  std::vector<std::uint64_t> Masks;
  std::vector<std::int64_t> LinkStart;
  std::vector<Link> Links;
  std::int64_t InnerEdges = 0;
  std::int64_t OuterEdges = 0;
};

} // namespace msynth
