// SPDX-License-Identifier: BSD-3-Clause
#include "vtkMSTileImage.h"

#include "vtkMSEngineBridge.h"
#include "vtkMSLabelArrays.h"
#include "vtkMSPipeline.h"

#include "vtkFieldData.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationStringVectorKey.h"
#include "vtkInformationVector.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkStreamingDemandDrivenPipeline.h"
#include "vtkStringArray.h"
#include "vtkUnsignedCharArray.h"

#include "Core/Index.h"
#include "Formats/Image.h"
#include "Formats/TilePictures.h"
#include "Formats/Tileset.h"

#include <algorithm>
#include <vector>

vtkStandardNewMacro(vtkMSTileImage);
vtkInformationKeyMacro(vtkMSTileImage, TILESET, StringVector);

namespace
{
const char* const NoTileset =
  "No tileset: set TilesetFile to the tileset (.xml) the labels come from, or connect the "
  "output of a tileset synthesis (ModelSynth Tileset Synthesis), which names its tileset.";

/// The one value of the string array @p name of @p fd, or "".
std::string FieldString(vtkFieldData* fd, const char* name)
{
  auto* array = vtkStringArray::SafeDownCast(fd ? fd->GetAbstractArray(name) : nullptr);
  return array && array->GetNumberOfValues() > 0 ? array->GetValue(0) : std::string();
}
} // namespace

bool vtkMSTileImage::FindTileset(
  vtkInformation* inInfo, vtkDataObject* input, std::string& file, std::string& subset) const
{
  file = this->TilesetFile;
  subset = this->TilesetSubset;
  if (!file.empty())
    return true;
  if (inInfo && inInfo->Has(TILESET()) && inInfo->Length(TILESET()) == 2)
  {
    file = inInfo->Get(TILESET(), 0);
    subset = inInfo->Get(TILESET(), 1);
  }
  else if (input)
  {
    file = FieldString(input->GetFieldData(), "TilesetFile");
    if (input->GetFieldData()->GetAbstractArray("TilesetSubset"))
      subset = FieldString(input->GetFieldData(), "TilesetSubset");
  }
  return !file.empty();
}

int vtkMSTileImage::FillInputPortInformation(int, vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkImageData");
  return 1;
}

int vtkMSTileImage::RequestInformation(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  // The pixel extent: the input's sites times the tile size, read from the first tile image's
  // header (cheap). A bad tileset is reported here and again, in full, by RequestData.
  vtkInformation* inInfo = inputVector[0]->GetInformationObject(0);
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  int sites[6] = { 0, 0, 0, 0, 0, 0 };
  inInfo->Get(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), sites);
  int size = 1;
  std::string file, subset;
  // No tileset known yet (an input whose field data names it has not run): the picture's size
  // is unknown until RequestData, which also reports a missing tileset, once.
  if (this->FindTileset(inInfo, vtkDataObject::GetData(inInfo), file, subset))
    try
    {
      const msynth::Tileset tiles = msynth::ReadTilesetFile(file, subset);
      size = std::max(
        1, msynth::ReadImage(msynth::TileImageFile(file, tiles, tiles.Tiles.front(), 0)).Width);
    }
    catch (const std::exception& e)
    {
      vtkErrorMacro(<< e.what());
      return 0;
    }
  const int extent[6] = { 0, (sites[1] - sites[0] + 1) * size - 1, 0,
    (sites[3] - sites[2] + 1) * size - 1, 0, 0 };
  outInfo->Set(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), extent, 6);
  const double spacing[3] = { 1.0 / size, 1.0 / size, 1.0 };
  outInfo->Set(vtkDataObject::SPACING(), spacing, 3);
  vtkDataObject::SetPointDataActiveScalarInfo(outInfo, VTK_UNSIGNED_CHAR, 4);
  return 1;
}

int vtkMSTileImage::RequestUpdateExtent(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector*)
{
  // Output pixels are not input sites: always ask for all the sites.
  vtkMSPipeline::RequestWholeExtentOnPieceZero(inputVector[0]->GetInformationObject(0), 0);
  return 1;
}

int vtkMSTileImage::RequestData(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  vtkImageData* input = vtkImageData::GetData(inputVector[0], 0);
  vtkImageData* output = vtkImageData::GetData(outputVector, 0);
  if (input->GetNumberOfPoints() == 0 &&
    vtkMSPipeline::UpdatePiece(outputVector->GetInformationObject(0)) != 0)
  {
    output->Initialize(); // an empty piece of a parallel run: the model is on piece 0
    return 1;
  }
  std::string file, subset;
  if (!this->FindTileset(inputVector[0]->GetInformationObject(0), input, file, subset))
  {
    // Said once, without the executive's dump of the request: the empty image is the result.
    vtkErrorMacro(<< NoTileset);
    output->Initialize();
    return 1;
  }
  vtkDataArray* labels = vtkMSLabelArrays::FindLabelArray(input, nullptr);
  std::string problem;
  if (!labels || !vtkMSLabelArrays::CheckLabelArray(input, labels, problem))
  {
    vtkErrorMacro(<< (labels ? problem : std::string("The input has no label array.")));
    return 0;
  }
  msynth::Tileset tiles;
  try
  {
    tiles = msynth::ReadTilesetFile(file, subset);
  }
  catch (const std::exception& e)
  {
    vtkErrorMacro(<< e.what());
    return 0;
  }

  std::vector<msynth::TilePicture> pictures;
  int size = 0;
  try
  {
    pictures = msynth::LoadTilePictures(file, tiles);
    size = pictures.empty() ? 0 : pictures.front().Size;
  }
  catch (const std::exception& e)
  {
    vtkErrorMacro(<< e.what());
    return 0;
  }

  int dims[3];
  input->GetDimensions(dims);
  output->SetExtent(0, dims[0] * size - 1, 0, dims[1] * size - 1, 0, 0);
  output->SetSpacing(1.0 / size, 1.0 / size, 1.0);
  vtkNew<vtkUnsignedCharArray> rgba;
  rgba->SetName("RGBA");
  rgba->SetNumberOfComponents(4);
  const vtkIdType width = static_cast<vtkIdType>(dims[0]) * size;
  rgba->SetNumberOfTuples(width * dims[1] * size);
  std::vector<std::int32_t> row(msynth::ToIndex(dims[0]));
  for (int y = 0; y < dims[1]; ++y)
  {
    for (int x = 0; x < dims[0]; ++x)
    {
      const double b = labels->GetTuple1(x + static_cast<vtkIdType>(dims[0]) * y);
      if (!(b >= 0 && b < tiles.NumberOfLabels()))
      {
        vtkErrorMacro(<< "Label " << b << " at (" << x << ", " << y << ") is not a label of '"
                      << file << "'.");
        return 0;
      }
      row[msynth::ToIndex(x)] = static_cast<std::int32_t>(b);
    }
    for (int j = 0; j < size; ++j) // one row of pixels at a time
      msynth::ComposeTileRow(row.data(), dims[0], pictures, j,
        rgba->GetPointer(4 * ((static_cast<vtkIdType>(y) * size + j) * width)));
  }
  output->GetPointData()->SetScalars(rgba);
  return 1;
}

void vtkMSTileImage::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "TilesetFile: " << this->TilesetFile << "\n";
  os << indent << "TilesetSubset: " << this->TilesetSubset << "\n";
}
