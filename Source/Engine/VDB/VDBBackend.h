// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/**
 * @file VDBBackend.h
 * @brief The OpenVDB module's entry points, loaded on first use.
 *
 * OpenVDB is linked with immediate binding and brings log4cplus, Imath, Blosc and Boost: loading
 * it binds about 60 000 symbols, two thirds of a process start-up. So the OpenVDB code
 * (VDBFile.cxx) is a separate module, `libModelSynthOpenVDB.so`, that the light library
 * `libModelSynthVDB` (VDBModule.cxx, IsolatedRead.cxx, VDBLayout.cxx) opens with dlopen the
 * first time a VDB file is written, read or listed. Runs that write no `.vdb` never load it.
 *
 * The module exports one C function, `msynth_openvdb_backend`, returning this table.
 */
#include "VDB/RenderGrids.h"

namespace msynth
{
namespace vdb
{
namespace detail
{

struct Backend
{
  void (*Initialize)();
  void (*Write)(const std::string& path, const std::vector<DenseGridView>& grids,
    const std::vector<MeshGridView>& meshes, const std::vector<LabelRenderView>& labels,
    const MetadataMap& metadata);
  FileContents (*Read)(const std::string& path, const ReadOptions& options);
  std::vector<GridSummary> (*List)(const std::string& path, MetadataMap* fileMetadata);
  /// In a forked reader: OpenVDB's TBB runs one thread (the parent's workers do not exist).
  void (*LimitToOneThread)();
};

/// The module's table, loading the module (next to libModelSynthVDB) on the first call.
/// @throw Error naming the module and the loader's message when it cannot be loaded.
const Backend& LoadedBackend();

} // namespace detail
} // namespace vdb
} // namespace msynth

/// The symbol the module exports (C linkage, so dlsym finds it by this name).
#define MSYNTH_OPENVDB_BACKEND_SYMBOL "msynth_openvdb_backend"
