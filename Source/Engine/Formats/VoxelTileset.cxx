// SPDX-License-Identifier: BSD-3-Clause
#include "Formats/VoxelTileset.h"

#include "Core/Error.h"
#include "Core/Index.h"
#include "Core/Memory.h"
#include "Formats/VoxModel.h"
#include "Formats/Xml.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <dirent.h>
#include <set>
#include <sstream>
#include <sys/stat.h>

namespace msynth
{

CubeSymmetry CubeSymmetry::QuarterTurn(int axis)
{
  CubeSymmetry s;
  if (axis == 2) // (x, y, z) <- (y, S-1-x, z)
    s.M = { { { { 0, 1, 0 } }, { { -1, 0, 0 } }, { { 0, 0, 1 } } } };
  else if (axis == 1) // (x, y, z) <- (z, y, S-1-x)
    s.M = { { { { 0, 0, 1 } }, { { 0, 1, 0 } }, { { -1, 0, 0 } } } };
  else // (x, y, z) <- (x, z, S-1-y)
    s.M = { { { { 1, 0, 0 } }, { { 0, 0, 1 } }, { { 0, -1, 0 } } } };
  return s;
}

CubeSymmetry CubeSymmetry::MirrorX()
{
  CubeSymmetry s;
  s.M[0][0] = -1;
  return s;
}

CubeSymmetry CubeSymmetry::Then(const CubeSymmetry& first, const CubeSymmetry& second)
{
  // second(first(V))(d) = first(V)(M2 d) = V(M1 M2 d).
  CubeSymmetry s;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
    {
      int sum = 0;
      for (int k = 0; k < 3; ++k)
        sum += first.M[i][k] * second.M[k][j];
      s.M[i][j] = sum;
    }
  return s;
}

int CubeSymmetry::MapsAxis(int axis) const
{
  // A voxel at p of the tile appears at M^T p in the image, and so does the displacement +axis.
  for (int i = 0; i < 3; ++i)
    if (this->M[axis][i] != 0)
      return this->M[axis][i] > 0 ? 1 + i : -1 - i;
  return 0;
}

const std::vector<CubeSymmetry>& SymmetryGroup(bool full)
{
  static const std::vector<CubeSymmetry> square = []()
  {
    std::vector<CubeSymmetry> g;
    for (int mirror = 0; mirror < 2; ++mirror)
    {
      CubeSymmetry s = mirror ? CubeSymmetry::MirrorX() : CubeSymmetry();
      for (int k = 0; k < 4; ++k)
      {
        g.push_back(s);
        s = CubeSymmetry::Then(s, CubeSymmetry::QuarterTurn(2));
      }
    }
    return g;
  }();
  static const std::vector<CubeSymmetry> cube = []()
  {
    std::vector<CubeSymmetry> g = square;
    const CubeSymmetry generators[3] = { CubeSymmetry::QuarterTurn(2), CubeSymmetry::QuarterTurn(1),
      CubeSymmetry::MirrorX() };
    for (std::size_t i = 0; i < g.size(); ++i) // closure, in breadth-first order
      for (const auto& gen : generators)
      {
        const CubeSymmetry s = CubeSymmetry::Then(g[i], gen);
        if (std::find(g.begin(), g.end(), s) == g.end())
          g.push_back(s);
      }
    return g;
  }();
  return full ? cube : square;
}

int SymmetryIndex(bool full, const CubeSymmetry& s)
{
  const auto& g = SymmetryGroup(full);
  const auto it = std::find(g.begin(), g.end(), s);
  return it == g.end() ? -1 : static_cast<int>(it - g.begin());
}

bool ParseTurns(const std::string& prefix, CubeSymmetry& out)
{
  out = CubeSymmetry();
  for (std::size_t i = prefix.size(); i-- > 0;)
  {
    const char c = prefix[i];
    if (c < 'x' || c > 'z')
      return false;
    out = CubeSymmetry::Then(out, CubeSymmetry::QuarterTurn(c - 'x'));
  }
  return true;
}

VoxelBlock TransformVoxels(const VoxelBlock& tile, const CubeSymmetry& s)
{
  VoxelBlock out;
  // Source axis j reads destination axis i where M[j][i] != 0 (reversed when negative).
  int axis[3] = { 0, 0, 0 }, sign[3] = { 1, 1, 1 };
  for (int j = 0; j < 3; ++j)
    for (int i = 0; i < 3; ++i)
      if (s.M[j][i] != 0)
      {
        axis[j] = i;
        sign[j] = s.M[j][i];
        out.Size[ToIndex(i)] = tile.Size[ToIndex(j)];
      }
  out.Voxels.resize(tile.Voxels.size());
  const int nx = out.Size[0], ny = out.Size[1], nz = out.Size[2];
  std::size_t n = 0;
  for (int z = 0; z < nz; ++z)
    for (int y = 0; y < ny; ++y)
      for (int x = 0; x < nx; ++x, ++n)
      {
        const int d[3] = { x, y, z };
        int src[3];
        for (int j = 0; j < 3; ++j)
        {
          const int v = d[axis[j]];
          src[j] = sign[j] > 0 ? v : tile.Size[ToIndex(j)] - 1 - v;
        }
        out.Voxels[n] =
          tile.Voxels[ToIndex(src[0] + tile.Size[0] * (src[1] + tile.Size[1] * src[2]))];
      }
  return out;
}

std::array<std::uint8_t, 4> UnpackColour(std::uint32_t c)
{
  return { { static_cast<std::uint8_t>(c & 255), static_cast<std::uint8_t>((c >> 8) & 255),
    static_cast<std::uint8_t>((c >> 16) & 255), static_cast<std::uint8_t>(c >> 24) } };
}

VoxelBlock ReadVoxelBlock(const std::string& path)
{
  const VoxModel vox = ReadVoxModelFile(path, std::int64_t(1) << 21);
  VoxelBlock block;
  const auto& d = vox.Grid.Dimensions();
  for (int a = 0; a < 3; ++a)
    block.Size[ToIndex(a)] = static_cast<int>(d[ToIndex(a)]);
  block.Voxels.resize(ToIndex(d[0] * d[1] * d[2]));
  std::size_t n = 0;
  for (std::int64_t z = 0; z < d[2]; ++z)
    for (std::int64_t y = 0; y < d[1]; ++y)
      for (std::int64_t x = 0; x < d[0]; ++x, ++n)
      {
        const Label index = vox.Grid.At(x, y, z);
        if (index == 0)
          continue;
        const auto& c = vox.Palette[ToIndex(index)];
        block.Voxels[n] = std::uint32_t(c[0]) | (std::uint32_t(c[1]) << 8) |
          (std::uint32_t(c[2]) << 16) | (std::uint32_t(255) << 24);
      }
  return block;
}

/// A tile file missing from @p folder whose subfolders hold it (MarkovJunior's Knots3D keeps its
/// tile sets in Knots3D/3, Knots3D/4, ...): an error that names them and how to choose one.
void RefuseMissingTile(const std::string& folder, const std::string& file)
{
  struct stat info;
  if (::stat((folder + "/" + file).c_str(), &info) == 0)
    return;
  std::vector<std::string> holding;
  if (DIR* dir = ::opendir(folder.c_str()))
  {
    while (const dirent* entry = ::readdir(dir))
    {
      const std::string name = entry->d_name;
      if (name != "." && name != ".." &&
        ::stat((folder + "/" + name + "/" + file).c_str(), &info) == 0)
        holding.push_back(name);
    }
    ::closedir(dir);
  }
  if (holding.empty())
    return; // the reader's own message: missing or unreadable
  std::sort(holding.begin(), holding.end());
  std::string list;
  for (std::size_t i = 0; i < holding.size() && i < 12; ++i)
    list += (i ? ", " : "") + holding[i];
  const std::string::size_type slash = folder.rfind('/');
  const std::string base = slash == std::string::npos ? folder : folder.substr(slash + 1);
  throw Error::InFile(folder + "/" + file,
    "is missing; the tileset's folder holds its tiles in the subfolders " + list +
      ": choose one as the tiles folder (msynth --tiles " + base + "/" + holding.front() +
      "; the filters' TilesFolder)");
}

std::string VoxelTilesFolder(const std::string& xmlPath, const std::string& tiles)
{
  if (tiles.empty())
    return TilesetImageFolder(xmlPath);
  struct stat info;
  if (::stat(tiles.c_str(), &info) == 0 || tiles[0] == '/')
    return tiles;
  const std::string::size_type slash = xmlPath.rfind('/');
  const std::string beside =
    (slash == std::string::npos ? std::string(".") : xmlPath.substr(0, slash)) + "/" + tiles;
  return ::stat(beside.c_str(), &info) == 0 ? beside : tiles;
}

LabelGrid ComposeVoxels(const Tileset& set, const LabelGrid& labels,
  std::vector<std::array<std::uint8_t, 4>>& palette, bool skipUnknown)
{
  if (!set.Voxel)
    throw Error("the tileset is not a voxel tileset");
  // The palette: colours in order of first appearance over the labels, the same for every model.
  std::vector<std::uint32_t> colours;
  std::vector<std::vector<Label>> indexed(set.LabelVoxels.size());
  for (std::size_t b = 0; b < set.LabelVoxels.size(); ++b)
    for (const std::uint32_t c : set.LabelVoxels[b])
    {
      Label index = 0;
      if (c != 0)
      {
        auto it = std::find(colours.begin(), colours.end(), c);
        if (it == colours.end())
        {
          if (colours.size() == 255)
            throw Error("the tiles have more than 255 colours, more than a MagicaVoxel palette");
          colours.push_back(c);
          it = colours.end() - 1;
        }
        index = static_cast<Label>(it - colours.begin()) + 1;
      }
      indexed[b].push_back(index);
    }
  palette.assign(256, { { 0, 0, 0, 0 } });
  for (std::size_t i = 0; i < colours.size(); ++i)
    palette[i + 1] = UnpackColour(colours[i]);
  const auto& d = labels.Dimensions();
  const std::int64_t s[3] = { set.VoxelSize[0], set.VoxelSize[1], set.VoxelSize[2] };
  const std::uint64_t bytes =
    static_cast<std::uint64_t>(d[0] * s[0] * d[1] * s[1] * d[2] * s[2]) * sizeof(Label);
  if (bytes > AvailableMemory() / 2 || bytes > (std::uint64_t(1) << 36))
    throw Error("the model's " + std::to_string(d[0] * s[0]) + " x " + std::to_string(d[1] * s[1]) +
      " x " + std::to_string(d[2] * s[2]) + " voxels need " + FormatBytes(bytes) +
      ", more than half the memory available (" + FormatBytes(AvailableMemory()) + ")");
  LabelGrid out(d[0] * s[0], d[1] * s[1], d[2] * s[2], 0);
  for (std::int64_t z = 0; z < d[2]; ++z)
    for (std::int64_t y = 0; y < d[1]; ++y)
      for (std::int64_t x = 0; x < d[0]; ++x)
      {
        const Label b = labels.At(x, y, z);
        if (skipUnknown && (b < 0 || b >= set.NumberOfLabels()))
          continue;
        if (b < 0 || b >= set.NumberOfLabels())
          throw Error("site (" + std::to_string(x) + ", " + std::to_string(y) + ", " +
            std::to_string(z) + ") has label " + std::to_string(b) + ", not one of the " +
            std::to_string(set.NumberOfLabels()) + " tile images");
        const auto& v = indexed[ToIndex(b)];
        std::size_t n = 0;
        for (std::int64_t k = 0; k < s[2]; ++k)
          for (std::int64_t j = 0; j < s[1]; ++j)
            for (std::int64_t i = 0; i < s[0]; ++i, ++n)
              if (v[n] != 0)
                out.Set(x * s[0] + i, y * s[1] + j, z * s[2] + k, v[n]);
      }
  return out;
}

namespace detail
{
namespace
{
/// MarkovJunior's <tileset> read into a Tileset: the tiles' images, then the rules' images.
class VoxelTilesetParser
{
public:
  VoxelTilesetParser(XmlReader& xml, const XmlElement& root, const std::string& name)
    : Xml(xml)
    , Root(root)
    , Name(name)
  {
  }

  Tileset Read(const std::string& tiles)
  {
    this->Set.Voxel = true;
    if (const std::string* full = this->Root.Attribute("fullSymmetry"))
    {
      std::string f = *full;
      for (auto& ch : f)
        ch = static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
      this->Set.FullSymmetry = f == "true";
    }
    this->Set.TilesFolder = VoxelTilesFolder(this->Name, tiles);
    const XmlElement* list = this->Child(this->Root, "tiles");
    if (!list)
      this->Xml.Fail("<tileset> has no <tiles>", this->Root.Line);
    for (const auto& t : list->Children)
      if (t.Name == "tile")
        this->AddTile(t);
    if (this->Set.Tiles.empty())
      this->Xml.Fail("the tileset has no tiles", list->Line);
    std::set<std::uint32_t> colours;
    for (const auto& v : this->Set.LabelVoxels)
      colours.insert(v.begin(), v.end());
    colours.erase(0);
    if (colours.size() > 255)
      this->Xml.Fail("the tiles have " + std::to_string(colours.size()) +
          " colours; a MagicaVoxel model holds at most 255",
        list->Line);
    std::array<std::set<std::pair<int, int>>, 3> pairs;
    if (const XmlElement* neighbors = this->Child(this->Root, "neighbors"))
      for (const auto& n : neighbors->Children)
        if (n.Name == "neighbor")
          this->AddRule(n, pairs);
    for (std::size_t axis = 0; axis < 3; ++axis)
      this->Set.Pairs[axis].assign(pairs[axis].begin(), pairs[axis].end());
    return std::move(this->Set);
  }

private:
  static const XmlElement* Child(const XmlElement& e, const std::string& name)
  {
    for (const auto& c : e.Children)
      if (c.Name == name)
        return &c;
    return nullptr;
  }

  void CheckSize(const VoxelBlock& block, const std::string& file, int line)
  {
    const auto& s = block.Size;
    if (this->Set.Tiles.empty())
    {
      if (s[0] != s[1])
        this->Xml.Fail("tile '" + file + "' is " + std::to_string(s[0]) + " x " +
            std::to_string(s[1]) + " x " + std::to_string(s[2]) + ": tiles are square in x and y",
          line);
      if (this->Set.FullSymmetry && s[2] != s[0])
        this->Xml.Fail("tile '" + file + "' is " + std::to_string(s[0]) + " x " +
            std::to_string(s[1]) + " x " + std::to_string(s[2]) +
            ": with fullSymmetry tiles are cubes",
          line);
      if (s[0] > 128 || s[2] > 128)
        this->Xml.Fail("tile '" + file + "' is larger than 128 voxels a side", line);
      this->Set.VoxelSize = s;
    }
    else if (s != this->Set.VoxelSize)
      this->Xml.Fail("tile '" + file + "' is " + std::to_string(s[0]) + " x " +
          std::to_string(s[1]) + " x " + std::to_string(s[2]) + ", the first tile " +
          std::to_string(this->Set.VoxelSize[0]) + " x " + std::to_string(this->Set.VoxelSize[1]) +
          " x " + std::to_string(this->Set.VoxelSize[2]) + ": all tiles have one size",
        line);
  }

  void AddTile(const XmlElement& t)
  {
    const std::string* tileName = t.Attribute("name");
    if (!tileName || tileName->empty())
      this->Xml.Fail("a <tile> has no name", t.Line);
    for (const auto& other : this->Set.Tiles)
      if (other.Name == *tileName)
        this->Xml.Fail("tile '" + *tileName + "' is defined twice", t.Line);
    if (tileName->find('/') != std::string::npos || *tileName == "..")
      this->Xml.Fail("tile name '" + *tileName + "' is not a file name", t.Line);
    TilesetTile tile;
    tile.Name = *tileName;
    if (const std::string* weight = t.Attribute("weight"))
      if (!ParseTileWeight(*weight, tile.Weight))
        this->Xml.Fail(
          "tile '" + tile.Name + "' has weight '" + *weight + "'; weights are positive numbers",
          t.Line);
    const std::string file = this->Set.TilesFolder + "/" + tile.Name + ".vox";
    RefuseMissingTile(this->Set.TilesFolder, tile.Name + ".vox");
    const VoxelBlock block = ReadVoxelBlock(file);
    this->CheckSize(block, file, t.Line);
    // Bounds on what a file may make us allocate: the labels' rules grow as their square, their
    // voxels as the labels times the tile.
    const auto& groupSize = SymmetryGroup(this->Set.FullSymmetry);
    if (this->Set.NumberOfLabels() + static_cast<int>(groupSize.size()) > 8192)
      this->Xml.Fail("more than 8192 tile images (labels)", t.Line);
    if (static_cast<std::uint64_t>(this->Set.NumberOfLabels() + 48) * block.Voxels.size() >
      (std::uint64_t(1) << 26))
      this->Xml.Fail("the tiles' images would hold more than 2^26 voxels", t.Line);
    tile.FirstLabel = this->Set.NumberOfLabels();
    const auto& group = SymmetryGroup(this->Set.FullSymmetry);
    for (std::size_t g = 0; g < group.size(); ++g)
    {
      const VoxelBlock image = TransformVoxels(block, group[g]);
      int label = -1;
      for (int b = tile.FirstLabel; b < this->Set.NumberOfLabels(); ++b)
        if (this->Set.LabelVoxels[ToIndex(b)] == image.Voxels)
          label = b;
      if (label < 0)
      {
        label = this->Set.NumberOfLabels();
        this->Set.LabelTile.push_back(static_cast<int>(this->Set.Tiles.size()));
        this->Set.LabelOrientation.push_back(static_cast<int>(g));
        this->Set.LabelVoxels.push_back(image.Voxels);
      }
      tile.SymmetryLabels.push_back(label);
    }
    tile.Orientations = this->Set.NumberOfLabels() - tile.FirstLabel;
    this->Blocks.push_back(block);
    this->Set.Tiles.push_back(std::move(tile));
  }

  /// One side of a rule: the tile and the symmetry h whose image of the tile it is.
  void ParseRef(const XmlElement& n, const char* side, int& tileIndex, CubeSymmetry& h) const
  {
    const std::string* ref = n.Attribute(side);
    if (!ref)
      this->Xml.Fail(std::string("a <neighbor> has no '") + side + "'", n.Line);
    std::istringstream words(*ref);
    std::string first, second, extra;
    words >> first >> second >> extra;
    if (first.empty() || !extra.empty())
      this->Xml.Fail("'" + *ref + "' is not 'tile' or 'turns tile' (such as 'zzx Turn')", n.Line);
    const std::string& tileName = second.empty() ? first : second;
    CubeSymmetry turns;
    if (!second.empty() && !ParseTurns(first, turns))
      this->Xml.Fail(
        "'" + *ref + "': turns are quarter turns about x, y or z (letters x, y, z)", n.Line);
    tileIndex = -1;
    for (std::size_t i = 0; i < this->Set.Tiles.size(); ++i)
      if (this->Set.Tiles[i].Name == tileName)
        tileIndex = static_cast<int>(i);
    if (tileIndex < 0)
      this->Xml.Fail("a <neighbor> names tile '" + tileName + "', which is not defined", n.Line);
    h = turns;
    if (SymmetryIndex(this->Set.FullSymmetry, turns) >= 0)
      return;
    // A turn about x or y of a set without fullSymmetry: the image must still be one of the
    // tile's (a tile symmetric enough); then its symmetry stands for it.
    const VoxelBlock& block = this->Blocks[ToIndex(tileIndex)];
    const VoxelBlock image = TransformVoxels(block, turns);
    const TilesetTile& tile = this->Set.Tiles[ToIndex(tileIndex)];
    for (int b = tile.FirstLabel; b < tile.FirstLabel + tile.Orientations; ++b)
      if (image.Size == block.Size && this->Set.LabelVoxels[ToIndex(b)] == image.Voxels)
      {
        h = SymmetryGroup(false)[ToIndex(this->Set.LabelOrientation[ToIndex(b)])];
        return;
      }
    this->Xml.Fail("'" + *ref + "' is not an image of tile '" + tileName +
        "' under the square's symmetries (turns about x and y need fullSymmetry=\"True\")",
      n.Line);
  }

  void AddRule(const XmlElement& n, std::array<std::set<std::pair<int, int>>, 3>& pairs) const
  {
    const bool sideways = n.Attribute("left") || n.Attribute("right");
    const bool vertical = n.Attribute("top") || n.Attribute("bottom");
    if (sideways == vertical)
      this->Xml.Fail("a <neighbor> has either left and right or top and bottom", n.Line);
    int tiles[2];
    CubeSymmetry h[2];
    // The first tile lies at the origin, the second at +x (left, right) or +z (bottom, top).
    this->ParseRef(n, sideways ? "left" : "bottom", tiles[0], h[0]);
    this->ParseRef(n, sideways ? "right" : "top", tiles[1], h[1]);
    const int axis = sideways ? 0 : 2;
    const bool full = this->Set.FullSymmetry;
    for (const CubeSymmetry& g : SymmetryGroup(full))
    {
      int label[2];
      for (int s = 0; s < 2; ++s)
        label[s] = this->Set.Tiles[ToIndex(tiles[s])]
                     .SymmetryLabels[ToIndex(SymmetryIndex(full, CubeSymmetry::Then(h[s], g)))];
      const int to = g.MapsAxis(axis);
      if (to > 0)
        pairs[ToIndex(to - 1)].insert({ label[0], label[1] });
      else
        pairs[ToIndex(-to - 1)].insert({ label[1], label[0] });
    }
  }

  XmlReader& Xml;
  const XmlElement& Root;
  const std::string& Name;
  std::vector<VoxelBlock> Blocks; ///< per tile, as read
  Tileset Set;
};
} // namespace

Tileset ReadVoxelTileset(
  XmlReader& xml, const XmlElement& root, const std::string& name, const std::string& tiles)
{
  return VoxelTilesetParser(xml, root, name).Read(tiles);
}
} // namespace detail

} // namespace msynth
