// SPDX-License-Identifier: BSD-3-Clause
#include "Formats/Tileset.h"

#include "Core/Error.h"

#include "Core/Index.h"
#include "Formats/VoxelTileset.h"
#include "Formats/Xml.h"

#include <cctype>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iterator>
#include <set>
#include <sstream>

namespace msynth
{
namespace
{
using detail::XmlElement;
using detail::XmlReader;

const XmlElement* Child(const XmlElement& e, const std::string& name)
{
  for (const auto& c : e.Children)
    if (c.Name == name)
      return &c;
  return nullptr;
}
} // namespace

// ---------------------------------------------------------------------------------------------
bool ParseTileWeight(const std::string& text, double& weight)
{
  char* end = nullptr;
  weight = std::strtod(text.c_str(), &end);
  return end != text.c_str() && !*end && weight > 0.0 && std::isfinite(weight);
}

int OrientationCount(char symmetry)
{
  switch (symmetry)
  {
    case 'X':
      return 1;
    case 'I':
    case '\\':
      return 2;
    case 'L':
    case 'T':
      return 4;
    case 'F':
      return 8;
    default:
      return 0;
  }
}

int TransformOrientation(char symmetry, int i, bool mirror)
{
  // Rotation r (90° counter-clockwise) and left-right mirror m on the orientations of each
  // class; they satisfy r^4 = m^2 = 1 and m r = r^-1 m (tested).
  switch (symmetry)
  {
    case 'I':
      return mirror ? i : 1 - i;
    case '\\':
      return 1 - i;
    case 'L':
      return mirror ? (i % 2 == 0 ? i + 1 : i - 1) : (i + 1) % 4;
    case 'T':
      return mirror ? (i % 2 == 0 ? i : 4 - i) : (i + 1) % 4;
    case 'F':
      if (mirror)
        return i < 4 ? i + 4 : i - 4;
      return i < 4 ? (i + 1) % 4 : 4 + (i + 3) % 4;
    default:
      return i; // X
  }
}

int TransformSides(int sides, int element)
{
  // Bits +x, -x, +y, -y. A quarter turn counter-clockwise moves +x to +y, +y to -x, -x to -y
  // and -y to +x, as AddRule turns positions; the mirror swaps +x and -x.
  for (int r = 0; r < element % 4; ++r)
    sides = ((sides & 1) << 2) | ((sides & 4) >> 1) | ((sides & 2) << 2) | ((sides & 8) >> 3);
  if (element >= 4)
    sides = (sides & 12) | ((sides & 1) << 1) | ((sides & 2) >> 1);
  return sides;
}

int DihedralAction(char symmetry, int orientation, int element)
{
  int o = orientation;
  for (int r = 0; r < element % 4; ++r)
    o = TransformOrientation(symmetry, o, false);
  return element >= 4 ? TransformOrientation(symmetry, o, true) : o;
}

std::string TilesetImageFolder(const std::string& xmlPath)
{
  const std::string::size_type slash = xmlPath.rfind('/');
  const std::string base = slash == std::string::npos ? xmlPath : xmlPath.substr(slash + 1);
  if (base == "data.xml") // the older layout: NAME/data.xml with the images beside it
    return slash == std::string::npos ? std::string(".") : xmlPath.substr(0, slash);
  const std::string::size_type dot = base.rfind('.');
  return xmlPath.substr(0, xmlPath.size() - (dot == std::string::npos ? 0 : base.size() - dot));
}

std::string TileImageFile(
  const std::string& xmlPath, const Tileset& set, const TilesetTile& tile, int orientation)
{
  const std::string stem = TilesetImageFolder(xmlPath) + "/" + tile.Name +
    (set.Unique ? " " + std::to_string(orientation) : std::string());
  for (const char* ext : { ".png", ".bmp" })
    if (std::ifstream(stem + ext).good())
      return stem + ext;
  return stem + ".png";
}

std::string Tileset::LabelName(int label) const
{
  const TilesetTile& t = this->Tiles[ToIndex(this->LabelTile[ToIndex(label)])];
  return t.Orientations == 1
    ? t.Name
    : t.Name + " " + std::to_string(this->LabelOrientation[ToIndex(label)]);
}

std::map<Label, Label> Tileset::TurnMap() const
{
  std::map<Label, Label> map;
  if (this->Voxel)
  {
    // Label with symmetry g turned a quarter about z: the image under g then the turn.
    const CubeSymmetry turn = CubeSymmetry::QuarterTurn(2);
    const auto& group = SymmetryGroup(this->FullSymmetry);
    for (int label = 0; label < this->NumberOfLabels(); ++label)
    {
      const TilesetTile& t = this->Tiles[ToIndex(this->LabelTile[ToIndex(label)])];
      const auto& g = group[ToIndex(this->LabelOrientation[ToIndex(label)])];
      map[label] =
        t.SymmetryLabels[ToIndex(SymmetryIndex(this->FullSymmetry, CubeSymmetry::Then(g, turn)))];
    }
    return map;
  }
  for (int label = 0; label < this->NumberOfLabels(); ++label)
  {
    const TilesetTile& t = this->Tiles[ToIndex(this->LabelTile[ToIndex(label)])];
    map[label] = t.FirstLabel +
      TransformOrientation(t.Symmetry, this->LabelOrientation[ToIndex(label)], false);
  }
  return map;
}

std::map<Label, Label> Tileset::MirrorMap(int axis) const
{
  std::map<Label, Label> map;
  if (!this->Voxel)
    return map;
  CubeSymmetry mirror;
  mirror.M[axis][axis] = -1;
  const auto& group = SymmetryGroup(this->FullSymmetry);
  for (int label = 0; label < this->NumberOfLabels(); ++label)
  {
    const auto i = ToIndex(label);
    const TilesetTile& t = this->Tiles[ToIndex(this->LabelTile[i])];
    const CubeSymmetry image =
      CubeSymmetry::Then(group[ToIndex(this->LabelOrientation[i])], mirror);
    const int g = SymmetryIndex(this->FullSymmetry, image);
    if (g >= 0)
    {
      map[label] = t.SymmetryLabels[ToIndex(g)];
      continue;
    }
    // A mirror in z of a set without fullSymmetry: only images that are their own mirror image.
    const VoxelBlock mirrored = TransformVoxels({ this->VoxelSize, this->LabelVoxels[i] }, mirror);
    if (mirrored.Voxels != this->LabelVoxels[i])
      throw Error("tile '" + t.Name +
        "' mirrored in z is none of its images (the set has no "
        "fullSymmetry): no mirror symmetry along z");
    map[label] = label;
  }
  return map;
}

AdjacencyRules Tileset::Rules() const
{
  std::vector<Label> values;
  std::vector<double> weights;
  for (int b = 0; b < this->NumberOfLabels(); ++b)
  {
    values.push_back(b);
    weights.push_back(this->Tiles[ToIndex(this->LabelTile[ToIndex(b)])].Weight);
  }
  return AdjacencyRules::FromPairs(values, weights, this->Pairs);
}

namespace
{
/// A tileset read as WaveFunctionCollapse reads its XML: the <set>'s attributes, the tiles of
/// the chosen subset with their symmetry and weight, and the neighbour rules, each in all eight
/// rotations and reflections of the two-tile configuration.
class TilesetParser
{
public:
  TilesetParser(XmlReader& xml, const XmlElement& root, const std::string& name)
    : Xml(xml)
    , Root(root)
    , Name(name)
  {
    if (root.Name != "set")
      xml.Fail("the top-level element is <" + root.Name +
          ">, not <set> (WaveFunctionCollapse) or <tileset> (MarkovJunior)",
        root.Line);
  }

  Tileset Read(const std::string& subsetName)
  {
    this->ReadSetAttributes();
    this->Tiles = Child(this->Root, "tiles");
    if (!this->Tiles)
      this->Xml.Fail("<set> has no <tiles>", this->Root.Line);
    this->ReadTiles(this->AllowedTiles(subsetName));
    if (this->Set.Tiles.empty())
      this->Xml.Fail("the tileset has no tiles" +
          (subsetName.empty() ? std::string() : " in subset '" + subsetName + "'"),
        this->Tiles->Line);
    this->ReadNeighbors();
    return std::move(this->Set);
  }

private:
  void ReadSetAttributes()
  {
    if (const std::string* unique = this->Root.Attribute("unique"))
    {
      std::string u = *unique;
      for (auto& ch : u)
        ch = static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
      this->Set.Unique = u == "true";
    }
    if (const std::string* turned = this->Root.Attribute("turned"))
    {
      if (*turned != "true" && *turned != "false")
        this->Xml.Fail(
          "<set turned=\"" + *turned + "\">: turned is true or false", this->Root.Line);
      this->Set.Turned = *turned == "true";
    }
    if (const std::string* size = this->Root.Attribute("size"))
    {
      char* end = nullptr;
      const long v = std::strtol(size->c_str(), &end, 10);
      if (end == size->c_str() || *end || v < 1 || v > 4096)
        this->Xml.Fail(
          "<set size=\"" + *size + "\">: the tile size is a whole number of pixels, 1 to 4096",
          this->Root.Line);
      this->Set.TileSize = static_cast<int>(v);
    }
  }

  /// The tile names of subset @p subsetName (empty: every tile).
  std::set<std::string> AllowedTiles(const std::string& subsetName) const
  {
    std::set<std::string> allowed;
    if (subsetName.empty())
      return allowed;
    const XmlElement* subsets = Child(this->Root, "subsets");
    const XmlElement* chosen = nullptr;
    if (subsets)
      for (const auto& s : subsets->Children) // by reference: chosen points into the tree
        if (s.Name == "subset" && s.Attribute("name") && *s.Attribute("name") == subsetName)
          chosen = &s;
    if (!chosen)
    {
      std::string names; // the subsets it has, to choose from
      if (subsets)
        for (const auto& s : subsets->Children)
          if (s.Name == "subset" && s.Attribute("name"))
            names += (names.empty() ? "" : ", ") + *s.Attribute("name");
      throw Error::InFile(this->Name,
        "has no subset named '" + subsetName + "'" +
          (names.empty() ? std::string("; it has no subsets") : "; its subsets: " + names));
    }
    for (const auto& t : chosen->Children)
      if (t.Name == "tile" && t.Attribute("name"))
        allowed.insert(*t.Attribute("name"));
    return allowed;
  }

  void ReadTiles(const std::set<std::string>& allowed)
  {
    for (const auto& t : this->Tiles->Children)
    {
      if (t.Name != "tile")
        continue;
      const std::string* tileName = t.Attribute("name");
      if (!tileName || tileName->empty())
        this->Xml.Fail("a <tile> has no name", t.Line);
      for (const auto& other : this->Set.Tiles)
        if (other.Name == *tileName)
          this->Xml.Fail("tile '" + *tileName + "' is defined twice", t.Line);
      if (!allowed.empty() && !allowed.count(*tileName))
        continue;
      this->AddTile(t, *tileName);
    }
  }

  void AddTile(const XmlElement& t, const std::string& tileName)
  {
    TilesetTile tile;
    tile.Name = tileName;
    const std::string* symmetry = t.Attribute("symmetry");
    tile.Symmetry = symmetry ? (symmetry->size() == 1 ? (*symmetry)[0] : '?') : 'X';
    tile.Orientations = OrientationCount(tile.Symmetry);
    if (tile.Orientations == 0)
      this->Xml.Fail("tile '" + tile.Name + "' has symmetry '" + (symmetry ? *symmetry : "") +
          "'; the classes are X, I, \\, L, T and F",
        t.Line);
    if (!this->Set.Turned && tile.Orientations != 1)
      this->Xml.Fail("tile '" + tile.Name + "' has symmetry '" + std::string(1, tile.Symmetry) +
          "' in a set whose tiles are never turned (turned=\"false\"); give it symmetry X",
        t.Line);
    if (const std::string* weight = t.Attribute("weight"))
      if (!ParseTileWeight(*weight, tile.Weight))
        this->Xml.Fail(
          "tile '" + tile.Name + "' has weight '" + *weight + "'; weights are positive numbers",
          t.Line);
    tile.FirstLabel = this->Set.NumberOfLabels();
    const std::vector<int> sides = this->ReadConnects(t, tile);
    for (int k = 0; k < tile.Orientations; ++k)
    {
      this->Set.LabelTile.push_back(static_cast<int>(this->Set.Tiles.size()));
      this->Set.LabelOrientation.push_back(k);
      this->Set.LabelSides.push_back(sides[ToIndex(k)]);
    }
    this->Set.Tiles.push_back(tile);
  }

  /// The `connects` attribute of @p t: per orientation the sides it connects through (-1
  /// without the attribute), orientation 0's as written, the others turned and mirrored.
  std::vector<int> ReadConnects(const XmlElement& t, const TilesetTile& tile) const
  {
    std::vector<int> sides(ToIndex(tile.Orientations), -1);
    const std::string* text = t.Attribute("connects");
    if (!text)
      return sides;
    static const char* const names[4][2] = { { "right", "+x" }, { "left", "-x" }, { "top", "+y" },
      { "bottom", "-y" } };
    int first = 0;
    std::istringstream words(*text);
    for (std::string w; words >> w;)
    {
      int bit = -1;
      for (int b = 0; b < 4; ++b)
        if (w == names[b][0] || w == names[b][1])
          bit = b;
      if (bit < 0)
        this->Xml.Fail("tile '" + tile.Name + "' connects through '" + w +
            "'; the sides are right, left, top and bottom (+x, -x, +y, -y)",
          t.Line);
      first |= 1 << bit;
    }
    if (!this->Set.Turned) // one orientation, drawn as is: the sides as written
      return std::vector<int>(1, first);
    for (int element = 0; element < 8; ++element)
    {
      const int o = DihedralAction(tile.Symmetry, 0, element);
      const int turned = TransformSides(first, element);
      int& at = sides[ToIndex(o)];
      if (at >= 0 && at != turned)
        this->Xml.Fail("tile '" + tile.Name + "': the sides it connects through (\"" + *text +
            "\") do not have its symmetry " + std::string(1, tile.Symmetry),
          t.Line);
      at = turned;
    }
    return sides;
  }

  /// One side of a <neighbor>: its tile and orientation. False for a tile outside the subset.
  bool ParseRef(const XmlElement& n, const char* side, int& tileIndex, int& orientation) const
  {
    const std::string* ref = n.Attribute(side);
    if (!ref)
      this->Xml.Fail(std::string("a <neighbor> has no '") + side + "'", n.Line);
    std::istringstream words(*ref);
    std::string tileName;
    words >> tileName;
    orientation = 0;
    std::string extra;
    if (words >> orientation)
      words >> extra;
    else if (!words.eof())
      this->Xml.Fail("'" + *ref + "' is not 'tile' or 'tile orientation'", n.Line);
    if (!extra.empty())
      this->Xml.Fail("'" + *ref + "' is not 'tile' or 'tile orientation'", n.Line);
    if (orientation < 0 || orientation > 7)
      this->Xml.Fail("'" + *ref +
          "': the number after a tile name is one of the 8 rotations and "
          "reflections, 0 to 7",
        n.Line);
    tileIndex = -1;
    for (std::size_t i = 0; i < this->Set.Tiles.size(); ++i)
      if (this->Set.Tiles[i].Name == tileName)
        tileIndex = static_cast<int>(i);
    if (tileIndex < 0)
    {
      bool defined = false;
      for (const auto& t : this->Tiles->Children)
        defined |= t.Attribute("name") && *t.Attribute("name") == tileName;
      if (!defined)
        this->Xml.Fail("a <neighbor> names tile '" + tileName + "', which is not defined", n.Line);
      return false; // defined but outside the chosen subset
    }
    // As WaveFunctionCollapse reads it (action[first][k]): element k of the dihedral group
    // (identity, three quarter turns, then the four mirrored) applied to orientation 0.
    orientation = DihedralAction(this->Set.Tiles[ToIndex(tileIndex)].Symmetry, 0, orientation);
    return true;
  }

  /// The pairs of one rule in all 8 rotations and reflections of the configuration.
  void AddRule(const int tiles[2], const int orient[2],
    std::array<std::set<std::pair<int, int>>, 3>& pairs) const
  {
    for (int mirror = 0; mirror < 2; ++mirror)
      for (int turns = 0; turns < 4; ++turns)
      {
        int px[2] = { 0, 1 }, py[2] = { 0, 0 }, label[2];
        for (int s = 0; s < 2; ++s)
        {
          const TilesetTile& t = this->Set.Tiles[ToIndex(tiles[s])];
          int o = orient[s];
          for (int r = 0; r < turns; ++r)
          {
            const int x = px[s];
            px[s] = -py[s];
            py[s] = x;
            o = TransformOrientation(t.Symmetry, o, false);
          }
          if (mirror)
          {
            px[s] = -px[s];
            o = TransformOrientation(t.Symmetry, o, true);
          }
          label[s] = t.FirstLabel + o;
        }
        if (px[0] != px[1])
          pairs[0].insert(px[0] < px[1] ? std::make_pair(label[0], label[1])
                                        : std::make_pair(label[1], label[0]));
        else
          pairs[1].insert(py[0] < py[1] ? std::make_pair(label[0], label[1])
                                        : std::make_pair(label[1], label[0]));
      }
  }

  void ReadNeighbors()
  {
    std::array<std::set<std::pair<int, int>>, 3> pairs;
    if (const XmlElement* neighbors = Child(this->Root, "neighbors"))
    {
      for (const auto& n : neighbors->Children)
      {
        if (n.Name != "neighbor")
          continue;
        int tiles[2], orient[2];
        const bool a = this->ParseRef(n, "left", tiles[0], orient[0]);
        const bool b = this->ParseRef(n, "right", tiles[1], orient[1]);
        if (a && b)
          this->AddRule(tiles, orient, pairs);
      }
    }
    for (std::size_t axis = 0; axis < 2; ++axis)
      this->Set.Pairs[axis].assign(pairs[axis].begin(), pairs[axis].end());
  }

  XmlReader& Xml;
  const XmlElement& Root;
  const std::string& Name;
  const XmlElement* Tiles = nullptr;
  Tileset Set;
};
} // namespace

Tileset ReadTileset(std::istream& in, const std::string& name, const std::string& subsetName,
  const std::string& tiles)
{
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (text.size() > (std::size_t(1) << 24))
    throw Error::InFile(name, "is larger than 16 MiB, too large for a tileset");
  XmlReader xml(std::move(text), name);
  const XmlElement root = xml.Parse();
  if (root.Name == "tileset")
  {
    if (!subsetName.empty())
      throw Error::InFile(name, "is a voxel tileset (<tileset>), which has no subsets");
    return detail::ReadVoxelTileset(xml, root, name, tiles);
  }
  return TilesetParser(xml, root, name).Read(subsetName);
}

Tileset ReadTilesetFile(
  const std::string& path, const std::string& subset, const std::string& tiles)
{
  std::ifstream in(path, std::ios::binary);
  if (!in)
    throw Error::InFile(path, "cannot be opened for reading (missing or unreadable)");
  return ReadTileset(in, path, subset, tiles);
}

} // namespace msynth
