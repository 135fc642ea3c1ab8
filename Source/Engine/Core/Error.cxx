// SPDX-License-Identifier: BSD-3-Clause
#include "Core/Error.h"

namespace msynth
{

std::string Printable(const std::string& text)
{
  std::string out = text;
  for (char& c : out)
    if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f)
      c = '?';
  return out;
}

Error::Error(const std::string& what)
  : std::runtime_error(Printable(what))
{
}

Error Error::InFile(const std::string& path, const std::string& problem)
{
  return Error("'" + path + "': " + problem);
}

} // namespace msynth
