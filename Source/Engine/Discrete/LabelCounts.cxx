// SPDX-License-Identifier: BSD-3-Clause
#include "Discrete/LabelCounts.h"

#include "Core/Error.h"

#include <algorithm>
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
  if (!c.Name.empty())
    return (c.Values.size() == 1 && c.Name == std::to_string(c.Values[0]) ? "label " : "tile ") +
      c.Name;
  return c.Values.size() == 1 ? "label " + std::to_string(c.Values[0]) : "a label set";
}

/// The labels that can still fill a site when those of maximum 0 are banned: a label stays
/// while, along every axis of more than one site, some staying label may follow or precede it.
std::vector<char> Possible(const AdjacencyRules& rules, const SynthesisOptions& options)
{
  const int k = rules.NumberOfLabels();
  std::vector<char> alive(static_cast<std::size_t>(k), 1);
  for (const LabelCount& c : options.Counts)
    if (c.Maximum == 0)
      for (Label v : c.Values)
        alive[static_cast<std::size_t>(rules.IndexOf(v))] = 0;
  auto meets = [&](const std::uint64_t* set)
  {
    for (int b = 0; b < k; ++b)
      if (alive[static_cast<std::size_t>(b)] && ((set[b >> 6] >> (b & 63)) & 1))
        return true;
    return false;
  };
  for (bool changed = true; changed;)
  {
    changed = false;
    for (int b = 0; b < k; ++b)
    {
      if (!alive[static_cast<std::size_t>(b)])
        continue;
      for (int axis = 0; axis < 3; ++axis)
        if (options.Size[static_cast<std::size_t>(axis)] > 1 &&
          !meets(rules.Compatible(2 * axis, b)) && !meets(rules.Compatible(2 * axis + 1, b)))
        {
          alive[static_cast<std::size_t>(b)] = 0;
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
  std::set<Label> seen;
  Wide minimum = 0, maximum = 0;
  for (const LabelCount& c : options.Counts)
  {
    const std::string name = "the count of " + NameOf(c);
    if (c.Values.empty())
      throw Error(name + " names no label");
    for (Label v : c.Values)
    {
      if (rules.IndexOf(v) < 0)
        throw Error(name + ": label " + std::to_string(v) + " does not occur in the example");
      if (!seen.insert(v).second)
        throw Error(name + ": label " + std::to_string(v) + " is counted twice");
    }
    if (c.Minimum < 0 || c.Maximum < c.Minimum)
      throw Error(name + " asks for " + std::to_string(c.Minimum) + " to " +
        std::to_string(c.Maximum) + " sites (need 0 <= MIN <= MAX)");
    if (c.Minimum > sites)
      throw Error(name + " asks for at least " + std::to_string(c.Minimum) +
        " sites, but the output has " + std::to_string(sites));
    minimum += c.Minimum;
    maximum += c.Maximum;
  }
  if (minimum > sites)
    throw Error("the label counts ask for at least " +
      std::to_string(static_cast<std::int64_t>(minimum)) + " sites together, but the output has " +
      std::to_string(sites));
  if (static_cast<int>(seen.size()) == rules.NumberOfLabels() && maximum < sites)
    throw Error("the label counts allow at most " +
      std::to_string(static_cast<std::int64_t>(maximum)) + " sites together, but the output has " +
      std::to_string(sites));
  const std::vector<char> alive = Possible(rules, options);
  if (std::find(alive.begin(), alive.end(), 1) == alive.end())
    throw Error("the label counts of maximum 0 leave no label the rules can fill the output with");
  for (const LabelCount& c : options.Counts)
  {
    bool possible = false;
    for (Label v : c.Values)
      possible |= alive[static_cast<std::size_t>(rules.IndexOf(v))] != 0;
    if (c.Minimum > 0 && !possible)
      throw Error("the count of " + NameOf(c) + " asks for at least " + std::to_string(c.Minimum) +
        " sites, but the rules never place it without a label whose maximum is 0");
  }
}

std::vector<LabelCountResult> CountLabels(
  const std::vector<LabelCount>& counts, const LabelGrid& model)
{
  std::vector<LabelCountResult> out;
  for (const LabelCount& c : counts)
  {
    LabelCountResult r;
    r.Requested = c;
    const std::set<Label> values(c.Values.begin(), c.Values.end());
    for (Label v : model.Data())
      r.Achieved += values.count(v) ? 1 : 0;
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
  r.Counts = CountLabels(options.Counts, r.Model);
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

CountBudget::CountBudget(const AdjacencyRules& rules, const SynthesisOptions& options,
  const std::vector<Block>& blocks, const Coord& n, const std::vector<std::int32_t>& fixed)
{
  const std::size_t counted = options.Counts.size();
  this->PositionOf.assign(static_cast<std::size_t>(rules.NumberOfLabels()), -1);
  for (std::size_t c = 0; c < counted; ++c)
  {
    for (Label v : options.Counts[c].Values)
      this->PositionOf[static_cast<std::size_t>(rules.IndexOf(v))] = static_cast<int>(c);
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
          this->Owners[static_cast<std::size_t>(p[0] + n[0] * (p[1] + n[1] * p[2]))] =
            static_cast<std::int32_t>(block.Index);
  }
  const auto per = static_cast<std::size_t>(indices);
  std::vector<std::int64_t> free(per, 0), pinned(per * counted, 0), total(counted, 0);
  for (std::size_t s = 0; s < fixed.size(); ++s)
  {
    const auto owner = static_cast<std::size_t>(this->Owners[s]);
    if (fixed[s] < 0)
    {
      ++free[owner];
      continue;
    }
    const int c = this->PositionOf[static_cast<std::size_t>(fixed[s])];
    if (c >= 0)
    {
      ++pinned[owner * counted + static_cast<std::size_t>(c)];
      ++total[static_cast<std::size_t>(c)];
    }
  }
  std::int64_t freeSites = 0;
  for (std::int64_t f : free)
    freeSites += f;
  this->Min.assign(per * counted, 0);
  this->Max.assign(per * counted, 0);
  for (std::size_t c = 0; c < counted; ++c)
  {
    const LabelCount& want = options.Counts[c];
    const std::string name = NameOf(want);
    if (total[c] > want.Maximum)
      throw Error("the boundary labels and pins already place " + std::to_string(total[c]) +
        " sites of " + name + ", more than its maximum " + std::to_string(want.Maximum));
    if (total[c] + freeSites < want.Minimum)
      throw Error(name + " can hold at most " + std::to_string(total[c] + freeSites) +
        " sites (the others are boundary labels or pins), fewer than its minimum " +
        std::to_string(want.Minimum));
    const std::int64_t low = std::max<std::int64_t>(0, want.Minimum - total[c]);
    const std::int64_t span = std::min(want.Maximum - total[c], freeSites) - low;
    std::int64_t before = 0;
    for (std::size_t i = 0; i < per; ++i)
    {
      const std::int64_t after = before + free[i];
      const std::size_t at = i * counted + c;
      this->Min[at] = pinned[at] +
        (freeSites > 0 ? Share(low, after, freeSites) - Share(low, before, freeSites) : 0);
      this->Max[at] = this->Min[at] +
        (freeSites > 0 ? Share(span, after, freeSites) - Share(span, before, freeSites) : 0);
      before = after;
    }
  }
}

} // namespace detail
} // namespace msynth
