// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/**
 * @file IsolatedRead.h
 * @brief Reading in a child process (internal): OpenVDB trusts sizes in the file (a negative
 * Blosc chunk size overflows its buffer), so the library reads in a forked child; only our own
 * serialization of the result crosses back, checked as untrusted data. A crash or overflow ends
 * the child, and the parent reports the file as corrupt. No OpenVDB header here: ReadFile and
 * ListGrids (VDBFile.h) are defined in IsolatedRead.cxx, the child's reads in VDBFile.cxx.
 */
#include "Core/Error.h"
#include "Core/Index.h"
#include "VDB/VDBFile.h"

#include <cstdint>
#include <cstring>
#include <functional>
#include <limits>
#include <string>
#include <unistd.h>

namespace msynth
{
namespace vdb
{
namespace detail
{
/// Appends values to a byte string (the child's side).
struct Packer
{
  std::string Bytes;
  void Raw(const void* p, std::size_t n) { this->Bytes.append(static_cast<const char*>(p), n); }
  void U64(std::uint64_t v) { this->Raw(&v, 8); }
  void F64(double v) { this->Raw(&v, 8); }
  void Str(const std::string& v)
  {
    this->U64(v.size());
    this->Raw(v.data(), v.size());
  }
  void Map(const MetadataMap& m)
  {
    this->U64(m.size());
    for (const auto& kv : m)
    {
      this->Str(kv.first);
      this->Str(kv.second);
    }
  }
};

/// Reads them back with every size checked (the parent's side).
struct Unpacker
{
  const std::string& Bytes;
  const std::string& Path;
  std::size_t Pos = 0;
  void Raw(void* p, std::size_t n)
  {
    if (n > this->Bytes.size() - this->Pos)
      throw Error::InFile(this->Path, "could not be read (the reading process sent too little)");
    std::memcpy(p, this->Bytes.data() + this->Pos, n);
    this->Pos += n;
  }
  std::uint64_t U64(std::uint64_t limit = std::numeric_limits<std::uint64_t>::max())
  {
    std::uint64_t v = 0;
    this->Raw(&v, 8);
    if (v > limit)
      throw Error::InFile(
        this->Path, "could not be read (a size out of range from the reading process)");
    return v;
  }
  double F64()
  {
    double v = 0;
    this->Raw(&v, 8);
    return v;
  }
  std::string Str()
  {
    std::string v(ToIndex(this->U64(this->Bytes.size() - this->Pos)), '\0');
    this->Raw(&v[0], v.size());
    return v;
  }
  MetadataMap Map()
  {
    MetadataMap m;
    for (std::uint64_t n = this->U64(this->Bytes.size()); n > 0; --n)
    {
      std::string key = this->Str();
      m[key] = this->Str();
    }
    return m;
  }
};

/// Reads exactly what the parent asks for from the child's pipe.
class PipeReader
{
public:
  PipeReader(int fd, const std::string& path)
    : Fd(fd)
    , Path(path)
  {
  }
  /// Up to @p n bytes; fewer only at the end of the pipe.
  std::size_t Some(void* data, std::size_t n)
  {
    char* p = static_cast<char*>(data);
    std::size_t done = 0;
    while (done < n)
    {
      const ssize_t k = ::read(this->Fd, p + done, n - done);
      if (k < 0 && errno == EINTR)
        continue;
      if (k <= 0)
        break;
      done += ToIndex(k);
    }
    return done;
  }
  void Exact(void* data, std::size_t n)
  {
    if (this->Some(data, n) != n)
      throw Error::InFile(this->Path, "is corrupt: the OpenVDB library failed reading it");
  }
  std::uint64_t U64()
  {
    std::uint64_t v = 0;
    this->Exact(&v, 8);
    return v;
  }
  /// A length-prefixed block of at most 64 MiB (the child's side: SendBlock).
  std::string Block()
  {
    const std::uint64_t n = this->U64();
    if (n > (std::uint64_t(64) << 20))
      throw Error::InFile(this->Path, "is corrupt: the OpenVDB library failed reading it");
    std::string bytes(ToIndex(n), '\0');
    this->Exact(&bytes[0], bytes.size());
    return bytes;
  }

private:
  int Fd;
  const std::string& Path;
};

/// OpenVDB's side, in VDBFile.cxx: its one-time set-up, and the reads the child makes.
void InitializeLibrary();
FileContents ReadFileHere(const std::string& path, const ReadOptions& options);
std::vector<GridSummary> ListGridsHere(const std::string& path, MetadataMap* fileMetadata);

void PackHeader(Packer& p, const GridHeader& h);
GridHeader UnpackHeader(Unpacker& u, std::int64_t maxVoxels);
/// Writes all of @p n bytes at @p data to @p fd (the child's side).
void WriteAll(int fd, const void* data, std::size_t n);
/// The child's answer: 'O', then @p bytes as a length-prefixed block (PipeReader::Block).
void SendBlock(int fd, const std::string& bytes);

/**
 * Runs @p child in a forked child that writes to the given pipe ('O' and its data, or 'E' and
 * a message), and @p parent on the parent's end, which reads that data. A crash of the child,
 * or data that do not follow the protocol, is an Error naming @p path. The child's address
 * space may grow by @p memoryBudget only, and it runs one TBB thread.
 */
void RunIsolated(const std::string& path, std::uint64_t memoryBudget,
  const std::function<void(int)>& child, const std::function<void(PipeReader&)>& parent);
/// One attempt of RunIsolated: false when the child deadlocked before sending anything (it is
/// killed; RunIsolated tries again, up to five times).
bool RunIsolatedOnce(const std::string& path, std::uint64_t memoryBudget,
  const std::function<void(int)>& child, const std::function<void(PipeReader&)>& parent);

} // namespace detail
} // namespace vdb
} // namespace msynth
