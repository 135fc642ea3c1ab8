// SPDX-License-Identifier: BSD-3-Clause
#include "Continuous/ContinuousMirror.h"

#include "Continuous/ConstraintPlan.h"
#include "Core/Error.h"
#include "Core/Index.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <sstream>

namespace msynth
{

namespace
{
std::int64_t Mod(std::int64_t a, std::int64_t m)
{
  return ((a % m) + m) % m;
}
const char* AxisName(int axis)
{
  return axis == 0 ? "x" : (axis == 1 ? "y" : "z");
}
} // namespace

ArrangementMirror PlanArrangementMirror(
  const PolyhedralAnalysis& analysis, const ArrangementParameters& parameters, int axis)
{
  if (axis < 0 || axis > 2 || (parameters.Planar && axis == 2))
    throw Error("mirror: the axis must be x or y (or z in 3D)");
  const PlaneFamilySet& set = analysis.Families();
  ArrangementMirror plan;
  plan.Axis = axis;
  const auto a = ToIndex(axis);
  // The seam: the last plane of the family normal to the axis at or before the middle.
  int across = -1;
  for (int f = 0; f < set.Size(); ++f)
  {
    const IntVec3& n = set.Normal(f);
    if (n[a] != 0 && n[(a + 1) % 3] == 0 && n[(a + 2) % 3] == 0)
      across = f;
  }
  if (across < 0)
    throw Error(std::string("mirror: the example has no faces across ") + AxisName(axis) +
      ", so there is no plane to mirror about");
  plan.Family = across;
  // Each family's reflected planes must be a family's planes; returns the first family that
  // fails for the seam @p seam, or −1.
  auto reflect = [&](std::int64_t seam)
  {
    plan.FamilyImage.clear();
    plan.Flipped.clear();
    for (int f = 0; f < set.Size(); ++f)
    {
      IntVec3 r = set.Normal(f);
      r[a] = -r[a];
      const IntVec3 minus{ -r[0], -r[1], -r[2] };
      int image = -1;
      bool flipped = false;
      for (int g = 0; g < set.Size() && image < 0; ++g)
      {
        if (set.Normal(g) == r || set.Normal(g) == minus)
        {
          image = g;
          flipped = set.Normal(g) == minus;
        }
      }
      const auto fs = ToIndex(f);
      bool planes = image >= 0 && parameters.Spacings[fs] == parameters.Spacings[ToIndex(image)];
      if (planes)
      {
        // X' = R(X): n·X = r·X' + 2M·n_a, so X' lies on r·X' ∈ o_f − 2M·n_a + s·Z.
        const std::int64_t s = parameters.Spacings[fs];
        const std::int64_t shifted = parameters.Offsets[fs] - Mod(2 * seam * set.Normal(f)[a], s);
        const std::int64_t target = parameters.Offsets[ToIndex(image)];
        planes = flipped ? Mod(target + shifted, s) == 0 : Mod(target - shifted, s) == 0;
      }
      if (!planes)
        return f;
      plan.FamilyImage.push_back(image);
      plan.Flipped.push_back(flipped ? 1 : 0);
    }
    return -1;
  };
  // The seam: the last plane of the family across the axis, at or before the middle of the box,
  // about which every family reflects onto planes.
  const std::int64_t k = set.Normal(across)[a]; // its planes: k·X_a = o + c·s
  const std::int64_t o = parameters.Offsets[ToIndex(across)];
  const std::int64_t s = parameters.Spacings[ToIndex(across)];
  const std::int64_t middle = (parameters.BoxLow[a] + parameters.BoxHigh[a]) / 2;
  int failing = -2;
  std::int64_t x = middle;
  while (x >= parameters.BoxLow[a] && Mod(k * x - o, s) != 0)
    --x;
  for (; x >= parameters.BoxLow[a]; --x) // exact units: a few million at most
  {
    if (Mod(k * x - o, s) != 0)
      continue;
    const int f = reflect(x);
    if (failing == -2)
      failing = f;
    if (f < 0)
    {
      plan.Seam = x;
      break;
    }
  }
  if (failing == -2)
    throw Error(std::string("mirror: no plane across ") + AxisName(axis) +
      " lies in the first half of the box");
  if (plan.FamilyImage.size() != ToIndex(set.Size()))
    throw Error("mirror: the planes of family h" + std::to_string(failing + 1) +
      " do not reflect onto planes of the arrangement across any plane of " + AxisName(axis) +
      " in the box (the example's faces are not mirror-symmetric on its plane spacing)");
  for (const auto& info : analysis.Labels())
    plan.LabelImage.push_back(analysis.Find(MirrorLabel(set, info.Label, plan)));
  return plan;
}

NeighbourhoodLabel MirrorLabel(
  const PlaneFamilySet& families, const NeighbourhoodLabel& label, const ArrangementMirror& plan)
{
  std::vector<int> images;
  for (int f : label.Families)
    images.push_back(plan.FamilyImage[ToIndex(f)]);
  std::vector<int> sorted = images;
  std::sort(sorted.begin(), sorted.end());
  return NeighbourhoodLabel::FromFunction(families, sorted,
    [&](const PlaneFamilySet::Cone& cone)
    {
      // The reflected cone's sign on family images[j] is the original sign on label family j,
      // negated when the reflected normal is minus the image's normal.
      unsigned original = 0;
      for (std::size_t j = 0; j < images.size(); ++j)
      {
        const auto position =
          ToIndex(std::find(sorted.begin(), sorted.end(), images[j]) - sorted.begin());
        bool plus = (cone.Mask >> position) & 1u;
        if (plan.Flipped[ToIndex(label.Families[j])])
          plus = !plus;
        if (plus)
          original |= 1u << j;
      }
      return static_cast<int>(label.Types[original]);
    });
}

void RestrictToMirrorImages(const std::vector<const ArrangementMirror*>& plans,
  const PlaneArrangement& part, std::vector<std::uint64_t>& catalogs)
{
  if (plans.empty())
    return;
  const int k = static_cast<int>(plans[0]->LabelImage.size());
  const auto words = ToIndex((k + 63) / 64);
  // Labels whose image under every product of the reflections exists (the reflections commute).
  std::vector<std::uint64_t> imaged(words, 0);
  for (int a = 0; a < k; ++a)
  {
    bool all = true;
    for (unsigned subset = 1; all && subset < (1u << plans.size()); ++subset)
    {
      int image = a;
      for (std::size_t j = 0; j < plans.size() && image >= 0; ++j)
        if ((subset >> j) & 1u)
          image = plans[j]->LabelImage[ToIndex(image)];
      all = image >= 0;
    }
    if (all)
      imaged[ToIndex(a >> 6)] |= std::uint64_t(1) << (a & 63);
  }
  const auto& p = part.Parameters();
  for (const ArrangementMirror* plan : plans)
  {
    std::vector<std::uint64_t> symmetric(words, 0);
    for (int a = 0; a < k; ++a)
      if (plan->LabelImage[ToIndex(a)] == a)
        symmetric[ToIndex(a >> 6)] |= std::uint64_t(1) << (a & 63);
    const auto axis = ToIndex(plan->Axis);
    const double seam = p.Origin[axis] + p.Quantum * static_cast<double>(plan->Seam);
    const double near = 0.25 * p.Spacing(part.Families(), plan->Family);
    for (std::int64_t v = 0; v < part.NumberOfVertices(); ++v)
    {
      // On the seam: on a plane of the family across the axis, and nearer than its spacing.
      const bool onSeam = ((part.FamilyMask(v) >> plan->Family) & 1u) &&
        std::abs(part.Position(v)[axis] - seam) < near;
      std::uint64_t* d = catalogs.data() + ToIndex(v) * words;
      for (std::size_t w = 0; w < words; ++w)
        d[w] &= onSeam ? symmetric[w] : imaged[w];
    }
  }
}

namespace
{
/// Vertices by position (cells of a quarter of the smallest spacing), to find a vertex's mirror.
class VertexFinder
{
public:
  VertexFinder(const PlaneArrangement& arrangement, double cell)
    : Arrangement(arrangement)
    , Cell(cell)
  {
    for (std::int64_t v = 0; v < arrangement.NumberOfVertices(); ++v)
      this->Cells[this->Key(arrangement.Position(v))].push_back(v);
  }
  /// The vertex within a tenth of a cell of @p p, or −1.
  std::int64_t Find(const Point3& p) const
  {
    const auto k = this->Key(p);
    for (std::int64_t dz = -1; dz <= 1; ++dz)
      for (std::int64_t dy = -1; dy <= 1; ++dy)
        for (std::int64_t dx = -1; dx <= 1; ++dx)
        {
          const auto it = this->Cells.find({ k[0] + dx, k[1] + dy, k[2] + dz });
          if (it == this->Cells.end())
            continue;
          for (std::int64_t v : it->second)
          {
            const Point3& q = this->Arrangement.Position(v);
            if (std::abs(q[0] - p[0]) + std::abs(q[1] - p[1]) + std::abs(q[2] - p[2]) <
              0.1 * this->Cell)
              return v;
          }
        }
    return -1;
  }

private:
  std::array<std::int64_t, 3> Key(const Point3& p) const
  {
    return { { static_cast<std::int64_t>(std::floor(p[0] / this->Cell)),
      static_cast<std::int64_t>(std::floor(p[1] / this->Cell)),
      static_cast<std::int64_t>(std::floor(p[2] / this->Cell)) } };
  }
  const PlaneArrangement& Arrangement;
  double Cell;
  std::map<std::array<std::int64_t, 3>, std::vector<std::int64_t>> Cells;
};
} // namespace

ContinuousSynthesisResult SynthesizeMirrored(const PolyhedralAnalysis& analysis,
  const PlaneArrangement& arrangement, const ContinuousSynthesisOptions& options)
{
  if (options.Snapshots > 0)
    throw Error("mirror: catalog snapshots are not available with reflection symmetry");
  if (options.MirrorAxes < 0 || options.MirrorAxes > 7)
    throw Error("mirror: the axes are bits 0 (x), 1 (y) and 2 (z)");
  int first = 0;
  while (!((options.MirrorAxes >> first) & 1))
    ++first;
  const ArrangementMirror plan = PlanArrangementMirror(analysis, arrangement.Parameters(), first);
  ArrangementParameters half = arrangement.Parameters();
  const auto axis = ToIndex(plan.Axis);
  half.BoxHigh[axis] = plan.Seam;
  const PlaneArrangement halfArrangement(arrangement.Families(), half);
  ContinuousSynthesisOptions o = options;
  o.MirrorAxes &= ~(1 << first); // the other axes mirror the half in turn
  o.PartOf.push_back(&plan);
  ContinuousSynthesisResult result = SynthesizeContinuous(analysis, halfArrangement, o);
  const std::vector<std::int32_t> halfLabels = std::move(result.Labels);
  const int empty = analysis.Find(NeighbourhoodLabel::Constant(0));
  result.Labels.assign(ToIndex(arrangement.NumberOfVertices()), empty);
  if (!result.Succeeded())
    return result;
  double smallest = 0;
  for (int f = 0; f < arrangement.Families().Size(); ++f)
  {
    const double s = half.Spacing(arrangement.Families(), f);
    smallest = f == 0 ? s : std::min(smallest, s);
  }
  const VertexFinder finder(halfArrangement, smallest / 4);
  const auto& p = arrangement.Parameters();
  const double seam = p.Origin[axis] + p.Quantum * static_cast<double>(plan.Seam);
  const double low = p.Origin[axis] + p.Quantum * static_cast<double>(p.BoxLow[axis]);
  const double tolerance = 0.1 * smallest / 4;
  for (std::int64_t v = 0; v < arrangement.NumberOfVertices(); ++v)
  {
    Point3 q = arrangement.Position(v);
    const bool reflected = q[axis] > seam + tolerance;
    if (reflected)
      q[axis] = 2 * seam - q[axis];
    if (q[axis] < low - tolerance)
      continue; // beyond twice the seam: empty
    const std::int64_t u = finder.Find(q);
    if (u < 0)
      throw Error("mirror: vertex " + std::to_string(v) + " has no mirror image in the half box");
    const int label = halfLabels[ToIndex(u)];
    result.Labels[ToIndex(v)] = reflected ? plan.LabelImage[ToIndex(label)] : label;
  }
  // A corner near the seam and its image may come closer than a tenth of a spacing: parts with
  // such corners are emptied on the whole arrangement, as the half's run did within the half.
  const ArrangementRules rules(analysis, arrangement);
  result.NarrowPartsRemoved +=
    detail::ConstraintPlan(analysis, arrangement, ContinuousConstraints(), options.Seed)
      .EmptyPartsAt(result.Labels, empty, rules.NarrowCorners(result.Labels));
  std::ostringstream at;
  at << seam;
  result.Message += ", mirrored across the plane at " + at.str();
  if (options.PartOf.empty()) // the whole model: its vertices, as an unmirrored run's message
    result.Message =
      std::to_string(arrangement.NumberOfVertices()) + " arrangement vertices, " + result.Message;
  return result;
}

} // namespace msynth
