// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class vtkMSImagePatterns
 * @brief Reads an image sample as the overlapping model sees it: its N × N patterns and the
 * pairs that may be neighbours (Discrete/OverlappingModel.h), for inspection.
 *
 * No input. Properties as vtkMSDiscreteSynthesis names them: SampleFile, PatternSize,
 * PatternSymmetry, PeriodicInput.
 *
 * Output port 0, "Patterns": vtkImageData of N × N × k points, slice z the pattern of label z
 * (rows bottom first, as VTK stores images, so each slice shows its pattern upright), with the
 * unsigned-char array `RGBA` (four components).
 *
 * Output port 1, "Pairs": a vtkTable with one row per allowed pair: `Axis` (0, 1), `Direction`
 * ("+x", "+y"), `From` and `To` (labels: pattern numbers, the values synthesis gives them).
 *
 * Output port 2, "Labels": a vtkTable with `Label`, `Count` (occurrences among the sample's
 * windows and their images) and `Frequency`.
 *
 * @sa vtkMSDiscreteSynthesis, vtkMSPatternImage
 */
#ifndef vtkMSImagePatterns_h
#define vtkMSImagePatterns_h

#include "ModelSynthFiltersModule.h" // for export macro
#include "vtkAlgorithm.h"

#include <string> // for ivars

namespace msynth
{
class PatternSet;
}

class MODELSYNTHFILTERS_EXPORT vtkMSImagePatterns : public vtkAlgorithm
{
public:
  static vtkMSImagePatterns* New();
  vtkTypeMacro(vtkMSImagePatterns, vtkAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /// The sample (.png, .bmp), its pattern size (1-8, default 3), symmetry (1-8, default 8) and
  /// whether windows wrap around it (default on).
  vtkSetStdStringFromCharMacro(SampleFile);
  vtkGetCharFromStdStringMacro(SampleFile);
  vtkSetClampMacro(PatternSize, int, 1, 8);
  vtkGetMacro(PatternSize, int);
  vtkSetClampMacro(PatternSymmetry, int, 1, 8);
  vtkGetMacro(PatternSymmetry, int);
  vtkSetMacro(PeriodicInput, bool);
  vtkGetMacro(PeriodicInput, bool);
  vtkBooleanMacro(PeriodicInput, bool);
  ///@}

  vtkTypeBool ProcessRequest(
    vtkInformation* request, vtkInformationVector** inInfo, vtkInformationVector* outInfo) override;

protected:
  vtkMSImagePatterns();
  ~vtkMSImagePatterns() override = default;

  int FillOutputPortInformation(int port, vtkInformation* info) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*);
  /// The sample's patterns into @p set; false (after an error event) when it cannot be read.
  bool Extract(msynth::PatternSet& set);

private:
  vtkMSImagePatterns(const vtkMSImagePatterns&) = delete;
  void operator=(const vtkMSImagePatterns&) = delete;

  std::string SampleFile;
  int PatternSize = 3;
  int PatternSymmetry = 8;
  bool PeriodicInput = true;
};

#endif
