// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/**
 * @file TimeVarying.h
 * @brief Time-varying models (dissertation §3.5.4): discrete model synthesis in four
 * dimensions, three of space and one of time. The example is a sequence of 3D label frames;
 * each site has spatial neighbours and temporal ones (the same place one frame earlier and
 * later), and the adjacency constraint (Eq. 3.3 extended by T_t) applies to both.
 *
 * The solver is Algorithms 3.1 and 3.4 on the shared propagation engine (Propagation.h) with
 * eight direction classes: the whole model at once, or overlapping 4D blocks from a trivial
 * start with rollback. With Loop, the last frame is followed by the first (a seam along t), so
 * the animation repeats without a jump.
 */
#include "Core/LabelGrid.h"
#include "Core/Propagation.h"
#include "Discrete/ConsistencyCheck.h"
#include "Discrete/DiscreteSynthesis.h"

#include <array>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace msynth
{

using Coord4 = std::array<std::int64_t, 4>;

/// A time-varying label model: equally sized 3D frames, one per time step.
struct TimeVaryingGrid
{
  std::vector<LabelGrid> Frames;
  /// nx, ny, nz, nt. @throw Error when there are no frames or their sizes differ.
  Coord4 Dimensions() const;
  /// The z slices of @p grid as frames (a 2D model over time stored as one volume).
  static TimeVaryingGrid FromSlices(const LabelGrid& grid);
};

/// The rules of a time-varying example: directions +x, -x, +y, -y, +z, -z, +t, -t.
class TimeVaryingRules : public CompatibilityRelation
{
public:
  static TimeVaryingRules FromExample(const TimeVaryingGrid& example);
  const std::vector<Label>& LabelValues() const { return this->Values; }
  const std::vector<double>& Weights() const { return this->LabelWeights; }
  int IndexOf(Label value) const;

private:
  std::vector<Label> Values;
  std::vector<double> LabelWeights;
};

struct TimeVaryingOptions
{
  Coord4 Size{ { 1, 1, 1, 1 } };      ///< nx, ny, nz, nt
  Coord4 BlockSize{ { 0, 0, 0, 0 } }; ///< 0 on an axis: the whole axis; all 0: Algorithm 3.1
  /// Overlap between consecutive blocks; -1 means half the block (the dissertation's choice).
  Coord4 Overlap{ { -1, -1, -1, -1 } };
  int AttemptsPerBlock = 10;
  std::uint64_t Seed = 0;
  LabelChoice Choice = LabelChoice::Uniform; ///< Uniform or Frequency
  SiteOrder Order = SiteOrder::ScanLine;     ///< ScanLine (x, y, z, then t) or Random
  bool Loop = false;                         ///< the last frame is followed by the first
  std::optional<Label> TrivialLabel;         ///< the trivial start; default: automatic
  std::function<bool(double)> Progress;      ///< fraction done; false cancels
};

struct TimeVaryingResult
{
  SynthesisStatus Status = SynthesisStatus::Failed;
  bool Succeeded() const { return this->Status == SynthesisStatus::Succeeded; }
  std::string Message;
  TimeVaryingGrid Model;
  SynthesisStatistics Statistics;
};

/// @throw Error on bad options (sizes, a resemblance choice, an unusable trivial start).
TimeVaryingResult SynthesizeTimeVarying(
  const TimeVaryingRules& rules, const TimeVaryingOptions& options);

/**
 * Checks every pair of neighbours of @p model, in space and in time (and from the last frame to
 * the first when @p loop), against the pairs recomputed from @p example's frames, without any
 * solver structure.
 */
ConsistencyReport CheckTimeVarying(
  const TimeVaryingGrid& example, const TimeVaryingGrid& model, bool loop = false);

} // namespace msynth
