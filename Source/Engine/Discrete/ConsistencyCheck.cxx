// SPDX-License-Identifier: BSD-3-Clause
#include "Discrete/ConsistencyCheck.h"
#include "Core/Index.h"

#include <set>
#include <tuple>

namespace msynth
{

std::string ConsistencyViolation::Describe() const
{
  static const char* const axes[4] = { "+x", "+y", "+z", "+t (the next frame)" };
  return "site (" + std::to_string(this->Site[0]) + ", " + std::to_string(this->Site[1]) + ", " +
    std::to_string(this->Site[2]) + ")" +
    (this->Time >= 0 ? " of frame " + std::to_string(this->Time) : std::string()) + ": label " +
    std::to_string(this->From) + " followed by " + std::to_string(this->To) + " along " +
    axes[this->Axis] + " is not allowed (never occurs in the example)";
}

namespace
{
ConsistencyReport CheckPairs(const std::set<std::tuple<int, Label, Label>>& allowed,
  const LabelGrid& model, std::size_t maxReported);
} // namespace

ConsistencyReport CheckConsistency(const std::array<std::vector<std::pair<int, int>>, 3>& pairs,
  const LabelGrid& model, std::size_t maxReported)
{
  return CheckConsistency(std::vector<LabelGrid>(), pairs, model, maxReported);
}

ConsistencyReport CheckConsistency(
  const LabelGrid& example, const LabelGrid& model, std::size_t maxReported)
{
  return CheckConsistency(std::vector<LabelGrid>{ example }, {}, model, maxReported);
}

ConsistencyReport CheckConsistency(const std::vector<LabelGrid>& examples,
  const std::array<std::vector<std::pair<int, int>>, 3>& pairs, const LabelGrid& model,
  std::size_t maxReported)
{
  std::set<std::tuple<int, Label, Label>> allowed;
  for (int axis = 0; axis < 3; ++axis)
    for (const auto& p : pairs[ToIndex(axis)])
      allowed.emplace(axis, p.first, p.second);
  // Eq. 3.1 directly: the set of (axis, E(x'), E(x' + d)) over each example.
  for (const LabelGrid& example : examples)
  {
    const auto& e = example.Dimensions();
    for (std::int64_t z = 0; z < e[2]; ++z)
      for (std::int64_t y = 0; y < e[1]; ++y)
        for (std::int64_t x = 0; x < e[0]; ++x)
        {
          if (x + 1 < e[0])
            allowed.emplace(0, example.At(x, y, z), example.At(x + 1, y, z));
          if (y + 1 < e[1])
            allowed.emplace(1, example.At(x, y, z), example.At(x, y + 1, z));
          if (z + 1 < e[2])
            allowed.emplace(2, example.At(x, y, z), example.At(x, y, z + 1));
        }
  }
  return CheckPairs(allowed, model, maxReported);
}

namespace
{
ConsistencyReport CheckPairs(const std::set<std::tuple<int, Label, Label>>& allowed,
  const LabelGrid& model, std::size_t maxReported)
{
  ConsistencyReport report;
  const auto& m = model.Dimensions();
  for (std::int64_t z = 0; z < m[2]; ++z)
    for (std::int64_t y = 0; y < m[1]; ++y)
      for (std::int64_t x = 0; x < m[0]; ++x)
      {
        const std::int64_t q[3][3] = { { x + 1, y, z }, { x, y + 1, z }, { x, y, z + 1 } };
        for (int axis = 0; axis < 3; ++axis)
        {
          if (!model.Contains(q[axis][0], q[axis][1], q[axis][2]))
            continue;
          ++report.PairsChecked;
          const Label b = model.At(x, y, z), c = model.At(q[axis][0], q[axis][1], q[axis][2]);
          if (!allowed.count({ axis, b, c }))
          {
            report.Consistent = false;
            ++report.Violations;
            if (report.First.size() < maxReported)
            {
              ConsistencyViolation v;
              v.Site = { { x, y, z } };
              v.Axis = axis;
              v.From = b;
              v.To = c;
              report.First.push_back(v);
            }
          }
        }
      }
  return report;
}
} // namespace

} // namespace msynth
