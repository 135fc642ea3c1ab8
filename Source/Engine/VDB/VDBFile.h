// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/**
 * @file VDBFile.h
 * @brief OpenVDB files behind a plain C++ interface (no OpenVDB or VTK types), so that only
 * src/VDBFile.cxx compiles OpenVDB's heavy headers.
 *
 * A dense grid is a box of voxels in index space [IndexMin, IndexMin + Dims) with x fastest
 * (the vtkImageData order). Index (i, j, k) sits at world position Origin + (i, j, k) * Spacing:
 * the VDB transform is a scale by Spacing and a translation by Origin, so VTK structured
 * indices (extents) are kept as VDB coordinates and round trips restore them exactly.
 *
 * Voxels equal to the background stay inactive, so label volumes whose empty label is the
 * background are stored sparsely. The dense extent is saved as grid metadata
 * (`msynth_index_min`, `msynth_index_max`) and restored on reading.
 */
#include <array>
#include <cstdint>
#include <map>
#include <string>
#include <vector>

namespace msynth
{
namespace vdb
{

/// Value types ModelSynth writes and reads.
enum class ValueType
{
  Int32,    ///< openvdb::Int32Grid (labels)
  Float,    ///< openvdb::FloatGrid (scalar fields)
  Vec3Float ///< openvdb::Vec3SGrid (3-component fields)
};

/// Components per voxel: 1, or 3 for Vec3Float.
int ComponentCount(ValueType type);

using MetadataMap = std::map<std::string, std::string>;

/// Geometry and description of a dense grid (shared by the view written and the grid read).
struct GridHeader
{
  std::string Name;
  ValueType Type = ValueType::Float;
  std::array<std::int32_t, 3> IndexMin{ { 0, 0, 0 } };
  std::array<std::int64_t, 3> Dims{ { 0, 0, 0 } };
  std::array<double, 3> Origin{ { 0.0, 0.0, 0.0 } };
  std::array<double, 3> Spacing{ { 1.0, 1.0, 1.0 } };
  double Background = 0.0; ///< value of inactive voxels (all components, for vectors)
  std::string GridClass;   ///< "" (unknown), "fog volume" or "level set"
  MetadataMap Metadata;    ///< extra string metadata stored on the grid

  std::int64_t NumberOfVoxels() const { return this->Dims[0] * this->Dims[1] * this->Dims[2]; }
};

/// A grid to write: header plus a pointer to NumberOfVoxels() × components values of Type
/// (std::int32_t or float), x fastest. The caller keeps the values alive during the write.
struct DenseGridView
{
  GridHeader Header;
  const void* Values = nullptr;
};

/**
 * A closed, outward-oriented polygon surface to write as a narrow-band level set
 * (`GRID_CLASS` "level set": signed distance, negative inside), and optionally as a fog volume
 * (`GRID_CLASS` "fog volume": density 1 inside, falling to 0 across the band) for volume
 * renderers. Polygons are convex (triangles and quads pass as they are, larger polygons are
 * fanned). The caller keeps Points and Polygons alive during the write.
 */
struct MeshGridView
{
  std::string Name; ///< e.g. "surface" or "surface_roof"
  const std::vector<std::array<double, 3>>* Points = nullptr;
  const std::vector<std::vector<std::int32_t>>* Polygons = nullptr;
  double VoxelSize = 1.0; ///< world units, > 0
  double HalfWidth = 3.0; ///< narrow band half width, in voxels (≥ 1)
  std::string FogName;    ///< also a fog volume of this name when set
  MetadataMap Metadata;   ///< extra string metadata on the grid(s)
  /// When not empty: the level set is the CSG union of these level sets made before it in the
  /// same file (Points and Polygons are not used), which costs far less than voxelizing again.
  std::vector<std::string> UnionOf;
};

/// A grid read from a file.
struct DenseGrid
{
  GridHeader Header;
  std::vector<std::int32_t> Ints; ///< Int32 values
  std::vector<float> Floats;      ///< Float or Vec3Float values (3 per voxel)
};

struct FileContents
{
  MetadataMap Metadata; ///< file-level string metadata
  std::vector<DenseGrid> Grids;
};

/// Summary of one grid as stored in a file, read without loading voxels.
struct GridSummary
{
  std::string Name;
  std::string TypeName; ///< OpenVDB's type name, e.g. "int32", "float", "vec3s"
  std::string GridClass;
  MetadataMap Metadata;
  std::int64_t ActiveVoxelCount = 0; ///< voxels whose value is not the background
  /// The active voxels' index bounding box (ActiveMin > ActiveMax when there are none).
  std::array<std::int32_t, 3> ActiveMin{ { 0, 0, 0 } };
  std::array<std::int32_t, 3> ActiveMax{ { -1, -1, -1 } };
  std::array<double, 3> VoxelSize{ { 1.0, 1.0, 1.0 } }; ///< world units along each axis
};

/**
 * @brief Writes @p grids and file-level @p metadata to @p path, atomically: the data goes to a
 * temporary file in the same folder that is renamed over @p path only when complete, so a
 * failed write never leaves a partial or clobbered file.
 * @throw Error naming the file and the problem (bad grid, unwritable folder, I/O error).
 * @note The file metadata always gets `generator` = "ModelSynth <version>".
 */
void WriteFile(
  const std::string& path, const std::vector<DenseGridView>& grids, const MetadataMap& metadata);
/// The same with level sets (and fog volumes) of meshes as well. @throw Error also on a mesh
/// with a bad point index, a non-positive voxel size or a band narrower than one voxel.
void WriteFile(const std::string& path, const std::vector<DenseGridView>& grids,
  const std::vector<MeshGridView>& meshes, const MetadataMap& metadata);

/// Options for ReadFile.
struct ReadOptions
{
  /// The largest dense grid (in voxels) a read may allocate; a grid whose extent is larger
  /// is refused with an error instead of exhausting memory.
  std::int64_t MaxVoxels = std::int64_t(1) << 28;
  /// Names of the grids to read; empty reads all.
  std::vector<std::string> GridNames;
};

/**
 * @brief Reads every Int32, Float and Vec3S grid of @p path into dense grids over their
 * stored extent (msynth_index_min/max metadata) or, for files from other tools, their active
 * bounding box.
 * @throw Error naming the file and the problem: not a VDB file, truncated or corrupt data, a
 * grid type we do not read, a rotated transform, or an extent larger than MaxVoxels.
 */
FileContents ReadFile(const std::string& path, const ReadOptions& options = ReadOptions());

/// Lists grids, their metadata and active voxel counts. @throw Error as ReadFile.
std::vector<GridSummary> ListGrids(const std::string& path, MetadataMap* fileMetadata = nullptr);

} // namespace vdb
} // namespace msynth
