// SPDX-License-Identifier: BSD-3-Clause
#include "vtkMSLabelCounts.h"

#include "vtkFieldData.h"
#include "vtkIdTypeArray.h"
#include "vtkNew.h"
#include "vtkStringArray.h"

#include "Core/Error.h"
#include "Core/Index.h"
#include "Core/TextLists.h"
#include "Formats/Tileset.h"

#include <array>
#include <limits>

namespace vtkMSLabelCounts
{
namespace
{
/// "; its tiles: A, B, ..." (the first twenty names), what a name may be.
std::string TileNames(const msynth::Tileset& tiles)
{
  std::string text = "; its tiles: ";
  const std::size_t most = 20;
  for (std::size_t i = 0; i < tiles.Tiles.size() && i < most; ++i)
    text += (i ? ", " : "") + msynth::Printable(tiles.Tiles[i].Name);
  if (tiles.Tiles.size() > most)
    text += ", ... (" + std::to_string(tiles.Tiles.size()) + " in all)";
  return text;
}
} // namespace

std::vector<msynth::LabelCount> Read(const std::string& text, const msynth::Tileset* tiles)
{
  std::vector<msynth::LabelCount> counts;
  for (const msynth::CountEntry& e : msynth::ParseCountEntries(text, "Counts"))
  {
    msynth::LabelCount c;
    c.Name = e.Name;
    c.Minimum = e.Minimum;
    c.Maximum = e.Maximum;
    long long value = 0;
    const std::string prefix = "region=";
    if (c.Name.compare(0, prefix.size(), prefix) == 0) // region=R:L:MIN:MAX
    {
      const std::size_t colon = c.Name.find(':');
      if (colon == std::string::npos ||
        !msynth::ParseInteger(c.Name.substr(prefix.size(), colon - prefix.size()), 0,
          std::numeric_limits<std::int32_t>::max(), value))
        throw msynth::Error("Counts: '" + msynth::Printable(e.Name) +
          "' is not region=R:L with R a guide region number (0 or more)");
      c.Region = static_cast<std::int32_t>(value);
      c.Name = c.Name.substr(colon + 1);
    }
    if (msynth::ParseInteger(c.Name, std::numeric_limits<msynth::Label>::min(),
          std::numeric_limits<msynth::Label>::max(), value))
      c.Values.push_back(static_cast<msynth::Label>(value));
    else if (tiles)
    {
      for (int b = 0; b < tiles->NumberOfLabels(); ++b)
      {
        const auto& tile = tiles->Tiles[msynth::ToIndex(tiles->LabelTile[msynth::ToIndex(b)])];
        if (tile.Name == c.Name || tiles->LabelName(b) == c.Name)
          c.Values.push_back(b);
      }
      if (c.Values.empty())
        throw msynth::Error("Counts: the tileset has no tile or label named '" +
          msynth::Printable(c.Name) + "'" + TileNames(*tiles));
    }
    else
      throw msynth::Error(
        "Counts: '" + msynth::Printable(c.Name) + "' is not a label value (names need a tileset)");
    counts.push_back(c);
  }
  return counts;
}

namespace
{
/// The label values @p item names: a value, or with @p tiles a tile's or a label's name.
std::vector<msynth::Label> NamedLabels(const std::string& item, const msynth::Tileset* tiles)
{
  std::vector<msynth::Label> values;
  long long value = 0;
  if (msynth::ParseInteger(item, std::numeric_limits<msynth::Label>::min(),
        std::numeric_limits<msynth::Label>::max(), value))
    values.push_back(static_cast<msynth::Label>(value));
  else if (tiles)
    for (int b = 0; b < tiles->NumberOfLabels(); ++b)
    {
      const auto& tile = tiles->Tiles[msynth::ToIndex(tiles->LabelTile[msynth::ToIndex(b)])];
      if (tile.Name == item || tiles->LabelName(b) == item)
        values.push_back(b);
    }
  return values;
}

/// @p text with the blanks around it removed.
std::string Trimmed(const std::string& text)
{
  const std::size_t first = text.find_first_not_of(" \t");
  return first == std::string::npos ? std::string()
                                    : text.substr(first, text.find_last_not_of(" \t") - first + 1);
}

/// The path of @p text ("A;B;...": sites "x,y[,z]" or labels) into @p network.
void ReadPath(
  const std::string& text, const msynth::Tileset* tiles, msynth::ConnectedNetwork& network)
{
  for (const std::string& raw : msynth::SplitText(text, ';'))
  {
    const std::string item = Trimmed(raw);
    if (item.empty())
      continue;
    const std::vector<std::string> parts = msynth::SplitText(item, ',');
    std::array<std::int64_t, 3> site{ { 0, 0, 0 } };
    bool isSite = parts.size() == 2 || parts.size() == 3;
    for (std::size_t a = 0; isSite && a < parts.size(); ++a)
    {
      long long v = 0;
      isSite = msynth::ParseInteger(Trimmed(parts[a]), -(1LL << 40), 1LL << 40, v);
      site[a] = v;
    }
    if (isSite)
    {
      network.PathSites.push_back(site);
      continue;
    }
    const std::vector<msynth::Label> values = NamedLabels(item, tiles);
    if (values.empty())
      throw msynth::Error("Path: '" + msynth::Printable(item) +
        "' is neither a site x,y[,z] nor a label value" +
        (tiles ? " or a tile or label name of the tileset" + TileNames(*tiles)
               : " (names need a tileset)"));
    network.PathLabels.insert(network.PathLabels.end(), values.begin(), values.end());
  }
}
} // namespace

msynth::ConnectedNetwork ReadConnected(
  const std::string& text, const msynth::Tileset* tiles, const std::string& path)
{
  msynth::ConnectedNetwork network;
  std::string list = text;
  const std::size_t colon = list.rfind(':');
  long long most = 1;
  if (colon != std::string::npos && list.find(':') != colon)
    throw msynth::Error("Connected: '" + msynth::Printable(text) +
      "' names more than one network; give one, LABELS[:N] (the labels separated by commas)");
  if (colon != std::string::npos && list.substr(colon + 1) == "open")
  {
    network.Open = true; // a world's meaning: no component closed off (Connectivity.h)
    list = list.substr(0, colon);
  }
  else if (colon != std::string::npos)
  {
    if (!msynth::ParseInteger(list.substr(colon + 1), 1, std::numeric_limits<int>::max(), most))
      throw msynth::Error("Connected: '" + msynth::Printable(list.substr(colon + 1)) +
        "' is not a number of components (1 or more) nor 'open'");
    list = list.substr(0, colon);
  }
  network.Maximum = most;
  for (std::string item : msynth::SplitText(list, ','))
  {
    const std::size_t first = item.find_first_not_of(" \t");
    if (first == std::string::npos)
      continue;
    item = item.substr(first, item.find_last_not_of(" \t") - first + 1);
    const std::size_t before = network.Values.size();
    const std::vector<msynth::Label> values = NamedLabels(item, tiles);
    network.Values.insert(network.Values.end(), values.begin(), values.end());
    if (network.Values.size() == before)
      throw msynth::Error("Connected: '" + msynth::Printable(item) +
        (tiles ? "' is neither a label value nor a tile or label name of the tileset" +
              TileNames(*tiles)
               : "' is not a label value (names need a tileset)"));
    network.Name += (network.Name.empty() ? "" : ",") + item;
  }
  if (!network.Values.empty() && tiles)
    for (msynth::Label v : network.Values)
    {
      const auto b = msynth::ToIndex(v);
      if (b < tiles->LabelSides.size() && tiles->LabelSides[b] >= 0)
        network.Sides[v] = static_cast<std::uint8_t>(tiles->LabelSides[b]);
    }
  ReadPath(path, tiles, network);
  return network;
}

void AddConnectedFields(vtkFieldData* fd, const msynth::ConnectedResult& connected)
{
  if (!connected.Requested)
    return;
  vtkNew<vtkStringArray> names;
  names->SetName("ConnectedLabels");
  names->InsertNextValue(connected.Name);
  fd->AddArray(names);
  const std::pair<const char*, std::int64_t> values[] = { { "ConnectedMaximum", connected.Maximum },
    { "ConnectedComponents", connected.Components }, { "ConnectedBefore", connected.Before },
    { "ConnectedRepairs", connected.Repairs }, { "ConnectedRedone", connected.Redone },
    { "ConnectedPathSites", connected.PathSites } };
  for (const auto& [name, value] : values)
  {
    vtkNew<vtkIdTypeArray> a;
    a->SetName(name);
    a->InsertNextValue(static_cast<vtkIdType>(value));
    fd->AddArray(a);
  }
}

void AddFields(vtkFieldData* fd, const std::vector<msynth::LabelCountResult>& counts)
{
  if (counts.empty())
    return;
  vtkNew<vtkStringArray> names;
  names->SetName("CountNames");
  vtkNew<vtkIdTypeArray> minimum, maximum, achieved, region;
  region->SetName("CountRegion");
  minimum->SetName("CountMinimum");
  maximum->SetName("CountMaximum");
  achieved->SetName("CountAchieved");
  for (const msynth::LabelCountResult& r : counts)
  {
    names->InsertNextValue(r.Requested.Name);
    minimum->InsertNextValue(static_cast<vtkIdType>(r.Requested.Minimum));
    maximum->InsertNextValue(static_cast<vtkIdType>(r.Requested.Maximum));
    achieved->InsertNextValue(static_cast<vtkIdType>(r.Achieved));
    region->InsertNextValue(static_cast<vtkIdType>(r.Requested.Region));
  }
  fd->AddArray(names);
  fd->AddArray(minimum);
  fd->AddArray(maximum);
  fd->AddArray(achieved);
  fd->AddArray(region);
}

} // namespace vtkMSLabelCounts
