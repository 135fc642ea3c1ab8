// SPDX-License-Identifier: BSD-3-Clause
#include "Formats/VoxSummary.h"

#include "Core/Error.h"
#include "Core/Index.h"

#include <sys/stat.h>

#include <fstream>
#include <map>
#include <set>
#include <sstream>

namespace msynth
{
namespace
{
// ---------------------------------------------------------------------------------------------
// internal
// ---------------------------------------------------------------------------------------------
/// Reads little-endian values from [Pos, End) of the bytes, failing with the file's name.
struct Reader
{
  const std::vector<std::uint8_t>& Bytes;
  const std::string& Name;
  std::size_t Pos = 0;
  std::size_t End = 0;

  [[noreturn]] void Fail(const std::string& problem) const
  {
    throw Error::InFile(Name, "is not a MagicaVoxel file we read (" + problem + ")");
  }
  void Need(std::uint64_t n, const char* what) const
  {
    if (n > this->End - this->Pos)
      this->Fail(std::string(what) + " runs past the end of its chunk");
  }
  std::int64_t I32(const char* what = "a number")
  {
    this->Need(4, what);
    const std::size_t p = this->Pos;
    this->Pos += 4;
    const std::uint32_t v = std::uint32_t(this->Bytes[p]) | std::uint32_t(this->Bytes[p + 1]) << 8 |
      std::uint32_t(this->Bytes[p + 2]) << 16 | std::uint32_t(this->Bytes[p + 3]) << 24;
    return static_cast<std::int32_t>(v);
  }
  std::string Text()
  {
    const std::int64_t n = this->I32("a string");
    if (n < 0)
      this->Fail("a string of negative length");
    this->Need(static_cast<std::uint64_t>(n), "a string");
    std::string s(this->Bytes.begin() + static_cast<std::ptrdiff_t>(this->Pos),
      this->Bytes.begin() + static_cast<std::ptrdiff_t>(this->Pos) + n);
    this->Pos += ToIndex(n);
    return s;
  }
  std::map<std::string, std::string> Dict()
  {
    std::map<std::string, std::string> d;
    const std::int64_t n = this->I32("a dictionary");
    if (n < 0 || static_cast<std::uint64_t>(n) > (this->End - this->Pos) / 8)
      this->Fail("a dictionary of " + std::to_string(n) + " entries");
    for (std::int64_t i = 0; i < n; ++i)
    {
      std::string key = this->Text();
      d[key] = this->Text();
    }
    return d;
  }
};

/// A scene node: a transform (translation, one child), a group (children) or a shape (models).
struct Node
{
  char Type = 'T';
  std::array<std::int64_t, 3> Translation{ { 0, 0, 0 } };
  std::vector<std::int64_t> Children; ///< nodes, or for a shape its models
};

void ReadNode(Reader& r, const std::string& id, std::map<std::int64_t, Node>& nodes)
{
  const std::int64_t key = r.I32("a node id");
  r.Dict();
  Node node;
  node.Type = id[1] == 'T' ? 'T' : (id[1] == 'G' ? 'G' : 'S');
  if (node.Type == 'T')
  {
    node.Children.push_back(r.I32());
    r.I32(); // reserved
    r.I32(); // layer
    const std::int64_t frames = r.I32("a frame count");
    if (frames < 0 || frames > 65536)
      r.Fail("a transform of " + std::to_string(frames) + " frames");
    for (std::int64_t f = 0; f < frames; ++f)
    {
      auto d = r.Dict();
      std::istringstream t(d.count("_t") ? d["_t"] : "");
      if (f == 0 && d.count("_t") &&
        !(t >> node.Translation[0] >> node.Translation[1] >> node.Translation[2]))
        r.Fail("a translation that is not three integers");
    }
  }
  else
  {
    const std::int64_t n = r.I32("a child count");
    if (n < 0 || static_cast<std::uint64_t>(n) > (r.End - r.Pos) / 4)
      r.Fail("a node of " + std::to_string(n) + " children");
    for (std::int64_t i = 0; i < n; ++i)
    {
      node.Children.push_back(r.I32());
      if (node.Type == 'S')
        r.Dict();
    }
  }
  if (!nodes.emplace(key, std::move(node)).second)
    r.Fail("two scene nodes with the id " + std::to_string(key));
}

/// Places the models under @p key: translations summed from the root (each node once).
void Place(Reader& r, const std::map<std::int64_t, Node>& nodes, std::int64_t key,
  std::array<std::int64_t, 3> at, std::set<std::int64_t>& seen, int depth, VoxSummary& s)
{
  const auto it = nodes.find(key);
  if (it == nodes.end())
    r.Fail("the scene names a missing node " + std::to_string(key));
  if (!seen.insert(key).second || depth > 64)
    r.Fail("the scene's nodes form a loop or are nested too deep");
  const Node& node = it->second;
  for (std::size_t a = 0; a < 3; ++a)
    at[a] += node.Translation[a];
  for (std::int64_t child : node.Children)
  {
    if (node.Type != 'S')
    {
      Place(r, nodes, child, at, seen, depth + 1, s);
      continue;
    }
    if (child < 0 || child >= static_cast<std::int64_t>(s.Models.size()))
      r.Fail("a shape names a missing model " + std::to_string(child));
    auto& model = s.Models[ToIndex(child)];
    model.Translation = at;
    model.Placed = true;
  }
}

void ReadChunk(Reader& r, const std::string& id, std::map<std::int64_t, Node>& nodes, VoxSummary& s)
{
  if (id == "SIZE")
  {
    VoxModelSummary m;
    for (auto& n : m.Size)
      if ((n = r.I32("a size")) < 1)
        r.Fail("a model of size " + std::to_string(n));
    s.Models.push_back(m);
  }
  else if (id == "XYZI")
  {
    if (s.Models.empty() || s.Models.back().Voxels > 0)
      r.Fail("an XYZI chunk does not follow a SIZE chunk");
    const std::int64_t n = r.I32("a voxel count");
    if (n < 0 || static_cast<std::uint64_t>(n) > (r.End - r.Pos) / 4)
      r.Fail("XYZI declares " + std::to_string(n) + " voxels but holds fewer");
    for (std::int64_t i = 0; i < n; ++i)
      ++s.Uses[r.Bytes[r.Pos + ToIndex(4 * i + 3)]];
    s.Models.back().Voxels = n;
  }
  else if (id == "RGBA")
  {
    r.Need(1024, "the RGBA chunk");
    s.HasPalette = true;
    s.Palette.assign(256, { { 0, 0, 0, 0 } });
    for (std::size_t i = 0; i < 255; ++i) // entry i is the colour of index i + 1
      for (std::size_t c = 0; c < 4; ++c)
        s.Palette[i + 1][c] = r.Bytes[r.Pos + 4 * i + c];
  }
  else if (id == "nTRN" || id == "nGRP" || id == "nSHP")
  {
    ReadNode(r, id, nodes);
    ++s.SceneNodes;
  }
}
} // namespace

VoxSummary SummarizeVox(const std::vector<std::uint8_t>& bytes, const std::string& name)
{
  Reader r{ bytes, name, 0, bytes.size() };
  r.Need(8, "the header");
  if (std::string(bytes.begin(), bytes.begin() + 4) != "VOX ")
    throw Error::InFile(name, "is not a MagicaVoxel file (no 'VOX ' header)");
  r.Pos = 4;
  VoxSummary s;
  s.Version = r.I32();
  r.Need(12, "the MAIN chunk");
  if (std::string(bytes.begin() + 8, bytes.begin() + 12) != "MAIN")
    r.Fail("no MAIN chunk");
  r.Pos = 12;
  const std::int64_t content = r.I32(), children = r.I32();
  if (content < 0 || children < 0)
    r.Fail("the MAIN chunk has a negative length");
  r.Need(static_cast<std::uint64_t>(content) + static_cast<std::uint64_t>(children), "MAIN");
  r.Pos += ToIndex(content);
  std::map<std::int64_t, Node> nodes;
  while (r.Pos < r.End)
  {
    r.Need(12, "a chunk header");
    const std::string id(bytes.begin() + static_cast<std::ptrdiff_t>(r.Pos),
      bytes.begin() + static_cast<std::ptrdiff_t>(r.Pos) + 4);
    r.Pos += 4;
    const std::int64_t size = r.I32(), nested = r.I32();
    if (size < 0 || nested < 0)
      r.Fail("chunk '" + id + "' has a negative length");
    r.Need(static_cast<std::uint64_t>(size) + static_cast<std::uint64_t>(nested), "a chunk");
    Reader chunk{ bytes, name, r.Pos, r.Pos + ToIndex(size) };
    ReadChunk(chunk, id, nodes, s);
    r.Pos += ToIndex(size + nested);
  }
  if (s.Models.empty())
    r.Fail("no model (SIZE and XYZI chunks) found");
  if (!nodes.empty())
  {
    std::set<std::int64_t> seen;
    Place(r, nodes, 0, { { 0, 0, 0 } }, seen, 0, s);
  }
  return s;
}

VoxSummary ReadVoxSummary(const std::string& path)
{
  struct stat info;
  if (::stat(path.c_str(), &info) != 0 || !S_ISREG(info.st_mode))
    throw Error::InFile(path, "cannot be read (missing or not a file)");
  if (info.st_size > (std::int64_t(1) << 28))
    throw Error::InFile(path, "is larger than 256 MiB");
  std::vector<std::uint8_t> bytes(ToIndex(info.st_size));
  std::ifstream in(path, std::ios::binary);
  in.read(reinterpret_cast<char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
  if (!in)
    throw Error::InFile(path, "could not be read");
  return SummarizeVox(bytes, path);
}

} // namespace msynth
