// SPDX-License-Identifier: BSD-3-Clause
// The checks of `msynth synthesize`'s options against each other and the example, in the
// command's terms (its options, not the filter's properties), and the filter's messages turned
// into those terms.
#include "Common.h"
#include "Synthesize.h"

#include "vtkDataArray.h"
#include "vtkImageData.h"
#include "vtkMSLabelArrays.h"

#include "Core/Error.h"
#include "Core/Index.h"
#include "Formats/Tileset.h"

#include <algorithm>
#include <iostream>
#include <set>
#include <stdexcept>
#include <string>

namespace msynth
{
namespace cli
{
namespace
{
const char* const AxisNames[3] = { "x", "y", "z" };

std::string Listed(const std::vector<int>& v, const char* separator = " ")
{
  std::string text;
  for (std::size_t i = 0; i < v.size(); ++i)
    text += (i ? separator : "") + std::to_string(v[i]);
  return text;
}

/// "0, 1, 2, ..." : the first @p most values of @p values.
std::string FirstValues(const std::set<long long>& values, std::size_t most = 20)
{
  std::string text;
  std::size_t n = 0;
  for (long long v : values)
  {
    if (n == most)
      return text + ", ... (" + std::to_string(values.size()) + " in all)";
    text += (n++ ? ", " : "") + std::to_string(v);
  }
  return text;
}

} // namespace

/// The option of the other kind of synthesis that does what @p name does (--block and
/// --blocks, --ground and --grounded), as "; ... takes ..." ("" when there is none).
std::string Counterpart(const std::string& name, bool polyhedral)
{
  if (polyhedral && name == "--block")
    return "; continuous synthesis takes --blocks N (a block's edge in plane spacings)";
  if (!polyhedral && name == "--blocks")
    return "; label grids and tilesets take --block NX NY NZ (in sites)";
  if (polyhedral && (name == "--ground" || name == "--empty"))
    return "; --grounded stands a continuous model on the ground";
  if (!polyhedral && name == "--grounded")
    return "; label grids and tilesets take --ground LABEL (and --empty LABEL)";
  return "";
}

void CheckDiscreteSizes(const SynthesizeOptions& o)
{
  const bool sample = IsSample(o.Example);
  const bool region = std::any_of(o.Region.begin(), o.Region.end(), [](int v) { return v != 0; });
  const std::string size = "--size " + Listed({ o.Size3[0], o.Size3[1], o.Size3[2] });
  if (region)
  {
    for (int a = 0; a < 3; ++a)
    {
      const int lo = o.Region[msynth::ToIndex(a)], hi = o.Region[msynth::ToIndex(a + 3)];
      const std::string axis = AxisNames[a];
      std::string what;
      if (lo < 0)
        what = axis + "0 = " + std::to_string(lo) + " is below 0";
      else if (hi > o.Size3[msynth::ToIndex(a)])
        what = axis + "1 = " + std::to_string(hi) + " is past the world's " +
          std::to_string(o.Size3[msynth::ToIndex(a)]) + " sites in " + axis;
      else if (lo >= hi)
        what = axis + "0 = " + std::to_string(lo) + " is not below " + axis +
          "1 = " + std::to_string(hi) + " (the box would be empty)";
      if (!what.empty())
        throw UsageError{ "--region " + Listed(o.Region) + ": " + what + " (" + size +
          "); expected X0 Y0 Z0 X1 Y1 Z1 with 0 <= X0 < X1 <= NX, 0 <= Y0 < Y1 <= NY and "
          "0 <= Z0 < Z1 <= NZ" };
    }
  }
  if (sample)
    for (int a = 0; a < 2; ++a)
    {
      const bool repeats = o.Translate.find(AxisNames[a][0]) != std::string::npos;
      if (!repeats && o.Size3[msynth::ToIndex(a)] < o.Pattern)
        throw UsageError{ size + ": a picture from '" + o.Example + "' is at least " +
          std::to_string(o.Pattern) + " x " + std::to_string(o.Pattern) +
          " pixels, its pattern size (--pattern " + std::to_string(o.Pattern) + ")" };
    }
  bool blocks = false; // more than one block along some axis
  for (std::size_t a = 0; a < 3; ++a)
    blocks = blocks || (o.Block[a] > 0 && o.Block[a] < o.Size3[a]);
  if ((o.Stream || o.Resume) && !blocks)
    throw UsageError{ "--stream computes the world block by block: give a --block smaller than " +
      size + " on at least one axis (--block " + Listed(o.Block) + ")" };
  bool larger = false, whole = true;
  for (int a = 0; a < 3; ++a)
  {
    const int b = o.Block[msynth::ToIndex(a)], n = o.Size3[msynth::ToIndex(a)];
    larger = larger || b > n;
    whole = whole && (b >= n || b <= 0);
  }
  if (larger && !sample)
    std::cout << "note: --block " << Listed(o.Block) << " is larger than the model ("
              << Triple(o.Size3.data()) << ")"
              << (whole ? ": the model runs whole, in one block"
                        : ": the blocks span the model on the axes where they are larger")
              << "\n";
}

namespace
{
/// A 3D example whose bottom layer is one label throughout stands on it, and a model without
/// --ground floats (roofs and walls with no ground under them): the note says which option
/// puts it under the model.
void NoteGround(const SynthesizeOptions& o, vtkImageData* example)
{
  int dims[3] = { 0, 0, 0 };
  if (example)
    example->GetDimensions(dims);
  vtkDataArray* labels = example ? vtkMSLabelArrays::FindLabelArray(example, nullptr) : nullptr;
  if (!labels || dims[2] < 2 || o.Size3[2] < 2 || labels->GetNumberOfTuples() < dims[0] * dims[1])
    return;
  const double ground = labels->GetTuple1(0);
  for (vtkIdType i = 1; i < static_cast<vtkIdType>(dims[0]) * dims[1]; ++i)
    if (labels->GetTuple1(i) != ground)
      return;
  if (ground == 0)
    return;
  bool air = false; // label 0 in the example: --empty 0 may go around the model
  for (vtkIdType i = 0; i < labels->GetNumberOfTuples() && !air; ++i)
    air = labels->GetTuple1(i) == 0;
  std::cout << "note: the example stands on a layer of label " << ground << "; --ground " << ground
            << " puts one under the model" << (air ? " (and --empty 0 air around it)" : "") << "\n";
}
} // namespace

void CheckBoundaryLabels(const SynthesizeOptions& o, vtkImageData* example)
{
  if (o.Ground.empty() && o.Empty.empty())
  {
    NoteGround(o, example);
    return;
  }
  std::set<long long> values;
  if (vtkDataArray* labels = example ? vtkMSLabelArrays::FindLabelArray(example, nullptr) : nullptr)
    for (vtkIdType i = 0; i < labels->GetNumberOfTuples(); ++i)
      values.insert(static_cast<long long>(labels->GetTuple1(i)));
  else if (IsTileset(o.Example)) // a tileset's labels: its tiles' orientations, numbered
  {
    const int n = msynth::ReadTilesetFile(o.Example, o.Subset, o.Tiles).NumberOfLabels();
    for (int b = 0; b < n; ++b)
      values.insert(b);
  }
  else
    return;
  for (const auto& [name, option] :
    { std::make_pair("--ground", &o.Ground), std::make_pair("--empty", &o.Empty) })
    if (!option->empty() && values.count((*option)[0]) == 0)
      throw UsageError{ std::string(name) + " " + std::to_string((*option)[0]) + ": label " +
        std::to_string((*option)[0]) + " does not occur in '" + o.Example + "'; its labels are " +
        FirstValues(values) +
        (example ? std::string() : " (msynth info '" + o.Example + "' lists them)") };
}

namespace
{
/// A message of vtkMSDiscreteSynthesis about the pinned sites naming --fixed, its file and
/// --size.
std::string InOptionTerms(const std::string& message, const SynthesizeOptions& o)
{
  std::string text = message;
  const std::string property = "Fixed File '"; // the filter's messages about the file it read
  if (text.compare(0, property.size(), property) == 0)
    return "--fixed '" + text.substr(property.size());
  if (!o.Fixed.empty() && text.find("the pinned sites cover") != std::string::npos)
  {
    text = "--fixed '" + o.Fixed + "': " + text;
    const std::string size = "the output's size";
    const std::size_t at = text.find(size);
    if (at != std::string::npos)
      text.insert(
        at + size.size(), " (--size " + Listed({ o.Size3[0], o.Size3[1], o.Size3[2] }) + ")");
  }
  return text;
}
} // namespace

void RunDiscrete(vtkAlgorithm* synthesis, const SynthesizeOptions& o)
{
  try
  {
    RunSynthesis(synthesis);
  }
  catch (const std::runtime_error& e)
  {
    throw std::runtime_error(InOptionTerms(e.what(), o));
  }
}

} // namespace cli
} // namespace msynth
