// SPDX-License-Identifier: BSD-3-Clause
// The dimensional constraints of ConstraintPlan (TVCG §4.5): thickness in slabs, widths of
// networks and overhang limits, each compiled to the labels allowed at a vertex.
#include "Continuous/ConstraintPlan.h"
#include "Core/Error.h"
#include "Core/Index.h"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <limits>
#include <map>

namespace msynth
{
namespace detail
{
namespace
{
/// The families of bit set @p mask, ascending.
std::vector<int> FamiliesOf(std::uint64_t mask)
{
  std::vector<int> out;
  for (int f = 0; f < 64; ++f)
    if ((mask >> f) & 1u)
      out.push_back(f);
  return out;
}

/**
 * Whether @p label fills a block around its vertex: with J its families and @p needs (sorted)
 * together, some side of the families of J outside @p needs on which every cone of J's
 * arrangement exists for each side of @p needs and passes @p test(type, sides of @p needs as
 * bits). Families of @p needs absent from the label may cut its cones, so the cones are those of
 * J, not the label's own.
 */
template <typename Test>
bool HasBlock(const PlaneFamilySet& set, const NeighbourhoodLabel& label,
  const std::vector<int>& needs, Test&& test)
{
  std::vector<int> joint;
  std::set_union(label.Families.begin(), label.Families.end(), needs.begin(), needs.end(),
    std::back_inserter(joint));
  if (static_cast<int>(joint.size()) > PlaneFamilySet::MaxFamiliesPerLabel)
    return false;
  std::vector<int> inLabel(joint.size(), -1), inNeeds(joint.size(), -1);
  for (std::size_t j = 0; j < joint.size(); ++j)
  {
    const auto l = std::lower_bound(label.Families.begin(), label.Families.end(), joint[j]);
    if (l != label.Families.end() && *l == joint[j])
      inLabel[j] = static_cast<int>(l - label.Families.begin());
    const auto n = std::lower_bound(needs.begin(), needs.end(), joint[j]);
    if (n != needs.end() && *n == joint[j])
      inNeeds[j] = static_cast<int>(n - needs.begin());
  }
  std::map<unsigned, std::pair<std::size_t, bool>> groups; // rest sides → (cones, all pass)
  for (const auto& cone : set.Cones(joint))
  {
    unsigned own = 0, sides = 0, rest = 0;
    for (std::size_t j = 0; j < joint.size(); ++j)
    {
      const bool plus = (cone.Mask >> j) & 1u;
      if (inLabel[j] >= 0 && plus)
        own |= 1u << inLabel[j];
      if (inNeeds[j] >= 0)
        sides |= plus ? 1u << inNeeds[j] : 0u;
      else if (plus)
        rest |= 1u << j;
    }
    const int type = label.Types[own];
    auto& g = groups.try_emplace(rest, 0, true).first->second;
    g.first += 1;
    g.second = g.second && type >= 0 && test(type, sides);
  }
  const std::size_t block = std::size_t(1) << needs.size();
  return std::any_of(groups.begin(), groups.end(),
    [block](const auto& g) { return g.second.first == block && g.second.second; });
}
} // namespace

void ConstraintPlan::PlanThickness()
{
  const PlaneFamilySet& set = this->Arrangement.Families();
  const auto& params = this->Arrangement.Parameters();
  // Dimensional constraints: per label, whether the type passes through (or ends on) a plane of
  // the family next to the vertex, from pairs of cones on either side of it.
  for (const auto& c : this->Constraints.Thickness)
  {
    if (c.Family < 0 || c.Family >= set.Size())
      throw Error("thickness: there is no plane family h" + std::to_string(c.Family + 1));
    if (c.Spacings < 1)
      throw Error("thickness: a type must be at least one plane spacing thick");
    const int t = this->BitOf(c.Type);
    if (t <= 0)
      throw Error("thickness: the example has no object type " + std::to_string(c.Type));
    if (!c.OrFamilies.empty())
    {
      this->PlanWidth(c);
      continue;
    }
    Slabs s;
    s.Family = c.Family;
    s.Spacings = c.Spacings;
    s.OuterAllowed.assign(ToIndex(this->Words), 0);
    s.InnerAllowed.assign(ToIndex(this->Words), 0);
    for (std::size_t a = 0; a < this->K; ++a)
    {
      const NeighbourhoodLabel& label = this->Analysis.Label(static_cast<int>(a)).Label;
      const auto it = std::find(label.Families.begin(), label.Families.end(), c.Family);
      bool through = false, ends = false;
      if (it == label.Families.end())
      {
        through = ((this->TypesOfLabel[a] >> t) & 1u) != 0;
      }
      else
      {
        const unsigned bit = 1u << (it - label.Families.begin());
        for (std::size_t m = 0; m < label.Types.size(); ++m)
        {
          if ((m & bit) || label.Types[m] < 0 || label.Types[m ^ bit] < 0)
            continue;
          const bool here = label.Types[m] == c.Type, there = label.Types[m ^ bit] == c.Type;
          through = through || (here && there);
          ends = ends || (here != there);
        }
      }
      if (!through || c.Multiples)
        SetLabel(s.OuterAllowed, a);
      if (!ends)
        SetLabel(s.InnerAllowed, a);
    }
    // Slabs are counted from the lowest plane of the family in the box: the ground's for a
    // family whose normal points down (storeys stand on the ground whichever way the example's
    // faces made the normal point).
    s.Lowest = std::numeric_limits<std::int64_t>::max();
    std::int64_t highest = std::numeric_limits<std::int64_t>::min();
    const IntVec3& n = set.Normal(c.Family);
    for (std::int64_t v = 0; v < this->Arrangement.NumberOfVertices(); ++v)
    {
      if (!((this->Arrangement.FamilyMask(v) >> c.Family) & 1u))
        continue;
      const Point3& p = this->Arrangement.Position(v);
      double dot = 0;
      for (std::size_t k = 0; k < 3; ++k)
        dot += static_cast<double>(n[k]) * (p[k] - params.Origin[k]) / params.Quantum;
      const auto plane = static_cast<std::int64_t>(
        std::llround((dot - static_cast<double>(params.Offsets[ToIndex(c.Family)])) /
          static_cast<double>(params.Spacings[ToIndex(c.Family)])));
      s.Lowest = std::min(s.Lowest, plane);
      highest = std::max(highest, plane);
    }
    if (n[ToIndex(this->GroundAxis)] < 0 && highest >= s.Lowest)
      s.Lowest = highest;
    this->Thickness.push_back(std::move(s));
  }
}

void ConstraintPlan::PlanWidth(const ThicknessConstraint& c)
{
  // A label is removed where, on one side, the type fills every cone around the vertex in the
  // directions of the width's families (a block two spacings across each of them); such labels
  // are only placed at vertices on all those families.
  Slabs s;
  s.Family = c.Family;
  s.Needs = std::uint64_t(1) << c.Family;
  for (int f : c.OrFamilies)
  {
    if (f < 0 || f >= this->Arrangement.Families().Size())
      throw Error("thickness: there is no plane family h" + std::to_string(f + 1));
    s.Needs |= std::uint64_t(1) << f;
  }
  if (c.Spacings != 1)
    throw Error("thickness: a width across several plane families is one spacing");
  const PlaneFamilySet& set = this->Arrangement.Families();
  const std::vector<int> needs = FamiliesOf(s.Needs);
  s.OuterAllowed.assign(ToIndex(this->Words), 0);
  for (std::size_t a = 0; a < this->K; ++a)
  {
    const NeighbourhoodLabel& label = this->Analysis.Label(static_cast<int>(a)).Label;
    if (!HasBlock(set, label, needs, [&](int type, unsigned) { return type == c.Type; }))
      SetLabel(s.OuterAllowed, a);
  }
  this->Thickness.push_back(std::move(s));
}

void ConstraintPlan::PlanOverhang()
{
  // Undersides at most one spacing wide: at vertices on planes across every axis, no label with
  // the type above and empty space below all around the vertex horizontally.
  if (this->Constraints.Overhang.empty())
    return;
  const PlaneFamilySet& set = this->Arrangement.Families();
  const int up = FamilyAlongAxis(set, this->GroundAxis);
  if (up < 0)
    throw Error(std::string("overhang: the example has no planes across ") +
      (this->GroundAxis == 2 ? "z" : "y") + " (no face facing up or down)");
  std::uint64_t horizontal = 0;
  for (int axis = 0; axis < (this->Arrangement.Planar() ? 2 : 3); ++axis)
  {
    const int f = axis == this->GroundAxis ? -1 : FamilyAlongAxis(set, axis);
    if (axis != this->GroundAxis && f < 0)
      throw Error(std::string("overhang: the example has no planes across ") + char('x' + axis));
    if (f >= 0)
      horizontal |= std::uint64_t(1) << f;
  }
  // Which side of the up family's planes is above (its normal may point down).
  const bool upIsPositive = set.Normal(up)[ToIndex(this->GroundAxis)] > 0;
  for (int type : this->Constraints.Overhang)
  {
    if (this->BitOf(type) <= 0)
      throw Error("overhang: the example has no object type " + std::to_string(type));
    Slabs s;
    s.Needs = horizontal | (std::uint64_t(1) << up);
    const std::vector<int> needs = FamiliesOf(s.Needs);
    const unsigned vertical = 1u << (std::find(needs.begin(), needs.end(), up) - needs.begin());
    s.OuterAllowed.assign(ToIndex(this->Words), 0);
    for (std::size_t a = 0; a < this->K; ++a)
    {
      const NeighbourhoodLabel& label = this->Analysis.Label(static_cast<int>(a)).Label;
      const bool wide = HasBlock(set, label, needs,
        [&](int t, unsigned sides)
        {
          const bool above = ((sides & vertical) != 0) == upIsPositive;
          return t == (above ? type : 0);
        });
      if (!wide)
        SetLabel(s.OuterAllowed, a);
    }
    this->Thickness.push_back(std::move(s));
  }
}

} // namespace detail
} // namespace msynth
