// SPDX-License-Identifier: BSD-3-Clause
#include "Discrete/Catalog.h"

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
  const SiteArcs* arcs = this->Arcs && !this->Arcs->Empty() ? this->Arcs : nullptr;
  return this->LabelDomains::Propagate(*this->Relation,
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
      if (!arcs)
      {
        return;
      }
      // Arcs to sites inside the region (those outside are fixed: see Constrain).
      const auto& o = this->RegionOrigin;
      const auto& n = arcs->Dims;
      const std::int64_t g = (o[0] + p[0]) + n[0] * ((o[1] + p[1]) + n[1] * (o[2] + p[2]));
      for (std::int64_t i = arcs->Start[static_cast<std::size_t>(g)];
           i < arcs->Start[static_cast<std::size_t>(g + 1)]; ++i)
      {
        const std::int64_t t = arcs->Target[static_cast<std::size_t>(i)];
        const std::int64_t q[3] = { t % n[0] - o[0], (t / n[0]) % n[1] - o[1],
          t / (n[0] * n[1]) - o[2] };
        if (q[0] < 0 || q[1] < 0 || q[2] < 0 || q[0] >= dims[0] || q[1] >= dims[1] ||
          q[2] >= dims[2])
        {
          continue;
        }
        if (!visit(
              q[0] + stride[1] * q[1] + stride[2] * q[2], arcs->Class[static_cast<std::size_t>(i)]))
        {
          return;
        }
      }
    });
}

} // namespace msynth
