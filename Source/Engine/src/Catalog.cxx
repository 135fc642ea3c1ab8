// SPDX-License-Identifier: BSD-3-Clause
#include "msynth/Catalog.h"

namespace msynth
{

void Catalog::Reset(
  const std::array<std::int64_t, 3>& origin, const std::array<std::int64_t, 3>& dims)
{
  this->RegionOrigin = origin;
  this->RegionDims = dims;
  this->LabelDomains::Reset(dims[0] * dims[1] * dims[2], this->Rules.NumberOfLabels());
}

std::array<std::int64_t, 3> Catalog::Coordinates(std::int64_t local) const
{
  const std::int64_t nx = this->RegionDims[0], ny = this->RegionDims[1];
  return { { local % nx, (local / nx) % ny, local / (nx * ny) } };
}

std::int64_t Catalog::Propagate()
{
  const auto& dims = this->RegionDims;
  const std::int64_t stride[3] = { 1, dims[0], dims[0] * dims[1] };
  return this->LabelDomains::Propagate(this->Rules,
    [&](std::int64_t v, auto&& visit)
    {
      const std::array<std::int64_t, 3> p = this->Coordinates(v);
      for (int d = 0; d < NumberOfDirections; ++d)
      {
        const int axis = AxisOf(d);
        const bool minus = d & 1;
        if ((minus && p[axis] == 0) || (!minus && p[axis] + 1 >= dims[axis]))
        {
          continue; // the neighbour is outside the region: fixed, nothing to revise
        }
        if (!visit(v + (minus ? -stride[axis] : stride[axis]), d))
        {
          return;
        }
      }
    });
}

} // namespace msynth
