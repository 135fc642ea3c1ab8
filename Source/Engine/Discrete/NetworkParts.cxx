// SPDX-License-Identifier: BSD-3-Clause
#include "Discrete/NetworkParts.h"

#include "Core/Error.h"
#include "Core/Index.h"

#include <algorithm>
#include <limits>

namespace msynth
{
namespace detail
{
namespace
{
Coord At(std::int64_t s, const Coord& n)
{
  return Coord{ { s % n[0], (s / n[0]) % n[1], s / (n[0] * n[1]) } };
}

void Include(Coord& low, Coord& high, const Coord& p)
{
  for (std::size_t a = 0; a < 3; ++a)
  {
    low[a] = std::min(low[a], p[a]);
    high[a] = std::max(high[a], p[a]);
  }
}

std::int64_t SetRoot(std::vector<std::int64_t>& parent, std::int64_t i)
{
  while (parent[ToIndex(i)] != i)
  {
    parent[ToIndex(i)] = parent[ToIndex(parent[ToIndex(i)])];
    i = parent[ToIndex(i)];
  }
  return i;
}

void Unite(std::vector<std::int64_t>& parent, std::int64_t a, std::int64_t b)
{
  a = SetRoot(parent, a);
  b = SetRoot(parent, b);
  if (a != b)
    parent[ToIndex(std::max(a, b))] = std::min(a, b);
}
} // namespace

NetworkParts::NetworkParts(const NetworkRule& rule, const std::vector<std::int32_t>& model,
  const Coord& n, const std::vector<std::int64_t>& pathSites)
  : Rule(rule)
  , Model(model)
  , N(n)
{
  const std::size_t total = ToIndex(n[0] * n[1] * n[2]);
  this->Listed.assign(total, 0);
  for (std::int64_t s : pathSites)
    this->Listed[ToIndex(s)] = 1;
  this->Comps = FindComponents(rule, model, n, &this->Id);
  this->Path.assign(this->Comps.size(), 0);
  for (std::size_t s = 0; s < total; ++s)
  {
    const std::int32_t b = model[s];
    this->PathLabels += this->IsPathLabel(b) ? 1 : 0;
    if (this->Id[s] != 0)
      this->Path[ToIndex(this->Id[s] - 1)] +=
        this->HoldsPathAt(static_cast<std::int64_t>(s), b) ? 1 : 0;
    else
      this->Outside += this->Listed[s];
  }
  for (std::size_t c = 0; c < this->Comps.size(); ++c)
  {
    this->Order.emplace(this->Comps[c].Sites, static_cast<std::int32_t>(c));
    this->PathComps += this->Path[c] > 0 ? 1 : 0;
  }
  this->Live = static_cast<std::int64_t>(this->Comps.size());
  this->Seen.assign(total, 0);
  this->SeenFlood.assign(total, 0);
  this->Relabeled.assign(total, 0);
}

bool NetworkParts::HoldsPathAt(std::int64_t s, std::int32_t label) const
{
  return label >= 0 && (this->IsPathLabel(label) || this->Listed[ToIndex(s)]);
}

bool NetworkParts::InBox(std::int64_t s) const
{
  const Coord p = At(s, this->N);
  for (std::size_t a = 0; a < 3; ++a)
    if (p[a] < this->Box.Origin[a] || p[a] >= this->BoxHigh[a])
      return false;
  return true;
}

std::int64_t NetworkParts::LocalOf(std::int64_t s) const
{
  const Coord p = At(s, this->N);
  const Coord& o = this->Box.Origin;
  return (p[0] - o[0]) + this->Box.Dims[0] * ((p[1] - o[1]) + this->Box.Dims[1] * (p[2] - o[2]));
}

bool NetworkParts::Linked(std::int64_t s, int d, std::int64_t& q) const
{
  const int sides = this->Rule.Sides(this->Model[ToIndex(s)]);
  const std::size_t a = ToIndex(d / 2);
  const std::int64_t stride[3] = { 1, this->N[0], this->N[0] * this->N[1] };
  const std::int64_t along = (s / stride[a]) % this->N[a];
  if (sides < 0 || !((sides >> d) & 1) || (d % 2 == 0 ? along + 1 >= this->N[a] : along == 0))
    return false;
  q = s + (d % 2 == 0 ? stride[a] : -stride[a]);
  const int other = this->Rule.Sides(this->Model[ToIndex(q)]);
  return other >= 0 && ((other >> (d ^ 1)) & 1);
}

std::int32_t NetworkParts::Root(std::int32_t f)
{
  while (this->FloodParent[ToIndex(f)] != f)
  {
    this->FloodParent[ToIndex(f)] = this->FloodParent[ToIndex(this->FloodParent[ToIndex(f)])];
    f = this->FloodParent[ToIndex(f)];
  }
  return f;
}

NetworkParts::Near* NetworkParts::Find(std::int32_t slot)
{
  const auto it = std::lower_bound(this->Nears.begin(), this->Nears.end(), slot,
    [](const Near& near, std::int32_t s) { return near.Slot < s; });
  if (it == this->Nears.end() || it->Slot != slot)
    throw Error("internal: a network site next to a repaired box belongs to no component");
  return &*it;
}

int NetworkParts::PieceOf(std::int64_t s)
{
  const Near* near = this->Find(this->Id[ToIndex(s)] - 1);
  if (near->Whole >= 0)
    return near->Whole;
  if (this->Seen[ToIndex(s)] == this->Call)
    return this->FloodPiece[ToIndex(this->Root(this->SeenFlood[ToIndex(s)]))];
  if (near->Rest < 0)
    throw Error("internal: a piece of a network component outside a repaired box was lost");
  return near->Rest;
}

void NetworkParts::Split(Near& near)
{
  // Every piece holds a ring site that was linked into the box. Such sites that the box's new
  // network joins start one flood together (they end in one component whatever lies outside);
  // the floods run in turn one site at a time, and floods that meet join. Stops when at most one
  // flood is still running: the finished ones are whole pieces, the last one is the rest of the
  // component (counted by difference, not walked). When the box joins them all, nothing is walked.
  const auto first = static_cast<std::int32_t>(this->Floods.size());
  std::int64_t active = this->StartFloods(near);
  const auto end = static_cast<std::int32_t>(this->Floods.size());
  if (this->RunFloods(first, end, active))
    this->TakePieces(near, first, end);
}

std::int64_t NetworkParts::StartFloods(const Near& near)
{
  std::int64_t active = 0;
  std::vector<std::pair<std::int64_t, std::int32_t>> byGroup; // (box group, flood)
  for (const auto& [r, inside] : near.Ring)
  {
    if (this->Seen[ToIndex(r)] == this->Call)
      continue;
    std::int64_t group = -1;
    for (int d = 0; d < 6 && group < 0; ++d)
    {
      std::int64_t q = 0;
      if (this->Linked(r, d, q) && q == inside)
        group = SetRoot(this->BoxJoin, this->LocalOf(q));
    }
    std::int32_t f = -1;
    for (const auto& [g, h] : byGroup)
      if (group >= 0 && g == group)
        f = h;
    if (f < 0)
    {
      f = static_cast<std::int32_t>(this->Floods.size());
      Flood flood;
      flood.Low = flood.High = At(r, this->N);
      this->Floods.push_back(std::move(flood));
      this->FloodParent.push_back(f);
      byGroup.emplace_back(group, f);
      ++active;
    }
    Flood& flood = this->Floods[ToIndex(f)];
    flood.Members.push_back(r);
    flood.Pending.push_back(r);
    flood.PathSites += this->HoldsPathAt(r, this->Model[ToIndex(r)]) ? 1 : 0;
    Include(flood.Low, flood.High, At(r, this->N));
    this->Seen[ToIndex(r)] = this->Call;
    this->SeenFlood[ToIndex(r)] = f;
  }
  return active;
}

bool NetworkParts::RunFloods(std::int32_t first, std::int32_t end, std::int64_t active)
{
  while (active > 1)
    for (std::int32_t f = first; f < end && active > 1; ++f)
    {
      Flood& flood = this->Floods[ToIndex(f)];
      if (this->FloodParent[ToIndex(f)] != f || flood.Finished)
        continue;
      if (flood.Pending.empty())
      {
        flood.Finished = true;
        --active;
        continue;
      }
      if (--this->Budget < 0)
        return false; // too far to tell: Propose reports no gain
      const std::int64_t s = flood.Pending.back();
      flood.Pending.pop_back();
      for (int d = 0; d < 6; ++d)
      {
        std::int64_t q = 0;
        if (!this->Linked(s, d, q) || this->InBox(q))
          continue;
        if (this->Seen[ToIndex(q)] != this->Call)
        {
          this->Seen[ToIndex(q)] = this->Call;
          this->SeenFlood[ToIndex(q)] = f;
          flood.Members.push_back(q);
          flood.Pending.push_back(q);
          flood.PathSites += this->HoldsPathAt(q, this->Model[ToIndex(q)]) ? 1 : 0;
          Include(flood.Low, flood.High, At(q, this->N));
          continue;
        }
        const std::int32_t g = this->Root(this->SeenFlood[ToIndex(q)]);
        if (g == f)
          continue;
        Flood& other = this->Floods[ToIndex(g)]; // met another flood: one piece
        if (other.Members.size() > flood.Members.size())
          flood.Members.swap(other.Members);
        flood.Members.insert(flood.Members.end(), other.Members.begin(), other.Members.end());
        if (other.Pending.size() > flood.Pending.size())
          flood.Pending.swap(other.Pending);
        flood.Pending.insert(flood.Pending.end(), other.Pending.begin(), other.Pending.end());
        flood.PathSites += other.PathSites;
        Include(flood.Low, flood.High, other.Low);
        Include(flood.Low, flood.High, other.High);
        active -= other.Finished ? 0 : 1;
        other = Flood();
        this->FloodParent[ToIndex(g)] = f;
      }
    }
  return true;
}

void NetworkParts::TakePieces(Near& near, std::int32_t first, std::int32_t end)
{
  std::int64_t sites = 0, path = 0;
  std::int32_t rest = -1;
  for (std::int32_t f = first; f < end; ++f)
  {
    if (this->FloodParent[ToIndex(f)] != f)
      continue;
    Flood& flood = this->Floods[ToIndex(f)];
    if (!flood.Finished && rest < 0)
    {
      rest = f;
      continue;
    }
    Piece piece;
    piece.Slot = near.Slot;
    piece.Sites = static_cast<std::int64_t>(flood.Members.size());
    piece.PathSites = flood.PathSites;
    piece.Low = flood.Low;
    piece.High = flood.High;
    piece.Listed = true;
    piece.Members = std::move(flood.Members);
    sites += piece.Sites;
    path += piece.PathSites;
    this->FloodPiece[ToIndex(f)] = static_cast<std::int32_t>(this->Pieces.size());
    this->Pieces.push_back(std::move(piece));
  }
  const Component& old = this->Comps[ToIndex(near.Slot)];
  if (rest >= 0)
  {
    Piece piece;
    piece.Slot = near.Slot;
    piece.Sites = old.Sites - near.InBox - sites;
    piece.PathSites = this->Path[ToIndex(near.Slot)] - near.PathInBox - path;
    piece.Low = old.Low; // the component's box: it holds the rest
    piece.High = old.High;
    // Its flood's sites: it may be several pieces the box joins, each with a site among them.
    piece.Members = std::move(this->Floods[ToIndex(rest)].Members);
    near.Rest = static_cast<int>(this->Pieces.size());
    this->FloodPiece[ToIndex(rest)] = near.Rest;
    this->Pieces.push_back(std::move(piece));
  }
}

void NetworkParts::Touch(const Block& box, const std::vector<std::int32_t>& before, Outcome& next)
{
  // The components with a site in the box or next to it, and the box's labels before and after.
  const Coord& n = this->N;
  struct Touch
  {
    std::int32_t Slot;
    std::int64_t Site, Inside; ///< a ring site and its box neighbour; -1: a box site
    bool Path;                 ///< a box site holding a path site before
    bool operator<(const Touch& o) const
    {
      return this->Slot != o.Slot ? this->Slot < o.Slot : this->Site < o.Site;
    }
  };
  std::vector<Touch> touched;
  std::size_t i = 0;
  ForEachSite(box, n,
    [&](std::size_t site)
    {
      const auto s = static_cast<std::int64_t>(site);
      const std::int32_t was = before[i++], now = this->Model[site];
      this->BoxSites.push_back(s);
      next.PathLabelSites += (this->IsPathLabel(now) ? 1 : 0) - (this->IsPathLabel(was) ? 1 : 0);
      if (this->Listed[site])
        next.PathSitesOutside +=
          (this->Rule.Sides(now) < 0 ? 1 : 0) - (this->Id[site] == 0 ? 1 : 0);
      if (this->Id[site] != 0)
        touched.push_back({ this->Id[site] - 1, -1, -1, this->HoldsPathAt(s, was) });
    });
  ForEachRingSite(box, n,
    [&](std::int64_t s, int toward, std::int64_t t)
    {
      if (this->Id[ToIndex(s)] == 0)
        return; // not a network site
      const int was = this->Rule.Sides(before[ToIndex(this->LocalOf(t))]);
      const bool linked = ((this->Rule.Sides(this->Model[ToIndex(s)]) >> toward) & 1) && was >= 0 &&
        ((was >> (toward ^ 1)) & 1);
      touched.push_back({ this->Id[ToIndex(s)] - 1, s, linked ? t : -2, false });
    });
  std::sort(touched.begin(), touched.end());
  for (const Touch& touch : touched)
  {
    if (this->Nears.empty() || this->Nears.back().Slot != touch.Slot)
    {
      this->Nears.emplace_back();
      this->Nears.back().Slot = touch.Slot;
    }
    Near& near = this->Nears.back();
    if (touch.Site < 0)
    {
      ++near.InBox;
      near.PathInBox += touch.Path ? 1 : 0;
    }
    else if (touch.Inside >= 0)
      near.Ring.emplace_back(touch.Site, touch.Inside); // a piece may start here
    else if (near.Any < 0)
      near.Any = touch.Site;
  }
}

NetworkParts::Outcome NetworkParts::Propose(
  const Block& box, const std::vector<std::int32_t>& before)
{
  if (++this->Call == 0) // wrapped: forget every stamp
  {
    std::fill(this->Seen.begin(), this->Seen.end(), 0);
    std::fill(this->Relabeled.begin(), this->Relabeled.end(), 0);
    this->Call = 1;
  }
  this->Box = box;
  for (std::size_t a = 0; a < 3; ++a)
    this->BoxHigh[a] = box.Origin[a] + box.Dims[a];
  this->Nears.clear();
  this->Pieces.clear();
  this->Floods.clear();
  this->FloodParent.clear();
  this->BoxSites.clear();
  this->Budget = VisitsPerBoxSite * box.Dims[0] * box.Dims[1] * box.Dims[2] + Visits;
  Outcome next{ this->Outside, this->PathComps, this->Live, this->PathLabels };

  this->Touch(box, before, next);

  // The box's new network, joined within the box.
  this->BoxJoin.resize(this->BoxSites.size());
  for (std::size_t j = 0; j < this->BoxSites.size(); ++j)
    this->BoxJoin[j] = static_cast<std::int64_t>(j);
  for (std::size_t j = 0; j < this->BoxSites.size(); ++j)
    for (int d = 0; d < 6; d += 2) // each pair once: toward +x, +y, +z
    {
      std::int64_t q = 0;
      if (this->Linked(this->BoxSites[j], d, q) && this->InBox(q))
        Unite(this->BoxJoin, static_cast<std::int64_t>(j), this->LocalOf(q));
    }

  // Their pieces outside the box.
  this->FloodPiece.clear();
  for (Near& near : this->Nears)
  {
    if (near.InBox == 0)
    {
      const Component& c = this->Comps[ToIndex(near.Slot)];
      Piece piece;
      piece.Slot = near.Slot;
      piece.Sites = c.Sites;
      piece.PathSites = this->Path[ToIndex(near.Slot)];
      piece.Low = c.Low;
      piece.High = c.High;
      piece.Members.assign(1, near.Any); // one component: one seed reaches it all
      near.Whole = static_cast<int>(this->Pieces.size());
      this->Pieces.push_back(std::move(piece));
      continue;
    }
    if (near.Ring.empty() && this->Comps[ToIndex(near.Slot)].Sites != near.InBox)
      throw Error("internal: a network component in a repaired box has no way out of it");
    this->FloodPiece.resize(this->Floods.size() + near.Ring.size(), -1);
    this->Split(near);
    if (this->Budget < 0)
    {
      next.Components = std::numeric_limits<std::int64_t>::max();
      this->Next = next;
      return next;
    }
  }

  this->Join(next);
  this->Next = next;
  return next;
}

void NetworkParts::Join(Outcome& next)
{
  // Joined through the box's network sites.
  const auto pieces = static_cast<std::int64_t>(this->Pieces.size());
  this->Joined.resize(ToIndex(pieces) + this->BoxSites.size());
  for (std::size_t j = 0; j < this->Joined.size(); ++j)
    this->Joined[j] = static_cast<std::int64_t>(j);
  for (std::size_t j = 0; j < this->BoxSites.size(); ++j)
  {
    const std::int64_t s = this->BoxSites[j];
    for (int d = 0; d < 6; ++d)
    {
      std::int64_t q = 0;
      if (!this->Linked(s, d, q))
        continue;
      if (this->InBox(q))
        Unite(this->Joined, pieces + static_cast<std::int64_t>(j), pieces + this->LocalOf(q));
      else
        Unite(this->Joined, pieces + static_cast<std::int64_t>(j), this->PieceOf(q));
    }
  }
  std::vector<std::int64_t> setPath(this->Joined.size(), -1);
  std::int64_t sets = 0, pathSets = 0;
  auto add = [&](std::int64_t node, std::int64_t path)
  {
    std::int64_t& p = setPath[ToIndex(SetRoot(this->Joined, node))];
    sets += p < 0 ? 1 : 0;
    pathSets += p <= 0 && path > 0 ? 1 : 0;
    p = std::max<std::int64_t>(p, 0) + path;
  };
  for (std::int64_t k = 0; k < pieces; ++k)
    add(k, this->Pieces[ToIndex(k)].PathSites);
  for (std::size_t j = 0; j < this->BoxSites.size(); ++j)
  {
    const std::int64_t s = this->BoxSites[j];
    if (this->Rule.Sides(this->Model[ToIndex(s)]) >= 0)
      add(pieces + static_cast<std::int64_t>(j), this->HoldsPathAt(s, this->Model[ToIndex(s)]));
  }
  for (const Near& near : this->Nears)
    next.PathParts -= this->Path[ToIndex(near.Slot)] > 0 ? 1 : 0;
  next.PathParts += pathSets;
  next.Components += sets - static_cast<std::int64_t>(this->Nears.size());
}

void NetworkParts::Members(Piece& piece)
{
  if (piece.Listed)
    return;
  // A flood over the piece: the sites outside the box linked to its seeds (in Members).
  for (std::int64_t s : piece.Members)
    this->Relabeled[ToIndex(s)] = this->Call;
  for (std::size_t k = 0; k < piece.Members.size(); ++k)
    for (int d = 0; d < 6; ++d)
    {
      std::int64_t q = 0;
      if (this->Linked(piece.Members[k], d, q) && !this->InBox(q) &&
        this->Relabeled[ToIndex(q)] != this->Call)
      {
        this->Relabeled[ToIndex(q)] = this->Call;
        piece.Members.push_back(q);
      }
    }
  piece.Listed = true;
}

std::vector<std::int32_t> NetworkParts::Keepers(
  const std::vector<Set>& sets, std::vector<std::int32_t>& claimed) const
{
  const auto pieces = static_cast<std::int64_t>(this->Pieces.size());
  // Each new component keeps the number of one of its pieces, the largest pieces first (so the
  // rest of a large component keeps its number), and its other sites are listed (relabelled after
  // all are listed: listing reads the old numbers).
  std::vector<std::int64_t> bySize(ToIndex(pieces)), setOfPiece(ToIndex(pieces));
  for (std::size_t k = 0; k < sets.size(); ++k)
    for (std::int64_t piece : sets[k].Pieces)
      setOfPiece[ToIndex(piece)] = static_cast<std::int64_t>(k);
  for (std::int64_t k = 0; k < pieces; ++k)
    bySize[ToIndex(k)] = k;
  std::stable_sort(bySize.begin(), bySize.end(),
    [&](std::int64_t a, std::int64_t b)
    { return this->Pieces[ToIndex(a)].Sites > this->Pieces[ToIndex(b)].Sites; });
  std::vector<std::int32_t> keeps(sets.size(), -1);
  for (std::int64_t k : bySize)
  {
    const std::int32_t slot = this->Pieces[ToIndex(k)].Slot;
    std::int32_t& keep = keeps[ToIndex(setOfPiece[ToIndex(k)])];
    if (keep < 0 && std::find(claimed.begin(), claimed.end(), slot) == claimed.end())
    {
      keep = slot;
      claimed.push_back(slot);
    }
  }
  return keeps;
}

void NetworkParts::Apply()
{
  const Coord& n = this->N;
  const auto pieces = static_cast<std::int64_t>(this->Pieces.size());
  // The new components: pieces and box sites by their root.
  std::vector<std::int64_t> setOf(this->Joined.size(), -1);
  std::vector<Set> sets;
  auto setFor = [&](std::int64_t node) -> Set&
  {
    std::int64_t& k = setOf[ToIndex(SetRoot(this->Joined, node))];
    if (k < 0)
    {
      k = static_cast<std::int64_t>(sets.size());
      sets.emplace_back();
    }
    return sets[ToIndex(k)];
  };
  for (std::int64_t k = 0; k < pieces; ++k)
    setFor(k).Pieces.push_back(k);
  for (std::size_t j = 0; j < this->BoxSites.size(); ++j)
    if (this->Rule.Sides(this->Model[ToIndex(this->BoxSites[j])]) >= 0)
      setFor(pieces + static_cast<std::int64_t>(j)).Sites.push_back(this->BoxSites[j]);

  for (const Near& near : this->Nears)
  {
    const Component& c = this->Comps[ToIndex(near.Slot)];
    this->Order.erase({ c.Sites, near.Slot });
    this->PathComps -= this->Path[ToIndex(near.Slot)] > 0 ? 1 : 0;
    --this->Live;
  }
  std::vector<std::int32_t> claimed;
  const std::vector<std::int32_t> keeps = this->Keepers(sets, claimed);
  std::vector<std::pair<std::int64_t, std::int32_t>> relabel;
  std::vector<std::pair<std::int32_t, Component>> made;
  std::vector<std::int64_t> madePath;
  for (std::size_t i = 0; i < sets.size(); ++i)
  {
    Set& set = sets[i];
    std::int32_t keep = keeps[i];
    if (keep < 0)
    {
      keep = static_cast<std::int32_t>(this->Comps.size());
      this->Comps.emplace_back();
      this->Path.push_back(0);
    }
    Component c;
    c.Sites = static_cast<std::int64_t>(set.Sites.size());
    c.Low.fill(std::numeric_limits<std::int64_t>::max());
    c.High.fill(-1);
    std::int64_t path = 0;
    for (std::int64_t k : set.Pieces)
    {
      Piece& piece = this->Pieces[ToIndex(k)];
      c.Sites += piece.Sites;
      path += piece.PathSites;
      Include(c.Low, c.High, piece.Low);
      Include(c.Low, c.High, piece.High);
      if (piece.Slot == keep)
        continue; // its sites have the number already
      this->Members(piece);
      for (std::int64_t s : piece.Members)
        relabel.emplace_back(s, keep);
    }
    for (std::int64_t s : set.Sites)
    {
      Include(c.Low, c.High, At(s, n));
      path += this->HoldsPathAt(s, this->Model[ToIndex(s)]) ? 1 : 0;
    }
    made.emplace_back(keep, c);
    madePath.push_back(path);
  }
  for (const Near& near : this->Nears)
    if (std::find(claimed.begin(), claimed.end(), near.Slot) == claimed.end())
    {
      this->Comps[ToIndex(near.Slot)].Sites = 0; // gone
      this->Path[ToIndex(near.Slot)] = 0;
    }
  for (const std::int64_t s : this->BoxSites)
    this->Id[ToIndex(s)] = 0;
  for (std::size_t k = 0; k < sets.size(); ++k)
  {
    const std::int32_t slot = made[k].first;
    for (std::int64_t s : sets[k].Sites)
      this->Id[ToIndex(s)] = slot + 1;
    this->Comps[ToIndex(slot)] = made[k].second;
    this->Path[ToIndex(slot)] = madePath[k];
    this->Order.emplace(made[k].second.Sites, slot);
    this->PathComps += madePath[k] > 0 ? 1 : 0;
    ++this->Live;
  }
  for (const auto& [s, slot] : relabel)
    this->Id[ToIndex(s)] = slot + 1;
  this->Outside = this->Next.PathSitesOutside;
  this->PathLabels = this->Next.PathLabelSites;
}

} // namespace detail
} // namespace msynth
