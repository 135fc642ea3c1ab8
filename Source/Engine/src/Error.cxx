// SPDX-License-Identifier: BSD-3-Clause
#include "msynth/Error.h"

namespace msynth
{

Error::Error(const std::string& what)
  : std::runtime_error(what)
{
}

Error Error::InFile(const std::string& path, const std::string& problem)
{
  return Error("'" + path + "': " + problem);
}

} // namespace msynth
