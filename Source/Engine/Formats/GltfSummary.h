// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/**
 * @file GltfSummary.h
 * @brief What a glTF 2.0 file (.glb or .gltf) holds, read and checked without trusting it: its
 * meshes, their primitives and counts, its materials and their colours (for `msynth info`).
 *
 * The binary container's header and chunks are checked before tinygltf parses the JSON (their
 * lengths against the file's size), the JSON's nesting is bounded, images are not decoded, and
 * every accessor a primitive uses is checked to lie inside its buffer view and that view inside
 * its buffer. Memory is bounded by the file's size (and that of the buffers it names beside it).
 */
#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace msynth
{

struct GltfPrimitiveSummary
{
  int Mode = 4;               ///< glTF's primitive mode (4: triangles)
  std::int64_t Vertices = 0;  ///< the POSITION accessor's count
  std::int64_t Triangles = 0; ///< triangles drawn (indices, or vertices, by the mode)
  int Material = -1;          ///< the material's index, -1 none
};

struct GltfMeshSummary
{
  std::string Name;
  std::vector<GltfPrimitiveSummary> Primitives;
};

struct GltfMaterialSummary
{
  std::string Name;
  std::array<double, 4> BaseColor{ { 1, 1, 1, 1 } }; ///< linear RGBA, as glTF stores it
  bool DoubleSided = false;
};

struct GltfSummary
{
  bool Binary = false; ///< a .glb container (else JSON)
  std::string Version; ///< asset.version
  std::string Generator;
  std::int64_t Nodes = 0;
  std::int64_t Scenes = 0;
  std::int64_t BufferBytes = 0; ///< the buffers' bytes in all
  std::vector<GltfMeshSummary> Meshes;
  std::vector<GltfMaterialSummary> Materials;
};

/**
 * @brief The summary of the glTF held in @p bytes (a .glb when @p binary, else JSON text);
 * @p name names it in messages. External files (buffers, images) are read from @p folder when
 * it is not empty, else refused.
 * @throw Error naming @p name and the problem (a damaged container, bad JSON, an accessor or
 * view outside its buffer, a count out of range).
 */
GltfSummary SummarizeGltf(const std::vector<std::uint8_t>& bytes, const std::string& name,
  bool binary, const std::string& folder);

/// SummarizeGltf of the file @p path (binary when it starts with glTF's magic, at most 2 GiB),
/// its external files beside it. @throw Error naming the file and the problem.
GltfSummary ReadGltfSummary(const std::string& path);

} // namespace msynth
