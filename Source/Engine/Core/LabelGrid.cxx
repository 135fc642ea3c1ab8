// SPDX-License-Identifier: BSD-3-Clause
#include "Core/LabelGrid.h"

#include "Core/Error.h"
#include "Core/Index.h"

#include <string>
#include <utility>

namespace msynth
{

void LabelGrid::CheckDimensions(std::int64_t nx, std::int64_t ny, std::int64_t nz)
{
  if (nx < 1 || ny < 1 || nz < 1)
  {
    throw Error("label grid dimensions must be at least 1, got " + std::to_string(nx) + " x " +
      std::to_string(ny) + " x " + std::to_string(nz));
  }
  // Multiply step by step so the product cannot overflow before the comparison.
  if (nx > MaxSites || ny > MaxSites / nx || nz > MaxSites / (nx * ny))
  {
    throw Error("label grid of " + std::to_string(nx) + " x " + std::to_string(ny) + " x " +
      std::to_string(nz) + " sites exceeds the limit of " + std::to_string(MaxSites) + " sites");
  }
}

LabelGrid::LabelGrid(std::int64_t nx, std::int64_t ny, std::int64_t nz, Label fill)
{
  CheckDimensions(nx, ny, nz);
  this->Dims = { { nx, ny, nz } };
  this->Labels.assign(ToIndex(nx * ny * nz), fill);
}

LabelGrid::LabelGrid(std::array<std::int64_t, 3> dims, std::vector<Label> labels)
{
  CheckDimensions(dims[0], dims[1], dims[2]);
  if (static_cast<std::int64_t>(labels.size()) != dims[0] * dims[1] * dims[2])
  {
    throw Error("label grid of " + std::to_string(dims[0]) + " x " + std::to_string(dims[1]) +
      " x " + std::to_string(dims[2]) + " sites was given " + std::to_string(labels.size()) +
      " labels");
  }
  this->Dims = dims;
  this->Labels = std::move(labels);
}

} // namespace msynth
