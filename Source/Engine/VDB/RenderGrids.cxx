// SPDX-License-Identifier: BSD-3-Clause
// The render grids of a label volume (RenderGrids.h), in the OpenVDB module: a fog volume of
// the solid voxels, their colours, and level sets of the solid and of each named label.
#include "VDB/RenderGridsOpenVDB.h"

#include "Core/Error.h"
#include "Core/Index.h"

#include <openvdb/tools/Dense.h>
#include <openvdb/tools/SignedFloodFill.h>
#include <openvdb/tree/LeafManager.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <set>
#include <unordered_map>

namespace msynth
{
namespace vdb
{
namespace detail
{
namespace
{
// ---------------------------------------------------------------------------------------------
// internal
// ---------------------------------------------------------------------------------------------
constexpr float Far = std::numeric_limits<float>::infinity();
using Extent = std::array<std::int64_t, 3>;

/// Whether a voxel of @p label is solid: not empty, nor undecided (a catalog snapshot's INT_MIN,
/// empty in mesh.vtp too).
bool IsSolid(const LabelRenderView& view, std::int32_t label)
{
  return label != view.EmptyLabel && label != std::numeric_limits<std::int32_t>::min();
}

/// A box of voxels: its lowest index and its dimensions.
struct Box
{
  Extent Lo{ { 0, 0, 0 } };
  Extent Dims{ { 0, 0, 0 } };
  std::int64_t Size() const { return this->Dims[0] * this->Dims[1] * this->Dims[2]; }
  std::int64_t Hi(std::size_t a) const { return this->Lo[a] + this->Dims[a] - 1; }
};

/// Maps label values (or name keys) to small indices: a table over their range when it is
/// small, a hash map otherwise.
class KeyIndex
{
public:
  KeyIndex(const std::map<std::int32_t, int>& indices)
  {
    if (indices.empty())
      return;
    this->Low = indices.begin()->first;
    const std::int64_t range = std::int64_t(indices.rbegin()->first) - this->Low + 1;
    if (range <= (std::int64_t(1) << 20))
    {
      this->Table.assign(ToIndex(range), -1);
      for (const auto& [key, index] : indices)
        this->Table[ToIndex(std::int64_t(key) - this->Low)] = index;
    }
    else
      this->Hashed.insert(indices.begin(), indices.end());
  }
  /// The index of @p key, -1 when it has none.
  int operator()(std::int32_t key) const
  {
    if (!this->Table.empty())
    {
      const std::int64_t i = std::int64_t(key) - this->Low;
      return i >= 0 && i < static_cast<std::int64_t>(this->Table.size()) ? this->Table[ToIndex(i)]
                                                                         : -1;
    }
    const auto it = this->Hashed.find(key);
    return it == this->Hashed.end() ? -1 : it->second;
  }

private:
  std::int64_t Low = 0;
  std::vector<int> Table;
  std::unordered_map<std::int32_t, int> Hashed;
};

/**
 * One axis of the separable minimum: @p d (over @p box, x fastest) becomes, along axis @p a,
 * min over |k| ≤ reach of d(p + k e_a) + cost[|k|]. Along x line by line; along y and z whole
 * rows of x at a time (contiguous, so the inner loop vectorizes). Each line's result depends on
 * that line alone, so it is the same for any thread count.
 */
void MinimumAlong(
  std::vector<float>& d, const Box& box, std::size_t a, int reach, const std::vector<float>& cost)
{
  const std::int64_t nx = box.Dims[0], ny = box.Dims[1], n = box.Dims[a];
  if (a == 0)
  {
    tbb::parallel_for(tbb::blocked_range<std::int64_t>(0, box.Size() / nx, 64),
      [&](const tbb::blocked_range<std::int64_t>& range)
      {
        std::vector<float> line(ToIndex(nx));
        for (std::int64_t l = range.begin(); l < range.end(); ++l)
        {
          float* row = d.data() + ToIndex(l * nx);
          std::copy(row, row + nx, line.begin());
          for (std::int64_t i = 0; i < nx; ++i)
          {
            float best = line[ToIndex(i)];
            const std::int64_t from = std::max<std::int64_t>(0, i - reach);
            const std::int64_t to = std::min<std::int64_t>(nx - 1, i + reach);
            for (std::int64_t j = from; j <= to; ++j)
              best = std::min(best, line[ToIndex(j)] + cost[ToIndex(std::abs(j - i))]);
            row[i] = best;
          }
        }
      });
    return;
  }
  // Rows along a are rowStride apart; groups of them (a slice for y, a column of rows for z)
  // outerStride apart.
  const std::int64_t rowStride = a == 1 ? nx : nx * ny;
  const std::int64_t outer = a == 1 ? box.Dims[2] : ny;
  const std::int64_t outerStride = a == 1 ? nx * ny : nx;
  tbb::parallel_for(tbb::blocked_range<std::int64_t>(0, outer),
    [&](const tbb::blocked_range<std::int64_t>& range)
    {
      std::vector<float> rows(ToIndex(n * nx));
      for (std::int64_t o = range.begin(); o < range.end(); ++o)
      {
        float* base = d.data() + ToIndex(o * outerStride);
        for (std::int64_t i = 0; i < n; ++i)
          std::copy(base + i * rowStride, base + i * rowStride + nx, rows.begin() + i * nx);
        for (std::int64_t i = 0; i < n; ++i)
        {
          float* out = base + i * rowStride;
          const std::int64_t from = std::max<std::int64_t>(0, i - reach);
          const std::int64_t to = std::min<std::int64_t>(n - 1, i + reach);
          for (std::int64_t j = from; j <= to; ++j)
          {
            if (j == i)
              continue;
            const float c = cost[ToIndex(std::abs(j - i))];
            const float* in = rows.data() + j * nx;
            for (std::int64_t x = 0; x < nx; ++x)
              out[x] = std::min(out[x], in[x] + c);
          }
        }
      }
    });
}

/// The geometry of a band: the reach along each axis (in voxels) and the cost of each step.
struct Band
{
  std::array<int, 3> Reach{ { 1, 1, 1 } };
  std::array<std::vector<float>, 3> Cost;
  float Background = 3.0f; ///< the band's half width in world units
};

Band MakeBand(const LabelRenderView& view)
{
  const auto& s = view.Geometry.Spacing;
  const double h = std::min({ s[0], s[1], s[2] });
  Band band;
  band.Background = static_cast<float>(view.HalfWidth * h);
  for (std::size_t a = 0; a < 3; ++a)
  {
    // A voxel k steps away along a is at least (k - 1/2) s_a away: those below the band count.
    const double w = view.HalfWidth * h / s[a] + 0.5;
    band.Reach[a] = std::max(1, static_cast<int>(std::ceil(w)) - 1);
    band.Cost[a].resize(ToIndex(band.Reach[a] + 1));
    for (int k = 0; k <= band.Reach[a]; ++k)
    {
      const double step = k == 0 ? 0.0 : (k - 0.5) * s[a];
      band.Cost[a][ToIndex(k)] = static_cast<float>(step * step);
    }
  }
  return band;
}

/// The values of @p box (x fastest) into @p grid; those equal to its background stay inactive.
void CopyFromBox(const Box& box, float* values, openvdb::FloatGrid& grid)
{
  const auto c = [](std::int64_t v) { return static_cast<openvdb::Int32>(v); };
  const openvdb::CoordBBox bounds(openvdb::Coord(c(box.Lo[0]), c(box.Lo[1]), c(box.Lo[2])),
    openvdb::Coord(c(box.Hi(0)), c(box.Hi(1)), c(box.Hi(2))));
  openvdb::tools::Dense<float, openvdb::tools::LayoutXYZ> dense(bounds, values);
  openvdb::tools::copyFromDense(dense, grid, 0.0f);
}

/// Squared distances over @p box from each voxel to the nearest voxel box of the set whose
/// voxels hold 0 in @p d (Far elsewhere): exact below the band, Far or more beyond it.
void SquaredDistances(std::vector<float>& d, const Box& box, const Band& band)
{
  for (std::size_t a = 0; a < 3; ++a)
    if (box.Dims[a] > 1)
      MinimumAlong(d, box, a, band.Reach[a], band.Cost[a]);
}

/**
 * The level set of the voxels for which @p inside(i) holds (i the index of a voxel of the label
 * box @p labels; voxels outside it are outside), over @p box (the set's bounding box grown by
 * the band's reach).
 */
template <typename Inside>
openvdb::FloatGrid::Ptr LevelSet(const Box& labels, const Box& box, const Band& band,
  const openvdb::math::Transform& transform, const Inside& inside)
{
  const auto n = ToIndex(box.Size());
  std::vector<float> toSolid(n), toEmpty(n);
  const std::int64_t nx = box.Dims[0], ny = box.Dims[1];
  tbb::parallel_for(tbb::blocked_range<std::int64_t>(0, box.Dims[2]),
    [&](const tbb::blocked_range<std::int64_t>& range)
    {
      for (std::int64_t z = range.begin(); z < range.end(); ++z)
        for (std::int64_t y = 0; y < ny; ++y)
        {
          // The row's place in the label box (outside it: empty).
          const std::int64_t ly = box.Lo[1] + y - labels.Lo[1];
          const std::int64_t lz = box.Lo[2] + z - labels.Lo[2];
          const bool within = ly >= 0 && ly < labels.Dims[1] && lz >= 0 && lz < labels.Dims[2];
          const std::int64_t row = labels.Dims[0] * (ly + labels.Dims[1] * lz);
          for (std::int64_t x = 0; x < nx; ++x)
          {
            const std::int64_t lx = box.Lo[0] + x - labels.Lo[0];
            const bool solid = within && lx >= 0 && lx < labels.Dims[0] && inside(row + lx);
            const auto i = ToIndex(x + nx * (y + ny * z));
            toSolid[i] = solid ? 0.0f : Far;
            toEmpty[i] = solid ? Far : 0.0f;
          }
        }
    });
  SquaredDistances(toSolid, box, band);
  SquaredDistances(toEmpty, box, band);
  // Signed distances below the band; the background elsewhere (made negative inside by the
  // flood fill below), so that exactly the band is active.
  const float bg = band.Background;
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, std::size_t(1) << 16),
    [&](const tbb::blocked_range<std::size_t>& range)
    {
      for (std::size_t i = range.begin(); i < range.end(); ++i)
      {
        const float v = toEmpty[i] > 0 ? -std::sqrt(toEmpty[i]) : std::sqrt(toSolid[i]);
        toSolid[i] = std::abs(v) < bg ? v : bg;
      }
    });
  std::vector<float>().swap(toEmpty);
  openvdb::FloatGrid::Ptr grid = openvdb::FloatGrid::create(bg);
  CopyFromBox(box, toSolid.data(), *grid);
  openvdb::tools::signedFloodFill(grid->tree());
  grid->setTransform(transform.copy());
  grid->setGridClass(openvdb::GRID_LEVEL_SET);
  return grid;
}

/// @p box grown by the band's reach along each axis.
Box Grown(Box box, const Band& band)
{
  for (std::size_t a = 0; a < 3; ++a)
  {
    box.Lo[a] -= band.Reach[a];
    box.Dims[a] += 2 * band.Reach[a];
  }
  return box;
}

void StoreExtent(openvdb::GridBase& grid, const Box& box)
{
  const auto c = [](std::int64_t v) { return static_cast<int>(v); };
  grid.insertMeta(
    IndexMinKey, openvdb::Vec3IMetadata(openvdb::Vec3i(c(box.Lo[0]), c(box.Lo[1]), c(box.Lo[2]))));
  grid.insertMeta(
    IndexMaxKey, openvdb::Vec3IMetadata(openvdb::Vec3i(c(box.Hi(0)), c(box.Hi(1)), c(box.Hi(2)))));
}

/// `density` (1 at the solid voxels) and `color` (their labels' linear colours).
void AppendDensityAndColor(const LabelRenderView& view, const Box& labels,
  const openvdb::math::Transform& transform, openvdb::GridPtrVec& out)
{
  const auto n = ToIndex(labels.Size());
  std::vector<float> solid(n);
  for (std::size_t i = 0; i < n; ++i)
    solid[i] = IsSolid(view, view.Labels[i]) ? 1.0f : 0.0f;
  openvdb::FloatGrid::Ptr density = openvdb::FloatGrid::create(0.0f);
  CopyFromBox(labels, solid.data(), *density);
  density->setName("density");
  density->setGridClass(openvdb::GRID_FOG_VOLUME);
  density->setTransform(transform.copy());
  StoreExtent(*density, labels);
  std::vector<float>().swap(solid);

  // The colours on the density's voxels, leaf by leaf on threads.
  std::map<std::int32_t, int> indices;
  std::vector<openvdb::Vec3s> colors;
  for (const auto& [label, rgb] : view.Colors)
  {
    indices[label] = static_cast<int>(colors.size());
    colors.emplace_back(rgb[0], rgb[1], rgb[2]);
  }
  const KeyIndex colorOf(indices);
  openvdb::Vec3SGrid::Ptr color = openvdb::Vec3SGrid::create(openvdb::Vec3s(0.0f));
  color->tree().topologyUnion(density->tree());
  openvdb::tree::LeafManager<openvdb::Vec3STree> leaves(color->tree());
  leaves.foreach (
    [&](openvdb::Vec3STree::LeafNodeType& leaf, std::size_t)
    {
      for (auto v = leaf.beginValueOn(); v; ++v)
      {
        const openvdb::Coord c = v.getCoord();
        const std::int64_t at = (c.x() - labels.Lo[0]) +
          labels.Dims[0] * ((c.y() - labels.Lo[1]) + labels.Dims[1] * (c.z() - labels.Lo[2]));
        const int k = colorOf(view.Labels[ToIndex(at)]);
        v.setValue(k < 0 ? openvdb::Vec3s(0.5f) : colors[ToIndex(k)]);
      }
    });
  color->setName("color");
  color->setTransform(transform.copy());
  StoreExtent(*color, labels);
  out.push_back(density);
  out.push_back(color);
}

/// The `surface_NAME` grids: each name's voxels, their bounding box found in one pass. Returns
/// how many were written (a name no solid voxel has gets none).
int AppendLabelSurfaces(const LabelRenderView& view, const Box& labels, const Band& band,
  const openvdb::math::Transform& transform, openvdb::GridPtrVec& out)
{
  std::map<std::string, int> nameIndex;
  std::map<std::int32_t, int> keys;
  for (const auto& [key, name] : view.Names)
    keys[key] = nameIndex.emplace(name, static_cast<int>(nameIndex.size())).first->second;
  const KeyIndex nameOf(keys);
  const std::int32_t* key = view.NameKeys ? view.NameKeys : view.Labels;
  std::vector<Box> boxes(nameIndex.size());
  std::vector<std::array<std::int64_t, 6>> bounds(
    nameIndex.size(), { { INT64_MAX, INT64_MAX, INT64_MAX, INT64_MIN, INT64_MIN, INT64_MIN } });
  std::int64_t next = 0;
  for (std::int64_t z = 0; z < labels.Dims[2]; ++z)
    for (std::int64_t y = 0; y < labels.Dims[1]; ++y)
      for (std::int64_t x = 0; x < labels.Dims[0]; ++x, ++next)
      {
        const auto at = ToIndex(next);
        const int k = IsSolid(view, view.Labels[at]) ? nameOf(key[at]) : -1;
        if (k < 0)
          continue;
        auto& b = bounds[ToIndex(k)];
        const std::int64_t p[3] = { x, y, z };
        for (std::size_t a = 0; a < 3; ++a)
        {
          b[a] = std::min(b[a], p[a]);
          b[a + 3] = std::max(b[a + 3], p[a]);
        }
      }
  int written = 0;
  for (const auto& [name, k] : nameIndex)
  {
    const auto& b = bounds[ToIndex(k)];
    if (b[0] > b[3])
      continue; // a name no solid voxel has
    ++written;
    Box box;
    for (std::size_t a = 0; a < 3; ++a)
    {
      box.Lo[a] = labels.Lo[a] + b[a];
      box.Dims[a] = b[a + 3] - b[a] + 1;
    }
    const int wanted = k;
    openvdb::FloatGrid::Ptr grid = LevelSet(labels, Grown(box, band), band, transform,
      [&](std::int64_t at)
      {
        const auto site = ToIndex(at);
        return IsSolid(view, view.Labels[site]) && nameOf(key[site]) == wanted;
      });
    grid->setName("surface_" + GridNameSuffix(name));
    grid->insertMeta("label_name", openvdb::StringMetadata(name));
    std::string values;
    for (const auto& [value, index] : keys)
      if (index == wanted)
        values += (values.empty() ? "" : " ") + std::to_string(value);
    grid->insertMeta(view.NameKeys ? "name_keys" : "labels", openvdb::StringMetadata(values));
    out.push_back(grid);
  }
  return written;
}
} // namespace

// ---------------------------------------------------------------------------------------------
// the module's render grids
// ---------------------------------------------------------------------------------------------
void AppendRenderGrids(
  const LabelRenderView& view, const openvdb::math::Transform& transform, openvdb::GridPtrVec& out)
{
  if (!view.Labels || view.Geometry.NumberOfVoxels() <= 0)
    throw Error("the render grids have no labels");
  if (!(view.HalfWidth >= 1) || !std::isfinite(view.HalfWidth))
    throw Error("the render grids' band half width must be at least one voxel");
  Box labels;
  for (std::size_t a = 0; a < 3; ++a)
  {
    labels.Lo[a] = view.Geometry.IndexMin[a];
    labels.Dims[a] = view.Geometry.Dims[a];
  }
  const Band band = MakeBand(view);
  // The level set first: its distance buffers are freed before the colours' tree is made
  // (together they were the writer's peak: 1.04 GB for 10^7 sites).
  openvdb::FloatGrid::Ptr surface = LevelSet(labels, Grown(labels, band), band, transform,
    [&view](std::int64_t at) { return IsSolid(view, view.Labels[ToIndex(at)]); });
  surface->setName("surface");
  AppendDensityAndColor(view, labels, transform, out);
  std::set<std::string> names;
  for (const auto& kv : view.Names)
    names.insert(kv.second);
  const bool fit = LabelSurfacesFit(labels.Size(), names.size(), view.LabelSurfaceBudget);
  out.push_back(surface);
  std::string note = "none: the labels have no names";
  if (!names.empty() && !fit)
    note = "skipped: " + std::to_string(labels.Size()) + " voxels x " +
      std::to_string(names.size()) + " named labels is over the budget of " +
      std::to_string(static_cast<long long>(view.LabelSurfaceBudget));
  else if (!names.empty())
  {
    const int written = AppendLabelSurfaces(view, labels, band, transform, out);
    note = std::to_string(written) + " written (surface_NAME)";
    if (written < static_cast<int>(names.size()))
      note +=
        "; " + std::to_string(names.size() - ToIndex(written)) + " named labels have no solid site";
  }
  surface->insertMeta("msynth_label_surfaces", openvdb::StringMetadata(note));
}

} // namespace detail
} // namespace vdb
} // namespace msynth
