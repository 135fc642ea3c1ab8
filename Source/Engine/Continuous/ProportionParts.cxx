// SPDX-License-Identifier: BSD-3-Clause
// Proportions that hold (issue 29): after synthesis, whole solid parts are emptied while that
// brings the object types' shares nearer the targets. Emptying a connected solid part is always
// consistent (its vertices then see only empty space), so the model stays valid.
#include "Continuous/ConstraintPlan.h"
#include "Continuous/ContinuousMesh.h"
#include "Core/Index.h"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <limits>
#include <sstream>

namespace msynth
{
namespace detail
{

namespace
{
/// How far shares are from targets: the largest relative deviation over the solid types, then
/// their sum (compared in that order). Infinite for an empty model.
struct Deviation
{
  double Worst = std::numeric_limits<double>::infinity();
  double Sum = std::numeric_limits<double>::infinity();
  bool operator<(const Deviation& o) const
  {
    return this->Worst < o.Worst - 1e-12 || (this->Worst <= o.Worst + 1e-12 && this->Sum < o.Sum);
  }
};

Deviation DeviationOf(const std::vector<double>& total, const std::vector<double>& target)
{
  double solid = 0;
  for (std::size_t t = 1; t < total.size(); ++t)
    solid += total[t];
  Deviation d;
  if (!(solid > 1e-9))
    return d;
  d.Worst = d.Sum = 0;
  for (std::size_t t = 1; t < total.size(); ++t)
  {
    const double share = total[t] / solid;
    const double off = target[t] > 0 ? std::abs(share - target[t]) / target[t] : share;
    d.Worst = std::max(d.Worst, off);
    d.Sum += off;
  }
  return d;
}

/**
 * Each part's volume per type bit ([part][type]): the faces of the labels' mesh (oriented from
 * InsideType to OutsideType), each face's divergence-theorem term added to its inside type and
 * taken from its outside type, in the part of its first corner (a face bounds one part: its
 * corners are joined by edges that touch solid). Vertex occupancy, which the steering tallies,
 * counts regions of many planes (roof slopes) several times over.
 */
template <typename BitOf>
std::vector<double> PartVolumes(const PolyhedralAnalysis& analysis,
  const PlaneArrangement& arrangement, const std::vector<std::int32_t>& labels,
  const std::vector<std::int64_t>& component, std::int64_t parts, std::size_t nt, unsigned threads,
  BitOf bitOf)
{
  std::vector<double> volumes(ToIndex(parts) * nt, 0.0);
  if (parts == 0)
    return volumes;
  for (const MeshFace& face : FaceMeasures(analysis, arrangement, labels, threads))
  {
    const std::int64_t c = component[ToIndex(face.Corner)];
    if (c < 0)
      continue;
    const int inside = bitOf(face.Inside);
    const int outside = bitOf(face.Outside);
    if (inside > 0)
      volumes[ToIndex(c) * nt + ToIndex(inside)] += face.Measure;
    if (outside > 0)
      volumes[ToIndex(c) * nt + ToIndex(outside)] -= face.Measure;
  }
  return volumes;
}
} // namespace

ConstraintPlan::Proportioned ConstraintPlan::KeepProportionateParts(
  std::vector<std::int32_t>& labels, int emptyLabel, unsigned threads) const
{
  Proportioned out;
  if (!this->Proportions || !this->GuideWeights.empty())
    return out; // a guide asks for types in places (masks too): emptying parts would undo it
  std::vector<std::int64_t> component;
  const std::int64_t parts = SolidComponents(
    this->Arrangement, labels, [this](int d, int a) { return this->EdgeTypes(d, a); }, this->Solid,
    this->TypesOfLabel, component);
  const std::size_t nt = this->Types.size();
  // Each part's volume per type, and the model's.
  const std::vector<double> occupancy = PartVolumes(this->Analysis, this->Arrangement, labels,
    component, parts, nt, threads, [this](int type) { return this->BitOf(type); });
  std::vector<double> total(nt, 0.0);
  for (std::int64_t c = 0; c < parts; ++c)
    for (std::size_t t = 1; t < nt; ++t)
      total[t] += occupancy[ToIndex(c) * nt + t];
  double before = 0;
  for (std::size_t t = 1; t < nt; ++t)
    before += total[t];
  // Greedy: empty the part whose removal brings the shares nearest the targets, while that is
  // nearer than keeping it and some type is further off than ProportionMargin (ties: the part found
  // first, so the choice is deterministic).
  std::vector<char> removed(ToIndex(parts), 0);
  // A network of one type grown from seeds (a road among houses) is what the user asked to
  // keep: the parts holding it are not emptied for the shares.
  const std::uint64_t network = this->NetworkMask();
  for (std::int64_t c = 0; c < parts && network; ++c)
    for (std::size_t t = 1; t < nt; ++t)
      if (((network >> t) & 1u) && occupancy[ToIndex(c) * nt + t] > 0)
        removed[ToIndex(c)] = 2; // kept: never tried
  Deviation now = DeviationOf(total, this->Target);
  std::vector<double> trial(nt);
  while (now.Worst > ProportionMargin)
  {
    std::int64_t best = -1;
    Deviation bestDeviation = now;
    for (std::int64_t c = 0; c < parts; ++c)
    {
      if (removed[ToIndex(c)])
        continue;
      for (std::size_t t = 1; t < nt; ++t)
        trial[t] = total[t] - occupancy[ToIndex(c) * nt + t];
      const Deviation d = DeviationOf(trial, this->Target);
      if (d < bestDeviation)
      {
        bestDeviation = d;
        best = c;
      }
    }
    if (best < 0)
      break;
    removed[ToIndex(best)] = 1;
    for (std::size_t t = 1; t < nt; ++t)
      total[t] -= occupancy[ToIndex(best) * nt + t];
    now = bestDeviation;
    ++out.Removed;
  }
  if (out.Removed > 0)
  {
    for (std::int64_t v = 0; v < this->Arrangement.NumberOfVertices(); ++v)
    {
      const std::int64_t c = component[ToIndex(v)];
      if (c >= 0 && removed[ToIndex(c)] == 1)
        labels[ToIndex(v)] = emptyLabel;
    }
  }
  // What still falls outside the tolerance, and why emptying parts could not help.
  double solid = 0;
  for (std::size_t t = 1; t < nt; ++t)
    solid += total[t];
  if (before > 0)
    out.VolumeRemoved = std::max(0.0, 1 - solid / before);
  std::ostringstream why;
  why << std::setprecision(2) << std::fixed;
  for (std::size_t t = 1; t < nt && solid > 0; ++t)
  {
    const double share = total[t] / solid, target = this->Target[t];
    if (target > 0 && std::abs(share - target) <= ProportionTolerance * target)
      continue;
    out.Outside.push_back(this->Types[t]);
    why << (why.tellp() > 0 ? "; " : "") << "type " << this->Types[t] << ": " << share
        << " of the solid (example " << target << "), "
        << (share > target
               ? "too much, and emptying any part holding it takes as much of the other types"
               : "too little: the draw favours it, but its labels are mostly forced by the "
                 "adjacency constraint, and emptying parts cannot add it");
  }
  out.Reason = why.str();
  out.Worst = now.Worst;
  out.Sum = now.Sum;
  out.Kept = solid;
  out.Shares.assign(nt, 0.0);
  for (std::size_t t = 1; t < nt && solid > 0; ++t)
    out.Shares[t] = total[t] / solid;
  return out;
}

} // namespace detail
} // namespace msynth
