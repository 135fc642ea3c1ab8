// SPDX-License-Identifier: BSD-3-Clause
#include "vtkMSLabelCounts.h"

#include "vtkFieldData.h"
#include "vtkIdTypeArray.h"
#include "vtkNew.h"
#include "vtkStringArray.h"

#include "Core/Error.h"
#include "Core/TextLists.h"
#include "Formats/Tileset.h"

#include <limits>

namespace vtkMSLabelCounts
{

std::vector<msynth::LabelCount> Read(const std::string& text, const msynth::Tileset* tiles)
{
  std::vector<msynth::LabelCount> counts;
  for (const msynth::CountEntry& e : msynth::ParseCountEntries(text, "Counts"))
  {
    msynth::LabelCount c;
    c.Name = e.Name;
    c.Minimum = e.Minimum;
    c.Maximum = e.Maximum;
    long long value = 0;
    if (msynth::ParseInteger(e.Name, std::numeric_limits<msynth::Label>::min(),
          std::numeric_limits<msynth::Label>::max(), value))
      c.Values.push_back(static_cast<msynth::Label>(value));
    else if (tiles)
    {
      for (int b = 0; b < tiles->NumberOfLabels(); ++b)
      {
        const auto& tile =
          tiles->Tiles[static_cast<std::size_t>(tiles->LabelTile[static_cast<std::size_t>(b)])];
        if (tile.Name == e.Name || tiles->LabelName(b) == e.Name)
          c.Values.push_back(b);
      }
      if (c.Values.empty())
        throw msynth::Error(
          "Counts: the tileset has no tile or label named '" + msynth::Printable(e.Name) + "'");
    }
    else
      throw msynth::Error(
        "Counts: '" + msynth::Printable(e.Name) + "' is not a label value (names need a tileset)");
    counts.push_back(c);
  }
  return counts;
}

void AddFields(vtkFieldData* fd, const std::vector<msynth::LabelCountResult>& counts)
{
  if (counts.empty())
    return;
  vtkNew<vtkStringArray> names;
  names->SetName("CountNames");
  vtkNew<vtkIdTypeArray> minimum, maximum, achieved;
  minimum->SetName("CountMinimum");
  maximum->SetName("CountMaximum");
  achieved->SetName("CountAchieved");
  for (const msynth::LabelCountResult& r : counts)
  {
    names->InsertNextValue(r.Requested.Name);
    minimum->InsertNextValue(static_cast<vtkIdType>(r.Requested.Minimum));
    maximum->InsertNextValue(static_cast<vtkIdType>(r.Requested.Maximum));
    achieved->InsertNextValue(static_cast<vtkIdType>(r.Achieved));
  }
  fd->AddArray(names);
  fd->AddArray(minimum);
  fd->AddArray(maximum);
  fd->AddArray(achieved);
}

} // namespace vtkMSLabelCounts
