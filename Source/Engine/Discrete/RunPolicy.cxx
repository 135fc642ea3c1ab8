// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file RunPolicy.cxx
 * @brief The choices the engine makes for a run, declared in Discrete/DiscreteSynthesis.h: the
 * automatic block start (ChooseBlockStart: a probe world from the trivial start, and from an
 * undecided start, then a whole-model start, where the first looks blank), the snapshots' memory
 * (SnapshotBytes) and the fingerprint processes compare before they exchange blocks
 * (RunFingerprint).
 */
#include "Core/BlockDriver.h"
#include "Core/BlockSynthesis.h"
#include "Core/Error.h"
#include "Core/Index.h"
#include "Discrete/DiscreteSynthesis.h"
#include "Discrete/MirrorPlan.h"
#include "Discrete/SymmetryPlan.h"

#include <algorithm>
#include <map>
#include <numeric>
#include <sstream>

namespace msynth
{
namespace
{
using Coord = std::array<std::int64_t, 3>;

/// The distinct labels of @p model in the box [@p low, @p high) and the share of its most
/// frequent one.
std::pair<std::size_t, double> Variety(const LabelGrid& model, const Coord& low, const Coord& high)
{
  std::map<Label, std::int64_t> counts;
  std::int64_t sites = 0;
  for (std::int64_t z = low[2]; z < high[2]; ++z)
    for (std::int64_t y = low[1]; y < high[1]; ++y)
      for (std::int64_t x = low[0]; x < high[0]; ++x, ++sites)
        ++counts[model.At(x, y, z)];
  std::int64_t most = 0;
  for (const auto& c : counts)
    most = std::max(most, c.second);
  return { counts.size(),
    sites > 0 ? static_cast<double>(most) / static_cast<double>(sites) : 1.0 };
}

std::pair<std::size_t, double> Variety(const LabelGrid& model)
{
  return Variety(model, { { 0, 0, 0 } }, model.Dimensions());
}

/// More than 1.25 times the distinct labels of @p than, or a most frequent label's share under
/// 0.8 times its.
bool MoreVaried(const std::pair<std::size_t, double>& v, const std::pair<std::size_t, double>& than)
{
  return static_cast<double>(v.first) > 1.25 * static_cast<double>(than.first) ||
    v.second < 0.8 * than.second;
}

/// Whether a block run over the whole output from the trivial start left it blank (the
/// criterion of a world that is its own probe): its trivial label covers over 90 % of the
/// sites, or over 1.25 times its share of the example (by the labels' weights).
bool LooksBlankByWeight(const AdjacencyRules& rules, const SynthesisResult& trivial)
{
  if (!trivial.Statistics.TrivialLabel)
    return false;
  const Label t = *trivial.Statistics.TrivialLabel;
  const auto& data = trivial.Model.Data();
  const double share =
    static_cast<double>(std::count(data.begin(), data.end(), t)) / static_cast<double>(data.size());
  const auto& weights = rules.Weights();
  const double total = std::accumulate(weights.begin(), weights.end(), 0.0);
  const int b = rules.IndexOf(t);
  const double example = b >= 0 && total > 0.0 ? weights[ToIndex(b)] / total : 1.0;
  return share > 0.9 || share > 1.25 * example;
}

/// Whether a probe is blank: one label on over 90 % of its sites and fewer than half of the
/// rules' labels. (Not against the labels' weights: a tileset without weights gives its ground
/// tile 1/29 of them, a castle of air is 85 % air in a whole run and 63 % in its example.)
bool LooksBlank(const AdjacencyRules& rules, const std::pair<std::size_t, double>& v)
{
  return v.second > 0.9 && 2 * v.first < ToIndex(rules.NumberOfLabels());
}

/// A probe of its own: no messages to other processes, no counts or network (the whole
/// output's), no snapshots, the first 1 % of progress.
SynthesisOptions ProbeOptions(const SynthesisOptions& options)
{
  SynthesisOptions probe = options;
  probe.Exchange = BlockExchange();
  probe.Counts.clear();
  probe.Connected = ConnectedNetwork();
  probe.OnSnapshot = nullptr;
  probe.SnapshotsPerBlock = 0;
  probe.Progress = nullptr;
  if (options.Progress)
    probe.Progress = [&options](double f) { return options.Progress(std::max(1e-6, 0.01 * f)); };
  return probe;
}

/**
 * The trivial start's probe of a large world: one block of the run ringed by the trivial label
 * (a world of the block and one site on each side along the axes the blocks divide, those
 * faces fixed to the label), synthesized whole: what every block inside the world meets, for the
 * cost of one block. A block that cannot be synthesized keeps the trivial label: blank.
 */
std::pair<std::size_t, double> RingedBlockVariety(const AdjacencyRules& rules,
  const SynthesisOptions& options, const Coord& m, int trivial, SynthesisStatus& status)
{
  SynthesisOptions ring = ProbeOptions(options);
  ring.BlockSize = { { 0, 0, 0 } };
  ring.BlocksWhenWholeFails = false;
  ring.StartFrom = BlockStart::Trivial;
  for (Translation& t : ring.Translate) // a block inside the world, away from the seams
    t = Translation();
  Coord low{ { 0, 0, 0 } }, high = options.Size;
  for (std::size_t a = 0; a < 3; ++a)
    if (m[a] < options.Size[a])
    {
      ring.Size[a] = m[a] + 2;
      ring.Boundary[2 * a] = ring.Boundary[2 * a + 1] = rules.LabelValues()[ToIndex(trivial)];
      low[a] = 1;
      high[a] = m[a] + 1;
    }
  const SynthesisResult r = Synthesize(rules, ring);
  status = r.Status;
  if (!r.Succeeded()) // no evidence either way (too few attempts): Algorithm 3.4's start
    return { ToIndex(rules.NumberOfLabels()), 0.0 };
  return Variety(r.Model, low, high);
}

/// The label of the trivial start of a world without guide or pins (TrivialStart), or -1 when
/// it would be layered.
int TrivialLabelOf(const AdjacencyRules& rules, const SynthesisOptions& options)
{
  if (options.TrivialLabel)
    return rules.IndexOf(*options.TrivialLabel);
  return ChooseTrivialLabel(rules.NumberOfLabels(), rules.IndexOf(0),
    [&](int b) { return rules.SelfAdjacent(b, options.Size); });
}
/**
 * ChooseBlockStart once the trivial start looks blank: the undecided start when it decides
 * every site of @p probe with no failed block and more variety than @p t (not with translation:
 * the blocks along the seam meet decided sites on both sides); else a whole-model solution that
 * the blocks modify, so as varied as a whole run (the run falls back to the trivial start where
 * its whole run fails). Only a small world, its own probe (@p first), tries the whole-model start
 * first and keeps the trivial one unless that is less blank: elsewhere it would cost a whole run.
 */
template <typename Keep>
BlockStart ChooseAfterBlank(const AdjacencyRules& rules, SynthesisOptions& probe,
  const std::pair<std::size_t, double>& t, bool translated, std::optional<SynthesisResult>& first,
  const Keep& keep)
{
  if (!translated)
  {
    probe.StartFrom = BlockStart::Undecided;
    SynthesisResult other = Synthesize(rules, probe);
    if (other.Status == SynthesisStatus::Cancelled ||
      (other.Succeeded() && other.Statistics.BlocksFailed == 0 &&
        MoreVaried(Variety(other.Model), t)))
      return keep(std::move(other), BlockStart::Undecided);
  }
  if (!first)
    return BlockStart::WholeModel;
  probe.StartFrom = BlockStart::WholeModel;
  SynthesisResult whole = Synthesize(rules, probe);
  if (whole.Status == SynthesisStatus::Cancelled ||
    (whole.Succeeded() && whole.Statistics.BlocksFailed == 0 &&
      Variety(whole.Model).second < t.second))
    return keep(std::move(whole), BlockStart::WholeModel);
  return keep(std::move(*first), BlockStart::Trivial);
}
} // namespace

BlockStart ChooseBlockStart(const AdjacencyRules& rules, const SynthesisOptions& options,
  std::optional<SynthesisResult>* done)
{
  if (options.StartFrom != BlockStart::Automatic)
    return options.StartFrom;
  std::array<std::int64_t, 3> m, step;
  if (BlockGeometry<3>(options.Size, options.BlockSize, options.Overlap, m, step) ||
    options.Start || options.Soft.Active() || detail::AnyMirror(options) ||
    options.Rotate.Enabled || options.SnapshotsPerBlock > 0)
    return BlockStart::Trivial;
  // With translation the blocks along the seam meet decided sites on both sides, which an
  // undecided start cannot close (WaveFunctionCollapse's City): no undecided probe there.
  const bool translated = detail::AnySeamSymmetry(options);
  // A small world (up to 4 block steps past one block per axis) is its own probe, kept as the
  // result when its start is chosen; a larger one is probed by one block ringed by the trivial
  // label, then by a world of 2 blocks per axis from the undecided start.
  bool small = true;
  for (std::size_t a = 0; a < 3; ++a)
    small &= options.Size[a] <= m[a] + 4 * step[a];
  const int trivial = small ? -1 : TrivialLabelOf(rules, options);
  if (!small && (options.Pins || options.Guide || trivial < 0))
    return BlockStart::Trivial;
  const auto keep = [&](SynthesisResult r, BlockStart start)
  {
    if (done && (small || r.Status == SynthesisStatus::Cancelled))
      *done = std::move(r);
    return start;
  };
  SynthesisOptions probe = small ? options : ProbeOptions(options);
  probe.StartFrom = BlockStart::Trivial;
  std::pair<std::size_t, double> t;
  std::optional<SynthesisResult> first; // a small world's trivial run
  if (small)
  {
    try
    {
      first = Synthesize(rules, probe);
    }
    catch (const Error&)
    {
      // No label tiles space and no layers of such labels fit (WaveFunctionCollapse's Large
      // Circles): no trivial start at all, so the other starts, as for a blank one.
      if (options.TrivialLabel || TrivialLabelOf(rules, options) >= 0)
        throw;
      return ChooseAfterBlank(rules, probe, { 0, 1.0 }, translated, first, keep);
    }
    if (!first->Succeeded() || !LooksBlankByWeight(rules, *first))
      return keep(std::move(*first), BlockStart::Trivial);
    t = Variety(first->Model);
  }
  else
  {
    SynthesisStatus status = SynthesisStatus::Succeeded;
    t = RingedBlockVariety(rules, options, m, trivial, status);
    if (status == SynthesisStatus::Cancelled || !LooksBlank(rules, t))
      return BlockStart::Trivial;
    for (std::size_t a = 0; a < 3; ++a)
      probe.Size[a] = std::min(options.Size[a], m[a] + step[a]);
  }
  return ChooseAfterBlank(rules, probe, t, translated, first, keep);
}

SynthesisResult SynthesizeFromWholeModel(
  const AdjacencyRules& rules, const SynthesisOptions& options)
{
  std::array<std::int64_t, 3> m, step;
  SynthesisOptions whole = options;
  whole.StartFrom = BlockStart::Trivial;
  if (BlockGeometry<3>(options.Size, options.BlockSize, options.Overlap, m, step))
    return Synthesize(rules, whole); // no blocks: the whole run is the model
  whole.BlockSize = { { 0, 0, 0 } };
  whole.OnSnapshot = nullptr;
  whole.SnapshotsPerBlock = 0;
  whole.Exchange = BlockExchange();
  whole.BlocksWhenWholeFails = false;
  if (options.Progress) // the whole run is the first tenth
    whole.Progress = [&options](double f) { return options.Progress(std::max(1e-6, 0.1 * f)); };
  SynthesisResult start = Synthesize(rules, whole);
  if (!start.Succeeded())
  {
    if (start.Status != SynthesisStatus::Cancelled)
      start.Message = "the whole-model start of the blocks failed: " + start.Message;
    return start;
  }
  SynthesisOptions blocks = options;
  blocks.Start = std::move(start.Model);
  blocks.StartFrom = BlockStart::Trivial;
  SynthesisResult r = Synthesize(rules, blocks);
  r.Statistics.StartFrom = "whole";
  return r;
}

SynthesisOptions UndecidedWorld(const SynthesisOptions& world)
{
  SynthesisOptions w = world;
  if (w.UndecidedFirst && w.StartFrom == BlockStart::Automatic)
  {
    w.StartFrom = BlockStart::Undecided;
    w.Start.reset();
  }
  w.UndecidedFirst = false;
  return w;
}

double SnapshotBytes(const SynthesisOptions& options)
{
  // A label, a catalog size and an entropy (4 bytes each) per site and snapshot.
  return static_cast<double>(CountSnapshots(options)) * static_cast<double>(options.Size[0]) *
    static_cast<double>(options.Size[1]) * static_cast<double>(options.Size[2]) * 12.0;
}

void CheckSnapshotMemory(const SynthesisOptions& options, double limit)
{
  const double bytes = SnapshotBytes(options);
  if (bytes <= limit)
    return;
  std::ostringstream text;
  text << CountSnapshots(options) << " catalog snapshots of " << options.Size[0] << " x "
       << options.Size[1] << " x " << options.Size[2] << " sites need " << bytes / 1048576.0
       << " MiB, more than the limit of " << limit / 1048576.0
       << " MiB; use fewer snapshots per block, larger blocks or a smaller output";
  throw Error(text.str());
}

std::uint64_t RunFingerprint(const std::vector<std::string>& files,
  const std::vector<Label>& labels, const SynthesisOptions& options)
{
  std::uint64_t h = 1469598103934665603ull; // FNV-1a
  auto mix = [&h](std::uint64_t v)
  {
    h ^= v;
    h *= 1099511628211ull;
  };
  for (const std::string& file : files)
    for (const char c : file)
      mix(static_cast<unsigned char>(c));
  for (const Label v : labels)
    mix(static_cast<std::uint64_t>(static_cast<std::int64_t>(v)));
  for (std::size_t a = 0; a < 3; ++a)
    mix(static_cast<std::uint64_t>(options.Size[a]) * 31 +
      static_cast<std::uint64_t>(options.BlockSize[a]));
  mix(options.Seed);
  return (h >> 2) | 1; // never 0: 0 means "not synthesizing"
}

} // namespace msynth
