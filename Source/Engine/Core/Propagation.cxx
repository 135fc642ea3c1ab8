// SPDX-License-Identifier: BSD-3-Clause
#include "Core/Propagation.h"

#include "Core/Error.h"
#include "Core/Index.h"
#include "Core/Memory.h"

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
    // SWAR: the build does not assume a popcount instruction (__builtin_popcountll is a call).
    std::uint64_t x = bits[i];
    x = x - ((x >> 1) & 0x5555555555555555ull);
    x = (x & 0x3333333333333333ull) + ((x >> 2) & 0x3333333333333333ull);
    x = (x + (x >> 4)) & 0x0f0f0f0f0f0f0f0full;
    n += static_cast<int>((x * 0x0101010101010101ull) >> 56);
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
  this->BuildLists();
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

void CompatibilityRelation::BuildLists()
{
  this->ListStart.clear();
  this->ReverseStart.clear();
  this->ListLabels.clear();
  this->MeanList = 0;
  this->ListsForUnions = false;
  if (this->K <= 512 || this->K >= 65536)
  {
    // Up to 512 labels the chunk unions cost at most k/8 lookups a revision, less than keeping
    // Applied (measured with support counts: City, k = 93, 40 x 40 x 10 took 44 % longer);
    // 65536 labels and more: no 16-bit labels.
    return;
  }
  if (this->Bits.size() >= (std::size_t(1) << 26))
  {
    return; // over 2^32 pairs possible: the offsets would not fit
  }
  const auto pairs =
    static_cast<std::uint64_t>(PopCount(this->Bits.data(), static_cast<int>(this->Bits.size())));
  if (4 * pairs > std::uint64_t(this->D) * std::uint64_t(this->K) * std::uint64_t(this->K))
  {
    return; // dense: the unions are cheap compared with the lists
  }
  const std::size_t rows = ToIndex(this->D) * ToIndex(this->K);
  this->ListStart.reserve(rows + 1);
  this->ListLabels.resize(2 * pairs);
  // The supports' offsets: how many lists hold each label, then the running sums.
  this->ReverseStart.assign(rows + 1, 0);
  this->ListStart.push_back(0);
  std::size_t at = 0;
  for (int d = 0; d < this->D; ++d)
  {
    for (int b = 0; b < this->K; ++b)
    {
      const std::uint64_t* c = this->Compatible(d, b);
      for (int w = 0; w < this->W; ++w)
      {
        for (std::uint64_t bits = c[w]; bits; bits &= bits - 1)
        {
          const int label = w * 64 + __builtin_ctzll(bits);
          this->ListLabels[at++] = static_cast<std::uint16_t>(label);
          ++this->ReverseStart[ToIndex(d) * ToIndex(this->K) + ToIndex(label) + 1];
        }
      }
      this->ListStart.push_back(static_cast<std::uint32_t>(at));
    }
  }
  this->ReverseStart[0] = static_cast<std::uint32_t>(pairs);
  for (std::size_t r = 0; r < rows; ++r)
  {
    this->ReverseStart[r + 1] += this->ReverseStart[r];
  }
  // Fill the supports in ascending order of b (the lists are walked in that order).
  std::vector<std::uint32_t> next(this->ReverseStart.begin(), this->ReverseStart.end() - 1);
  for (int d = 0; d < this->D; ++d)
  {
    for (int b = 0; b < this->K; ++b)
    {
      for (const std::uint16_t* c = this->ListBegin(d, b); c != this->ListEnd(d, b); ++c)
      {
        this->ListLabels[next[ToIndex(d) * ToIndex(this->K) + *c]++] =
          static_cast<std::uint16_t>(b);
      }
    }
  }
  this->MeanList = static_cast<double>(pairs) / (double(this->D) * double(this->K));
  // A list entry costs about as much as 4 words of an or (measured on Font, k = 2468).
  this->ListsForUnions = 4 * this->MeanList < this->W;
}

void CompatibilityRelation::UnionOf(int d, const std::uint64_t* domain, std::uint64_t* out) const
{
  std::fill(out, out + this->W, 0);
  if (this->ListsForUnions)
  {
    // A sparse relation: setting the bits of the lists is cheaper than or-ing whole sets.
    for (int w = 0; w < this->W; ++w)
    {
      for (std::uint64_t bits = domain[w]; bits; bits &= bits - 1)
      {
        const int b = w * 64 + __builtin_ctzll(bits);
        for (const std::uint16_t* c = this->ListBegin(d, b); c != this->ListEnd(d, b); ++c)
        {
          out[*c >> 6] |= std::uint64_t(1) << (*c & 63);
        }
      }
    }
    return;
  }
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
  this->Scratch.assign(ToIndex(this->W), 0);
  this->Sup.On = false; // until the first Propagate decides
  this->Sup.ByRemovals = 0;
  this->Record(this->Recording); // an empty trail, and stamps for the new sites
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
    for (int w = 0; w < this->W; ++w)
    {
      const std::uint64_t now = d[w] & mask[w];
      if (now != d[w] && this->Recording)
      {
        this->Save(TrailKind::Domain, this->SavedDomain, ToIndex(site) * this->W + w, d[w]);
      }
      d[w] = now;
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

void LabelDomains::Record(bool on)
{
  this->Recording = on;
  this->Trail.clear();
  this->TrailBase = 0;
  this->LastMark = 0;
  this->SavedDomain.clear();
  this->SavedApplied.clear();
  const std::size_t words = ToIndex(this->NumberOfSites()) * ToIndex(this->W);
  if (on && words <= (std::size_t(1) << 24))
  {
    this->SavedDomain.assign(words, 0);
    if (this->Sup.On)
    {
      this->SavedApplied.assign(words, 0);
    }
  }
}

void LabelDomains::Undo(std::size_t mark)
{
  if (mark < this->TrailBase)
  {
    throw Error("label domains: undo past the forgotten part of the trail");
  }
  for (std::int64_t q : this->Queue)
  {
    this->Queued[ToIndex(q)] = 0;
  }
  this->Queue.clear();
  // Newest first, so that the oldest entry after the mark (the value at the mark) wins.
  const std::size_t keep = mark - this->TrailBase;
  const std::uint64_t indexBits = (std::uint64_t(1) << 62) - 1;
  std::vector<std::int64_t>& touched = this->Touched;
  touched.clear();
  while (this->Trail.size() > keep)
  {
    const std::size_t at = this->Trail.size() - 2;
    const auto kind = static_cast<TrailKind>(this->Trail[at] >> 62);
    const std::size_t index = this->Trail[at] & indexBits;
    const std::uint64_t old = this->Trail[at + 1];
    this->Trail.resize(at);
    if (kind == TrailKind::Fresh)
    {
      this->Sup.Fresh[index] = static_cast<std::uint8_t>(old);
      continue;
    }
    const auto site = static_cast<std::int64_t>(index / ToIndex(this->W));
    std::vector<std::uint64_t>& saved =
      kind == TrailKind::Applied ? this->SavedApplied : this->SavedDomain;
    if (!saved.empty())
    {
      saved[index] = 0;
    }
    if (kind == TrailKind::Applied)
    {
      this->Sup.Applied[index] = old;
      continue;
    }
    this->Bits[index] = old;
    if (!this->Queued[ToIndex(site)])
    {
      this->Queued[ToIndex(site)] = 1;
      touched.push_back(site);
    }
  }
  for (const std::int64_t site : touched)
  {
    this->Queued[ToIndex(site)] = 0;
    const int count = PopCount(this->Domain(site), this->W);
    const int now = this->Counts[ToIndex(site)];
    this->DecidedSites += (count == 1) - (now == 1);
    this->Counts[ToIndex(site)] = count;
    this->ChangedSites.push_back(site);
  }
  this->LastMark = mark;
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

void LabelDomains::StartRemovals(const CompatibilityRelation& rules)
{
  // Applied takes as much memory as the sets: at most a quarter of the memory available (a
  // 10^8-site whole model with k > 512 may go by the unions alone).
  RemovalState& sup = this->Sup;
  const std::uint64_t bytes = std::uint64_t(this->Bits.size()) * 8;
  sup.On = this->RemovalsAllowed && this->W > 1 && rules.HasLists() &&
    rules.NumberOfLabels() == this->K &&
    (bytes <= sup.Applied.capacity() * 8 || bytes <= AvailableMemory() / 4);
  if (!sup.On)
  {
    return;
  }
  sup.Rules = &rules;
  sup.Applied = this->Bits;
  if (!this->SavedDomain.empty())
  {
    this->SavedApplied.assign(this->SavedDomain.size(), 0);
  }
  sup.Fresh.assign(ToIndex(this->NumberOfSites()), 1);
  sup.Delta.assign(ToIndex(this->W), 0);
  sup.Candidates.assign(ToIndex(this->W), 0);
}

bool LabelDomains::BeginRevision(const CompatibilityRelation& rules, std::int64_t v)
{
  RemovalState& sup = this->Sup;
  std::uint64_t* applied = sup.Applied.data() + ToIndex(v) * this->W;
  const std::uint64_t* dv = this->Domain(v);
  const bool fresh = sup.Fresh[ToIndex(v)] != 0;
  int removed = 0;
  for (int w = 0; w < this->W; ++w)
  {
    const std::uint64_t delta = applied[w] & ~dv[w];
    sup.Delta[ToIndex(w)] = delta;
    removed += PopCountWord(delta);
    if (delta && this->Recording)
    {
      this->Save(TrailKind::Applied, this->SavedApplied, ToIndex(v) * this->W + w, applied[w]);
    }
    applied[w] = dv[w];
  }
  if (fresh)
  {
    // The first revision from v goes by the union: it removes the labels that had no support
    // in v's set from the start.
    if (this->Recording)
    {
      this->Trail.push_back(
        (static_cast<std::uint64_t>(TrailKind::Fresh) << 62) | static_cast<std::uint64_t>(v));
      this->Trail.push_back(1);
    }
    sup.Fresh[ToIndex(v)] = 0;
    return false;
  }
  // The cost of each way, in list entries per neighbour: the union walks the lists of v's
  // labels, the removals those of the removed labels and the supports of the labels of the
  // neighbour found in them (about as many again).
  const int size = this->Counts[ToIndex(v)];
  if (2 * double(removed) * rules.MeanListLength() * 4 >= rules.UnionCost(size))
  {
    return false;
  }
  ++sup.ByRemovals;
  return true;
}

bool LabelDomains::RemoveUnsupported(
  const CompatibilityRelation& rules, std::int64_t v, std::int64_t u, int d)
{
  // The labels of u that a removed label of v allowed: only these may have lost their last
  // support in v.
  std::uint64_t* candidates = this->Sup.Candidates.data();
  const std::uint64_t* delta = this->Sup.Delta.data();
  for (int w = 0; w < this->W; ++w)
  {
    for (std::uint64_t bits = delta[w]; bits; bits &= bits - 1)
    {
      const int b = w * 64 + __builtin_ctzll(bits);
      for (const std::uint16_t* c = rules.ListBegin(d, b); c != rules.ListEnd(d, b); ++c)
      {
        candidates[*c >> 6] |= std::uint64_t(1) << (*c & 63);
      }
    }
  }
  const std::uint64_t* du = this->Domain(u);
  const std::uint64_t* dv = this->Domain(v);
  bool any = false;
  for (int w = 0; w < this->W; ++w)
  {
    std::uint64_t keep = ~std::uint64_t(0);
    for (std::uint64_t bits = candidates[w] & du[w]; bits; bits &= bits - 1)
    {
      const int c = w * 64 + __builtin_ctzll(bits);
      const std::uint16_t* b = rules.SupportsBegin(d, c);
      const std::uint16_t* end = rules.SupportsEnd(d, c);
      while (b != end && !((dv[*b >> 6] >> (*b & 63)) & 1u))
      {
        ++b;
      }
      if (b == end)
      {
        keep &= ~(std::uint64_t(1) << (c & 63));
      }
    }
    candidates[w] = keep; // the mask for Restrict
    any = any || keep != ~std::uint64_t(0);
  }
  if (any)
  {
    this->Restrict(u, candidates);
  }
  std::fill_n(candidates, this->W, 0);
  return this->Counts[ToIndex(u)] > 0;
}

} // namespace msynth
