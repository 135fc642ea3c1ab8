// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/**
 * @file SymmetryPlan.h
 * @brief Translation and rotation symmetry (dissertation §3.5.2) for discrete synthesis.
 *
 * The dissertation imposes symmetry with extra transition matrices between distant sites. Here
 * only a fundamental domain is synthesized (one period; a quadrant), and the symmetry becomes
 * the domain's seams: extra arcs between domain sites whose images are neighbours in the
 * output, each with its own relation (the adjacency rule composed with a power of the label map
 * f). A site linked to itself becomes a unary constraint. The output is the domain repeated
 * (turned) with the labels mapped by powers of f.
 */
#include "Core/Index.h"
#include "Discrete/AdjacencyRules.h"
#include "Discrete/Catalog.h"
#include "Discrete/DiscreteSynthesis.h"

#include <array>
#include <cstdint>
#include <functional>
#include <memory>
#include <vector>

namespace msynth
{
namespace detail
{

/// The six axis classes of the rules, then per extra relation i the classes 6 + 2i (label c may
/// be at the arc's target when its source holds b: Extra[i](b, c)) and 6 + 2i + 1 (converse).
class ExtendedRelation : public CompatibilityRelation
{
public:
  ExtendedRelation(
    const AdjacencyRules& rules, const std::vector<std::function<bool(int, int)>>& extra);
};

/// A permutation of label indices, applied to any power through its cycles.
class LabelMap
{
public:
  LabelMap() = default;
  explicit LabelMap(std::vector<int> f);
  int Apply(int b) const { return this->F[ToIndex(b)]; }
  /// f^j(b) for any j ≥ 0.
  int Power(int b, std::int64_t j) const;
  const std::vector<int>& Values() const { return this->F; }

private:
  std::vector<int> F;
  std::vector<int> Cycle, Position; ///< per label: its cycle and place in it
  std::vector<std::vector<int>> Cycles;
};

struct SymmetryPlan
{
  std::array<std::int64_t, 3> Full{ { 1, 1, 1 } };
  std::array<std::int64_t, 3> Domain{ { 1, 1, 1 } };
  SynthesisOptions DomainOptions; ///< the options for the domain (symmetry off, faces adjusted)
  std::unique_ptr<ExtendedRelation> Relation;
  SiteArcs Arcs; ///< over domain sites
  /// Unary constraints per domain site (Words() words each): sites linked to themselves, the
  /// centre of a rotation, and the guide at every image. Empty when there are none.
  std::vector<std::uint64_t> SiteMasks;
  std::array<std::int64_t, 3> Period{ { 0, 0, 0 } }; ///< per axis; 0: not translated
  std::array<LabelMap, 3> Shift;                     ///< per translated axis: f
  bool Rotate = false;
  LabelMap Turn; ///< the rotation's f
  /// Per xy site of the output: the domain xy site it is a turned copy of, and how many
  /// quarter turns (j: the site is R^j of the domain site, and holds f^j of its label).
  std::vector<std::int64_t> TurnSource;
  std::vector<std::uint8_t> TurnPower;

  /// The domain site (linear index) whose label gives output site @p q.
  std::int64_t Source(const std::array<std::int64_t, 3>& q) const;
  /// The label index at output site @p q given label @p b at its domain site Source(q).
  int Image(const std::array<std::int64_t, 3>& q, int b) const;
  bool HasMasks() const { return !this->SiteMasks.empty(); }
};

bool AnySeamSymmetry(const SynthesisOptions& options);

/// Validates the translation/rotation options against @p rules and plans the domain, its seams
/// and unary masks. @throw Error naming what is wrong.
std::unique_ptr<SymmetryPlan> PlanSymmetry(
  const AdjacencyRules& rules, const SynthesisOptions& options);

} // namespace detail
} // namespace msynth
