// SPDX-License-Identifier: BSD-3-Clause
#include "msynth/Catalog.h"

#include "msynth/Error.h"

namespace msynth
{
namespace
{
int PopCount(const std::uint64_t* bits, int words)
{
  int n = 0;
  for (int i = 0; i < words; ++i)
  {
    n += __builtin_popcountll(bits[i]);
  }
  return n;
}
} // namespace

Catalog::Catalog(const AdjacencyRules& rules)
  : Rules(rules)
  , W(rules.Words())
  , Scratch(static_cast<std::size_t>(rules.Words()))
{
}

void Catalog::Reset(
  const std::array<std::int64_t, 3>& origin, const std::array<std::int64_t, 3>& dims)
{
  this->RegionOrigin = origin;
  this->RegionDims = dims;
  const auto n = static_cast<std::size_t>(dims[0] * dims[1] * dims[2]);
  const int k = this->Rules.NumberOfLabels();
  // Every label possible: all bits below k set.
  std::vector<std::uint64_t> full(static_cast<std::size_t>(this->W), ~std::uint64_t(0));
  if (k % 64)
  {
    full.back() = (std::uint64_t(1) << (k % 64)) - 1;
  }
  this->Bits.resize(n * this->W);
  for (std::size_t s = 0; s < n; ++s)
  {
    std::copy(full.begin(), full.end(), this->Bits.begin() + s * this->W);
  }
  this->Counts.assign(n, k);
  this->DecidedSites = k == 1 ? static_cast<std::int64_t>(n) : 0;
  this->Queued.assign(n, 0);
  this->Stack.clear();
  this->ChangedSites.clear();
  this->EmptySite = -1;
}

std::array<std::int64_t, 3> Catalog::Coordinates(std::int64_t local) const
{
  const std::int64_t nx = this->RegionDims[0], ny = this->RegionDims[1];
  return { { local % nx, (local / nx) % ny, local / (nx * ny) } };
}

int Catalog::Single(std::int64_t local) const
{
  const std::uint64_t* d = this->Domain(local);
  for (int w = 0; w < this->W; ++w)
  {
    if (d[w])
    {
      return w * 64 + __builtin_ctzll(d[w]);
    }
  }
  return -1;
}

void Catalog::Push(std::int64_t local)
{
  if (!this->Queued[static_cast<std::size_t>(local)])
  {
    this->Queued[static_cast<std::size_t>(local)] = 1;
    this->Stack.push_back(local);
  }
}

bool Catalog::Restrict(std::int64_t local, const std::uint64_t* mask)
{
  std::uint64_t* d = this->Bits.data() + static_cast<std::size_t>(local) * this->W;
  bool changed = false;
  for (int w = 0; w < this->W; ++w)
  {
    const std::uint64_t kept = d[w] & mask[w];
    changed |= kept != d[w];
    d[w] = kept;
  }
  if (changed)
  {
    const int count = PopCount(d, this->W);
    const int before = this->Counts[static_cast<std::size_t>(local)];
    this->DecidedSites += (count == 1) - (before == 1);
    this->Counts[static_cast<std::size_t>(local)] = count;
    this->ChangedSites.push_back(local);
    this->Push(local);
    if (count == 0 && this->EmptySite < 0)
    {
      this->EmptySite = local;
    }
  }
  return this->Counts[static_cast<std::size_t>(local)] > 0;
}

bool Catalog::Assign(std::int64_t local, int b)
{
  if (!this->Contains(local, b))
  {
    return false;
  }
  std::fill(this->Scratch.begin(), this->Scratch.end(), 0);
  this->Scratch[static_cast<std::size_t>(b >> 6)] = std::uint64_t(1) << (b & 63);
  return this->Restrict(local, this->Scratch.data());
}

bool Catalog::Constrain(std::int64_t local, int d, int b)
{
  return this->Restrict(local, this->Rules.Compatible(d, b));
}

std::int64_t Catalog::Propagate()
{
  const auto& dims = this->RegionDims;
  const std::int64_t stride[3] = { 1, dims[0], dims[0] * dims[1] };
  std::vector<std::uint64_t>& allowed = this->Scratch;
  // First in, first out: a site waits while its neighbours shrink, so it is revised once for
  // several changes instead of once per change.
  std::size_t head = 0;
  while (head < this->Stack.size() && this->EmptySite < 0)
  {
    const std::int64_t v = this->Stack[head++];
    if (head > 4096 && head * 2 > this->Stack.size())
    {
      this->Stack.erase(
        this->Stack.begin(), this->Stack.begin() + static_cast<std::ptrdiff_t>(head));
      head = 0;
    }
    this->Queued[static_cast<std::size_t>(v)] = 0;
    const std::array<std::int64_t, 3> p = this->Coordinates(v);
    const std::uint64_t* dv = this->Domain(v);
    for (int d = 0; d < NumberOfDirections; ++d)
    {
      const int axis = AxisOf(d);
      const bool minus = d & 1;
      if ((minus && p[axis] == 0) || (!minus && p[axis] + 1 >= dims[axis]))
      {
        continue; // the neighbour is outside the region: fixed, nothing to revise
      }
      const std::int64_t u = v + (minus ? -stride[axis] : stride[axis]);
      const int countV = this->Counts[static_cast<std::size_t>(v)];
      if (this->Counts[static_cast<std::size_t>(u)] == 0)
      {
        continue;
      }
      const std::uint64_t* mask;
      if (countV == this->Rules.NumberOfLabels())
      {
        mask = this->Rules.CompatibleWithAny(d); // v is unconstrained: precomputed union
      }
      else
      {
        // The labels some label of v allows at u = v + d.
        this->Rules.UnionOf(d, dv, allowed.data());
        mask = allowed.data();
      }
      if (!this->Restrict(u, mask))
      {
        break;
      }
    }
  }
  if (this->EmptySite >= 0)
  {
    // Leave the catalog in a state where the caller can inspect the empty site; drop the queue.
    for (std::size_t i = head; i < this->Stack.size(); ++i)
    {
      this->Queued[static_cast<std::size_t>(this->Stack[i])] = 0;
    }
  }
  this->Stack.clear();
  return this->EmptySite;
}

} // namespace msynth
