// SPDX-License-Identifier: BSD-3-Clause
#include "Core/AtomicFile.h"

#include "Core/Error.h"
#include "Core/Index.h"

#include <atomic>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fcntl.h>
#include <fstream>
#include <streambuf>
#include <sys/stat.h>
#include <unistd.h>
#include <vector>

namespace msynth
{

void CheckReplaceable(const std::string& path)
{
  struct stat info;
  if (::stat(path.c_str(), &info) == 0 && !S_ISREG(info.st_mode))
    throw Error::InFile(path,
      S_ISDIR(info.st_mode) ? "is a folder, not a file to write"
                            : "exists and is not a regular file (a device, a pipe or a socket); "
                              "it is not written over");
}

std::string TemporaryPathBeside(const std::string& path)
{
  CheckReplaceable(path);
  static std::atomic<unsigned> counter{ 0 };
  return path + ".tmp-" + std::to_string(::getpid()) + "-" + std::to_string(counter++);
}

void CommitTemporaryFile(const std::string& temporary, const std::string& path)
{
  try
  {
    CheckReplaceable(path); // again: it may have appeared while the file was written
  }
  catch (const Error&)
  {
    std::remove(temporary.c_str());
    throw;
  }
  if (std::rename(temporary.c_str(), path.c_str()) != 0)
  {
    const std::string reason = std::strerror(errno);
    std::remove(temporary.c_str());
    throw Error::InFile(path, "could not be written: " + reason);
  }
}

namespace
{
/**
 * A file buffer that remembers the first failed write or seek for good (errno), whatever the
 * writer does with its stream's state afterwards: OpenVDB, for one, seeks and clears while it
 * writes, which can hide a short write from the stream's flags.
 */
class CheckedFileBuffer : public std::streambuf
{
public:
  explicit CheckedFileBuffer(int fd)
    : Fd(fd)
    , Buffer(1 << 16)
  {
    this->setp(this->Buffer.data(), this->Buffer.data() + this->Buffer.size());
  }
  int Error() const { return this->Failed; }
  /// Writes what is buffered; false (and Error() set) on failure.
  bool Drain()
  {
    const char* p = this->pbase();
    while (p < this->pptr() && !this->Failed)
    {
      const ssize_t n = ::write(this->Fd, p, ToIndex(this->pptr() - p));
      if (n < 0 && errno == EINTR)
        continue;
      if (n <= 0)
        this->Failed = n < 0 ? errno : EIO;
      else
        p += n;
    }
    this->setp(this->Buffer.data(), this->Buffer.data() + this->Buffer.size());
    return !this->Failed;
  }

protected:
  int_type overflow(int_type c) override
  {
    if (!this->Drain())
      return traits_type::eof();
    if (!traits_type::eq_int_type(c, traits_type::eof()))
    {
      *this->pptr() = traits_type::to_char_type(c);
      this->pbump(1);
    }
    return traits_type::not_eof(c);
  }
  std::streamsize xsputn(const char* data, std::streamsize n) override
  {
    const std::streamsize room = this->epptr() - this->pptr();
    if (n <= room)
    {
      std::memcpy(this->pptr(), data, ToIndex(n));
      this->pbump(static_cast<int>(n));
      return n;
    }
    if (!this->Drain())
      return 0;
    if (n < static_cast<std::streamsize>(this->Buffer.size()))
      return this->xsputn(data, n);
    // Large pieces go straight to the file.
    std::size_t done = 0;
    while (done < ToIndex(n) && !this->Failed)
    {
      const ssize_t k = ::write(this->Fd, data + done, ToIndex(n) - done);
      if (k < 0 && errno == EINTR)
        continue;
      if (k <= 0)
        this->Failed = k < 0 ? errno : EIO;
      else
        done += ToIndex(k);
    }
    return this->Failed ? 0 : n;
  }
  int sync() override { return this->Drain() ? 0 : -1; }
  pos_type seekoff(off_type off, std::ios_base::seekdir dir, std::ios_base::openmode) override
  {
    if (!this->Drain())
      return pos_type(off_type(-1));
    const int whence = dir == std::ios_base::beg ? SEEK_SET
      : dir == std::ios_base::cur                ? SEEK_CUR
                                                 : SEEK_END;
    const off_t at = ::lseek(this->Fd, static_cast<off_t>(off), whence);
    if (at < 0)
    {
      this->Failed = errno;
      return pos_type(off_type(-1));
    }
    return pos_type(static_cast<off_type>(at));
  }
  pos_type seekpos(pos_type pos, std::ios_base::openmode mode) override
  {
    return this->seekoff(off_type(pos), std::ios_base::beg, mode);
  }

private:
  int Fd;
  std::vector<char> Buffer;
  int Failed = 0;
};
} // namespace

void WriteFileAtomically(const std::string& path, const std::function<void(std::ostream&)>& write)
{
  const std::string tmp = TemporaryPathBeside(path);
  const int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd < 0)
  {
    throw Error::InFile(path, std::string("could not be written: ") + std::strerror(errno));
  }
  // Every write is checked (a full disk is ENOSPC from write(2)), and so is the close.
  CheckedFileBuffer buffer(fd);
  std::ostream out(&buffer);
  try
  {
    write(out);
  }
  catch (...)
  {
    ::close(fd);
    std::remove(tmp.c_str());
    throw;
  }
  buffer.Drain();
  int error = buffer.Error();
  if (!error && !out)
  {
    error = EIO;
  }
  if (::close(fd) != 0 && !error)
  {
    error = errno;
  }
  if (error)
  {
    std::remove(tmp.c_str());
    throw Error::InFile(path, std::string("could not be written: ") + std::strerror(error));
  }
  CommitTemporaryFile(tmp, path);
}

} // namespace msynth
