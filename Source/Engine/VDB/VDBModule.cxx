// SPDX-License-Identifier: BSD-3-Clause
// The light side of VDB I/O: the public functions of VDBFile.h, forwarded to the OpenVDB module
// that is loaded on first use (see VDBBackend.h).
#include "VDB/VDBBackend.h"

#include "Core/Error.h"
#include "Core/ModuleBeside.h"
#include "VDB/IsolatedRead.h"

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
const Backend* Load()
{
  using Entry = const Backend* (*)();
  try
  {
    // Kept loaded for the life of the process (OpenVDB registers types and TBB state globally).
    const auto entry = reinterpret_cast<Entry>(ModuleEntryBeside(
      reinterpret_cast<const void*>(&Load), MSYNTH_OPENVDB_MODULE, MSYNTH_OPENVDB_BACKEND_SYMBOL));
    if (const Backend* backend = entry())
      return backend;
    throw Error(std::string("the module '") + MSYNTH_OPENVDB_MODULE + "' gave no backend");
  }
  catch (const Error& e)
  {
    throw Error(std::string("cannot read or write OpenVDB files: ") + e.what());
  }
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
