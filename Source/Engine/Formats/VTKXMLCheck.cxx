// SPDX-License-Identifier: BSD-3-Clause
#include "Formats/VTKXMLCheck.h"

#include "Core/Error.h"
#include "Core/FileBytes.h"

#include "Core/Index.h"
#include "Formats/Xml.h"

#include <lz4.h>
#include <lzma.h>
#include <zlib.h>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <iterator>
#include <limits>
#include <map>

namespace msynth
{
namespace
{
using detail::XmlElement;
using detail::XmlReader;

constexpr std::uint64_t MaximumBytes = std::uint64_t(1) << 32; ///< per array, uncompressed

int TypeSize(const std::string& type)
{
  static const std::map<std::string, int> sizes = { { "Int8", 1 }, { "UInt8", 1 }, { "Int16", 2 },
    { "UInt16", 2 }, { "Int32", 4 }, { "UInt32", 4 }, { "Int64", 8 }, { "UInt64", 8 },
    { "Float32", 4 }, { "Float64", 8 }, { "String", 1 }, { "Char", 1 }, { "Bit", 1 },
    { "IdType", 8 } };
  const auto it = sizes.find(type);
  return it == sizes.end() ? 0 : it->second;
}

bool IsBase64(char c)
{
  return std::isalnum(static_cast<unsigned char>(c)) || c == '+' || c == '/' || c == '=';
}

int Base64Value(char c)
{
  if (c >= 'A' && c <= 'Z')
    return c - 'A';
  if (c >= 'a' && c <= 'z')
    return c - 'a' + 26;
  if (c >= '0' && c <= '9')
    return c - '0' + 52;
  return c == '+' ? 62 : c == '/' ? 63 : -1;
}

/// Decodes the base64 characters [from, from + n) of @p text (no white space inside).
std::string Base64(const std::string& text, std::size_t from, std::size_t n)
{
  std::string out;
  out.reserve(n / 4 * 3);
  for (std::size_t i = from; i + 3 < from + n && i + 3 < text.size(); i += 4)
  {
    int v[4];
    int valid = 4;
    for (int k = 0; k < 4; ++k)
    {
      v[k] = Base64Value(text[i + ToIndex(k)]);
      if (v[k] < 0)
      {
        valid = std::min(valid, k);
        v[k] = 0;
      }
    }
    const std::uint32_t w = (std::uint32_t(v[0]) << 18) | (std::uint32_t(v[1]) << 12) |
      (std::uint32_t(v[2]) << 6) | std::uint32_t(v[3]);
    if (valid >= 2)
      out += static_cast<char>((w >> 16) & 255);
    if (valid >= 3)
      out += static_cast<char>((w >> 8) & 255);
    if (valid >= 4)
      out += static_cast<char>(w & 255);
  }
  return out;
}

/// Where an array's bytes are: raw bytes, or base64 text to decode piece by piece.
struct Source
{
  const std::string* Text = nullptr;
  std::size_t Start = 0; ///< offset in Text
  bool Encoded = false;  ///< base64
};

class Checker
{
public:
  Checker(const std::string& path)
    : Path(path)
  {
  }

  [[noreturn]] void Fail(const std::string& what) const { throw Error::InFile(this->Path, what); }

  void Run(const std::string& bytes)
  {
    // The XML part: the whole file, or what comes before the appended data (raw bytes follow
    // "<AppendedData encoding=...>" and the marker '_').
    std::string xmlText = bytes;
    const std::size_t appended = bytes.find("<AppendedData");
    std::string appendedEncoding;
    if (appended != std::string::npos)
    {
      const std::size_t tagEnd = bytes.find('>', appended);
      const std::size_t marker =
        tagEnd == std::string::npos ? tagEnd : bytes.find_first_not_of(" \t\r\n", tagEnd + 1);
      if (marker == std::string::npos || bytes[marker] != '_')
        this->Fail("its <AppendedData> does not start with '_'");
      XmlReader tag(bytes.substr(appended, tagEnd - appended) + "/>", this->Path);
      const XmlElement e = tag.Parse();
      appendedEncoding = e.Attribute("encoding") ? *e.Attribute("encoding") : "base64";
      if (appendedEncoding != "raw" && appendedEncoding != "base64")
        this->Fail("its appended data have encoding '" + appendedEncoding + "'");
      this->Appended = bytes.substr(marker + 1);
      xmlText = bytes.substr(0, appended);
      const std::size_t root = xmlText.find("<VTKFile");
      if (root == std::string::npos)
        this->Fail("is not a VTK XML file (no <VTKFile>)");
      xmlText += "</VTKFile>";
      if (appendedEncoding == "base64")
      {
        // Keep only the base64 characters (the closing tags follow the data).
        std::string clean;
        for (char c : this->Appended)
        {
          if (c == '<')
            break;
          if (IsBase64(c))
            clean += c;
        }
        this->Appended = clean;
      }
    }
    this->AppendedEncoded = appendedEncoding == "base64";
    XmlReader reader(xmlText, this->Path);
    XmlElement root;
    try
    {
      root = reader.Parse();
    }
    catch (const Error& e)
    {
      // "'path', line N: problem" -> "line N: problem"
      const std::string text = e.what();
      const std::size_t cut = text.find(", line ");
      this->Fail(cut == std::string::npos ? text : text.substr(cut + 2));
    }
    if (root.Name != "VTKFile")
      this->Fail("is not a VTK XML file (its top element is <" + root.Name + ">)");
    const std::string* header = root.Attribute("header_type");
    this->HeaderSize = !header || *header == "UInt32" ? 4 : *header == "UInt64" ? 8 : 0;
    if (!this->HeaderSize)
      this->Fail("has header_type '" + *header + "' (UInt32 or UInt64)");
    const std::string* order = root.Attribute("byte_order");
    if (order && *order != "LittleEndian" && *order != "BigEndian")
      this->Fail("has byte_order '" + *order + "'");
    this->Swap = order && *order == "BigEndian";
    if (const std::string* compressor = root.Attribute("compressor"))
    {
      if (*compressor == "vtkZLibDataCompressor")
        this->Compressor = 1;
      else if (*compressor == "vtkLZ4DataCompressor")
        this->Compressor = 2;
      else if (*compressor == "vtkLZMADataCompressor")
        this->Compressor = 3;
      else if (!compressor->empty())
        this->Fail("uses the compressor '" + *compressor + "', which is not known");
    }
    this->Walk(root, 0, 0);
  }

private:
  /**
   * The points of the extent attribute @p name of @p e ("x0 x1 y0 y1 z0 z1"), 0 when it is
   * absent, not six numbers, or too large to count (left to the reader's own limit, whose
   * message names it). @throw Error when an axis is reversed (its end before its start): VTK
   * sizes its arrays from such extents without checking them.
   */
  std::uint64_t ExtentPoints(const XmlElement& e, const char* name, std::uint64_t* cells) const
  {
    const std::string* extent = e.Attribute(name);
    long long x[6] = { 0, 0, 0, 0, 0, 0 };
    if (!extent ||
      std::sscanf(extent->c_str(), "%lld %lld %lld %lld %lld %lld", &x[0], &x[1], &x[2], &x[3],
        &x[4], &x[5]) != 6)
      return 0;
    std::uint64_t points = 1, n[3] = { 0, 0, 0 };
    constexpr long long bound = 1LL << 40; // no overflow in the differences below
    for (int a = 0; a < 3; ++a)
    {
      if (x[2 * a + 1] < x[2 * a])
        this->Fail(std::string("has a reversed ") + name + " '" + *extent + "' (axis " + "xyz"[a] +
          " ends before it starts)");
      const auto inBound = [](long long v) { return v >= -bound && v <= bound; };
      if (!inBound(x[2 * a]) || !inBound(x[2 * a + 1]) || x[2 * a + 1] - x[2 * a] >= (1LL << 20))
        return 0;
      n[a] = static_cast<std::uint64_t>(x[2 * a + 1] - x[2 * a] + 1);
      points *= n[a];
    }
    if (points > (std::uint64_t(1) << 40))
      return 0;
    if (cells)
      *cells = std::max<std::uint64_t>(n[0] - 1, 1) * std::max<std::uint64_t>(n[1] - 1, 1) *
        std::max<std::uint64_t>(n[2] - 1, 1);
    return points;
  }

  /**
   * A structured dataset (<ImageData>, <RectilinearGrid>, <StructuredGrid>): its pieces must
   * hold every point of its WholeExtent, which VTK's reader allocates before it reads them (a
   * WholeExtent of 10^10 points over a piece of four would ask for that much memory).
   */
  void WalkStructured(const XmlElement& e)
  {
    const std::uint64_t whole = this->ExtentPoints(e, "WholeExtent", nullptr);
    this->PiecePoints = 0;
    this->Walk(e, 0, 0);
    const std::string* extent = e.Attribute("WholeExtent");
    if (extent && whole == 0)
      this->Fail("has a WholeExtent '" + *extent +
        "' too large to read (over 2^20 points along an axis or 2^40 in all)");
    if (extent && this->PiecePoints < whole)
      this->Fail("has a WholeExtent '" + *extent + "' of " + std::to_string(whole) +
        " points, but its pieces hold " + std::to_string(this->PiecePoints));
  }

  /// Visits @p e; @p points and @p cells are the current piece's counts (0: unknown).
  void Walk(const XmlElement& e, std::uint64_t points, std::uint64_t cells)
  {
    if (e.Name == "Piece")
    {
      cells = 0;
      points = this->ExtentPoints(e, "Extent", &cells);
      // The counts size-check the piece's arrays.
      this->PiecePoints += points;
    }
    const std::string parent = e.Name;
    // VTK's readers take every element inside these as an array, whatever its name.
    static const char* const holders[] = { "FieldData", "PointData", "CellData", "Points", "Cells",
      "Verts", "Lines", "Strips", "Polys", "Coordinates" };
    const bool holdsArrays = std::any_of(
      std::begin(holders), std::end(holders), [&parent](const char* h) { return parent == h; });
    for (const auto& child : e.Children)
    {
      if (child.Name == "ImageData" || child.Name == "RectilinearGrid" ||
        child.Name == "StructuredGrid")
        this->WalkStructured(child);
      else if (holdsArrays || child.Name == "DataArray" || child.Name == "Array")
      {
        std::uint64_t tuples = 0;
        if (parent == "PointData")
          tuples = points;
        else if (parent == "CellData")
          tuples = cells;
        this->CheckArray(child, tuples);
      }
      else
        this->Walk(child, points, cells);
    }
  }

  std::uint64_t Word(const std::string& bytes, std::size_t at) const
  {
    std::uint64_t v = 0;
    for (int i = 0; i < this->HeaderSize; ++i)
    {
      const int k = this->Swap ? i : this->HeaderSize - 1 - i;
      v = (v << 8) | static_cast<unsigned char>(bytes[at + ToIndex(k)]);
    }
    return v;
  }

  /// @p n bytes of @p src from byte @p offset (raw), or from the encoded unit at @p offset.
  std::string Take(
    const Source& src, std::size_t offset, std::uint64_t n, const std::string& what) const
  {
    const std::string& t = *src.Text;
    if (!src.Encoded)
    {
      if (src.Start + offset > t.size() || n > t.size() - src.Start - offset)
        this->Fail(what + " needs " + std::to_string(n) + " bytes, more than the file holds");
      return t.substr(src.Start + offset, ToIndex(n));
    }
    const std::uint64_t chars = (n + 2) / 3 * 4;
    if (src.Start + offset > t.size() || chars > t.size() - src.Start - offset)
      this->Fail(what + " needs " + std::to_string(n) + " bytes, more than the file holds");
    std::string out = Base64(t, src.Start + offset, ToIndex(chars));
    if (out.size() < n)
      this->Fail(what + " is not valid base64");
    out.resize(ToIndex(n));
    return out;
  }

  /// The array's uncompressed bytes' count, checking every header; fills @p data with the
  /// uncompressed bytes when @p decode.
  std::uint64_t Binary(
    const Source& src, const std::string& what, bool decode, std::string& data) const
  {
    const std::size_t hs = ToIndex(this->HeaderSize);
    if (!this->Compressor)
    {
      const std::uint64_t n = this->Word(this->Take(src, 0, hs, what + " (header)"), 0);
      if (n > MaximumBytes)
        this->Fail(what + " declares " + std::to_string(n) + " bytes");
      // Header and data are one unit (one base64 stream when encoded).
      const std::string both = this->Take(src, 0, hs + n, what);
      if (decode)
        data = both.substr(hs);
      return n;
    }
    const std::string head = this->Take(src, 0, 3 * hs, what + " (compression header)");
    const std::uint64_t blocks = this->Word(head, 0), blockSize = this->Word(head, hs),
                        lastSize = this->Word(head, 2 * hs);
    // VTK computes the size as blocks * blockSize - blockSize + lastSize (when lastSize is not
    // 0) and divides by blockSize whenever that is not 0: with no blocks, a last size alone
    // made it divide by zero.
    if (blocks > (std::uint64_t(1) << 24) || lastSize > blockSize || blockSize > MaximumBytes ||
      (blocks > 0 && blockSize == 0) || (blocks == 0 && lastSize > 0))
      this->Fail(what + " has a compression header of " + std::to_string(blocks) + " blocks of " +
        std::to_string(blockSize) + " bytes (the last " + std::to_string(lastSize) + ")");
    const std::uint64_t headerBytes = (3 + blocks) * hs;
    const std::string full = this->Take(src, 0, headerBytes, what + " (compression header)");
    const std::size_t dataStart =
      src.Encoded ? ToIndex((headerBytes + 2) / 3 * 4) : ToIndex(headerBytes);
    std::uint64_t total = 0;
    std::vector<std::uint64_t> sizes;
    for (std::uint64_t b = 0; b < blocks; ++b)
    {
      sizes.push_back(this->Word(full, ToIndex((3 + b) * hs)));
      total += sizes.back();
      if (sizes.back() > MaximumBytes || total > MaximumBytes)
        this->Fail(what + " declares compressed blocks larger than the file");
    }
    const std::string compressed = this->Take(src, dataStart, total, what + " (compressed data)");
    const std::uint64_t uncompressed =
      blocks == 0 ? 0 : (blocks - 1) * blockSize + (lastSize ? lastSize : blockSize);
    if (uncompressed > MaximumBytes)
      this->Fail(what + " declares " + std::to_string(uncompressed) + " bytes");
    if (decode)
    {
      std::size_t at = 0;
      for (std::uint64_t b = 0; b < blocks; ++b)
      {
        const std::uint64_t want = b + 1 == blocks && lastSize ? lastSize : blockSize;
        std::string out(ToIndex(want), '\0');
        const std::size_t in = ToIndex(sizes[ToIndex(b)]);
        bool ok = false;
        if (this->Compressor == 1)
        {
          uLongf length = static_cast<uLongf>(want);
          ok = uncompress(reinterpret_cast<Bytef*>(&out[0]), &length,
                 reinterpret_cast<const Bytef*>(compressed.data() + at),
                 static_cast<uLong>(in)) == Z_OK &&
            length == want;
        }
        else if (this->Compressor == 2)
        {
          ok = in <= ToIndex(std::numeric_limits<int>::max()) &&
            LZ4_decompress_safe(compressed.data() + at, &out[0], static_cast<int>(in),
              static_cast<int>(want)) == static_cast<int>(want);
        }
        else
        {
          std::uint64_t memlimit = 1ULL << 30;
          std::size_t inPos = 0, outPos = 0;
          ok = lzma_stream_buffer_decode(&memlimit, 0, nullptr,
                 reinterpret_cast<const std::uint8_t*>(compressed.data() + at), &inPos, in,
                 reinterpret_cast<std::uint8_t*>(&out[0]), &outPos, out.size()) == LZMA_OK &&
            outPos == want;
        }
        if (!ok)
          this->Fail(what + ": block " + std::to_string(b) + " does not decompress to its size");
        data += out;
        at += in;
      }
    }
    return uncompressed;
  }

  void CheckArray(const XmlElement& a, std::uint64_t tuples)
  {
    const std::string name = a.Attribute("Name") ? *a.Attribute("Name") : std::string("(unnamed)");
    const std::string what = "array '" + name + "'";
    const std::string type = a.Attribute("type") ? *a.Attribute("type") : std::string();
    const int size = TypeSize(type);
    if (!size)
      this->Fail(what + " has type '" + type + "', which VTK does not know");
    long long components = 1;
    if (const std::string* c = a.Attribute("NumberOfComponents"))
      components = std::atoll(c->c_str());
    if (components < 1 || components > 1000000)
      this->Fail(what + " has " + std::to_string(components) + " components");
    if (const std::string* t = a.Attribute("NumberOfTuples"))
    {
      const long long n = std::atoll(t->c_str());
      if (n < 0 || static_cast<std::uint64_t>(n) > MaximumBytes)
        this->Fail(what + " declares " + *t + " tuples");
      tuples = static_cast<std::uint64_t>(n);
    }
    const std::uint64_t values = tuples * static_cast<std::uint64_t>(components);
    const bool strings = type == "String";
    const std::string format =
      a.Attribute("format") ? *a.Attribute("format") : std::string("ascii");
    std::string data;
    std::uint64_t bytes = 0;
    if (format == "ascii")
    {
      if (strings)
      {
        // Character codes; each string ends with 0.
        std::uint64_t count = 0;
        const char* p = a.Text.c_str();
        char* end = nullptr;
        for (long v = std::strtol(p, &end, 10); end != p; p = end, v = std::strtol(p, &end, 10))
          count += v == 0;
        data.assign(ToIndex(count), '\0');
      }
      else
        return; // numbers as text: VTK's reader checks their count
    }
    else if (format == "binary")
    {
      std::string clean;
      for (char c : a.Text)
        if (IsBase64(c))
          clean += c;
      const Source src{ &clean, 0, true };
      bytes = this->Binary(src, what, strings, data);
    }
    else if (format == "appended")
    {
      const std::string* offset = a.Attribute("offset");
      const long long at = offset ? std::atoll(offset->c_str()) : -1;
      if (at < 0 ||
        static_cast<std::uint64_t>(at) >= this->Appended.size() + (this->Appended.empty() ? 1 : 0))
        this->Fail(what + " has offset '" + (offset ? *offset : std::string()) +
          "', outside the appended data");
      const Source src{ &this->Appended, ToIndex(at), this->AppendedEncoded };
      bytes = this->Binary(src, what, strings, data);
    }
    else
      this->Fail(what + " has format '" + format + "' (ascii, binary or appended)");
    if (strings)
    {
      std::uint64_t count = 0;
      for (char c : data)
        count += c == '\0';
      if (count != values)
        this->Fail(what + " holds " + std::to_string(count) + " strings but declares " +
          std::to_string(values));
    }
    else if (values > 0 && type != "Bit" && bytes != values * static_cast<std::uint64_t>(size))
      this->Fail(what + " holds " + std::to_string(bytes) + " bytes; " + std::to_string(values) +
        " values of " + type + " need " +
        std::to_string(values * static_cast<std::uint64_t>(size)));
  }

  std::string Path;
  std::string Appended;
  bool AppendedEncoded = false;
  int HeaderSize = 4;
  bool Swap = false;
  int Compressor = 0;            ///< 0 none, 1 zlib, 2 LZ4, 3 LZMA
  std::uint64_t PiecePoints = 0; ///< the points of the current structured dataset's pieces
};
} // namespace

void CheckVTKXMLFile(const std::string& path)
{
  Checker(path).Run(ReadFileBytes(path, MaximumBytes, "is larger than 4 GB"));
}

} // namespace msynth
