// SPDX-License-Identifier: BSD-3-Clause
#include "vtkMSPolyhedralExampleReader.h"

#include "vtkMSEngineBridge.h"
#include "vtkMSPolyhedra.h"

#include "vtkFieldData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkIntArray.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPolyData.h"
#include "vtkStringArray.h"
#include "vtkXMLPolyDataReader.h"

#include "Core/Error.h"
#include "Formats/MeshFormats.h"
#include "Formats/VTKXMLCheck.h"

#include <cctype>
#include <sys/stat.h>

vtkStandardNewMacro(vtkMSPolyhedralExampleReader);

namespace
{

std::string Extension(const std::string& name)
{
  const auto dot = name.find_last_of('.');
  std::string ext = dot == std::string::npos ? "" : name.substr(dot + 1);
  for (auto& c : ext)
  {
    c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  }
  return ext;
}

/// "roof=2;wall=1" → {roof: 2, wall: 1}. @throw msynth::Error on a malformed entry.
msynth::ObjectTypeOptions ParseObjectTypes(const std::string& text)
{
  msynth::ObjectTypeOptions options;
  std::string entry;
  auto flush = [&]()
  {
    const auto begin = entry.find_first_not_of(" \t");
    if (begin == std::string::npos)
    {
      entry.clear();
      return;
    }
    const auto eq = entry.find('=');
    if (eq == std::string::npos)
    {
      throw msynth::Error("ObjectTypes entry '" + entry + "' is not name=type");
    }
    std::string name = entry.substr(begin, eq - begin);
    name.erase(name.find_last_not_of(" \t") + 1);
    const std::string value = entry.substr(eq + 1);
    char* end = nullptr;
    const long type = std::strtol(value.c_str(), &end, 10);
    if (end == value.c_str() || type < 1 || type > 32767)
    {
      throw msynth::Error("ObjectTypes entry '" + entry + "' needs a type in 1..32767");
    }
    options.TypeOfName[name] = static_cast<int>(type);
    entry.clear();
  };
  for (char c : text)
  {
    if (c == ';' || c == ',')
    {
      flush();
    }
    else
    {
      entry += c;
    }
  }
  flush();
  return options;
}

} // namespace

vtkMSPolyhedralExampleReader::vtkMSPolyhedralExampleReader()
{
  this->SetNumberOfInputPorts(0);
}

vtkMSPolyhedralExampleReader::~vtkMSPolyhedralExampleReader() = default;

int vtkMSPolyhedralExampleReader::CanReadFile(const char* name)
{
  if (!name)
  {
    return 0;
  }
  const std::string ext = Extension(name);
  return ext == "obj" || ext == "vtp" || ext == "ply" || ext == "stl";
}

int vtkMSPolyhedralExampleReader::RequestData(
  vtkInformation*, vtkInformationVector**, vtkInformationVector* outputVector)
{
  vtkPolyData* output = vtkPolyData::GetData(outputVector, 0);
  if (this->FileName.empty())
  {
    vtkErrorMacro(<< "No file name was given.");
    return 0;
  }
  struct stat info;
  if (::stat(this->FileName.c_str(), &info) != 0 || !S_ISREG(info.st_mode))
  {
    vtkErrorMacro(<< "'" << this->FileName << "': no such file.");
    return 0;
  }
  const std::string ext = Extension(this->FileName);
  try
  {
    msynth::PolyhedralExample example;
    if (ext == "obj")
    {
      example = msynth::ReadOBJExample(this->FileName, ParseObjectTypes(this->ObjectTypes));
    }
    else if (ext == "ply")
    {
      example = msynth::ReadPLYExample(this->FileName); // hardened: counts checked first
    }
    else if (ext == "stl")
    {
      example = msynth::ReadSTLExample(this->FileName);
    }
    else if (ext == "vtp")
    {
      msynth::CheckVTKXMLFile(this->FileName); // what VTK's reader trusts, first
      vtkNew<vtkXMLPolyDataReader> reader;
      reader->SetFileName(this->FileName.c_str());
      std::string messages;
      if (!vtkMSEngineBridge::Execute(reader, messages))
      {
        vtkErrorMacro(<< "'" << this->FileName << "': cannot be read as .vtp (" << messages << ")");
        return 0;
      }
      example = vtkMSPolyhedra::ToPolyhedralExample(reader->GetOutput(), this->FileName);
    }
    else
    {
      vtkErrorMacro(<< "'" << this->FileName << "': unknown extension '." << ext
                    << "' (expected .obj, .vtp, .ply or .stl).");
      return 0;
    }
    if (this->UpAxis == 1)
    {
      msynth::TurnYUpToZUp(example);
    }
    msynth::ValidateExample(example);
    vtkMSPolyhedra::FromPolyhedralExample(example, output);
    vtkNew<vtkStringArray> file;
    file->SetName("ExampleFile");
    file->InsertNextValue(this->FileName);
    output->GetFieldData()->AddArray(file);
    vtkNew<vtkIntArray> typeIds;
    typeIds->SetName("TypeIds");
    vtkNew<vtkStringArray> typeNames;
    typeNames->SetName("TypeNames");
    for (const auto& [type, name] : example.TypeNames)
    {
      typeIds->InsertNextValue(type);
      typeNames->InsertNextValue(name);
    }
    output->GetFieldData()->AddArray(typeIds);
    output->GetFieldData()->AddArray(typeNames);
    vtkNew<vtkStringArray> objectNames; // by ObjectId, for messages downstream
    objectNames->SetName("ObjectNames");
    for (const std::string& name : example.ObjectNames)
    {
      objectNames->InsertNextValue(name);
    }
    output->GetFieldData()->AddArray(objectNames);
  }
  catch (const std::exception& e)
  {
    output->Initialize();
    vtkErrorMacro(<< e.what());
    return 0;
  }
  return 1;
}

void vtkMSPolyhedralExampleReader::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "FileName: " << this->FileName << "\n";
  os << indent << "ObjectTypes: " << this->ObjectTypes << "\n";
  os << indent << "UpAxis: " << (this->UpAxis == 1 ? "y" : "z") << "\n";
}
