// SPDX-License-Identifier: BSD-3-Clause
#include "Continuous/ContinuousConstraints.h"

#include "Continuous/ConstraintPlan.h"
#include "Core/Error.h"
#include "Core/Index.h"
#include "Core/Random.h"
#include "Core/TextLists.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <numeric>
#include <set>

namespace msynth
{

int FamilyAlongAxis(const PlaneFamilySet& families, int axis)
{
  for (int f = 0; f < families.Size(); ++f)
  {
    const IntVec3& n = families.Normal(f);
    if (n[ToIndex(axis)] != 0 && n[ToIndex((axis + 1) % 3)] == 0 && n[ToIndex((axis + 2) % 3)] == 0)
    {
      return f;
    }
  }
  return -1;
}

int ParseObjectType(const std::string& text, const std::map<int, std::string>& typeNames)
{
  long long value = 0;
  if (ParseInteger(text, 1, 1 << 30, value))
    return static_cast<int>(value);
  for (const auto& [type, name] : typeNames)
  {
    if (name == text)
      return type;
  }
  std::string known;
  for (const auto& [type, name] : typeNames)
    known += (known.empty() ? "" : ", ") + name + "=" + std::to_string(type);
  throw Error("'" + text + "' is not an object type (a number ≥ 1" +
    (known.empty() ? std::string(")") : ", or one of " + known + ")"));
}

ThicknessConstraint ParseThickness(const std::string& text, const PlaneFamilySet& families,
  const std::map<int, std::string>& typeNames)
{
  const auto parts = SplitText(text, ':');
  if (parts.size() < 2 || parts.size() > 3)
    throw Error("thickness '" + text + "' is not TYPE:AXIS[:N] or TYPE:AXIS:N+");
  ThicknessConstraint c;
  try
  {
    c.Type = ParseObjectType(parts[0], typeNames);
  }
  catch (const Error& e)
  {
    throw Error("thickness '" + text + "': " + e.what());
  }
  // AXES: x, y, z and hK, one after the other.
  std::vector<int> across;
  long long value = 0;
  for (std::size_t at = 0; at < parts[1].size();)
  {
    const char a = parts[1][at];
    if (a == 'x' || a == 'y' || a == 'z')
    {
      const int family = FamilyAlongAxis(families, a - 'x');
      if (family < 0)
        throw Error("thickness '" + text + "': the example has no planes across " +
          std::string(1, a) + " (no face with a normal along " + std::string(1, a) +
          "); name a family as h1..h" + std::to_string(families.Size()));
      across.push_back(family);
      ++at;
      continue;
    }
    std::size_t end = at + 1;
    while (end < parts[1].size() && std::isdigit(static_cast<unsigned char>(parts[1][end])))
      ++end;
    if (a != 'h' || !ParseInteger(parts[1].substr(at + 1, end - at - 1), 1, families.Size(), value))
      throw Error("thickness '" + text + "': the axis must be x, y, z or h1..h" +
        std::to_string(families.Size()) + " (or several for a width), not '" + parts[1] + "'");
    across.push_back(static_cast<int>(value) - 1);
    at = end;
  }
  if (across.empty())
    throw Error("thickness '" + text + "' names no axis");
  std::sort(across.begin(), across.end());
  across.erase(std::unique(across.begin(), across.end()), across.end());
  c.Family = across[0];
  c.OrFamilies.assign(across.begin() + 1, across.end());
  if (!c.OrFamilies.empty() && parts.size() == 3)
    throw Error("thickness '" + text + "': a width across several axes is one spacing (no :N)");
  std::string spacings = parts.size() == 3 ? parts[2] : "1";
  c.Multiples = !spacings.empty() && spacings.back() == '+';
  if (c.Multiples)
    spacings.pop_back();
  if (!ParseInteger(spacings, 1, 1000000, value))
    throw Error("thickness '" + text +
      "': N must be a whole number of plane spacings ≥ 1 (N+ for multiples of N)");
  c.Spacings = static_cast<int>(value);
  return c;
}

ConnectivityConstraint ParseConnected(
  const std::string& text, const std::map<int, std::string>& typeNames)
{
  const auto parts = SplitText(text, ':');
  if (parts.size() > 2 || parts[0].empty())
    throw Error("connectivity '" + text + "' is not TYPE[:SEEDS]");
  ConnectivityConstraint c;
  try
  {
    c.Type = parts[0] == "solid" ? 0 : ParseObjectType(parts[0], typeNames);
  }
  catch (const Error& e)
  {
    throw Error("connectivity '" + text + "': " + e.what());
  }
  long long value = 1;
  if (parts.size() == 2 && !ParseInteger(parts[1], 0, 1000000, value))
    throw Error("connectivity '" + text + "': SEEDS must be a whole number ≥ 0");
  c.Seeds = static_cast<int>(value);
  return c;
}

namespace detail
{

std::int64_t SolidComponents(const PlaneArrangement& arrangement,
  const std::vector<std::int32_t>& labels, const std::function<std::uint64_t(int, int)>& edgeTypes,
  std::uint64_t solidMask, const std::vector<std::uint64_t>& labelTypes,
  std::vector<std::int64_t>& component)
{
  const std::int64_t n = arrangement.NumberOfVertices();
  component.assign(ToIndex(n), -1);
  std::int64_t parts = 0;
  std::vector<std::int64_t> stack;
  for (std::int64_t s = 0; s < n; ++s)
  {
    if (component[ToIndex(s)] >= 0 || !(labelTypes[ToIndex(labels[ToIndex(s)])] & solidMask))
      continue;
    component[ToIndex(s)] = parts;
    stack.push_back(s);
    while (!stack.empty())
    {
      const std::int64_t v = stack.back();
      stack.pop_back();
      const int a = labels[ToIndex(v)];
      for (const auto* l = arrangement.LinksBegin(v); l != arrangement.LinksEnd(v); ++l)
      {
        if (l->Vertex >= 0 && component[ToIndex(l->Vertex)] < 0 &&
          (edgeTypes(l->Direction, a) & solidMask))
        {
          component[ToIndex(l->Vertex)] = parts;
          stack.push_back(l->Vertex);
        }
      }
    }
    ++parts;
  }
  return parts;
}

ConstraintPlan::ConstraintPlan(const PolyhedralAnalysis& analysis,
  const PlaneArrangement& arrangement, const ContinuousConstraints& constraints, std::uint64_t seed)
  : Analysis(analysis)
  , Arrangement(arrangement)
  , Constraints(constraints)
  , K(ToIndex(analysis.NumberOfLabels()))
  , Words(static_cast<int>((analysis.NumberOfLabels() + 63) / 64))
{
  const PlaneFamilySet& set = arrangement.Families();
  std::set<int> types{ 0 };
  for (const auto& info : analysis.Labels())
    for (int t : info.Label.TypesPresent())
      types.insert(t);
  this->Types.assign(types.begin(), types.end());
  if (this->Types.size() > 64)
    throw Error("continuous synthesis: constraints handle at most 63 object types");
  const std::size_t nt = this->Types.size();
  for (std::size_t t = 1; t < nt; ++t)
    this->Solid |= Bit(static_cast<int>(t));
  this->TypesOfLabel.resize(this->K);
  this->Share.assign(this->K * nt, 0.0);
  this->WithType.assign(nt, std::vector<std::uint64_t>(ToIndex(this->Words), 0));
  for (std::size_t a = 0; a < this->K; ++a)
  {
    const NeighbourhoodLabel& label = analysis.Label(static_cast<int>(a)).Label;
    int cones = 0;
    for (auto type : label.Types)
    {
      if (type < 0)
        continue;
      ++cones;
      const int t = this->BitOf(type);
      this->TypesOfLabel[a] |= Bit(t);
      this->Share[a * nt + ToIndex(t)] += 1;
    }
    for (std::size_t t = 0; t < nt; ++t)
    {
      this->Share[a * nt + t] /= std::max(cones, 1);
      if ((this->TypesOfLabel[a] >> t) & 1u)
        SetLabel(this->WithType[t], a);
    }
  }
  const int directions = arrangement.NumberOfDirections();
  this->TypesOfEdge.resize(ToIndex(directions) * this->K);
  for (int d = 0; d < directions; ++d)
  {
    for (std::size_t a = 0; a < this->K; ++a)
    {
      std::uint64_t mask = 0;
      for (int type : analysis.Label(static_cast<int>(a))
                        .Label.Evaluate(set, arrangement.Direction(d))
                        .TypesPresent())
        mask |= Bit(this->BitOf(type));
      this->TypesOfEdge[ToIndex(d) * this->K + a] = mask;
    }
  }

  this->PlanGround();
  this->PlanThickness();
  this->PlanOverhang();
  this->PlanGuide();
  this->PlanTargets();
  this->PlanSeeds(seed);
}

void ConstraintPlan::PlanGround()
{
  // Grounded: which labels the example has on its ground, and above it.
  const auto& params = this->Arrangement.Parameters();
  this->GroundAxis = this->Arrangement.Planar() ? 1 : 2;
  const auto g = ToIndex(this->GroundAxis);
  this->GroundLevel = params.Origin[g] + params.Quantum * static_cast<double>(params.BoxLow[g]);
  this->GroundTolerance =
    1e-6 * params.Quantum * static_cast<double>(params.BoxHigh[g] - params.BoxLow[g]) +
    1e-9 * params.Quantum;
  if (this->Constraints.Grounded)
  {
    const double level = this->Analysis.Low()[g];
    const double tolerance = 1e-6 * std::max(this->Analysis.High()[g] - level, 1e-300);
    std::vector<char> onGround(this->K, 0), above(this->K, 0);
    for (const auto& f : this->Analysis.Features())
    {
      const bool ground =
        std::abs(f.A[g] - level) <= tolerance && std::abs(f.B[g] - level) <= tolerance;
      (ground ? onGround : above)[ToIndex(f.Label)] = 1;
    }
    this->GroundAllowed.assign(ToIndex(this->Words), 0);
    this->AboveAllowed.assign(ToIndex(this->Words), 0);
    for (std::size_t a = 0; a < this->K; ++a)
    {
      const bool volume = this->Analysis.Label(static_cast<int>(a)).Kind == FeatureKind::Volume;
      if (volume || onGround[a])
        SetLabel(this->GroundAllowed, a);
      if (volume || above[a])
        SetLabel(this->AboveAllowed, a);
    }
    this->Grow |= this->Solid;
    this->GrowGroups.push_back(this->Solid);
  }
}

void ConstraintPlan::PlanGuide()
{
  // The guide's weights by type bit.
  if (this->Constraints.Guide)
  {
    const auto& guide = *this->Constraints.Guide;
    const std::int64_t cells = guide.Dims[0] * guide.Dims[1] * guide.Dims[2];
    for (const auto& [type, weights] : guide.Weights)
    {
      if (type < 1)
        throw Error("guide: weights are for object types ≥ 1 (empty space cannot be removed)");
      if (static_cast<std::int64_t>(weights.size()) != cells)
        throw Error("guide: the weights of type " + std::to_string(type) + " have " +
          std::to_string(weights.size()) + " values for " + std::to_string(cells) + " cells");
      for (float w : weights)
        if (!(w >= 0) || !std::isfinite(w))
          throw Error(
            "guide: the weights of type " + std::to_string(type) + " must be finite and ≥ 0");
      const int t = this->BitOf(type);
      if (t > 0)
      {
        this->GuideWeights.emplace_back(t, &weights);
        this->HasGuideWeights = this->HasGuideWeights ||
          std::any_of(weights.begin(), weights.end(), [](float w) { return w != 0 && w != 1; });
      }
    }
  }
}

void ConstraintPlan::PlanTargets()
{
  const std::size_t nt = this->Types.size();
  // Proportions: the example's volume fractions, replaced by the targets given.
  this->Target.assign(nt, 0.0);
  double given = 0, rest = 0;
  for (const auto& [type, fraction] : this->Constraints.TargetFractions)
  {
    const int t = this->BitOf(type);
    if (t <= 0)
      throw Error("target: the example has no object type " + std::to_string(type));
    if (!(fraction >= 0 && fraction <= 1))
      throw Error("target: the fraction of type " + std::to_string(type) + " must be in [0, 1]");
    this->Target[ToIndex(t)] = fraction;
    given += fraction;
  }
  if (given > 1 + 1e-9)
    throw Error("target: the fractions add up to more than 1");
  for (const auto& [type, volume] : this->Analysis.TypeVolumes())
  {
    const int t = this->BitOf(type);
    if (t > 0 && !this->Constraints.TargetFractions.count(type))
      rest += std::max(volume, 0.0);
  }
  for (const auto& [type, volume] : this->Analysis.TypeVolumes())
  {
    const int t = this->BitOf(type);
    if (t > 0 && !this->Constraints.TargetFractions.count(type) && rest > 0)
      this->Target[ToIndex(t)] = (1 - given) * std::max(volume, 0.0) / rest;
  }
  this->Proportions =
    !this->Constraints.TargetFractions.empty() || (this->Constraints.KeepProportions && nt > 2);
}

void ConstraintPlan::PlanSeeds(std::uint64_t seed)
{
  // Connectivity seeds: random vertices that can hold the type's interior.
  Random rng = Random::Derived(seed, 0x5eed5, 0);
  std::map<std::int64_t, std::uint64_t> seeds;
  for (const auto& c : this->Constraints.Connected)
  {
    if (c.Seeds < 0)
      throw Error("connectivity: the number of seeds must be ≥ 0");
    const int t = c.Type == 0 ? 0 : this->BitOf(c.Type);
    if (c.Type != 0 && t <= 0)
      throw Error("connectivity: the example has no object type " + std::to_string(c.Type));
    if (c.Seeds == 0)
      continue;
    const std::uint64_t mask = c.Type == 0 ? this->Solid : Bit(t);
    this->Grow |= mask;
    if (c.Type != 0)
      this->Networks |= mask;
    this->GrowGroups.push_back(mask);
    this->FillMask |= mask;
    const int interior =
      this->Analysis.Find(NeighbourhoodLabel::Constant(c.Type == 0 ? this->Types.back() : c.Type));
    std::vector<std::int64_t> candidates;
    for (std::int64_t v = 0; v < this->Arrangement.NumberOfVertices(); ++v)
    {
      if (this->Constraints.Grounded ? this->OnGround(v)
                                     : interior >= 0 && this->Arrangement.FamilyMask(v) == 0)
        candidates.push_back(v); // on the ground; else inside a cell, where interiors can go
    }
    if (this->Constraints.Grounded)
      this->GroundSeeded |= mask; // these types start at their seeds only, not on all the ground
    if (candidates.empty())
    {
      for (std::int64_t v = 0; v < this->Arrangement.NumberOfVertices(); ++v)
        candidates.push_back(v);
    }
    for (int s = 0; s < c.Seeds && !candidates.empty(); ++s)
    {
      const auto i = ToIndex(rng.Below(candidates.size()));
      seeds[candidates[i]] |= mask;
      candidates.erase(candidates.begin() + static_cast<std::ptrdiff_t>(i));
    }
  }
  for (const auto& [v, mask] : seeds)
  {
    this->SeedVertices.push_back(v);
    this->SeedMask.push_back(mask);
  }
  this->PlanFill();
}

void ConstraintPlan::PlanFill()
{
  // Grown objects keep growing until they fill the example's share of its bounding box (a
  // road network spreads over the box instead of closing its first loop).
  if (!this->FillMask)
    return;
  double box = 1, grown = 0;
  for (std::size_t c = 0; c < 3; ++c)
  {
    const double extent = this->Analysis.High()[c] - this->Analysis.Low()[c];
    if (extent > 0)
      box *= extent;
  }
  for (const auto& [type, volume] : this->Analysis.TypeVolumes())
  {
    const int t = this->BitOf(type);
    if (t > 0 && ((this->FillMask >> t) & 1u))
      grown += std::max(volume, 0.0);
  }
  this->FillTarget = box > 0 ? std::clamp(grown / box, 0.0, 1.0) : 0.0;
}

int ConstraintPlan::BitOf(int type) const
{
  const auto it = std::lower_bound(this->Types.begin(), this->Types.end(), type);
  return it != this->Types.end() && *it == type ? static_cast<int>(it - this->Types.begin()) : -1;
}

bool ConstraintPlan::OnGround(std::int64_t v) const
{
  return this->Arrangement.Position(v)[ToIndex(this->GroundAxis)] <=
    this->GroundLevel + this->GroundTolerance;
}

std::uint64_t ConstraintPlan::SeedTypes(std::int64_t v) const
{
  const auto it = std::lower_bound(this->SeedVertices.begin(), this->SeedVertices.end(), v);
  return it != this->SeedVertices.end() && *it == v
    ? this->SeedMask[ToIndex(it - this->SeedVertices.begin())]
    : 0;
}

std::uint64_t ConstraintPlan::StartTypes(std::int64_t v) const
{
  std::uint64_t mask = this->SeedTypes(v);
  if (this->Constraints.Grounded && this->OnGround(v))
    mask |= this->Solid & ~this->GroundSeeded;
  return mask;
}

std::int64_t ConstraintPlan::CellOf(std::int64_t v) const
{
  const auto& guide = *this->Constraints.Guide;
  const auto& params = this->Arrangement.Parameters();
  const Point3& p = this->Arrangement.Position(v);
  std::int64_t cell[3] = { 0, 0, 0 };
  for (std::size_t c = 0; c < 3; ++c)
  {
    const double low = params.Origin[c] + params.Quantum * static_cast<double>(params.BoxLow[c]);
    const double extent =
      params.Quantum * static_cast<double>(params.BoxHigh[c] - params.BoxLow[c]);
    if (extent > 0)
      cell[c] = std::clamp<std::int64_t>(static_cast<std::int64_t>(std::floor((p[c] - low) /
                                           extent * static_cast<double>(guide.Dims[c]))),
        0, guide.Dims[c] - 1);
  }
  return cell[0] + guide.Dims[0] * (cell[1] + guide.Dims[1] * cell[2]);
}

void ConstraintPlan::Restrict(std::int64_t v, std::uint64_t* domain) const
{
  auto keep = [&](const std::vector<std::uint64_t>& allowed)
  {
    for (int w = 0; w < this->Words; ++w)
      domain[w] &= allowed[ToIndex(w)];
  };
  if (this->Constraints.Grounded)
    keep(this->OnGround(v) ? this->GroundAllowed : this->AboveAllowed);
  const auto& params = this->Arrangement.Parameters();
  for (const auto& s : this->Thickness)
  {
    if (s.Needs)
    {
      if ((this->Arrangement.FamilyMask(v) & s.Needs) == s.Needs)
        keep(s.OuterAllowed);
      continue;
    }
    if (!((this->Arrangement.FamilyMask(v) >> s.Family) & 1u))
      continue;
    if (s.Spacings == 1)
    {
      keep(s.OuterAllowed);
      continue;
    }
    const IntVec3& n = this->Arrangement.Families().Normal(s.Family);
    const Point3& p = this->Arrangement.Position(v);
    double dot = 0;
    for (std::size_t k = 0; k < 3; ++k)
      dot += static_cast<double>(n[k]) * (p[k] - params.Origin[k]) / params.Quantum;
    const std::int64_t c =
      std::llround((dot - static_cast<double>(params.Offsets[ToIndex(s.Family)])) /
        static_cast<double>(params.Spacings[ToIndex(s.Family)]));
    keep((c - s.Lowest) % s.Spacings == 0 ? s.OuterAllowed : s.InnerAllowed);
  }
  if (!this->GuideWeights.empty())
  {
    const auto cell = ToIndex(this->CellOf(v));
    for (const auto& [t, weights] : this->GuideWeights)
    {
      if ((*weights)[cell] == 0)
      {
        const auto& with = this->WithType[ToIndex(t)];
        for (int w = 0; w < this->Words; ++w)
          domain[w] &= ~with[ToIndex(w)];
      }
    }
  }
}

namespace
{
/// The proportion steering's weight by occupancy: a label holding a fraction f of its cones of a
/// type whose share is r times too small is weighted r^(16 f) more (a face, f = 1/2: r^8; the
/// edge that ends the object, f = 1/4: r^4). 8 and 32 were tried on the bundled examples: 16
/// held the grounded cottage in 5 of 5 seeds and changed no other example's matrix.
constexpr double OccupancyGain = 16;
} // namespace

double ConstraintPlan::Factor(std::int64_t v, int label, const std::vector<double>& tally) const
{
  double factor = 1;
  const std::uint64_t types = this->LabelTypes(label);
  if (this->HasGuideWeights)
  {
    const auto cell = ToIndex(this->CellOf(v));
    for (const auto& [t, weights] : this->GuideWeights)
      if ((types >> t) & 1u)
        factor *= (*weights)[cell];
  }
  if (this->FillTarget > 0 && (types & this->FillMask))
  {
    // Labels holding more of a grown type weigh more while the grown types fill less of the
    // whole box than they fill of the example's (vertices of the arrangement stand for equal
    // parts of the box).
    double grown = 0, held = 0;
    for (std::size_t t = 0; t < this->Types.size(); ++t)
    {
      if ((this->FillMask >> t) & 1u)
      {
        grown += tally[t];
        held += this->Occupancy(label, static_cast<int>(t));
      }
    }
    grown /= static_cast<double>(std::max<std::int64_t>(this->Arrangement.NumberOfVertices(), 1));
    const double ratio = std::clamp(this->FillTarget / std::max(grown, 1e-12), 1.0 / 64, 64.0);
    factor *= std::pow(ratio, 2 * held);
  }
  if (this->Proportions && (types & this->Solid))
  {
    // Shares so far, with a prior of 32 vertices' worth at the targets.
    const double prior = 32;
    double total = prior;
    for (std::size_t t = 1; t < this->Types.size(); ++t)
      total += tally[t];
    for (std::size_t t = 1; t < this->Types.size(); ++t)
    {
      if (!((types >> t) & 1u))
        continue;
      const double share = (tally[t] + prior * this->Target[t]) / total;
      const double ratio = this->Target[t] / std::max(share, 1e-12);
      // By presence, not by the label's share of the type: labels that start an object (a
      // corner holds an eighth of it) decide the proportions as much as those inside one.
      factor *= std::clamp(ratio * ratio, 1.0 / 64, 64.0);
      // And by how much of it the label holds: among labels that all hold a type that is short,
      // the one holding more of it (the porch's top face that carries it on, rather than the edge
      // that ends it) wins, so a scarce type grows as well as starts (issue 29: the cottage's
      // porches and chimneys).
      factor *=
        std::clamp(std::pow(ratio, OccupancyGain * this->Occupancy(label, static_cast<int>(t))),
          1.0 / 64, 64.0);
    }
  }
  return factor;
}

double ConstraintPlan::Mismatch(const std::vector<double>& tally) const
{
  double total = 0, sum = 0;
  for (std::size_t t = 1; t < this->Types.size(); ++t)
    total += tally[t];
  if (!(total > 0))
    return 0;
  for (std::size_t t = 1; t < this->Types.size(); ++t)
  {
    const double d = tally[t] / total - this->Target[t];
    sum += d * d;
  }
  return sum;
}

std::int64_t ConstraintPlan::SeedsOfAllSolid() const
{
  std::uint64_t seeded = 0;
  std::int64_t seeds = 0;
  for (const auto& c : this->Constraints.Connected)
  {
    if (c.Seeds <= 0)
      continue;
    seeded |= c.Type == 0 ? this->Solid : Bit(this->BitOf(c.Type));
    seeds += c.Seeds;
  }
  return seeded != 0 && seeded == this->Solid ? seeds : 0;
}

bool ConstraintPlan::RemovesStrayParts() const
{
  return this->Constraints.Grounded || !this->SeedVertices.empty();
}

ConstraintPlan::Removed ConstraintPlan::RemoveStrayParts(
  std::vector<std::int32_t>& labels, int emptyLabel) const
{
  Removed removed;
  if (!this->RemovesStrayParts())
    return removed;
  std::vector<std::int64_t> component;
  const std::int64_t parts = SolidComponents(
    this->Arrangement, labels, [this](int d, int a) { return this->EdgeTypes(d, a); }, this->Solid,
    this->TypesOfLabel, component);
  std::vector<char> keep(ToIndex(parts), this->Constraints.Grounded ? 0 : 1);
  std::vector<std::int64_t> size(ToIndex(parts), 0);
  for (std::int64_t v = 0; v < this->Arrangement.NumberOfVertices(); ++v)
  {
    const std::int64_t c = component[ToIndex(v)];
    if (c < 0)
      continue;
    size[ToIndex(c)] += 1;
    if (this->Constraints.Grounded && this->OnGround(v))
      keep[ToIndex(c)] = 1;
  }
  removed.Floating = parts - std::count(keep.begin(), keep.end(), 1);
  if (const std::int64_t seeds = this->SeedsOfAllSolid())
  {
    // The largest parts kept, as many as the seeds (ties: the part found first).
    std::vector<std::int64_t> order;
    for (std::int64_t c = 0; c < parts; ++c)
      if (keep[ToIndex(c)])
        order.push_back(c);
    std::stable_sort(order.begin(), order.end(),
      [&size](std::int64_t x, std::int64_t y) { return size[ToIndex(x)] > size[ToIndex(y)]; });
    for (std::size_t k = ToIndex(seeds); k < order.size(); ++k)
    {
      keep[ToIndex(order[k])] = 0;
      ++removed.BeyondSeeds;
    }
  }
  else
  {
    // A type grown from seeds among others (a road network among houses): later blocks can
    // cut it, so the parts holding the most of it are kept, as many as its seeds, and the
    // other parts holding it emptied (with what stands on or against them).
    for (const auto& c : this->Constraints.Connected)
    {
      const std::uint64_t mask = c.Type == 0 ? 0 : Bit(this->BitOf(c.Type));
      if (c.Seeds <= 0 || !(mask & this->Networks))
        continue;
      std::vector<std::int64_t> held(ToIndex(parts), 0);
      for (std::int64_t v = 0; v < this->Arrangement.NumberOfVertices(); ++v)
        if (const std::int64_t p = component[ToIndex(v)];
            p >= 0 && (this->TypesOfLabel[ToIndex(labels[ToIndex(v)])] & mask))
          held[ToIndex(p)] += 1;
      std::vector<std::int64_t> order;
      for (std::int64_t p = 0; p < parts; ++p)
        if (keep[ToIndex(p)] && held[ToIndex(p)] > 0)
          order.push_back(p);
      std::stable_sort(order.begin(), order.end(),
        [&held](std::int64_t x, std::int64_t y) { return held[ToIndex(x)] > held[ToIndex(y)]; });
      for (std::size_t k = ToIndex(c.Seeds); k < order.size(); ++k)
      {
        keep[ToIndex(order[k])] = 0;
        ++removed.BeyondSeeds;
      }
    }
  }
  for (std::int64_t v = 0; v < this->Arrangement.NumberOfVertices(); ++v)
  {
    const std::int64_t c = component[ToIndex(v)];
    if (c >= 0 && !keep[ToIndex(c)])
      labels[ToIndex(v)] = emptyLabel;
  }
  return removed;
}

std::int64_t ConstraintPlan::EmptyPartsAt(std::vector<std::int32_t>& labels, int emptyLabel,
  const std::vector<std::int64_t>& vertices) const
{
  if (vertices.empty())
    return 0;
  std::vector<std::int64_t> component;
  const std::int64_t parts = SolidComponents(
    this->Arrangement, labels, [this](int d, int a) { return this->EdgeTypes(d, a); }, this->Solid,
    this->TypesOfLabel, component);
  std::vector<char> empty(ToIndex(parts), 0);
  for (const std::int64_t v : vertices)
    if (component[ToIndex(v)] >= 0)
      empty[ToIndex(component[ToIndex(v)])] = 1;
  for (std::int64_t v = 0; v < this->Arrangement.NumberOfVertices(); ++v)
  {
    const std::int64_t c = component[ToIndex(v)];
    if (c >= 0 && empty[ToIndex(c)])
      labels[ToIndex(v)] = emptyLabel;
  }
  return std::count(empty.begin(), empty.end(), 1);
}

} // namespace detail

ArrangementMeasures MeasureArrangement(const PolyhedralAnalysis& analysis,
  const PlaneArrangement& arrangement, const std::vector<std::int32_t>& labels)
{
  ContinuousConstraints none;
  none.KeepProportions = false;
  const detail::ConstraintPlan plan(analysis, arrangement, none, 0);
  ArrangementMeasures m;
  std::vector<std::int64_t> component;
  std::vector<std::uint64_t> types(ToIndex(analysis.NumberOfLabels()));
  for (int a = 0; a < analysis.NumberOfLabels(); ++a)
    types[ToIndex(a)] = plan.LabelTypes(a);
  m.Components = detail::SolidComponents(
    arrangement, labels, [&plan](int d, int a) { return plan.EdgeTypes(d, a); }, plan.SolidMask(),
    types, component);
  std::set<std::int64_t> grounded;
  std::vector<double> tally(ToIndex(plan.NumberOfTypes()), 0.0);
  double solid = 0;
  for (std::int64_t v = 0; v < arrangement.NumberOfVertices(); ++v)
  {
    const auto c = component[ToIndex(v)];
    if (c >= 0 && plan.OnGround(v))
      grounded.insert(c);
    for (int t = 1; t < plan.NumberOfTypes(); ++t)
    {
      const double o = plan.Occupancy(labels[ToIndex(v)], t);
      tally[ToIndex(t)] += o;
      solid += o;
    }
  }
  m.GroundedComponents = static_cast<std::int64_t>(grounded.size());
  for (int t = 1; t < plan.NumberOfTypes(); ++t)
    m.TypeShares[plan.TypeAt(t)] = solid > 0 ? tally[ToIndex(t)] / solid : 0.0;
  return m;
}

} // namespace msynth
