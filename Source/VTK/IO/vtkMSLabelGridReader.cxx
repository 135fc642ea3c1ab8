// SPDX-License-Identifier: BSD-3-Clause
#include "vtkMSLabelGridReader.h"

#include "vtkMSEngineBridge.h"
#include "vtkMSFieldData.h"
#include "vtkMSLabelArrays.h"

#include "vtkCellData.h"
#include "vtkDataArraySelection.h"
#include "vtkErrorCode.h"
#include "vtkFieldData.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkIntArray.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkStreamingDemandDrivenPipeline.h"
#include "vtkStringArray.h"
#include "vtkUnsignedCharArray.h"
#include "vtkXMLImageDataReader.h"

#include "Formats/TextModel.h"
#include "Formats/VTKXMLCheck.h"
#include "Formats/VoxModel.h"

#include <array>
#include <cctype>

#include <sys/stat.h>

vtkStandardNewMacro(vtkMSLabelGridReader);

struct vtkMSLabelGridReader::Internals
{
  std::string Key;        ///< file name, size and time of the cached model
  msynth::TextModel Text; ///< .txt and .vox files (Grid; Pieces for .txt)
  std::vector<std::array<std::uint8_t, 4>> Palette; ///< .vox files
  int VoxModels = 0;      ///< how many models the .vox file holds (0 for other files)
  std::string CheckedKey; ///< file name, size and time of the last .vti that passed the check
};

namespace
{
bool EndsWith(const std::string& s, const char* suffix)
{
  const std::string x(suffix);
  if (s.size() < x.size())
  {
    return false;
  }
  for (std::size_t i = 0; i < x.size(); ++i)
  {
    if (std::tolower(static_cast<unsigned char>(s[s.size() - x.size() + i])) != x[i])
    {
      return false;
    }
  }
  return true;
}
} // namespace

vtkMSLabelGridReader::vtkMSLabelGridReader()
  : Reader(vtkSmartPointer<vtkXMLImageDataReader>::New())
  , Internal(new Internals)
{
  this->SetNumberOfInputPorts(0);
  this->SetNumberOfOutputPorts(2);
}

int vtkMSLabelGridReader::FillOutputPortInformation(int port, vtkInformation* info)
{
  info->Set(vtkDataObject::DATA_TYPE_NAME(), port == 0 ? "vtkImageData" : "vtkPolyData");
  return 1;
}

vtkPolyData* vtkMSLabelGridReader::GetGeometryOutput()
{
  return vtkPolyData::SafeDownCast(this->GetOutputDataObject(1));
}

vtkMSLabelGridReader::~vtkMSLabelGridReader()
{
  delete this->Internal;
}

int vtkMSLabelGridReader::CanReadFile(const char* name)
{
  if (!name)
  {
    return 0;
  }
  const std::string s(name);
  return EndsWith(s, ".vti") || EndsWith(s, ".txt") || EndsWith(s, ".vox") ? 1 : 0;
}

bool vtkMSLabelGridReader::ReadText()
{
  struct stat info;
  ::stat(this->FileName.c_str(), &info);
  const std::string key = this->FileName + '\n' + std::to_string(info.st_size) + '\n' +
    std::to_string(info.st_mtime) + '\n' + std::to_string(this->MaximumNumberOfSites) +
    (this->VoxScene ? "\nscene" : "");
  if (key == this->Internal->Key)
  {
    return true;
  }
  this->Internal->Key.clear();
  try
  {
    this->Internal->Palette.clear();
    this->Internal->VoxModels = 0;
    if (EndsWith(this->FileName, ".vox"))
    {
      msynth::VoxModel vox = this->VoxScene
        ? msynth::ReadVoxSceneFile(this->FileName, this->MaximumNumberOfSites)
        : msynth::ReadVoxModelFile(this->FileName, this->MaximumNumberOfSites);
      if (vox.NumberOfModels > 1 && !this->VoxScene)
      {
        vtkWarningMacro(<< "'" << this->FileName << "': holds " << vox.NumberOfModels
                        << " models; only the first is read.");
      }
      this->Internal->Text = msynth::TextModel();
      this->Internal->Text.Grid = std::move(vox.Grid);
      this->Internal->Palette = std::move(vox.Palette);
      this->Internal->VoxModels = vox.NumberOfModels;
    }
    else
    {
      this->Internal->Text = msynth::ReadTextModelFile(this->FileName, this->MaximumNumberOfSites);
      if (!this->Internal->Text.ObjectsProblem.empty())
      {
        vtkWarningMacro(<< "'" << this->FileName << "', " << this->Internal->Text.ObjectsProblem);
      }
    }
  }
  catch (const std::exception& e)
  {
    vtkErrorMacro(<< e.what());
    this->SetErrorCode(vtkErrorCode::FileFormatError);
    return false;
  }
  this->Internal->Key = key;
  return true;
}

void vtkMSLabelGridReader::Fail(const std::string& problem)
{
  vtkErrorMacro(<< "'" << this->FileName << "': " << problem);
  this->SetErrorCode(vtkErrorCode::FileFormatError);
}

bool vtkMSLabelGridReader::ReadHeader()
{
  this->SetErrorCode(vtkErrorCode::NoError);
  if (this->FileName.empty())
  {
    vtkErrorMacro(<< "No file name was given.");
    this->SetErrorCode(vtkErrorCode::NoFileNameError);
    return false;
  }
  struct stat info;
  if (::stat(this->FileName.c_str(), &info) != 0 || !S_ISREG(info.st_mode))
  {
    vtkErrorMacro(<< "'" << this->FileName << "': no such file.");
    this->SetErrorCode(vtkErrorCode::FileNotFoundError);
    return false;
  }
  this->IsText = EndsWith(this->FileName, ".txt") || EndsWith(this->FileName, ".vox");
  if (this->IsText)
  {
    return this->ReadText();
  }
  // What VTK's XML reader trusts is checked first (msynth/VTKXMLCheck.h): it crashes on some
  // damaged files instead of failing.
  const std::string key =
    this->FileName + '\n' + std::to_string(info.st_size) + '\n' + std::to_string(info.st_mtime);
  if (key != this->Internal->CheckedKey)
  {
    try
    {
      msynth::CheckVTKXMLFile(this->FileName);
    }
    catch (const std::exception& e)
    {
      // "'path': problem" -> "'path': not a readable VTK image data (.vti) file: problem"
      const std::string what = e.what(), prefix = "'" + this->FileName + "': ";
      this->Fail("not a readable VTK image data (.vti) file: " +
        (what.compare(0, prefix.size(), prefix) == 0 ? what.substr(prefix.size()) : what));
      return false;
    }
    this->Internal->CheckedKey = key;
  }
  this->Reader->SetFileName(this->FileName.c_str());
  std::string messages;
  if (!vtkMSEngineBridge::Execute(this->Reader, messages, /*informationOnly=*/true))
  {
    this->Fail("not a readable VTK image data (.vti) file: " + messages);
    return false;
  }
  vtkDataArraySelection* points = this->Reader->GetPointDataArraySelection();
  vtkDataArraySelection* cells = this->Reader->GetCellDataArraySelection();
  if (points->ArrayExists(this->LabelArrayName.c_str()))
  {
    this->LabelsOnCells = false;
  }
  else if (cells->ArrayExists(this->LabelArrayName.c_str()))
  {
    this->LabelsOnCells = true;
  }
  else
  {
    std::string present;
    for (int i = 0; i < points->GetNumberOfArrays(); ++i)
    {
      present += std::string(present.empty() ? "" : ", ") + points->GetArrayName(i);
    }
    for (int i = 0; i < cells->GetNumberOfArrays(); ++i)
    {
      present += std::string(present.empty() ? "" : ", ") + cells->GetArrayName(i);
    }
    this->Fail("has no label array '" + this->LabelArrayName +
      "' (arrays present: " + (present.empty() ? std::string("none") : present) + ")");
    return false;
  }
  // Read only the label array.
  points->DisableAllArrays();
  cells->DisableAllArrays();
  (this->LabelsOnCells ? cells : points)->EnableArray(this->LabelArrayName.c_str());
  return true;
}

int vtkMSLabelGridReader::RequestInformation(
  vtkInformation*, vtkInformationVector**, vtkInformationVector* outputVector)
{
  // The geometry (port 1) comes in pieces: a slab of the sites each.
  outputVector->GetInformationObject(1)->Set(CAN_HANDLE_PIECE_REQUEST(), 1);
  if (!this->ReadHeader())
  {
    return 0;
  }
  int extent[6];
  double origin[3], spacing[3];
  if (this->IsText)
  {
    const auto& d = this->Internal->Text.Grid.Dimensions();
    vtkInformation* outInfo = outputVector->GetInformationObject(0);
    const int whole[6] = { 0, static_cast<int>(d[0]) - 1, 0, static_cast<int>(d[1]) - 1, 0,
      static_cast<int>(d[2]) - 1 };
    const double unit[3] = { 1, 1, 1 }, zero[3] = { 0, 0, 0 };
    outInfo->Set(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), whole, 6);
    outInfo->Set(vtkDataObject::ORIGIN(), zero, 3);
    outInfo->Set(vtkDataObject::SPACING(), unit, 3);
    vtkDataObject::SetPointDataActiveScalarInfo(outInfo, VTK_INT, 1);
    return 1;
  }
  vtkInformation* fileInfo = this->Reader->GetOutputInformation(0);
  fileInfo->Get(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), extent);
  fileInfo->Get(vtkDataObject::ORIGIN(), origin);
  fileInfo->Get(vtkDataObject::SPACING(), spacing);
  if (this->LabelsOnCells)
  {
    // One site per cell, at the cell center: axes with cells lose one point.
    for (int a = 0; a < 3; ++a)
    {
      if (extent[2 * a + 1] > extent[2 * a])
      {
        extent[2 * a + 1] -= 1;
        origin[a] += 0.5 * spacing[a];
      }
    }
  }
  vtkIdType sites = 1;
  for (int a = 0; a < 3; ++a)
  {
    const vtkIdType n = vtkIdType(extent[2 * a + 1]) - extent[2 * a] + 1;
    if (n < 1)
    {
      this->Fail("has an empty extent");
      return 0;
    }
    if (n > this->MaximumNumberOfSites / sites)
    {
      this->Fail("declares more than the maximum of " + std::to_string(this->MaximumNumberOfSites) +
        " sites");
      return 0;
    }
    sites *= n;
  }
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  outInfo->Set(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), extent, 6);
  outInfo->Set(vtkDataObject::ORIGIN(), origin, 3);
  outInfo->Set(vtkDataObject::SPACING(), spacing, 3);
  vtkDataObject::SetPointDataActiveScalarInfo(outInfo, VTK_INT, 1);
  return 1;
}

namespace
{
/// A model of the original program's text format (or a .vox model) as a label image, with what
/// the file says of its labels as field data: piece names, the trailer, the palette.
void FillFromTextModel(vtkImageData* output, const msynth::TextModel& text,
  const std::vector<std::array<std::uint8_t, 4>>& colours)
{
  const auto& d = text.Grid.Dimensions();
  output->SetExtent(
    0, static_cast<int>(d[0]) - 1, 0, static_cast<int>(d[1]) - 1, 0, static_cast<int>(d[2]) - 1);
  output->SetOrigin(0, 0, 0);
  output->SetSpacing(1, 1, 1);
  vtkSmartPointer<vtkIntArray> labels;
  labels.TakeReference(vtkMSLabelArrays::NewLabelArray(text.Grid, "Label"));
  output->GetPointData()->SetScalars(labels);
  vtkNew<vtkIntArray> pieceLabels;
  pieceLabels->SetName("PieceLabels");
  vtkNew<vtkStringArray> pieceNames;
  pieceNames->SetName("PieceNames");
  for (const auto& kv : text.Pieces)
  {
    for (const auto& name : kv.second)
    {
      pieceLabels->InsertNextValue(kv.first);
      pieceNames->InsertNextValue(name);
    }
  }
  if (pieceNames->GetNumberOfValues() > 0)
  {
    output->GetFieldData()->AddArray(pieceLabels);
    output->GetFieldData()->AddArray(pieceNames);
  }
  if (!text.Trailer.empty())
  {
    // The text after the last value (the <Objects> section), written back unchanged by
    // vtkMSLabelGridWriter so the original program's loaders find the scene and pieces.
    vtkNew<vtkStringArray> trailer;
    trailer->SetName("TextModelTrailer");
    trailer->InsertNextValue(text.Trailer);
    output->GetFieldData()->AddArray(trailer);
  }
  if (!colours.empty())
  {
    vtkNew<vtkUnsignedCharArray> palette;
    palette->SetName("PaletteRGBA");
    palette->SetNumberOfComponents(4);
    for (const auto& rgba : colours)
    {
      palette->InsertNextTypedTuple(rgba.data());
    }
    output->GetFieldData()->AddArray(palette);
  }
}

/// The sites of @p image: its points, or with @p onCells one point per cell at the centres.
void SitesOf(vtkImageData* image, bool onCells, vtkImageData* sites)
{
  int extent[6];
  double origin[3], spacing[3];
  image->GetExtent(extent);
  image->GetOrigin(origin);
  image->GetSpacing(spacing);
  if (onCells)
  {
    for (int a = 0; a < 3; ++a)
    {
      if (extent[2 * a + 1] > extent[2 * a])
      {
        extent[2 * a + 1] -= 1;
        origin[a] += 0.5 * spacing[a];
      }
    }
  }
  sites->SetExtent(extent);
  sites->SetOrigin(origin);
  sites->SetSpacing(spacing);
  sites->SetDirectionMatrix(image->GetDirectionMatrix());
}
} // namespace

int vtkMSLabelGridReader::RequestData(
  vtkInformation*, vtkInformationVector**, vtkInformationVector* outputVector)
{
  vtkImageData* output = vtkImageData::GetData(outputVector, 0);
  vtkPolyData::GetData(outputVector, 1)->Initialize();
  if (!this->ReadGrid(output))
  {
    output->Initialize();
    return 0;
  }
  std::string problem;
  if (!vtkMSLabelArrays::FillGeometryPort(output, this->GenerateGeometry, this->EmptyLabel,
        outputVector->GetInformationObject(1), problem))
  {
    output->Initialize();
    this->Fail(problem);
    return 0;
  }
  return 1;
}

bool vtkMSLabelGridReader::ReadGrid(vtkImageData* output)
{
  if (!this->ReadHeader())
  {
    return false;
  }
  vtkNew<vtkStringArray> source;
  source->SetName("ExampleFile");
  source->InsertNextValue(this->FileName);
  if (this->IsText)
  {
    FillFromTextModel(output, this->Internal->Text, this->Internal->Palette);
    if (this->VoxScene && this->Internal->VoxModels > 0) // the models the scene placed
      vtkMSFieldData::AddFieldValue<vtkIntArray>(
        output->GetFieldData(), "VoxModels", this->Internal->VoxModels);
    output->GetFieldData()->AddArray(source);
    return true;
  }
  std::string messages;
  const bool ok = vtkMSEngineBridge::Execute(this->Reader, messages);
  vtkImageData* image = this->Reader->GetOutput();
  if (!ok || !image)
  {
    this->Fail("could not be read: " + messages);
    return false;
  }
  vtkDataArray* labels = this->LabelsOnCells
    ? image->GetCellData()->GetArray(this->LabelArrayName.c_str())
    : image->GetPointData()->GetArray(this->LabelArrayName.c_str());
  if (!labels)
  {
    this->Fail("array '" + this->LabelArrayName + "' is not a numeric array");
    return false;
  }

  vtkNew<vtkImageData> sites;
  SitesOf(image, this->LabelsOnCells, sites);
  std::string problem;
  if (!vtkMSLabelArrays::CheckLabelArray(sites, labels, problem))
  {
    this->Fail(problem);
    return false;
  }
  vtkNew<vtkIntArray> out;
  out->SetName("Label");
  out->SetNumberOfTuples(labels->GetNumberOfTuples());
  for (vtkIdType i = 0; i < labels->GetNumberOfTuples(); ++i)
  {
    out->SetValue(i, static_cast<int>(labels->GetTuple1(i)));
  }
  output->CopyStructure(sites);
  output->GetPointData()->SetScalars(out);
  output->GetFieldData()->AddArray(source);
  return true;
}

void vtkMSLabelGridReader::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "GenerateGeometry: " << this->GenerateGeometry << " (EmptyLabel "
     << this->EmptyLabel << ")\n";
  os << indent << "FileName: " << this->FileName << "\n";
  os << indent << "LabelArrayName: " << this->LabelArrayName << "\n";
  os << indent << "MaximumNumberOfSites: " << this->MaximumNumberOfSites << "\n";
  os << indent << "VoxScene: " << this->VoxScene << "\n";
}
