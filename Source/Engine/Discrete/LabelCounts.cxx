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

CountBudget::CountBudget(const AdjacencyRules& rules, const SynthesisOptions& options,
  const std::vector<Block>& blocks, const Coord& n, const std::vector<std::int32_t>& fixed)
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
  }
  std::int64_t indices = 0;
  for (const Block& block : blocks)
    indices = std::max(indices, block.Index + 1);
  this->Owners.assign(fixed.size(), 0);
  for (const Block& block : blocks) // in run order: the last one to cover a site owns it
  {
    Coord p;
    for (p[2] = block.Origin[2]; p[2] < block.Origin[2] + block.Dims[2]; ++p[2])
      for (p[1] = block.Origin[1]; p[1] < block.Origin[1] + block.Dims[1]; ++p[1])
        for (p[0] = block.Origin[0]; p[0] < block.Origin[0] + block.Dims[0]; ++p[0])
          this->Owners[ToIndex(p[0] + n[0] * (p[1] + n[1] * p[2]))] =
            static_cast<std::int32_t>(block.Index);
  }
  // Per block and count: its own free sites where the count applies, and its pinned ones.
  const auto per = ToIndex(indices);
  std::vector<std::int64_t> free(per * counted, 0), pinned(per * counted, 0), total(counted, 0);
  std::vector<std::int64_t> freeSites(counted, 0);
  for (std::size_t s = 0; s < fixed.size(); ++s)
  {
    const auto owner = ToIndex(this->Owners[s]);
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
      continue;
    }
    const int c = this->Position(fixed[s], slot);
    if (c >= 0)
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
    const std::string name = NameOf(want);
    const std::int64_t open = freeSites[c];
    if (total[c] > want.Maximum)
      throw Error("the boundary labels and pins already place " + std::to_string(total[c]) +
        " sites of " + name + ", more than its maximum " + std::to_string(want.Maximum));
    if (total[c] + open < want.Minimum)
      throw Error(name + " can hold at most " + std::to_string(total[c] + open) +
        " sites (the others are boundary labels or pins), fewer than its minimum " +
        std::to_string(want.Minimum));
    const std::int64_t low = std::max<std::int64_t>(0, want.Minimum - total[c]);
    const std::int64_t span = std::min(want.Maximum - total[c], open) - low;
    std::int64_t before = 0;
    for (std::size_t i = 0; i < per; ++i)
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
}

} // namespace detail
} // namespace msynth
