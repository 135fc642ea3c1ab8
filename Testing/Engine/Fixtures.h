// SPDX-License-Identifier: BSD-3-Clause
// Example grids shared by the engine tests.
#pragma once
#include "msynth/LabelGrid.h"

#include <vector>

namespace msynth_test
{
/// A 2D grid from rows written top (largest y) first, as in the dissertation's figures.
inline msynth::LabelGrid Grid2D(const std::vector<std::vector<msynth::Label>>& rowsTopToBottom)
{
  const auto ny = static_cast<std::int64_t>(rowsTopToBottom.size());
  const auto nx = static_cast<std::int64_t>(rowsTopToBottom[0].size());
  msynth::LabelGrid g(nx, ny, 1);
  for (std::int64_t y = 0; y < ny; ++y)
    for (std::int64_t x = 0; x < nx; ++x)
      g.Set(x, y, 0,
        rowsTopToBottom[static_cast<std::size_t>(ny - 1 - y)][static_cast<std::size_t>(x)]);
  return g;
}
} // namespace msynth_test
