// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/**
 * @file RunEnds.h
 * @brief Parts as long as the example's: where a label would end an object type's run along x
 * or y, it is drawn with the chance that the example's runs of that length end.
 *
 * Labels are drawn one vertex at a time from what the neighbours allow, so whether a wall goes
 * on or ends is decided afresh at every vertex along it, with the same odds whatever its length
 * so far: lengths come out geometric, most of them a spacing or two, and a town's houses a
 * sixth of its example's. The example's runs (ExampleRuns: the lengths of each type's runs of
 * voxels along x and along y, complete ones and those cut by the example's box) give instead
 * the chance that a run which has reached length L ends there (its hazard). At a vertex whose
 * neighbour behind it along an axis is decided and carries a type, the candidate labels that
 * end the type ahead and those that carry it on are rescaled to that chance, the length behind
 * measured over the decided vertices of the block. Only upright types are followed (every face
 * vertical or horizontal: walls, slabs, roads): the rows of a gabled roof narrow toward its
 * ridge, so its short runs near the top would look like ends; it follows its walls. Beyond the
 * papers (their runs are memoryless; their dimensional constraints fix lengths the user gives).
 */
#include "Continuous/ConstraintPlan.h"
#include "Continuous/PlaneArrangement.h"
#include "Formats/PolyhedralExample.h"

#include <array>
#include <map>
#include <vector>

namespace msynth
{

/// The runs of one type along one axis, in world lengths (ascending).
struct TypeRuns
{
  std::vector<double> Complete; ///< both ends inside the example's box
  std::vector<double> Cut;      ///< touching the box (the run goes on beyond the example)
  /// The chance that a run which has reached @p length ends there (lengths within half of
  /// @p step of it), or -1 without runs that long to tell.
  double EndChance(double length, double step) const;
  /// The share of the example's runs that fit in @p room (complete runs no longer, against
  /// them and the cut runs longer), or -1 without runs to tell.
  double FitChance(double room, double step) const;
  /// The longest run, complete or cut (0 without runs).
  double Longest() const;
};

/// Per object type, its runs along x and along y.
using ExampleRuns = std::map<int, std::array<TypeRuns, 2>>;

/**
 * The block edge (in plane spacings of @p reference length) that leaves room for the
 * example's parts: twice its longest complete run of a followed type (blocks overlap by half,
 * so a part that long fits whole in the next block that meets it), at least 4 spacings; 4
 * without runs.
 */
double AutomaticBlockSize(const ExampleRuns& runs, double reference);

/// The runs of @p example's upright solid types (no sloped face) along x and y, on voxels of
/// about @p voxel (the classification of MeasureStructure). @throw Error as MeasureStructure.
ExampleRuns MeasureRuns(const PolyhedralExample& example, double voxel);

namespace detail
{

class RunEnds
{
public:
  RunEnds(const ExampleRuns& runs, const PlaneArrangement& arrangement, const ConstraintPlan& plan);
  /**
   * Rescales @p weight (of the candidate labels @p candidates at vertex @p v) so that, along
   * each axis direction whose vertex behind @p v carries a type with runs, the labels ending it
   * ahead take the example's chance of ending at the run's length. @p labelOf(u, distance) is the
   * label of decided vertex u, -1 when undecided, or -2 when it may not be read (outside the
   * block and @p distance from v along the axis or more; 0 for v's neighbours, which may always
   * be). Labels that begin a type's run are weighed first by the chance that it fits
   * (WeighFits).
   */
  template <typename LabelOf>
  void Weigh(std::int64_t v, const std::vector<int>& candidates, std::vector<double>& weight,
    LabelOf&& labelOf) const
  {
    for (const Axis& axis : this->Axes)
      if (axis.Forward)
        this->WeighFits(v, axis, candidates, weight, labelOf);
    for (const Axis& axis : this->Axes)
    {
      const std::int64_t first = this->Behind(v, axis.Direction);
      const int behind = first >= 0 ? labelOf(first, 0.0) : -1;
      if (behind < 0)
        continue;
      const std::uint64_t carried = this->Plan.EdgeTypes(axis.Direction, behind) & this->Tracked;
      for (int t = 0; t < this->Plan.NumberOfTypes(); ++t)
      {
        if (!((carried >> t) & 1u))
          continue;
        // The length behind v: over decided vertices whose edge toward v carries the type.
        const double step = this->Distance(first, v);
        double length = step;
        for (std::int64_t u = first, w = this->Behind(u, axis.Direction); w >= 0;
             u = w, w = this->Behind(u, axis.Direction))
        {
          const double further = length + this->Distance(w, u);
          const int label = labelOf(w, further);
          if (label < 0 || !((this->Plan.EdgeTypes(axis.Direction, label) >> t) & 1u))
            break;
          length = further;
        }
        const TypeRuns& runs = this->Runs[ToIndex(t)][ToIndex(axis.Index)];
        this->Rescale(runs.EndChance(length, step), t, axis.Direction, candidates, weight);
      }
    }
  }

private:
  struct Axis
  {
    int Direction = 0;    ///< the direction class of +x, -x, +y or -y
    int Index = 0;        ///< 0: x, 1: y
    bool Forward = false; ///< +x or +y
  };

  /// Labels that carry a followed type along @p axis (a +x or +y direction class) where no
  /// decided vertex of its run lies on either side yet (a run begun at v, or around it) take
  /// the chance that the example's runs fit in the room it has: up to the first decided vertex
  /// each way that stops the type. No house is begun in a gap it cannot fill.
  template <typename LabelOf>
  void WeighFits(std::int64_t v, const Axis& axis, const std::vector<int>& candidates,
    std::vector<double>& weight, LabelOf& labelOf) const
  {
    const int d = axis.Direction;
    std::uint64_t carried = 0;
    for (int c : candidates)
      carried |= this->Plan.EdgeTypes(d, c) | this->Plan.EdgeTypes(d ^ 1, c);
    carried &= this->Tracked;
    for (int t = 0; carried; ++t, carried >>= 1)
    {
      if (!(carried & 1u))
        continue;
      const TypeRuns& runs = this->Runs[ToIndex(t)][ToIndex(axis.Index)];
      double step = 0, back = 0;
      const double ahead = this->Room(v, d, t, runs.Longest(), step, labelOf);
      const double behind = this->Room(v, d ^ 1, t, runs.Longest(), back, labelOf);
      for (std::size_t k = 0; k < candidates.size(); ++k)
      {
        const bool forth = (this->Plan.EdgeTypes(d, candidates[k]) >> t) & 1u;
        const bool backward = (this->Plan.EdgeTypes(d ^ 1, candidates[k]) >> t) & 1u;
        if ((!forth && !backward) || (forth && ahead < 0) || (backward && behind < 0))
          continue;
        const double fit =
          runs.FitChance((forth ? ahead : 0.0) + (backward ? behind : 0.0), std::max(step, back));
        if (fit >= 0)
          weight[k] *= std::max(0.02, fit);
      }
    }
  }

  /// The length a run of type bit @p t through @p v may take from it along direction class
  /// @p d: up to the vertex before the first decided one that does not carry it on, or the
  /// model's side; -1 when it reaches a decided vertex that carries it (the run is not new),
  /// may go on past @p limit, or into vertices that may not be read. @p step: the distance to
  /// the first vertex ahead.
  template <typename LabelOf>
  double Room(std::int64_t v, int d, int t, double limit, double& step, LabelOf& labelOf) const
  {
    double room = 0;
    for (std::int64_t u = v, w = this->Behind(v, d ^ 1); w >= 0; u = w, w = this->Behind(w, d ^ 1))
    {
      const double gap = this->Distance(u, w);
      if (u == v)
        step = gap;
      const int label = labelOf(w, u == v ? 0.0 : room + gap);
      if (label == -2)
        return -1;
      if (label >= 0)
        return (this->Plan.EdgeTypes(d ^ 1, label) >> t) & 1u ? -1.0 : room;
      room += gap;
      if (room > limit)
        return -1;
    }
    return room;
  }
  /// The vertex behind @p v looking along direction class @p d (the neighbour along d ^ 1).
  std::int64_t Behind(std::int64_t v, int d) const;
  double Distance(std::int64_t a, std::int64_t b) const;
  void Rescale(double chance, int t, int d, const std::vector<int>& candidates,
    std::vector<double>& weight) const;

  const PlaneArrangement& Arrangement;
  const ConstraintPlan& Plan;
  std::vector<Axis> Axes;
  std::vector<std::array<TypeRuns, 2>> Runs; ///< per type bit
  std::uint64_t Tracked = 0;                 ///< type bits with runs
};

} // namespace detail
} // namespace msynth
