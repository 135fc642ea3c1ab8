// SPDX-License-Identifier: BSD-3-Clause
// Shared modules opened beside the library that uses them (ModuleBeside.h).
#include "Core/ModuleBeside.h"

#include "Core/Error.h"

#include <dlfcn.h>

namespace msynth
{

void* ModuleEntryBeside(const void* anchor, const std::string& fileName, const char* symbol)
{
  std::string folder;
  Dl_info info{};
  if (dladdr(anchor, &info) != 0 && info.dli_fname)
  {
    const std::string library = info.dli_fname;
    const std::size_t slash = library.rfind('/');
    if (slash != std::string::npos)
      folder = library.substr(0, slash + 1);
  }
  const std::string path = folder + fileName;
  void* handle = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
  if (!handle)
  {
    const char* why = dlerror();
    throw Error(
      "the module '" + path + "' does not load (" + (why ? why : "no reason given") + ")");
  }
  void* entry = dlsym(handle, symbol);
  if (!entry)
    throw Error("the module '" + path + "' has no " + symbol);
  return entry;
}

} // namespace msynth
