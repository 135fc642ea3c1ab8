// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class vtkMSPipeline
 * @brief Pipeline policies the classes share: pieces (work done once, on piece 0), label image
 * outputs, time steps.
 *
 * Static functions shared by ModelSynth's VTK classes (not wrapped for Python: their signatures
 * use engine types).
 */
#ifndef vtkMSPipeline_h
#define vtkMSPipeline_h

#include "ModelSynthIOModule.h" // for export macro
#include <cstddef>

class vtkInformation;
class vtkInformationVector;

class MODELSYNTHIO_EXPORT vtkMSPipeline
{
public:
  /**
   * Parallel policy of algorithms that need the whole input at once (analysis, writers): piece
   * 0 asks @p inInfo for the whole extent, every other piece for an empty one, so the work is
   * done once and gathered results are not duplicated.
   */
  static void RequestWholeExtentOnPieceZero(vtkInformation* inInfo, int piece);

  /// The piece an output information object asks for (UPDATE_PIECE_NUMBER), 0 when unset.
  static int UpdatePiece(vtkInformation* outInfo);

  /// The number of pieces an output information object asks for, 1 when unset.
  static int UpdateNumberOfPieces(vtkInformation* outInfo);

  /// The information of the output port whose update asked for this REQUEST_DATA @p request
  /// (FROM_OUTPUT_PORT), port 0's when it names none: where the requested time step is.
  static vtkInformation* RequestingPort(vtkInformation* request, vtkInformationVector* outputs);

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
};

#endif
