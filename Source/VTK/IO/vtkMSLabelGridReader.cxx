// SPDX-License-Identifier: BSD-3-Clause
#include "vtkMSLabelGridReader.h"

#include "vtkMSEngineBridge.h"

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
#include "vtkStreamingDemandDrivenPipeline.h"
#include "vtkStringArray.h"
#include "vtkXMLImageDataReader.h"

#include <sys/stat.h>

vtkStandardNewMacro(vtkMSLabelGridReader);

vtkMSLabelGridReader::vtkMSLabelGridReader()
  : Reader(vtkSmartPointer<vtkXMLImageDataReader>::New())
{
  this->SetNumberOfInputPorts(0);
}

vtkMSLabelGridReader::~vtkMSLabelGridReader() = default;

int vtkMSLabelGridReader::CanReadFile(const char* name)
{
  if (!name)
  {
    return 0;
  }
  const std::string s(name);
  return s.size() > 4 && s.compare(s.size() - 4, 4, ".vti") == 0 ? 1 : 0;
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
  if (!this->ReadHeader())
  {
    return 0;
  }
  vtkInformation* fileInfo = this->Reader->GetOutputInformation(0);
  int extent[6];
  double origin[3], spacing[3];
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

int vtkMSLabelGridReader::RequestData(
  vtkInformation*, vtkInformationVector**, vtkInformationVector* outputVector)
{
  vtkImageData* output = vtkImageData::GetData(outputVector, 0);
  if (!this->ReadHeader())
  {
    return 0;
  }
  std::string messages;
  const bool ok = vtkMSEngineBridge::Execute(this->Reader, messages);
  vtkImageData* image = this->Reader->GetOutput();
  if (!ok || !image)
  {
    this->Fail("could not be read: " + messages);
    return 0;
  }
  vtkDataArray* labels = this->LabelsOnCells
    ? image->GetCellData()->GetArray(this->LabelArrayName.c_str())
    : image->GetPointData()->GetArray(this->LabelArrayName.c_str());
  if (!labels)
  {
    this->Fail("array '" + this->LabelArrayName + "' is not a numeric array");
    return 0;
  }

  // The sites: the image's points, or one point per cell at the cell centers.
  vtkNew<vtkImageData> sites;
  int extent[6];
  double origin[3], spacing[3];
  image->GetExtent(extent);
  image->GetOrigin(origin);
  image->GetSpacing(spacing);
  if (this->LabelsOnCells)
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

  std::string problem;
  if (!vtkMSEngineBridge::CheckLabelArray(sites, labels, problem))
  {
    this->Fail(problem);
    return 0;
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
  vtkNew<vtkStringArray> source;
  source->SetName("ExampleFile");
  source->InsertNextValue(this->FileName);
  output->GetFieldData()->AddArray(source);
  return 1;
}

void vtkMSLabelGridReader::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "FileName: " << this->FileName << "\n";
  os << indent << "LabelArrayName: " << this->LabelArrayName << "\n";
  os << indent << "MaximumNumberOfSites: " << this->MaximumNumberOfSites << "\n";
}
