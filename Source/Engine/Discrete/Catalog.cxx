// SPDX-License-Identifier: BSD-3-Clause
#include "Discrete/Catalog.h"
#include "Core/Index.h"

namespace msynth
{

void Catalog::Reset(
  const std::array<std::int64_t, 3>& origin, const std::array<std::int64_t, 3>& dims)
{
  this->RegionOrigin = origin;
  this->RegionDims = dims;
  this->LabelDomains::Reset(dims[0] * dims[1] * dims[2], this->Rules.NumberOfLabels());
  unsigned lower[3] = { 0, 0, 0 }, upper[3] = { 0, 0, 0 };
  for (int d = 0; d < NumberOfDirections; ++d)
  {
    ((d & 1) ? lower : upper)[AxisOf(d)] |= 1u << d;
  }
  this->Inside.resize(ToIndex(dims[0] * dims[1] * dims[2]));
  std::size_t s = 0;
  for (std::int64_t z = 0; z < dims[2]; ++z)
  {
    const unsigned bz = (z > 0 ? lower[2] : 0) | (z + 1 < dims[2] ? upper[2] : 0);
    for (std::int64_t y = 0; y < dims[1]; ++y)
    {
      const unsigned byz = bz | (y > 0 ? lower[1] : 0) | (y + 1 < dims[1] ? upper[1] : 0);
      for (std::int64_t x = 0; x < dims[0]; ++x)
      {
        this->Inside[s++] = static_cast<std::uint8_t>(
          byz | (x > 0 ? lower[0] : 0) | (x + 1 < dims[0] ? upper[0] : 0));
      }
    }
  }
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
      const unsigned inside = this->Inside[ToIndex(v)];
      for (int d = 0; d < NumberOfDirections; ++d)
      {
        if (!((inside >> d) & 1u))
        {
          continue; // the neighbour is outside the region: fixed, nothing to revise
        }
        const std::int64_t step = stride[AxisOf(d)];
        if (!visit(v + ((d & 1) ? -step : step), d))
        {
          return;
        }
      }
      if (!arcs)
      {
        return;
      }
      // Arcs to sites inside the region (those outside are fixed: see Constrain).
      const std::array<std::int64_t, 3> p = this->Coordinates(v);
      const auto& o = this->RegionOrigin;
      const auto& n = arcs->Dims;
      const std::int64_t g = (o[0] + p[0]) + n[0] * ((o[1] + p[1]) + n[1] * (o[2] + p[2]));
      for (std::int64_t i = arcs->Start[ToIndex(g)]; i < arcs->Start[ToIndex(g + 1)]; ++i)
      {
        const std::int64_t t = arcs->Target[ToIndex(i)];
        const std::int64_t q[3] = { t % n[0] - o[0], (t / n[0]) % n[1] - o[1],
          t / (n[0] * n[1]) - o[2] };
        if (q[0] < 0 || q[1] < 0 || q[2] < 0 || q[0] >= dims[0] || q[1] >= dims[1] ||
          q[2] >= dims[2])
        {
          continue;
        }
        if (!visit(q[0] + stride[1] * q[1] + stride[2] * q[2], arcs->Class[ToIndex(i)]))
        {
          return;
        }
      }
    });
}

} // namespace msynth
