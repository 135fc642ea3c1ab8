// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/**
 * @file InfoFiles.h
 * @brief `msynth info` on the files msynth writes, one file per format: InfoVolume.cxx (.vdb),
 * InfoGltf.cxx (.glb, .gltf), InfoVox.cxx (.vox), InfoPieces.cxx (.pvti). Each prints what the
 * file holds, or throws one line naming the file and its problem; none allocates more than the
 * file's size from what the file says (the .vdb is read by OpenVDB in a child process).
 */
#include <string>

namespace msynth
{
namespace cli
{

/// The lower-case extension of @p path (".vdb"), "" without one.
std::string LowerExtension(const std::string& path);
/// Whether info describes @p path as a file msynth writes (by its extension; .vox is both).
bool IsWrittenFile(const std::string& path);
/// A .vdb: each grid's name, value type, class, active voxels, index bounds and voxel size.
int VolumeInfo(const std::string& path);
/// A .glb or .gltf: its meshes, primitives, vertex and triangle counts, materials and colours.
int GltfInfo(const std::string& path);
/// A .vox: its models, their sizes, voxels and placements, the palette entries used. Returns
/// the number of models (the caller then analyses its labels as an example's).
int VoxInfo(const std::string& path);
/// A .pvti: the whole extent, the pieces and their extents (each piece file checked to exist),
/// the arrays.
int PiecesInfo(const std::string& path);

} // namespace cli
} // namespace msynth
