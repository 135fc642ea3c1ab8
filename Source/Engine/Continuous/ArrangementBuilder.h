// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/**
 * @file ArrangementBuilder.h
 * @brief How a PlaneArrangement is built (internal; D§4.5.1-4.5.2), in named
 * steps: check the parameters, find each family's planes through the box, list the generating
 * tuples of families, (1) generate the vertices exactly, (2) number them in scan-line order,
 * (3) list the line directions, (4) link every vertex to the next one along each line.
 * Steps (1) and (4) run on threads in chunks joined in order, so the arrangement is the same for
 * any thread count.
 */
#include "Continuous/ExactArithmetic.h"
#include "Continuous/PlaneArrangement.h"
#include "Core/Index.h"

#include <array>
#include <cstdint>
#include <map>
#include <vector>

namespace msynth
{
namespace detail
{

class ArrangementBuilder
{
public:
  ArrangementBuilder(const PlaneFamilySet& set, const ArrangementParameters& params);

  /// Builds the arrangement into @p out's vertices, directions and links.
  void Build(PlaneArrangement& out);

private:
  /// dim families with independent normals; their candidate vertices (one per plane of each)
  /// in rows: the planes of all families but the last fixed, a row is a line.
  struct Tuple
  {
    std::array<int, 3> F{};
    std::array<Wide, 3> Lo{};
    std::array<Wide, 3> Count{};
    std::size_t RowBase = 0;        ///< its first row in RowStart
    std::array<IntVec3, 3> Cross{}; ///< n1×n2, n2×n0, n0×n1 (3D)
    Wide Det = 0;
  };

  void CheckParameters() const;
  void FindPlaneRanges();
  void ListTuples();
  void GenerateVertices();
  void NumberInScanLineOrder(PlaneArrangement& out);
  void ListDirections(PlaneArrangement& out);
  void LinkVertices(PlaneArrangement& out);
  /// The next vertex from @p x along direction @p d (-1: the line leaves the box); @p scratch
  /// holds plane indices (one per thread, so no allocation a link).
  std::int32_t NextAlong(const Exact& x, const IntVec3& d, std::vector<Wide>& scratch) const;
  /// The direction classes of the lines through a vertex of families @p mask, sorted.
  void LinesThrough(std::uint64_t mask, std::vector<int>& lines) const;

  const IntVec3& Normal(int f) const { return this->Set.Normal(f); }
  Wide Offset(int f) const { return static_cast<Wide>(this->Params.Offsets[ToIndex(f)]); }
  Wide SpacingOf(int f) const { return static_cast<Wide>(this->Params.Spacings[ToIndex(f)]); }
  Wide Determinant(const int* t) const;
  /// The intersection point of the tuple's planes of values @p value (Den > 0, not reduced).
  Exact Solve(const Tuple& tu, const std::array<Wide, 3>& value) const;
  bool InBox(const Exact& x) const;
  /// Families with a plane through @p x (bits), their plane indices into @p planeIndex.
  std::uint64_t FamiliesThrough(const Exact& x, std::vector<Wide>& planeIndex) const;
  /// The lexicographically first independent tuple among the families of @p mask.
  const Tuple* FirstTuple(std::uint64_t mask) const;
  /// The row of @p tu holding the vertex of plane indices @p planeIndex, and its key (the last
  /// family's plane, from the tuple's lowest) within the row.
  std::size_t RowOf(const Tuple& tu, const std::vector<Wide>& planeIndex, std::int32_t& key) const;
  /// The first and one-past-last key of row (@p c0, @p c1) of @p tu whose candidates can lie in
  /// the box (a line meets the box in a segment); empty when none.
  std::array<Wide, 2> KeysInBox(const Tuple& tu, Wide c0, Wide c1) const;
  std::size_t TripleSlot(int a, int b, int c) const
  {
    return (ToIndex(a) * ToIndex(this->M) + ToIndex(b)) * ToIndex(this->M) + ToIndex(c);
  }
  IntVec3 LineDirection(int a, int b) const;

  const PlaneFamilySet& Set;
  const ArrangementParameters& Params;
  int M = 0;                              ///< families
  int Dim = 3;                            ///< 2 for a planar arrangement
  std::vector<std::array<Wide, 2>> Range; ///< per family: plane indices meeting the box
  std::vector<Tuple> Tuples;
  /// Per family triple (a, b, c) at (a·M + b)·M + c (c = 0 in 2D): its tuple, or -1 when the
  /// normals are dependent.
  std::vector<std::int32_t> TupleAt;
  /// The vertices by generating tuple and row (compressed rows): row r's are entries
  /// RowStart[r] .. RowStart[r + 1] of Keys (ascending) and Ids. Memory in proportion to the
  /// vertices and rows, not to every candidate of the tuples' plane boxes.
  std::vector<std::int64_t> RowStart;
  std::vector<std::int32_t> Keys;
  std::vector<std::int32_t> Ids;
  std::vector<Exact> Vertices; ///< exact positions, then in scan-line order
  std::vector<std::uint64_t> Masks;
  std::map<IntVec3, int> DirectionIndex;
};

} // namespace detail
} // namespace msynth
