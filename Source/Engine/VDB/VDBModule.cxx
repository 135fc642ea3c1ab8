// SPDX-License-Identifier: BSD-3-Clause
// The light side of VDB I/O: the public functions of VDBFile.h, forwarded to the OpenVDB module
// that is loaded on first use (see VDBBackend.h).
#include "VDB/VDBBackend.h"

#include "Core/Error.h"
#include "VDB/IsolatedRead.h"

#include <dlfcn.h>

#include <string>

namespace msynth
{
namespace vdb
{

int ComponentCount(ValueType type)
{
  return type == ValueType::Vec3Float ? 3 : 1;
}

namespace detail
{
namespace
{
/// The folder of this library, where the module is installed and built beside it.
std::string ThisLibraryFolder()
{
  Dl_info info{};
  if (dladdr(reinterpret_cast<void*>(&ThisLibraryFolder), &info) == 0 || !info.dli_fname)
  {
    return std::string();
  }
  const std::string path = info.dli_fname;
  const std::size_t slash = path.rfind('/');
  return slash == std::string::npos ? std::string() : path.substr(0, slash + 1);
}

const Backend* Load()
{
  const std::string path = ThisLibraryFolder() + MSYNTH_OPENVDB_MODULE;
  // Kept loaded for the life of the process (OpenVDB registers types and TBB state globally).
  void* handle = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
  if (!handle)
  {
    const char* why = dlerror();
    throw Error("cannot read or write OpenVDB files: the module '" + path + "' does not load (" +
      (why ? why : "no reason given") + ")");
  }
  using Entry = const Backend* (*)();
  auto entry = reinterpret_cast<Entry>(dlsym(handle, MSYNTH_OPENVDB_BACKEND_SYMBOL));
  const Backend* backend = entry ? entry() : nullptr;
  if (!backend)
  {
    throw Error("cannot read or write OpenVDB files: the module '" + path + "' has no " +
      MSYNTH_OPENVDB_BACKEND_SYMBOL);
  }
  return backend;
}
} // namespace

const Backend& LoadedBackend()
{
  // A throwing initialization is retried by the next call (C++ static-local semantics).
  static const Backend* const backend = Load();
  return *backend;
}

void InitializeLibrary()
{
  LoadedBackend().Initialize();
}

FileContents ReadFileHere(const std::string& path, const ReadOptions& options)
{
  return LoadedBackend().Read(path, options);
}

std::vector<GridSummary> ListGridsHere(const std::string& path, MetadataMap* fileMetadata)
{
  return LoadedBackend().List(path, fileMetadata);
}
} // namespace detail

void WriteFile(
  const std::string& path, const std::vector<DenseGridView>& grids, const MetadataMap& metadata)
{
  WriteFile(path, grids, {}, metadata);
}

void WriteFile(const std::string& path, const std::vector<DenseGridView>& grids,
  const std::vector<MeshGridView>& meshes, const MetadataMap& metadata)
{
  detail::LoadedBackend().Write(path, grids, meshes, {}, metadata);
}

void WriteFile(const std::string& path, const std::vector<DenseGridView>& grids,
  const std::vector<MeshGridView>& meshes, const std::vector<LabelRenderView>& labels,
  const MetadataMap& metadata)
{
  detail::LoadedBackend().Write(path, grids, meshes, labels, metadata);
}

} // namespace vdb
} // namespace msynth
