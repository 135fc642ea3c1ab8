// SPDX-License-Identifier: BSD-3-Clause
#include "Formats/VoxModel.h"

#include "Core/AtomicFile.h"
#include "Core/Error.h"
#include "Core/Index.h"

#include <algorithm>
#include <climits>
#include <cstring>
#include <fstream>
#include <map>
#include <sstream>

namespace msynth
{
namespace
{
/// Little-endian reads within [Position, End), failing cleanly past the end.
class Cursor
{
public:
  Cursor(const std::vector<std::uint8_t>& bytes, const std::string& name)
    : Bytes(bytes)
    , Name(name)
    , End(bytes.size())
  {
  }
  [[noreturn]] void Fail(const std::string& problem) const
  {
    throw Error::InFile(this->Name,
      "is not a valid MagicaVoxel file: " + problem + " (at byte " +
        std::to_string(this->Position) + ")");
  }
  void Need(std::size_t n) const
  {
    if (n > this->End - this->Position)
      this->Fail("the data ends early");
  }
  std::uint32_t U32()
  {
    this->Need(4);
    const std::uint8_t* p = this->Bytes.data() + this->Position;
    this->Position += 4;
    return std::uint32_t(p[0]) | (std::uint32_t(p[1]) << 8) | (std::uint32_t(p[2]) << 16) |
      (std::uint32_t(p[3]) << 24);
  }
  std::string Id()
  {
    this->Need(4);
    std::string id(reinterpret_cast<const char*>(this->Bytes.data() + this->Position), 4);
    this->Position += 4;
    return id;
  }
  const std::uint8_t* Take(std::size_t n)
  {
    this->Need(n);
    const std::uint8_t* p = this->Bytes.data() + this->Position;
    this->Position += n;
    return p;
  }
  const std::vector<std::uint8_t>& Bytes;
  const std::string& Name;
  std::size_t Position = 0;
  std::size_t End;
};

/// MagicaVoxel's default palette, as its file format documentation defines it (ABGR words).
const std::uint32_t DefaultPalette[256] = { 0x00000000, 0xffffffff, 0xffccffff, 0xff99ffff,
  0xff66ffff, 0xff33ffff, 0xff00ffff, 0xffffccff, 0xffccccff, 0xff99ccff, 0xff66ccff, 0xff33ccff,
  0xff00ccff, 0xffff99ff, 0xffcc99ff, 0xff9999ff, 0xff6699ff, 0xff3399ff, 0xff0099ff, 0xffff66ff,
  0xffcc66ff, 0xff9966ff, 0xff6666ff, 0xff3366ff, 0xff0066ff, 0xffff33ff, 0xffcc33ff, 0xff9933ff,
  0xff6633ff, 0xff3333ff, 0xff0033ff, 0xffff00ff, 0xffcc00ff, 0xff9900ff, 0xff6600ff, 0xff3300ff,
  0xff0000ff, 0xffffffcc, 0xffccffcc, 0xff99ffcc, 0xff66ffcc, 0xff33ffcc, 0xff00ffcc, 0xffffcccc,
  0xffcccccc, 0xff99cccc, 0xff66cccc, 0xff33cccc, 0xff00cccc, 0xffff99cc, 0xffcc99cc, 0xff9999cc,
  0xff6699cc, 0xff3399cc, 0xff0099cc, 0xffff66cc, 0xffcc66cc, 0xff9966cc, 0xff6666cc, 0xff3366cc,
  0xff0066cc, 0xffff33cc, 0xffcc33cc, 0xff9933cc, 0xff6633cc, 0xff3333cc, 0xff0033cc, 0xffff00cc,
  0xffcc00cc, 0xff9900cc, 0xff6600cc, 0xff3300cc, 0xff0000cc, 0xffffff99, 0xffccff99, 0xff99ff99,
  0xff66ff99, 0xff33ff99, 0xff00ff99, 0xffffcc99, 0xffcccc99, 0xff99cc99, 0xff66cc99, 0xff33cc99,
  0xff00cc99, 0xffff9999, 0xffcc9999, 0xff999999, 0xff669999, 0xff339999, 0xff009999, 0xffff6699,
  0xffcc6699, 0xff996699, 0xff666699, 0xff336699, 0xff006699, 0xffff3399, 0xffcc3399, 0xff993399,
  0xff663399, 0xff333399, 0xff003399, 0xffff0099, 0xffcc0099, 0xff990099, 0xff660099, 0xff330099,
  0xff000099, 0xffffff66, 0xffccff66, 0xff99ff66, 0xff66ff66, 0xff33ff66, 0xff00ff66, 0xffffcc66,
  0xffcccc66, 0xff99cc66, 0xff66cc66, 0xff33cc66, 0xff00cc66, 0xffff9966, 0xffcc9966, 0xff999966,
  0xff669966, 0xff339966, 0xff009966, 0xffff6666, 0xffcc6666, 0xff996666, 0xff666666, 0xff336666,
  0xff006666, 0xffff3366, 0xffcc3366, 0xff993366, 0xff663366, 0xff333366, 0xff003366, 0xffff0066,
  0xffcc0066, 0xff990066, 0xff660066, 0xff330066, 0xff000066, 0xffffff33, 0xffccff33, 0xff99ff33,
  0xff66ff33, 0xff33ff33, 0xff00ff33, 0xffffcc33, 0xffcccc33, 0xff99cc33, 0xff66cc33, 0xff33cc33,
  0xff00cc33, 0xffff9933, 0xffcc9933, 0xff999933, 0xff669933, 0xff339933, 0xff009933, 0xffff6633,
  0xffcc6633, 0xff996633, 0xff666633, 0xff336633, 0xff006633, 0xffff3333, 0xffcc3333, 0xff993333,
  0xff663333, 0xff333333, 0xff003333, 0xffff0033, 0xffcc0033, 0xff990033, 0xff660033, 0xff330033,
  0xff000033, 0xffffff00, 0xffccff00, 0xff99ff00, 0xff66ff00, 0xff33ff00, 0xff00ff00, 0xffffcc00,
  0xffcccc00, 0xff99cc00, 0xff66cc00, 0xff33cc00, 0xff00cc00, 0xffff9900, 0xffcc9900, 0xff999900,
  0xff669900, 0xff339900, 0xff009900, 0xffff6600, 0xffcc6600, 0xff996600, 0xff666600, 0xff336600,
  0xff006600, 0xffff3300, 0xffcc3300, 0xff993300, 0xff663300, 0xff333300, 0xff003300, 0xffff0000,
  0xffcc0000, 0xff990000, 0xff660000, 0xff330000, 0xff0000ee, 0xff0000dd, 0xff0000bb, 0xff0000aa,
  0xff000088, 0xff000077, 0xff000055, 0xff000044, 0xff000022, 0xff000011, 0xff00ee00, 0xff00dd00,
  0xff00bb00, 0xff00aa00, 0xff008800, 0xff007700, 0xff005500, 0xff004400, 0xff002200, 0xff001100,
  0xffee0000, 0xffdd0000, 0xffbb0000, 0xffaa0000, 0xff880000, 0xff770000, 0xff550000, 0xff440000,
  0xff220000, 0xff110000, 0xffeeeeee, 0xffdddddd, 0xffbbbbbb, 0xffaaaaaa, 0xff888888, 0xff777777,
  0xff555555, 0xff444444, 0xff222222, 0xff111111 };

/// Past the header ("VOX ", the version: 150 and 200 are in use, the chunks we read are the
/// same) and into MAIN: the cursor then walks MAIN's children.
void EnterMain(Cursor& c, const std::vector<std::uint8_t>& bytes)
{
  if (bytes.size() < 8 || std::memcmp(bytes.data(), "VOX ", 4) != 0)
    c.Fail("it does not start with 'VOX '");
  c.Position = 4;
  c.U32();
  if (c.Id() != "MAIN")
    c.Fail("the first chunk is not MAIN");
  const std::uint32_t mainContent = c.U32();
  const std::uint32_t mainChildren = c.U32();
  c.Take(mainContent);
  if (mainChildren > c.End - c.Position)
    c.Fail("MAIN declares more children than the file holds");
  c.End = c.Position + mainChildren;
}

/// MagicaVoxel's default palette (a file without an RGBA chunk).
void SetDefaultPalette(std::vector<std::array<std::uint8_t, 4>>& palette)
{
  for (std::size_t i = 0; i < 256; ++i)
  {
    const std::uint32_t abgr = DefaultPalette[i];
    palette[i] = { { static_cast<std::uint8_t>(abgr & 0xff),
      static_cast<std::uint8_t>((abgr >> 8) & 0xff), static_cast<std::uint8_t>((abgr >> 16) & 0xff),
      static_cast<std::uint8_t>(abgr >> 24) } };
  }
}
/// The first SIZE chunk's model, all empty (checked against 1..2048 a side and @p maxSites).
LabelGrid ReadSizeChunk(Cursor& c, std::uint32_t content, std::int64_t maxSites)
{
  if (content < 12)
    c.Fail("SIZE chunk is too short");
  std::array<std::int64_t, 3> size{ { 0, 0, 0 } };
  for (auto& d : size)
    d = static_cast<std::int64_t>(c.U32());
  for (auto d : size)
    if (d < 1 || d > 2048)
      c.Fail("model size " + std::to_string(size[0]) + " x " + std::to_string(size[1]) + " x " +
        std::to_string(size[2]) + " is outside 1..2048");
  if (size[0] * size[1] * size[2] > maxSites) // a valid file, larger than the reader may hold
    throw Error::InFile(c.Name,
      "declares a model of " + std::to_string(size[0]) + " x " + std::to_string(size[1]) + " x " +
        std::to_string(size[2]) + " voxels, more than the " + std::to_string(maxSites) +
        " this reading may hold (the memory available allows no more)");
  return LabelGrid(size[0], size[1], size[2], 0);
}

/// The first XYZI chunk's voxels into @p grid (each inside it).
void ReadVoxelChunk(Cursor& c, std::uint32_t content, LabelGrid& grid)
{
  const std::uint32_t count = c.U32();
  if (count > (content - 4) / 4 || content < 4)
    c.Fail("XYZI declares " + std::to_string(count) + " voxels but holds " +
      std::to_string(content >= 4 ? (content - 4) / 4 : 0));
  const std::uint8_t* v = c.Take(std::size_t(count) * 4);
  for (std::uint32_t i = 0; i < count; ++i)
  {
    const std::int64_t x = v[4 * i], y = v[4 * i + 1], z = v[4 * i + 2];
    if (!grid.Contains(x, y, z))
      c.Fail("voxel (" + std::to_string(x) + ", " + std::to_string(y) + ", " + std::to_string(z) +
        ") lies outside the model size");
    grid.Set(x, y, z, v[4 * i + 3]);
  }
}

/// An RGBA chunk: entry i is the colour of palette index i + 1; index 0 is empty.
void ReadPaletteChunk(
  Cursor& c, std::uint32_t content, std::vector<std::array<std::uint8_t, 4>>& palette)
{
  if (content < 1024)
    c.Fail("RGBA chunk is shorter than 256 colours");
  const std::uint8_t* p = c.Take(1024);
  palette[0] = { { 0, 0, 0, 0 } };
  for (int i = 0; i < 255; ++i)
    palette[ToIndex(i + 1)] = { { p[4 * i], p[4 * i + 1], p[4 * i + 2], p[4 * i + 3] } };
}
} // namespace

VoxModel ReadVoxModel(
  const std::vector<std::uint8_t>& bytes, const std::string& name, std::int64_t maxSites)
{
  Cursor c(bytes, name);
  EnterMain(c, bytes);

  VoxModel model;
  bool haveSize = false, haveVoxels = false, havePalette = false;
  int models = 0;
  model.Palette.resize(256);
  while (c.Position < c.End)
  {
    const std::string id = c.Id();
    const std::uint32_t content = c.U32();
    const std::uint32_t children = c.U32();
    const std::size_t start = c.Position;
    c.Need(content);
    if (id == "SIZE")
    {
      ++models;
      if (!haveSize)
        model.Grid = ReadSizeChunk(c, content, maxSites);
      else if (content < 12)
        c.Fail("SIZE chunk is too short");
      haveSize = true;
    }
    else if (id == "XYZI")
    {
      if (!haveSize)
        c.Fail("XYZI chunk before any SIZE chunk");
      if (!haveVoxels)
        ReadVoxelChunk(c, content, model.Grid);
      haveVoxels = true;
    }
    else if (id == "RGBA")
    {
      ReadPaletteChunk(c, content, model.Palette);
      havePalette = true;
    }
    // Other chunks (PACK, scene graph, materials, ...) are skipped.
    if (children > c.End - start - content)
      c.Fail("chunk '" + id + "' declares more children than its parent holds");
    c.Position = start + content + children;
  }
  if (!haveSize || !haveVoxels)
    c.Fail("no model (SIZE and XYZI chunks) found");
  if (!havePalette)
    SetDefaultPalette(model.Palette);
  model.NumberOfModels = models;
  return model;
}

namespace
{
std::vector<std::uint8_t> ReadFileBytes(const std::string& path)
{
  std::ifstream in(path, std::ios::binary | std::ios::ate);
  if (!in)
    throw Error::InFile(path, "cannot be opened for reading (missing or unreadable)");
  const std::streamoff size = in.tellg();
  if (size < 0 || size > (std::streamoff(1) << 28))
    throw Error::InFile(path, "is larger than 256 MiB, too large for a MagicaVoxel model");
  std::vector<std::uint8_t> bytes(ToIndex(size));
  in.seekg(0);
  in.read(reinterpret_cast<char*>(bytes.data()), size);
  if (!in)
    throw Error::InFile(path, "could not be read");
  return bytes;
}
} // namespace

VoxModel ReadVoxModelFile(const std::string& path, std::int64_t maxSites)
{
  return ReadVoxModel(ReadFileBytes(path), path, maxSites);
}

void WriteVoxModel(std::ostream& out, const VoxModel& model, const std::string& name)
{
  const auto& d = model.Grid.Dimensions();
  if (d[0] > 256 || d[1] > 256 || d[2] > 256)
    throw Error::InFile(name,
      "cannot hold a " + std::to_string(d[0]) + " x " + std::to_string(d[1]) + " x " +
        std::to_string(d[2]) + " model: MagicaVoxel models are at most 256 voxels a side");
  std::vector<std::uint8_t> voxels;
  for (std::int64_t z = 0; z < d[2]; ++z)
    for (std::int64_t y = 0; y < d[1]; ++y)
      for (std::int64_t x = 0; x < d[0]; ++x)
      {
        const Label b = model.Grid.At(x, y, z);
        if (b == 0)
          continue;
        if (b < 0 || b > 255)
          throw Error::InFile(name,
            "cannot hold label " + std::to_string(b) + " at (" + std::to_string(x) + ", " +
              std::to_string(y) + ", " + std::to_string(z) +
              "): MagicaVoxel labels are palette indices 1..255");
        for (std::int64_t v : { x, y, z, std::int64_t(b) })
          voxels.push_back(static_cast<std::uint8_t>(v));
      }
  const auto u32 = [&out](std::uint32_t v)
  {
    const char b[4] = { static_cast<char>(v & 255), static_cast<char>((v >> 8) & 255),
      static_cast<char>((v >> 16) & 255), static_cast<char>(v >> 24) };
    out.write(b, 4);
  };
  const bool palette = model.Palette.size() == 256;
  const std::uint32_t sizeChunk = 12 + 12,
                      xyziChunk = 12 + 4 + static_cast<std::uint32_t>(voxels.size()),
                      rgbaChunk = palette ? 12 + 1024 : 0;
  out.write("VOX ", 4);
  u32(150);
  out.write("MAIN", 4);
  u32(0);
  u32(sizeChunk + xyziChunk + rgbaChunk);
  out.write("SIZE", 4);
  u32(12);
  u32(0);
  for (std::int64_t n : d)
    u32(static_cast<std::uint32_t>(n));
  out.write("XYZI", 4);
  u32(4 + static_cast<std::uint32_t>(voxels.size()));
  u32(0);
  u32(static_cast<std::uint32_t>(voxels.size() / 4));
  if (!voxels.empty()) // an empty model: no bytes (and no null pointer to write from)
    out.write(
      reinterpret_cast<const char*>(voxels.data()), static_cast<std::streamsize>(voxels.size()));
  if (palette)
  {
    // Entry i of the chunk is palette index i + 1.
    out.write("RGBA", 4);
    u32(1024);
    u32(0);
    for (std::size_t i = 1; i <= 256; ++i)
    {
      const auto& c = i < 256 ? model.Palette[i] : std::array<std::uint8_t, 4>{ { 0, 0, 0, 0 } };
      out.write(reinterpret_cast<const char*>(c.data()), 4);
    }
  }
}

void WriteVoxModelFile(const std::string& path, const VoxModel& model)
{
  WriteFileAtomically(path, [&](std::ostream& out) { WriteVoxModel(out, model, path); });
}

namespace
{
/// One node of a MagicaVoxel scene graph.
struct SceneNode
{
  char Type = 0; ///< 'T' transform, 'G' group, 'S' shape
  std::vector<int> Children;
  std::array<std::int64_t, 3> Translation{ { 0, 0, 0 } };
};

std::string ReadString(Cursor& c)
{
  const std::uint32_t n = c.U32();
  const std::uint8_t* p = c.Take(n);
  return std::string(reinterpret_cast<const char*>(p), n);
}

std::vector<std::pair<std::string, std::string>> ReadDict(Cursor& c)
{
  std::vector<std::pair<std::string, std::string>> dict;
  const std::uint32_t n = c.U32();
  if (n > 1024)
    c.Fail("a scene dictionary has more than 1024 entries");
  for (std::uint32_t i = 0; i < n; ++i)
  {
    std::string key = ReadString(c);
    dict.emplace_back(std::move(key), ReadString(c));
  }
  return dict;
}

/// Reads the scene node chunk @p id, whose content starts at the cursor.
void ReadNode(Cursor& c, const std::string& id, std::map<int, SceneNode>& nodes)
{
  const int nodeId = static_cast<int>(c.U32());
  ReadDict(c);
  SceneNode node;
  node.Type = id == "nTRN" ? 'T' : (id == "nGRP" ? 'G' : 'S');
  if (node.Type == 'T')
  {
    node.Children.push_back(static_cast<int>(c.U32()));
    c.U32(); // reserved
    c.U32(); // layer
    const std::uint32_t frames = c.U32();
    for (std::uint32_t f = 0; f < frames && f < 1024; ++f)
      for (const auto& kv : ReadDict(c))
      {
        if (f == 0 && kv.first == "_t")
        {
          std::istringstream in(kv.second);
          in >> node.Translation[0] >> node.Translation[1] >> node.Translation[2];
          for (auto t : node.Translation)
            if (!in || t < -100000 || t > 100000)
              c.Fail("transform node " + std::to_string(nodeId) + " has translation '" + kv.second +
                "'");
        }
        if (f == 0 && kv.first == "_r" && kv.second != "4")
          c.Fail("transform node " + std::to_string(nodeId) + " rotates its model ('_r' " +
            kv.second + "), which is not read");
      }
  }
  else
  {
    const std::uint32_t n = c.U32();
    if (n > 1000000)
      c.Fail("a scene node has more than a million children");
    for (std::uint32_t i = 0; i < n; ++i)
    {
      node.Children.push_back(static_cast<int>(c.U32()));
      if (node.Type == 'S')
        ReadDict(c);
    }
  }
  nodes[nodeId] = std::move(node);
}

struct ScenePiece
{
  std::array<std::int64_t, 3> Size{ { 0, 0, 0 } };
  std::vector<std::uint8_t> Voxels; ///< x, y, z, index per voxel
};

struct Placement
{
  int Model;
  std::array<std::int64_t, 3> Corner;
};

/// The models reached from node @p id with the translation @p t summed so far.
void Place(Cursor& c, const std::map<int, SceneNode>& nodes, const std::vector<ScenePiece>& models,
  int id, std::array<std::int64_t, 3> t, int depth, std::vector<Placement>& out, int& budget)
{
  if (--budget < 0)
    c.Fail("the scene graph visits more than a million nodes");
  const auto it = nodes.find(id);
  if (it == nodes.end())
    c.Fail("the scene refers to node " + std::to_string(id) + ", which is not there");
  if (depth > 64 || out.size() > 65536)
    c.Fail("the scene is nested more than 64 deep or places more than 65536 models");
  const SceneNode& node = it->second;
  if (node.Type == 'T')
    for (int a = 0; a < 3; ++a)
      t[ToIndex(a)] += node.Translation[ToIndex(a)];
  for (const int child : node.Children)
  {
    if (node.Type != 'S')
    {
      Place(c, nodes, models, child, t, depth + 1, out, budget);
      continue;
    }
    if (child < 0 || ToIndex(child) >= models.size())
      c.Fail("a shape node names model " + std::to_string(child) + ", which is not there");
    Placement p{ child, t };
    for (int a = 0; a < 3; ++a) // the translation is the model's centre, rounded down
      p.Corner[ToIndex(a)] -= models[ToIndex(child)].Size[ToIndex(a)] / 2;
    out.push_back(p);
  }
}

/// The chunks of MAIN: models, palette and scene nodes.
void ReadSceneChunks(Cursor& c, std::vector<ScenePiece>& models, VoxModel& result,
  std::map<int, SceneNode>& nodes, bool& havePalette)
{
  while (c.Position < c.End)
  {
    const std::string id = c.Id();
    const std::uint32_t content = c.U32();
    const std::uint32_t children = c.U32();
    const std::size_t start = c.Position;
    c.Need(content);
    const std::size_t outerEnd = c.End;
    c.End = start + content; // a chunk's fields stay inside its content
    if (id == "SIZE")
    {
      if (models.size() >= 65536)
        c.Fail("more than 65536 models");
      ScenePiece m;
      for (auto& d : m.Size)
        d = static_cast<std::int64_t>(c.U32());
      for (auto d : m.Size)
        if (d < 1 || d > 256)
          c.Fail("a model size is outside 1..256");
      models.push_back(std::move(m));
    }
    else if (id == "XYZI")
    {
      if (models.empty() || !models.back().Voxels.empty())
        c.Fail("an XYZI chunk does not follow a SIZE chunk");
      const std::uint32_t count = c.U32();
      const std::uint8_t* v = c.Take(std::size_t(count) * 4);
      models.back().Voxels.assign(v, v + std::size_t(count) * 4);
    }
    else if (id == "RGBA")
    {
      const std::uint8_t* p = c.Take(1024);
      result.Palette[0] = { { 0, 0, 0, 0 } };
      for (std::size_t i = 0; i < 255; ++i)
        result.Palette[i + 1] = { { p[4 * i], p[4 * i + 1], p[4 * i + 2], p[4 * i + 3] } };
      havePalette = true;
    }
    else if (id == "nTRN" || id == "nGRP" || id == "nSHP")
      ReadNode(c, id, nodes);
    c.End = outerEnd;
    if (children > c.End - start - content)
      c.Fail("chunk '" + id + "' declares more children than its parent holds");
    c.Position = start + content + children;
  }
}
/// A scene is composed into one grid, so models placed far apart would make a small file a grid
/// of empty space taking seconds to minutes and gigabytes to read and check (two 5^3 models
/// 1000 voxels apart: 6 * 10^8 sites). Past 2^24 sites, a scene whose models' boxes fill less
/// than 1/64 of its box is refused; scenes MagicaVoxel users build of touching or nearby models,
/// and the scenes WriteVoxScene writes (pieces that tile the model), fill theirs.
void RefuseFarApart(const Cursor& c, const std::vector<Placement>& placed,
  const std::vector<ScenePiece>& models, const std::int64_t n[3])
{
  constexpr std::int64_t SparseFloor = std::int64_t(1) << 24;
  constexpr std::int64_t SparseFactor = 64;
  const std::int64_t box = n[0] * n[1] * n[2];
  std::int64_t filled = 0;
  for (const auto& p : placed)
  {
    const auto& size = models[ToIndex(p.Model)].Size;
    filled += size[0] * size[1] * size[2];
  }
  if (box <= SparseFloor || filled * SparseFactor >= box)
    return;
  throw Error::InFile(c.Name,
    "places its " + std::to_string(placed.size()) + " models far apart: their boxes hold " +
      std::to_string(filled) + " voxels of the " + std::to_string(n[0]) + " x " +
      std::to_string(n[1]) + " x " + std::to_string(n[2]) +
      " it spans, which is read as one model; move the models together (in MagicaVoxel) or "
      "save them as separate files");
}
} // namespace

VoxModel ReadVoxScene(
  const std::vector<std::uint8_t>& bytes, const std::string& name, std::int64_t maxSites)
{
  Cursor c(bytes, name);
  EnterMain(c, bytes);
  VoxModel result;
  result.Palette.resize(256);
  std::vector<ScenePiece> models;
  std::map<int, SceneNode> nodes;
  bool havePalette = false;
  ReadSceneChunks(c, models, result, nodes, havePalette);
  if (models.empty())
    c.Fail("no model (SIZE and XYZI chunks) found");
  std::vector<Placement> placed;
  int budget = 1000000;
  if (nodes.count(0))
    Place(c, nodes, models, 0, { { 0, 0, 0 } }, 0, placed, budget);
  else
    for (std::size_t m = 0; m < models.size(); ++m)
      placed.push_back({ static_cast<int>(m), { { 0, 0, 0 } } });
  if (placed.empty())
    c.Fail("the scene places no model");
  std::array<std::int64_t, 3> low{ { INT64_MAX, INT64_MAX, INT64_MAX } }, high{ { 0, 0, 0 } };
  for (std::size_t a = 0; a < 3; ++a)
  {
    high[a] = INT64_MIN;
    for (const auto& p : placed)
    {
      low[a] = std::min(low[a], p.Corner[a]);
      high[a] = std::max(high[a], p.Corner[a] + models[ToIndex(p.Model)].Size[a]);
    }
  }
  const std::int64_t n[3] = { high[0] - low[0], high[1] - low[1], high[2] - low[2] };
  if (n[0] * n[1] * n[2] > maxSites) // before the span is allocated
    throw Error::InFile(c.Name,
      "places its models over " + std::to_string(n[0]) + " x " + std::to_string(n[1]) + " x " +
        std::to_string(n[2]) + " voxels, more than the " + std::to_string(maxSites) +
        " this reading may hold (the memory available allows no more)");
  RefuseFarApart(c, placed, models, n);
  result.Grid = LabelGrid(n[0], n[1], n[2], 0);
  for (const auto& p : placed)
  {
    const ScenePiece& m = models[ToIndex(p.Model)];
    for (std::size_t i = 0; i + 3 < m.Voxels.size(); i += 4)
    {
      const std::int64_t v[3] = { m.Voxels[i], m.Voxels[i + 1], m.Voxels[i + 2] };
      if (v[0] >= m.Size[0] || v[1] >= m.Size[1] || v[2] >= m.Size[2])
        c.Fail("voxel (" + std::to_string(v[0]) + ", " + std::to_string(v[1]) + ", " +
          std::to_string(v[2]) + ") lies outside its model's size");
      result.Grid.Set(p.Corner[0] - low[0] + v[0], p.Corner[1] - low[1] + v[1],
        p.Corner[2] - low[2] + v[2], m.Voxels[i + 3]);
    }
  }
  if (!havePalette)
    SetDefaultPalette(result.Palette);
  result.NumberOfModels = static_cast<int>(models.size());
  return result;
}

VoxModel ReadVoxSceneFile(const std::string& path, std::int64_t maxSites)
{
  return ReadVoxScene(ReadFileBytes(path), path, maxSites);
}

namespace
{
/// The children of a .vox file's MAIN chunk being written.
struct VoxChunks
{
  std::string Body;

  static void U32(std::string& s, std::uint32_t v)
  {
    for (int k = 0; k < 4; ++k)
      s.push_back(static_cast<char>((v >> (8 * k)) & 255));
  }
  static void Dict(std::string& s, const std::vector<std::pair<std::string, std::string>>& kv)
  {
    U32(s, static_cast<std::uint32_t>(kv.size()));
    for (const auto& p : kv)
      for (const std::string* str : { &p.first, &p.second })
      {
        U32(s, static_cast<std::uint32_t>(str->size()));
        s += *str;
      }
  }
  void Chunk(const char* id, const std::string& content)
  {
    this->Body.append(id, 4);
    U32(this->Body, static_cast<std::uint32_t>(content.size()));
    U32(this->Body, 0);
    this->Body += content;
  }
};

/// SIZE and XYZI of the model's box @p p (corner and size) into @p chunks.
void AppendVoxModel(VoxChunks& chunks, const VoxModel& model, const std::array<std::int64_t, 6>& p,
  const std::string& name)
{
  std::string size, voxels;
  for (std::size_t a = 0; a < 3; ++a)
    VoxChunks::U32(size, static_cast<std::uint32_t>(p[3 + a]));
  std::uint32_t count = 0;
  for (std::int64_t z = 0; z < p[5]; ++z)
    for (std::int64_t y = 0; y < p[4]; ++y)
      for (std::int64_t x = 0; x < p[3]; ++x)
      {
        const Label b = model.Grid.At(p[0] + x, p[1] + y, p[2] + z);
        if (b == 0)
          continue;
        if (b < 0 || b > 255)
          throw Error::InFile(name,
            "cannot hold label " + std::to_string(b) +
              ": MagicaVoxel labels are palette indices 1..255");
        for (std::int64_t v : { x, y, z, std::int64_t(b) })
          voxels.push_back(static_cast<char>(v));
        ++count;
      }
  std::string xyzi;
  VoxChunks::U32(xyzi, count);
  chunks.Chunk("SIZE", size);
  chunks.Chunk("XYZI", xyzi + voxels);
}

/// The scene: transform 0 -> group 1 -> (transform 2k + 2 -> shape 2k + 3 -> model k), each
/// model's transform placing its box's centre.
void AppendVoxScene(VoxChunks& chunks, const std::vector<std::array<std::int64_t, 6>>& pieces)
{
  using C = VoxChunks;
  std::string node;
  C::U32(node, 0);
  C::Dict(node, {});
  C::U32(node, 1);
  C::U32(node, 0xffffffffu);
  C::U32(node, 0xffffffffu);
  C::U32(node, 1);
  C::Dict(node, {});
  chunks.Chunk("nTRN", node);
  node.clear();
  C::U32(node, 1);
  C::Dict(node, {});
  C::U32(node, static_cast<std::uint32_t>(pieces.size()));
  for (std::size_t k = 0; k < pieces.size(); ++k)
    C::U32(node, static_cast<std::uint32_t>(2 * k + 2));
  chunks.Chunk("nGRP", node);
  for (std::size_t k = 0; k < pieces.size(); ++k)
  {
    const auto& p = pieces[k];
    node.clear();
    C::U32(node, static_cast<std::uint32_t>(2 * k + 2));
    C::Dict(node, {});
    C::U32(node, static_cast<std::uint32_t>(2 * k + 3));
    C::U32(node, 0xffffffffu);
    C::U32(node, 0);
    C::U32(node, 1);
    C::Dict(node,
      { { "_t",
        std::to_string(p[0] + p[3] / 2) + " " + std::to_string(p[1] + p[4] / 2) + " " +
          std::to_string(p[2] + p[5] / 2) } });
    chunks.Chunk("nTRN", node);
    node.clear();
    C::U32(node, static_cast<std::uint32_t>(2 * k + 3));
    C::Dict(node, {});
    C::U32(node, 1);
    C::U32(node, static_cast<std::uint32_t>(k));
    C::Dict(node, {});
    chunks.Chunk("nSHP", node);
  }
}
} // namespace

void WriteVoxScene(std::ostream& out, const VoxModel& model, const std::string& name)
{
  const auto& d = model.Grid.Dimensions();
  if (d[0] > 2048 * 256 || d[1] > 2048 * 256 || d[2] > 2048 * 256)
    throw Error::InFile(name, "cannot hold a model this large");
  std::vector<std::array<std::int64_t, 6>> pieces; // corner and size
  for (std::int64_t z = 0; z < d[2]; z += 256)
    for (std::int64_t y = 0; y < d[1]; y += 256)
      for (std::int64_t x = 0; x < d[0]; x += 256)
        pieces.push_back({ { x, y, z, std::min<std::int64_t>(256, d[0] - x),
          std::min<std::int64_t>(256, d[1] - y), std::min<std::int64_t>(256, d[2] - z) } });
  VoxChunks chunks;
  for (const auto& p : pieces)
    AppendVoxModel(chunks, model, p, name);
  AppendVoxScene(chunks, pieces);
  if (model.Palette.size() == 256)
  {
    std::string rgba;
    for (std::size_t i = 1; i <= 256; ++i)
    {
      const auto& c = i < 256 ? model.Palette[i] : std::array<std::uint8_t, 4>{ { 0, 0, 0, 0 } };
      rgba.append(reinterpret_cast<const char*>(c.data()), 4);
    }
    chunks.Chunk("RGBA", rgba);
  }
  std::string head("VOX ");
  VoxChunks::U32(head, 150);
  head += "MAIN";
  VoxChunks::U32(head, 0);
  VoxChunks::U32(head, static_cast<std::uint32_t>(chunks.Body.size()));
  out.write(head.data(), static_cast<std::streamsize>(head.size()));
  out.write(chunks.Body.data(), static_cast<std::streamsize>(chunks.Body.size()));
}

void WriteVoxSceneFile(const std::string& path, const VoxModel& model)
{
  WriteFileAtomically(path, [&](std::ostream& out) { WriteVoxScene(out, model, path); });
}

} // namespace msynth
