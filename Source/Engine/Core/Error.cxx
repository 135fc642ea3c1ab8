// SPDX-License-Identifier: BSD-3-Clause
#include "Core/Error.h"
#include "Core/Index.h"

namespace msynth
{

std::string Printable(const std::string& text)
{
  std::string out;
  out.reserve(text.size());
  for (std::size_t i = 0; i < text.size();)
  {
    const auto c = static_cast<unsigned char>(text[i]);
    // Bytes a UTF-8 sequence starting with c needs after it (0: ASCII; -1: never a start).
    const int more = c < 0x80  ? 0
      : c >= 0xc2 && c <= 0xdf ? 1
      : c >= 0xe0 && c <= 0xef ? 2
      : c >= 0xf0 && c <= 0xf4 ? 3
                               : -1;
    bool valid = more >= 0 && i + ToIndex(more) < text.size() + (more == 0);
    for (int k = 1; valid && k <= more; ++k)
      valid = (static_cast<unsigned char>(text[i + ToIndex(k)]) & 0xc0) == 0x80;
    if (!valid || c < 0x20 || c == 0x7f)
    {
      out += '?'; // a control character, or a byte that is no UTF-8 (from a damaged file)
      ++i;
      continue;
    }
    out.append(text, i, ToIndex(more) + 1);
    i += ToIndex(more) + 1;
  }
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
