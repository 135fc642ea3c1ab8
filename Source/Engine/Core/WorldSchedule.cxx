// SPDX-License-Identifier: BSD-3-Clause
#include "Core/WorldSchedule.h"

#include "Core/Error.h"
#include "Core/Index.h"

#include <algorithm>

namespace msynth
{

WorldLattice::WorldLattice(const WorldBox& world, const WorldBox& m, const WorldBox& step)
  : N(world)
  , M(m)
  , Step(step)
{
  for (std::size_t a = 0; a < 3; ++a)
  {
    if (world[a] < 1 || m[a] < 1 || step[a] < 1 || step[a] > m[a])
      throw Error("world lattice: sizes must be positive and steps at most the block");
    // Origins k · step for k = 0 .. K - 1, the last the first with k · step + m >= n.
    this->Counts[a] = world[a] <= m[a] ? 1 : (world[a] - m[a] + step[a] - 1) / step[a] + 1;
    this->Periods[a] = this->Counts[a] > 1 ? (m[a] + 1 + step[a] - 1) / step[a] : 1;
  }
  for (int a : PhaseDigitOrder<3>(this->Counts, PhaseDigits::FewestOriginsFirst))
  {
    this->Radix[ToIndex(a)] = this->NumberOfPhases;
    this->NumberOfPhases *= static_cast<int>(this->Periods[ToIndex(a)]);
  }
}

BoxBlock<3> WorldLattice::At(const WorldBox& g) const
{
  BoxBlock<3> b;
  b.Index = g[0] + this->Counts[0] * (g[1] + this->Counts[1] * g[2]);
  for (std::size_t a = 0; a < 3; ++a)
  {
    b.Origin[a] = g[a] * this->Step[a];
    b.Dims[a] = std::min(this->M[a], this->N[a] - b.Origin[a]);
    b.Phase += static_cast<int>(this->Radix[a] * (g[a] % this->Periods[a]));
  }
  return b;
}

void WorldLattice::Meeting(
  int phase, const WorldBox& lo, const WorldBox& hi, std::vector<BoxBlock<3>>& out) const
{
  std::array<std::vector<std::int64_t>, 3> along;
  for (std::size_t a = 0; a < 3; ++a)
  {
    const std::int64_t digit = this->Digit(phase, static_cast<int>(a));
    // Blocks [k · step, k · step + m) with k · step < hi and k · step + m > lo.
    const std::int64_t first = std::max<std::int64_t>(0, (lo[a] - this->M[a]) / this->Step[a]);
    const std::int64_t last = std::min(this->Counts[a] - 1, (hi[a] - 1) / this->Step[a]);
    for (std::int64_t k = first; k <= last; ++k)
      if (k % this->Periods[a] == digit && k * this->Step[a] < hi[a] &&
        k * this->Step[a] + this->M[a] > lo[a])
        along[a].push_back(k);
  }
  for (std::int64_t k2 : along[2])
    for (std::int64_t k1 : along[1])
      for (std::int64_t k0 : along[0])
        out.push_back(this->At({ { k0, k1, k2 } }));
}

RegionCone PlanRegion(
  const WorldLattice& lattice, const WorldBox& lo, const WorldBox& hi, int passes)
{
  const WorldBox& n = lattice.World();
  for (std::size_t a = 0; a < 3; ++a)
    if (lo[a] < 0 || hi[a] > n[a] || lo[a] >= hi[a])
      throw Error("the region is not a non-empty box inside the world");
  RegionCone cone;
  cone.World = n;
  cone.Phases = lattice.Phases();
  cone.Whole = lattice.NumberOfBlocks() == 1;
  cone.WindowLow = lo;
  cone.WindowHigh = hi;
  const int total = lattice.Phases() * std::max(passes, 1);
  std::vector<std::vector<BoxBlock<3>>> phases(ToIndex(total));
  for (int q = total - 1; q >= 0; --q)
  {
    const int p = q % lattice.Phases();
    auto& blocks = phases[ToIndex(q)];
    lattice.Meeting(p, cone.WindowLow, cone.WindowHigh, blocks);
    // What these blocks read after phase p - 1: their footprints and the ring around them.
    for (const auto& b : blocks)
      for (std::size_t a = 0; a < 3; ++a)
      {
        cone.WindowLow[a] = std::min(cone.WindowLow[a], std::max<std::int64_t>(0, b.Origin[a] - 1));
        cone.WindowHigh[a] =
          std::max(cone.WindowHigh[a], std::min(n[a], b.Origin[a] + b.Dims[a] + 1));
      }
  }
  cone.Passes.resize(ToIndex(std::max(passes, 1)));
  for (int q = 0; q < total; ++q)
  {
    auto& pass = cone.Passes[ToIndex(q / lattice.Phases())];
    const auto& blocks = phases[ToIndex(q)];
    pass.insert(pass.end(), blocks.begin(), blocks.end());
  }
  cone.Blocks = cone.Passes[0];
  return cone;
}

} // namespace msynth
