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
  this->ListLabels.clear();
  this->Supports.clear();
  this->MeanList = 0;
  this->MaxSupports = 0;
  this->ListsForUnions = false;
  if (this->K <= 512 || this->K >= 65536)
  {
    // Up to 512 labels the chunk unions cost at most k/8 lookups a revision, less than setting
    // the counts up (measured: City, k = 93, 40 x 40 x 10 took 44 % longer with counts);
    // 65536 labels and more: no 16-bit counts.
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
  this->ListStart.reserve(ToIndex(this->D) * ToIndex(this->K) + 1);
  this->ListLabels.reserve(pairs);
  this->Supports.assign(ToIndex(this->D) * ToIndex(this->K), 0);
  this->ListStart.push_back(0);
  for (int d = 0; d < this->D; ++d)
  {
    std::uint16_t* supports = this->Supports.data() + ToIndex(d) * ToIndex(this->K);
    for (int b = 0; b < this->K; ++b)
    {
      const std::uint64_t* c = this->Compatible(d, b);
      for (int w = 0; w < this->W; ++w)
      {
        for (std::uint64_t bits = c[w]; bits; bits &= bits - 1)
        {
          const int label = w * 64 + __builtin_ctzll(bits);
          this->ListLabels.push_back(static_cast<std::uint16_t>(label));
          this->MaxSupports = std::max<int>(this->MaxSupports, ++supports[label]);
        }
      }
      this->ListStart.push_back(static_cast<std::uint32_t>(this->ListLabels.size()));
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
  this->Trail.clear();
  this->TrailBase = 0;
  this->Scratch.assign(ToIndex(this->W), 0);
  for (const std::int64_t v : this->Sup.StaleSites)
  {
    std::fill_n(this->Sup.Stale.data() + ToIndex(v) * this->W, this->W, 0);
  }
  this->Sup.StaleSites.clear();
  this->Sup.On = false; // until the first Propagate sets the counts up
  this->Sup.ByRemovals = 0;
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
    if (this->Trail[at] >> 63)
    {
      this->UndoApplied(static_cast<std::int64_t>(this->Trail[at] & ~(std::uint64_t(1) << 63)),
        this->Trail[at + 1] != 0, this->Trail.data() + at + 2);
      this->Trail.resize(at);
      continue;
    }
    const auto site = static_cast<std::int64_t>(this->Trail[at]);
    const int count = static_cast<int>(this->Trail[at + 1]);
    std::copy_n(this->Trail.data() + at + 2, this->W, this->Bits.data() + ToIndex(site) * this->W);
    if (this->Sup.On)
    {
      // A set restored from before the counts were set up may hold labels Applied lacks.
      this->UndoApplied(site, this->Sup.Fresh[ToIndex(site)] != 0, this->Domain(site));
    }
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

bool LabelDomains::SupportsFit(std::size_t pairs) const
{
  // The counts take at most a quarter of the memory available (a 10^8-site whole model with
  // k > 512 never has them: it goes by the unions).
  const std::uint64_t width = this->Sup.Narrow ? 1 : 2;
  const std::uint64_t bytes = std::uint64_t(pairs) * std::uint64_t(this->K) * width +
    2 * std::uint64_t(this->NumberOfSites()) * std::uint64_t(this->W) * 8;
  return bytes <= std::uint64_t(this->Sup.Allocated) || bytes <= AvailableMemory() / 4;
}

bool LabelDomains::NumberPairs(const std::vector<std::int8_t>& state)
{
  SupportState& sup = this->Sup;
  sup.Countable.assign(state.size(), 0);
  for (std::size_t d = 0; d < state.size(); ++d)
  {
    sup.Countable[d] = state[d] > 0;
  }
  // Site by site, so that the pairs of a site are together.
  std::size_t pairs = 0;
  for (std::size_t i = 0; i < sup.PairOf.size(); ++i)
  {
    if (sup.PairOf[i] != NoPair && sup.Countable[i % sup.Classes])
    {
      sup.PairOf[i] = static_cast<std::uint32_t>(pairs++);
    }
  }
  if (pairs == 0 || !this->SupportsFit(pairs))
  {
    return false;
  }
  const std::size_t bytes = pairs * ToIndex(this->K) * (sup.Narrow ? 1 : 2);
  if (bytes > sup.Allocated)
  {
    // Not value-initialised: a pair's counts are written when first needed, so pages of pairs
    // never counted are never touched.
    sup.Counts.reset();
    sup.Counts.reset(new std::uint8_t[bytes]);
    AdviseHugePages(sup.Counts.get(), bytes);
    sup.Allocated = bytes;
  }
  sup.Pairs = pairs;
  sup.Ready.assign(pairs, 0);
  sup.Applied = this->Bits;
  sup.Fresh.assign(ToIndex(this->NumberOfSites()), 1);
  if (!sup.Stale.empty())
  {
    sup.Stale.assign(ToIndex(this->NumberOfSites()) * ToIndex(this->W), 0);
  }
  sup.Delta.assign(ToIndex(this->W), 0);
  sup.Removed.assign(ToIndex(this->W), 0);
  sup.On = true;
  return true;
}

template <typename Tally>
void LabelDomains::CountSupports(
  const CompatibilityRelation& rules, Tally* counts, int d, const std::uint64_t* source)
{
  const int size = PopCount(source, this->W);
  if (2 * size < this->K)
  {
    std::fill_n(counts, this->K, 0);
    AddSupports(rules, counts, d, source);
    return;
  }
  // Most labels possible: all of them, less the supports of the missing ones.
  const std::uint16_t* full = rules.FullSupports(d);
  for (int c = 0; c < this->K; ++c)
  {
    counts[c] = static_cast<Tally>(full[c]);
  }
  for (int w = 0; w < this->W; ++w)
  {
    const bool last = w == this->W - 1 && this->K % 64;
    const std::uint64_t all = last ? (std::uint64_t(1) << (this->K % 64)) - 1 : ~std::uint64_t(0);
    for (std::uint64_t bits = all & ~source[w]; bits; bits &= bits - 1)
    {
      const int b = w * 64 + __builtin_ctzll(bits);
      for (const std::uint16_t* c = rules.ListBegin(d, b); c != rules.ListEnd(d, b); ++c)
      {
        --counts[*c];
      }
    }
  }
}

template <typename Tally>
void LabelDomains::AddSupports(
  const CompatibilityRelation& rules, Tally* counts, int d, const std::uint64_t* labels)
{
  const int words = rules.Words();
  for (int w = 0; w < words; ++w)
  {
    for (std::uint64_t bits = labels[w]; bits; bits &= bits - 1)
    {
      const int b = w * 64 + __builtin_ctzll(bits);
      for (const std::uint16_t* c = rules.ListBegin(d, b); c != rules.ListEnd(d, b); ++c)
      {
        ++counts[*c];
      }
    }
  }
}

void LabelDomains::RecordApplied(std::int64_t site)
{
  const std::uint64_t* applied = this->Sup.Applied.data() + ToIndex(site) * this->W;
  this->Trail.push_back(static_cast<std::uint64_t>(site) | (std::uint64_t(1) << 63));
  this->Trail.push_back(this->Sup.Fresh[ToIndex(site)]);
  this->Trail.insert(this->Trail.end(), applied, applied + this->W);
}

bool LabelDomains::BeginRevision(const CompatibilityRelation& rules, std::int64_t v)
{
  SupportState& sup = this->Sup;
  std::uint64_t* applied = sup.Applied.data() + ToIndex(v) * this->W;
  if (sup.Fresh[ToIndex(v)])
  {
    // The first revision from v goes by the union: it removes the labels that had no support
    // in v's set from the start (their counts are zero).
    if (this->Recording)
    {
      this->RecordApplied(v);
    }
    sup.Fresh[ToIndex(v)] = 0;
    return false;
  }
  const std::uint64_t* dv = this->Domain(v);
  int removed = 0;
  for (int w = 0; w < this->W; ++w)
  {
    sup.Delta[ToIndex(w)] = applied[w] & ~dv[w];
    removed += PopCountWord(sup.Delta[ToIndex(w)]);
  }
  if (removed == 0)
  {
    return false;
  }
  // The cost of each way, in words or list entries per neighbour: the union walks v's labels
  // (with k <= 512, at most k/8 table entries), the removals their lists.
  // A count brought down costs about 4 words of an or (a scattered write to k counts against a
  // sequential read; measured on Font, k = 2468).
  const double byUnion = rules.UnionCost(this->Counts[ToIndex(v)]);
  if (4 * double(removed) * rules.MeanListLength() >= byUnion)
  {
    return false;
  }
  if (this->Recording)
  {
    this->RecordApplied(v);
  }
  std::copy_n(dv, this->W, applied);
  ++sup.ByRemovals;
  return true;
}

void LabelDomains::AddSupportsTo(
  const CompatibilityRelation& rules, std::uint32_t pair, int d, const std::uint64_t* labels)
{
  if (this->Sup.Narrow)
  {
    AddSupports(rules, this->CountsOf<std::uint8_t>(pair), d, labels);
  }
  else
  {
    AddSupports(rules, this->CountsOf<std::uint16_t>(pair), d, labels);
  }
}

void LabelDomains::RemoveUnsupported(
  const CompatibilityRelation& rules, std::int64_t v, std::int64_t u, int d, std::uint32_t pair)
{
  const bool any = this->Sup.Narrow ? this->FindUnsupported<std::uint8_t>(rules, v, u, d, pair)
                                    : this->FindUnsupported<std::uint16_t>(rules, v, u, d, pair);
  if (any)
  {
    std::uint64_t* removed = this->Sup.Removed.data();
    for (int w = 0; w < this->W; ++w)
    {
      removed[w] = ~removed[w];
    }
    this->Restrict(u, removed);
  }
}

template <typename Tally>
bool LabelDomains::FindUnsupported(
  const CompatibilityRelation& rules, std::int64_t v, std::int64_t u, int d, std::uint32_t pair)
{
  Tally* counts = this->CountsOf<Tally>(pair);
  const std::uint64_t* du = this->Domain(u);
  const bool live = this->EmptySite < 0 && this->Counts[ToIndex(u)] > 0;
  std::uint64_t* removed = this->Sup.Removed.data();
  bool any = false;
  if (!this->Sup.Ready[pair])
  {
    // First use: the counts of Domain(v) (= Applied[v] now); the labels of u with none go.
    this->Sup.Ready[pair] = 1;
    this->CountSupports(rules, counts, d, this->Domain(v));
    for (int w = 0; w < this->W && live; ++w)
    {
      removed[w] = 0;
      for (std::uint64_t bits = du[w]; bits; bits &= bits - 1)
      {
        const int c = w * 64 + __builtin_ctzll(bits);
        if (counts[c] == 0)
        {
          removed[w] |= std::uint64_t(1) << (c & 63);
          any = true;
        }
      }
    }
  }
  else
  {
    for (int w = 0; w < this->W; ++w)
    {
      for (std::uint64_t bits = this->Sup.Delta[ToIndex(w)]; bits; bits &= bits - 1)
      {
        const int b = w * 64 + __builtin_ctzll(bits);
        for (const std::uint16_t* c = rules.ListBegin(d, b); c != rules.ListEnd(d, b); ++c)
        {
          if (--counts[*c] == 0 && live && ((du[*c >> 6] >> (*c & 63)) & 1u))
          {
            if (!any)
            {
              std::fill_n(removed, this->W, 0);
              any = true;
            }
            removed[*c >> 6] |= std::uint64_t(1) << (*c & 63);
          }
        }
      }
    }
  }
  return any;
}

std::uint64_t* LabelDomains::StaleOf(std::int64_t site)
{
  SupportState& sup = this->Sup;
  if (sup.Stale.empty())
  {
    sup.Stale.assign(ToIndex(this->NumberOfSites()) * ToIndex(this->W), 0);
  }
  std::uint64_t* stale = sup.Stale.data() + ToIndex(site) * this->W;
  if (std::all_of(stale, stale + this->W, [](std::uint64_t x) { return x == 0; }))
  {
    sup.StaleSites.push_back(site);
  }
  return stale;
}

void LabelDomains::UndoApplied(std::int64_t site, bool fresh, const std::uint64_t* applied)
{
  SupportState& sup = this->Sup;
  if (!sup.On)
  {
    return;
  }
  std::uint64_t* now = sup.Applied.data() + ToIndex(site) * this->W;
  std::uint64_t* stale = nullptr;
  for (int w = 0; w < this->W; ++w)
  {
    const std::uint64_t back = applied[w] & ~now[w];
    if (back)
    {
      stale = stale ? stale : this->StaleOf(site);
      stale[w] |= back;
      now[w] |= back;
    }
  }
  sup.Fresh[ToIndex(site)] = fresh ? 1 : 0;
}

} // namespace msynth
