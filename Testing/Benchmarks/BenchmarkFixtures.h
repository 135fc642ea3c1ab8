// SPDX-License-Identifier: BSD-3-Clause
#pragma once
#include "msynth/LabelGrid.h"

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
