// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/**
 * @file GltfFile.h
 * @brief Binary glTF 2.0 (.glb) output for game engines and Blender: triangle meshes grouped by
 * material. The only code that uses tinygltf (Debian's libtinygltf, linked privately).
 */
#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace msynth
{
/// Triangles that share one material (a label, or a label and its palette colour).
struct GltfPart
{
  std::string Name;                     ///< the material's and the mesh's name, e.g. "label 3"
  std::array<double, 4> Color{};        ///< display colour (sRGB) and alpha, each in [0, 1]
  std::vector<float> Positions;         ///< x, y, z of each vertex, z up (the model's frame)
  std::vector<std::uint32_t> Triangles; ///< three vertex indices per triangle
};

/**
 * @brief Writes @p parts as a binary glTF 2.0 file at @p path, atomically (complete or absent).
 *
 * One node and one mesh per part, each with one triangle primitive (POSITION and 32-bit
 * indices, accessors with their bounds; no normals: glTF readers then shade flat, as voxels
 * are) and its own material: baseColorFactor is Color turned linear (glTF's colours are linear;
 * Blender and game engines show it as the sRGB colour given), metallic 0, roughness 1. Positions
 * turn from the model's z up to glTF's y up: (x, y, z) -> (x, z, -y), so Blender's importer
 * gives back the model's axes. Parts without triangles are left out; none with triangles: a
 * file with the asset alone (no scene). @p generator goes into asset.generator.
 * @throw Error naming @p path when a part is inconsistent (an index out of range, positions not
 * in threes), the file would pass glTF's 4 GiB limit, or the file cannot be written.
 */
void WriteGlbFile(
  const std::string& path, const std::vector<GltfPart>& parts, const std::string& generator);
} // namespace msynth
