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
 * Memory is k bits plus a few bytes per site. With k > 512 and a sparse relation, Propagate
 * also keeps each site's set as of its last revision (Applied: k bits more per site) when that
 * takes at most a quarter of the memory available, and revises by the labels removed since then
 * where that is cheaper than by the union: a removal costs the labels compatible with it.
 */
#include "Core/Index.h"
#include <cstdint>
#include <memory>
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

  /// Compatible(d, b) as a list of labels (ascending), for revisions by removals; empty unless
  /// HasLists().
  const std::uint16_t* ListBegin(int d, int b) const
  {
    return this->ListLabels.data() + this->ListStart[ToIndex(d) * ToIndex(this->K) + ToIndex(b)];
  }
  const std::uint16_t* ListEnd(int d, int b) const
  {
    return this->ListLabels.data() +
      this->ListStart[ToIndex(d) * ToIndex(this->K) + ToIndex(b) + 1];
  }
  /// The labels b with @p c in Compatible(d, b) (ascending): the supports of c along d; empty
  /// unless HasLists().
  const std::uint16_t* SupportsBegin(int d, int c) const
  {
    return this->ListLabels.data() + this->ReverseStart[ToIndex(d) * ToIndex(this->K) + ToIndex(c)];
  }
  const std::uint16_t* SupportsEnd(int d, int c) const
  {
    return this->ListLabels.data() +
      this->ReverseStart[ToIndex(d) * ToIndex(this->K) + ToIndex(c) + 1];
  }
  /**
   * Whether the lists exist: with 512 < k < 65536 labels and at most a quarter of the pairs
   * allowed (then the lists take at most 8 times the bit sets' memory).
   */
  bool HasLists() const { return !this->ListStart.empty(); }
  /// Mean length of a list: the mean cost of one removed label at one neighbour.
  double MeanListLength() const { return this->MeanList; }
  /// The cost of UnionOf for a set of @p size labels, in words of an or (k > 512).
  double UnionCost(int size) const
  {
    return (this->ListsForUnions ? 4 * this->MeanList : double(this->W)) * size;
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
  std::vector<std::uint32_t> ListStart;    ///< [direction][label], D·k + 1 offsets into ListLabels
  std::vector<std::uint32_t> ReverseStart; ///< [direction][label]: offsets of the supports
  std::vector<std::uint16_t> ListLabels;   ///< the pairs of Bits as lists, then as supports
  double MeanList = 0;
  bool ListsForUnions = false; ///< UnionOf walks the lists (a sparse relation)

  void BuildLists();
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
   * Undo support for search with backtracking: while recording, every change keeps the old
   * words of the set. Mark() names the current state; Undo(mark) restores it (and reports the
   * restored sites as changed). Recording costs 2 words per changed word of a set (with support
   * counts, also per changed word of Applied), each word kept once between two marks when the
   * sites' stamps fit (8 bytes per site and word, at most 2^24 words): Undo needs only the state
   * at the mark, so a site revised many times after one choice is recorded once.
   */
  void Record(bool on);
  /// Names the current state for Undo. Marks count every word recorded since Record(true), also
  /// those that Forget() dropped.
  std::size_t Mark()
  {
    this->LastMark = this->TrailBase + this->Trail.size();
    return this->LastMark;
  }
  /// Words of the trail kept now (those Forget() dropped not counted).
  std::size_t TrailWords() const { return this->Trail.size(); }
  /// Restores the state of @p mark, which must not be older than the last Forget().
  void Undo(std::size_t mark);
  /// Drops the record of the changes before @p mark (no Undo will go back past it), when that
  /// is most of the trail: a long search keeps only the trail it can still undo.
  void Forget(std::size_t mark);

  /**
   * Whether Propagate may revise by removals (see RemovalState) where k, the relation and the
   * memory allow; on by default. Either way the sets, and the order of Changed(), are the same.
   * Takes effect at the next Reset.
   */
  void AllowRevisionsByRemovals(bool on) { this->RemovalsAllowed = on; }
  /// Whether the propagation since the last Reset may revise by removals.
  bool UsesRevisionsByRemovals() const { return this->Sup.On; }
  /// Revisions since the last Reset that went by removals (the rest by unions).
  std::int64_t RevisionsByRemovals() const { return this->Sup.ByRemovals; }

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
      this->StartRemovals(rules);
      for (std::int64_t s = 0; s < this->NumberOfSites(); ++s)
        this->Push(s);
    }
    else if (this->Sup.On && &rules != this->Sup.Rules)
    {
      this->Sup.On = false; // another relation: Applied does not hold for it
    }
    std::size_t head = this->W == 1 ? this->Drain<true>(rules, forEachNeighbour)
      : this->Sup.On                ? this->DrainByRemovals(rules, forEachNeighbour)
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
  /// The queue's site at @p head, taken off it (the queue compacted once most of it is done).
  std::int64_t Pop(std::size_t& head)
  {
    const std::int64_t v = this->Queue[head++];
    if (head > 4096 && head * 2 > this->Queue.size())
    {
      this->Queue.erase(
        this->Queue.begin(), this->Queue.begin() + static_cast<std::ptrdiff_t>(head));
      head = 0;
    }
    this->Queued[ToIndex(v)] = 0;
    return v;
  }

  /// Propagate's loop over the queue; returns how far it got. OneWord: k <= 64, the sets and
  /// the unions as single words, inline.
  template <bool OneWord, class ForEachNeighbour>
  std::size_t Drain(const CompatibilityRelation& rules, ForEachNeighbour& forEachNeighbour)
  {
    std::vector<std::uint64_t>& allowed = this->Scratch;
    std::size_t head = 0;
    while (head < this->Queue.size() && this->EmptySite < 0)
    {
      const std::int64_t v = this->Pop(head);
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
  /**
   * Drain by removals: a site v whose set lost fewer labels since its last revision (Applied)
   * than it has left revises its neighbours by those removals (RemoveUnsupported: each removed
   * label costs its list, each label of a neighbour that lost a support its reverse list);
   * otherwise, and on its first revision, by the union as Drain does. Both give the same sets,
   * in the same order of revisions.
   */
  template <class ForEachNeighbour>
  std::size_t DrainByRemovals(
    const CompatibilityRelation& rules, ForEachNeighbour& forEachNeighbour)
  {
    std::vector<std::uint64_t>& allowed = this->Scratch;
    std::size_t head = 0;
    while (head < this->Queue.size() && this->EmptySite < 0)
    {
      const std::int64_t v = this->Pop(head);
      const bool byRemovals = this->BeginRevision(rules, v);
      const std::uint64_t* dv = this->Domain(v);
      forEachNeighbour(v,
        [&](std::int64_t u, int d) -> bool
        {
          if (this->Counts[ToIndex(u)] == 0)
          {
            return true;
          }
          if (byRemovals)
          {
            return this->RemoveUnsupported(rules, v, u, d);
          }
          const std::uint64_t* mask;
          if (this->Counts[ToIndex(v)] == this->K)
          {
            mask = rules.CompatibleWithAny(d); // v is unconstrained: precomputed union
          }
          else
          {
            rules.UnionOf(d, dv, allowed.data());
            mask = allowed.data();
          }
          return this->Restrict(u, mask);
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
        this->Save(TrailKind::Domain, this->SavedDomain, ToIndex(site), d);
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

  /**
   * Revision by removals, set up by the first Propagate after Reset when k > 512, the relation
   * has lists and Applied fits in a quarter of the memory available. Invariant: each label at a
   * neighbour u of a site v has a support in Applied[v] (the set of v at its last revision), so
   * when v loses labels, only the labels of u in the lists of those removals can lose their
   * last support, and each is checked against Domain(v) by its reverse list (AC-3 with the
   * removals as the delta; no per-pair counts to keep, so no memory per site and label beyond
   * Applied's bit, and Undo restores Applied from the trail).
   */
  struct RemovalState
  {
    bool On = false;
    const CompatibilityRelation* Rules = nullptr;
    std::vector<std::uint64_t> Applied;    ///< [site][word]: the set at the site's last revision
    std::vector<std::uint8_t> Fresh;       ///< per site: not yet revised since Reset
    std::vector<std::uint64_t> Delta;      ///< the revision's removals (Words() words)
    std::vector<std::uint64_t> Candidates; ///< labels of a neighbour that lost a support
    std::int64_t ByRemovals = 0;
  };

  /// Decides whether the sets go by removals (k, the relation's lists and the memory).
  void StartRemovals(const CompatibilityRelation& rules);
  /// Before v revises its neighbours: true when by its removals (Sup.Delta), false when by the
  /// union (also the first revision from v after Reset); either way Applied[v] = Domain(v).
  bool BeginRevision(const CompatibilityRelation& rules, std::int64_t v);
  /// Removes the labels of u (along @p d from v) left without support by Sup.Delta; false when
  /// u's set became empty.
  bool RemoveUnsupported(const CompatibilityRelation& rules, std::int64_t v, std::int64_t u, int d);

  /// What a trail entry holds: a word of a set, a word of Applied, or Fresh of a site.
  enum class TrailKind : std::uint64_t
  {
    Domain = 0,
    Applied = 1,
    Fresh = 2
  };
  /**
   * Trail entry [kind and index, old value] for word @p index (site · Words() + word; a site
   * for Fresh) before it changes, unless it was kept since the last mark (@p saved: per word,
   * 1 + the position of its latest entry; empty when the stamps did not fit).
   */
  void Save(TrailKind kind, std::vector<std::uint64_t>& saved, std::size_t index, std::uint64_t old)
  {
    if (!saved.empty())
    {
      std::uint64_t& at = saved[index];
      if (at > this->LastMark)
      {
        return; // kept since the last mark: Undo restores that older value
      }
      at = this->TrailBase + this->Trail.size() + 1;
    }
    this->Trail.push_back((static_cast<std::uint64_t>(kind) << 62) | index);
    this->Trail.push_back(old);
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
  bool FromScratch = false;                ///< set by Reset: the next Propagate revises every site
  std::vector<std::uint64_t> Trail;        ///< [kind and index, old value] per recorded change
  std::size_t TrailBase = 0;               ///< words recorded before Trail[0] (dropped by Forget)
  std::size_t LastMark = 0;                ///< the latest Mark() (or Undo's mark)
  std::vector<std::uint64_t> SavedDomain;  ///< per word of Bits: see Save
  std::vector<std::uint64_t> SavedApplied; ///< per word of Sup.Applied: see Save
  std::vector<std::int64_t> Touched;       ///< Undo's restored sites
  RemovalState Sup;
  bool RemovalsAllowed = true;
};

} // namespace msynth
