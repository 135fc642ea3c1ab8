// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/**
 * @file Propagation.h
 * @brief The propagation engine shared by discrete synthesis (a label grid) and continuous
 * synthesis (the vertices of a plane arrangement).
 *
 * - CompatibilityRelation: for each direction class d and label b, the set of labels allowed at
 *   the neighbour reached from a site holding b along d, as a bit set of k bits. The grid has six
 *   direction classes (±x, ±y, ±z); an arrangement has two per line direction.
 * - LabelDomains: the catalog C (dissertation §3.3.2, Algorithms 3.2–3.3): the labels still
 *   possible at each of n sites as bit sets, and arc-consistency propagation over any
 *   neighbourhood structure given as a callable. When the set at v shrinks, each neighbour u of v
 *   keeps only the labels some label of v allows there.
 *
 * Memory is k bits plus a few bytes per site; there are no per-label support counters.
 */
#include "Core/Index.h"
#include <cstdint>
#include <vector>

namespace msynth
{

class CompatibilityRelation
{
public:
  int NumberOfLabels() const { return this->K; }
  /// 64-bit words per label set.
  int Words() const { return this->W; }
  /// Number of direction classes.
  int Directions() const { return this->D; }

  /// Labels allowed at the neighbour along direction @p d of a site holding @p b (Words() words).
  const std::uint64_t* Compatible(int d, int b) const
  {
    return this->Bits.data() + (ToIndex(d) * this->K + b) * this->W;
  }
  /// Union over b of Compatible(d, b).
  const std::uint64_t* CompatibleWithAny(int d) const
  {
    return this->AnyBits.data() + ToIndex(d) * this->W;
  }
  /**
   * Writes to @p out (Words() words) the union of Compatible(d, b) over b in @p domain. With
   * k ≤ 512 this reads precomputed unions of 8-label chunks (k/8 lookups); otherwise it walks
   * the labels.
   */
  void UnionOf(int d, const std::uint64_t* domain, std::uint64_t* out) const;
  /// UnionOf for k <= 64 (one word): the unions of the set's 8-label chunks, inline.
  std::uint64_t UnionOfWord(int d, std::uint64_t domain) const
  {
    const int chunks = (this->K + 7) / 8;
    const std::uint64_t* table = this->ChunkUnions.data() + ToIndex(d) * ToIndex(chunks) * 256;
    std::uint64_t out = 0;
    for (int j = 0; j < chunks && domain; ++j, domain >>= 8, table += 256)
    {
      out |= (domain & 0xffu) ? table[domain & 0xffu] : 0;
    }
    return out;
  }
  bool Allowed(int d, int b, int c) const
  {
    return (this->Compatible(d, b)[c >> 6] >> (c & 63)) & 1u;
  }

protected:
  /// k labels, @p directions direction classes, nothing allowed yet. @throw Error if k < 1.
  void Allocate(int k, int directions);
  /// Label @p c may be the neighbour along @p d of a site holding @p b (one direction only).
  void AllowOne(int d, int b, int c)
  {
    this->Bits[(ToIndex(d) * this->K + b) * this->W + (c >> 6)] |= std::uint64_t(1) << (c & 63);
  }
  /// Builds the unions; call once after the last AllowOne().
  void Finish();

private:
  int K = 0;
  int W = 0;
  int D = 0;
  std::vector<std::uint64_t> Bits;    // [direction][label][word]
  std::vector<std::uint64_t> AnyBits; // [direction][word]
  /// [direction][chunk of 8 labels][byte value][word]; empty when k > 512.
  std::vector<std::uint64_t> ChunkUnions;
};

class LabelDomains
{
public:
  /// @p n sites, each with every one of @p k labels possible.
  void Reset(std::int64_t n, int k);
  /// @p n sites with the given initial sets (@p initial holds n · Words() words).
  void Reset(std::int64_t n, int k, std::vector<std::uint64_t> initial);

  std::int64_t NumberOfSites() const { return static_cast<std::int64_t>(this->Counts.size()); }
  int NumberOfLabels() const { return this->K; }
  int Words() const { return this->W; }
  /// Number of labels possible at @p site.
  int Count(std::int64_t site) const { return this->Counts[ToIndex(site)]; }
  const std::uint64_t* Domain(std::int64_t site) const
  {
    return this->Bits.data() + ToIndex(site) * this->W;
  }
  bool Contains(std::int64_t site, int b) const
  {
    return (this->Domain(site)[b >> 6] >> (b & 63)) & 1u;
  }
  /// Sites with exactly one label left.
  std::int64_t Decided() const { return this->DecidedSites; }
  /// The only (lowest) label left at @p site; -1 if none.
  int Single(std::int64_t site) const;

  /// Keeps only label @p b at @p site. Returns false when @p b was not possible there.
  bool Assign(std::int64_t site, int b);
  /// Keeps at @p site only the labels of @p mask (Words() words). False if nothing is left.
  bool Keep(std::int64_t site, const std::uint64_t* mask);

  /**
   * Undo support for search with backtracking: while recording, every change keeps the old set.
   * Mark() names the current state; Undo(mark) restores it (and reports the restored sites as
   * changed). Recording costs Words() + 2 words per change.
   */
  void Record(bool on)
  {
    this->Recording = on;
    this->Trail.clear();
    this->TrailBase = 0;
  }
  /// Marks count every word recorded since Record(true), also those that Forget() dropped.
  std::size_t Mark() const { return this->TrailBase + this->Trail.size(); }
  /// Restores the state of @p mark, which must not be older than the last Forget().
  void Undo(std::size_t mark);
  /// Drops the record of the changes before @p mark (no Undo will go back past it), when that
  /// is most of the trail: a long search keeps only the trail it can still undo.
  void Forget(std::size_t mark);

  /// Sites whose sets changed since ClearChanged().
  const std::vector<std::int64_t>& Changed() const { return this->ChangedSites; }
  void ClearChanged() { this->ChangedSites.clear(); }

  /**
   * Propagates every change since the last call (Algorithm 3.2's loop, first in first out); the
   * first call after Reset revises every site.
   * @p forEachNeighbour(v, visit) calls visit(u, d) for each neighbour u reached from v along
   * direction class d of @p rules; visit returns false to stop (a set became empty).
   * Returns -1 when every set is non-empty, else a site whose set became empty.
   */
  template <class ForEachNeighbour>
  std::int64_t Propagate(const CompatibilityRelation& rules, ForEachNeighbour&& forEachNeighbour)
  {
    if (this->FromScratch)
    {
      // The first pass after Reset revises every site, not only the changed ones, so the sets
      // become arc consistent from the start (the catalog C of Statement 3.6): a label without
      // support at a neighbour goes before any choice. Changed sites keep their place first.
      this->FromScratch = false;
      for (std::int64_t s = 0; s < this->NumberOfSites(); ++s)
        this->Push(s);
    }
    std::size_t head = this->W == 1 ? this->Drain<true>(rules, forEachNeighbour)
                                    : this->Drain<false>(rules, forEachNeighbour);
    if (this->EmptySite >= 0)
    {
      for (std::size_t i = head; i < this->Queue.size(); ++i)
      {
        this->Queued[ToIndex(this->Queue[i])] = 0;
      }
    }
    this->Queue.clear();
    return this->EmptySite;
  }

private:
  /// Propagate's loop over the queue; returns how far it got. OneWord: k <= 64, the sets and
  /// the unions as single words, inline.
  template <bool OneWord, class ForEachNeighbour>
  std::size_t Drain(const CompatibilityRelation& rules, ForEachNeighbour& forEachNeighbour)
  {
    std::vector<std::uint64_t>& allowed = this->Scratch;
    std::size_t head = 0;
    while (head < this->Queue.size() && this->EmptySite < 0)
    {
      const std::int64_t v = this->Queue[head++];
      if (head > 4096 && head * 2 > this->Queue.size())
      {
        this->Queue.erase(
          this->Queue.begin(), this->Queue.begin() + static_cast<std::ptrdiff_t>(head));
        head = 0;
      }
      this->Queued[ToIndex(v)] = 0;
      const std::uint64_t* dv = this->Domain(v);
      forEachNeighbour(v,
        [&](std::int64_t u, int d) -> bool
        {
          if (this->Counts[ToIndex(u)] == 0)
          {
            return true;
          }
          const bool any = this->Counts[ToIndex(v)] == this->K;
          if constexpr (OneWord)
          {
            // v unconstrained: the precomputed union
            return this->RestrictWord(
              u, any ? *rules.CompatibleWithAny(d) : rules.UnionOfWord(d, *dv));
          }
          else
          {
            const std::uint64_t* mask;
            if (any)
            {
              mask = rules.CompatibleWithAny(d); // v is unconstrained: precomputed union
            }
            else
            {
              rules.UnionOf(d, dv, allowed.data());
              mask = allowed.data();
            }
            return this->Restrict(u, mask);
          }
        });
    }
    return head;
  }
  /// Restrict for one-word sets.
  bool RestrictWord(std::int64_t site, std::uint64_t mask)
  {
    std::uint64_t& d = this->Bits[ToIndex(site)];
    int& count = this->Counts[ToIndex(site)];
    if ((d & mask) != d)
    {
      if (this->Recording)
      {
        if (this->Trail.capacity() - this->Trail.size() < 3)
        {
          this->Trail.reserve(2 * this->Trail.size() + 1024);
        }
        this->Trail.push_back(static_cast<std::uint64_t>(site));
        this->Trail.push_back(static_cast<std::uint64_t>(count));
        this->Trail.push_back(d);
      }
      d &= mask;
      const int now = PopCountWord(d);
      this->DecidedSites += (now == 1) - (count == 1);
      count = now;
      this->ChangedSites.push_back(site);
      this->Push(site);
      if (now == 0 && this->EmptySite < 0)
      {
        this->EmptySite = site;
      }
    }
    return count > 0;
  }
  static int PopCountWord(std::uint64_t x)
  {
    x = x - ((x >> 1) & 0x5555555555555555ull);
    x = (x & 0x3333333333333333ull) + ((x >> 2) & 0x3333333333333333ull);
    x = (x + (x >> 4)) & 0x0f0f0f0f0f0f0f0full;
    return static_cast<int>((x * 0x0101010101010101ull) >> 56);
  }

  /// Counts, queue and trail for @p n sites whose sets are in Bits.
  void Start(std::int64_t n);
  bool Restrict(std::int64_t site, const std::uint64_t* mask);
  void Push(std::int64_t site)
  {
    if (!this->Queued[ToIndex(site)])
    {
      this->Queued[ToIndex(site)] = 1;
      this->Queue.push_back(site);
    }
  }

  int K = 0;
  int W = 0;
  std::vector<std::uint64_t> Bits;
  std::vector<int> Counts;
  std::vector<std::uint8_t> Queued;
  std::vector<std::int64_t> Queue;
  std::vector<std::int64_t> ChangedSites;
  std::vector<std::uint64_t> Scratch;
  std::int64_t EmptySite = -1;
  std::int64_t DecidedSites = 0;
  bool Recording = false;
  bool FromScratch = false;         ///< set by Reset: the next Propagate revises every site
  std::vector<std::uint64_t> Trail; ///< [site, count, W old words] per recorded change
  std::size_t TrailBase = 0;        ///< words recorded before Trail[0] (dropped by Forget)
};

} // namespace msynth
