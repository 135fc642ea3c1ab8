// SPDX-License-Identifier: BSD-3-Clause
#include "msynth/AdjacencyRules.h"

#include "msynth/Error.h"

#include <algorithm>
#include <cmath>

namespace msynth
{

void AdjacencyRules::Allocate(int k)
{
  if (k < 1)
  {
    throw Error("adjacency rules need at least one label");
  }
  this->K = k;
  this->W = (k + 63) / 64;
  this->Bits.assign(static_cast<std::size_t>(NumberOfDirections) * k * this->W, 0);
}

void AdjacencyRules::Allow(int axis, int b, int c)
{
  // c may follow b along +axis, so b may precede c along -axis.
  const int plus = 2 * axis, minus = 2 * axis + 1;
  this->Bits[(static_cast<std::size_t>(plus) * this->K + b) * this->W + (c >> 6)] |=
    std::uint64_t(1) << (c & 63);
  this->Bits[(static_cast<std::size_t>(minus) * this->K + c) * this->W + (b >> 6)] |=
    std::uint64_t(1) << (b & 63);
}

void AdjacencyRules::Finish()
{
  this->AnyBits.assign(static_cast<std::size_t>(NumberOfDirections) * this->W, 0);
  for (int d = 0; d < NumberOfDirections; ++d)
  {
    for (int b = 0; b < this->K; ++b)
    {
      for (int w = 0; w < this->W; ++w)
      {
        this->AnyBits[static_cast<std::size_t>(d) * this->W + w] |= this->Compatible(d, b)[w];
      }
    }
  }
  this->ChunkUnions.clear();
  if (this->K > 512)
  {
    return;
  }
  const int chunks = (this->K + 7) / 8;
  this->ChunkUnions.assign(
    static_cast<std::size_t>(NumberOfDirections) * chunks * 256 * this->W, 0);
  for (int d = 0; d < NumberOfDirections; ++d)
  {
    for (int j = 0; j < chunks; ++j)
    {
      std::uint64_t* table =
        this->ChunkUnions.data() + (static_cast<std::size_t>(d) * chunks + j) * 256 * this->W;
      // Entry v = entry (v without its lowest bit) | Compatible(label of that bit).
      for (int v = 1; v < 256; ++v)
      {
        const int low = __builtin_ctz(static_cast<unsigned>(v));
        const int b = 8 * j + low;
        const std::uint64_t* rest = table + static_cast<std::size_t>(v & (v - 1)) * this->W;
        std::uint64_t* entry = table + static_cast<std::size_t>(v) * this->W;
        for (int w = 0; w < this->W; ++w)
        {
          entry[w] = rest[w] | (b < this->K ? this->Compatible(d, b)[w] : 0);
        }
      }
    }
  }
}

void AdjacencyRules::UnionOf(int d, const std::uint64_t* domain, std::uint64_t* out) const
{
  std::fill(out, out + this->W, 0);
  if (!this->ChunkUnions.empty())
  {
    const int chunks = (this->K + 7) / 8;
    const std::uint64_t* tables =
      this->ChunkUnions.data() + static_cast<std::size_t>(d) * chunks * 256 * this->W;
    for (int j = 0; j < chunks; ++j)
    {
      const auto byte = static_cast<unsigned>((domain[j >> 3] >> (8 * (j & 7))) & 0xffu);
      if (byte)
      {
        const std::uint64_t* entry = tables + (static_cast<std::size_t>(j) * 256 + byte) * this->W;
        for (int w = 0; w < this->W; ++w)
        {
          out[w] |= entry[w];
        }
      }
    }
    return;
  }
  for (int w = 0; w < this->W; ++w)
  {
    for (std::uint64_t bits = domain[w]; bits; bits &= bits - 1)
    {
      const std::uint64_t* c = this->Compatible(d, w * 64 + __builtin_ctzll(bits));
      for (int i = 0; i < this->W; ++i)
      {
        out[i] |= c[i];
      }
    }
  }
}

AdjacencyRules AdjacencyRules::FromExample(const ExampleAnalysis& analysis)
{
  AdjacencyRules rules;
  rules.Allocate(analysis.NumberOfLabels());
  rules.Values = analysis.Labels();
  rules.LabelWeights.reserve(analysis.LabelCounts().size());
  for (auto n : analysis.LabelCounts())
  {
    rules.LabelWeights.push_back(static_cast<double>(n));
  }
  for (int axis = 0; axis < 3; ++axis)
  {
    for (const auto& t : analysis.Transitions(axis))
    {
      rules.Allow(axis, t.From, t.To);
    }
  }
  rules.Finish();
  return rules;
}

AdjacencyRules AdjacencyRules::FromPairs(std::vector<Label> values, std::vector<double> weights,
  const std::array<std::vector<std::pair<int, int>>, 3>& pairs)
{
  AdjacencyRules rules;
  const int k = static_cast<int>(values.size());
  rules.Allocate(k);
  if (weights.size() != values.size())
  {
    throw Error("adjacency rules: " + std::to_string(values.size()) + " labels but " +
      std::to_string(weights.size()) + " weights");
  }
  for (std::size_t i = 0; i < weights.size(); ++i)
  {
    if (!(weights[i] > 0.0) || !std::isfinite(weights[i]))
    {
      throw Error("adjacency rules: label " + std::to_string(values[i]) +
        " has a weight that is not positive and finite");
    }
  }
  for (int axis = 0; axis < 3; ++axis)
  {
    for (const auto& p : pairs[axis])
    {
      if (p.first < 0 || p.first >= k || p.second < 0 || p.second >= k)
      {
        throw Error("adjacency rules: pair (" + std::to_string(p.first) + ", " +
          std::to_string(p.second) + ") names a label index outside 0.." + std::to_string(k - 1));
      }
      rules.Allow(axis, p.first, p.second);
    }
  }
  rules.Values = std::move(values);
  rules.LabelWeights = std::move(weights);
  rules.Finish();
  return rules;
}

int AdjacencyRules::IndexOf(Label value) const
{
  const auto it = std::find(this->Values.begin(), this->Values.end(), value);
  return it == this->Values.end() ? -1 : static_cast<int>(it - this->Values.begin());
}

bool AdjacencyRules::SelfAdjacent(int b, const std::array<std::int64_t, 3>& outputSize) const
{
  for (int axis = 0; axis < 3; ++axis)
  {
    if (outputSize[axis] > 1 && !this->Allowed(2 * axis, b, b))
    {
      return false;
    }
  }
  return true;
}

} // namespace msynth
