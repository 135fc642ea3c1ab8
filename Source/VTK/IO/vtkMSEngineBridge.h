// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class vtkMSEngineBridge
 * @brief Conversions between VTK data and the plain-C++ engine, shared by ModelSynth's VTK
 * classes (not wrapped for Python: its signatures use engine types).
 *
 * Also an error collector: internal VTK algorithms report through ErrorEvent; the collector
 * keeps their messages so that our own classes can report one clear error that names the file.
 */
#ifndef vtkMSEngineBridge_h
#define vtkMSEngineBridge_h

#include "Core/BlockSynthesis.h" // for AddStatistics
#include "ModelSynthIOModule.h"  // for export macro
#include "vtkFieldData.h"        // for AddFieldValue
#include "vtkNew.h"              // for AddFieldValue
#include "vtkObject.h"

#include "Continuous/ContinuousMesh.h"     // for msynth::ContinuousMesh
#include "Continuous/PlaneArrangement.h"   // for msynth::ArrangementParameters
#include "Continuous/PolyhedralAnalysis.h" // for msynth::PolyhedralAnalysis
#include "Core/LabelGrid.h"                // for msynth::LabelGrid
#include "Formats/PolyhedralExample.h"     // for msynth::PolyhedralExample

#include <string>

class vtkAlgorithm;
class vtkDataArray;
class vtkDataObject;
class vtkImageData;
class vtkInformation;
class vtkIntArray;
class vtkPolyData;

class MODELSYNTHIO_EXPORT vtkMSEngineBridge : public vtkObject
{
public:
  static vtkMSEngineBridge* New();
  vtkTypeMacro(vtkMSEngineBridge, vtkObject);

  /// True when @p array holds integers (any width or signedness).
  static bool IsIntegerArray(vtkDataArray* array);

  /**
   * Checks that @p array can serve as labels of @p image's points: integer type, one
   * component, one value per point, values within the 32-bit range. On failure returns false
   * and sets @p problem to a sentence naming the array and what is wrong.
   */
  static bool CheckLabelArray(vtkImageData* image, vtkDataArray* array, std::string& problem);

  /**
   * The label array of @p image: @p selected (the filter's input array to process) when set,
   * else the point array "Label", else the active point scalars; nullptr when there is none.
   */
  static vtkDataArray* FindLabelArray(vtkImageData* image, vtkDataArray* selected);

  /// Copies a checked label array into an engine grid (x fastest, as VTK stores points).
  static msynth::LabelGrid ToLabelGrid(vtkImageData* image, vtkDataArray* labels);

  /**
   * FindLabelArray, CheckLabelArray and ToLabelGrid in one: @p image's labels (@p selected when
   * set) as a grid. False, with @p problem set to a sentence, when there is no usable array.
   */
  static bool ReadLabels(
    vtkImageData* image, vtkDataArray* selected, msynth::LabelGrid& grid, std::string& problem);

  /**
   * A polyhedral example from polygons: cell array `ObjectType` gives each polygon's type
   * (default 1), `ObjectId` its object (default: connected components per type). Not validated.
   * @p name is used in messages. @throw msynth::Error when there are no polygons.
   */
  static msynth::PolyhedralExample ToPolyhedralExample(
    vtkPolyData* polygons, const std::string& name);
  /**
   * A synthesized continuous model (vtkMSArrangementMesh's output, or model.vtp read back): its
   * polygons with the cell arrays InsideType and OutsideType (3D) or ObjectType (2D).
   * @throw msynth::Error naming @p name when the arrays are missing or a polygon is bad.
   */
  static msynth::ContinuousMesh ToContinuousMesh(vtkPolyData* model, const std::string& name);
  /// Polygons with cell arrays `ObjectType` and `ObjectId` (the inverse of the above).
  static void FromPolyhedralExample(const msynth::PolyhedralExample& example, vtkPolyData* output);
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

  /// The example's file name from field data `ExampleFile`, else "the input".
  static std::string ExampleName(vtkDataObject* data);
  /**
   * Reads, validates and analyzes the polyhedral example @p polygons (continuous synthesis).
   * @p angleToleranceDegrees and @p maximumSmallInteger are the analysis options.
   * @throw msynth::Error naming the example on bad input.
   */
  static msynth::PolyhedralAnalysis AnalyzeExample(vtkPolyData* polygons,
    double angleToleranceDegrees, int maximumSmallInteger, msynth::PolyhedralExample& example);

  /// What a plane arrangement output carries so later stages rebuild it exactly.
  struct ArrangementRecord
  {
    msynth::ArrangementParameters Parameters;
    std::vector<msynth::IntVec3> Normals;
    double AngleToleranceDegrees = 0.01;
    int MaximumSmallInteger = 12;
  };
  /// Field data arrays ArrangementOrigin, ArrangementQuantum, ArrangementBox, FamilyNormals,
  /// FamilyOffsets, FamilySpacings, Planar, AngleTolerance, MaximumSmallInteger.
  static void StoreArrangement(const ArrangementRecord& record, vtkFieldData* fields);
  /// @throw msynth::Error naming @p where and the missing or malformed array.
  static ArrangementRecord LoadArrangement(vtkFieldData* fields, const std::string& where);

  /// A new vtkIntArray named @p name holding @p grid's labels.
  static vtkIntArray* NewLabelArray(const msynth::LabelGrid& grid, const char* name);

  /**
   * Runs @p algorithm's pipeline pass (UpdateInformation when @p informationOnly, else Update)
   * and returns whether it succeeded, judged by the executive's return status (so it holds even
   * when VTK's global warning display is off) and by any ErrorEvent. @p messages receives the
   * collected error messages, or a generic sentence when the algorithm failed silently.
   */
  static bool Execute(vtkAlgorithm* algorithm, std::string& messages, bool informationOnly = false);

  /**
   * Parallel policy of algorithms that need the whole input at once (analysis, writers): piece
   * 0 asks @p inInfo for the whole extent, every other piece for an empty one, so the work is
   * done once and gathered results are not duplicated.
   */
  static void RequestWholeExtentOnPieceZero(vtkInformation* inInfo, int piece);
  /// The piece an output information object asks for (UPDATE_PIECE_NUMBER), 0 when unset.
  static int UpdatePiece(vtkInformation* outInfo);
  /**
   * Announces a label image of @p size sites on @p outInfo: its whole extent, the spacing and
   * origin of the example described by @p inInfo (1 and 0 without one), and Int labels.
   */
  static void SetOutputLabelGrid(
    vtkInformation* inInfo, vtkInformation* outInfo, const int size[3]);
  /// Announces time steps 0, 1, ..., @p count − 1 on @p outInfo (removes them when 0).
  static void SetTimeSteps(vtkInformation* outInfo, std::size_t count);
  /// The step of 0 ... @p count − 1 that @p outInfo asks for (UPDATE_TIME_STEP rounded and
  /// clamped), the last one when it asks for none. @p count must be > 0.
  static std::size_t RequestedStep(vtkInformation* outInfo, std::size_t count);

  /// Starts collecting ErrorEvent messages of @p source (removes earlier observation).
  void Watch(vtkObject* source);
  /// Stops collecting and forgets messages.
  void Reset();
  /// Collected messages, joined by "; " (empty when none).
  const std::string& GetMessages() const { return this->Messages; }
  bool HasErrors() const { return !this->Messages.empty(); }

protected:
  vtkMSEngineBridge() = default;
  ~vtkMSEngineBridge() override;

private:
  vtkMSEngineBridge(const vtkMSEngineBridge&) = delete;
  void operator=(const vtkMSEngineBridge&) = delete;

  void OnError(vtkObject* caller, unsigned long event, void* data);

  vtkObject* Source = nullptr;
  unsigned long Tag = 0;
  std::string Messages;
};

#endif
