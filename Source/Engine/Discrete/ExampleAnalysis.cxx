// SPDX-License-Identifier: BSD-3-Clause
#include "Discrete/ExampleAnalysis.h"

#include "Core/Error.h"
#include "Core/Index.h"

#include <algorithm>
#include <unordered_map>

namespace msynth
{

ExampleAnalysis ExampleAnalysis::FromExample(const LabelGrid& example)
{
  if (example.NumberOfSites() == 0)
  {
    throw Error("the example model is empty");
  }
  ExampleAnalysis result;

  // Distinct labels, ascending.
  std::vector<Label> values = example.Data();
  std::sort(values.begin(), values.end());
  values.erase(std::unique(values.begin(), values.end()), values.end());
  result.LabelValues = std::move(values);

  // Label index of every site, then frequencies.
  std::unordered_map<Label, int> indexOf;
  indexOf.reserve(result.LabelValues.size() * 2);
  for (std::size_t i = 0; i < result.LabelValues.size(); ++i)
  {
    indexOf.emplace(result.LabelValues[i], static_cast<int>(i));
  }
  std::vector<int> site(example.Data().size());
  result.Counts.assign(result.LabelValues.size(), 0);
  for (std::size_t i = 0; i < site.size(); ++i)
  {
    site[i] = indexOf.at(example.Data()[i]);
    ++result.Counts[ToIndex(site[i])];
  }

  // Eq. 3.2: count every (E(x'), E(x' + d)) pair with both sites inside E.
  const auto& d = example.Dimensions();
  const std::array<std::int64_t, 3> stride{ { 1, d[0], d[0] * d[1] } };
  for (int axis = 0; axis < 3; ++axis)
  {
    std::unordered_map<std::uint64_t, std::int64_t> counts;
    for (std::int64_t z = 0; z < d[2]; ++z)
    {
      for (std::int64_t y = 0; y < d[1]; ++y)
      {
        for (std::int64_t x = 0; x < d[0]; ++x)
        {
          const std::array<std::int64_t, 3> p{ { x, y, z } };
          if (p[axis] + 1 >= d[axis])
          {
            continue;
          }
          const std::int64_t i = example.Index(x, y, z);
          const auto from = static_cast<std::uint32_t>(site[ToIndex(i)]);
          const auto to = static_cast<std::uint32_t>(site[ToIndex(i + stride[axis])]);
          ++counts[(std::uint64_t(from) << 32) | to];
        }
      }
    }
    auto& pairs = result.Pairs[axis];
    pairs.reserve(counts.size());
    for (const auto& kv : counts)
    {
      pairs.push_back(
        { static_cast<int>(kv.first >> 32), static_cast<int>(kv.first & 0xffffffffu), kv.second });
    }
    std::sort(pairs.begin(), pairs.end(),
      [](const Transition& a, const Transition& b)
      { return a.From != b.From ? a.From < b.From : a.To < b.To; });
  }
  return result;
}

int ExampleAnalysis::IndexOf(Label value) const
{
  return IndexOfLabel(this->LabelValues, value);
}

std::int64_t ExampleAnalysis::PairCount(int axis, int from, int to) const
{
  const auto& pairs = this->Pairs[axis];
  const auto it = std::lower_bound(pairs.begin(), pairs.end(), Transition{ from, to, 0 },
    [](const Transition& a, const Transition& b)
    { return a.From != b.From ? a.From < b.From : a.To < b.To; });
  if (it == pairs.end() || it->From != from || it->To != to)
  {
    return 0;
  }
  return it->Count;
}

} // namespace msynth
