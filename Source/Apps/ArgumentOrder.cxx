// SPDX-License-Identifier: BSD-3-Clause
// Files msynth wrote, told from examples by what they hold (a label grid's or model's field data
// naming its example, a picture's text chunk), and `msynth check` and `quality` refusing a model
// given where the example goes.
#include "Common.h"
#include "Examples.h"
#include "InfoFiles.h"

#include "vtkDataArraySelection.h"
#include "vtkFieldData.h"
#include "vtkImageData.h"
#include "vtkPolyData.h"
#include "vtkStringArray.h"
#include "vtkXMLImageDataReader.h"
#include "vtkXMLPolyDataReader.h"

#include "Formats/Image.h"
#include "Formats/VTKXMLCheck.h"

#include <sys/stat.h>

namespace msynth
{
namespace cli
{

vtkSmartPointer<vtkPolyData> WrittenModel(const std::string& path)
{
  if (LowerExtension(path) != ".vtp")
    return nullptr;
  msynth::CheckVTKXMLFile(path);
  vtkNew<vtkXMLPolyDataReader> reader;
  reader->SetFileName(path.c_str());
  Run(reader);
  vtkPolyData* model = reader->GetOutput();
  if (!vtkStringArray::SafeDownCast(model->GetFieldData()->GetAbstractArray("ExampleFile")))
    return nullptr;
  return model;
}

std::string WrittenFrom(const std::string& path)
{
  if (LowerExtension(path) != ".vti")
    return "";
  msynth::CheckVTKXMLFile(path);
  vtkNew<vtkXMLImageDataReader> reader;
  reader->SetFileName(path.c_str());
  reader->UpdateInformation();
  reader->GetPointDataArraySelection()->DisableAllArrays();
  reader->GetCellDataArraySelection()->DisableAllArrays();
  Run(reader);
  vtkFieldData* fd = reader->GetOutput()->GetFieldData();
  if (!fd->GetArray("Seed"))
    return "";
  // A label grid's, a tileset's or an image sample's model.
  for (const char* name : { "ExampleFile", "TilesetFile", "SampleFile" })
    if (auto* example = vtkStringArray::SafeDownCast(fd->GetAbstractArray(name)))
      if (example->GetNumberOfValues() > 0 && !example->GetValue(0).empty())
        return example->GetValue(0);
  return "";
}

std::string WrittenExample(const std::string& path)
{
  if (LowerExtension(path) == ".vtp")
    if (const auto model = WrittenModel(path))
      return vtkStringArray::SafeDownCast(model->GetFieldData()->GetAbstractArray("ExampleFile"))
        ->GetValue(0);
  return WrittenFrom(path);
}

namespace
{
/// What msynth wrote @p path as ("a model msynth wrote from E", "a picture msynth wrote", "the
/// pieces of a streamed model"), or "" when it is not a file msynth wrote or that cannot be told
/// (.txt, .vox) or read (the command's own checks then say why).
std::string WrittenAs(const std::string& path)
{
  try
  {
    const std::string ext = LowerExtension(path);
    if (ext == ".pvti")
      return "the pieces of a model msynth streamed";
    if (ext == ".png")
      return msynth::IsWrittenPng(path) ? "a picture msynth wrote" : "";
    const std::string from = WrittenExample(path);
    return from.empty() ? "" : "a model msynth wrote from " + from;
  }
  catch (const std::exception&)
  {
    return "";
  }
}

/// The kind of example @p path is by its extension when it can only be an example ("" else).
std::string ExampleOnly(const std::string& path)
{
  const std::string ext = LowerExtension(path);
  if (ext == ".xml")
    return "a tileset";
  if (ext == ".obj" || ext == ".ply" || ext == ".stl")
    return "a polyhedron";
  return "";
}

bool Exists(const std::string& path)
{
  struct stat info;
  return ::stat(path.c_str(), &info) == 0 && S_ISREG(info.st_mode);
}
} // namespace

void CheckOrder(
  const std::string& usage, const std::vector<std::string>& examples, const std::string& model)
{
  if (!Exists(model))
    return; // the command's own check names the missing file
  const std::string modelKind = ExampleOnly(model);
  const bool modelWritten = !WrittenAs(model).empty();
  for (const std::string& example : examples)
  {
    if (!Exists(example))
      continue;
    const std::string exampleWritten = WrittenAs(example);
    // A model where the example goes: an example where the model goes, or a file msynth wrote
    // as the example of one it did not (two models of msynth may be compared).
    std::string what;
    if (!modelKind.empty() && ExampleOnly(example).empty())
      what = "'" + model + "' is an example (" + modelKind + ")" +
        (exampleWritten.empty() ? "" : " and '" + example + "' is " + exampleWritten);
    else if (!exampleWritten.empty() && !modelWritten)
      what = "'" + example + "' is " + exampleWritten + " and '" + model + "' is not";
    if (what.empty())
      continue;
    std::string swapped;
    for (const std::string& other : examples)
      swapped += " " + (other == example ? model : other);
    throw UsageError{ what + ": the order is msynth " + usage + " (msynth " +
      usage.substr(0, usage.find(' ')) + swapped + " " + example + ")" };
  }
}

} // namespace cli
} // namespace msynth
