// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/**
 * @file NetworkParts.h
 * @brief The components of a connected network kept up to date while boxes of the model are
 * synthesized again (internal to Discrete/NetworkRepair.cxx).
 *
 * A repair rewrites one box B. Only the components with a site in B or next to it (the ring)
 * can change: each of those with a site in B falls into pieces outside B, found by floods from
 * its ring sites run in turn one site at a time until all but one have finished (so the work is
 * that of the smaller pieces, not of the component); the pieces and B's new network sites are
 * then joined through B. Accepting a change relabels every new component but its largest piece
 * (small into large). So a repair costs about its box and the small pieces around it, not a
 * flood of the whole model, and a run's repairs stay linear in the model.
 */
#include "Discrete/Connectivity.h"
#include "Discrete/NetworkComponents.h"

#include <cstdint>
#include <set>
#include <utility>
#include <vector>

namespace msynth
{
namespace detail
{

class NetworkParts
{
public:
  /// The components of @p model (@p n sites); @p pathSites: the listed path sites' indices.
  NetworkParts(const NetworkRule& rule, const std::vector<std::int32_t>& model, const Coord& n,
    const std::vector<std::int64_t>& pathSites);

  /// The components by number (Sites == 0: gone); bounding boxes may be larger than the
  /// component where it lost sites.
  const std::vector<Component>& Parts() const { return this->Comps; }
  /// Per site, its component's number + 1 (0: not in the network).
  const std::vector<std::int32_t>& Ids() const { return this->Id; }
  /// The components, smallest first (ties by number): (sites, number).
  const std::set<std::pair<std::int64_t, std::int32_t>>& BySize() const { return this->Order; }
  std::int64_t Count() const { return this->Live; }
  /// Whether component @p c holds a listed path site or a site of a path label.
  bool HoldsPath(std::int32_t c) const { return this->Path[ToIndex(c)] > 0; }
  /// Listed path sites outside the network.
  std::int64_t PathSitesOutside() const { return this->Outside; }
  /// Components holding path sites.
  std::int64_t PathParts() const { return this->PathComps; }
  /// Sites holding path labels.
  std::int64_t PathLabelSites() const { return this->PathLabels; }

  /// What a change of the box would give (Propose).
  struct Outcome
  {
    std::int64_t PathSitesOutside = 0, PathParts = 0, Components = 0, PathLabelSites = 0;
  };
  /**
   * The components if the model's box @p box now holds what it holds (its labels before are
   * @p before, in ForEachSite order). Apply() then makes it so; nothing changes otherwise.
   */
  Outcome Propose(const Block& box, const std::vector<std::int32_t>& before);
  /// Propose walks at most this many sites outside the box, plus VisitsPerBoxSite per box site;
  /// past that it reports the change as no gain (Components: the largest number): the pieces it
  /// could not tell apart lie far around, and a repair that splits a component does not help.
  static constexpr std::int64_t Visits = 256, VisitsPerBoxSite = 4;
  /// Takes the last Propose()'s components.
  void Apply();

private:
  /// A part of an old component outside the box (or all of it).
  struct Piece
  {
    std::int32_t Slot = 0;
    std::int64_t Sites = 0, PathSites = 0;
    Coord Low{ { 0, 0, 0 } }, High{ { 0, 0, 0 } };
    bool Listed = false; ///< Members holds all its sites (else sites a flood of it starts from)
    std::vector<std::int64_t> Members;
  };
  /// What Propose learnt of an old component near the box.
  struct Near
  {
    std::int32_t Slot = 0;
    std::int64_t InBox = 0, PathInBox = 0;
    /// Its sites next to the box that were linked into it, with their box neighbours.
    std::vector<std::pair<std::int64_t, std::int64_t>> Ring;
    std::int64_t Any = -1;     ///< one of its sites next to the box
    int Whole = -1, Rest = -1; ///< its piece when it has no site in the box; its unfinished
  };
  /// One flood of Split.
  struct Flood
  {
    std::vector<std::int64_t> Members, Pending;
    std::int64_t PathSites = 0;
    Coord Low, High;
    bool Finished = false;
  };

  /// A new component: its pieces and its box sites.
  struct Set
  {
    std::vector<std::int64_t> Pieces, Sites;
  };

  /// Propose's first step: the components near the box (Nears) and the box's path figures.
  void Touch(const Block& box, const std::vector<std::int32_t>& before, Outcome& next);
  /// Propose's last step: the pieces and the box's sites joined, the figures counted.
  void Join(Outcome& next);
  /// Split's floods: started (returns how many), run (false past the budget), taken as pieces.
  std::int64_t StartFloods(const Near& near);
  bool RunFloods(std::int32_t first, std::int32_t end, std::int64_t active);
  void TakePieces(Near& near, std::int32_t first, std::int32_t end);
  /// Apply's numbers for @p sets (-1: a new one), the old numbers they keep in @p claimed.
  std::vector<std::int32_t> Keepers(
    const std::vector<Set>& sets, std::vector<std::int32_t>& claimed) const;
  bool InBox(std::int64_t s) const;
  /// The index of box site @p s in the box (ForEachSite order).
  std::int64_t LocalOf(std::int64_t s) const;
  bool Linked(std::int64_t s, int d, std::int64_t& q) const;
  bool HoldsPathAt(std::int64_t s, std::int32_t label) const;
  bool IsPathLabel(std::int32_t label) const { return label >= 0 && this->Rule.OnPath(label); }
  Near* Find(std::int32_t slot);
  int PieceOf(std::int64_t s);
  void Split(Near& near);
  void Members(Piece& piece);
  std::int32_t Root(std::int32_t f);

  const NetworkRule& Rule;
  const std::vector<std::int32_t>& Model;
  Coord N;
  std::vector<char> Listed;
  std::vector<Component> Comps;
  std::vector<std::int64_t> Path; ///< per component, its path sites
  std::vector<std::int32_t> Id;
  std::set<std::pair<std::int64_t, std::int32_t>> Order;
  std::int64_t Live = 0, Outside = 0, PathComps = 0, PathLabels = 0;

  // Propose's state, which Apply reads.
  Block Box;
  Coord BoxHigh{ { 0, 0, 0 } };
  std::vector<Near> Nears;
  std::vector<Piece> Pieces;
  std::vector<Flood> Floods;
  std::vector<std::int32_t> FloodParent, FloodPiece;
  std::vector<std::int64_t> BoxJoin; ///< union-find over the box's sites
  std::vector<std::int64_t> Joined;  ///< union-find over pieces, then the box's network sites
  std::vector<std::int64_t> BoxSites;
  Outcome Next;
  std::vector<std::uint32_t> Seen;      ///< per site: the Propose that flooded it last
  std::vector<std::int32_t> SeenFlood;  ///< and which of its floods
  std::vector<std::uint32_t> Relabeled; ///< per site: the Apply that listed it last
  std::uint32_t Call = 0;
  std::int64_t Budget = 0; ///< sites Split may still walk
};

} // namespace detail
} // namespace msynth
