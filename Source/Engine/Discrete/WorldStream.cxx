// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file WorldStream.cxx
 * @brief Parts of a world (Core/WorldSchedule.h) declared in Discrete/DiscreteSynthesis.h: a
 * region computed from its dependency cone (SynthesizeRegion), and the whole world streamed
 * slab by slab as a wavefront of its blocks in bounded memory (SynthesizeStreamed).
 */
#include "Core/Error.h"
#include "Core/Index.h"
#include "Core/WorldSchedule.h"
#include "Discrete/Connectivity.h"
#include "Discrete/DiscreteSynthesis.h"
#include "Discrete/LabelCounts.h"
#include "Discrete/WindowRun.h"

#include <algorithm>
#include <chrono>

namespace msynth
{
using namespace detail;

void detail::CheckWorldOptions(const SynthesisOptions& world, const char* what)
{
  for (std::size_t a = 0; a < 3; ++a)
    if (world.Size[a] < 1 || world.Size[a] > (std::int64_t(1) << 31))
      throw Error(
        "a world has 1 to 2^31 sites along each axis, not " + std::to_string(world.Size[a]));
  const bool mirror =
    world.Symmetry[0].Enabled || world.Symmetry[1].Enabled || world.Symmetry[2].Enabled;
  const bool seams = world.Rotate.Enabled || world.Translate[0].Enabled ||
    world.Translate[1].Enabled || world.Translate[2].Enabled;
  if (mirror || seams || world.Soft.Active() || world.Guide || world.Start ||
    world.SnapshotsPerBlock > 0 || world.Choice == LabelChoice::Resemblance ||
    (world.Connected.Active() && (!world.Connected.Open || world.Connected.HasPath())))
    throw Error(std::string(what) +
      " takes no symmetry, soft constraints, guide, given start, snapshots, resemblance "
      "choice, or connected network but an open one, LABELS:open (each needs the whole world)");
}

SynthesisOptions detail::WindowOptions(
  const AdjacencyRules& rules, const SynthesisOptions& world, const RegionCone& cone)
{
  SynthesisOptions window = world;
  for (std::size_t a = 0; a < 3; ++a)
  {
    window.Size[a] = cone.WindowHigh[a] - cone.WindowLow[a];
    if ((window.Size[a] == 1) != (world.Size[a] == 1))
      throw Error("a region's window must keep the world's flat axes");
    if (cone.WindowLow[a] > 0) // boundary labels only on the world's own faces
      window.Boundary[2 * a].reset();
    if (cone.WindowHigh[a] < world.Size[a])
      window.Boundary[2 * a + 1].reset();
  }
  if (world.Pins) // the pins that fall in the window
  {
    window.Pins = PinsOfBox(world, cone.WindowLow, cone.WindowHigh);
    window.PinsOrigin.reset();
  }
  CheckSynthesisMemory(rules, window);
  return window;
}

namespace
{
/// The block lattice of @p world's options.
WorldLattice LatticeOf(const SynthesisOptions& world)
{
  Coord m, step;
  BlockGeometry<3>(world.Size, world.BlockSize, world.Overlap, m, step);
  return WorldLattice(world.Size, m, step);
}

int Passes(const SynthesisOptions& world)
{
  return world.RepairFailedBlocks ? 1 + RepairPasses : 1;
}
} // namespace

namespace
{
/// Fails @p r: the site @p p was left undecided.
void LeftUndecided(const Coord& p, SynthesisResult& r)
{
  r.Status = SynthesisStatus::Failed;
  r.Message = "block synthesis from an undecided start left site " + Format(p) +
    " undecided (every block over it failed). Try another seed, larger blocks, or the trivial "
    "start";
}

/// Runs @p cone's blocks in its window and crops the region [@p low, @p high); failed when a
/// site of the region is left undecided.
SynthesisResult RegionOfCone(const AdjacencyRules& rules, const SynthesisOptions& resolved,
  const RegionCone& planned, const WorldBox& low, const WorldBox& high)
{
  // With pins, the window first grows to hold the placements it meets; a placement that must
  // grow (its block could not be solved) grows the window again and the region runs again.
  Coord m, step;
  const bool placed = resolved.Pins &&
    !BlockGeometry<3>(resolved.Size, resolved.BlockSize, resolved.Overlap, m, step);
  PinScales scales;
  RegionCone cone;
  SharedModel keep;
  SynthesisResult r;
  SynthesisOptions window;
  for (bool again = true; again;)
  {
    again = false;
    cone = planned;
    if (placed)
      GrowWindowForPins(resolved, m, cone, scales);
    window = WindowOptions(rules, resolved, cone);
    WindowRun run;
    run.Cone = &cone;
    run.Scales = &scales;
    run.Keep = &keep;
    try
    {
      r = SynthesizeDirect(rules, window, nullptr, nullptr, &run);
    }
    catch (const PinScaleNeeded& need)
    {
      scales[need.Group] = need.Scale;
      again = true;
    }
  }
  if (!r.Succeeded())
    return r;
  const Coord& w = window.Size;
  std::vector<Label> labels;
  labels.reserve(ToIndex((high[0] - low[0]) * (high[1] - low[1]) * (high[2] - low[2])));
  std::vector<std::int32_t> last;
  last.reserve(labels.capacity());
  for (std::int64_t z = low[2]; z < high[2]; ++z)
    for (std::int64_t y = low[1]; y < high[1]; ++y)
      for (std::int64_t x = low[0]; x < high[0]; ++x)
      {
        const auto s = ToIndex((x - cone.WindowLow[0]) +
          w[0] * ((y - cone.WindowLow[1]) + w[1] * (z - cone.WindowLow[2])));
        if (keep.Model[s] < 0)
        {
          LeftUndecided({ { x, y, z } }, r);
          return r;
        }
        labels.push_back(rules.LabelValues()[ToIndex(keep.Model[s])]);
        last.push_back(keep.LastBlock[s]);
      }
  r.Model =
    LabelGrid({ { high[0] - low[0], high[1] - low[1], high[2] - low[2] } }, std::move(labels));
  r.LastBlock = std::move(last);
  r.Message += " (the region's cone of " + std::to_string(cone.Blocks.size()) +
    " blocks in a window of " + std::to_string(w[0]) + " x " + std::to_string(w[1]) + " x " +
    std::to_string(w[2]) + " sites)";
  return r;
}

/// Whether a block of @p failures (world keys of @p lattice) covers a site of [@p low, @p high).
bool FailedOver(const WorldLattice& lattice, const std::vector<BlockFailure>& failures,
  const WorldBox& low, const WorldBox& high)
{
  for (const BlockFailure& f : failures)
  {
    const std::int64_t c0 = lattice.Count(0), c1 = lattice.Count(1);
    const BoxBlock<3> b =
      lattice.At({ { f.Block % c0, (f.Block / c0) % c1, f.Block / (c0 * c1) } });
    bool meets = true;
    for (std::size_t a = 0; a < 3; ++a)
      meets = meets && b.Origin[a] < high[a] && b.Origin[a] + b.Dims[a] > low[a];
    if (meets)
      return true;
  }
  return false;
}
} // namespace

namespace
{
/// @p failures (read back from a file) with the world keys of the blocks at their origins.
std::vector<BlockFailure> Keyed(const WorldLattice& lattice, std::vector<BlockFailure> failures)
{
  for (BlockFailure& f : failures)
  {
    WorldBox g{};
    for (std::size_t a = 0; a < 3; ++a)
      g[a] = std::clamp<std::int64_t>(f.Origin[a] / lattice.StepAlong(static_cast<int>(a)), 0,
        lattice.Count(static_cast<int>(a)) - 1);
    f.Block = lattice.At(g).Index;
  }
  return failures;
}

/// The world's block start; a whole-model one is refused: no region is a function of it alone.
BlockStart WorldStart(const AdjacencyRules& rules, const SynthesisOptions& world)
{
  const BlockStart start = ChooseBlockStart(rules, world);
  if (start == BlockStart::WholeModel)
    throw Error("the blocks of this world start from a whole-model solution (their trivial start "
                "leaves them blank and an undecided start cannot close them), which a region or a "
                "stream cannot compute: choose the trivial or the undecided start");
  return start;
}
} // namespace

SynthesisResult SynthesizeRegion(const AdjacencyRules& rules, const SynthesisOptions& given,
  const std::array<std::int64_t, 3>& low, const std::array<std::int64_t, 3>& high)
{
  const SynthesisOptions world = UndecidedWorld(given);
  CheckWorldOptions(world, "a region of a world");
  CheckAxesWithoutPairs(rules, world);
  CheckCountRequest(rules, world); // shares by position (LabelCounts.h): as in the whole run
  CheckConnectedRequest(rules, world);
  const WorldLattice lattice = LatticeOf(world);
  SynthesisOptions resolved = world;
  resolved.StartFrom = WorldStart(rules, world); // the world's, wherever the region lies
  if (world.RepairFailedBlocks)
  {
    // The repair passes run failed blocks only, so they change the region only when a block over
    // it failed: first the narrower cone of the first pass alone.
    SynthesisOptions once = resolved;
    once.RepairFailedBlocks = false;
    SynthesisResult r = RegionOfCone(rules, once, PlanRegion(lattice, low, high, 1), low, high);
    if (r.Status == SynthesisStatus::Cancelled ||
      (r.Succeeded() && !FailedOver(lattice, r.Statistics.Failures, low, high)))
    {
      if (r.Succeeded())
        r.Message += "; no block over the region failed, so no repair pass was needed";
      return r;
    }
  }
  return RegionOfCone(rules, resolved, PlanRegion(lattice, low, high, Passes(world)), low, high);
}

namespace
{
/**
 * The world's schedule as a wavefront along one axis: block b of global phase t (pass t / P,
 * phase t % P) at lattice row g runs in step g + Delay[t]; a window runs a run of steps, its
 * blocks by global phase. Of two blocks that touch, the one of the earlier phase t1 must not
 * run in a later window than the other (t2): it lies at most Need(t1, t2) rows further along,
 * and Delay[t2] - Delay[t1] >= Need(t1, t2). So every block sees what it sees in a whole run.
 */
struct Wavefront
{
  Wavefront(const WorldLattice& lattice, int axis, int passes)
    : Lattice(lattice)
    , Axis(axis)
    , P(lattice.Phases())
    , T(lattice.Phases() * passes)
    , Rows(lattice.Count(axis))
  {
    // Delay: the longest path through Need, in phase order.
    this->Delay.assign(ToIndex(this->T), 0);
    for (int t2 = 1; t2 < this->T; ++t2)
    {
      auto& d = this->Delay[ToIndex(t2)];
      d = this->Delay[ToIndex(t2 - 1)];
      for (int t1 = 0; t1 < t2; ++t1)
        d = std::max(d, this->Delay[ToIndex(t1)] + this->Need(t1, t2));
    }
  }

  /// Phase @p t's digit along the axis: its blocks lie in the rows g with g % Period == digit.
  std::int64_t Digit(int t) const { return this->Lattice.Digit(t % this->P, this->Axis); }

  /// How many rows further along a block of phase @p t1 may lie than one of phase @p t2 it
  /// touches (blocks touch when fewer than Period rows apart).
  std::int64_t Need(int t1, int t2) const
  {
    const std::int64_t period = this->Lattice.Period(this->Axis);
    const std::int64_t d = ((this->Digit(t1) - this->Digit(t2)) % period + period) % period;
    return d; // 0 .. period - 1, each a distance at which such blocks touch
  }

  /// Restricts the run to the cone of the slab from @p low to the world's end along the axis
  /// (Core/WorldSchedule.h's walk, along one axis): MinRow[t], the first row phase t runs.
  void From(std::int64_t low)
  {
    const auto a = ToIndex(this->Axis);
    const std::int64_t period = this->Lattice.Period(this->Axis);
    this->MinRow.assign(ToIndex(this->T), this->Rows);
    for (int t = this->T - 1; t >= 0; --t)
    {
      const std::int64_t digit = this->Digit(t);
      for (std::int64_t g = digit; g < this->Rows; g += period)
      {
        const WorldBox probe{ { 0, 0, 0 } };
        WorldBox at = probe;
        at[a] = g;
        const BoxBlock<3> b = this->Lattice.At(at);
        if (b.Origin[a] + b.Dims[a] > low)
        {
          this->MinRow[ToIndex(t)] = g;
          low = std::min(low, std::max<std::int64_t>(0, b.Origin[a] - 1));
          break;
        }
      }
    }
    this->FirstStep = this->LastStep();
    for (int t = 0; t < this->T; ++t)
      if (this->MinRow[ToIndex(t)] < this->Rows)
        this->FirstStep =
          std::min(this->FirstStep, this->MinRow[ToIndex(t)] + this->Delay[ToIndex(t)]);
  }

  std::int64_t LastStep() const { return this->Rows - 1 + this->Delay.back(); }

  /// Appends the blocks of step @p s and global phase @p t.
  void Blocks(std::int64_t s, int t, std::vector<BoxBlock<3>>& out) const
  {
    const std::int64_t g = s - this->Delay[ToIndex(t)];
    if (g < this->MinRow[ToIndex(t)] || g >= this->Rows)
      return;
    const int o1 = this->Axis == 0 ? 1 : 0, o2 = this->Axis == 2 ? 1 : 2;
    WorldBox at{};
    at[ToIndex(this->Axis)] = g;
    for (at[ToIndex(o2)] = 0; at[ToIndex(o2)] < this->Lattice.Count(o2); ++at[ToIndex(o2)])
      for (at[ToIndex(o1)] = 0; at[ToIndex(o1)] < this->Lattice.Count(o1); ++at[ToIndex(o1)])
      {
        const BoxBlock<3> b = this->Lattice.At(at);
        if (b.Phase == t % this->P)
          out.push_back(b);
      }
  }

  /// Rows [0, Final(s)) along the axis are final once the steps before @p s have run.
  std::int64_t Final(std::int64_t s) const
  {
    const std::int64_t n = this->Lattice.World()[ToIndex(this->Axis)];
    if (s > this->LastStep())
      return n;
    const std::int64_t g = s - this->Delay.back();
    return g <= 0 ? 0 : std::min(n, g * this->Lattice.StepAlong(this->Axis) - 1);
  }

  const WorldLattice& Lattice;
  int Axis, P, T;
  std::int64_t Rows;
  std::vector<std::int64_t> Delay;
  std::vector<std::int64_t> MinRow;
  std::int64_t FirstStep = 0;
};

/// Labels (indices) and last blocks of the slab [Low, High) of a world along the stream's axis.
struct Slab
{
  std::int64_t Low = 0, High = 0;
  std::vector<std::int32_t> Model, LastBlock;
};

/// The stream's state between windows.
class Stream
{
public:
  Stream(const AdjacencyRules& rules, const SynthesisOptions& world, const StreamLayout& layout,
    const std::function<bool(StreamChunk&&)>& onChunk)
    : Rules(rules)
    , World(world)
    , Layout(layout)
    , OnChunk(onChunk)
    , Axis(ToIndex(layout.Axis))
  {
  }

  /// Runs the blocks @p passes (world coordinates) in a window that also holds every site not
  /// yet handed out; false when cancelled or failed (@p r says which).
  bool RunWindow(std::vector<std::vector<BoxBlock<3>>>& passes, SynthesisResult& r);
  /// Hands out every slab below @p final and keeps what later windows read; false when a slab
  /// holds undecided sites (@p r failed) or the receiver cancels.
  bool Emit(std::int64_t final, SynthesisResult& r);

  /// Adds the counted labels of @p c's own layers (not the one it shares) to Counts.
  void Tally(const StreamChunk& c);

  int NextChunk = 0;
  std::vector<LabelCountResult> Counts; ///< the world's counts, slab by slab
  std::vector<BlockFailure> Failures; ///< of the blocks run, still failed (a later pass may repair)
  std::vector<BlockFailure> Handed;   ///< the failures handed out with the slabs (final)
  SynthesisStatistics Totals;
  std::function<bool(double)> Progress;
  int Phases = 1;

private:
  /// Sites per row before the stream's axis (x-fastest order), and rows of those after it.
  std::int64_t Inner() const;
  std::int64_t Outer() const;
  void Add(const SynthesisStatistics& s);
  /// The world's block size (the placement blocks' first size).
  Coord BlockEdge() const
  {
    Coord m, step;
    BlockGeometry<3>(this->World.Size, this->World.BlockSize, this->World.Overlap, m, step);
    return m;
  }

  const AdjacencyRules& Rules;
  const SynthesisOptions& World;
  const StreamLayout& Layout;
  const std::function<bool(StreamChunk&&)>& OnChunk;
  std::size_t Axis;
  Slab Held;        ///< what the last window left that is still needed or not yet handed out
  PinScales Scales; ///< the placement scales of pin groups that had to grow (RegionOfCone's)
  bool First = true;
};

/// Copies rows [@p a, @p b) along the stream's axis from a slab starting at @p srcLow,
/// @p srcRows thick, to one starting at @p dstLow, @p dstRows thick (@p inner sites per row
/// before the axis, @p outer after it, as in x-fastest order).
template <class T>
void CopyRows(const std::vector<T>& src, std::int64_t srcLow, std::int64_t srcRows,
  std::vector<T>& dst, std::int64_t dstLow, std::int64_t dstRows, std::int64_t a, std::int64_t b,
  std::int64_t inner, std::int64_t outer)
{
  if (b <= a)
    return;
  const auto count = inner * (b - a);
  for (std::int64_t o = 0; o < outer; ++o)
  {
    const auto from = src.begin() + inner * ((a - srcLow) + srcRows * o);
    std::copy(from, from + count, dst.begin() + inner * ((a - dstLow) + dstRows * o));
  }
}

void Stream::Add(const SynthesisStatistics& s)
{
  SynthesisStatistics& t = this->Totals;
  t.Blocks += s.Blocks;
  t.BlocksAccepted += s.BlocksAccepted;
  t.BlocksFailed += s.BlocksFailed;
  t.BlocksRejected += s.BlocksRejected;
  t.BlocksRepaired += s.BlocksRepaired;
  t.Attempts += s.Attempts;
  t.Assignments += s.Assignments;
  t.Backtracks += s.Backtracks;
  t.Threads = std::max(t.Threads, s.Threads);
  t.Processes = std::max(t.Processes, s.Processes);
  if (this->First)
  {
    t.TrivialLabel = s.TrivialLabel;
    t.StartFrom = s.StartFrom;
  }
}

void Stream::Tally(const StreamChunk& c)
{
  if (this->World.Counts.empty())
    return; // nothing counted: no pass over the slab
  if (this->Counts.empty())
    for (const LabelCount& want : this->World.Counts)
      this->Counts.push_back({ want, 0 });
  const Coord& d = c.Model.Dimensions();
  const std::vector<Label>& data = c.Model.Data();
  for (std::size_t s = 0; s < data.size(); ++s)
  {
    const auto i = static_cast<std::int64_t>(s);
    const std::int64_t along[3] = { i % d[0], (i / d[0]) % d[1], i / (d[0] * d[1]) };
    if (along[this->Axis] < c.Shared)
      continue;
    for (LabelCountResult& r : this->Counts)
      if (std::find(r.Requested.Values.begin(), r.Requested.Values.end(), data[s]) !=
        r.Requested.Values.end())
        ++r.Achieved;
  }
}

std::int64_t Stream::Inner() const
{
  std::int64_t inner = 1;
  for (std::size_t k = 0; k < this->Axis; ++k)
    inner *= this->World.Size[k];
  return inner;
}

std::int64_t Stream::Outer() const
{
  std::int64_t outer = 1;
  for (std::size_t k = this->Axis + 1; k < 3; ++k)
    outer *= this->World.Size[k];
  return outer;
}

bool Stream::RunWindow(std::vector<std::vector<BoxBlock<3>>>& passes, SynthesisResult& r)
{
  const std::size_t a = this->Axis;
  const std::int64_t n = this->World.Size[a];
  WorldBox chunkLow, chunkHigh;
  this->Layout.Box(this->NextChunk, chunkLow, chunkHigh);
  std::int64_t low =
    this->NextChunk < this->Layout.Chunks ? std::max<std::int64_t>(0, chunkLow[a] - 1) : n;
  std::int64_t high = this->Held.High;
  for (auto& pass : passes)
  {
    for (const auto& b : pass)
    {
      low = std::min(low, std::max<std::int64_t>(0, b.Origin[a] - 1));
      high = std::max(high, std::min(n, b.Origin[a] + b.Dims[a] + 1));
    }
    std::sort(pass.begin(), pass.end(),
      [](const BoxBlock<3>& x, const BoxBlock<3>& y)
      { return x.Phase != y.Phase ? x.Phase < y.Phase : x.Index < y.Index; });
  }
  RegionCone cone;
  cone.World = this->World.Size;
  cone.Phases = this->Phases;
  cone.WindowHigh = this->World.Size;
  cone.WindowLow[a] = low;
  cone.WindowHigh[a] = high;
  cone.Passes = passes;
  cone.Blocks = passes.front();
  const Slab& held = this->Held;
  const std::int64_t inner = this->Inner(), outer = this->Outer();
  SharedModel keep;
  std::int64_t from = low, to = high; // the window's rows, grown for pin placements
  for (bool again = true; again;)
  {
    again = false;
    RegionCone grown = cone;
    if (this->World.Pins) // as a region's (RegionOfCone): the placements the window meets
      GrowWindowForPins(this->World, this->BlockEdge(), grown, this->Scales);
    from = grown.WindowLow[a];
    to = grown.WindowHigh[a];
    SynthesisOptions window = WindowOptions(this->Rules, this->World, grown);
    window.Progress = this->Progress;
    WindowRun run;
    run.Cone = &grown;
    run.Failures = &this->Failures;
    run.Keep = &keep;
    run.Scales = &this->Scales;
    run.Carry = [&](SharedModel& m)
    {
      const std::int64_t c0 = std::max(from, held.Low), c1 = std::min(to, held.High);
      CopyRows(
        held.Model, held.Low, held.High - held.Low, m.Model, from, to - from, c0, c1, inner, outer);
      CopyRows(held.LastBlock, held.Low, held.High - held.Low, m.LastBlock, from, to - from, c0, c1,
        inner, outer);
    };
    try
    {
      r = SynthesizeDirect(this->Rules, window, nullptr, nullptr, &run);
    }
    catch (const PinScaleNeeded& need) // thrown before any block ran: grow and run again
    {
      this->Scales[need.Group] = need.Scale;
      again = true;
    }
  }
  this->Add(r.Statistics);
  this->First = false;
  if (!r.Succeeded())
    return false;
  // Keep the window's own rows: rows a placement grew it by hold no block's labels yet.
  Slab next;
  next.Low = low;
  next.High = high;
  next.Model.resize(ToIndex(inner * outer * (high - low)));
  next.LastBlock.resize(next.Model.size());
  CopyRows(keep.Model, from, to - from, next.Model, low, high - low, low, high, inner, outer);
  CopyRows(
    keep.LastBlock, from, to - from, next.LastBlock, low, high - low, low, high, inner, outer);
  this->Held = std::move(next);
  return true;
}

bool Stream::Emit(std::int64_t final, SynthesisResult& r)
{
  const std::size_t a = this->Axis;
  const std::int64_t inner = this->Inner(), outer = this->Outer();
  Slab& held = this->Held;
  const auto& values = this->Rules.LabelValues();
  while (this->NextChunk < this->Layout.Chunks)
  {
    StreamChunk c;
    c.Index = this->NextChunk;
    this->Layout.Box(c.Index, c.Low, c.High);
    c.Shared = c.Low[a] > 0 ? 1 : 0; // the previous slab's last layer, as VTK's pieces share
    c.Low[a] -= c.Shared;
    if (c.High[a] > final || c.High[a] > held.High || c.Low[a] < held.Low)
      break;
    const std::int64_t rows = c.High[a] - c.Low[a];
    std::vector<std::int32_t> model(ToIndex(inner * outer * rows));
    c.LastBlock.resize(model.size());
    CopyRows(held.Model, held.Low, held.High - held.Low, model, c.Low[a], rows, c.Low[a], c.High[a],
      inner, outer);
    CopyRows(held.LastBlock, held.Low, held.High - held.Low, c.LastBlock, c.Low[a], rows, c.Low[a],
      c.High[a], inner, outer);
    const Coord dims{ { c.High[0] - c.Low[0], c.High[1] - c.Low[1], c.High[2] - c.Low[2] } };
    std::vector<Label> labels(model.size());
    for (std::size_t s = 0; s < model.size(); ++s)
    {
      if (model[s] < 0)
      {
        const auto i = static_cast<std::int64_t>(s);
        const Coord p{ { c.Low[0] + i % dims[0], c.Low[1] + (i / dims[0]) % dims[1],
          c.Low[2] + i / (dims[0] * dims[1]) } };
        LeftUndecided(p, r);
        return false;
      }
      labels[s] = values[ToIndex(model[s])];
    }
    c.Model = LabelGrid(dims, std::move(labels));
    for (const BlockFailure& f : this->Failures) // final: every block over the slab has run
      if (f.Origin[a] >= c.Low[a] + c.Shared && f.Origin[a] < c.High[a])
        c.Failures.push_back(f);
    this->Handed.insert(this->Handed.end(), c.Failures.begin(), c.Failures.end());
    this->Tally(c);
    ++this->NextChunk;
    if (!this->OnChunk(std::move(c)))
    {
      r.Status = SynthesisStatus::Cancelled;
      r.Message = "cancelled";
      return false;
    }
  }
  // Keep only what a later window reads or a later slab holds.
  WorldBox low, high;
  this->Layout.Box(std::min(this->NextChunk, this->Layout.Chunks - 1), low, high);
  const std::int64_t keep = std::min(final,
    this->NextChunk < this->Layout.Chunks ? std::max<std::int64_t>(0, low[a] - 1)
                                          : this->World.Size[a]);
  if (keep > held.Low && !held.Model.empty())
  {
    Slab rest;
    rest.Low = std::min(keep, held.High);
    rest.High = held.High;
    rest.Model.resize(ToIndex(inner * outer * (rest.High - rest.Low)));
    rest.LastBlock.resize(rest.Model.size());
    CopyRows(held.Model, held.Low, held.High - held.Low, rest.Model, rest.Low, rest.High - rest.Low,
      rest.Low, rest.High, inner, outer);
    CopyRows(held.LastBlock, held.Low, held.High - held.Low, rest.LastBlock, rest.Low,
      rest.High - rest.Low, rest.Low, rest.High, inner, outer);
    held = std::move(rest);
  }
  return true;
}
} // namespace

SynthesisResult SynthesizeStreamed(const AdjacencyRules& rules, const SynthesisOptions& world,
  const StreamLayout& layout, const std::function<bool(StreamChunk&&)>& onChunk, int firstChunk,
  const std::vector<BlockFailure>& kept)
{
  const auto start = std::chrono::steady_clock::now();
  CheckWorldOptions(world, "a streamed world");
  CheckAxesWithoutPairs(rules, world);
  CheckCountRequest(rules, world);
  CheckConnectedRequest(rules, world);
  if (firstChunk < 0 || firstChunk > layout.Chunks || layout.World != world.Size)
    throw Error("a streamed run resumes at one of its own slabs");
  const WorldLattice lattice = LatticeOf(world);
  if (lattice.NumberOfBlocks() == 1)
    throw Error("a streamed world is computed in blocks: give blocks smaller than the world");
  const std::vector<BlockFailure> earlier = Keyed(lattice, kept);
  if (firstChunk == layout.Chunks) // interrupted after its last slab: nothing is left to compute
  {
    SynthesisResult done;
    done.Status = SynthesisStatus::Succeeded;
    done.Statistics.Failures = earlier;
    done.Statistics.BlocksFailed = static_cast<std::int64_t>(earlier.size());
    done.Message = "streamed in " + std::to_string(layout.Chunks) + " slabs along " +
      "xyz"[layout.Axis] + ", all kept from the earlier run";
    return done;
  }
  SynthesisOptions resolved = world;
  resolved.StartFrom = WorldStart(rules, world); // the world's, as every region's
  Wavefront wave(lattice, layout.Axis, Passes(world));
  WorldBox low, high;
  layout.Box(firstChunk, low, high);
  wave.From(low[ToIndex(layout.Axis)]);
  Stream stream(rules, resolved, layout, onChunk);
  stream.NextChunk = firstChunk;
  stream.Phases = lattice.Phases();
  const std::int64_t step = lattice.StepAlong(layout.Axis);
  // Each window advances by a slab, or when slabs are thinner by up to four slabs and about
  // 2^21 sites (a window's start and carry cost about its size, whatever it computes).
  const std::int64_t advance = std::max(
    layout.Thickness, std::min(4 * layout.Thickness, layout.LayersOf(std::int64_t(1) << 21)));
  const std::int64_t g = std::max<std::int64_t>(1, (advance + step - 1) / step);
  const double total = static_cast<double>(wave.LastStep() - wave.FirstStep + 1);
  SynthesisResult r;
  r.Status = SynthesisStatus::Succeeded;
  for (std::int64_t s0 = wave.FirstStep; s0 <= wave.LastStep(); s0 += g)
  {
    const std::int64_t s1 = std::min(s0 + g, wave.LastStep() + 1);
    std::vector<std::vector<BoxBlock<3>>> passes(ToIndex(Passes(world)));
    bool any = false;
    for (std::int64_t s = s0; s < s1; ++s)
      for (int t = 0; t < wave.T; ++t)
      {
        auto& pass = passes[ToIndex(t / wave.P)];
        wave.Blocks(s, t, pass);
        any = any || !pass.empty();
      }
    stream.Progress = nullptr;
    if (world.Progress)
      stream.Progress = [&world, s0, s1, total, first = wave.FirstStep](double f)
      {
        return world.Progress(
          (static_cast<double>(s0 - first) + f * static_cast<double>(s1 - s0)) / total);
      };
    if ((any && !stream.RunWindow(passes, r)) || !stream.Emit(wave.Final(s1), r))
      break;
  }
  const SynthesisStatus status = r.Status;
  const std::string message = r.Message;
  r = SynthesisResult();
  r.Status = status;
  r.Statistics = stream.Totals;
  r.Statistics.Failures = stream.Failures;
  if (status == SynthesisStatus::Succeeded)
  {
    // The world's failures: a resumed run also ran first passes of blocks below its first slab
    // whose repairs it did not need; their outcome is the earlier run's, handed out with its
    // slabs (kept).
    r.Statistics.Failures = earlier;
    r.Statistics.Failures.insert(
      r.Statistics.Failures.end(), stream.Handed.begin(), stream.Handed.end());
    r.Statistics.BlocksFailed = static_cast<std::int64_t>(r.Statistics.Failures.size());
  }
  r.Statistics.Phases = lattice.Phases();
  r.Statistics.Seconds =
    std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (firstChunk == 0) // a resumed stream did not see the slabs it kept
    r.Counts = stream.Counts;
  const std::string miss =
    status == SynthesisStatus::Succeeded ? CountMiss(r.Counts) : std::string();
  if (!miss.empty()) // cannot be, when every block kept its share: say so if it happens
  {
    r.Status = SynthesisStatus::Failed;
    r.Message = "the label counts were not kept: " + miss;
    return r;
  }
  r.Message = status == SynthesisStatus::Succeeded ? Summary(r.Statistics, false) +
      " (streamed in " + std::to_string(layout.Chunks) + " slabs along " + "xyz"[layout.Axis] +
      (firstChunk == 0 ? std::string()
                       : ": " + std::to_string(firstChunk) + " kept from the earlier run, " +
            std::to_string(layout.Chunks - firstChunk) + " computed now") +
      ")"
                                                   : message;
  return r;
}

void StreamLayout::Box(
  int j, std::array<std::int64_t, 3>& low, std::array<std::int64_t, 3>& high) const
{
  low = { { 0, 0, 0 } };
  high = this->World;
  const auto a = ToIndex(this->Axis);
  low[a] = static_cast<std::int64_t>(j) * this->Thickness;
  high[a] = std::min(this->World[a], low[a] + this->Thickness);
}

StreamLayout PlanStream(const SynthesisOptions& world, std::int64_t thickness)
{
  CheckWorldOptions(world, "a streamed world");
  const WorldLattice lattice = LatticeOf(world);
  if (lattice.NumberOfBlocks() == 1)
    throw Error("a streamed world is computed in blocks: give blocks smaller than the world");
  StreamLayout layout;
  layout.World = world.Size;
  for (int a = 0; a < 3; ++a)
    if (lattice.Count(a) >= lattice.Count(layout.Axis) && lattice.Count(a) > 1)
      layout.Axis = a;
  if (lattice.Count(layout.Axis) == 1)
    layout.Axis = 0;
  const auto a = ToIndex(layout.Axis);
  if (thickness < 0)
    throw Error("a stream's slabs must be at least one site thick");
  layout.Thickness = thickness > 0
    ? thickness
    : std::max(lattice.StepAlong(layout.Axis), layout.LayersOf(std::int64_t(1) << 21));
  layout.Thickness = std::min(layout.Thickness, world.Size[a]);
  const std::int64_t chunks = (world.Size[a] + layout.Thickness - 1) / layout.Thickness;
  if (chunks > 1000000)
    throw Error("a stream of " + std::to_string(chunks) + " slabs is too many: make them thicker");
  layout.Chunks = static_cast<int>(chunks);
  return layout;
}

} // namespace msynth
