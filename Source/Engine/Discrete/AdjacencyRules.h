// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/**
 * @file AdjacencyRules.h
 * @brief The adjacency constraint (dissertation Eq. 3.3) in the form the solver uses: for each
 * of the six axis directions d and each label index b, the set of labels c allowed at x + d when
 * x holds b, as a bit set of k bits. Built from an example's transition tables (Eq. 3.2) or from
 * an explicit list of allowed pairs (tilesets).
 */
#include "Core/Propagation.h"
#include "Discrete/ExampleAnalysis.h"

#include <array>
#include <cstdint>
#include <utility>
#include <vector>

namespace msynth
{

/// The six directions: +x, -x, +y, -y, +z, -z. Opposite(d) = d ^ 1.
enum Direction : int
{
  PlusX = 0,
  MinusX = 1,
  PlusY = 2,
  MinusY = 3,
  PlusZ = 4,
  MinusZ = 5
};
constexpr int NumberOfDirections = 6;
inline int Opposite(int d)
{
  return d ^ 1;
}
inline int AxisOf(int d)
{
  return d >> 1;
}
/// Unit offset of direction @p d along each axis.
inline std::array<int, 3> Offset(int d)
{
  std::array<int, 3> o{ { 0, 0, 0 } };
  o[AxisOf(d)] = (d & 1) ? -1 : 1;
  return o;
}

class AdjacencyRules : public CompatibilityRelation
{
public:
  /// Rules of Eq. 3.3 from an analyzed example; weights are the label frequencies.
  static AdjacencyRules FromExample(const ExampleAnalysis& analysis);

  /**
   * Rules from explicit allowed pairs: @p pairs[axis] lists (b, c) label indices meaning c may
   * follow b along +axis. @p values are the label values of the k labels (ascending, each
   * once), @p weights their relative frequencies (all > 0 and finite).
   * @throw Error on an index out of range, values out of order or a bad weight.
   */
  static AdjacencyRules FromPairs(std::vector<Label> values, std::vector<double> weights,
    const std::array<std::vector<std::pair<int, int>>, 3>& pairs);

  const std::vector<Label>& LabelValues() const { return this->Values; }
  const std::vector<double>& Weights() const { return this->LabelWeights; }
  /// Index of label value @p value, or -1.
  int IndexOf(Label value) const;

  /// True when label @p b may be next to itself along every axis whose output size is > 1.
  bool SelfAdjacent(int b, const std::array<std::int64_t, 3>& outputSize) const;

private:
  void Allocate(int k) { CompatibilityRelation::Allocate(k, NumberOfDirections); }
  void Allow(int axis, int b, int c);

  std::vector<Label> Values;
  std::vector<double> LabelWeights;
};

} // namespace msynth
