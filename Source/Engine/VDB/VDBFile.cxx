// SPDX-License-Identifier: BSD-3-Clause
// The only translation unit of ModelSynth that includes OpenVDB's headers (they compile
// slowly). Everything OpenVDB-specific stays in this file, the OpenVDB module that
// libModelSynthVDB loads on first use (VDBBackend.h); its functions reach the rest of the
// program only through the table msynth_openvdb_backend returns.
#include "VDB/VDBBackend.h"

#include "Core/AtomicFile.h"
#include "Core/Error.h"
#include "Core/Index.h"
#include "Core/Memory.h"
#include "VDB/IsolatedRead.h"
#include "VDB/RenderGridsOpenVDB.h"

#include <cerrno>
#include <csignal>
#include <cstring>
#include <functional>
#include <openvdb/io/File.h>
#include <openvdb/io/Stream.h>
#include <openvdb/openvdb.h>
#include <openvdb/tools/Composite.h>
#include <openvdb/tools/Dense.h>
#include <openvdb/tools/LevelSetUtil.h>
#include <openvdb/tools/MeshToVolume.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <tbb/global_control.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <limits>
#include <type_traits>

namespace msynth
{
namespace vdb
{

namespace
{
// ---------------------------------------------------------------------------------------------
// internal
// ---------------------------------------------------------------------------------------------
using detail::IndexMaxKey;
using detail::IndexMinKey;

void InitializeOpenVDB()
{
  // openvdb::initialize() is idempotent and guarded by OpenVDB's own mutex.
  openvdb::initialize();
}

openvdb::math::Transform::Ptr MakeTransform(const GridHeader& h)
{
  for (double s : h.Spacing)
  {
    if (!(s > 0.0) || !std::isfinite(s))
    {
      throw Error("grid '" + h.Name + "' has a spacing that is not positive and finite");
    }
  }
  for (double o : h.Origin)
  {
    if (!std::isfinite(o))
    {
      throw Error("grid '" + h.Name + "' has an origin that is not finite");
    }
  }
  const openvdb::Vec3d scale(h.Spacing[0], h.Spacing[1], h.Spacing[2]);
  const openvdb::Vec3d translate(h.Origin[0], h.Origin[1], h.Origin[2]);
  openvdb::math::MapBase::Ptr map(new openvdb::math::ScaleTranslateMap(scale, translate));
  return openvdb::math::Transform::Ptr(new openvdb::math::Transform(map));
}

template <typename GridT, typename ValueT>
typename GridT::Ptr DenseToGrid(const DenseGridView& view, const ValueT& background)
{
  const GridHeader& h = view.Header;
  const openvdb::Coord lo(h.IndexMin[0], h.IndexMin[1], h.IndexMin[2]);
  const openvdb::Coord hi(static_cast<openvdb::Int32>(h.IndexMin[0] + h.Dims[0] - 1),
    static_cast<openvdb::Int32>(h.IndexMin[1] + h.Dims[1] - 1),
    static_cast<openvdb::Int32>(h.IndexMin[2] + h.Dims[2] - 1));
  typename GridT::Ptr grid = GridT::create(background);
  const ValueT* values = static_cast<const ValueT*>(view.Values);
  bool extreme = false; // copyFromDense compares as a - b, which must not overflow
  if constexpr (std::is_integral<ValueT>::value)
  {
    const auto far = [](ValueT v) { return v < -(ValueT(1) << 29) || v > (ValueT(1) << 29); };
    extreme = far(background);
    for (std::int64_t i = 0, n = h.NumberOfVoxels(); i < n && !extreme; ++i)
      extreme = far(values[i]);
  }
  if (extreme)
  {
    // Exactly the voxels unequal to the background become active, one by one (labels such as
    // the catalog's undecided INT_MIN would overflow copyFromDense's comparison).
    auto accessor = grid->getAccessor();
    std::size_t i = 0;
    for (openvdb::Int32 z = lo.z(); z <= hi.z(); ++z)
      for (openvdb::Int32 y = lo.y(); y <= hi.y(); ++y)
        for (openvdb::Int32 x = lo.x(); x <= hi.x(); ++x, ++i)
          if (values[i] != background)
            accessor.setValueOn(openvdb::Coord(x, y, z), values[i]);
  }
  else
  {
    // copyFromDense only reads the dense buffer; the Dense class just lacks a const flavour.
    openvdb::tools::Dense<ValueT, openvdb::tools::LayoutXYZ> dense(
      openvdb::CoordBBox(lo, hi), const_cast<ValueT*>(values));
    // Tolerance zero: exactly the voxels equal to the background become inactive.
    openvdb::tools::copyFromDense(dense, *grid, openvdb::zeroVal<ValueT>());
  }
  grid->insertMeta(IndexMinKey, openvdb::Vec3IMetadata(openvdb::Vec3i(lo.x(), lo.y(), lo.z())));
  grid->insertMeta(IndexMaxKey, openvdb::Vec3IMetadata(openvdb::Vec3i(hi.x(), hi.y(), hi.z())));
  return grid;
}

openvdb::GridBase::Ptr MakeGrid(const DenseGridView& view)
{
  const GridHeader& h = view.Header;
  if (h.Name.empty())
  {
    throw Error("a grid has no name");
  }
  if (view.Values == nullptr)
  {
    throw Error("grid '" + h.Name + "' has no values");
  }
  for (int a = 0; a < 3; ++a)
  {
    const std::int64_t last = std::int64_t(h.IndexMin[a]) + h.Dims[a] - 1;
    if (h.Dims[a] < 1 || last > std::numeric_limits<std::int32_t>::max())
    {
      throw Error("grid '" + h.Name + "' has an extent OpenVDB cannot index");
    }
  }
  openvdb::GridBase::Ptr grid;
  switch (h.Type)
  {
    case ValueType::Int32:
      grid = DenseToGrid<openvdb::Int32Grid, std::int32_t>(
        view, static_cast<std::int32_t>(h.Background));
      break;
    case ValueType::Float:
      grid = DenseToGrid<openvdb::FloatGrid, float>(view, static_cast<float>(h.Background));
      break;
    case ValueType::Vec3Float:
    {
      const auto b = static_cast<float>(h.Background);
      grid = DenseToGrid<openvdb::Vec3SGrid, openvdb::Vec3s>(view, openvdb::Vec3s(b, b, b));
      break;
    }
  }
  grid->setName(h.Name);
  grid->setTransform(MakeTransform(h));
  if (h.GridClass == "level set")
  {
    grid->setGridClass(openvdb::GRID_LEVEL_SET);
  }
  else if (h.GridClass == "fog volume")
  {
    grid->setGridClass(openvdb::GRID_FOG_VOLUME);
  }
  else if (!h.GridClass.empty())
  {
    throw Error("grid '" + h.Name + "' has unknown grid class '" + h.GridClass + "'");
  }
  for (const auto& kv : h.Metadata)
  {
    grid->insertMeta(kv.first, openvdb::StringMetadata(kv.second));
  }
  return grid;
}

MetadataMap StringMetadataOf(const openvdb::MetaMap& meta)
{
  MetadataMap result;
  for (auto it = meta.beginMeta(); it != meta.endMeta(); ++it)
  {
    // Only user-level strings; OpenVDB's own entries (class, stats...) are reachable elsewhere.
    if (it->second && it->second->typeName() == openvdb::StringMetadata::staticTypeName())
    {
      result[it->first] = it->second->str();
    }
  }
  return result;
}

/// Index-space extent to read: our stored extent, else the active voxel bounding box.
/// The largest index coordinate accepted in a box: far from the 32-bit ends, so OpenVDB's
/// own box arithmetic (max + 1, dimensions) cannot overflow.
constexpr std::int64_t MaximumIndex = std::int64_t(1) << 30;

/**
 * Damaged metadata must not cost what an honest box costs: our writer's box holds the active
 * voxels, and a box of more than 2^24 voxels holds them with fewer than 64 empty voxels for each
 * voxel of their bounding box (a file of one voxel whose box claimed 2^28 took 60 s and 2 GB).
 */
void CheckStoredBox(const openvdb::GridBase& grid, const openvdb::CoordBBox& stored)
{
  const openvdb::CoordBBox active = grid.evalActiveVoxelBoundingBox();
  const auto box = [](const openvdb::CoordBBox& b)
  {
    return "(" + std::to_string(b.min().x()) + ", " + std::to_string(b.min().y()) + ", " +
      std::to_string(b.min().z()) + ") - (" + std::to_string(b.max().x()) + ", " +
      std::to_string(b.max().y()) + ", " + std::to_string(b.max().z()) + ")";
  };
  if (!active.empty() && !stored.isInside(active))
    throw Error("grid '" + grid.getName() + "' has active voxels in " + box(active) +
      ", outside the index box it stores, " + box(stored) + " (damaged metadata)");
  constexpr std::uint64_t large = std::uint64_t(1) << 24;
  const std::uint64_t data = active.empty() ? 1 : active.volume();
  if (stored.volume() > large && stored.volume() / 64 > data)
    throw Error("grid '" + grid.getName() + "' stores the index box " + box(stored) + " of " +
      std::to_string(stored.volume()) + " voxels around " + std::to_string(data) +
      " voxels of data (damaged metadata)");
}

/// The extent a grid stands for: our writer's stored index box (metadata, which a file may
/// get wrong: checked), else the active voxels' bounding box.
openvdb::CoordBBox ExtentOf(const openvdb::GridBase& grid)
{
  auto lo = grid.getMetadata<openvdb::Vec3IMetadata>(IndexMinKey);
  auto hi = grid.getMetadata<openvdb::Vec3IMetadata>(IndexMaxKey);
  if (lo && hi)
  {
    const openvdb::Vec3i a = lo->value(), b = hi->value();
    for (int k = 0; k < 3; ++k)
    {
      // 64-bit arithmetic: the values are the file's, not ours.
      const std::int64_t from = a[k], to = b[k];
      if (from > to || from < -MaximumIndex || to > MaximumIndex)
        throw Error("grid '" + grid.getName() + "' stores the index box (" + std::to_string(a.x()) +
          ", " + std::to_string(a.y()) + ", " + std::to_string(a.z()) + ") - (" +
          std::to_string(b.x()) + ", " + std::to_string(b.y()) + ", " + std::to_string(b.z()) +
          "), which is empty or outside +-2^30");
    }
    const openvdb::CoordBBox stored(
      openvdb::Coord(a.x(), a.y(), a.z()), openvdb::Coord(b.x(), b.y(), b.z()));
    CheckStoredBox(grid, stored);
    return stored;
  }
  const openvdb::CoordBBox box = grid.evalActiveVoxelBoundingBox();
  if (!box.empty())
    for (int k = 0; k < 3; ++k)
      if (box.min()[k] < -MaximumIndex || box.max()[k] > MaximumIndex)
        throw Error("grid '" + grid.getName() + "' has active voxels outside +-2^30");
  return box;
}

/**
 * The grid's values over @p box, x fastest, as openvdb::tools::copyToDense gives them, at the
 * cost of filling the box plus visiting the tree: the background everywhere, then every tile
 * above the leaves whose value differs from it, then the leaves. (copyToDense probes the tree
 * block by block: 7 s for a 2^28-voxel box around one voxel, on the reading child's one thread.)
 */
template <typename GridT, typename ValueT>
void GridToDense(const GridT& grid, const openvdb::CoordBBox& box, ValueT* out)
{
  openvdb::tools::Dense<ValueT, openvdb::tools::LayoutXYZ> dense(box, out);
  const auto background = grid.background();
  std::fill(out, out + box.volume(), static_cast<ValueT>(background));
  auto tile = grid.tree().cbeginValueAll();
  tile.setMaxDepth(static_cast<openvdb::Index>(grid.tree().treeDepth() - 2)); // not the voxels
  for (; tile; ++tile)
  {
    openvdb::CoordBBox part;
    tile.getBoundingBox(part);
    part.intersect(box);
    if (part.empty() || *tile == background)
      continue;
    const auto value = static_cast<ValueT>(*tile);
    for (openvdb::Int32 z = part.min().z(); z <= part.max().z(); ++z)
      for (openvdb::Int32 y = part.min().y(); y <= part.max().y(); ++y)
      {
        ValueT* row = out + dense.coordToOffset(openvdb::Coord(part.min().x(), y, z));
        std::fill(row, row + part.dim().x(), value);
      }
  }
  for (auto leaf = grid.tree().cbeginLeaf(); leaf; ++leaf)
  {
    openvdb::CoordBBox part = leaf->getNodeBoundingBox();
    part.intersect(box);
    if (!part.empty())
      leaf->copyToDense(part, dense);
  }
}

DenseGrid ReadGrid(const openvdb::GridBase::Ptr& base, const ReadOptions& options)
{
  DenseGrid out;
  GridHeader& h = out.Header;
  h.Name = base->getName();
  if (base->isType<openvdb::Int32Grid>())
  {
    h.Type = ValueType::Int32;
  }
  else if (base->isType<openvdb::FloatGrid>())
  {
    h.Type = ValueType::Float;
  }
  else if (base->isType<openvdb::Vec3SGrid>())
  {
    h.Type = ValueType::Vec3Float;
  }
  else
  {
    throw Error("grid '" + h.Name + "' has value type '" + base->valueType() +
      "', which ModelSynth does not read (int32, float and vec3s grids are supported)");
  }

  const openvdb::math::Transform& xform = base->transform();
  if (!xform.isLinear())
  {
    throw Error("grid '" + h.Name + "' has a non-linear (frustum) transform");
  }
  const openvdb::Mat4d m = xform.baseMap()->getAffineMap()->getMat4();
  for (int r = 0; r < 3; ++r)
  {
    for (int c = 0; c < 3; ++c)
    {
      if (r != c && m(r, c) != 0.0)
      {
        throw Error("grid '" + h.Name +
          "' has a rotated or sheared transform; only "
          "axis-aligned voxel grids map to image data");
      }
    }
  }
  const openvdb::Vec3d origin = xform.indexToWorld(openvdb::Vec3d(0.0, 0.0, 0.0));
  h.Origin = { { origin.x(), origin.y(), origin.z() } };
  h.Spacing = { { m(0, 0), m(1, 1), m(2, 2) } };

  const openvdb::GridClass cls = base->getGridClass();
  h.GridClass = cls == openvdb::GRID_LEVEL_SET ? "level set"
    : cls == openvdb::GRID_FOG_VOLUME          ? "fog volume"
                                               : "";
  h.Metadata = StringMetadataOf(*base);

  openvdb::CoordBBox box = ExtentOf(*base);
  if (box.empty())
  {
    // A grid with no active voxel and no stored extent: one background voxel.
    box = openvdb::CoordBBox(openvdb::Coord(0), openvdb::Coord(0));
  }
  h.IndexMin = { { box.min().x(), box.min().y(), box.min().z() } };
  for (int k = 0; k < 3; ++k)
    h.Dims[ToIndex(k)] = std::int64_t(box.max()[k]) - box.min()[k] + 1;
  const std::int64_t limit = options.MaxVoxels;
  if (h.Dims[0] > limit || h.Dims[1] > limit / h.Dims[0] ||
    h.Dims[2] > limit / (h.Dims[0] * h.Dims[1]))
  {
    throw Error("grid '" + h.Name + "' spans " + std::to_string(h.Dims[0]) + " x " +
      std::to_string(h.Dims[1]) + " x " + std::to_string(h.Dims[2]) +
      " voxels, more than the limit of " + std::to_string(limit) + " voxels");
  }
  const auto n = ToIndex(h.NumberOfVoxels());
  CheckMemory(n * (h.Type == ValueType::Vec3Float ? 12 : 4),
    "reading grid '" + h.Name + "' (" + std::to_string(h.Dims[0]) + " x " +
      std::to_string(h.Dims[1]) + " x " + std::to_string(h.Dims[2]) + " voxels)");
  switch (h.Type)
  {
    case ValueType::Int32:
    {
      const auto& g = static_cast<const openvdb::Int32Grid&>(*base);
      h.Background = g.background();
      ResizeOnHugePages(out.Ints, n);
      GridToDense(g, box, out.Ints.data());
      break;
    }
    case ValueType::Float:
    {
      const auto& g = static_cast<const openvdb::FloatGrid&>(*base);
      h.Background = g.background();
      ResizeOnHugePages(out.Floats, n);
      GridToDense(g, box, out.Floats.data());
      break;
    }
    case ValueType::Vec3Float:
    {
      const auto& g = static_cast<const openvdb::Vec3SGrid&>(*base);
      h.Background = g.background().x();
      ResizeOnHugePages(out.Floats, 3 * n);
      GridToDense(g, box, reinterpret_cast<openvdb::Vec3s*>(out.Floats.data()));
      break;
    }
  }
  return out;
}

/// Writes grids exactly as openvdb::io::File does (Archive::write to a seekable stream), but to
/// a stream the caller owns and checks: io::File never looks at its stream's state, so a full
/// disk would go unnoticed.
class CheckedArchive : public openvdb::io::Archive
{
public:
  openvdb::io::Archive::Ptr copy() const override
  {
    return openvdb::io::Archive::Ptr(new CheckedArchive(*this));
  }
  void Write(
    std::ostream& out, const openvdb::GridPtrVec& grids, const openvdb::MetaMap& meta) const
  {
    this->write(out, grids, /*seekable=*/true, meta);
  }
};

/// A whole VDB file in memory: its metadata and grids.
struct Archive
{
  openvdb::MetaMap::Ptr Metadata;
  openvdb::GridPtrVecPtr Grids;
};

/// Reads all of @p path through a stream we own, so that a short read (a truncated file) is
/// seen as the stream's failure: OpenVDB itself does not check every read.
Archive LoadArchive(const std::string& path)
{
  std::ifstream in(path, std::ios::binary);
  if (!in)
  {
    throw Error::InFile(path, "cannot be opened for reading (missing or unreadable)");
  }
  char magic[8] = {};
  in.read(magic, 8);
  // OpenVDB files start with the 64-bit magic number 0x56444220 ("VDB ") in little endian.
  if (!in || static_cast<unsigned char>(magic[0]) != 0x20 || magic[1] != 'B' || magic[2] != 'D' ||
    magic[3] != 'V')
  {
    throw Error::InFile(path, "is not a readable OpenVDB file (wrong magic number)");
  }
  in.seekg(0);
  // Throw at the first short read: OpenVDB does not check its reads, and after a failed one it
  // would go on with garbage lengths (allocating up to 2 GB per string).
  in.exceptions(std::ios::failbit | std::ios::badbit);
  Archive archive;
  try
  {
    openvdb::io::Stream stream(in, /*delayLoad=*/false);
    archive.Metadata = stream.getMetadata();
    archive.Grids = stream.getGrids();
  }
  catch (const std::ios_base::failure&)
  {
    throw Error::InFile(path, "is truncated or corrupt (the file ended before its data)");
  }
  catch (const std::bad_alloc&)
  {
    throw Error::InFile(path, "is corrupt or needs more memory than is available");
  }
  catch (const openvdb::Exception& e)
  {
    // "IoError: not a VDB file": the library's description of the file, without its class.
    std::string what = e.what();
    const std::size_t colon = what.find(": ");
    if (colon != std::string::npos && what.compare(colon - 5, 5, "Error") == 0)
      what.erase(0, colon + 2);
    throw Error::InFile(path, "is not a readable OpenVDB file (" + what + ")");
  }
  catch (const std::exception&)
  {
    // A C++ library's own text ("vector::reserve") says nothing to a user.
    throw Error::InFile(path, "is corrupt (a size or count in it is out of range)");
  }
  in.exceptions(std::ios::goodbit);
  if (in.fail() || !archive.Metadata || !archive.Grids)
  {
    throw Error::InFile(path, "is truncated or corrupt (the file ended before its data)");
  }
  in.peek();
  if (!in.eof())
  {
    throw Error::InFile(path, "is corrupt (unexpected data after the last grid)");
  }
  return archive;
}

/// The level set (and fog volume) of one mesh.
/// @p grid named and classed as the level set of @p mesh (with its metadata), and its fog volume
/// when the mesh asks for one, appended to @p out.
void AddLevelSet(
  const MeshGridView& mesh, const openvdb::FloatGrid::Ptr& grid, openvdb::GridPtrVec& out)
{
  grid->setName(mesh.Name);
  grid->setGridClass(openvdb::GRID_LEVEL_SET);
  for (const auto& kv : mesh.Metadata)
    grid->insertMeta(kv.first, openvdb::StringMetadata(kv.second));
  out.push_back(grid);
  if (!mesh.FogName.empty())
  {
    openvdb::FloatGrid::Ptr fog = grid->deepCopy();
    openvdb::tools::sdfToFogVolume(*fog);
    fog->setName(mesh.FogName);
    fog->setGridClass(openvdb::GRID_FOG_VOLUME);
    out.push_back(fog);
  }
}

/// The union of level sets already in @p out (and its fog volume), as MakeMeshGrids makes them.
void MakeUnionGrid(const MeshGridView& mesh, openvdb::GridPtrVec& out)
{
  openvdb::FloatGrid::Ptr grid;
  for (const auto& name : mesh.UnionOf)
  {
    openvdb::FloatGrid::Ptr part;
    for (const auto& g : out)
      if (g->getName() == name)
        part = openvdb::gridPtrCast<openvdb::FloatGrid>(g);
    if (!part || part->getGridClass() != openvdb::GRID_LEVEL_SET)
      throw Error("mesh grid '" + mesh.Name + "': no level set '" + name + "' to unite");
    grid = grid ? openvdb::tools::csgUnionCopy(*grid, *part) : part->deepCopy();
  }
  if (!grid)
    throw Error("mesh grid '" + mesh.Name + "': a union of no level sets");
  grid->clearMetadata();
  AddLevelSet(mesh, grid, out);
}

void MakeMeshGrids(const MeshGridView& mesh, openvdb::GridPtrVec& out)
{
  if (!mesh.UnionOf.empty())
  {
    MakeUnionGrid(mesh, out);
    return;
  }
  if (!mesh.Points || !mesh.Polygons)
  {
    throw Error("mesh grid '" + mesh.Name + "' has no points or polygons");
  }
  if (!(mesh.VoxelSize > 0) || !std::isfinite(mesh.VoxelSize))
  {
    throw Error("mesh grid '" + mesh.Name + "': the voxel size must be positive");
  }
  if (!(mesh.HalfWidth >= 1) || !std::isfinite(mesh.HalfWidth))
  {
    throw Error("mesh grid '" + mesh.Name + "': the band half width must be at least one voxel");
  }
  std::vector<openvdb::Vec3s> points;
  points.reserve(mesh.Points->size());
  for (const auto& p : *mesh.Points)
  {
    points.emplace_back(
      static_cast<float>(p[0]), static_cast<float>(p[1]), static_cast<float>(p[2]));
  }
  std::vector<openvdb::Vec3I> triangles;
  std::vector<openvdb::Vec4I> quads;
  const auto n = static_cast<std::int64_t>(points.size());
  for (const auto& poly : *mesh.Polygons)
  {
    for (auto i : poly)
    {
      if (i < 0 || i >= n)
      {
        throw Error("mesh grid '" + mesh.Name + "' has a polygon with a point index out of range");
      }
    }
    // The sign comes from OpenVDB's inside/outside flood fill, not from the winding.
    if (poly.size() == 4)
    {
      quads.emplace_back(poly[0], poly[1], poly[2], poly[3]);
    }
    else
    {
      for (std::size_t k = 1; k + 1 < poly.size(); ++k)
      {
        triangles.emplace_back(poly[0], poly[k], poly[k + 1]);
      }
    }
  }
  const auto transform = openvdb::math::Transform::createLinearTransform(mesh.VoxelSize);
  openvdb::FloatGrid::Ptr grid = openvdb::tools::meshToLevelSet<openvdb::FloatGrid>(
    *transform, points, triangles, quads, static_cast<float>(mesh.HalfWidth));
  AddLevelSet(mesh, grid, out);
}

// ---------------------------------------------------------------------------------------------
// the module's entry points (names local to the module, so the forwarding functions of the
// same role in libModelSynthVDB never interpose them)
// ---------------------------------------------------------------------------------------------
void WriteHere(const std::string& path, const std::vector<DenseGridView>& grids,
  const std::vector<MeshGridView>& meshes, const std::vector<LabelRenderView>& labels,
  const MetadataMap& metadata)
{
  InitializeOpenVDB();
  if (path.empty())
  {
    throw Error("no output file name was given");
  }
  openvdb::GridPtrVec vdbGrids;
  try
  {
    for (const auto& view : grids)
    {
      for (const auto& g : vdbGrids)
      {
        if (g->getName() == view.Header.Name)
        {
          throw Error("two grids are named '" + view.Header.Name + "'");
        }
      }
      vdbGrids.push_back(MakeGrid(view));
    }
    for (const auto& mesh : meshes)
    {
      MakeMeshGrids(mesh, vdbGrids);
    }
    for (const auto& view : labels)
    {
      detail::AppendRenderGrids(view, *MakeTransform(view.Geometry), vdbGrids);
    }
    for (std::size_t i = 0; i < vdbGrids.size(); ++i)
    {
      for (std::size_t j = 0; j < i; ++j)
      {
        if (vdbGrids[i]->getName() == vdbGrids[j]->getName())
        {
          throw Error("two grids are named '" + vdbGrids[i]->getName() + "'");
        }
      }
    }
  }
  catch (const std::exception& e)
  {
    throw Error::InFile(path, std::string("not written: ") + e.what());
  }

  openvdb::MetaMap fileMeta;
  for (const auto& kv : metadata)
  {
    fileMeta.insertMeta(kv.first, openvdb::StringMetadata(kv.second));
  }
  fileMeta.insertMeta(
    "generator", openvdb::StringMetadata(std::string("ModelSynth ") + MSYNTH_VERSION));

  // Written as io::File writes (a seekable archive), through a checked stream of ours.
  WriteFileAtomically(path,
    [&](std::ostream& out)
    {
      try
      {
        CheckedArchive().Write(out, vdbGrids, fileMeta);
      }
      catch (const Error&)
      {
        throw;
      }
      catch (const std::exception& e)
      {
        throw Error::InFile(path, std::string("could not be written: ") + e.what());
      }
    });
}

FileContents ReadHere(const std::string& path, const ReadOptions& options)
{
  InitializeOpenVDB();
  const Archive archive = LoadArchive(path);
  FileContents contents;
  try
  {
    contents.Metadata = StringMetadataOf(*archive.Metadata);
    for (const auto& grid : *archive.Grids)
    {
      const std::string name = grid->getName();
      if (!options.GridNames.empty() &&
        std::find(options.GridNames.begin(), options.GridNames.end(), name) ==
          options.GridNames.end())
      {
        continue;
      }
      contents.Grids.push_back(ReadGrid(grid, options));
    }
    for (const auto& wanted : options.GridNames)
    {
      if (std::none_of(contents.Grids.begin(), contents.Grids.end(),
            [&](const DenseGrid& g) { return g.Header.Name == wanted; }))
      {
        throw Error("has no grid named '" + wanted + "'");
      }
    }
  }
  catch (const std::bad_alloc&)
  {
    throw Error::InFile(path, "needs more memory than is available");
  }
  catch (const std::exception& e)
  {
    throw Error::InFile(path, e.what());
  }
  return contents;
}

std::vector<GridSummary> ListHere(const std::string& path, MetadataMap* fileMetadata)
{
  InitializeOpenVDB();
  const Archive archive = LoadArchive(path);
  if (fileMetadata)
  {
    *fileMetadata = StringMetadataOf(*archive.Metadata);
  }
  std::vector<GridSummary> result;
  for (const auto& g : *archive.Grids)
  {
    GridSummary s;
    s.Name = g->getName();
    s.TypeName = g->valueType();
    s.GridClass = openvdb::GridBase::gridClassToString(g->getGridClass());
    s.Metadata = StringMetadataOf(*g);
    s.ActiveVoxelCount = static_cast<std::int64_t>(g->activeVoxelCount());
    const openvdb::CoordBBox box = g->evalActiveVoxelBoundingBox();
    if (!box.empty())
      for (std::size_t a = 0; a < 3; ++a)
      {
        s.ActiveMin[a] = box.min()[static_cast<int>(a)];
        s.ActiveMax[a] = box.max()[static_cast<int>(a)];
      }
    const openvdb::Vec3d size = g->voxelSize();
    s.VoxelSize = { { size.x(), size.y(), size.z() } };
    result.push_back(std::move(s));
  }
  return result;
}

void LimitToOneThread()
{
  static tbb::global_control one(tbb::global_control::max_allowed_parallelism, 1);
}
} // namespace

} // namespace vdb
} // namespace msynth

extern "C" const msynth::vdb::detail::Backend* msynth_openvdb_backend()
{
  using namespace msynth::vdb;
  static const detail::Backend backend{ &InitializeOpenVDB, &WriteHere, &ReadHere, &ListHere,
    &LimitToOneThread };
  return &backend;
}
