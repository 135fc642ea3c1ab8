// SPDX-License-Identifier: BSD-3-Clause
#include "Discrete/VoxelSurface.h"

#include "Core/Index.h"
#include "Core/ParallelChunks.h"

#include <algorithm>
#include <vector>

namespace msynth
{

namespace
{
// For each direction: the face's four corner offsets, counter-clockwise seen from outside.
const int Faces[6][4][3] = {
  { { 1, 0, 0 }, { 1, 1, 0 }, { 1, 1, 1 }, { 1, 0, 1 } }, // +x
  { { 0, 0, 0 }, { 0, 0, 1 }, { 0, 1, 1 }, { 0, 1, 0 } }, // -x
  { { 0, 1, 0 }, { 0, 1, 1 }, { 1, 1, 1 }, { 1, 1, 0 } }, // +y
  { { 0, 0, 0 }, { 1, 0, 0 }, { 1, 0, 1 }, { 0, 0, 1 } }, // -y
  { { 0, 0, 1 }, { 1, 0, 1 }, { 1, 1, 1 }, { 0, 1, 1 } }, // +z
  { { 0, 0, 0 }, { 0, 1, 0 }, { 1, 1, 0 }, { 1, 0, 0 } }, // -z
};
const int Steps[6][3] = { { 1, 0, 0 }, { -1, 0, 0 }, { 0, 1, 0 }, { 0, -1, 0 }, { 0, 0, 1 },
  { 0, 0, -1 } };

/// The merged faces of @p grid that face direction @p d, their points numbered from 0.
VoxelSurface MergedFacesToward(int d, const LabelGrid& grid, Label empty,
  const std::array<double, 3>& origin, const std::array<double, 3>& spacing)
{
  VoxelSurface surface;
  const auto& n = grid.Dimensions();
  const Label* data = grid.Data().data();
  const std::array<std::int64_t, 3> stride{ { 1, n[0], n[0] * n[1] } };
  std::vector<Label> mask;
  std::vector<std::int64_t> plane; // per corner of the slice's plane: its point, or -1
  std::vector<std::size_t> used;   // corners of the plane numbered so far
  // Slices across axis a; in a slice, u and v are the other two axes in increasing order.
  // Points are shared by the rectangles of one plane (a flat-shaded surface needs no more).
  const int a = d / 2, u = a == 0 ? 1 : 0, v = a == 2 ? 1 : 2;
  const std::int64_t toward = Steps[d][a] * stride[ToIndex(a)];
  mask.assign(ToIndex(n[u] * n[v]), empty);
  plane.assign(ToIndex((n[u] + 1) * (n[v] + 1)), -1);
  for (std::int64_t s = 0; s < n[a]; ++s)
  {
    const bool inside = s + Steps[d][a] >= 0 && s + Steps[d][a] < n[a];
    for (std::int64_t j = 0; j < n[v]; ++j)
      for (std::int64_t i = 0; i < n[u]; ++i)
      {
        const std::int64_t at =
          s * stride[ToIndex(a)] + i * stride[ToIndex(u)] + j * stride[ToIndex(v)];
        const Label b = data[at];
        const bool exposed = b != empty && (!inside || data[at + toward] != b);
        mask[ToIndex(i + n[u] * j)] = exposed ? b : empty;
      }
    for (std::size_t c : used)
      plane[c] = -1;
    used.clear();
    auto corner = [&](std::int64_t i, std::int64_t j, std::int64_t k)
    {
      const auto key = ToIndex(i + (n[u] + 1) * j);
      if (plane[key] < 0)
      {
        plane[key] = static_cast<std::int64_t>(surface.Points.size());
        used.push_back(key);
        std::array<double, 3> p;
        const std::array<std::int64_t, 3> lattice{ { a == 0 ? k : i, a == 1 ? k : (a == 0 ? i : j),
          a == 2 ? k : j } };
        for (std::size_t c = 0; c < 3; ++c)
          p[c] = origin[c] + (double(lattice[c]) - 0.5) * spacing[c];
        surface.Points.push_back(p);
      }
      return plane[key];
    };
    // Greedy rectangles: as wide as the row allows, then as high as whole rows allow.
    auto cell = [&](std::int64_t i, std::int64_t j) -> Label&
    { return mask[ToIndex(i + n[u] * j)]; };
    for (std::int64_t v0 = 0; v0 < n[v]; ++v0)
      for (std::int64_t u0 = 0; u0 < n[u];)
      {
        const Label b = cell(u0, v0);
        if (b == empty)
        {
          ++u0;
          continue;
        }
        std::int64_t u1 = u0 + 1, v1 = v0 + 1;
        while (u1 < n[u] && cell(u1, v0) == b)
          ++u1;
        for (bool whole = true; whole && v1 < n[v];)
        {
          for (std::int64_t i = u0; i < u1 && whole; ++i)
            whole = cell(i, v1) == b;
          v1 += whole ? 1 : 0;
        }
        for (std::int64_t j = v0; j < v1; ++j)
          std::fill(&cell(u0, j), &cell(u0, j) + (u1 - u0), empty);
        std::array<std::int64_t, 4> quad;
        for (int k = 0; k < 4; ++k) // the unit face's corner, stretched over the rectangle
          quad[ToIndex(k)] =
            corner(Faces[d][k][u] ? u1 : u0, Faces[d][k][v] ? v1 : v0, s + Faces[d][k][a]);
        surface.Quads.push_back(quad);
        surface.QuadLabels.push_back(b);
        u0 = u1;
      }
  }
  return surface;
}
} // namespace

VoxelSurface ExtractMergedVoxelSurface(const LabelGrid& grid, Label empty,
  const std::array<double, 3>& origin, const std::array<double, 3>& spacing)
{
  // The six directions on threads, joined in direction order: the same surface, with the same
  // numbering, as one pass over the directions.
  std::array<VoxelSurface, 6> parts;
  RunChunks(parts.size(), 0,
    [&](std::size_t d)
    { parts[d] = MergedFacesToward(static_cast<int>(d), grid, empty, origin, spacing); });
  VoxelSurface surface;
  std::size_t points = 0, quads = 0;
  for (const VoxelSurface& part : parts)
  {
    points += part.Points.size();
    quads += part.Quads.size();
  }
  surface.Points.reserve(points);
  surface.Quads.reserve(quads);
  surface.QuadLabels.reserve(quads);
  for (VoxelSurface& part : parts)
  {
    const auto first = static_cast<std::int64_t>(surface.Points.size());
    surface.Points.insert(surface.Points.end(), part.Points.begin(), part.Points.end());
    for (auto quad : part.Quads)
    {
      for (auto& corner : quad)
        corner += first;
      surface.Quads.push_back(quad);
    }
    surface.QuadLabels.insert(
      surface.QuadLabels.end(), part.QuadLabels.begin(), part.QuadLabels.end());
    part = VoxelSurface(); // its memory back before the next part is copied
  }
  return surface;
}

SiteSlab PieceSlab(const LabelGrid& grid, int piece, int pieces)
{
  const auto& n = grid.Dimensions();
  SiteSlab slab;
  slab.Axis = 0;
  for (int a = 1; a < 3; ++a)
    if (n[a] > n[slab.Axis])
      slab.Axis = a;
  if (pieces < 1 || piece < 0 || piece >= pieces)
  {
    slab.Begin = slab.End = 0;
    return slab;
  }
  const std::int64_t length = n[slab.Axis];
  slab.Begin = length * piece / pieces;
  slab.End = length * (piece + 1) / pieces;
  return slab;
}

VoxelSurface ExtractVoxelSurface(const LabelGrid& grid, Label empty,
  const std::array<double, 3>& origin, const std::array<double, 3>& spacing, const SiteSlab& slab)
{
  VoxelSurface surface;
  const auto& n = grid.Dimensions();
  // Cube corners are lattice points (i, j, k) in [0, n]; corner (i, j, k) lies at
  // origin + (i - 1/2, j - 1/2, k - 1/2) * spacing. Points are numbered as first met; the faces
  // of the voxels of layer z use corner layers k = z and z + 1 only, so two layers of numbers
  // (-1: not met yet) are all the lookup needs.
  const auto across = ToIndex((n[0] + 1) * (n[1] + 1));
  std::vector<std::int64_t> layers[2] = { std::vector<std::int64_t>(across, -1),
    std::vector<std::int64_t>(across, -1) };
  auto corner = [&](std::int64_t i, std::int64_t j, std::int64_t k)
  {
    std::int64_t& id = layers[k & 1][ToIndex(i + (n[0] + 1) * j)];
    if (id < 0)
    {
      id = static_cast<std::int64_t>(surface.Points.size());
      surface.Points.push_back({ { origin[0] + (double(i) - 0.5) * spacing[0],
        origin[1] + (double(j) - 0.5) * spacing[1], origin[2] + (double(k) - 0.5) * spacing[2] } });
    }
    return id;
  };
  for (std::int64_t z = 0; z < n[2]; ++z)
  {
    if (z > 0) // layer z + 1 takes the numbers of layer z - 1, which no face uses any more
      std::fill(layers[(z + 1) & 1].begin(), layers[(z + 1) & 1].end(), -1);
    for (std::int64_t y = 0; y < n[1]; ++y)
      for (std::int64_t x = 0; x < n[0]; ++x)
      {
        const std::int64_t along = slab.Axis == 0 ? x : slab.Axis == 1 ? y : z;
        if (along < slab.Begin || along >= slab.End)
          continue;
        const Label b = grid.At(x, y, z);
        if (b == empty)
          continue;
        for (int d = 0; d < 6; ++d)
        {
          const std::int64_t qx = x + Steps[d][0], qy = y + Steps[d][1], qz = z + Steps[d][2];
          const Label c = grid.Contains(qx, qy, qz) ? grid.At(qx, qy, qz) : empty;
          if (c == b)
            continue;
          std::array<std::int64_t, 4> quad;
          for (int v = 0; v < 4; ++v)
            quad[ToIndex(v)] = corner(x + Faces[d][v][0], y + Faces[d][v][1], z + Faces[d][v][2]);
          surface.Quads.push_back(quad);
          surface.QuadLabels.push_back(b);
        }
      }
  }
  return surface;
}

} // namespace msynth
