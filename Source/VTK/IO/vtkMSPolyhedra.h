// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class vtkMSPolyhedra
 * @brief Polygons as the engine's polyhedral examples and continuous models, and back; the analysis
 * of an example.
 *
 * Static functions shared by ModelSynth's VTK classes (not wrapped for Python: their signatures
 * use engine types).
 */
#ifndef vtkMSPolyhedra_h
#define vtkMSPolyhedra_h

#include "Continuous/ContinuousMesh.h"     // for msynth::ContinuousMesh
#include "Continuous/PolyhedralAnalysis.h" // for msynth::PolyhedralAnalysis
#include "Formats/PolyhedralExample.h"     // for msynth::PolyhedralExample
#include "ModelSynthIOModule.h"            // for export macro

#include <string>

class vtkPolyData;

class MODELSYNTHIO_EXPORT vtkMSPolyhedra
{
public:
  /**
   * A polyhedral example from polygons: cell array `ObjectType` gives each polygon's type
   * (default 1), `ObjectId` its object (default: connected components per type), named by field
   * data `ObjectNames` (by id, as the example reader writes it). Not validated.
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

  /**
   * Reads, validates and analyzes the polyhedral example @p polygons (continuous synthesis).
   * @p angleToleranceDegrees and @p maximumSmallInteger are the analysis options.
   * @throw msynth::Error naming the example on bad input.
   */
  static msynth::PolyhedralAnalysis AnalyzeExample(vtkPolyData* polygons,
    double angleToleranceDegrees, int maximumSmallInteger, msynth::PolyhedralExample& example);
};

#endif
