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
  /// A unit normal per vertex (x, y, z, z up as Positions), or none: glTF readers then shade
  /// flat, each triangle by its winding (counter-clockwise seen from the front).
  std::vector<float> Normals;
  bool DoubleSided = false; ///< the material shows both sides (a flat model seen from below)
};

/**
 * @brief Appends @p polygons (corner indices into @p points, each planar and counter-clockwise
 * seen from the side it faces) to @p part as flat-shaded triangles with normals: every polygon's
 * unit normal (Newell's) on its own vertices, a vertex shared by the part's polygons that share
 * its point and normal. A convex polygon of n corners is n - 2 triangles fanned from its first
 * corner, or, when a corner is straight (a polygon keeping the corners of its neighbours, as
 * continuous models' do), n triangles fanned around its centre (one added vertex), so no
 * triangle is degenerate; any other polygon is cut into ears. Polygons of no area (or fewer than
 * three corners) are left out.
 * @throw Error when a corner index is outside @p points.
 */
void AppendFlatPolygons(GltfPart& part, const std::vector<std::array<double, 3>>& points,
  const std::vector<std::vector<std::int32_t>>& polygons);

/**
 * @brief Writes @p parts as a binary glTF 2.0 file at @p path, atomically (complete or absent).
 *
 * One node and one mesh per part, each with one triangle primitive (POSITION and 32-bit
 * indices, accessors with their bounds; NORMAL when the part has normals, else none: glTF
 * readers then shade flat, as voxels are) and its own material: baseColorFactor is Color turned
 * linear (glTF's colours are linear; Blender and game engines show it as the sRGB colour given),
 * metallic 0, roughness 1, doubleSided as the part. Positions and normals turn from the model's
 * z up to glTF's y up: (x, y, z) -> (x, z, -y) (a rotation, so windings keep their sense), so
 * Blender's importer gives back the model's axes. Parts without triangles are left out; none with
 * triangles: a file with the asset alone (no scene). @p generator goes into asset.generator.
 * @throw Error naming @p path when a part is inconsistent (an index out of range, positions not
 * in threes, normals not one per vertex), the file would pass glTF's 4 GiB limit, or the file
 * cannot be written.
 */
void WriteGlbFile(
  const std::string& path, const std::vector<GltfPart>& parts, const std::string& generator);
} // namespace msynth
