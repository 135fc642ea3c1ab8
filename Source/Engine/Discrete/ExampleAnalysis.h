// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/**
 * @file ExampleAnalysis.h
 * @brief What the discrete solver needs to know about an example model E (dissertation §3.1).
 *
 * - the distinct labels K of E (sorted by value; a label's position in that list is its
 *   *index* 0 ≤ b < k, the form the transition matrices and catalogs use);
 * - how often each label occurs (label frequencies, used for frequency-weighted choices);
 * - the transition matrices Tx, Ty, Tz of Eq. 3.2: T_d[b, c] = 1 iff some site x' of E has
 *   E(x') = b and E(x' + d) = c. They are stored sparsely, as the sorted list of allowed pairs
 *   with the number of times each pair occurs, so memory is O(pairs), never O(k²).
 */
#include "Core/LabelGrid.h"

#include <array>
#include <cstdint>
#include <vector>

namespace msynth
{

class ExampleAnalysis
{
public:
  /// One allowed pair of Eq. 3.2 along an axis: label index From, then To at +axis.
  struct Transition
  {
    int From = 0;
    int To = 0;
    std::int64_t Count = 0; ///< how many times the pair occurs in the example
    bool operator==(const Transition& o) const
    {
      return this->From == o.From && this->To == o.To && this->Count == o.Count;
    }
  };

  /// Analyzes @p example. @throw Error when the example is empty.
  static ExampleAnalysis FromExample(const LabelGrid& example);

  /// k, the number of distinct labels.
  int NumberOfLabels() const { return static_cast<int>(this->LabelValues.size()); }
  /// The distinct label values, ascending; index b of this list is label index b.
  const std::vector<Label>& Labels() const { return this->LabelValues; }
  /// The index of label value @p value, or -1 when the example does not contain it.
  int IndexOf(Label value) const;
  /// Occurrences of each label index in the example.
  const std::vector<std::int64_t>& LabelCounts() const { return this->Counts; }
  /// Allowed pairs along @p axis, sorted by (From, To).
  const std::vector<Transition>& Transitions(int axis) const { return this->Pairs[axis]; }
  /// T_axis[from, to] of Eq. 3.2 (label indices).
  bool Allowed(int axis, int from, int to) const { return this->PairCount(axis, from, to) > 0; }
  /// How often label index @p to follows @p from along +axis in the example (0 if never).
  std::int64_t PairCount(int axis, int from, int to) const;

private:
  std::vector<Label> LabelValues;
  std::vector<std::int64_t> Counts;
  std::array<std::vector<Transition>, 3> Pairs;
};

} // namespace msynth
