// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class vtkMSFieldData
 * @brief Field data the classes share: one-value arrays, a solver's statistics under their one
 * naming, the timing left out of written files, the example's file name.
 *
 * Static functions shared by ModelSynth's VTK classes (not wrapped for Python: their signatures
 * use engine types).
 */
#ifndef vtkMSFieldData_h
#define vtkMSFieldData_h

#include "Core/BlockSynthesis.h" // for AddStatistics
#include "ModelSynthIOModule.h"  // for export macro
#include "vtkFieldData.h"        // for AddFieldValue
#include "vtkNew.h"              // for AddFieldValue
#include "vtkSmartPointer.h"     // for WithoutTiming

#include <string>

class vtkDataObject;

class MODELSYNTHIO_EXPORT vtkMSFieldData
{
public:
  /// Adds the one-value array @p name of type @p ArrayT (e.g. vtkIdTypeArray) to @p fields.
  template <class ArrayT, class ValueT>
  static void AddFieldValue(vtkFieldData* fields, const char* name, ValueT value)
  {
    vtkNew<ArrayT> a;
    a->SetName(name);
    a->InsertNextValue(value);
    fields->AddArray(a);
  }

  /**
   * A solver's statistics in @p fields under their one naming (msynth::StatisticsFields: counts
   * as vtkIdTypeArray, Seconds as vtkDoubleArray), with `Status` ("succeeded", ...), `Message`,
   * `TrivialLabel` when block synthesis used one, and per failed block `FailedBlockOrigins` and
   * `FailedBlockSites` (3 components each).
   */
  static void AddStatistics(vtkFieldData* fields, const msynth::SynthesisStatistics& statistics,
    msynth::SynthesisStatus status, const std::string& message);

  /// True for the field data of a run's timing (`Seconds`, `FirstValidSeconds`,
  /// `SampleSeconds`), which differ between equal runs.
  static bool IsTiming(const char* name);

  /**
   * What outputs are written from, reproducibly: a shallow copy of @p data without its timing
   * field data (IsTiming), so the same inputs and seed give byte-identical files; the timing
   * goes to statistics.json only.
   */
  static vtkSmartPointer<vtkDataObject> WithoutTiming(vtkDataObject* data);

  /// The example's file name from field data `ExampleFile`, else "the input".
  static std::string ExampleName(vtkDataObject* data);
};

#endif
