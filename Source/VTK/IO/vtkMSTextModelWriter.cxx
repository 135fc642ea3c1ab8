// SPDX-License-Identifier: BSD-3-Clause
#include "vtkMSTextModelWriter.h"

#include "vtkMSEngineBridge.h"

#include "vtkErrorCode.h"
#include "vtkFieldData.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkObjectFactory.h"
#include "vtkStringArray.h"

#include "msynth/AtomicFile.h"
#include "msynth/TextModel.h"

vtkStandardNewMacro(vtkMSTextModelWriter);

void vtkMSTextModelWriter::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "FileName: " << this->FileName << "\n";
  os << indent << "Trailer: " << this->Trailer.size() << " characters\n";
}

int vtkMSTextModelWriter::FillInputPortInformation(int, vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkImageData");
  return 1;
}

void vtkMSTextModelWriter::WriteData()
{
  this->SetErrorCode(vtkErrorCode::NoError);
  if (this->FileName.empty())
  {
    vtkErrorMacro(<< "No file name was given.");
    this->SetErrorCode(vtkErrorCode::NoFileNameError);
    return;
  }
  vtkImageData* image = vtkImageData::SafeDownCast(this->GetInput());
  msynth::TextModel model;
  std::string problem;
  if (!image || !vtkMSEngineBridge::ReadLabels(image, nullptr, model.Grid, problem))
  {
    vtkErrorMacro(<< "'" << this->FileName << "': cannot be written: "
                  << (image ? problem : std::string("the input is not image data")));
    this->SetErrorCode(vtkErrorCode::UnknownError);
    return;
  }
  model.Header = msynth::GeneratedTextModelHeader();
  auto* trailer =
    vtkStringArray::SafeDownCast(image->GetFieldData()->GetAbstractArray("TextModelTrailer"));
  model.Trailer =
    trailer && trailer->GetNumberOfValues() > 0 ? trailer->GetValue(0) : this->Trailer;
  try
  {
    msynth::WriteFileAtomically(
      this->FileName, [&](std::ostream& out) { msynth::WriteTextModel(out, model); });
  }
  catch (const std::exception& e)
  {
    vtkErrorMacro(<< e.what());
    this->SetErrorCode(vtkErrorCode::CannotOpenFileError);
  }
}
