// SPDX-License-Identifier: BSD-3-Clause
#include "Discrete/VoxelSurface.h"

#include <unordered_map>

namespace msynth
{

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
  // origin + (i - 1/2, j - 1/2, k - 1/2) * spacing.
  std::unordered_map<std::int64_t, std::int64_t> corners;
  auto corner = [&](std::int64_t i, std::int64_t j, std::int64_t k)
  {
    const std::int64_t key = i + (n[0] + 1) * (j + (n[1] + 1) * k);
    auto it = corners.find(key);
    if (it != corners.end())
      return it->second;
    const auto id = static_cast<std::int64_t>(surface.Points.size());
    surface.Points.push_back({ { origin[0] + (double(i) - 0.5) * spacing[0],
      origin[1] + (double(j) - 0.5) * spacing[1], origin[2] + (double(k) - 0.5) * spacing[2] } });
    corners.emplace(key, id);
    return id;
  };
  // For each direction: the face's four corner offsets, counter-clockwise seen from outside.
  static const int faces[6][4][3] = {
    { { 1, 0, 0 }, { 1, 1, 0 }, { 1, 1, 1 }, { 1, 0, 1 } }, // +x
    { { 0, 0, 0 }, { 0, 0, 1 }, { 0, 1, 1 }, { 0, 1, 0 } }, // -x
    { { 0, 1, 0 }, { 0, 1, 1 }, { 1, 1, 1 }, { 1, 1, 0 } }, // +y
    { { 0, 0, 0 }, { 1, 0, 0 }, { 1, 0, 1 }, { 0, 0, 1 } }, // -y
    { { 0, 0, 1 }, { 1, 0, 1 }, { 1, 1, 1 }, { 0, 1, 1 } }, // +z
    { { 0, 0, 0 }, { 0, 1, 0 }, { 1, 1, 0 }, { 1, 0, 0 } }, // -z
  };
  static const int step[6][3] = { { 1, 0, 0 }, { -1, 0, 0 }, { 0, 1, 0 }, { 0, -1, 0 }, { 0, 0, 1 },
    { 0, 0, -1 } };
  for (std::int64_t z = 0; z < n[2]; ++z)
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
          const std::int64_t qx = x + step[d][0], qy = y + step[d][1], qz = z + step[d][2];
          const Label c = grid.Contains(qx, qy, qz) ? grid.At(qx, qy, qz) : empty;
          if (c == b)
            continue;
          std::array<std::int64_t, 4> quad;
          for (int v = 0; v < 4; ++v)
            quad[static_cast<std::size_t>(v)] =
              corner(x + faces[d][v][0], y + faces[d][v][1], z + faces[d][v][2]);
          surface.Quads.push_back(quad);
          surface.QuadLabels.push_back(b);
        }
      }
  return surface;
}

} // namespace msynth
