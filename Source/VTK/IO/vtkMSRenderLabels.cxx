// SPDX-License-Identifier: BSD-3-Clause
#include "vtkMSRenderLabels.h"

#include "vtkDataArray.h"
#include "vtkFieldData.h"
#include "vtkStringArray.h"
#include "vtkUnsignedCharArray.h"

#include "Core/Index.h"
#include "Core/LabelColor.h"

#include <limits>
#include <unordered_set>

namespace
{
/// The distinct values of @p values (@p n of them): a run of equal values costs one compare.
std::vector<std::int32_t> Distinct(const std::int32_t* values, std::int64_t n)
{
  std::unordered_set<std::int32_t> seen;
  for (std::int64_t i = 0; i < n; ++i)
    if (i == 0 || values[msynth::ToIndex(i)] != values[msynth::ToIndex(i - 1)])
      seen.insert(values[msynth::ToIndex(i)]);
  return std::vector<std::int32_t>(seen.begin(), seen.end());
}

/// A tileset label's name without its orientation ("corner 2" -> "corner").
std::string TileOf(const std::string& name)
{
  const std::size_t space = name.rfind(' ');
  if (space == std::string::npos || space + 1 == name.size())
    return name;
  for (std::size_t i = space + 1; i < name.size(); ++i)
    if (name[i] < '0' || name[i] > '9')
      return name;
  return name.substr(0, space);
}

void AddNames(vtkFieldData* fields, msynth::vdb::LabelRenderView& view)
{
  auto* tiles = vtkStringArray::SafeDownCast(fields->GetAbstractArray("LabelTile"));
  auto* labelNames = vtkStringArray::SafeDownCast(fields->GetAbstractArray("TileNames"));
  if (tiles || labelNames)
  {
    // A tileset's label b is its b-th label.
    for (vtkIdType b = 0; tiles && b < tiles->GetNumberOfValues(); ++b)
      view.Names[static_cast<std::int32_t>(b)] = tiles->GetValue(b);
    for (vtkIdType b = 0; !tiles && b < labelNames->GetNumberOfValues(); ++b)
      view.Names[static_cast<std::int32_t>(b)] = TileOf(labelNames->GetValue(b));
    return;
  }
  auto* ids = vtkDataArray::SafeDownCast(fields->GetAbstractArray("PieceLabels"));
  auto* names = vtkStringArray::SafeDownCast(fields->GetAbstractArray("PieceNames"));
  for (vtkIdType i = 0;
       ids && names && i < ids->GetNumberOfTuples() && i < names->GetNumberOfValues(); ++i)
    if (!names->GetValue(i).empty())
    {
      // A label of several pieces ("wall", "window") is named by all: "wall+window".
      std::string& name = view.Names[static_cast<std::int32_t>(ids->GetTuple1(i))];
      name += (name.empty() ? "" : "+") + names->GetValue(i);
    }
}
} // namespace

void vtkMSRenderLabels::Describe(
  vtkFieldData* fields, bool named, msynth::vdb::LabelRenderView& view)
{
  auto* palette =
    vtkUnsignedCharArray::SafeDownCast(fields ? fields->GetAbstractArray("PaletteRGBA") : nullptr);
  if (palette && palette->GetNumberOfComponents() != 4)
    palette = nullptr;
  for (std::int32_t label : Distinct(view.Labels, view.Geometry.NumberOfVoxels()))
  {
    if (label == view.EmptyLabel)
      continue;
    std::array<double, 3> rgb{ { 0.5, 0.5, 0.5 } };
    if (!palette && label != std::numeric_limits<std::int32_t>::min()) // not an undecided site
      rgb = msynth::LabelColor(label);
    else if (label >= 0 && label < palette->GetNumberOfTuples())
      for (int c = 0; c < 3; ++c)
        rgb[msynth::ToIndex(c)] = palette->GetValue(4 * vtkIdType(label) + c) / 255.0;
    view.Colors[label] = { { msynth::vdb::LinearFromSrgb(rgb[0]),
      msynth::vdb::LinearFromSrgb(rgb[1]), msynth::vdb::LinearFromSrgb(rgb[2]) } };
  }
  if (named && fields)
    AddNames(fields, view);
}
