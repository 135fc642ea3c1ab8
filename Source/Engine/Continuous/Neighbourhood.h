// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/**
 * @file Neighbourhood.h
 * @brief Labels of continuous model synthesis: the neighbourhood (vertex figure, dissertation
 * Eq. 4.22) of a point, as a function on the cones of a central plane arrangement (§4.5.1–4.5.5,
 * TVCG §4.2–4.3).
 *
 * Plane families are directions up to sign. Each family i has an exact integer normal n_i and
 * the half-space h_i = { x : n_i·(x − p) < 0 } at the point p considered ("behind" n_i; the
 * analysis orients n_i along the outward normal of the family's first face, so h_i is the inside
 * of that face). Near p only the families S of the faces through p matter: their planes through
 * p cut space into open cones, each a sign vector σ over S (bit j of a cone mask set ⇔ σ_j = +,
 * that is n_j·d > 0 for the cone's directions d, outside h_j). A label maps each non-empty cone to
 * an object type (0 = empty space).
 *
 * The canonical form keeps only the families whose plane has a type change somewhere near p, so
 * equal neighbourhoods compare equal however they were derived. All sign computations are exact
 * (128-bit integer arithmetic on the integer normals).
 */
#include <array>
#include <cstdint>
#include <functional>
#include <map>
#include <string>
#include <vector>

namespace msynth
{

/// An exact integer direction (a family normal or a direction of travel).
using IntVec3 = std::array<std::int64_t, 3>;
/// Wide integer vector for products of normals (cones' interior directions).
using WideVec3 = std::array<__int128, 3>;

/// The plane families of an example: their exact normals, as indices 0..m−1 (printed h1..hm).
class PlaneFamilySet
{
public:
  PlaneFamilySet() = default;
  /// @throw Error when a normal is zero or two normals are parallel.
  explicit PlaneFamilySet(std::vector<IntVec3> normals);

  int Size() const { return static_cast<int>(this->Normals.size()); }
  const IntVec3& Normal(int family) const { return this->Normals.at(family); }
  const std::vector<IntVec3>& AllNormals() const { return this->Normals; }

  /// The sign of n_family·d, exactly.
  int Side(int family, const IntVec3& d) const;

  /// One cone of the central arrangement of a family subset: its sign mask (bit j ⇔ σ_j = +
  /// for the j-th family of the subset) and an interior direction.
  struct Cone
  {
    unsigned Mask = 0;
    WideVec3 Direction{};
    std::array<double, 3> UnitDirection{}; ///< Direction, normalized in floating point
  };
  /// The non-empty open cones of the arrangement of the planes n_i·d = 0, i ∈ @p families
  /// (sorted family indices, at most MaxFamiliesPerLabel), by ascending mask. Computed exactly
  /// from the arrangement's rays and cached.
  const std::vector<Cone>& Cones(const std::vector<int>& families) const;
  /// Rank of the normals of @p families (0–3): the codimension of the feature they meet in.
  int Rank(const std::vector<int>& families) const;

  static constexpr int MaxFamiliesPerLabel = 12;

private:
  std::vector<IntVec3> Normals;
  mutable std::map<std::vector<int>, std::vector<Cone>> ConeCache;
};

/// What a label describes, by the rank of its families: volume (interior or exterior), face,
/// edge or vertex (in 2D: region, edge, vertex).
enum class FeatureKind
{
  Volume = 0,
  Face = 1,
  Edge = 2,
  Vertex = 3
};
const char* FeatureKindName(FeatureKind kind, bool planar);

/// A neighbourhood label: the families S (sorted) and the object type of each cone of their
/// arrangement, indexed by cone mask; −1 marks a sign vector that is no cone.
class NeighbourhoodLabel
{
public:
  std::vector<int> Families;
  std::vector<std::int16_t> Types;

  /// Builds the label of the type function @p typeOfCone (called once per non-empty cone with
  /// its mask and interior direction) over @p families, in canonical form.
  static NeighbourhoodLabel FromFunction(const PlaneFamilySet& set, std::vector<int> families,
    const std::function<int(const PlaneFamilySet::Cone&)>& typeOfCone);
  /// The constant label: every direction has @p type (∅ for 0).
  static NeighbourhoodLabel Constant(int type);

  /// Drops every family whose plane has no type change; unique result.
  void Canonicalize();
  /// The label met when travelling from the point in direction @p d (§4.5.5), canonical.
  NeighbourhoodLabel Evaluate(const PlaneFamilySet& set, const IntVec3& d) const;
  FeatureKind Kind(const PlaneFamilySet& set) const;
  /// The object types present (ascending, 0 included when some cone is empty space).
  std::vector<int> TypesPresent() const;
  /// A readable Boolean expression: minimized union of intersections of h_i and h_iᶜ, factored;
  /// "∅", "ℝ³" (ℝ² for @p planar); with several object types "1·(…) + 2·(…)".
  std::string Expression(bool planar) const;

  bool operator==(const NeighbourhoodLabel& o) const
  {
    return this->Families == o.Families && this->Types == o.Types;
  }
  bool operator!=(const NeighbourhoodLabel& o) const { return !(*this == o); }
  bool operator<(const NeighbourhoodLabel& o) const;
};

/// Two labels joined along an edge of direction @p d (from @p a toward @p b) are compatible
/// when eval(a, d) = eval(b, −d) (§4.5.5).
bool CompatibleAlong(const PlaneFamilySet& set, const NeighbourhoodLabel& a,
  const NeighbourhoodLabel& b, const IntVec3& d);

/// A Boolean function of a few variables printed as a minimized, factored formula; variable j
/// prints as names[j], its complement as names[j] + "ᶜ". Minterm bit j set ⇔ variable j false
/// (outside h_j, matching cone masks). @p dontCare minterms may be covered or not.
std::string MinimizedExpression(int numberOfVariables, const std::vector<bool>& on,
  const std::vector<bool>& dontCare, const std::vector<std::string>& names);

} // namespace msynth
