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
/// The distinct labels of @p model and the share of its most frequent one.
std::pair<std::size_t, double> Variety(const LabelGrid& model)
{
  std::map<Label, std::int64_t> counts;
  for (const Label v : model.Data())
    ++counts[v];
  std::int64_t most = 0;
  for (const auto& c : counts)
    most = std::max(most, c.second);
  return { counts.size(), static_cast<double>(most) / static_cast<double>(model.NumberOfSites()) };
}

/// More than 1.25 times the distinct labels of @p than, or a most frequent label's share under
/// 0.8 times its.
bool MoreVaried(const std::pair<std::size_t, double>& v, const std::pair<std::size_t, double>& than)
{
  return static_cast<double>(v.first) > 1.25 * static_cast<double>(than.first) ||
    v.second < 0.8 * than.second;
}

/// Whether a block run from the trivial start left its model blank: its trivial label covers
/// over 90 % of the sites, or over 1.25 times its share of the example (by the labels' weights).
bool LooksBlank(const AdjacencyRules& rules, const SynthesisResult& trivial)
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
} // namespace

BlockStart ChooseBlockStart(const AdjacencyRules& rules, const SynthesisOptions& options,
  std::optional<SynthesisResult>* done)
{
  if (options.StartFrom != BlockStart::Automatic)
    return options.StartFrom;
  std::array<std::int64_t, 3> m, step;
  if (BlockGeometry<3>(options.Size, options.BlockSize, options.Overlap, m, step) ||
    options.Start || options.Soft.Active() || detail::AnyMirror(options) ||
    detail::AnySeamSymmetry(options) || options.SnapshotsPerBlock > 0)
    return BlockStart::Trivial;
  SynthesisOptions probe = options;
  bool whole = true;
  for (std::size_t a = 0; a < 3; ++a)
  {
    probe.Size[a] = std::min(options.Size[a], m[a] + 4 * step[a]);
    whole &= probe.Size[a] == options.Size[a];
  }
  if (!whole && (options.Pins || options.Guide))
    return BlockStart::Trivial;
  if (!whole) // a probe of its own: no messages to other processes, the first 1 % of progress
  {
    probe.Exchange = BlockExchange();
    probe.Counts.clear();                 // the counts are the whole output's
    probe.Connected = ConnectedNetwork(); // so is the network
    if (options.Progress)
      probe.Progress = [&options](double f) { return options.Progress(std::max(1e-6, 0.01 * f)); };
  }
  probe.StartFrom = BlockStart::Trivial;
  SynthesisResult trivial = Synthesize(rules, probe);
  const auto keep = [&](SynthesisResult r, BlockStart start)
  {
    if (done && (whole || r.Status == SynthesisStatus::Cancelled))
      *done = std::move(r);
    return start;
  };
  if (trivial.Status == SynthesisStatus::Cancelled)
    return keep(std::move(trivial), BlockStart::Trivial);
  if (!trivial.Succeeded() || !LooksBlank(rules, trivial))
    return keep(std::move(trivial), BlockStart::Trivial);
  // The undecided start, then a whole-model one, when it decides every site with no failed
  // block: the undecided start with more variety than the trivial start; the whole-model start
  // (a whole-model output modified, so as varied as one) with any less blank model.
  const auto t = Variety(trivial.Model);
  for (const BlockStart start : { BlockStart::Undecided, BlockStart::WholeModel })
  {
    probe.StartFrom = start;
    SynthesisResult other = Synthesize(rules, probe);
    if (other.Status == SynthesisStatus::Cancelled)
      return keep(std::move(other), start);
    if (!other.Succeeded() || other.Statistics.BlocksFailed > 0)
      continue;
    const auto v = Variety(other.Model);
    if (start == BlockStart::Undecided ? MoreVaried(v, t) : v.second < t.second)
      return keep(std::move(other), start);
  }
  return keep(std::move(trivial), BlockStart::Trivial);
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
