// SPDX-License-Identifier: BSD-3-Clause
#include "vtkMSLabelGridWriter.h"

#include "vtkMSEngineBridge.h"
#include "vtkMSLabelArrays.h"

#include "vtkDataArray.h"
#include "vtkErrorCode.h"
#include "vtkFieldData.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkObjectFactory.h"
#include "vtkStringArray.h"

#include "Core/AtomicFile.h"
#include "Core/Index.h"
#include "Formats/TextModel.h"
#include "Formats/VoxModel.h"

vtkStandardNewMacro(vtkMSLabelGridWriter);

void vtkMSLabelGridWriter::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "FileName: " << this->FileName << "\n";
}

int vtkMSLabelGridWriter::FillInputPortInformation(int, vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkImageData");
  return 1;
}

void vtkMSLabelGridWriter::WriteData()
{
  this->SetErrorCode(vtkErrorCode::NoError);
  if (this->FileName.empty())
  {
    vtkErrorMacro(<< "No file name was given.");
    this->SetErrorCode(vtkErrorCode::NoFileNameError);
    return;
  }
  const std::string& path = this->FileName;
  const auto endsWith = [&path](const char* ext)
  { return path.size() > 4 && path.compare(path.size() - 4, 4, ext) == 0; };
  vtkImageData* image = vtkImageData::SafeDownCast(this->GetInput());
  msynth::LabelGrid grid;
  std::string problem;
  if (!endsWith(".txt") && !endsWith(".vox"))
  {
    problem = "the extension must be .txt (the original program's format) or .vox (MagicaVoxel)";
  }
  else if (!image)
  {
    problem = "the input is not image data";
  }
  else
  {
    vtkMSLabelArrays::ReadLabels(image, nullptr, grid, problem);
  }
  if (!problem.empty())
  {
    vtkErrorMacro(<< "'" << path << "': cannot be written: " << problem);
    this->SetErrorCode(vtkErrorCode::UnknownError);
    return;
  }
  vtkFieldData* fields = image->GetFieldData();
  try
  {
    if (endsWith(".txt"))
    {
      msynth::TextModel model;
      model.Grid = std::move(grid);
      model.Header = msynth::GeneratedTextModelHeader();
      auto* trailer = vtkStringArray::SafeDownCast(fields->GetAbstractArray("TextModelTrailer"));
      if (trailer && trailer->GetNumberOfValues() > 0)
        model.Trailer = trailer->GetValue(0);
      msynth::WriteFileAtomically(
        path, [&](std::ostream& out) { msynth::WriteTextModel(out, model); });
    }
    else
    {
      msynth::VoxModel model;
      model.Grid = std::move(grid);
      vtkDataArray* palette = fields->GetArray("PaletteRGBA");
      if (palette && palette->GetNumberOfTuples() == 256 && palette->GetNumberOfComponents() == 4)
      {
        model.Palette.resize(256);
        for (vtkIdType i = 0; i < 256; ++i)
          for (int c = 0; c < 4; ++c)
            model.Palette[msynth::ToIndex(i)][msynth::ToIndex(c)] =
              static_cast<std::uint8_t>(palette->GetComponent(i, c));
      }
      msynth::WriteVoxModelFile(path, model);
    }
  }
  catch (const std::exception& e)
  {
    vtkErrorMacro(<< e.what());
    this->SetErrorCode(vtkErrorCode::CannotOpenFileError);
  }
}
