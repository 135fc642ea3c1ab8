// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/**
 * @file WorldSchedule.h
 * @brief A world as a function of its inputs: the block lattice of modify-in-blocks
 * (Algorithm 3.4, D§3.3.6) fixed to the world's origin, with its phases of non-touching blocks,
 * computed for any box of a world of up to 2^31 sites per axis without listing the world's
 * blocks; and the dependency cone of a region (the blocks computing it needs, phase by phase).
 *
 * A block reads only its footprint and the ring of sites around it, and writes only its
 * footprint; the blocks of a phase never touch; every draw of a block comes from (seed, block
 * key, attempt). So a block's result is a function of what earlier phases left on its footprint
 * and ring. Walking the phases backwards from a region R (phase p's blocks meeting the box S add
 * their footprints and rings to S) gives the blocks to run, forwards, for R's labels to equal
 * the same sites of a whole run: the cone. Its box (the window) is all such a run holds.
 */
#include "Core/BlockSynthesis.h"
#include "Core/Index.h"

#include <array>
#include <cstdint>
#include <vector>

namespace msynth
{

using WorldBox = std::array<std::int64_t, 3>;

/// The world's block lattice: blocks of M sites (clipped to the world), origins Step apart from
/// 0 along each axis until a block reaches the world's end; the same blocks, indices and
/// phases as PlanBoxBlocks<3>(World, M, Step, NonTouching).
class WorldLattice
{
public:
  WorldLattice(const WorldBox& world, const WorldBox& m, const WorldBox& step);

  int Phases() const { return this->NumberOfPhases; }
  /// Block origins along axis @p a.
  std::int64_t Count(int a) const { return this->Counts[ToIndex(a)]; }
  std::int64_t NumberOfBlocks() const
  {
    return this->Counts[0] * this->Counts[1] * this->Counts[2];
  }
  const WorldBox& World() const { return this->N; }
  /// Lattice positions apart along axis @p a that blocks of one phase are.
  std::int64_t Period(int a) const { return this->Periods[ToIndex(a)]; }
  /// Phase @p phase's digit along axis @p a: its blocks lie at the lattice positions g along
  /// the axis with g % Period(a) == digit (PhaseDigits::FewestOriginsFirst).
  std::int64_t Digit(int phase, int a) const
  {
    return (phase / this->Radix[ToIndex(a)]) % this->Periods[ToIndex(a)];
  }
  /// The block step along axis @p a.
  std::int64_t StepAlong(int a) const { return this->Step[ToIndex(a)]; }

  /// The block at lattice position @p g (its index: g0 + C0 · (g1 + C1 · g2)).
  BoxBlock<3> At(const WorldBox& g) const;

  /// Appends the blocks of phase @p phase meeting the box [@p lo, @p hi), in index order.
  void Meeting(
    int phase, const WorldBox& lo, const WorldBox& hi, std::vector<BoxBlock<3>>& out) const;

private:
  WorldBox N, M, Step, Counts, Periods, Radix;
  int NumberOfPhases = 1;
};

/// What computing a region takes: the blocks of its cone in run order (by phase, then index)
/// and the box [WindowLow, WindowHigh) they read and write. A run of several passes over the
/// lattice (the first pass, then passes that repair the blocks still failed) has the blocks each
/// pass may run in Passes; Blocks is the first.
struct RegionCone
{
  std::vector<BoxBlock<3>> Blocks;
  std::vector<std::vector<BoxBlock<3>>> Passes;
  WorldBox WindowLow{}, WindowHigh{};
  WorldBox World{};   ///< the world's size
  int Phases = 1;     ///< the world's phases
  bool Whole = false; ///< one block covers the world (Algorithm 3.1)
};

/// The cone of the region [@p lo, @p hi) of @p lattice's world (see the file comment) over
/// @p passes passes of the lattice's phases.
RegionCone PlanRegion(
  const WorldLattice& lattice, const WorldBox& lo, const WorldBox& hi, int passes = 1);

} // namespace msynth
