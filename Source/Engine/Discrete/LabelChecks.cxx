// SPDX-License-Identifier: BSD-3-Clause
#include "Discrete/LabelChecks.h"

#include "Core/Error.h"
#include "Core/Index.h"
#include "Core/TextLists.h"
#include "Formats/Tileset.h"

#include <algorithm>
#include <functional>
#include <map>
#include <set>

namespace msynth
{
namespace
{
/// The label values @p name gives: a value, or the labels of a tile or label name of @p set.
std::vector<long long> NamedValues(const std::string& name, const Tileset& set)
{
  std::vector<long long> values;
  long long v = 0;
  if (ParseInteger(name, -(1LL << 31), (1LL << 31) - 1, v))
    values.push_back(v);
  for (int b = 0; b < set.NumberOfLabels(); ++b)
    if (set.LabelName(b) == name || set.Tiles[ToIndex(set.LabelTile[ToIndex(b)])].Name == name)
      values.push_back(b);
  return values;
}

std::string Plural(long long n, const char* word)
{
  return std::to_string(n) + " " + word + (n == 1 ? "" : "s");
}

/// The network's sites: per site the sides it joins through (bits +x -x +y -y +z -z), -1 off.
struct Network
{
  std::vector<int> Mask;
  std::vector<std::int64_t> Parent;
  std::int64_t Root(std::int64_t i)
  {
    while (this->Parent[ToIndex(i)] != i)
      i = this->Parent[ToIndex(i)] = this->Parent[ToIndex(this->Parent[ToIndex(i)])];
    return i;
  }
};

/// Joins face neighbours of @p net in @p model whose facing sides both connect.
void JoinNeighbours(const LabelGrid& model, Network& net)
{
  const auto& dims = model.Dimensions();
  const std::int64_t stride[3] = { 1, dims[0], dims[0] * dims[1] };
  for (std::int64_t i = 0; i < model.NumberOfSites(); ++i)
  {
    const int here = net.Mask[ToIndex(i)];
    const std::int64_t at[3] = { i % dims[0], (i / dims[0]) % dims[1], i / stride[2] };
    for (int a = 0; a < 3 && here >= 0; ++a)
    {
      if (at[a] + 1 >= dims[a] || !((here >> (2 * a)) & 1))
        continue;
      const int there = net.Mask[ToIndex(i + stride[a])];
      if (there >= 0 && ((there >> (2 * a + 1)) & 1))
        net.Parent[ToIndex(net.Root(i))] = net.Root(i + stride[a]);
    }
  }
}

/// The sites of @p path: listed sites and every site of the listed labels.
std::vector<std::int64_t> PathSites(
  const LabelGrid& model, const std::vector<std::string>& path, const Tileset& set)
{
  const auto& dims = model.Dimensions();
  std::vector<std::int64_t> sites;
  for (const std::string& item : path)
  {
    const std::vector<std::string> parts = SplitText(item, ',');
    long long c[3] = { 0, 0, 0 };
    bool isSite = parts.size() == 2 || parts.size() == 3;
    for (std::size_t a = 0; isSite && a < parts.size(); ++a)
      isSite = ParseInteger(parts[a], -(1LL << 40), 1LL << 40, c[a]);
    if (isSite)
    {
      for (int a = 0; a < 3; ++a)
        if (c[a] < 0 || c[a] >= dims[a])
          throw Error("--path: site " + item + " is outside the model (" + std::to_string(dims[0]) +
            " x " + std::to_string(dims[1]) + " x " + std::to_string(dims[2]) + " sites)");
      sites.push_back(model.Index(c[0], c[1], c[2]));
      continue;
    }
    const std::vector<long long> values = NamedValues(item, set);
    if (values.empty())
      throw Error("--path: '" + item + "' is neither a site x,y[,z] nor a label value or name");
    for (std::int64_t i = 0; i < model.NumberOfSites(); ++i)
      if (std::find(values.begin(), values.end(),
            static_cast<long long>(model.Data()[ToIndex(i)])) != values.end())
        sites.push_back(i);
  }
  return sites;
}

/// Whether the sites of @p path hold network labels and lie in one component of @p net.
void CheckPath(const LabelGrid& model, const std::vector<std::string>& path, const Tileset& set,
  Network& net, NetworkCheck& check)
{
  check.HasPath = true;
  const std::vector<std::int64_t> sites = PathSites(model, path, set);
  const auto& dims = model.Dimensions();
  std::set<std::int64_t> roots;
  for (std::int64_t s : sites)
  {
    if (net.Mask[ToIndex(s)] < 0)
    {
      check.PathJoined = false;
      check.PathSites = static_cast<long long>(sites.size());
      check.PathLine = "path not joined: site (" + std::to_string(s % dims[0]) + ", " +
        std::to_string((s / dims[0]) % dims[1]) + ", " + std::to_string(s / (dims[0] * dims[1])) +
        ") holds label " + std::to_string(model.Data()[ToIndex(s)]) + ", not one of the network's";
      return;
    }
    roots.insert(net.Root(s));
  }
  check.PathJoined = roots.size() <= 1;
  check.PathSites = static_cast<long long>(sites.size());
  check.PathComponents = static_cast<long long>(roots.size());
  check.PathLine = std::string(check.PathJoined ? "path joined: " : "path not joined: ") +
    Plural(check.PathSites, "site") + " in " + Plural(check.PathComponents, "component") +
    " of the network";
}
} // namespace

std::string PinsCheck::Describe() const
{
  if (this->Kept())
    return "pins kept: " + Plural(this->Pinned, "pinned site") + " hold their labels";
  return "pins missed: " + std::to_string(this->Missed) + " of " +
    Plural(this->Pinned, "pinned site") + " hold another label (the first: " + this->First + ")";
}

PinsCheck CheckPinnedLabels(const LabelGrid& model, const LabelGrid& pins,
  const std::array<long long, 3>& origin, bool emptyFree)
{
  const auto& n = model.Dimensions();
  const auto& m = pins.Dimensions();
  for (std::size_t a = 0; a < 3; ++a)
    if (origin[a] < 0 || origin[a] + m[a] > n[a])
      throw Error("the pins (" + std::to_string(m[0]) + " x " + std::to_string(m[1]) + " x " +
        std::to_string(m[2]) + " sites from (" + std::to_string(origin[0]) + ", " +
        std::to_string(origin[1]) + ", " + std::to_string(origin[2]) +
        ")) do not lie inside the model (" + std::to_string(n[0]) + " x " + std::to_string(n[1]) +
        " x " + std::to_string(n[2]) + " sites)");
  PinsCheck out;
  std::size_t i = 0;
  for (long long z = 0; z < m[2]; ++z)
    for (long long y = 0; y < m[1]; ++y)
      for (long long x = 0; x < m[0]; ++x, ++i)
      {
        const Label want = pins.Data()[i];
        if (want == -1 || (emptyFree && want == 0))
          continue;
        ++out.Pinned;
        const long long p[3] = { x + origin[0], y + origin[1], z + origin[2] };
        const Label has = model.Data()[ToIndex(p[0] + n[0] * (p[1] + n[1] * p[2]))];
        if (has == want)
          continue;
        if (out.Missed++ == 0)
          out.First = "(" + std::to_string(p[0]) + ", " + std::to_string(p[1]) + ", " +
            std::to_string(p[2]) + ") holds " + std::to_string(has) + ", pinned to " +
            std::to_string(want);
      }
  return out;
}

std::string CountCheck::Describe() const
{
  return std::string(this->Kept() ? "count kept: " : "count missed: ") + this->Name + " holds " +
    std::to_string(this->Achieved) + " sites (wanted " + std::to_string(this->Minimum) + " to " +
    std::to_string(this->Maximum) + ")";
}

std::vector<CountCheck> CheckLabelCounts(const LabelGrid& model, const std::string& counts,
  const Tileset& set, const std::string& source, const std::vector<long long>* regions)
{
  std::vector<CountCheck> checks;
  for (CountEntry e : ParseCountEntries(counts, "--count"))
  {
    long long region = -1;
    if (e.Name.compare(0, 7, "region=") == 0)
    {
      const std::size_t colon = e.Name.find(':');
      if (colon == std::string::npos ||
        !ParseInteger(e.Name.substr(7, colon - 7), 0, (1LL << 31) - 1, region))
        throw Error("--count: '" + e.Name + "' is not region=R:L (R from 0)");
      if (!regions || regions->size() != model.Data().size())
        throw Error("--count region=R:...: give the guide with --guide GUIDE.vti (the check's "
                    "CountGuideFile)");
      e.Name = e.Name.substr(colon + 1);
    }
    std::set<long long> values;
    long long v = 0;
    if (ParseInteger(e.Name, -(1LL << 31), (1LL << 31) - 1, v))
      values.insert(v);
    for (int b = 0; b < set.NumberOfLabels() && values.empty(); ++b)
      if (set.LabelName(b) == e.Name)
        values.insert(b);
    for (int b = 0; b < set.NumberOfLabels(); ++b)
      if (set.Tiles[ToIndex(set.LabelTile[ToIndex(b)])].Name == e.Name)
        values.insert(b);
    if (values.empty())
      throw Error("--count: '" + e.Name + "' is neither a label value nor a name of " + source);
    CountCheck c{ e.Name, e.Minimum, e.Maximum, 0 };
    if (region >= 0)
      c.Name += " in guide region " + std::to_string(region);
    const auto& labels = model.Data();
    for (std::size_t i = 0; i < labels.size(); ++i)
      c.Achieved +=
        values.count(static_cast<long long>(labels[i])) && (region < 0 || (*regions)[i] == region)
        ? 1
        : 0;
    checks.push_back(c);
  }
  return checks;
}

std::string NetworkCheck::Describe() const
{
  if (this->Open)
    return std::string(this->Closed == 0 ? "connected: " : "not connected: ") + this->Labels +
      " form " + Plural(this->Components, "component") + ", " + std::to_string(this->Closed) +
      " of them closed off (reaching no border of the model; wanted none)";
  return std::string(this->Components <= this->Maximum ? "connected: " : "not connected: ") +
    this->Labels + " form " + Plural(this->Components, "component") + " (wanted at most " +
    std::to_string(this->Maximum) + ")";
}

NetworkCheck CheckLabelNetwork(const LabelGrid& model, const std::string& spec,
  const std::vector<std::string>& path, const Tileset& set, const std::string& source)
{
  NetworkCheck check;
  check.Labels = spec;
  const std::size_t colon = spec.rfind(':');
  if (colon != std::string::npos && spec.substr(colon + 1) == "open")
  {
    check.Open = true;
    check.Labels.resize(colon);
  }
  else if (colon != std::string::npos)
  {
    if (!ParseInteger(spec.substr(colon + 1), 1, 1LL << 40, check.Maximum))
      throw Error(
        "--connected: '" + spec.substr(colon + 1) + "' is not a number of components (1 or more)");
    check.Labels.resize(colon);
  }
  std::map<long long, int> sides; // network label -> the sides it joins through
  for (const std::string& name : SplitText(check.Labels, ','))
  {
    const std::size_t before = sides.size();
    for (long long v : NamedValues(name, set))
      sides[v] = 63;
    if (sides.size() == before && !name.empty())
      throw Error("--connected: '" + name + "' is neither a label value nor a name of " + source);
  }
  for (auto& [label, mask] : sides)
    if (label >= 0 && label < static_cast<long long>(set.LabelSides.size()) &&
      set.LabelSides[ToIndex(label)] >= 0)
      mask = set.LabelSides[ToIndex(label)];
  const std::size_t total = ToIndex(model.NumberOfSites());
  Network net{ std::vector<int>(total, -1), std::vector<std::int64_t>(total) };
  for (std::size_t i = 0; i < total; ++i)
  {
    net.Parent[i] = static_cast<std::int64_t>(i);
    const auto found = sides.find(static_cast<long long>(model.Data()[i]));
    if (found != sides.end())
      net.Mask[i] = found->second;
  }
  JoinNeighbours(model, net);
  std::vector<char> border(check.Open ? total : 0, 0); // per root: reaches the model's border
  const auto& dims = model.Dimensions();
  for (std::size_t i = 0; i < border.size(); ++i)
  {
    const auto s = static_cast<std::int64_t>(i);
    const std::int64_t at[3] = { s % dims[0], (s / dims[0]) % dims[1], s / (dims[0] * dims[1]) };
    bool edge = false;
    for (int a = 0; a < 3; ++a)
      edge = edge || (dims[a] > 1 && (at[a] == 0 || at[a] == dims[a] - 1));
    if (net.Mask[i] >= 0 && edge)
      border[ToIndex(net.Root(s))] = 1;
  }
  for (std::size_t i = 0; i < total; ++i)
    if (net.Mask[i] >= 0 && net.Root(static_cast<std::int64_t>(i)) == static_cast<std::int64_t>(i))
    {
      ++check.Components;
      check.Closed += check.Open && !border[i] ? 1 : 0;
    }
  if (!path.empty())
    CheckPath(model, path, set, net, check);
  return check;
}

} // namespace msynth
