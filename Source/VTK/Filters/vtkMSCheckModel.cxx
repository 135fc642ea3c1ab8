// SPDX-License-Identifier: BSD-3-Clause
#include "vtkMSCheckModel.h"

#include "vtkMSCheckKinds.h"
#include "vtkMSFieldData.h"
#include "vtkMSLabelArrays.h"
#include "vtkMSPipeline.h"
#include "vtkMSPolyhedra.h"

#include "vtkDataArray.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkIdTypeArray.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkIntArray.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPolyData.h"
#include "vtkStringArray.h"

#include "Continuous/ContinuousMesh.h"
#include "Core/Error.h"
#include "Discrete/ConsistencyCheck.h"
#include "Formats/Tileset.h"
#include "Patterns/PatternQuality.h"

#include <cmath>
#include <exception>

vtkStandardNewMacro(vtkMSCheckModel);

vtkMSCheckModel::vtkMSCheckModel()
{
  this->SetNumberOfInputPorts(2);
}

int vtkMSCheckModel::FillInputPortInformation(int port, vtkInformation* info)
{
  info->Remove(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE());
  info->Append(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkImageData");
  info->Append(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkPolyData");
  if (port == 1)
  {
    info->Set(vtkAlgorithm::INPUT_IS_OPTIONAL(), 1);
    info->Set(vtkAlgorithm::INPUT_IS_REPEATABLE(), 1);
  }
  return 1;
}

int vtkMSCheckModel::RequestUpdateExtent(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector*)
{
  // The checks look at every site of the model and the examples.
  for (int port = 0; port < 2; ++port)
    for (int i = 0; i < inputVector[port]->GetNumberOfInformationObjects(); ++i)
      vtkMSPipeline::RequestWholeExtentOnPieceZero(inputVector[port]->GetInformationObject(i), 0);
  return 1;
}

namespace
{
/// The one string field data @p name of @p fd, "" when absent.
std::string Recorded(vtkFieldData* fd, const char* name)
{
  auto* a = vtkStringArray::SafeDownCast(fd ? fd->GetAbstractArray(name) : nullptr);
  return a && a->GetNumberOfValues() > 0 ? a->GetValue(0) : std::string();
}

/// One number of field data @p name, @p otherwise when absent.
double RecordedNumber(vtkFieldData* fd, const char* name, double otherwise)
{
  vtkDataArray* a = fd ? fd->GetArray(name) : nullptr;
  return a && a->GetNumberOfTuples() == 1 ? a->GetTuple1(0) : otherwise;
}

/// The first violations as arrays: ViolationSites, ViolationAxes, ViolationLabels; the verdict
/// @p valid (the pairs' and the other checks').
void AddViolations(vtkFieldData* out, const msynth::ConsistencyReport& report, bool valid)
{
  vtkNew<vtkIdTypeArray> sites;
  sites->SetName("ViolationSites");
  sites->SetNumberOfComponents(3);
  vtkNew<vtkIntArray> axes;
  axes->SetName("ViolationAxes");
  vtkNew<vtkIntArray> labels;
  labels->SetName("ViolationLabels");
  labels->SetNumberOfComponents(2);
  std::vector<std::string> lines;
  for (const msynth::ConsistencyViolation& v : report.First)
  {
    const vtkIdType site[3] = { v.Site[0], v.Site[1], v.Site[2] };
    sites->InsertNextTypedTuple(site);
    axes->InsertNextValue(v.Axis);
    const int pair[2] = { v.From, v.To };
    labels->InsertNextTypedTuple(pair);
    lines.push_back(v.Describe());
  }
  vtkMSCheckKinds::AddVerdict(out, valid, report.Violations, report.PairsChecked, lines);
  out->AddArray(sites);
  out->AddArray(axes);
  out->AddArray(labels);
}

/// KL_<shape> per shape of @p shapes and PatternLogProbability (PatternQuality.h).
void AddQuality(vtkFieldData* out, const std::vector<msynth::LabelGrid>& examples,
  const msynth::LabelGrid& model, const std::string& shapes, double epsilon)
{
  std::vector<msynth::Stencil> soft;
  for (const msynth::Stencil& s : msynth::ParseStencils(shapes))
  {
    vtkMSFieldData::AddFieldValue<vtkDoubleArray>(
      out, ("KL_" + s.Name).c_str(), msynth::PatternKL(examples, model, s));
    if (s.Offsets.size() > 2)
      soft.push_back(s);
  }
  vtkMSFieldData::AddFieldValue<vtkDoubleArray>(
    out, "PatternLogProbability", msynth::PatternLogProbability(examples, model, soft, epsilon));
}
} // namespace

bool vtkMSCheckModel::CheckLabels(
  vtkImageData* model, vtkInformationVector* examples, vtkFieldData* out)
{
  msynth::LabelGrid grid;
  std::string problem;
  if (!vtkMSLabelArrays::ReadLabels(model, nullptr, grid, problem))
  {
    vtkErrorMacro(<< "The model (" << vtkMSFieldData::ExampleName(model) << "): " << problem);
    return false;
  }
  std::vector<msynth::LabelGrid> grids;
  for (int i = 0; i < examples->GetNumberOfInformationObjects(); ++i)
  {
    vtkImageData* example = vtkImageData::GetData(examples, i);
    grids.emplace_back();
    if (!example || !vtkMSLabelArrays::ReadLabels(example, nullptr, grids.back(), problem))
    {
      vtkErrorMacro(<< "Example " << i + 1 << " ("
                    << (example ? vtkMSFieldData::ExampleName(example) : "not a label image")
                    << "): " << (example ? problem : "a label model needs label examples"));
      return false;
    }
  }
  vtkFieldData* fd = model->GetFieldData();
  const bool recorded = this->TilesetFile.empty() && grids.empty();
  const std::string tileset = recorded ? Recorded(fd, "TilesetFile") : this->TilesetFile;
  if (grids.empty() && tileset.empty())
  {
    vtkErrorMacro(<< "Nothing to check the model against: connect its example(s) or set a "
                     "TilesetFile.");
    return false;
  }
  msynth::ConsistencyReport report;
  try
  {
    std::array<std::vector<std::pair<int, int>>, 3> pairs;
    if (!tileset.empty())
      pairs = msynth::ReadTilesetFile(tileset,
        recorded ? Recorded(fd, "TilesetSubset") : this->TilesetSubset,
        recorded ? Recorded(fd, "TilesFolder") : this->TilesFolder)
                .Pairs;
    report =
      msynth::CheckConsistency(grids, pairs, grid, static_cast<std::size_t>(this->MaximumReported));
    // Counts and network: names of ConnectedTilesetFile, else of the tileset checked against.
    const bool own = !this->ConnectedTilesetFile.empty();
    vtkMSCheckKinds::NetworkRequest request{ this->Counts, this->Connected, this->Path,
      own ? this->ConnectedTilesetFile : tileset,
      own || !recorded ? this->TilesetSubset : Recorded(fd, "TilesetSubset"),
      own || !recorded ? this->TilesFolder : Recorded(fd, "TilesFolder"), {} };
    request.Source = !request.Tileset.empty() ? request.Tileset
      : examples->GetNumberOfInformationObjects() > 0
      ? vtkMSFieldData::ExampleName(vtkImageData::GetData(examples, 0))
      : std::string("the model");
    const bool kept = vtkMSCheckKinds::CheckNetwork(grid, request, out);
    AddViolations(out, report, report.Consistent && kept);
    // Shapes, else the soft shapes a pattern synthesis recorded.
    const std::string shapes = this->Shapes.empty() ? Recorded(fd, "SoftShapes") : this->Shapes;
    if (!shapes.empty())
      AddQuality(out, grids, grid, shapes, this->Epsilon);
  }
  catch (const std::exception& e)
  {
    vtkErrorMacro(<< e.what());
    return false;
  }
  return true;
}

bool vtkMSCheckModel::CheckContinuous(
  vtkPolyData* model, vtkInformationVector* examples, vtkFieldData* out)
{
  vtkPolyData* example = vtkPolyData::GetData(examples, 0);
  if (!example || examples->GetNumberOfInformationObjects() != 1)
  {
    vtkErrorMacro(<< "A continuous model is checked against one polyhedral example (port 1).");
    return false;
  }
  // The example analyzed with the direction snapping its arrangement used (recorded in the
  // model by the mesh filter; a rotated polygon's directions may have been snapped to fit exact
  // arithmetic), else the defaults.
  vtkFieldData* fd = model->GetFieldData();
  const double degrees = RecordedNumber(fd, "AngleTolerance", 0.01);
  const double largest = RecordedNumber(fd, "MaximumSmallInteger", 12);
  if (!(degrees > 0 && degrees <= 10) || !(largest >= 1 && largest <= 1000000))
  {
    vtkErrorMacro(<< "The model's AngleTolerance or MaximumSmallInteger is out of range.");
    return false;
  }
  try
  {
    msynth::PolyhedralExample ex;
    const msynth::PolyhedralAnalysis analysis =
      vtkMSPolyhedra::AnalyzeExample(example, degrees, static_cast<int>(largest), ex);
    const auto mesh = vtkMSPolyhedra::ToContinuousMesh(model, "the model");
    // Features are held to a fraction of the smallest plane spacing the mesh filter recorded.
    const double spacing = RecordedNumber(fd, "SmallestSpacing", 0);
    if (!(spacing >= 0) || !std::isfinite(spacing))
    {
      vtkErrorMacro(<< "The model's SmallestSpacing is out of range.");
      return false;
    }
    const auto report = msynth::CheckContinuousModel(analysis, mesh, ex.TypeNames, spacing);
    vtkMSCheckKinds::AddVerdict(out, report.Valid, report.Valid ? 0 : 1, 0,
      report.Valid ? std::vector<std::string>() : std::vector<std::string>{ report.Problem });
    vtkMSFieldData::AddFieldValue<vtkIntArray>(out, "Objects", report.Objects);
    vtkMSFieldData::AddFieldValue<vtkIntArray>(out, "DistinctLabels", report.DistinctLabels);
    vtkMSFieldData::AddFieldValue<vtkDoubleArray>(out, "SmallestFeature", report.SmallestFeature);
    vtkMSFieldData::AddFieldValue<vtkDoubleArray>(
      out, "SmallestFeatureFraction", spacing > 0 ? report.SmallestFeature / spacing : 0.0);
  }
  catch (const std::exception& e)
  {
    vtkErrorMacro(<< e.what());
    return false;
  }
  return true;
}

bool vtkMSCheckModel::CheckOther(vtkImageData* model, vtkFieldData* out)
{
  try
  {
    const auto limit = static_cast<std::size_t>(this->MaximumReported);
    if (!this->SampleFile.empty())
    {
      vtkMSCheckKinds::PictureCheck check{ this->SampleFile, this->PatternSize,
        this->PatternSymmetry, this->PeriodicInput, this->Ground,
        { this->PeriodicOutput[0] != 0, this->PeriodicOutput[1] != 0 } };
      vtkMSCheckKinds::CheckPicture(model, check, limit, out);
    }
    else if (this->TilesetFile.empty())
      throw msynth::Error("A voxel model is checked against a voxel tileset: set TilesetFile.");
    else
      vtkMSCheckKinds::CheckVoxels(model, this->TilesetFile, this->TilesFolder, limit, out);
  }
  catch (const std::exception& e)
  {
    vtkErrorMacro(<< e.what());
    return false;
  }
  return true;
}

int vtkMSCheckModel::RequestData(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  vtkDataObject* input = vtkDataObject::GetData(inputVector[0], 0);
  vtkDataObject* output = vtkDataObject::GetData(outputVector, 0);
  output->ShallowCopy(input);
  vtkNew<vtkFieldData> fields; // the model's own field data stays the input's
  fields->DeepCopy(input->GetFieldData());
  output->SetFieldData(fields);
  auto* image = vtkImageData::SafeDownCast(input);
  const bool other = image && (!this->SampleFile.empty() || this->VoxelModel);
  const bool checked = other ? this->CheckOther(image, fields)
    : image
    ? this->CheckLabels(image, inputVector[1], fields)
    : this->CheckContinuous(vtkPolyData::SafeDownCast(input), inputVector[1], fields);
  if (!checked)
    output->Initialize(); // no verdict: no output
  return checked ? 1 : 0;
}

void vtkMSCheckModel::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "TilesetFile: " << this->TilesetFile << "\n";
  os << indent << "TilesetSubset: " << this->TilesetSubset << "\n";
  os << indent << "TilesFolder: " << this->TilesFolder << "\n";
  os << indent << "SampleFile: " << this->SampleFile << "\n";
  os << indent << "PatternSize: " << this->PatternSize << "\n";
  os << indent << "PatternSymmetry: " << this->PatternSymmetry << "\n";
  os << indent << "PeriodicInput: " << this->PeriodicInput << "\n";
  os << indent << "Ground: " << this->Ground << "\n";
  os << indent << "PeriodicOutput: " << this->PeriodicOutput[0] << " " << this->PeriodicOutput[1]
     << "\n";
  os << indent << "VoxelModel: " << this->VoxelModel << "\n";
  os << indent << "Counts: " << this->Counts << "\n";
  os << indent << "Connected: " << this->Connected << "\n";
  os << indent << "Path: " << this->Path << "\n";
  os << indent << "ConnectedTilesetFile: " << this->ConnectedTilesetFile << "\n";
  os << indent << "Shapes: " << this->Shapes << "\n";
  os << indent << "Epsilon: " << this->Epsilon << "\n";
  os << indent << "MaximumReported: " << this->MaximumReported << "\n";
}
