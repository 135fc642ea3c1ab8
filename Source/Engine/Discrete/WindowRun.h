// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/**
 * @file WindowRun.h
 * @brief Internal: block synthesis of a window of a world (Core/WorldSchedule.h), for regions
 * (SynthesizeRegion) and for streamed runs (SynthesizeStreamed), which run the world's blocks a
 * window at a time and carry each window's labels and failed blocks into the next.
 */
#include "Core/WorldSchedule.h"
#include "Discrete/BlockSolver.h"
#include "Discrete/DiscreteSynthesis.h"

#include <functional>
#include <vector>

namespace msynth
{
namespace detail
{

/// What a run of a window of a world is given and gives back.
struct WindowRun
{
  /// The blocks to run (the world's keys and phases, world coordinates) and the window
  /// [WindowLow, WindowHigh) they read and write.
  const RegionCone* Cone = nullptr;
  /// Writes the labels (indices, -1 undecided) and last blocks an earlier window left on this
  /// window's sites over the start, before any block runs.
  std::function<void(SharedModel&)> Carry;
  /// Failed blocks carried in (earlier windows' failures a repair pass of this one may retry)
  /// and out (the failures after this window).
  std::vector<BlockFailure>* Failures = nullptr;
  /// When given, receives the window's labels (indices, -1 undecided) instead of the result's
  /// Model, and sites left undecided are not an error (a later window decides them).
  SharedModel* Keep = nullptr;
  /// The placement scales of pin groups the window was grown for (BlockSolver::PlacePins).
  const PinScales* Scales = nullptr;
};

/// Algorithm 3.4 (or 3.1 for one block as large as the output) on @p options' output, with a
/// mirror plan or symmetry seams when a part of a symmetric output is synthesized; with
/// @p run, the output is the window of a world and its blocks are the run's.
SynthesisResult SynthesizeDirect(const AdjacencyRules& rules, const SynthesisOptions& options,
  const MirrorPlan* plan, const SymmetryPlan* seams, const WindowRun* run = nullptr);

/// The window options for the cone @p cone of the world @p world: its size, the boundary labels
/// on the world's own faces only, and the world's block start.
SynthesisOptions WindowOptions(
  const AdjacencyRules& rules, const SynthesisOptions& world, const RegionCone& cone);

/// @throw Error when @p world's options need the whole world (symmetry, soft constraints, pins,
/// guide, a given start, snapshots, resemblance); @p what names the run ("a region").
void CheckWorldOptions(const SynthesisOptions& world, const char* what);

/// The estimate of the memory a run of @p o takes (model and catalogs), checked against the
/// machine. @throw Error naming the need when it does not fit.
void CheckSynthesisMemory(const AdjacencyRules& rules, const SynthesisOptions& o);

/**
 * The pins of @p world (Pins placed at PinsOrigin) over the box [@p low, @p high) of the world,
 * FreeSite where none: the pins a window of the world takes.
 * @throw Error when the placed pin grid does not lie inside the world.
 */
LabelGrid PinsOfBox(const SynthesisOptions& world, const Coord& low, const Coord& high);

/**
 * Grows @p cone's window until it holds, with the site ring around it, the placement block
 * (BlockSolver::PlacePins, at its scale in @p scales, else its first size) of every group of
 * touching pins of @p world whose block or ring meets the window: the window's placements then
 * read and write what they do in a whole run.
 */
void GrowWindowForPins(
  const SynthesisOptions& world, const Coord& m, RegionCone& cone, const PinScales& scales);

/// Passes after the first that repair failed blocks (SynthesisOptions::RepairFailedBlocks).
constexpr int RepairPasses = 3;

} // namespace detail
} // namespace msynth
