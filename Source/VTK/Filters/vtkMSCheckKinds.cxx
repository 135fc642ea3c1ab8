// SPDX-License-Identifier: BSD-3-Clause
#include "vtkMSCheckKinds.h"

#include "vtkMSEngineBridge.h"
#include "vtkMSFieldData.h"
#include "vtkMSLabelArrays.h"
#include "vtkMSLabelCounts.h"
#include "vtkMSLabelGridReader.h"

#include "vtkDataArray.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkIdTypeArray.h"
#include "vtkImageData.h"
#include "vtkIntArray.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkStringArray.h"
#include "vtkUnsignedCharArray.h"
#include "vtkXMLImageDataReader.h"

#include "Continuous/ModelStructure.h"
#include "Core/Error.h"
#include "Core/Index.h"
#include "Core/TextLists.h"
#include "Discrete/LabelChecks.h"
#include "Discrete/OverlappingModel.h"
#include "Formats/Image.h"
#include "Formats/Tileset.h"
#include "Formats/VTKXMLCheck.h"
#include "Formats/VoxelTileset.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <initializer_list>

namespace vtkMSCheckKinds
{
void AddVerdict(vtkFieldData* out, bool valid, std::int64_t violations, std::int64_t pairs,
  const std::vector<std::string>& problems)
{
  vtkMSFieldData::AddFieldValue<vtkIntArray>(out, "Valid", valid ? 1 : 0);
  vtkMSFieldData::AddFieldValue<vtkIdTypeArray>(
    out, "Violations", static_cast<vtkIdType>(violations));
  vtkMSFieldData::AddFieldValue<vtkIdTypeArray>(out, "PairsChecked", static_cast<vtkIdType>(pairs));
  vtkNew<vtkStringArray> lines;
  lines->SetName("Problems");
  for (const std::string& line : problems)
    lines->InsertNextValue(line);
  out->AddArray(lines);
}

void CheckPicture(
  vtkImageData* model, const PictureCheck& check, std::size_t limit, vtkFieldData* out)
{
  vtkUnsignedCharArray* bytes = vtkMSLabelArrays::PictureBytes(model);
  if (!bytes)
    throw msynth::Error("The model of an image sample is a picture (unsigned char colours, as "
                        "a PNG reader gives them), not labels.");
  const msynth::RgbaImage picture = vtkMSLabelArrays::PictureRows(model, bytes, "the picture");
  msynth::OverlappingOptions options;
  options.N = check.PatternSize;
  options.Symmetry = check.PatternSymmetry;
  options.PeriodicInput = check.PeriodicInput;
  options.Ground = check.Ground;
  const msynth::Periodic periodic{ { check.PeriodicOutput[0], check.PeriodicOutput[1] } };
  const std::vector<std::string> problems =
    msynth::CheckPicture(msynth::ReadImage(check.SampleFile), options, picture, periodic,
      std::max<std::size_t>(limit, 1));
  AddVerdict(out, problems.empty(), static_cast<std::int64_t>(problems.size()), 0,
    std::vector<std::string>(
      problems.begin(), problems.begin() + static_cast<long>(std::min(limit, problems.size()))));
}

void CheckVoxels(vtkImageData* model, const std::string& tileset, const std::string& tiles,
  std::size_t limit, vtkFieldData* out)
{
  msynth::LabelGrid grid;
  std::string problem;
  if (!vtkMSLabelArrays::ReadLabels(model, nullptr, grid, problem))
    throw msynth::Error("The voxel model: " + problem);
  auto* colours =
    vtkUnsignedCharArray::SafeDownCast(model->GetFieldData()->GetAbstractArray("PaletteRGBA"));
  if (!colours || colours->GetNumberOfComponents() != 4)
    throw msynth::Error("The voxel model has no palette (field data PaletteRGBA, as the label "
                        "grid reader gives a .vox file).");
  std::vector<std::array<std::uint8_t, 4>> palette(msynth::ToIndex(colours->GetNumberOfTuples()));
  for (std::size_t i = 0; i < palette.size(); ++i)
    std::copy_n(colours->GetPointer(4 * static_cast<vtkIdType>(i)), 4, palette[i].data());
  const msynth::VoxelCheckReport report = msynth::CheckVoxelModel(tileset, tiles, grid, palette);
  AddVerdict(out, report.Valid, report.Problems, report.PairsChecked,
    std::vector<std::string>(report.First.begin(),
      report.First.begin() + static_cast<long>(std::min(limit, report.First.size()))));
  vtkMSFieldData::AddFieldValue<vtkIdTypeArray>(out, "Cells", static_cast<vtkIdType>(report.Cells));
}

namespace
{
/// The region of every site of @p model (x fastest) from the `Region` point array of the guide
/// @p path stretched over it: a site at p of n reads the guide point floor((p + 1/2) D / n) per
/// axis, as a synthesis guide is read (arithmetic of the check's own).
std::vector<long long> GuideRegions(const std::string& path, const msynth::LabelGrid& model)
{
  vtkNew<vtkXMLImageDataReader> reader;
  if (!reader->CanReadFile(path.c_str()))
    throw msynth::Error("'" + path + "': not a readable guide volume (.vti)");
  msynth::CheckVTKXMLFile(path); // what VTK's reader trusts, first
  reader->SetFileName(path.c_str());
  std::string messages;
  if (!vtkMSEngineBridge::Execute(reader, messages))
    throw msynth::Error("'" + path + "': not a readable guide volume: " + messages);
  vtkImageData* guide = reader->GetOutput();
  vtkDataArray* region = guide->GetPointData()->GetArray("Region");
  if (!region || !vtkMSLabelArrays::IsIntegerArray(region))
    throw msynth::Error("'" + path + "': the guide has no integer point array Region");
  int d[3];
  guide->GetDimensions(d);
  if (d[0] < 1 || d[1] < 1 || d[2] < 1 || region->GetNumberOfTuples() != guide->GetNumberOfPoints())
    throw msynth::Error("'" + path + "': the guide's Region array does not cover its extent");
  const auto& n = model.Dimensions();
  std::vector<long long> out;
  out.reserve(model.Data().size());
  for (std::int64_t z = 0; z < n[2]; ++z)
    for (std::int64_t y = 0; y < n[1]; ++y)
      for (std::int64_t x = 0; x < n[0]; ++x)
      {
        const std::int64_t p[3] = { x, y, z };
        std::int64_t cell[3];
        for (int a = 0; a < 3; ++a)
          cell[a] = std::min<std::int64_t>(d[a] - 1, (p[a] * 2 * d[a] + d[a]) / (2 * n[a]));
        out.push_back(static_cast<long long>(
          region->GetTuple1(static_cast<vtkIdType>(cell[0] + d[0] * (cell[1] + d[1] * cell[2])))));
      }
  return out;
}

/// The pins of @p path (a label grid; -1 free) and where its first site lies in the model (a
/// .vti's extent, else 0): read by the reader, compared by LabelChecks.h.
msynth::LabelGrid ReadPins(const std::string& path, std::array<long long, 3>& origin)
{
  if (msynth::IsImageFile(path))
    throw msynth::Error(
      "'" + path + "': the check reads pins from a label grid (.vti, .txt, .vox), not a picture");
  std::array<int, 3> first{};
  msynth::LabelGrid pins = vtkMSLabelArrays::ReadLabelGridFile(path, first);
  origin = { { first[0], first[1], first[2] } };
  return pins;
}
} // namespace

bool CheckNetwork(const msynth::LabelGrid& model, const NetworkRequest& request, vtkFieldData* out)
{
  if (request.Counts.empty() && request.Connected.empty() && request.Pins.empty())
  {
    if (!request.Path.empty())
      throw msynth::Error("A Path needs Connected: the labels that carry the path.");
    return true;
  }
  const msynth::Tileset names = request.Tileset.empty()
    ? msynth::Tileset()
    : msynth::ReadTilesetFile(request.Tileset, request.Subset, request.Tiles);
  vtkNew<vtkStringArray> findings;
  findings->SetName("Findings");
  bool kept = true;
  if (!request.Pins.empty())
  {
    std::array<long long, 3> origin{ { 0, 0, 0 } };
    const msynth::LabelGrid pins = ReadPins(request.Pins, origin);
    const msynth::PinsCheck p =
      msynth::CheckPinnedLabels(model, pins, origin, request.PinsEmptyFree);
    vtkMSFieldData::AddFieldValue<vtkIdTypeArray>(
      out, "PinsChecked", static_cast<vtkIdType>(p.Pinned));
    vtkMSFieldData::AddFieldValue<vtkIdTypeArray>(
      out, "PinsMissed", static_cast<vtkIdType>(p.Missed));
    vtkMSFieldData::AddFieldValue<vtkIntArray>(out, "PinsKept", p.Kept() ? 1 : 0);
    findings->InsertNextValue(p.Describe());
    kept = p.Kept();
  }
  if (!request.Counts.empty())
  {
    std::vector<msynth::LabelCountResult> counted;
    bool counts = true;
    const std::vector<long long> regions =
      request.Guide.empty() ? std::vector<long long>() : GuideRegions(request.Guide, model);
    for (const msynth::CountCheck& c : msynth::CheckLabelCounts(model, request.Counts, names,
           request.Source, request.Guide.empty() ? nullptr : &regions))
    {
      counted.push_back({ { {}, c.Name, c.Minimum, c.Maximum }, c.Achieved });
      counts = counts && c.Kept();
      findings->InsertNextValue(c.Describe());
    }
    vtkMSLabelCounts::AddFields(out, counted);
    vtkMSFieldData::AddFieldValue<vtkIntArray>(out, "CountsKept", counts ? 1 : 0);
    kept = kept && counts;
  }
  if (!request.Connected.empty())
  {
    const msynth::NetworkCheck n = msynth::CheckLabelNetwork(model, request.Connected,
      request.Path.empty() ? std::vector<std::string>() : msynth::SplitText(request.Path, ';'),
      names, request.Source);
    msynth::ConnectedResult result;
    result.Requested = true;
    result.Maximum = n.Maximum;
    result.Name = n.Labels;
    result.Before = result.Components = n.Components;
    result.PathSites = n.PathSites;
    vtkMSLabelCounts::AddConnectedFields(out, result);
    vtkMSFieldData::AddFieldValue<vtkIntArray>(
      out, "ConnectedKept", (n.Open ? n.Closed == 0 : n.Components <= n.Maximum) ? 1 : 0);
    if (n.Open)
      vtkMSFieldData::AddFieldValue<vtkIdTypeArray>(
        out, "ConnectedClosed", static_cast<vtkIdType>(n.Closed));
    findings->InsertNextValue(n.Describe());
    if (n.HasPath)
    {
      vtkMSFieldData::AddFieldValue<vtkIntArray>(out, "PathJoined", n.PathJoined ? 1 : 0);
      vtkMSFieldData::AddFieldValue<vtkIdTypeArray>(
        out, "PathComponents", static_cast<vtkIdType>(n.PathComponents));
      findings->InsertNextValue(n.PathLine);
    }
    kept = kept && n.Kept();
  }
  out->AddArray(findings);
  return kept;
}
int AddResemblance(vtkFieldData* out, const msynth::PolyhedralExample& example,
  const msynth::PolyhedralExample& model, double spacing)
{
  if (example.Planar || model.Planar)
    return 0;
  double extent = 0;
  for (int k = 0; k < 2; ++k)
  {
    double lo = HUGE_VAL, hi = -HUGE_VAL;
    for (const auto& p : example.Points)
    {
      lo = std::min(lo, p[msynth::ToIndex(k)]);
      hi = std::max(hi, p[msynth::ToIndex(k)]);
    }
    extent = std::max(extent, hi - lo);
  }
  const double voxel = msynth::StructureVoxel(spacing, extent);
  const double reach = msynth::StructureReach(spacing, extent);
  const auto items = msynth::CompareStructure(msynth::MeasureStructure(example, voxel, reach),
    msynth::MeasureStructure(model, voxel, reach), example.TypeNames);
  vtkNew<vtkStringArray> measure, bounds;
  vtkNew<vtkDoubleArray> inExample, inModel;
  vtkNew<vtkIntArray> passes;
  measure->SetName("ResemblanceMeasure");
  bounds->SetName("ResemblanceBounds");
  inExample->SetName("ResemblanceExample");
  inModel->SetName("ResemblanceModel");
  passes->SetName("ResemblancePasses");
  int failed = 0;
  for (const auto& item : items)
  {
    measure->InsertNextValue(item.Measure);
    bounds->InsertNextValue(item.Bounds);
    inExample->InsertNextValue(item.Example);
    inModel->InsertNextValue(item.Model);
    passes->InsertNextValue(item.Passes ? 1 : 0);
    failed += item.Passes ? 0 : 1;
  }
  for (vtkAbstractArray* a :
    std::initializer_list<vtkAbstractArray*>{ measure, bounds, inExample, inModel, passes })
    out->AddArray(a);
  vtkMSFieldData::AddFieldValue<vtkIntArray>(out, "ResemblanceFailed", failed);
  return failed;
}
} // namespace vtkMSCheckKinds
