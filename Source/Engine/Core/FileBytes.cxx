// SPDX-License-Identifier: BSD-3-Clause
#include "Core/FileBytes.h"

#include "Core/Error.h"
#include "Core/Index.h"

#include <fstream>

namespace msynth
{

std::string ReadFileBytes(
  const std::string& path, std::uint64_t maxBytes, const std::string& tooLarge)
{
  std::ifstream in(path, std::ios::binary);
  if (!in)
    throw Error::InFile(path, "cannot be opened for reading (missing or unreadable)");
  in.seekg(0, std::ios::end);
  const std::streamoff size = in.tellg();
  if (size < 0 || static_cast<std::uint64_t>(size) > maxBytes)
    throw Error::InFile(path, tooLarge);
  in.seekg(0);
  std::string bytes(ToIndex(size), '\0');
  in.read(&bytes[0], size);
  if (!in)
    throw Error::InFile(path, "could not be read");
  return bytes;
}

} // namespace msynth
