// SPDX-License-Identifier: BSD-3-Clause
// The independent check of a composed voxel model (VoxelTileset.h: CheckVoxelModel). It shares
// no code with the voxel tileset reader: no symmetry matrices, no labels, no pair tables. The
// tiles' images and the rules' configurations are closed under the generators applied as the
// format states them (source lookups on voxel arrays), and the model is compared by voxels.
#include "Formats/VoxelTileset.h"

#include "Core/Error.h"
#include "Core/Index.h"
#include "Formats/VoxModel.h"
#include "Formats/Xml.h"

#include <cctype>
#include <fstream>
#include <iterator>
#include <map>
#include <set>
#include <sstream>
#include <tuple>

namespace msynth
{
namespace
{
using Voxels = std::vector<std::uint32_t>;
using Key = std::string; // the voxels' bytes

Key KeyOf(const Voxels& v)
{
  return Key(reinterpret_cast<const char*>(v.data()), v.size() * sizeof(std::uint32_t));
}

std::uint32_t Pack(const std::array<std::uint8_t, 4>& c)
{
  return std::uint32_t(c[0]) | (std::uint32_t(c[1]) << 8) | (std::uint32_t(c[2]) << 16) |
    0xff000000u;
}

/// The generators as the format states them: the image's voxel (x, y, z) is the tile's voxel
/// at the formula's coordinates. 'z', 'y', 'x' quarter turns, 'm' the mirror x -> S-1-x.
Voxels Apply(const Voxels& v, int s, int sz, char op)
{
  Voxels out(v.size());
  for (int z = 0; z < sz; ++z)
    for (int y = 0; y < s; ++y)
      for (int x = 0; x < s; ++x)
      {
        int a = x, b = y, c = z;
        if (op == 'z')
        {
          a = y;
          b = s - 1 - x;
        }
        else if (op == 'y')
        {
          a = z;
          c = s - 1 - x;
        }
        else if (op == 'x')
        {
          b = z;
          c = s - 1 - y;
        }
        else
          a = s - 1 - x;
        out[ToIndex(x + s * (y + s * z))] = v[ToIndex(a + s * (b + s * c))];
      }
  return out;
}

/// Where a displacement between two tiles goes under the generator.
std::array<int, 3> Move(const std::array<int, 3>& d, char op)
{
  switch (op)
  {
    case 'z':
      return { { -d[1], d[0], d[2] } };
    case 'y':
      return { { -d[2], d[1], d[0] } };
    case 'x':
      return { { d[0], -d[2], d[1] } };
    default:
      return { { -d[0], d[1], d[2] } };
  }
}

using Configuration = std::tuple<int, int, int>; // axis, image at the origin, image at +axis

class Checker
{
public:
  Checker(const std::string& xmlPath, const std::string& tiles)
  {
    std::ifstream in(xmlPath, std::ios::binary);
    if (!in)
      throw Error::InFile(xmlPath, "cannot be opened for reading (missing or unreadable)");
    std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    if (text.size() > (std::size_t(1) << 24))
      throw Error::InFile(xmlPath, "is larger than 16 MiB, too large for a tileset");
    detail::XmlReader xml(std::move(text), xmlPath);
    const detail::XmlElement root = xml.Parse();
    if (root.Name != "tileset")
      xml.Fail("the top-level element is <" + root.Name + ">, not <tileset>", root.Line);
    const std::string* full = root.Attribute("fullSymmetry");
    this->Generators = full && (*full == "True" || *full == "true") ? "zym" : "zm";
    const std::string folder = VoxelTilesFolder(xmlPath, tiles);
    for (const auto& list : root.Children)
      if (list.Name == "tiles")
        for (const auto& t : list.Children)
          if (t.Name == "tile" && t.Attribute("name"))
            this->ReadTile(*t.Attribute("name"), folder + "/" + *t.Attribute("name") + ".vox");
    for (const auto& list : root.Children)
      if (list.Name == "neighbors")
        for (const auto& n : list.Children)
          if (n.Name == "neighbor")
            this->AddRule(xml, n);
  }

  int S = 0, SZ = 0;
  std::map<Key, std::string> Images; ///< every image of every tile, and the tile's name
  std::set<Configuration> Allowed;   ///< by the index of the images' keys (Index)

  /// The index of an image's key (a new index for an image not seen before).
  int Index(const Key& key)
  {
    const auto it = this->Indices.emplace(key, static_cast<int>(this->Indices.size())).first;
    if (this->Indices.size() > 1000000)
      throw Error("the tileset's images and rules make more than a million tile images");
    return it->second;
  }
  /// The index of a key, or -1.
  int Find(const Key& key) const
  {
    const auto it = this->Indices.find(key);
    return it == this->Indices.end() ? -1 : it->second;
  }

private:
  void ReadTile(const std::string& name, const std::string& file)
  {
    const VoxModel vox = ReadVoxModelFile(file, std::int64_t(1) << 21);
    const auto& d = vox.Grid.Dimensions();
    if (this->S == 0)
    {
      this->S = static_cast<int>(d[0]);
      this->SZ = static_cast<int>(d[2]);
    }
    if (d[0] != this->S || d[1] != this->S || d[2] != this->SZ ||
      (this->Generators.size() == 3 && this->S != this->SZ))
      throw Error::InFile(file, "does not have the tileset's tile size");
    Voxels v;
    for (std::int64_t z = 0; z < d[2]; ++z)
      for (std::int64_t y = 0; y < d[1]; ++y)
        for (std::int64_t x = 0; x < d[0]; ++x)
        {
          const Label i = vox.Grid.At(x, y, z);
          v.push_back(i == 0 ? 0u : Pack(vox.Palette[ToIndex(i)]));
        }
    this->Tiles[name] = v;
    std::vector<Voxels> queue{ v };
    this->Images.emplace(KeyOf(v), name);
    this->Index(KeyOf(v));
    for (std::size_t i = 0; i < queue.size(); ++i)
      for (const char op : this->Generators)
      {
        Voxels image = Apply(queue[i], this->S, this->SZ, op);
        if (this->Images.emplace(KeyOf(image), name).second)
        {
          this->Index(KeyOf(image));
          this->Bytes += image.size() * sizeof(std::uint32_t);
          if (this->Bytes > (std::size_t(1) << 28))
            throw Error::InFile(file, "makes the tiles' images larger than 256 MB");
          queue.push_back(std::move(image));
        }
      }
  }

  Voxels Side(const detail::XmlReader& xml, const detail::XmlElement& n, const char* side) const
  {
    const std::string* ref = n.Attribute(side);
    if (!ref)
      xml.Fail(std::string("a <neighbor> has no '") + side + "'", n.Line);
    std::istringstream words(*ref);
    std::string a, b;
    words >> a >> b;
    const std::string& name = b.empty() ? a : b;
    const auto tile = this->Tiles.find(name);
    if (tile == this->Tiles.end())
      xml.Fail("a <neighbor> names tile '" + name + "', which is not defined", n.Line);
    Voxels v = tile->second;
    if (!b.empty())
      for (std::size_t i = a.size(); i-- > 0;) // right to left
      {
        if (a[i] != 'x' && a[i] != 'y' && a[i] != 'z')
          xml.Fail("'" + *ref + "': unknown turn '" + a.substr(i, 1) + "'", n.Line);
        if (a[i] != 'z' && this->S != this->SZ)
          xml.Fail("'" + *ref + "': tiles that are not cubes turn about z only", n.Line);
        v = Apply(v, this->S, this->SZ, a[i]);
      }
    return v;
  }

  void AddRule(const detail::XmlReader& xml, const detail::XmlElement& n)
  {
    const bool sideways = n.Attribute("left") != nullptr;
    Voxels first = this->Side(xml, n, sideways ? "left" : "bottom");
    Voxels second = this->Side(xml, n, sideways ? "right" : "top");
    // The configuration (first at 0, second at d) under every product of the generators.
    struct State
    {
      std::array<int, 3> D;
      Voxels First, Second;
    };
    std::vector<State> queue{ { { { sideways ? 1 : 0, 0, sideways ? 0 : 1 } }, first, second } };
    std::set<std::tuple<std::array<int, 3>, int, int>> seen;
    seen.emplace(queue[0].D, this->Index(KeyOf(first)), this->Index(KeyOf(second)));
    for (std::size_t i = 0; i < queue.size(); ++i)
    {
      const State s = queue[i];
      const int axis = s.D[0] != 0 ? 0 : (s.D[1] != 0 ? 1 : 2);
      const int a = this->Index(KeyOf(s.First)), b = this->Index(KeyOf(s.Second));
      if (s.D[ToIndex(axis)] > 0)
        this->Allowed.emplace(axis, a, b);
      else
        this->Allowed.emplace(axis, b, a);
      for (const char op : this->Generators)
      {
        State t{ Move(s.D, op), Apply(s.First, this->S, this->SZ, op),
          Apply(s.Second, this->S, this->SZ, op) };
        if (seen.emplace(t.D, this->Index(KeyOf(t.First)), this->Index(KeyOf(t.Second))).second)
          queue.push_back(std::move(t));
      }
    }
  }

  std::string Generators;
  std::map<std::string, Voxels> Tiles;
  std::map<Key, int> Indices;
  std::size_t Bytes = 0; ///< of the images
};

std::string Cell(std::int64_t x, std::int64_t y, std::int64_t z)
{
  return "(" + std::to_string(x) + ", " + std::to_string(y) + ", " + std::to_string(z) + ")";
}
} // namespace

VoxelCheckReport CheckVoxelModel(const std::string& xmlPath, const std::string& tiles,
  const LabelGrid& model, const std::vector<std::array<std::uint8_t, 4>>& palette)
{
  Checker rules(xmlPath, tiles);
  VoxelCheckReport report;
  const auto problem = [&report](const std::string& line)
  {
    ++report.Problems;
    if (report.First.size() < 10)
      report.First.push_back(line);
  };
  const auto& d = model.Dimensions();
  const std::int64_t s[3] = { rules.S, rules.S, rules.SZ };
  if (s[0] == 0 || d[0] % s[0] || d[1] % s[1] || d[2] % s[2])
  {
    problem("the model is " + std::to_string(d[0]) + " x " + std::to_string(d[1]) + " x " +
      std::to_string(d[2]) + " voxels, not a whole number of " + std::to_string(s[0]) + " x " +
      std::to_string(s[1]) + " x " + std::to_string(s[2]) + " tiles");
    return report;
  }
  const std::int64_t n[3] = { d[0] / s[0], d[1] / s[1], d[2] / s[2] };
  // Each cell as the index of its tile image (-1: none) and that tile's name.
  std::vector<int> cells;
  std::map<int, std::string> names;
  for (std::int64_t z = 0; z < n[2]; ++z)
    for (std::int64_t y = 0; y < n[1]; ++y)
      for (std::int64_t x = 0; x < n[0]; ++x)
      {
        Voxels v;
        for (std::int64_t k = 0; k < s[2]; ++k)
          for (std::int64_t j = 0; j < s[1]; ++j)
            for (std::int64_t i = 0; i < s[0]; ++i)
            {
              const Label p = model.At(x * s[0] + i, y * s[1] + j, z * s[2] + k);
              v.push_back(p <= 0 || ToIndex(p) >= palette.size() ? 0u : Pack(palette[ToIndex(p)]));
            }
        const Key key = KeyOf(v);
        const auto image = rules.Images.find(key);
        cells.push_back(image == rules.Images.end() ? -1 : rules.Find(key));
        if (image == rules.Images.end())
          problem("tile cell " + Cell(x, y, z) + " is no image of any tile");
        else
          names[cells.back()] = image->second;
        ++report.Cells;
      }
  const char* axes = "xyz";
  for (std::int64_t z = 0; z < n[2]; ++z)
    for (std::int64_t y = 0; y < n[1]; ++y)
      for (std::int64_t x = 0; x < n[0]; ++x)
        for (int a = 0; a < 3; ++a)
        {
          const std::int64_t c[3] = { x + (a == 0), y + (a == 1), z + (a == 2) };
          if (c[a] >= n[a])
            continue;
          const int first = cells[ToIndex(x + n[0] * (y + n[1] * z))];
          const int second = cells[ToIndex(c[0] + n[0] * (c[1] + n[1] * c[2]))];
          ++report.PairsChecked;
          if (first < 0 || second < 0)
            continue; // reported above
          if (!rules.Allowed.count(Configuration(a, first, second)))
            problem("tile cells " + Cell(x, y, z) + " (" + names[first] + ") and " +
              Cell(c[0], c[1], c[2]) + " (" + names[second] + ") along +" + axes[a] +
              ": no rule allows this pair");
        }
  report.Valid = report.Problems == 0;
  return report;
}

} // namespace msynth
