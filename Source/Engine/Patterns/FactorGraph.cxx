// SPDX-License-Identifier: BSD-3-Clause
#include "Patterns/FactorGraph.h"

#include "Core/Error.h"
#include "Core/Index.h"
#include "Core/TextLists.h"

#include <algorithm>
#include <cctype>
#include <set>
#include <sstream>

namespace msynth
{

namespace
{

constexpr int MaxStencilSites = 64;
constexpr int MaxStencilExtent = 64;

Error BadShape(const std::string& text, const std::string& problem)
{
  return Error("factor or block shape '" + text + "': " + problem);
}

int ParseCount(const std::string& text, const std::string& digits, int lowest)
{
  if (digits.empty() || digits.size() > 3 ||
    !std::all_of(digits.begin(), digits.end(), [](char c) { return std::isdigit(c); }))
    throw BadShape(text, "'" + digits + "' is not a size");
  const int n = std::stoi(digits);
  if (n < lowest || n > MaxStencilExtent)
    throw BadShape(text, "sizes must be " + std::to_string(lowest) + " to 64");
  return n;
}

int ParseOffset(const std::string& text, const std::string& digits)
{
  std::string d = digits;
  bool negative = false;
  if (!d.empty() && d[0] == '-')
  {
    negative = true;
    d.erase(0, 1);
  }
  if (d.empty() || d.size() > 2 ||
    !std::all_of(d.begin(), d.end(), [](char c) { return std::isdigit(c); }))
    throw BadShape(text, "'" + digits + "' is not an offset");
  const int v = std::stoi(d);
  return negative ? -v : v;
}

Stencil Normalised(const std::string& name, std::vector<std::array<int, 3>> offsets)
{
  std::array<int, 3> low{ { offsets[0][0], offsets[0][1], offsets[0][2] } };
  for (const auto& o : offsets)
    for (int a = 0; a < 3; ++a)
      low[a] = std::min(low[a], o[a]);
  Stencil s;
  s.Name = name;
  for (auto o : offsets)
  {
    for (int a = 0; a < 3; ++a)
    {
      o[a] -= low[a];
      s.Extent[a] = std::max(s.Extent[a], o[a] + 1);
    }
    s.Offsets.push_back(o);
  }
  std::sort(s.Offsets.begin(), s.Offsets.end());
  if (std::adjacent_find(s.Offsets.begin(), s.Offsets.end()) != s.Offsets.end())
    throw BadShape(name, "an offset is given twice");
  for (int a = 0; a < 3; ++a)
    if (s.Extent[a] > MaxStencilExtent)
      throw BadShape(name, "it spans more than 64 sites along an axis");
  return s;
}

Stencil Box(const std::string& name, int nx, int ny, int nz)
{
  std::vector<std::array<int, 3>> offsets;
  for (int z = 0; z < nz; ++z)
    for (int y = 0; y < ny; ++y)
      for (int x = 0; x < nx; ++x)
        offsets.push_back({ { x, y, z } });
  if (static_cast<int>(offsets.size()) > MaxStencilSites)
    throw BadShape(name, "it has more than 64 sites");
  return Normalised(name, std::move(offsets));
}

} // namespace

Stencil ParseStencil(const std::string& text)
{
  if (text.empty())
    throw BadShape(text, "it is empty");
  if (text.find(':') != std::string::npos)
  {
    std::vector<std::array<int, 3>> offsets;
    for (const std::string& point : SplitText(text, '+'))
    {
      const std::vector<std::string> c = SplitText(point, ':');
      if (c.size() != 2 && c.size() != 3)
        throw BadShape(text, "'" + point + "' is not an offset x:y or x:y:z");
      offsets.push_back({ { ParseOffset(text, c[0]), ParseOffset(text, c[1]),
        c.size() == 3 ? ParseOffset(text, c[2]) : 0 } });
      if (static_cast<int>(offsets.size()) > MaxStencilSites)
        throw BadShape(text, "it has more than 64 sites");
    }
    return Normalised(text, std::move(offsets));
  }
  const char last = static_cast<char>(std::toupper(static_cast<unsigned char>(text.back())));
  if (last == 'H' || last == 'V' || last == 'D')
  {
    const int n = ParseCount(text, text.substr(0, text.size() - 1), 1);
    std::string name = text;
    name.back() = last;
    return Box(name, last == 'H' ? n : 1, last == 'V' ? n : 1, last == 'D' ? n : 1);
  }
  std::string lower = text;
  std::transform(lower.begin(), lower.end(), lower.begin(),
    [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  const std::vector<std::string> sizes = SplitText(lower, 'x');
  if (sizes.size() == 2 || sizes.size() == 3)
  {
    const int nx = ParseCount(text, sizes[0], 1);
    const int ny = ParseCount(text, sizes[1], 1);
    const int nz = sizes.size() == 3 ? ParseCount(text, sizes[2], 1) : 1;
    return Box(lower, nx, ny, nz);
  }
  throw BadShape(text, "expected NH, NV, ND, AxB, AxBxC or offsets such as 0:0+1:0+1:1");
}

std::string SoftShapes(const std::string& factors)
{
  std::string soft;
  for (const Stencil& s : ParseStencils(factors))
  {
    if (s.Offsets.size() == 2 && (s.Name == "2H" || s.Name == "2V" || s.Name == "2D"))
      continue;
    soft += (soft.empty() ? "" : ",") + s.Name;
  }
  return soft;
}

std::vector<Stencil> ParseStencils(const std::string& list)
{
  std::vector<Stencil> shapes;
  for (const std::string& item : SplitText(list, ','))
    if (!item.empty())
      shapes.push_back(ParseStencil(item));
  return shapes;
}

std::vector<Stencil> BlockScheme(int scheme, bool threeD)
{
  if (scheme < 1 || scheme > 6)
    throw Error("block scheme B" + std::to_string(scheme) + ": schemes are B1 to B6");
  static const char* const names2D[6][2] = { { "1H", nullptr }, { "2H", "2V" }, { "2x2", nullptr },
    { "3H", "3V" }, { "3x3", nullptr }, { "4H", "4V" } };
  static const char* const names3D[6] = { nullptr, "2D", "2x2x2", "3D", "3x3x3", "4D" };
  std::vector<Stencil> shapes;
  for (int k = 0; k < scheme; ++k)
  {
    for (const char* name : names2D[k])
      if (name)
        shapes.push_back(ParseStencil(name));
    if (threeD && names3D[k])
      shapes.push_back(ParseStencil(names3D[k]));
  }
  shapes[0].Name = "1x1";
  return shapes;
}

namespace
{

bool Fits(const Stencil& s, const LabelGrid& g)
{
  for (int a = 0; a < 3; ++a)
    if (s.Extent[a] > g.Size(a))
      return false;
  return true;
}

/// Calls @p f(tiles) with the tile indices under @p s at every anchor where it fits in @p g.
template <typename F>
void ForEachConfiguration(const LabelGrid& g, const Stencil& s, const FactorModel& m, F&& f)
{
  if (!Fits(s, g))
    return;
  std::vector<std::int32_t> tiles(s.Offsets.size());
  const auto& d = g.Dimensions();
  for (std::int64_t z = 0; z + s.Extent[2] <= d[2]; ++z)
    for (std::int64_t y = 0; y + s.Extent[1] <= d[1]; ++y)
      for (std::int64_t x = 0; x + s.Extent[0] <= d[0]; ++x)
      {
        for (std::size_t k = 0; k < s.Offsets.size(); ++k)
        {
          const auto& o = s.Offsets[k];
          tiles[k] = m.TileIndex(g.At(x + o[0], y + o[1], z + o[2]));
        }
        f(tiles);
      }
}

} // namespace

FactorModel LearnFactors(const std::vector<LabelGrid>& exemplars,
  const std::vector<Stencil>& softShapes, const std::vector<Stencil>& blockShapes,
  const LabelPairs& extra)
{
  if (exemplars.empty() && extra[0].empty() && extra[1].empty() && extra[2].empty())
    throw Error("pattern synthesis needs at least one exemplar or a tileset");
  FactorModel m;
  m.NumberOfExemplars = static_cast<int>(exemplars.size());
  {
    std::set<Label> values;
    for (const LabelGrid& g : exemplars)
    {
      values.insert(g.Data().begin(), g.Data().end());
      if (values.size() > 65536)
        throw Error("the exemplars hold more than 65536 distinct labels");
    }
    for (const auto& pairs : extra)
      for (const auto& [b, c] : pairs)
      {
        values.insert(b);
        values.insert(c);
      }
    if (values.size() > 65536)
      throw Error("the exemplars and the tileset hold more than 65536 distinct labels");
    m.Tiles.assign(values.begin(), values.end());
  }
  const std::size_t t = m.Tiles.size();
  for (int a = 0; a < 3; ++a)
  {
    m.Pairs[a].assign(t * t, 0);
    for (const auto& [b, c] : extra[ToIndex(a)])
    {
      m.Pairs[a][ToIndex(m.TileIndex(b)) * t + ToIndex(m.TileIndex(c))] = 1;
      m.AxisSeen[a] = true;
    }
    for (const LabelGrid& g : exemplars)
    {
      if (g.Size(a) < 2)
        continue;
      m.AxisSeen[a] = true;
      const auto& d = g.Dimensions();
      for (std::int64_t z = 0; z < d[2]; ++z)
        for (std::int64_t y = 0; y < d[1]; ++y)
          for (std::int64_t x = 0; x < d[0]; ++x)
          {
            std::int64_t q[3] = { x, y, z };
            ++q[a];
            if (!g.Contains(q[0], q[1], q[2]))
              continue;
            const auto b = ToIndex(m.TileIndex(g.At(x, y, z)));
            const auto c = ToIndex(m.TileIndex(g.At(q[0], q[1], q[2])));
            m.Pairs[a][b * t + c] = 1;
          }
    }
  }
  m.SoftShapes = softShapes;
  for (const Stencil& s : softShapes)
  {
    std::vector<std::unordered_set<std::uint64_t>> perExemplar(exemplars.size());
    for (std::size_t e = 0; e < exemplars.size(); ++e)
      ForEachConfiguration(exemplars[e], s, m,
        [&](const std::vector<std::int32_t>& tiles)
        { perExemplar[e].insert(ConfigurationKey(tiles.data(), tiles.size())); });
    m.Observed.push_back(std::move(perExemplar));
  }
  for (const Stencil& b : blockShapes)
  {
    std::set<std::vector<std::int32_t>> distinct;
    for (const LabelGrid& g : exemplars)
      ForEachConfiguration(
        g, b, m, [&](const std::vector<std::int32_t>& tiles) { distinct.insert(tiles); });
    if (b.Offsets.size() == 1)
      for (std::int32_t k = 0; k < static_cast<std::int32_t>(t); ++k)
        distinct.insert({ k });
    if (distinct.empty())
      continue;
    std::vector<std::int32_t> flat;
    flat.reserve(distinct.size() * b.Offsets.size());
    for (const auto& tiles : distinct)
      flat.insert(flat.end(), tiles.begin(), tiles.end());
    m.BlockShapes.push_back(b);
    m.BlockTiles.push_back(std::move(flat));
  }
  if (m.BlockShapes.empty())
    throw Error("no replacement block shape fits in any exemplar (give single tiles, 1x1)");
  return m;
}

} // namespace msynth
