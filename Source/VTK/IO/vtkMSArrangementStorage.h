// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class vtkMSArrangementStorage
 * @brief What a plane arrangement output carries so that later stages rebuild it exactly.
 *
 * Static functions shared by ModelSynth's VTK classes (not wrapped for Python: their signatures
 * use engine types).
 */
#ifndef vtkMSArrangementStorage_h
#define vtkMSArrangementStorage_h

#include "Continuous/PlaneArrangement.h" // for msynth::ArrangementParameters
#include "ModelSynthIOModule.h"          // for export macro

#include <memory>
#include <string>
#include <vector>

class vtkFieldData;

class MODELSYNTHIO_EXPORT vtkMSArrangementStorage
{
public:
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

  /// The smallest distance between parallel planes of the arrangement @p fields carries (world
  /// units); 0 when @p fields carry none.
  static double SmallestSpacing(vtkFieldData* fields);

  /**
   * The arrangement of @p families with @p parameters, built once for the stages of a pipeline
   * that each rebuild the same one from the field data (the arrangement, the solver, the mesh:
   * three builds of a third of a large run each before). The last one built is kept (one, under a
   * lock) until another is asked for. @throw msynth::Error as PlaneArrangement's constructor.
   */
  static std::shared_ptr<const msynth::PlaneArrangement> SharedArrangement(
    const msynth::PlaneFamilySet& families, const msynth::ArrangementParameters& parameters);
};

#endif
