// SPDX-License-Identifier: BSD-3-Clause
#include "vtkMSPatternImage.h"

#include "vtkMSLabelArrays.h"
#include "vtkMSPipeline.h"

#include "vtkDataArray.h"
#include "vtkFieldData.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationIntegerVectorKey.h"
#include "vtkInformationVector.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkStreamingDemandDrivenPipeline.h"
#include "vtkStringArray.h"
#include "vtkUnsignedCharArray.h"

#include "Discrete/OverlappingModel.h"
#include "Formats/Image.h"

#include <algorithm>

vtkStandardNewMacro(vtkMSPatternImage);
vtkInformationKeyRestrictedMacro(vtkMSPatternImage, PATTERN_PICTURE, IntegerVector, 3);

int vtkMSPatternImage::FillInputPortInformation(int, vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkImageData");
  return 1;
}

namespace
{
/// The picture's pixels along x and y for @p sites pattern sites (whole extent) and the
/// pattern size and repetition in @p pattern (N, periodic x, periodic y).
void PictureExtent(const int sites[6], const int pattern[3], int extent[6])
{
  for (int a = 0; a < 2; ++a)
  {
    const int n = sites[2 * a + 1] - sites[2 * a] + 1;
    extent[2 * a] = 0;
    extent[2 * a + 1] = (pattern[1 + a] ? n : n + pattern[0] - 1) - 1;
  }
  extent[4] = extent[5] = 0;
}

/// An integer the input's field data records, or @p otherwise.
int Recorded(vtkFieldData* fd, const char* name, int component, int otherwise)
{
  vtkDataArray* a = fd ? fd->GetArray(name) : nullptr;
  return a && a->GetNumberOfValues() > component
    ? static_cast<int>(a->GetVariantValue(component).ToInt())
    : otherwise;
}
} // namespace

int vtkMSPatternImage::RequestInformation(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  vtkInformation* inInfo = inputVector[0]->GetInformationObject(0);
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  int sites[6] = { 0, 0, 0, 0, 0, 0 };
  inInfo->Get(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), sites);
  int pattern[3] = { this->PatternSize, this->PeriodicOutput[0], this->PeriodicOutput[1] };
  if (inInfo->Has(PATTERN_PICTURE()))
    inInfo->Get(PATTERN_PICTURE(), pattern);
  int extent[6];
  PictureExtent(sites, pattern, extent);
  outInfo->Set(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), extent, 6);
  const double spacing[3] = { 1.0, 1.0, 1.0 }, origin[3] = { 0.0, 0.0, 0.0 };
  outInfo->Set(vtkDataObject::SPACING(), spacing, 3);
  outInfo->Set(vtkDataObject::ORIGIN(), origin, 3);
  vtkDataObject::SetPointDataActiveScalarInfo(outInfo, VTK_UNSIGNED_CHAR, 4);
  return 1;
}

int vtkMSPatternImage::RequestUpdateExtent(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector*)
{
  // Output pixels are not input sites: always ask for all the sites.
  vtkMSPipeline::RequestWholeExtentOnPieceZero(inputVector[0]->GetInformationObject(0), 0);
  return 1;
}

int vtkMSPatternImage::RequestData(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  vtkImageData* input = vtkImageData::GetData(inputVector[0], 0);
  vtkImageData* output = vtkImageData::GetData(outputVector, 0);
  vtkDataArray* labels = vtkMSLabelArrays::FindLabelArray(input, nullptr);
  std::string problem;
  if (!labels || !vtkMSLabelArrays::CheckLabelArray(input, labels, problem))
  {
    vtkErrorMacro(<< (labels ? problem : std::string("The input has no label array.")));
    return 0;
  }
  vtkFieldData* fd = input->GetFieldData();
  vtkStringArray* recorded = vtkStringArray::SafeDownCast(fd->GetAbstractArray("SampleFile"));
  const std::string sample = !this->SampleFile.empty() ? this->SampleFile
    : recorded && recorded->GetNumberOfValues() > 0    ? recorded->GetValue(0)
                                                       : std::string();
  if (sample.empty())
  {
    vtkErrorMacro(<< "No SampleFile, and the labels do not name the sample they came from.");
    return 0;
  }
  msynth::OverlappingOptions po;
  po.N = Recorded(fd, "PatternSize", 0, this->PatternSize);
  po.Symmetry = Recorded(fd, "PatternSymmetry", 0, this->PatternSymmetry);
  po.PeriodicInput = Recorded(fd, "PeriodicInput", 0, this->PeriodicInput) != 0;
  const msynth::Periodic periodic{ { Recorded(fd, "PeriodicOutput", 0, this->PeriodicOutput[0]) !=
      0,
    Recorded(fd, "PeriodicOutput", 1, this->PeriodicOutput[1]) != 0 } };
  msynth::RgbaImage picture;
  try
  {
    const msynth::PatternSet set = msynth::ExtractPatterns(msynth::ReadImage(sample), po, sample);
    picture = set.Compose(vtkMSLabelArrays::ToLabelGrid(input, labels), periodic);
  }
  catch (const std::exception& e)
  {
    vtkErrorMacro(<< e.what());
    return 0;
  }
  int announced[6];
  outputVector->GetInformationObject(0)->Get(
    vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), announced);
  if (announced[1] + 1 != picture.Width || announced[3] + 1 != picture.Height)
  {
    vtkErrorMacro(<< "The labels record pattern size " << po.N << " and repetition " << periodic[0]
                  << " " << periodic[1] << "; set PatternSize and PeriodicOutput to the same.");
    return 0;
  }
  vtkMSLabelArrays::SetPicture(output, picture);
  return 1;
}

void vtkMSPatternImage::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "SampleFile: " << this->SampleFile << "\n";
  os << indent << "PatternSize: " << this->PatternSize << "\n";
  os << indent << "PatternSymmetry: " << this->PatternSymmetry << "\n";
  os << indent << "PeriodicInput: " << this->PeriodicInput << "\n";
  os << indent << "PeriodicOutput: " << this->PeriodicOutput[0] << " " << this->PeriodicOutput[1]
     << "\n";
}
