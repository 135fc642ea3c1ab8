// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class vtkMSPlaneArrangement
 * @brief The plane arrangement of continuous model synthesis (dissertation §4.5.2, §4.5.7;
 * msynth::PlaneArrangement): evenly spaced planes of every plane family of a polyhedral example,
 * clipped to the output box, with their vertices computed exactly.
 *
 * Input: the example (polygons with `ObjectType`, as vtkMSPolyhedralExampleReader gives).
 *
 * Output, a vtkPolyData: one point and one vertex cell per arrangement vertex, and one line per
 * edge between consecutive vertices. Point arrays `Families` (bit i set when a plane of family i
 * passes through), `NumberOfFamilies` and `CatalogSize` (the labels allowed there before
 * solving: the catalog's start). Cell array `Direction` (the line's direction class, −1 on
 * vertex cells). Field data: the exact parameters (`ArrangementOrigin`, `ArrangementQuantum`,
 * `ArrangementBox`, `FamilyNormals`, `FamilyOffsets`, `FamilySpacings`, `Planar`, ...) from
 * which vtkMSContinuousSynthesis and vtkMSArrangementMesh rebuild the same arrangement, and
 * `ExampleFile`.
 *
 * A planar example (all z = 0) gives the 2D variant with line families; OutputSize[2] is then
 * ignored.
 *
 * @sa vtkMSContinuousSynthesis vtkMSArrangementMesh
 */
#ifndef vtkMSPlaneArrangement_h
#define vtkMSPlaneArrangement_h

#include "ModelSynthFiltersModule.h" // for export macro
#include "vtkPolyDataAlgorithm.h"

#include <string>
#include <vector>

class MODELSYNTHFILTERS_EXPORT vtkMSPlaneArrangement : public vtkPolyDataAlgorithm
{
public:
  static vtkMSPlaneArrangement* New();
  vtkTypeMacro(vtkMSPlaneArrangement, vtkPolyDataAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /// Size of the output box in the example's units, from the example's lowest corner. A zero
  /// component means four times the example's extent along that axis. Default 0 0 0.
  vtkSetVector3Macro(OutputSize, double);
  vtkGetVector3Macro(OutputSize, double);
  ///@}

  ///@{
  /// Plane spacing: 0 derives each family's spacing from the example (the largest spacing that
  /// puts a plane on every example face); S > 0 scales those so the smallest is S, keeping their
  /// ratios. Default 0.
  vtkSetClampMacro(Spacing, double, 0.0, VTK_DOUBLE_MAX);
  vtkGetMacro(Spacing, double);
  ///@}

  ///@{
  /// Faces whose normals differ by less than this angle (degrees) share a plane family.
  vtkSetClampMacro(AngleTolerance, double, 1e-9, 10.0);
  vtkGetMacro(AngleTolerance, double);
  ///@}

  ///@{
  /// Largest integer component tried when snapping family normals exactly. Default 12.
  vtkSetClampMacro(MaximumSmallInteger, int, 1, 1000);
  vtkGetMacro(MaximumSmallInteger, int);
  ///@}

  ///@{
  /// Arrangements with more vertices are refused with an error. Default 20,000,000.
  vtkSetClampMacro(MaximumVertices, vtkIdType, 1, 2000000000);
  vtkGetMacro(MaximumVertices, vtkIdType);
  ///@}

protected:
  vtkMSPlaneArrangement();
  ~vtkMSPlaneArrangement() override;

  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

private:
  struct Corners
  {
    bool NonTrihedral = false; ///< four or more planes meet at a corner of the example
    bool OnLattice = false;    ///< small-integer directions, and every such corner has sites
  };
  /// Analyzes the example with the given direction snapping and fills @p output; what to warn
  /// of goes to Warnings (shown by Warn() for the build that is kept).
  Corners Build(
    vtkPolyData* input, vtkPolyData* output, double angleTolerance, int maximumSmallInteger);
  void Warn();
  /// Builds with directions snapped to small integers within up to 3 degrees when the example
  /// needs four or more planes to meet and they would not otherwise; false to build as usual.
  /// Returns whether @p output holds the build to keep (as given, or on the lattice).
  bool BuildOnLattice(vtkPolyData* input, vtkPolyData* output);
  vtkMSPlaneArrangement(const vtkMSPlaneArrangement&) = delete;
  void operator=(const vtkMSPlaneArrangement&) = delete;

  double OutputSize[3] = { 0, 0, 0 };
  double Spacing = 0;
  double AngleTolerance = 0.01;
  int MaximumSmallInteger = 12;
  std::vector<std::string> Warnings; ///< of the last Build
  vtkIdType MaximumVertices = 20000000;
};

#endif
