// SPDX-License-Identifier: BSD-3-Clause
#include "Formats/MeshFormats.h"

#include "Core/Error.h"
#include "Core/FileBytes.h"
#include "Core/Index.h"

#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <iterator>
#include <map>
#include <sstream>

namespace msynth
{
namespace
{
std::string Slurp(const std::string& path)
{
  return ReadFileBytes(path, std::uint64_t(1) << 31, "is larger than 2 GB");
}

/// At most 60 characters of @p s for a message (msynth::Error shows control bytes as '?').
std::string Shown(const std::string& s)
{
  return s.substr(0, 60);
}

/// Faces of one type, objects by connectivity; points merged by exact coordinates.
class MeshBuilder
{
public:
  explicit MeshBuilder(const std::string& path) { this->Example.Source = path; }
  int Point(const Point3& p)
  {
    const auto it = this->Index.emplace(p, static_cast<int>(this->Example.Points.size()));
    if (it.second)
      this->Example.Points.push_back(p);
    return it.first->second;
  }
  PolyhedralExample Finish()
  {
    if (this->Example.Faces.empty())
      throw Error::InFile(this->Example.Source, "has no polygons");
    AssignObjectsByConnectivity(this->Example, std::vector<int>(this->Example.Faces.size(), 1));
    return std::move(this->Example);
  }
  PolyhedralExample Example;

private:
  std::map<Point3, int> Index;
};

// ---------------------------------------------------------------------------------------------
// PLY
struct PlyProperty
{
  std::string Name;
  std::string Type;      ///< scalar type, or the item type of a list
  std::string CountType; ///< empty for a scalar property
};

struct PlyElement
{
  std::string Name;
  std::uint64_t Count = 0;
  std::vector<PlyProperty> Properties;
};

int ScalarSize(const std::string& type)
{
  static const std::map<std::string, int> sizes = { { "char", 1 }, { "uchar", 1 }, { "int8", 1 },
    { "uint8", 1 }, { "short", 2 }, { "ushort", 2 }, { "int16", 2 }, { "uint16", 2 }, { "int", 4 },
    { "uint", 4 }, { "int32", 4 }, { "uint32", 4 }, { "float", 4 }, { "float32", 4 },
    { "double", 8 }, { "float64", 8 } };
  const auto it = sizes.find(type);
  return it == sizes.end() ? 0 : it->second;
}

/// Reads values of a PLY body, ascii or binary, with every read checked against the end.
class PlyBody
{
public:
  PlyBody(const std::string& bytes, std::size_t start, int format, const std::string& path)
    : Bytes(bytes)
    , Pos(start)
    , Format(format)
    , Path(path)
  {
  }
  double Read(const std::string& type)
  {
    if (this->Format == 0)
      return this->ReadAscii();
    const int size = ScalarSize(type);
    if (this->Pos + ToIndex(size) > this->Bytes.size())
      throw Error::InFile(
        this->Path, "ends inside its data (byte " + std::to_string(this->Pos) + ")");
    unsigned char b[8];
    std::memcpy(b, this->Bytes.data() + this->Pos, ToIndex(size));
    this->Pos += ToIndex(size);
    if (this->Format == 2) // big endian
      for (int i = 0; i < size / 2; ++i)
        std::swap(b[i], b[size - 1 - i]);
    const bool isSigned = type[0] != 'u';
    if (type == "float" || type == "float32")
    {
      float f;
      std::memcpy(&f, b, 4);
      return f;
    }
    if (type == "double" || type == "float64")
    {
      double d;
      std::memcpy(&d, b, 8);
      return d;
    }
    std::uint64_t u = 0;
    for (int i = size - 1; i >= 0; --i)
      u = (u << 8) | b[i];
    if (isSigned && size < 8 && (u >> (8 * size - 1)))
      return static_cast<double>(static_cast<std::int64_t>(u) - (std::int64_t(1) << (8 * size)));
    return static_cast<double>(u);
  }
  std::size_t Remaining() const { return this->Bytes.size() - this->Pos; }

private:
  double ReadAscii()
  {
    while (this->Pos < this->Bytes.size() &&
      std::isspace(static_cast<unsigned char>(this->Bytes[this->Pos])))
      ++this->Pos;
    const std::size_t start = this->Pos;
    while (this->Pos < this->Bytes.size() &&
      !std::isspace(static_cast<unsigned char>(this->Bytes[this->Pos])))
      ++this->Pos;
    if (start == this->Pos)
      throw Error::InFile(this->Path, "ends inside its data");
    const std::string token =
      this->Bytes.substr(start, std::min<std::size_t>(this->Pos - start, 64));
    char* end = nullptr;
    const double v = std::strtod(token.c_str(), &end);
    if (end == token.c_str() || *end)
      throw Error::InFile(this->Path, "'" + Shown(token) + "' is not a number");
    return v;
  }
  const std::string& Bytes;
  std::size_t Pos;
  int Format; ///< 0 ascii, 1 little endian, 2 big endian
  const std::string& Path;
};

std::uint64_t CheckedIndex(
  double v, std::uint64_t limit, const std::string& path, const std::string& what)
{
  if (!(v >= 0) || v >= static_cast<double>(limit) || v != std::floor(v))
    throw Error::InFile(path,
      what + " " + std::to_string(v) + " is not one of 0.." +
        std::to_string(limit == 0 ? 0 : limit - 1));
  return static_cast<std::uint64_t>(v);
}
} // namespace

namespace
{
/// The PLY header: its format (0 ascii, 1 little endian, 2 big endian) and elements; @p pos
/// ends at the first byte of the body.
int ReadPlyHeader(const std::string& bytes, const std::string& path, std::size_t& pos,
  std::vector<PlyElement>& elements)
{
  auto line = [&]() -> std::string
  {
    const std::size_t end = bytes.find('\n', pos);
    if (end == std::string::npos)
      throw Error::InFile(path, "ends inside its header (no 'end_header')");
    std::string l = bytes.substr(pos, end - pos);
    pos = end + 1;
    if (!l.empty() && l.back() == '\r')
      l.pop_back();
    return l;
  };
  if (bytes.compare(0, 3, "ply") != 0 || line() != "ply")
    throw Error::InFile(path, "is not a PLY file (it does not start with 'ply')");
  int format = -1;
  for (int lines = 0;; ++lines)
  {
    if (lines > 100000)
      throw Error::InFile(path, "has a header of more than 100000 lines");
    std::istringstream words(line());
    std::string keyword;
    words >> keyword;
    if (keyword == "end_header")
      break;
    if (keyword == "comment" || keyword == "obj_info" || keyword.empty())
      continue;
    if (keyword == "format")
    {
      std::string kind, version;
      words >> kind >> version;
      format = kind == "ascii"           ? 0
        : kind == "binary_little_endian" ? 1
        : kind == "binary_big_endian"    ? 2
                                         : -1;
      if (format < 0 || version != "1.0")
        throw Error::InFile(path,
          "has format '" + Shown(kind + " " + version) +
            "'; ascii, binary_little_endian and binary_big_endian 1.0 are read");
    }
    else if (keyword == "element")
    {
      PlyElement e;
      std::string count;
      words >> e.Name >> count;
      char* end = nullptr;
      const unsigned long long n = std::strtoull(count.c_str(), &end, 10);
      if (e.Name.empty() || count.empty() || *end || count[0] == '-')
        throw Error::InFile(path, "has an element line without a name and count");
      e.Count = n;
      elements.push_back(e);
    }
    else if (keyword == "property")
    {
      if (elements.empty())
        throw Error::InFile(path, "has a property before any element");
      PlyProperty p;
      std::string type;
      words >> type;
      if (type == "list")
        words >> p.CountType >> p.Type >> p.Name;
      else
      {
        p.Type = type;
        words >> p.Name;
      }
      if (!ScalarSize(p.Type) || (!p.CountType.empty() && !ScalarSize(p.CountType)) ||
        p.Name.empty())
        throw Error::InFile(path, "has a property of unknown type '" + Shown(type) + "'");
      if (!p.CountType.empty() &&
        (p.CountType.find("float") != std::string::npos || p.CountType == "double"))
        throw Error::InFile(path, "has a list counted by a floating-point type");
      elements.back().Properties.push_back(p);
    }
    else
      throw Error::InFile(path, "has an unknown header line '" + Shown(keyword) + "'");
  }
  if (format < 0)
    throw Error::InFile(path, "has no format line");
  return format;
}
} // namespace

PolyhedralExample ReadPLYExample(const std::string& path)
{
  const std::string bytes = Slurp(path);
  std::size_t pos = 0;
  std::vector<PlyElement> elements;
  const int format = ReadPlyHeader(bytes, path, pos, elements);
  PlyBody body(bytes, pos, format, path);
  MeshBuilder mesh(path);
  std::vector<int> pointOf; // PLY vertex index -> merged point
  bool sawVertices = false;
  for (const auto& e : elements)
  {
    // Every element takes at least one byte (binary) or two characters (ascii): a count the
    // file cannot hold is refused before anything is allocated.
    std::uint64_t minimum = 0;
    for (const auto& p : e.Properties)
      minimum += format == 0
        ? 2
        : static_cast<std::uint64_t>(ScalarSize(p.CountType.empty() ? p.Type : p.CountType));
    if (e.Count > 0 && (minimum == 0 || e.Count > body.Remaining() / minimum))
      throw Error::InFile(path,
        "declares " + std::to_string(e.Count) + " " + Shown(e.Name) + " elements, more than its " +
          std::to_string(body.Remaining()) + " bytes of data hold");
    const bool vertex = e.Name == "vertex", face = e.Name == "face";
    if (vertex)
    {
      sawVertices = true;
      pointOf.reserve(ToIndex(e.Count));
    }
    for (std::uint64_t i = 0; i < e.Count; ++i)
    {
      Point3 p{ { 0, 0, 0 } };
      std::vector<int> polygon;
      for (const auto& prop : e.Properties)
      {
        if (prop.CountType.empty())
        {
          const double v = body.Read(prop.Type);
          if (vertex && (prop.Name == "x" || prop.Name == "y" || prop.Name == "z"))
          {
            if (!std::isfinite(v))
              throw Error::InFile(
                path, "vertex " + std::to_string(i) + " has a coordinate that is not finite");
            p[ToIndex(prop.Name[0] - 'x')] = v;
          }
          continue;
        }
        const double count = body.Read(prop.CountType);
        if (!(count >= 0) || count > 1e6 ||
          count * (format == 0 ? 2 : ScalarSize(prop.Type)) > static_cast<double>(body.Remaining()))
          throw Error::InFile(path,
            Shown(e.Name) + " " + std::to_string(i) + " has a list of " + std::to_string(count) +
              " items, more than the file holds");
        const bool indices = face && (prop.Name == "vertex_indices" || prop.Name == "vertex_index");
        for (int k = 0; k < static_cast<int>(count); ++k)
        {
          const double v = body.Read(prop.Type);
          if (indices)
          {
            if (!sawVertices)
              throw Error::InFile(path, "has faces before its vertices");
            polygon.push_back(pointOf[CheckedIndex(
              v, pointOf.size(), path, "face " + std::to_string(i) + ": vertex index")]);
          }
        }
      }
      if (vertex)
        pointOf.push_back(mesh.Point(p));
      if (face)
      {
        if (polygon.size() < 3)
          throw Error::InFile(path, "face " + std::to_string(i) + " has fewer than 3 vertices");
        mesh.Example.Faces.push_back(std::move(polygon));
      }
    }
  }
  return mesh.Finish();
}

PolyhedralExample ReadSTLExample(const std::string& path)
{
  const std::string bytes = Slurp(path);
  MeshBuilder mesh(path);
  // Binary when the declared triangles fill the file exactly (some binary files start with
  // "solid" too), ascii when it starts with "solid", else binary with a checked count.
  bool binary = true;
  std::uint32_t count = 0;
  if (bytes.size() >= 84)
  {
    std::memcpy(&count, bytes.data() + 80, 4); // little endian on every platform we build for
    binary = 84 + 50 * static_cast<std::uint64_t>(count) == bytes.size() ||
      bytes.compare(0, 5, "solid") != 0;
  }
  else
    binary = bytes.compare(0, 5, "solid") != 0;
  if (binary)
  {
    if (bytes.size() < 84)
      throw Error::InFile(path,
        "is not an STL file (" + std::to_string(bytes.size()) +
          " bytes, less than a binary header)");
    if (84 + 50 * static_cast<std::uint64_t>(count) > bytes.size())
      throw Error::InFile(path,
        "declares " + std::to_string(count) + " triangles but holds " +
          std::to_string((bytes.size() - 84) / 50));
    for (std::uint32_t t = 0; t < count; ++t)
    {
      std::vector<int> face;
      for (int v = 0; v < 3; ++v)
      {
        float xyz[3];
        std::memcpy(xyz, bytes.data() + 84 + 50 * ToIndex(t) + 12 + 12 * ToIndex(v), 12);
        if (!std::isfinite(xyz[0]) || !std::isfinite(xyz[1]) || !std::isfinite(xyz[2]))
          throw Error::InFile(
            path, "triangle " + std::to_string(t) + " has a coordinate that is not finite");
        face.push_back(mesh.Point({ { xyz[0], xyz[1], xyz[2] } }));
      }
      mesh.Example.Faces.push_back(std::move(face));
    }
    return mesh.Finish();
  }
  std::istringstream words(bytes);
  std::string word;
  std::vector<int> loop;
  bool inLoop = false;
  while (words >> word)
  {
    if (word == "outer")
    {
      loop.clear();
      inLoop = true;
    }
    else if (word == "vertex")
    {
      Point3 p;
      for (auto& c : p)
      {
        std::string token;
        words >> token;
        char* end = nullptr;
        c = std::strtod(token.c_str(), &end);
        if (token.empty() || *end || !std::isfinite(c))
          throw Error::InFile(path, "a vertex has the coordinate '" + Shown(token) + "'");
      }
      if (!inLoop)
        throw Error::InFile(path, "has a vertex outside 'outer loop'");
      loop.push_back(mesh.Point(p));
    }
    else if (word == "endloop")
    {
      if (loop.size() < 3)
        throw Error::InFile(path, "has a facet with fewer than 3 vertices");
      mesh.Example.Faces.push_back(loop);
      inLoop = false;
    }
  }
  return mesh.Finish();
}

} // namespace msynth
