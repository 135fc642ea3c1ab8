// SPDX-License-Identifier: BSD-3-Clause
#include "Discrete/LabelCounts.h"

#include "Core/Error.h"
#include "Core/Index.h"

#include <algorithm>
#include <array>
#include <map>
#include <set>

namespace msynth
{
namespace detail
{
namespace
{
__extension__ typedef __int128 Wide;

/// floor(@p total · @p part / @p whole) without overflow (@p whole > 0).
std::int64_t Share(std::int64_t total, std::int64_t part, std::int64_t whole)
{
  return static_cast<std::int64_t>(static_cast<Wide>(total) * part / whole);
}

/// "label 3" or "tile road", as the count was named.
std::string NameOf(const LabelCount& c)
{
  const std::string where =
    c.Region >= 0 ? " in guide region " + std::to_string(c.Region) : std::string();
  if (!c.Name.empty())
    return (c.Values.size() == 1 && c.Name == std::to_string(c.Values[0]) ? "label " : "tile ") +
      c.Name + where;
  return (c.Values.size() == 1 ? "label " + std::to_string(c.Values[0]) : "a label set") + where;
}

/// The guide cell along axis @p a of coordinate @p p in an output of @p n sites (GuideVolume).
std::int64_t CellAlong(const GuideVolume& guide, int a, std::int64_t p, std::int64_t n)
{
  const std::int64_t d = guide.Dims[ToIndex(a)];
  return std::min(d - 1, ((2 * p + 1) * d) / (2 * n));
}

/// The number of output sites of @p size in each region of @p guide (region → sites).
std::map<std::int32_t, std::int64_t> RegionSites(const GuideVolume& guide, const Coord& size)
{
  std::array<std::vector<std::int64_t>, 3> along;
  for (int a = 0; a < 3; ++a)
  {
    along[ToIndex(a)].assign(ToIndex(guide.Dims[a]), 0);
    for (std::int64_t p = 0; p < size[ToIndex(a)]; ++p)
      ++along[ToIndex(a)][ToIndex(CellAlong(guide, a, p, size[ToIndex(a)]))];
  }
  std::map<std::int32_t, std::int64_t> sites;
  std::size_t cell = 0;
  for (std::int64_t z = 0; z < guide.Dims[2]; ++z)
    for (std::int64_t y = 0; y < guide.Dims[1]; ++y)
      for (std::int64_t x = 0; x < guide.Dims[0]; ++x, ++cell)
        sites[guide.Regions[cell]] +=
          along[0][ToIndex(x)] * along[1][ToIndex(y)] * along[2][ToIndex(z)];
  return sites;
}

/// The guide region of every site of an output of @p n sites (x fastest).
std::vector<std::int32_t> SiteRegions(const GuideVolume& guide, const Coord& n)
{
  std::vector<std::int32_t> regions(ToIndex(n[0] * n[1] * n[2]));
  std::size_t s = 0;
  Coord p;
  for (p[2] = 0; p[2] < n[2]; ++p[2])
    for (p[1] = 0; p[1] < n[1]; ++p[1])
      for (p[0] = 0; p[0] < n[0]; ++p[0], ++s)
        regions[s] = guide.Regions[ToIndex(guide.CellOf(p, n))];
  return regions;
}

/// Whether any of @p counts is of a guide region.
bool AnyRegion(const std::vector<LabelCount>& counts)
{
  return std::any_of(
    counts.begin(), counts.end(), [](const LabelCount& c) { return c.Region >= 0; });
}

/// The guide regions @p options.Counts name, each checked to hold sites of the output
/// (region → its sites); empty without region counts.
std::map<std::int32_t, std::int64_t> CountedRegions(const SynthesisOptions& options)
{
  if (!AnyRegion(options.Counts))
    return {};
  const GuideVolume* guide = options.Guide ? &*options.Guide : nullptr;
  if (!guide || guide->Regions.empty())
    throw Error("the count of " +
      NameOf(*std::find_if(options.Counts.begin(), options.Counts.end(),
        [](const LabelCount& c) { return c.Region >= 0; })) +
      " needs a guide with regions (an integer point array Region)");
  if (static_cast<std::int64_t>(guide->Regions.size()) !=
    guide->Dims[0] * guide->Dims[1] * guide->Dims[2])
    throw Error("the guide's regions do not have one value per guide cell");
  const std::map<std::int32_t, std::int64_t> all = RegionSites(*guide, options.Size);
  std::map<std::int32_t, std::int64_t> counted;
  for (const LabelCount& c : options.Counts)
  {
    if (c.Region < 0)
      continue;
    const auto it = all.find(c.Region);
    if (it == all.end() || it->second == 0)
      throw Error("the count of " + NameOf(c) + ": the guide's region " + std::to_string(c.Region) +
        " holds no site of the output");
    counted[c.Region] = it->second;
  }
  return counted;
}

/// The labels that can still fill a site when those of maximum 0 are banned: a label stays
/// while, along every axis of more than one site, some staying label may follow or precede it.
std::vector<char> Possible(const AdjacencyRules& rules, const SynthesisOptions& options)
{
  const int k = rules.NumberOfLabels();
  std::vector<char> alive(ToIndex(k), 1);
  for (const LabelCount& c : options.Counts)
    if (c.Maximum == 0 && c.Region < 0) // a region's maximum 0 bans the label there only
      for (Label v : c.Values)
        alive[ToIndex(rules.IndexOf(v))] = 0;
  auto meets = [&](const std::uint64_t* set)
  {
    for (int b = 0; b < k; ++b)
      if (alive[ToIndex(b)] && ((set[b >> 6] >> (b & 63)) & 1))
        return true;
    return false;
  };
  for (bool changed = true; changed;)
  {
    changed = false;
    for (int b = 0; b < k; ++b)
    {
      if (!alive[ToIndex(b)])
        continue;
      for (int axis = 0; axis < 3; ++axis)
        if (options.Size[ToIndex(axis)] > 1 && !meets(rules.Compatible(2 * axis, b)) &&
          !meets(rules.Compatible(2 * axis + 1, b)))
        {
          alive[ToIndex(b)] = 0;
          changed = true;
          break;
        }
    }
  }
  return alive;
}
} // namespace

void CheckCountRequest(const AdjacencyRules& rules, const SynthesisOptions& options)
{
  if (options.Counts.empty())
    return;
  bool symmetric = options.Rotate.Enabled;
  for (std::size_t a = 0; a < 3; ++a)
    symmetric |= options.Symmetry[a].Enabled || options.Translate[a].Enabled;
  if (symmetric)
    throw Error("label counts cannot be combined with symmetry (only a part of the output is "
                "synthesized)");
  if (options.Soft.Active())
    throw Error("label counts cannot be combined with soft constraints (which roll blocks back)");
  if (static_cast<Wide>(options.Size[0]) * options.Size[1] * options.Size[2] >
    (static_cast<Wide>(1) << 62))
    throw Error("label counts take a world of at most 2^62 sites");
  const std::int64_t sites = options.Size[0] * options.Size[1] * options.Size[2];
  const std::map<std::int32_t, std::int64_t> regions = CountedRegions(options);
  std::set<std::pair<std::int32_t, Label>> seen;
  std::map<std::int32_t, Wide> minimum, maximum; // per scope: -1 the whole output, or a region
  std::map<std::int32_t, int> labels;
  for (const LabelCount& c : options.Counts)
  {
    const std::string name = "the count of " + NameOf(c);
    const std::int64_t scope = c.Region < 0 ? sites : regions.at(c.Region);
    const std::string of = c.Region < 0 ? "the output" : "the region";
    if (c.Values.empty())
      throw Error(name + " names no label");
    for (Label v : c.Values)
    {
      if (rules.IndexOf(v) < 0)
        throw Error(name + ": label " + std::to_string(v) + " does not occur in the example");
      if (!seen.insert({ c.Region, v }).second)
        throw Error(name + ": label " + std::to_string(v) + " is counted twice");
      if (seen.count({ -1, v }) &&
        (c.Region >= 0 ||
          std::any_of(seen.begin(), seen.end(),
            [&](const std::pair<std::int32_t, Label>& e)
            { return e.first >= 0 && e.second == v; })))
        throw Error(name + ": label " + std::to_string(v) +
          " is counted both in the whole output and in a guide region");
    }
    if (c.Minimum < 0 || c.Maximum < c.Minimum)
      throw Error(name + " asks for " + std::to_string(c.Minimum) + " to " +
        std::to_string(c.Maximum) + " sites (need 0 <= MIN <= MAX)");
    if (c.Minimum > scope)
      throw Error(name + " asks for at least " + std::to_string(c.Minimum) + " sites, but " + of +
        " has " + std::to_string(scope));
    minimum[c.Region] += c.Minimum;
    maximum[c.Region] += c.Maximum;
    labels[c.Region] += static_cast<int>(c.Values.size());
  }
  for (const auto& [region, least] : minimum)
  {
    const std::int64_t scope = region < 0 ? sites : regions.at(region);
    const std::string of = region < 0 ? "the output" : "guide region " + std::to_string(region);
    if (least > scope)
      throw Error("the label counts ask for at least " +
        std::to_string(static_cast<std::int64_t>(least)) + " sites together, but " + of + " has " +
        std::to_string(scope));
    if (labels[region] == rules.NumberOfLabels() && maximum[region] < scope)
      throw Error("the label counts allow at most " +
        std::to_string(static_cast<std::int64_t>(maximum[region])) + " sites together, but " + of +
        " has " + std::to_string(scope));
  }
  const std::vector<char> alive = Possible(rules, options);
  if (std::find(alive.begin(), alive.end(), 1) == alive.end())
    throw Error("the label counts of maximum 0 leave no label the rules can fill the output with");
  for (const LabelCount& c : options.Counts)
  {
    bool possible = false;
    for (Label v : c.Values)
      possible |= alive[ToIndex(rules.IndexOf(v))] != 0;
    if (c.Minimum > 0 && !possible)
      throw Error("the count of " + NameOf(c) + " asks for at least " + std::to_string(c.Minimum) +
        " sites, but the rules never place it without a label whose maximum is 0");
  }
}

std::vector<LabelCountResult> CountLabels(const std::vector<LabelCount>& counts,
  const LabelGrid& model, const std::optional<GuideVolume>& guide)
{
  const std::vector<std::int32_t> regions = AnyRegion(counts) && guide && !guide->Regions.empty()
    ? SiteRegions(*guide, model.Dimensions())
    : std::vector<std::int32_t>();
  std::vector<LabelCountResult> out;
  for (const LabelCount& c : counts)
  {
    LabelCountResult r;
    r.Requested = c;
    const std::set<Label> values(c.Values.begin(), c.Values.end());
    const std::vector<Label>& data = model.Data();
    for (std::size_t s = 0; s < data.size(); ++s)
      r.Achieved += values.count(data[s]) && (c.Region < 0 || regions[s] == c.Region) ? 1 : 0;
    out.push_back(r);
  }
  return out;
}

std::string CountMiss(const std::vector<LabelCountResult>& results)
{
  for (const LabelCountResult& r : results)
    if (r.Achieved < r.Requested.Minimum || r.Achieved > r.Requested.Maximum)
      return NameOf(r.Requested) + " holds " + std::to_string(r.Achieved) + " sites, not " +
        std::to_string(r.Requested.Minimum) + " to " + std::to_string(r.Requested.Maximum);
  return std::string();
}

SynthesisResult CountsKept(
  const SynthesisOptions& options, SynthesisResult r, std::int64_t misses, bool finished)
{
  if (!finished)
  {
    if (misses > 0)
      r.Message += " (" + std::to_string(misses) + " solved attempts missed the label counts)";
    return r;
  }
  r.Counts = CountLabels(options.Counts, r.Model, options.Guide);
  const std::string miss = CountMiss(r.Counts);
  if (miss.empty())
    return r;
  r.Status = SynthesisStatus::Failed;
  r.Message = "the label counts were not kept: " + miss + " (" +
    std::to_string(r.Statistics.BlocksFailed) + " blocks failed, " + std::to_string(misses) +
    " solved attempts missed their counts). Try another seed, more attempts, larger blocks or "
    "wider counts";
  r.Model = LabelGrid();
  r.LastBlock.clear();
  return r;
}

namespace
{
/// The slot of each site (see LabelCounts.h) and the region of each slot past 0 (@p counted).
std::vector<std::int32_t> SlotsOf(
  const SynthesisOptions& options, const Coord& n, std::vector<std::int32_t>& counted)
{
  counted.clear();
  if (!AnyRegion(options.Counts))
    return {};
  for (const LabelCount& c : options.Counts)
    if (c.Region >= 0 && std::find(counted.begin(), counted.end(), c.Region) == counted.end())
      counted.push_back(c.Region);
  std::sort(counted.begin(), counted.end());
  std::vector<std::int32_t> slots = SiteRegions(*options.Guide, n);
  for (std::int32_t& r : slots)
  {
    const auto it = std::lower_bound(counted.begin(), counted.end(), r);
    r = it != counted.end() && *it == r ? static_cast<std::int32_t>(it - counted.begin()) + 1 : 0;
  }
  return slots;
}
} // namespace

namespace
{
/// Refuses a count its @p total fixed sites and @p open free ones make impossible.
void CheckFixedTotals(const LabelCount& want, std::int64_t total, std::int64_t open)
{
  if (total > want.Maximum)
    throw Error("the boundary labels and pins already place " + std::to_string(total) +
      " sites of " + NameOf(want) + ", more than its maximum " + std::to_string(want.Maximum));
  if (total + open < want.Minimum)
    throw Error(NameOf(want) + " can hold at most " + std::to_string(total + open) +
      " sites (the others are boundary labels or pins), fewer than its minimum " +
      std::to_string(want.Minimum));
}

} // namespace

/**
 * The sites of the world before block b's own ones in index order (its owners' prefix), and its
 * own sites. Along each axis the owner of a coordinate is the covering block of the highest phase
 * digit (phases compare by their z, then y, then x digit, and blocks of a digit never touch), so
 * a block owns a box, the product of its intervals along the axes, and owners grow with the
 * coordinate: the prefix is a sum of boxes (LabelCounts.h).
 */
struct OwnPrefix
{
  OwnPrefix(const SynthesisOptions& options, const Coord& world)
    : World(world)
  {
    Coord m, step;
    BlockGeometry<3>(world, options.BlockSize, options.Overlap, m, step);
    const WorldLattice lattice(world, m, step);
    for (std::size_t a = 0; a < 3; ++a)
    {
      this->M[a] = m[a];
      this->Step[a] = step[a];
      this->Count[a] = lattice.Count(static_cast<int>(a));
      this->Period[a] = lattice.Period(static_cast<int>(a));
    }
  }

  /// The block along axis @p a that owns coordinate @p x.
  std::int64_t OwnerAlong(std::size_t a, std::int64_t x) const
  {
    const std::int64_t last = std::min(this->Count[a] - 1, x / this->Step[a]);
    std::int64_t best = last;
    for (std::int64_t k = last; k >= 0 && k * this->Step[a] + this->M[a] > x; --k)
      if (k % this->Period[a] > best % this->Period[a])
        best = k;
    return best;
  }

  /// The first coordinate along axis @p a owned by block @p k or a later one.
  std::int64_t Before(std::size_t a, std::int64_t k) const
  {
    if (k >= this->Count[a])
      return this->World[a];
    std::int64_t x = k * this->Step[a];
    const std::int64_t end = std::min(this->World[a], x + this->M[a]);
    while (x < end && this->OwnerAlong(a, x) < k)
      ++x;
    return x;
  }

  /// The prefix and the own sites of block @p index.
  void Of(std::int64_t index, Wide& prefix, Wide& own) const
  {
    const std::int64_t k[3] = { index % this->Count[0], (index / this->Count[0]) % this->Count[1],
      index / (this->Count[0] * this->Count[1]) };
    Wide pre[3], size[3];
    for (std::size_t a = 0; a < 3; ++a)
    {
      pre[a] = this->Before(a, k[a]);
      size[a] = this->Before(a, k[a] + 1) - pre[a];
    }
    const Wide n0 = this->World[0], n1 = this->World[1];
    prefix = pre[2] * n1 * n0 + size[2] * (pre[1] * n0 + size[1] * pre[0]);
    own = size[0] * size[1] * size[2];
  }

  Coord World, M, Step, Count, Period;
};

namespace
{
/// Every block of @p cone's world (or of the world of @p n sites) meeting the model, in run order
/// (phase, then index), writes its key over its sites of @p owners: the world's owner of each.
void WorldOwners(const SynthesisOptions& options, const Coord& n, const RegionCone* cone,
  std::vector<std::int64_t>& owners)
{
  const Coord world = cone ? cone->World : n;
  const Coord off = cone ? cone->WindowLow : Coord{ { 0, 0, 0 } };
  Coord m, step;
  BlockGeometry<3>(world, options.BlockSize, options.Overlap, m, step);
  const WorldLattice lattice(world, m, step);
  const WorldBox high{ { off[0] + n[0], off[1] + n[1], off[2] + n[2] } };
  owners.assign(ToIndex(n[0] * n[1] * n[2]), -1);
  std::vector<BoxBlock<3>> met;
  for (int phase = 0; phase < lattice.Phases(); ++phase)
  {
    met.clear();
    lattice.Meeting(phase, off, high, met);
    for (const BoxBlock<3>& b : met)
    {
      Coord lo, hi;
      for (std::size_t a = 0; a < 3; ++a)
      {
        lo[a] = std::max(b.Origin[a], off[a]) - off[a];
        hi[a] = std::min(b.Origin[a] + b.Dims[a], high[a]) - off[a];
      }
      for (std::int64_t z = lo[2]; z < hi[2]; ++z)
        for (std::int64_t y = lo[1]; y < hi[1]; ++y)
        {
          const auto row = ToIndex(n[0] * (y + n[1] * z));
          std::fill(owners.begin() + static_cast<std::ptrdiff_t>(row + ToIndex(lo[0])),
            owners.begin() + static_cast<std::ptrdiff_t>(row + ToIndex(hi[0])), b.Index);
        }
    }
  }
}
} // namespace

std::vector<Block> CountedBlocks(const RegionCone& cone)
{
  std::vector<Block> all;
  std::set<std::int64_t> seen;
  for (const auto& pass : cone.Passes)
    for (Block b : pass)
      if (seen.insert(b.Index).second)
      {
        for (std::size_t a = 0; a < 3; ++a)
          b.Origin[a] -= cone.WindowLow[a];
        all.push_back(b);
      }
  return all;
}

CountBudget::CountBudget(const AdjacencyRules& rules, const SynthesisOptions& options,
  const std::vector<Block>& blocks, const Coord& n, const std::vector<std::int32_t>& fixed,
  const RegionCone* cone)
{
  const std::size_t counted = options.Counts.size();
  std::vector<std::int32_t> regions; // of slots 1, 2, ...
  this->Slots = SlotsOf(options, n, regions);
  this->K = ToIndex(rules.NumberOfLabels());
  this->PositionOf.assign((regions.size() + 1) * this->K, -1);
  for (std::size_t c = 0; c < counted; ++c)
  {
    const LabelCount& want = options.Counts[c];
    for (std::size_t slot = 0; slot <= regions.size(); ++slot)
      if (want.Region < 0 || (slot > 0 && regions[slot - 1] == want.Region))
        for (Label v : want.Values)
          this->PositionOf[slot * this->K + ToIndex(rules.IndexOf(v))] = static_cast<int>(c);
    this->Counted.push_back(static_cast<int>(c));
    this->WholeMin.push_back(want.Minimum);
    this->WholeMax.push_back(want.Maximum);
  }
  for (std::size_t i = 0; i < blocks.size(); ++i)
    this->Rows.emplace(blocks[i].Index, i);
  WorldOwners(options, n, cone, this->Owners);
  // Per block (its place in the run) and count: its own free sites where the count applies, its
  // pinned ones, and the world's units of the count's minimum and span its own sites carry.
  const std::size_t per = blocks.size();
  std::vector<std::int64_t> free(per * counted, 0), pinned(per * counted, 0), total(counted, 0);
  std::vector<std::int64_t> freeSites(counted, 0);
  const Coord world = cone ? cone->World : n;
  const Coord off = cone ? cone->WindowLow : Coord{ { 0, 0, 0 } };
  for (std::size_t s = 0; s < fixed.size(); ++s)
  {
    const auto row = this->Rows.find(this->Owners[s]);
    if (row == this->Rows.end())
      continue; // owned by a block this run does not run
    const std::size_t owner = row->second;
    const std::int32_t slot = this->Slot(s);
    if (fixed[s] < 0)
    {
      for (std::size_t c = 0; c < counted; ++c)
      {
        const std::int32_t r = options.Counts[c].Region;
        if (r < 0 || (slot > 0 && regions[ToIndex(slot - 1)] == r))
        {
          ++free[owner * counted + c];
          ++freeSites[c];
        }
      }
    }
    else if (const int c = this->Position(fixed[s], slot); c >= 0)
    {
      ++pinned[owner * counted + ToIndex(c)];
      ++total[ToIndex(c)];
    }
  }
  this->Min.assign(per * counted, 0);
  this->Max.assign(per * counted, 0);
  for (std::size_t c = 0; c < counted; ++c)
  {
    const LabelCount& want = options.Counts[c];
    if (want.Region >= 0 || !cone) // the model is all the count's scope: its fixed sites
      CheckFixedTotals(want, total[c], freeSites[c]);
    const auto plan = [&](const LabelCount& range)
    {
      if (range.Region < 0)
        this->WorldShares(range, c, blocks, OwnPrefix(options, world), off, free, pinned);
      else
        this->RegionShares(range, c, free, pinned, total[c], freeSites[c]);
    };
    // A network kept by repairs of the whole model (Connectivity.h): the blocks aim a quarter
    // of the span inside the range on each side, which leaves the repairs room to lay or lift
    // counted labels while they join components (they keep the whole range); the full range
    // when the pins leave a block no room for that.
    const std::int64_t margin =
      options.Connected.Active() && !options.Connected.Open ? (want.Maximum - want.Minimum) / 4 : 0;
    if (margin > 0)
    {
      LabelCount inner = want;
      inner.Minimum += margin;
      inner.Maximum -= margin;
      try
      {
        plan(inner);
        continue;
      }
      catch (const Error&)
      {
      }
    }
    plan(want);
  }
}

void CountBudget::WorldShares(const LabelCount& want, std::size_t c,
  const std::vector<Block>& blocks, const OwnPrefix& owners, const Coord& off,
  const std::vector<std::int64_t>& free, const std::vector<std::int64_t>& pinned)
{
  const std::size_t counted = this->Counted.size();
  const Coord& w = owners.World;
  const Wide sites = static_cast<Wide>(w[0]) * w[1] * w[2];
  const Wide wide = want.Maximum - want.Minimum;
  const auto share = [&](Wide total, Wide before, Wide after)
  { return static_cast<std::int64_t>(total * after / sites - total * before / sites); };
  for (std::size_t i = 0; i < blocks.size(); ++i)
  {
    const std::size_t at = i * counted + c;
    Wide before = 0, own = 0;
    owners.Of(blocks[i].Index, before, own);
    this->Min[at] = share(want.Minimum, before, before + own);
    this->Max[at] = this->Min[at] + share(wide, before, before + own);
    if (pinned[at] > this->Max[at] || pinned[at] + free[at] < this->Min[at])
      throw Error("the boundary labels and pins place " + std::to_string(pinned[at]) +
        " sites of " + NameOf(want) + " among the " + std::to_string(pinned[at] + free[at]) +
        " it may take in the block at " +
        Format({ { blocks[i].Origin[0] + off[0], blocks[i].Origin[1] + off[1],
          blocks[i].Origin[2] + off[2] } }) +
        ", outside its share " + std::to_string(this->Min[at]) + " to " +
        std::to_string(this->Max[at]) +
        " of the count (shares go by position: see the command-line guide)");
  }
}

void CountBudget::RegionShares(const LabelCount& want, std::size_t c,
  const std::vector<std::int64_t>& free, const std::vector<std::int64_t>& pinned,
  std::int64_t total, std::int64_t open)
{
  const std::size_t counted = this->Counted.size();
  const std::int64_t low = std::max<std::int64_t>(0, want.Minimum - total);
  const std::int64_t span = std::min(want.Maximum - total, open) - low;
  std::int64_t before = 0;
  for (std::size_t i = 0; i * counted < free.size(); ++i)
  {
    const std::size_t at = i * counted + c;
    const std::int64_t after = before + free[at];
    this->Min[at] =
      pinned[at] + (open > 0 ? Share(low, after, open) - Share(low, before, open) : 0);
    this->Max[at] =
      this->Min[at] + (open > 0 ? Share(span, after, open) - Share(span, before, open) : 0);
    before = after;
  }
}

} // namespace detail
} // namespace msynth
