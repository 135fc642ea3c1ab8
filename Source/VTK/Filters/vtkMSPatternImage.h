// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class vtkMSPatternImage
 * @brief Composes the picture of a model synthesized from an image sample (the overlapping
 * model): each site is an N × N window of the sample; its top-left pixel is the site's pixel,
 * and the last N − 1 rows and columns of a picture that does not repeat come from the last
 * sites' windows (Discrete/OverlappingModel.h).
 *
 * Input: vtkImageData of pattern labels (`Label`, else the active scalars), as
 * vtkMSDiscreteSynthesis produces with a SampleFile. The sample and its options come from the
 * input's field data (`SampleFile`, `PatternSize`, `PatternSymmetry`, `PeriodicInput`,
 * `PeriodicOutput`) when it has them; the properties below are used for labels without them
 * (and SampleFile, when set, names the sample to read instead of the recorded one).
 *
 * Output: vtkImageData of W × H pixels with the unsigned-char array `RGBA` (four components, the
 * active scalars), rows bottom first as VTK stores images: the picture right side up.
 *
 * @sa vtkMSDiscreteSynthesis, vtkMSTileImage
 */
#ifndef vtkMSPatternImage_h
#define vtkMSPatternImage_h

#include "ModelSynthFiltersModule.h" // for export macro
#include "vtkImageAlgorithm.h"

#include <string> // for ivars

class vtkInformationIntegerVectorKey;

class MODELSYNTHFILTERS_EXPORT vtkMSPatternImage : public vtkImageAlgorithm
{
public:
  static vtkMSPatternImage* New();
  vtkTypeMacro(vtkMSPatternImage, vtkImageAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /// The sample (.png, .bmp); "" (the default) reads the one the input's field data names.
  vtkSetStdStringFromCharMacro(SampleFile);
  vtkGetCharFromStdStringMacro(SampleFile);
  ///@}

  ///@{
  /// For labels without field data: the pattern size (default 3), symmetry (default 8),
  /// whether windows wrapped around the sample (default on) and whether the picture repeats
  /// along x and y (default 0 0).
  vtkSetClampMacro(PatternSize, int, 1, 8);
  vtkGetMacro(PatternSize, int);
  vtkSetClampMacro(PatternSymmetry, int, 1, 8);
  vtkGetMacro(PatternSymmetry, int);
  vtkSetMacro(PeriodicInput, bool);
  vtkGetMacro(PeriodicInput, bool);
  vtkBooleanMacro(PeriodicInput, bool);
  vtkSetVector2Macro(PeriodicOutput, int);
  vtkGetVector2Macro(PeriodicOutput, int);
  ///@}

  /// Pipeline information a synthesis from a sample puts on its output: pattern size and
  /// whether the picture repeats along x and y, so the picture's size is known before the run.
  static vtkInformationIntegerVectorKey* PATTERN_PICTURE();

protected:
  vtkMSPatternImage() = default;
  ~vtkMSPatternImage() override = default;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  int RequestInformation(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestUpdateExtent(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

private:
  vtkMSPatternImage(const vtkMSPatternImage&) = delete;
  void operator=(const vtkMSPatternImage&) = delete;

  std::string SampleFile;
  int PatternSize = 3;
  int PatternSymmetry = 8;
  bool PeriodicInput = true;
  int PeriodicOutput[2] = { 0, 0 };
};

#endif
