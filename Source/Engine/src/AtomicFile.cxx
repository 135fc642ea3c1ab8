// SPDX-License-Identifier: BSD-3-Clause
#include "msynth/AtomicFile.h"

#include "msynth/Error.h"

#include <atomic>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <unistd.h>

namespace msynth
{

std::string TemporaryPathBeside(const std::string& path)
{
  static std::atomic<unsigned> counter{ 0 };
  return path + ".tmp-" + std::to_string(::getpid()) + "-" + std::to_string(counter++);
}

void CommitTemporaryFile(const std::string& temporary, const std::string& path)
{
  if (std::rename(temporary.c_str(), path.c_str()) != 0)
  {
    const std::string reason = std::strerror(errno);
    std::remove(temporary.c_str());
    throw Error::InFile(path, "could not be written: " + reason);
  }
}

void WriteFileAtomically(const std::string& path, const std::function<void(std::ostream&)>& write)
{
  const std::string tmp = TemporaryPathBeside(path);
  std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
  if (!out)
  {
    throw Error::InFile(path, std::string("could not be written: ") + std::strerror(errno));
  }
  // Every write is checked (a full disk shows in the stream's state and errno), and so is the
  // close, which writes what is still buffered.
  errno = 0;
  try
  {
    write(out);
    out.flush();
  }
  catch (...)
  {
    out.close();
    std::remove(tmp.c_str());
    throw;
  }
  int error = out ? 0 : (errno ? errno : EIO);
  out.close();
  if (!error && out.fail())
  {
    error = errno ? errno : EIO;
  }
  if (error)
  {
    std::remove(tmp.c_str());
    throw Error::InFile(path, std::string("could not be written: ") + std::strerror(error));
  }
  CommitTemporaryFile(tmp, path);
}

} // namespace msynth
