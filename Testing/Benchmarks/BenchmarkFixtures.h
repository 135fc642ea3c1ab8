// SPDX-License-Identifier: BSD-3-Clause
#pragma once
#include "Core/LabelGrid.h"

#include <random>

namespace msynth_bench
{
/// A city-like label volume: ground, buildings of random heights and roofs, in empty space;
/// about 30% of the sites are non-empty. Deterministic for a given size.
inline msynth::LabelGrid City(std::int64_t n, std::int64_t nz)
{
  msynth::LabelGrid g(n, n, nz, 0);
  std::mt19937 rng(7);
  for (std::int64_t y = 0; y < n; ++y)
  {
    for (std::int64_t x = 0; x < n; ++x)
    {
      g.Set(x, y, 0, 1);
      const bool lot = (x / 4 + y / 4) % 2 == 0 && x % 4 != 0 && y % 4 != 0;
      const std::int64_t h =
        lot ? 1 + static_cast<std::int64_t>(rng() % static_cast<unsigned>(nz - 2)) : 0;
      for (std::int64_t z = 1; z <= h; ++z)
      {
        g.Set(x, y, z, 2 + static_cast<msynth::Label>(rng() % 8)); // wall variants
      }
      if (h > 0)
      {
        g.Set(x, y, h + 1 < nz ? h + 1 : h, 10);
      }
    }
  }
  return g;
}
} // namespace msynth_bench

namespace msynth_bench
{
/// A small city of about 100 labels in the spirit of the dissertation's Fig. 3.20, built of
/// modular pieces as its buildings are: each building piece is (style, position in the
/// footprint, storey kind), with 3 styles × 9 positions (corners, edges, middle) × 3 storey
/// kinds (ground floor, middle storeys, top storey) = 81 labels, 9 roof pieces, grass,
/// pavement around buildings, and empty space. Walls can stretch in x, y and z, so large
/// outputs exist. Deterministic.
inline msynth::LabelGrid City100()
{
  const std::int64_t n = 30, nz = 10;
  msynth::LabelGrid g(n, n, nz, 0);
  for (std::int64_t y = 0; y < n; ++y)
    for (std::int64_t x = 0; x < n; ++x)
      g.Set(x, y, 0, 1); // grass
  std::mt19937 rng(99);
  auto position = [](std::int64_t i, std::int64_t w) { return i == 0 ? 0 : (i == w - 1 ? 2 : 1); };
  for (std::int64_t by = 1; by + 6 < n; by += 7)
  {
    for (std::int64_t bx = 1; bx + 6 < n; bx += 7)
    {
      const std::int64_t w = 3 + static_cast<std::int64_t>(rng() % 3),
                         d = 3 + static_cast<std::int64_t>(rng() % 3);
      const std::int64_t h = 4 + static_cast<std::int64_t>(rng() % 5); // roof height
      const auto style = static_cast<msynth::Label>(rng() % 3);
      for (std::int64_t y = by - 1; y <= by + d; ++y)
        for (std::int64_t x = bx - 1; x <= bx + w; ++x)
          g.Set(x, y, 0, 2); // pavement around and under the building
      for (std::int64_t y = by; y < by + d; ++y)
        for (std::int64_t x = bx; x < bx + w; ++x)
        {
          const auto p = static_cast<msynth::Label>(position(x - bx, w) + 3 * position(y - by, d));
          for (std::int64_t z = 1; z < h; ++z)
          {
            const msynth::Label kind = z == 1 ? 0 : (z == h - 1 ? 2 : 1);
            g.Set(x, y, z, 10 + style * 27 + kind * 9 + p);
          }
          g.Set(x, y, h, 91 + p);
        }
    }
  }
  return g;
}
} // namespace msynth_bench
