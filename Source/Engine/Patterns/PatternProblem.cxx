// SPDX-License-Identifier: BSD-3-Clause
#include "Patterns/PatternProblem.h"

#include "Core/Error.h"
#include "Core/Index.h"

#include <algorithm>
#include <climits>
#include <cstdint>
#include <map>

namespace msynth
{
namespace detail
{

namespace
{

std::int32_t MirrorTile(const FactorModel& m, const PatternOptions& o, std::int32_t t)
{
  const auto it = o.MirrorMap.find(m.Tiles[ToIndex(t)]);
  return it == o.MirrorMap.end() ? t : m.TileIndex(it->second);
}

/// Per zone listed in ZoneTiles, which of the model's tiles it allows (zoning, §4).
/// @throw Error when a zone allows a label no exemplar holds.
std::map<std::int32_t, std::vector<std::uint8_t>> ZoneMasks(
  const FactorModel& model, const PatternOptions& options)
{
  std::map<std::int32_t, std::vector<std::uint8_t>> zoneMask;
  for (const auto& [zone, values] : options.ZoneTiles)
  {
    std::vector<std::uint8_t> mask(ToIndex(model.NumberOfTiles()), 0);
    for (Label v : values)
    {
      const int t = model.TileIndex(v);
      if (t < 0)
        throw Error("zone " + std::to_string(zone) + " allows label " + std::to_string(v) +
          ", which no exemplar holds");
      mask[ToIndex(t)] = 1;
    }
    zoneMask[zone] = std::move(mask);
  }
  return zoneMask;
}

/**
 * The tiles a site class allows (@p mask, and their list, returned): those that each image of
 * the site in @p key (zone or INT32_MIN, fixed tile or -1, mirror parity; after the seam bits
 * at key[0]) meets, mapped, and that can meet their mirror image across the seams of @p seam
 * (bit a: an even-sized mirrored axis a; bit 3 + a: an odd one, whose middle maps to itself).
 * @throw Error naming the site at @p c when no tile is left.
 */
std::vector<std::int32_t> ClassTilesOf(const FactorModel& model, const PatternOptions& options,
  const std::map<std::int32_t, std::vector<std::uint8_t>>& zoneMask,
  const std::vector<std::int32_t>& key, int seam, const std::array<std::int64_t, 3>& c,
  std::vector<std::uint8_t>& mask)
{
  const std::int32_t T = model.NumberOfTiles();
  mask.assign(ToIndex(T), 1);
  bool fixedAndZoned = false;
  for (std::size_t i = 1; i < key.size(); i += 3)
  {
    const std::int32_t zone = key[i], fixed = key[i + 1];
    fixedAndZoned = fixedAndZoned || (fixed >= 0 && zone != INT32_MIN);
    for (std::int32_t t = 0; t < T; ++t)
    {
      const std::int32_t image = key[i + 2] ? MirrorTile(model, options, t) : t;
      if ((zone != INT32_MIN && !zoneMask.at(zone)[ToIndex(image)]) ||
        (fixed >= 0 && image != fixed))
        mask[ToIndex(t)] = 0;
    }
  }
  for (std::int32_t t = 0; t < T; ++t)
    for (int a = 0; a < 3; ++a)
    {
      const std::int32_t f = MirrorTile(model, options, t);
      if ((seam & (1 << a)) && !model.Allowed(a, t, f))
        mask[ToIndex(t)] = 0;
      if ((seam & (8 << a)) && f != t)
        mask[ToIndex(t)] = 0;
    }
  std::vector<std::int32_t> tiles;
  for (std::int32_t t = 0; t < T; ++t)
    if (mask[ToIndex(t)])
      tiles.push_back(t);
  if (tiles.empty())
  {
    std::string where = "site (" + std::to_string(c[0]) + ", " + std::to_string(c[1]) + ", " +
      std::to_string(c[2]) + ")";
    if (fixedAndZoned)
      throw Error(where + " is fixed to a label that its zone does not allow");
    if (seam)
      throw Error(
        where + " is on the mirror seam and no tile it allows can meet its mirror image there");
    if (key.size() > 4)
      throw Error(where + " and its mirror images have zones or fixed labels no tile meets");
    throw Error("zone " + std::to_string(key[1]) + " allows no tile");
  }
  return tiles;
}

} // namespace

PatternProblem::PatternProblem(const FactorModel& model, const PatternOptions& options,
  const std::array<std::int64_t, 3>& size, bool seams)
  : Model(model)
  , Size(size)
{
  this->N = size[0] * size[1] * size[2];
  this->Stride = { { 1, size[0], size[0] * size[1] } };
  this->T = model.NumberOfTiles();
  this->Shapes = 3 + static_cast<int>(model.SoftShapes.size());
  const std::int64_t fullN = options.Size[0] * options.Size[1] * options.Size[2];
  if (!options.SiteZone.empty() && static_cast<std::int64_t>(options.SiteZone.size()) != fullN)
    throw Error("the zoning has " + std::to_string(options.SiteZone.size()) +
      " sites, the output " + std::to_string(fullN));
  if (!options.Fixed.empty() && static_cast<std::int64_t>(options.Fixed.size()) != fullN)
    throw Error("the fixed sites have " + std::to_string(options.Fixed.size()) +
      " sites, the output " + std::to_string(fullN));
  this->MarkFactors();
  this->BuildSiteClasses(options, seams);
  const std::vector<std::vector<int>> members = this->BuildSoftGroups(options);
  for (const auto& group : members)
  {
    std::vector<std::unordered_set<std::uint64_t>> perShape(model.SoftShapes.size());
    for (std::size_t k = 0; k < model.SoftShapes.size(); ++k)
      for (int e : group)
        perShape[k].insert(
          model.Observed[k][ToIndex(e)].begin(), model.Observed[k][ToIndex(e)].end());
    this->GroupObserved.push_back(std::move(perShape));
  }
}

void PatternProblem::MarkFactors()
{
  const FactorModel& model = this->Model;
  const auto& size = this->Size;
  this->Valid.assign(ToIndex(this->Shapes * this->N), 0);
  for (std::int64_t p = 0; p < this->N; ++p)
  {
    const auto c = this->Coordinates(p);
    for (int a = 0; a < 3; ++a)
      if (c[ToIndex(a)] + 1 < size[ToIndex(a)])
      {
        this->Valid[ToIndex(a * this->N + p)] = 1;
        ++this->HardCount;
      }
    for (std::size_t k = 0; k < model.SoftShapes.size(); ++k)
    {
      const auto& e = model.SoftShapes[k].Extent;
      if (c[0] + e[0] <= size[0] && c[1] + e[1] <= size[1] && c[2] + e[2] <= size[2])
      {
        this->Valid[ToIndex(static_cast<std::int64_t>(3 + k) * this->N + p)] = 1;
        ++this->SoftCount;
      }
    }
  }
  for (const Stencil& s : model.SoftShapes)
  {
    std::vector<std::int64_t> steps;
    for (const auto& o : s.Offsets)
      steps.push_back(o[0] + o[1] * this->Stride[1] + o[2] * this->Stride[2]);
    this->SoftSteps.push_back(std::move(steps));
  }
}

std::vector<std::vector<int>> PatternProblem::BuildSoftGroups(const PatternOptions& options)
{
  std::map<std::int32_t, std::int32_t> zoneGroup; // zone → group
  std::map<std::vector<int>, std::int32_t> groups;
  std::vector<std::vector<int>> groupMembers;
  auto groupOf = [&](std::vector<int> members)
  {
    const auto it = groups.find(members);
    if (it != groups.end())
      return it->second;
    const auto g = static_cast<std::int32_t>(groupMembers.size());
    groups.emplace(members, g);
    groupMembers.push_back(std::move(members));
    return g;
  };
  std::vector<int> all;
  for (int e = 0; e < this->Model.NumberOfExemplars; ++e)
    all.push_back(e);
  const std::int32_t allGroup = groupOf(all);
  for (const auto& [zone, members] : options.ZoneExemplars)
  {
    std::vector<int> sorted = members;
    std::sort(sorted.begin(), sorted.end());
    sorted.erase(std::unique(sorted.begin(), sorted.end()), sorted.end());
    for (int e : sorted)
      if (e < 0 || e >= this->Model.NumberOfExemplars)
        throw Error("zone " + std::to_string(zone) + " takes its factors from exemplar " +
          std::to_string(e + 1) + ", but there are " +
          std::to_string(this->Model.NumberOfExemplars));
    if (sorted.empty())
      throw Error("zone " + std::to_string(zone) + " takes its factors from no exemplar");
    zoneGroup[zone] = groupOf(sorted);
  }
  const auto& full = options.Size;
  this->SiteGroup.assign(ToIndex(this->N), allGroup);
  if (!options.SiteZone.empty() && !zoneGroup.empty())
    for (std::int64_t p = 0; p < this->N; ++p)
    {
      const auto c = this->Coordinates(p);
      const std::int64_t fp = c[0] + full[0] * (c[1] + full[1] * c[2]);
      const auto zg = zoneGroup.find(options.SiteZone[ToIndex(fp)]);
      if (zg != zoneGroup.end())
        this->SiteGroup[ToIndex(p)] = zg->second;
    }
  return groupMembers;
}

void PatternProblem::BuildSiteClasses(const PatternOptions& options, bool seams)
{
  const FactorModel& model = this->Model;
  const auto& size = this->Size;
  const auto& full = options.Size;
  const auto zoneMask = ZoneMasks(model, options);
  // A site's class: its seam, and the zone and fixed label of each of its images in the full
  // output (itself, and with mirroring its mirror images, whose tiles are its tiles mapped).
  std::map<std::vector<std::int32_t>, std::int32_t> classes;
  this->SiteClass.resize(ToIndex(this->N));
  std::vector<std::int32_t> key;
  for (std::int64_t p = 0; p < this->N; ++p)
  {
    const auto c = this->Coordinates(p);
    int seam = 0;
    int mirrored = 0; // bit a: axis a is mirrored
    if (seams)
      for (int a = 0; a < 3; ++a)
        if (options.Mirror[ToIndex(a)])
        {
          mirrored |= 1 << a;
          if (c[ToIndex(a)] == size[ToIndex(a)] - 1)
            seam |= (full[ToIndex(a)] % 2 == 0 ? 1 : 8) << a;
        }
    key.assign(1, seam);
    for (int flips = 0; flips < 8; ++flips)
    {
      if ((flips & ~mirrored) != 0)
        continue;
      std::int64_t q[3] = { c[0], c[1], c[2] };
      int parity = 0;
      for (int a = 0; a < 3; ++a)
        if (flips & (1 << a))
        {
          q[a] = full[ToIndex(a)] - 1 - q[a];
          parity ^= 1;
        }
      const std::int64_t fq = q[0] + full[0] * (q[1] + full[1] * q[2]);
      const std::int32_t zone = options.SiteZone.empty() ? 0 : options.SiteZone[ToIndex(fq)];
      key.push_back(zoneMask.count(zone) ? zone : INT32_MIN);
      key.push_back(options.Fixed.empty() ? -1 : model.TileIndex(options.Fixed[ToIndex(fq)]));
      key.push_back(parity);
    }
    auto it = classes.find(key);
    if (it == classes.end())
    {
      std::vector<std::uint8_t> mask;
      std::vector<std::int32_t> tiles = ClassTilesOf(model, options, zoneMask, key, seam, c, mask);
      it = classes.emplace(key, static_cast<std::int32_t>(this->ClassTiles.size())).first;
      this->ClassAllowed.push_back(std::move(mask));
      this->ClassTiles.push_back(std::move(tiles));
    }
    this->SiteClass[ToIndex(p)] = it->second;
  }
}

std::int64_t PatternProblem::CountSoft(
  const std::vector<std::int32_t>& tiles, std::vector<std::int32_t>* perSite) const
{
  if (perSite)
    perSite->assign(ToIndex(this->N), 0);
  std::int64_t total = 0;
  for (std::int64_t f = 3 * this->N; f < this->Shapes * this->N; ++f)
    if (this->Valid[ToIndex(f)] && this->Satisfied(f, tiles))
    {
      ++total;
      if (perSite)
        ++(*perSite)[ToIndex(f % this->N)];
    }
  return total;
}

std::int64_t PatternProblem::CountViolatedHard(const std::vector<std::int32_t>& tiles) const
{
  std::int64_t violated = 0;
  for (std::int64_t f = 0; f < 3 * this->N; ++f)
    if (this->Valid[ToIndex(f)] && !this->Satisfied(f, tiles))
      ++violated;
  return violated;
}

} // namespace detail
} // namespace msynth
