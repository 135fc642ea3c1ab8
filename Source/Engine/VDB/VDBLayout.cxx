// SPDX-License-Identifier: BSD-3-Clause
#include "VDB/VDBLayout.h"

#include "Core/Error.h"

#include <cstdint>
#include <cstring>
#include <fstream>

namespace msynth
{
namespace vdb
{
namespace
{
// Format versions (OpenVDB's version.h) that change the layout walked here.
constexpr std::uint32_t FirstVersionWalked = 220;  ///< selective compression; UUID as text
constexpr std::uint32_t GridInstancing = 216;      ///< descriptors name an instance parent
constexpr std::uint32_t NodeMaskCompression = 222; ///< per-grid compression flags; no file flag

/// Names shorter than this are kept for messages; longer ones are only skipped.
constexpr std::uint32_t NameKept = 256;

/// Reads a file front to back, every length checked against the bytes left.
class LayoutReader
{
public:
  explicit LayoutReader(const std::string& path)
    : Path(path)
    , In(path, std::ios::binary)
  {
    if (!this->In)
      throw Error::InFile(path, "cannot be opened for reading (missing or unreadable)");
    this->In.seekg(0, std::ios::end);
    const std::streamoff size = this->In.tellg();
    this->Size = size > 0 ? static_cast<std::uint64_t>(size) : 0;
    this->In.seekg(0);
  }

  [[noreturn]] void Fail(const std::string& what) const
  {
    throw Error::InFile(this->Path, "is corrupt: " + what);
  }

  std::uint64_t Left() const { return this->Size - this->Pos; }
  std::uint64_t At() const { return this->Pos; }
  std::uint64_t FileSize() const { return this->Size; }

  void Bytes(void* data, std::uint64_t n, const std::string& what)
  {
    if (n > this->Left())
      this->Fail(what + " runs past the end of the file");
    this->In.read(static_cast<char*>(data), static_cast<std::streamsize>(n));
    if (!this->In)
      this->Fail(what + " could not be read");
    this->Pos += n;
  }
  std::uint32_t U32(const std::string& what)
  {
    std::uint32_t v = 0;
    this->Bytes(&v, 4, what);
    return v;
  }
  std::int64_t I64(const std::string& what)
  {
    std::int64_t v = 0;
    this->Bytes(&v, 8, what);
    return v;
  }
  void Skip(std::uint64_t n, const std::string& what)
  {
    if (n > this->Left())
      this->Fail(what + " claims " + std::to_string(n) + " bytes; " + std::to_string(this->Left()) +
        " are left in the file");
    this->Seek(this->Pos + n);
  }
  void Seek(std::uint64_t to)
  {
    this->In.seekg(static_cast<std::streamoff>(to));
    this->Pos = to;
  }
  /// A string as OpenVDB stores it: a 32-bit length, then the bytes.
  std::string Str(const std::string& what)
  {
    const std::uint32_t n = this->U32(what);
    if (n >= NameKept)
    {
      this->Skip(n, what);
      return "(a name of " + std::to_string(n) + " bytes)";
    }
    std::string s(n, '\0');
    this->Bytes(&s[0], n, what);
    return s;
  }

private:
  std::string Path;
  std::ifstream In;
  std::uint64_t Size = 0;
  std::uint64_t Pos = 0;
};

/// A metadata map (MetaMap::readMeta): a count, then per entry a name, a type name and a value
/// of a stated size.
void WalkMetadata(LayoutReader& r, const std::string& owner)
{
  const std::uint32_t count = r.U32("the metadata count of " + owner);
  if (count > r.Left() / 12) // each entry has at least three 32-bit lengths
    r.Fail(owner + " claims " + std::to_string(count) + " metadata entries in " +
      std::to_string(r.Left()) + " bytes");
  for (std::uint32_t i = 0; i < count; ++i)
  {
    const std::string entry = "metadata entry " + std::to_string(i + 1) + " of " + owner;
    const std::string name = r.Str("the name of " + entry);
    const std::string what = "metadata '" + name + "' of " + owner;
    r.Str("the type name of " + what);
    r.Skip(r.U32("the size of " + what), what);
  }
}

/// Grid @p g's descriptor and the start of its data (compression, metadata, transform). With
/// offsets, returns where the next descriptor starts; 0 when the walk must stop here.
std::uint64_t WalkGrid(LayoutReader& r, std::uint32_t version, bool offsets, std::int32_t g)
{
  const std::string number = "grid " + std::to_string(g + 1);
  const std::string name = r.Str("the name of " + number);
  const std::string grid = "grid '" + name + "'";
  r.Str("the type name of " + grid);
  if (version >= GridInstancing)
    r.Str("the instance parent's name of " + grid);
  const std::int64_t gridPos = r.I64("the offsets of " + grid);
  const std::int64_t blockPos = r.I64("the offsets of " + grid);
  const std::int64_t endPos = r.I64("the offsets of " + grid);
  const std::uint64_t here = r.At();
  const auto size = static_cast<std::int64_t>(r.FileSize());
  if (offsets &&
    (gridPos < static_cast<std::int64_t>(here) || blockPos < gridPos || endPos < blockPos ||
      endPos > size))
    r.Fail(grid + " gives data offsets " + std::to_string(gridPos) + ", " +
      std::to_string(blockPos) + ", " + std::to_string(endPos) + " outside the file's " +
      std::to_string(size) + " bytes");
  if (version >= NodeMaskCompression)
    r.U32("the compression flags of " + grid);
  WalkMetadata(r, grid);
  r.Str("the transform type of " + grid);
  // The tree follows; without offsets (or with offsets not relative to the file's start)
  // nothing says where it ends: the rest is OpenVDB's to read.
  return offsets && gridPos == static_cast<std::int64_t>(here) ? static_cast<std::uint64_t>(endPos)
                                                               : 0;
}
} // namespace

void CheckLayout(const std::string& path)
{
  LayoutReader r(path);
  char magic[8] = {};
  if (r.Left() < 8)
    throw Error::InFile(path, "is not a readable OpenVDB file (wrong magic number)");
  r.Bytes(magic, 8, "the header");
  // The 64-bit magic number 0x56444220 ("VDB ") in little endian.
  if (static_cast<unsigned char>(magic[0]) != 0x20 || magic[1] != 'B' || magic[2] != 'D' ||
    magic[3] != 'V')
    throw Error::InFile(path, "is not a readable OpenVDB file (wrong magic number)");
  const std::uint32_t version = r.U32("the header");
  if (version < FirstVersionWalked)
    return; // an old layout: OpenVDB's own reader, in its child process, is the only check
  r.U32("the header"); // library version
  r.U32("the header");
  char offsets = 0;
  r.Bytes(&offsets, 1, "the header");
  if (version < NodeMaskCompression)
    r.Skip(1, "the header"); // the file's compression flag
  r.Skip(36, "the header");  // the UUID as text
  WalkMetadata(r, "the file");
  const auto grids = static_cast<std::int32_t>(r.U32("the grid count"));
  // A descriptor holds at least two string lengths and three offsets.
  if (grids < 0 || static_cast<std::uint64_t>(grids) > r.Left() / 32)
    r.Fail(
      "it claims " + std::to_string(grids) + " grids in " + std::to_string(r.Left()) + " bytes");
  for (std::int32_t g = 0; g < grids; ++g)
  {
    const std::uint64_t next = WalkGrid(r, version, offsets != 0, g);
    if (next == 0)
      return;
    r.Seek(next);
  }
}

} // namespace vdb
} // namespace msynth
