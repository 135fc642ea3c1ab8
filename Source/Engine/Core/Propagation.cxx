// SPDX-License-Identifier: BSD-3-Clause
#include "Core/Propagation.h"

#include "Core/Error.h"
#include "Core/Index.h"

#include <algorithm>

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

void CompatibilityRelation::Allocate(int k, int directions)
{
  if (k < 1)
  {
    throw Error("adjacency rules need at least one label");
  }
  this->K = k;
  this->W = (k + 63) / 64;
  this->D = directions;
  this->Bits.assign(ToIndex(directions) * k * this->W, 0);
}

void CompatibilityRelation::Finish()
{
  this->AnyBits.assign(ToIndex(this->D) * this->W, 0);
  for (int d = 0; d < this->D; ++d)
  {
    for (int b = 0; b < this->K; ++b)
    {
      for (int w = 0; w < this->W; ++w)
      {
        this->AnyBits[ToIndex(d) * this->W + w] |= this->Compatible(d, b)[w];
      }
    }
  }
  this->ChunkUnions.clear();
  if (this->K > 512)
  {
    return;
  }
  const int chunks = (this->K + 7) / 8;
  this->ChunkUnions.assign(ToIndex(this->D) * chunks * 256 * this->W, 0);
  for (int d = 0; d < this->D; ++d)
  {
    for (int j = 0; j < chunks; ++j)
    {
      std::uint64_t* table = this->ChunkUnions.data() + (ToIndex(d) * chunks + j) * 256 * this->W;
      // Entry v = entry (v without its lowest bit) | Compatible(label of that bit).
      for (int v = 1; v < 256; ++v)
      {
        const int low = __builtin_ctz(static_cast<unsigned>(v));
        const int b = 8 * j + low;
        const std::uint64_t* rest = table + ToIndex(v & (v - 1)) * this->W;
        std::uint64_t* entry = table + ToIndex(v) * this->W;
        for (int w = 0; w < this->W; ++w)
        {
          entry[w] = rest[w] | (b < this->K ? this->Compatible(d, b)[w] : 0);
        }
      }
    }
  }
}

void CompatibilityRelation::UnionOf(int d, const std::uint64_t* domain, std::uint64_t* out) const
{
  std::fill(out, out + this->W, 0);
  if (!this->ChunkUnions.empty())
  {
    const int chunks = (this->K + 7) / 8;
    const std::uint64_t* tables = this->ChunkUnions.data() + ToIndex(d) * chunks * 256 * this->W;
    for (int j = 0; j < chunks; ++j)
    {
      const auto byte = static_cast<unsigned>((domain[j >> 3] >> (8 * (j & 7))) & 0xffu);
      if (byte)
      {
        const std::uint64_t* entry = tables + (ToIndex(j) * 256 + byte) * this->W;
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

void LabelDomains::Reset(std::int64_t n, int k)
{
  // Every label possible: all bits below k set, written in place (blocks reset often).
  this->K = k;
  this->W = (k + 63) / 64;
  this->Bits.resize(ToIndex(n) * this->W);
  for (std::size_t s = 0; s < ToIndex(n); ++s)
  {
    for (int w = 0; w < this->W; ++w)
    {
      const bool last = w == this->W - 1 && k % 64;
      this->Bits[s * this->W + w] = last ? (std::uint64_t(1) << (k % 64)) - 1 : ~std::uint64_t(0);
    }
  }
  this->Start(n);
}

void LabelDomains::Reset(std::int64_t n, int k, std::vector<std::uint64_t> initial)
{
  this->K = k;
  this->W = (k + 63) / 64;
  if (initial.size() != ToIndex(n) * this->W)
  {
    throw Error("label domains: initial sets have the wrong size");
  }
  this->Bits = std::move(initial);
  this->Start(n);
}

void LabelDomains::Start(std::int64_t n)
{
  this->Counts.resize(ToIndex(n));
  this->DecidedSites = 0;
  this->EmptySite = -1;
  for (std::size_t s = 0; s < this->Counts.size(); ++s)
  {
    this->Counts[s] = PopCount(this->Bits.data() + s * this->W, this->W);
    this->DecidedSites += this->Counts[s] == 1;
    if (this->Counts[s] == 0 && this->EmptySite < 0)
    {
      this->EmptySite = static_cast<std::int64_t>(s);
    }
  }
  this->Queued.assign(ToIndex(n), 0);
  this->Queue.clear();
  this->FromScratch = true;
  this->ChangedSites.clear();
  this->Trail.clear();
  this->TrailBase = 0;
  this->Scratch.assign(ToIndex(this->W), 0);
}

int LabelDomains::Single(std::int64_t site) const
{
  const std::uint64_t* d = this->Domain(site);
  for (int w = 0; w < this->W; ++w)
  {
    if (d[w])
    {
      return w * 64 + __builtin_ctzll(d[w]);
    }
  }
  return -1;
}

bool LabelDomains::Keep(std::int64_t site, const std::uint64_t* mask)
{
  return this->Restrict(site, mask);
}

bool LabelDomains::Restrict(std::int64_t site, const std::uint64_t* mask)
{
  std::uint64_t* d = this->Bits.data() + ToIndex(site) * this->W;
  bool changed = false;
  for (int w = 0; w < this->W && !changed; ++w)
  {
    changed = (d[w] & mask[w]) != d[w];
  }
  if (changed)
  {
    if (this->Recording)
    {
      this->Trail.push_back(static_cast<std::uint64_t>(site));
      this->Trail.push_back(static_cast<std::uint64_t>(this->Counts[ToIndex(site)]));
      this->Trail.insert(this->Trail.end(), d, d + this->W);
    }
    for (int w = 0; w < this->W; ++w)
    {
      d[w] &= mask[w];
    }
    const int count = PopCount(d, this->W);
    const int before = this->Counts[ToIndex(site)];
    this->DecidedSites += (count == 1) - (before == 1);
    this->Counts[ToIndex(site)] = count;
    this->ChangedSites.push_back(site);
    this->Push(site);
    if (count == 0 && this->EmptySite < 0)
    {
      this->EmptySite = site;
    }
  }
  return this->Counts[ToIndex(site)] > 0;
}

void LabelDomains::Forget(std::size_t mark)
{
  if (mark <= this->TrailBase)
  {
    return;
  }
  const std::size_t drop = mark - this->TrailBase;
  if (drop < (std::size_t(1) << 16) || 2 * drop < this->Trail.size())
  {
    return; // not worth moving the rest yet
  }
  this->Trail.erase(this->Trail.begin(), this->Trail.begin() + static_cast<std::ptrdiff_t>(drop));
  this->TrailBase = mark;
}

void LabelDomains::Undo(std::size_t mark)
{
  if (mark < this->TrailBase)
  {
    throw Error("label domains: undo past the forgotten part of the trail");
  }
  mark -= this->TrailBase;
  const std::size_t entry = ToIndex(this->W) + 2;
  while (this->Trail.size() > mark)
  {
    const std::size_t at = this->Trail.size() - entry;
    const auto site = static_cast<std::int64_t>(this->Trail[at]);
    const int count = static_cast<int>(this->Trail[at + 1]);
    std::copy_n(this->Trail.data() + at + 2, this->W, this->Bits.data() + ToIndex(site) * this->W);
    const int now = this->Counts[ToIndex(site)];
    this->DecidedSites += (count == 1) - (now == 1);
    this->Counts[ToIndex(site)] = count;
    this->ChangedSites.push_back(site);
    this->Trail.resize(at);
  }
  for (std::int64_t q : this->Queue)
  {
    this->Queued[ToIndex(q)] = 0;
  }
  this->Queue.clear();
  this->EmptySite = -1;
}

bool LabelDomains::Assign(std::int64_t site, int b)
{
  if (!this->Contains(site, b))
  {
    return false;
  }
  std::fill(this->Scratch.begin(), this->Scratch.end(), 0);
  this->Scratch[ToIndex(b >> 6)] = std::uint64_t(1) << (b & 63);
  return this->Restrict(site, this->Scratch.data());
}

} // namespace msynth
