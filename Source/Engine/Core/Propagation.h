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
 * also keeps support counts (AC-4: per site, direction class and label, how many labels of the
 * neighbour allow it; 16 bits each, so 2 bytes per class and 2 bits more per site and label)
 * when they take at most a quarter of the memory available, and revises by the removed labels
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

  /// Compatible(d, b) as a list of labels (ascending), for support counting; empty unless
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
  /**
   * Whether the lists exist: with 512 < k < 65536 labels and at most a quarter of the pairs
   * allowed (then the lists take at most 4 times the bit sets' memory).
   */
  bool HasLists() const { return !this->ListStart.empty(); }
  /// Mean length of a list: the mean cost of counting one removed label at one neighbour.
  double MeanListLength() const { return this->MeanList; }
  /// The cost of UnionOf for a set of @p size labels, in words of an or (k > 512).
  double UnionCost(int size) const
  {
    return (this->ListsForUnions ? 4 * this->MeanList : double(this->W)) * size;
  }
  /// The largest FullSupports entry.
  int MostSupports() const { return this->MaxSupports; }
  /// Per label c, the number of labels b with c in Compatible(d, b) (HasLists() only).
  const std::uint16_t* FullSupports(int d) const
  {
    return this->Supports.data() + ToIndex(d) * ToIndex(this->K);
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
  std::vector<std::uint32_t> ListStart;  ///< [direction][label], D·k + 1 offsets into ListLabels
  std::vector<std::uint16_t> ListLabels; ///< the pairs of Bits as lists
  std::vector<std::uint16_t> Supports;   ///< [direction][label]: FullSupports
  double MeanList = 0;
  int MaxSupports = 0;
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
   * Undo support for search with backtracking: while recording, every change keeps the old set.
   * Mark() names the current state; Undo(mark) restores it (and reports the restored sites as
   * changed). Recording costs Words() + 2 words per change (with support counts, also per
   * revision by removals).
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

  /**
   * Whether Propagate may count supports (AC-4, see SupportState) where k, the relation and
   * the memory allow; on by default. Either way the sets, and the order of Changed(), are the
   * same. Takes effect at the next Reset.
   */
  void AllowSupportCounts(bool on) { this->CountsAllowed = on; }
  /// Whether the propagation since the last Reset counts supports.
  bool UsesSupportCounts() const { return this->Sup.On; }
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
      this->StartSupports(rules, forEachNeighbour);
      for (std::int64_t s = 0; s < this->NumberOfSites(); ++s)
        this->Push(s);
    }
    else if (this->Sup.On && &rules != this->Sup.Rules)
    {
      this->Sup.On = false; // another relation: the counts do not hold for it
    }
    else if (this->Sup.On && !this->Sup.StaleSites.empty())
    {
      this->Recount(rules, forEachNeighbour);
    }
    std::size_t head = this->W == 1 ? this->Drain<true>(rules, forEachNeighbour)
      : this->Sup.On                ? this->DrainCounted(rules, forEachNeighbour)
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
   * Drain with support counts: a site v whose set lost few labels since its counts were last
   * brought up to date (Sup.Applied) revises its neighbours by those removals (AC-4: each removed
   * label costs its list); otherwise, and along classes without counts, by the union as Drain
   * does. Both give the same sets (the counts hold at every site: see SupportState), in the same
   * order of revisions.
   */
  template <class ForEachNeighbour>
  std::size_t DrainCounted(const CompatibilityRelation& rules, ForEachNeighbour& forEachNeighbour)
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
          if (byRemovals)
          {
            // Every neighbour along a counted class has its counts brought down, also after a
            // set emptied (then nothing is removed), so that the counts stay those of Applied.
            const std::uint32_t pair = this->PairOf(u, d);
            if (pair != NoPair)
            {
              this->RemoveUnsupported(rules, v, u, d, pair);
              return true;
            }
            if (this->EmptySite >= 0)
            {
              return true;
            }
          }
          if (this->Counts[ToIndex(u)] == 0)
          {
            return true;
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
          return this->Restrict(u, mask) || byRemovals;
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

  /**
   * Support counts (AC-4), set up by the first Propagate after Reset when k > 512, the relation
   * has lists and the counts fit (SupportsFit). A pair is a site u and a counted direction
   * class d along which u is reached from one neighbour v (its source); Counts[pair][c] is the
   * number of labels b of Applied[v] with c in Compatible(d, b). Applied[v] holds Domain(v) and
   * the labels removed from v since its counts were last brought down. Every label c at u has a
   * non-zero count along each pair whose source has been revised once (Fresh[v] = 0): so
   * bringing the counts down by Applied[v] − Domain(v) finds exactly the labels at u without
   * support in Domain(v). A pair's counts are set up when its source first revises by removals
   * (Ready; untouched memory until then). Undo puts Applied back and lists the labels to count
   * again (Stale), done before the next Propagate's drain (Recount).
   */
  struct SupportState
  {
    bool On = false;
    const CompatibilityRelation* Rules = nullptr;
    std::size_t Classes = 0;
    std::vector<std::uint8_t> Countable; ///< per direction class: counted
    std::vector<std::uint32_t> PairOf;   ///< [site][class]: the pair, or NoPair
    std::size_t Pairs = 0;
    /// [pair][label], 8 bits each when no count exceeds 255 (Narrow), else 16; allocated, not
    /// initialised.
    std::unique_ptr<std::uint8_t[]> Counts;
    bool Narrow = false;
    std::size_t Allocated = 0;          ///< bytes of Counts
    std::vector<std::uint8_t> Ready;    ///< per pair: its counts set up
    std::vector<std::uint64_t> Applied; ///< [site][word]
    std::vector<std::uint8_t> Fresh;    ///< per site: its neighbours not yet revised from it
    std::vector<std::uint64_t> Stale;   ///< [site][word]: labels to count again (after Undo)
    std::vector<std::int64_t> StaleSites;
    std::vector<std::uint64_t> Delta;   ///< the removals being applied (Words() words)
    std::vector<std::uint64_t> Removed; ///< labels losing their last support at one neighbour
    std::int64_t ByRemovals = 0;
  };
  static constexpr std::uint32_t NoPair = ~std::uint32_t(0);

  /**
   * Decides whether the sets allow support counts (k, the relation's lists, each site reached
   * along each class from one neighbour other than itself, and the memory) and numbers the
   * pairs; their counts are set up when first needed.
   */
  template <class ForEachNeighbour>
  void StartSupports(const CompatibilityRelation& rules, ForEachNeighbour& forEachNeighbour)
  {
    SupportState& sup = this->Sup;
    sup.On = false;
    sup.Narrow = rules.HasLists() && rules.MostSupports() <= 255;
    const std::int64_t n = this->NumberOfSites();
    if (!this->CountsAllowed || this->W == 1 || !rules.HasLists() ||
      rules.NumberOfLabels() != this->K || !this->SupportsFit(ToIndex(n)) ||
      ToIndex(n) * ToIndex(rules.Directions()) >= NoPair)
    {
      return;
    }
    // Which classes occur, and whether a site is reached along a class more than once.
    sup.Classes = ToIndex(rules.Directions());
    sup.PairOf.assign(ToIndex(n) * sup.Classes, NoPair);
    std::vector<std::int8_t> state(sup.Classes, 0); // 0 unused, 1 counted, -1 not countable
    bool selfLoop = false;
    for (std::int64_t v = 0; v < n && !selfLoop; ++v)
    {
      forEachNeighbour(v,
        [&](std::int64_t u, int d) -> bool
        {
          std::uint32_t& pair = sup.PairOf[ToIndex(u) * sup.Classes + ToIndex(d)];
          state[ToIndex(d)] = pair != NoPair || state[ToIndex(d)] < 0 ? -1 : 1;
          pair = 0;
          selfLoop = selfLoop || u == v;
          return true;
        });
    }
    if (!selfLoop && this->NumberPairs(state))
    {
      sup.Rules = &rules;
    }
  }
  /// Counts the Stale labels again at the neighbours of the sites Undo listed.
  template <class ForEachNeighbour>
  void Recount(const CompatibilityRelation& rules, ForEachNeighbour& forEachNeighbour)
  {
    for (const std::int64_t v : this->Sup.StaleSites)
    {
      std::uint64_t* stale = this->Sup.Stale.data() + ToIndex(v) * this->W;
      forEachNeighbour(v,
        [&](std::int64_t u, int d) -> bool
        {
          const std::uint32_t pair = this->PairOf(u, d);
          if (pair != NoPair && this->Sup.Ready[pair])
          {
            this->AddSupportsTo(rules, pair, d, stale);
          }
          return true;
        });
      std::fill(stale, stale + this->W, 0);
    }
    this->Sup.StaleSites.clear();
  }
  std::uint32_t PairOf(std::int64_t u, int d) const
  {
    return this->Sup.Countable[ToIndex(d)]
      ? this->Sup.PairOf[ToIndex(u) * this->Sup.Classes + ToIndex(d)]
      : NoPair;
  }
  template <typename Tally>
  Tally* CountsOf(std::uint32_t pair) const
  {
    return reinterpret_cast<Tally*>(this->Sup.Counts.get()) + std::size_t(pair) * ToIndex(this->K);
  }
  /// Whether counts for @p pairs pairs fit in the memory the counts may take.
  bool SupportsFit(std::size_t pairs) const;
  /// Numbers the pairs of the classes @p state marks counted (PairOf holds 0 for each pair
  /// found) and allocates their counts; false (counts off) when there are none or too many.
  bool NumberPairs(const std::vector<std::int8_t>& state);
  /// Sets @p counts (along class @p d) from the set @p source of the pair's source.
  template <typename Tally>
  void CountSupports(
    const CompatibilityRelation& rules, Tally* counts, int d, const std::uint64_t* source);
  /// Adds the supports of the labels @p labels to @p counts (along @p d).
  template <typename Tally>
  static void AddSupports(
    const CompatibilityRelation& rules, Tally* counts, int d, const std::uint64_t* labels);
  /// AddSupports to the counts of @p pair.
  void AddSupportsTo(
    const CompatibilityRelation& rules, std::uint32_t pair, int d, const std::uint64_t* labels);
  /// Before v revises its neighbours: true when by its removals (Sup.Delta, then Applied[v] =
  /// Domain(v)), false when by the union (also the first revision from v after Reset).
  bool BeginRevision(const CompatibilityRelation& rules, std::int64_t v);
  /// Brings the counts of @p pair (u along @p d from v) down by Sup.Delta, first setting them
  /// up from Domain(v) if not yet; removes the labels of u left without support (unless a set
  /// is already empty).
  void RemoveUnsupported(
    const CompatibilityRelation& rules, std::int64_t v, std::int64_t u, int d, std::uint32_t pair);
  /// RemoveUnsupported's counting: true when labels of u go (those of Sup.Removed).
  template <typename Tally>
  bool FindUnsupported(
    const CompatibilityRelation& rules, std::int64_t v, std::int64_t u, int d, std::uint32_t pair);
  /// Undo of a record of Applied and Fresh (site with the top bit set, Fresh, the old Applied).
  void UndoApplied(std::int64_t site, bool fresh, const std::uint64_t* applied);
  /// The labels of @p site to count again (Words() words), listing the site in StaleSites.
  std::uint64_t* StaleOf(std::int64_t site);
  /// Trail entry of Applied[site] and Fresh[site] before a revision changes them.
  void RecordApplied(std::int64_t site);

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
  SupportState Sup;
  bool CountsAllowed = true;
};

} // namespace msynth
