// SPDX-License-Identifier: BSD-3-Clause
#include "vtkMSEngineBridge.h"

#include "vtkAlgorithm.h"
#include "vtkCellArray.h"
#include "vtkCellArrayIterator.h"
#include "vtkCellData.h"
#include "vtkCommand.h"
#include "vtkDataArray.h"
#include "vtkDoubleArray.h"
#include "vtkExecutive.h"
#include "vtkFieldData.h"
#include "vtkIdList.h"
#include "vtkIdTypeArray.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkIntArray.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSmartPointer.h"
#include "vtkStreamingDemandDrivenPipeline.h"
#include "vtkStringArray.h"
#include "vtkType.h"
#include "vtkTypeInt64Array.h"

#include "Core/Error.h"

#include <cmath>
#include <cstdint>
#include <limits>
#include <map>
#include <vector>

vtkStandardNewMacro(vtkMSEngineBridge);

vtkMSEngineBridge::~vtkMSEngineBridge()
{
  this->Reset();
}

bool vtkMSEngineBridge::IsIntegerArray(vtkDataArray* array)
{
  switch (array ? array->GetDataType() : VTK_VOID)
  {
    case VTK_CHAR:
    case VTK_SIGNED_CHAR:
    case VTK_UNSIGNED_CHAR:
    case VTK_SHORT:
    case VTK_UNSIGNED_SHORT:
    case VTK_INT:
    case VTK_UNSIGNED_INT:
    case VTK_LONG:
    case VTK_UNSIGNED_LONG:
    case VTK_LONG_LONG:
    case VTK_UNSIGNED_LONG_LONG:
    case VTK_ID_TYPE:
      return true;
    default:
      return false;
  }
}

bool vtkMSEngineBridge::CheckLabelArray(
  vtkImageData* image, vtkDataArray* array, std::string& problem)
{
  if (!image || !array)
  {
    problem = "no label array";
    return false;
  }
  const std::string name = array->GetName() ? array->GetName() : "(unnamed)";
  if (!IsIntegerArray(array))
  {
    problem = "array '" + name + "' holds " + array->GetDataTypeAsString() +
      " values; labels must be integers";
    return false;
  }
  if (array->GetNumberOfComponents() != 1)
  {
    problem = "array '" + name + "' has " + std::to_string(array->GetNumberOfComponents()) +
      " components; labels need exactly one";
    return false;
  }
  if (array->GetNumberOfTuples() != image->GetNumberOfPoints())
  {
    problem = "array '" + name + "' has " + std::to_string(array->GetNumberOfTuples()) +
      " values for " + std::to_string(image->GetNumberOfPoints()) + " sites";
    return false;
  }
  if (image->GetNumberOfPoints() == 0)
  {
    problem = "the label grid has no sites";
    return false;
  }
  double range[2];
  array->GetRange(range, 0);
  if (range[0] < std::numeric_limits<std::int32_t>::min() ||
    range[1] > std::numeric_limits<std::int32_t>::max())
  {
    problem = "array '" + name + "' has values outside the 32-bit integer range";
    return false;
  }
  return true;
}

vtkDataArray* vtkMSEngineBridge::FindLabelArray(vtkImageData* image, vtkDataArray* selected)
{
  if (selected || !image)
  {
    return selected;
  }
  vtkDataArray* labels = image->GetPointData()->GetArray("Label");
  return labels ? labels : image->GetPointData()->GetScalars();
}

bool vtkMSEngineBridge::ReadLabels(
  vtkImageData* image, vtkDataArray* selected, msynth::LabelGrid& grid, std::string& problem)
{
  vtkDataArray* labels = image ? FindLabelArray(image, selected) : nullptr;
  if (!labels)
  {
    problem = "the image has no label array (point array 'Label' or the active scalars)";
    return false;
  }
  if (!CheckLabelArray(image, labels, problem))
  {
    return false;
  }
  grid = ToLabelGrid(image, labels);
  return true;
}

msynth::LabelGrid vtkMSEngineBridge::ToLabelGrid(vtkImageData* image, vtkDataArray* labels)
{
  int dims[3];
  image->GetDimensions(dims);
  std::vector<msynth::Label> values(static_cast<std::size_t>(labels->GetNumberOfTuples()));
  for (vtkIdType i = 0; i < labels->GetNumberOfTuples(); ++i)
  {
    values[static_cast<std::size_t>(i)] = static_cast<msynth::Label>(labels->GetTuple1(i));
  }
  return msynth::LabelGrid({ { dims[0], dims[1], dims[2] } }, std::move(values));
}

vtkIntArray* vtkMSEngineBridge::NewLabelArray(const msynth::LabelGrid& grid, const char* name)
{
  vtkIntArray* array = vtkIntArray::New();
  array->SetName(name);
  array->SetNumberOfTuples(grid.NumberOfSites());
  std::copy(grid.Data().begin(), grid.Data().end(), array->GetPointer(0));
  return array;
}

bool vtkMSEngineBridge::Execute(
  vtkAlgorithm* algorithm, std::string& messages, bool informationOnly)
{
  vtkNew<vtkMSEngineBridge> errors;
  errors->Watch(algorithm);
  vtkExecutive* executive = algorithm->GetExecutive();
  int status = 0;
  std::string thrown;
  try
  {
    // A third-party reader may throw (std::bad_alloc for a size read from a damaged file):
    // that is a failed update, not the end of the process.
    status = informationOnly ? executive->UpdateInformation() : executive->Update();
  }
  catch (const std::bad_alloc&)
  {
    thrown = std::string(algorithm->GetClassName()) + " ran out of memory (a damaged file?)";
  }
  catch (const std::exception& e)
  {
    thrown = std::string(algorithm->GetClassName()) + " failed: " + e.what();
  }
  const bool ok = status != 0 && !errors->HasErrors() && thrown.empty();
  messages = errors->GetMessages() + thrown;
  if (!ok && messages.empty())
  {
    messages = std::string(algorithm->GetClassName()) + " failed";
  }
  return ok;
}

int vtkMSEngineBridge::UpdatePiece(vtkInformation* outInfo)
{
  return outInfo->Has(vtkStreamingDemandDrivenPipeline::UPDATE_PIECE_NUMBER())
    ? outInfo->Get(vtkStreamingDemandDrivenPipeline::UPDATE_PIECE_NUMBER())
    : 0;
}

void vtkMSEngineBridge::RequestWholeExtentOnPieceZero(vtkInformation* inInfo, int piece)
{
  if (piece == 0)
  {
    int whole[6];
    inInfo->Get(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), whole);
    inInfo->Set(vtkStreamingDemandDrivenPipeline::UPDATE_EXTENT(), whole, 6);
  }
  else
  {
    const int empty[6] = { 0, -1, 0, -1, 0, -1 };
    inInfo->Set(vtkStreamingDemandDrivenPipeline::UPDATE_EXTENT(), empty, 6);
  }
  inInfo->Set(vtkStreamingDemandDrivenPipeline::EXACT_EXTENT(), 1);
}

void vtkMSEngineBridge::Watch(vtkObject* source)
{
  this->Reset();
  this->Source = source;
  this->Tag = source->AddObserver(vtkCommand::ErrorEvent, this, &vtkMSEngineBridge::OnError);
}

void vtkMSEngineBridge::Reset()
{
  if (this->Source)
  {
    this->Source->RemoveObserver(this->Tag);
  }
  this->Source = nullptr;
  this->Messages.clear();
}

void vtkMSEngineBridge::OnError(vtkObject*, unsigned long, void* data)
{
  std::string message = data ? static_cast<const char*>(data) : "unknown error";
  // VTK prefixes messages with "ERROR: In <file>, line N\n<class> (<address>): "; keep the text.
  const auto pos = message.rfind("): ");
  if (pos != std::string::npos)
  {
    message = message.substr(pos + 3);
  }
  while (!message.empty() && (message.back() == '\n' || message.back() == ' '))
  {
    message.pop_back();
  }
  if (!this->Messages.empty())
  {
    this->Messages += "; ";
  }
  this->Messages += message;
}

msynth::PolyhedralExample vtkMSEngineBridge::ToPolyhedralExample(
  vtkPolyData* polygons, const std::string& name)
{
  msynth::PolyhedralExample example;
  example.Source = name;
  if (!polygons || !polygons->GetPolys() || polygons->GetNumberOfPolys() == 0)
  {
    throw msynth::Error::InFile(name, "has no polygons");
  }
  // Readable type names, as the example reader stores them (TypeIds[i] is named TypeNames[i]).
  auto* typeIds = vtkDataArray::SafeDownCast(polygons->GetFieldData()->GetAbstractArray("TypeIds"));
  auto* typeNames =
    vtkStringArray::SafeDownCast(polygons->GetFieldData()->GetAbstractArray("TypeNames"));
  if (typeIds && typeNames && typeIds->GetNumberOfValues() == typeNames->GetNumberOfValues())
  {
    for (vtkIdType i = 0; i < typeIds->GetNumberOfValues(); ++i)
    {
      example.TypeNames[static_cast<int>(typeIds->GetTuple1(i))] = typeNames->GetValue(i);
    }
  }
  const vtkIdType numberOfPoints = polygons->GetNumberOfPoints();
  example.Points.resize(static_cast<std::size_t>(numberOfPoints));
  for (vtkIdType i = 0; i < numberOfPoints; ++i)
  {
    double p[3];
    polygons->GetPoint(i, p);
    example.Points[i] = { p[0], p[1], p[2] };
  }
  // Polygons come after vertices and lines in cell order; only polygons are faces.
  const vtkIdType firstPoly = polygons->GetNumberOfVerts() + polygons->GetNumberOfLines();
  vtkDataArray* types = polygons->GetCellData()->GetArray("ObjectType");
  vtkDataArray* ids = polygons->GetCellData()->GetArray("ObjectId");
  std::vector<int> faceTypes;
  std::vector<int> faceIds;
  vtkNew<vtkIdList> cell;
  auto iterator = vtk::TakeSmartPointer(polygons->GetPolys()->NewIterator());
  vtkIdType index = firstPoly;
  for (iterator->GoToFirstCell(); !iterator->IsDoneWithTraversal();
       iterator->GoToNextCell(), ++index)
  {
    iterator->GetCurrentCell(cell);
    std::vector<int> face;
    for (vtkIdType k = 0; k < cell->GetNumberOfIds(); ++k)
    {
      face.push_back(static_cast<int>(cell->GetId(k)));
    }
    example.Faces.push_back(std::move(face));
    const double type = types ? types->GetComponent(index, 0) : 1.0;
    if (!(type >= 1 && type <= 32767) || type != static_cast<int>(type))
    {
      throw msynth::Error::InFile(name,
        "polygon " + std::to_string(index - firstPoly) + " has ObjectType " + std::to_string(type) +
          "; types are integers 1..32767");
    }
    faceTypes.push_back(static_cast<int>(type));
    if (ids)
    {
      const double id = ids->GetComponent(index, 0);
      if (!(id >= 0 && id < 1e9) || id != static_cast<int>(id))
      {
        throw msynth::Error::InFile(
          name, "polygon " + std::to_string(index - firstPoly) + " has an invalid ObjectId");
      }
      faceIds.push_back(static_cast<int>(id));
    }
  }
  if (!ids)
  {
    msynth::AssignObjectsByConnectivity(example, faceTypes);
    return example;
  }
  // Renumber the given object ids densely, in order of appearance.
  std::map<int, int> dense;
  for (std::size_t f = 0; f < faceIds.size(); ++f)
  {
    auto it = dense.find(faceIds[f]);
    if (it == dense.end())
    {
      it = dense.emplace(faceIds[f], example.NumberOfObjects()).first;
      example.ObjectTypes.push_back(faceTypes[f]);
      example.ObjectNames.push_back("object " + std::to_string(faceIds[f]));
    }
    else if (example.ObjectTypes[it->second] != faceTypes[f])
    {
      throw msynth::Error::InFile(
        name, "object " + std::to_string(faceIds[f]) + " has polygons of different ObjectType");
    }
    example.FaceObject.push_back(it->second);
  }
  return example;
}

void vtkMSEngineBridge::FromPolyhedralExample(
  const msynth::PolyhedralExample& example, vtkPolyData* output)
{
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  points->SetNumberOfPoints(static_cast<vtkIdType>(example.Points.size()));
  for (std::size_t i = 0; i < example.Points.size(); ++i)
  {
    points->SetPoint(static_cast<vtkIdType>(i), example.Points[i].data());
  }
  vtkNew<vtkCellArray> polys;
  vtkNew<vtkIntArray> types;
  types->SetName("ObjectType");
  vtkNew<vtkIntArray> ids;
  ids->SetName("ObjectId");
  for (std::size_t f = 0; f < example.Faces.size(); ++f)
  {
    polys->InsertNextCell(static_cast<vtkIdType>(example.Faces[f].size()));
    for (int v : example.Faces[f])
    {
      polys->InsertCellPoint(v);
    }
    types->InsertNextValue(example.ObjectTypes[example.FaceObject[f]]);
    ids->InsertNextValue(example.FaceObject[f]);
  }
  output->Initialize();
  output->SetPoints(points);
  output->SetPolys(polys);
  output->GetCellData()->AddArray(types);
  output->GetCellData()->AddArray(ids);
}

std::string vtkMSEngineBridge::ExampleName(vtkDataObject* data)
{
  if (data)
  {
    if (auto* file =
          vtkStringArray::SafeDownCast(data->GetFieldData()->GetAbstractArray("ExampleFile")))
    {
      if (file->GetNumberOfValues() > 0 && !file->GetValue(0).empty())
      {
        return file->GetValue(0);
      }
    }
  }
  return "the input";
}

msynth::PolyhedralAnalysis vtkMSEngineBridge::AnalyzeExample(vtkPolyData* polygons,
  double angleToleranceDegrees, int maximumSmallInteger, msynth::PolyhedralExample& example)
{
  example =
    vtkMSEngineBridge::ToPolyhedralExample(polygons, vtkMSEngineBridge::ExampleName(polygons));
  msynth::ValidateExample(example);
  msynth::PolyhedralAnalysis::Options options;
  options.AngleTolerance = angleToleranceDegrees * 3.14159265358979323846 / 180.0;
  options.MaxSmallInteger = maximumSmallInteger;
  return msynth::PolyhedralAnalysis::Analyze(example, options);
}

void vtkMSEngineBridge::StoreArrangement(const ArrangementRecord& record, vtkFieldData* fields)
{
  const auto& p = record.Parameters;
  const auto doubles = [&](const char* name, std::initializer_list<double> values)
  {
    vtkNew<vtkDoubleArray> a;
    a->SetName(name);
    for (double v : values)
    {
      a->InsertNextValue(v);
    }
    fields->AddArray(a);
  };
  const auto integers = [&](
                          const char* name, const std::vector<std::int64_t>& values, int components)
  {
    vtkNew<vtkTypeInt64Array> a;
    a->SetName(name);
    a->SetNumberOfComponents(components);
    for (auto v : values)
    {
      a->InsertNextValue(v);
    }
    fields->AddArray(a);
  };
  doubles("ArrangementOrigin", { p.Origin[0], p.Origin[1], p.Origin[2] });
  doubles("ArrangementQuantum", { p.Quantum });
  doubles("AngleTolerance", { record.AngleToleranceDegrees });
  integers("ArrangementBox",
    { p.BoxLow[0], p.BoxLow[1], p.BoxLow[2], p.BoxHigh[0], p.BoxHigh[1], p.BoxHigh[2] }, 1);
  std::vector<std::int64_t> normals;
  for (const auto& n : record.Normals)
  {
    normals.insert(normals.end(), n.begin(), n.end());
  }
  integers("FamilyNormals", normals, 3);
  integers("FamilyOffsets", p.Offsets, 1);
  integers("FamilySpacings", p.Spacings, 1);
  integers("Planar", { p.Planar ? 1 : 0 }, 1);
  integers("MaximumSmallInteger", { record.MaximumSmallInteger }, 1);
  integers("MaximumVertices", { p.MaxVertices }, 1);
}

vtkMSEngineBridge::ArrangementRecord vtkMSEngineBridge::LoadArrangement(
  vtkFieldData* fields, const std::string& where)
{
  const auto array = [&](const char* name, vtkIdType minimum) -> vtkDataArray*
  {
    vtkDataArray* a = fields ? fields->GetArray(name) : nullptr;
    if (!a || a->GetNumberOfValues() < minimum)
    {
      throw msynth::Error(where + ": field data array '" + std::string(name) +
        "' is missing or too short; the input must come from the ModelSynth Plane Arrangement "
        "filter");
    }
    return a;
  };
  const auto integer = [](vtkDataArray* a, vtkIdType i)
  { return static_cast<std::int64_t>(a->GetVariantValue(i).ToTypeInt64()); };
  ArrangementRecord r;
  auto& p = r.Parameters;
  vtkDataArray* origin = array("ArrangementOrigin", 3);
  for (int c = 0; c < 3; ++c)
  {
    p.Origin[static_cast<std::size_t>(c)] = origin->GetComponent(c, 0);
  }
  p.Quantum = array("ArrangementQuantum", 1)->GetTuple1(0);
  r.AngleToleranceDegrees = array("AngleTolerance", 1)->GetTuple1(0);
  vtkDataArray* box = array("ArrangementBox", 6);
  for (int c = 0; c < 3; ++c)
  {
    p.BoxLow[c] = integer(box, c);
    p.BoxHigh[c] = integer(box, c + 3);
  }
  vtkDataArray* normals = array("FamilyNormals", 3);
  vtkDataArray* offsets = array("FamilyOffsets", 1);
  vtkDataArray* spacings = array("FamilySpacings", 1);
  const vtkIdType m = normals->GetNumberOfValues() / 3;
  if (normals->GetNumberOfValues() != 3 * m || offsets->GetNumberOfValues() != m ||
    spacings->GetNumberOfValues() != m)
  {
    throw msynth::Error(where + ": the arrangement's family arrays disagree in length");
  }
  for (vtkIdType f = 0; f < m; ++f)
  {
    r.Normals.push_back(
      { integer(normals, 3 * f), integer(normals, 3 * f + 1), integer(normals, 3 * f + 2) });
    p.Offsets.push_back(integer(offsets, f));
    p.Spacings.push_back(integer(spacings, f));
  }
  p.Planar = integer(array("Planar", 1), 0) != 0;
  r.MaximumSmallInteger = static_cast<int>(integer(array("MaximumSmallInteger", 1), 0));
  p.MaxVertices = integer(array("MaximumVertices", 1), 0);
  if (!(p.Quantum > 0))
  {
    throw msynth::Error(where + ": the arrangement's quantum is not positive");
  }
  return r;
}

void vtkMSEngineBridge::SetOutputLabelGrid(
  vtkInformation* inInfo, vtkInformation* outInfo, const int size[3])
{
  const int extent[6] = { 0, size[0] - 1, 0, size[1] - 1, 0, size[2] - 1 };
  outInfo->Set(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), extent, 6);
  double spacing[3] = { 1, 1, 1 }, origin[3] = { 0, 0, 0 };
  if (inInfo && inInfo->Has(vtkDataObject::SPACING()))
  {
    inInfo->Get(vtkDataObject::SPACING(), spacing);
  }
  if (inInfo && inInfo->Has(vtkDataObject::ORIGIN()))
  {
    inInfo->Get(vtkDataObject::ORIGIN(), origin);
  }
  outInfo->Set(vtkDataObject::SPACING(), spacing, 3);
  outInfo->Set(vtkDataObject::ORIGIN(), origin, 3);
  vtkDataObject::SetPointDataActiveScalarInfo(outInfo, VTK_INT, 1);
}

void vtkMSEngineBridge::SetTimeSteps(vtkInformation* outInfo, std::size_t count)
{
  outInfo->Remove(vtkStreamingDemandDrivenPipeline::TIME_STEPS());
  outInfo->Remove(vtkStreamingDemandDrivenPipeline::TIME_RANGE());
  if (count == 0)
  {
    return;
  }
  std::vector<double> times(count);
  for (std::size_t i = 0; i < count; ++i)
  {
    times[i] = static_cast<double>(i);
  }
  outInfo->Set(
    vtkStreamingDemandDrivenPipeline::TIME_STEPS(), times.data(), static_cast<int>(count));
  const double range[2] = { 0.0, times.back() };
  outInfo->Set(vtkStreamingDemandDrivenPipeline::TIME_RANGE(), range, 2);
}

std::size_t vtkMSEngineBridge::RequestedStep(vtkInformation* outInfo, std::size_t count)
{
  const auto last = static_cast<double>(count - 1);
  double t = last;
  if (outInfo->Has(vtkStreamingDemandDrivenPipeline::UPDATE_TIME_STEP()))
  {
    t = outInfo->Get(vtkStreamingDemandDrivenPipeline::UPDATE_TIME_STEP());
  }
  return static_cast<std::size_t>(std::min(std::max(std::floor(t + 0.5), 0.0), last));
}

msynth::ContinuousMesh vtkMSEngineBridge::ToContinuousMesh(
  vtkPolyData* model, const std::string& name)
{
  vtkDataArray* object = model->GetCellData()->GetArray("ObjectType");
  vtkDataArray* inside = object ? object : model->GetCellData()->GetArray("InsideType");
  vtkDataArray* outside = model->GetCellData()->GetArray("OutsideType");
  if (!inside || (!object && !outside))
  {
    throw msynth::Error::InFile(name,
      "not a continuous model: it needs cell arrays InsideType "
      "and OutsideType (3D) or ObjectType (2D)");
  }
  std::vector<msynth::Point3> points(static_cast<std::size_t>(model->GetNumberOfPoints()));
  for (vtkIdType i = 0; i < model->GetNumberOfPoints(); ++i)
  {
    model->GetPoint(i, points[static_cast<std::size_t>(i)].data());
  }
  std::vector<std::vector<std::int32_t>> polygons;
  std::vector<std::int32_t> in, out;
  auto it = vtk::TakeSmartPointer(model->GetPolys()->NewIterator());
  vtkIdType cell = model->GetNumberOfVerts() + model->GetNumberOfLines();
  for (it->GoToFirstCell(); !it->IsDoneWithTraversal(); it->GoToNextCell(), ++cell)
  {
    vtkIdType n;
    const vtkIdType* ids;
    it->GetCurrentCell(n, ids);
    polygons.emplace_back(ids, ids + n);
    in.push_back(static_cast<std::int32_t>(inside->GetTuple1(cell)));
    if (!object)
    {
      out.push_back(static_cast<std::int32_t>(outside->GetTuple1(cell)));
    }
  }
  try
  {
    return msynth::MeshFromPolygons(
      object != nullptr, std::move(points), std::move(polygons), std::move(in), std::move(out));
  }
  catch (const msynth::Error& e)
  {
    throw msynth::Error::InFile(name, e.what());
  }
}

void vtkMSEngineBridge::AddStatistics(vtkFieldData* fields,
  const msynth::SynthesisStatistics& statistics, msynth::SynthesisStatus status,
  const std::string& message)
{
  for (const auto& f : msynth::StatisticsFields(statistics))
  {
    if (f.Integer)
      AddFieldValue<vtkIdTypeArray>(fields, f.Name.c_str(), static_cast<vtkIdType>(f.Value));
    else
      AddFieldValue<vtkDoubleArray>(fields, f.Name.c_str(), f.Value);
  }
  AddFieldValue<vtkStringArray>(fields, "Status", std::string(msynth::ToString(status)));
  AddFieldValue<vtkStringArray>(fields, "Message", message);
  if (statistics.TrivialLabel)
    AddFieldValue<vtkIntArray>(fields, "TrivialLabel", *statistics.TrivialLabel);
  vtkNew<vtkIdTypeArray> origins, sites;
  origins->SetName("FailedBlockOrigins");
  origins->SetNumberOfComponents(3);
  sites->SetName("FailedBlockSites");
  sites->SetNumberOfComponents(3);
  for (const auto& f : statistics.Failures)
  {
    const vtkIdType o[3] = { f.Origin[0], f.Origin[1], f.Origin[2] };
    const vtkIdType e[3] = { f.EmptySite[0], f.EmptySite[1], f.EmptySite[2] };
    origins->InsertNextTypedTuple(o);
    sites->InsertNextTypedTuple(e);
  }
  fields->AddArray(origins);
  fields->AddArray(sites);
}
