// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class vtkMSNeighbourhoodLabels
 * @brief The catalog of continuous model synthesis: the neighbourhood labels of a polyhedral
 * example (dissertation §4.5.1–4.5.4, TVCG §4.2–4.3; msynth::PolyhedralAnalysis).
 *
 * Input: polygons with cell arrays `ObjectType` (default 1) and `ObjectId` (default: connected
 * components), as vtkMSPolyhedralExampleReader produces; validated again here.
 *
 * Output 0, a vtkTable with one row per label: `Id`, `Kind` (volume, face, edge, vertex; in 2D
 * region, edge, vertex), `Codimension`, `Families` ("h1 h3"), `HalfSpaces` (how many),
 * `Expression` (the Boolean expression, e.g. "h1 ∩ (h2 ∪ h3)"), `Occurrences` (sampled features
 * of the example with this label) and `ObjectTypes` present. Field data: `FamilyNormals` (the
 * exact integer normals, 3 components), `FamilyUnitNormals`, `Planar`.
 *
 * Output 1, the example marked with label ids, so one sees which parts are "the same"
 * neighbourhood: its faces (polygons; −1 where a face has several labels because another
 * object covers part of it; in 2D the regions carry their interior label), its edge pieces
 * (lines, split where other objects touch them) and its vertices (vertex cells). Cell arrays
 * `LabelId`, `Codimension` and `ObjectType` (−1 on lines and vertices).
 *
 * @sa vtkMSPolyhedralExampleReader
 */
#ifndef vtkMSNeighbourhoodLabels_h
#define vtkMSNeighbourhoodLabels_h

#include "ModelSynthFiltersModule.h" // for export macro
#include "vtkTableAlgorithm.h"

class vtkPolyData;
class vtkTable;

class MODELSYNTHFILTERS_EXPORT vtkMSNeighbourhoodLabels : public vtkTableAlgorithm
{
public:
  static vtkMSNeighbourhoodLabels* New();
  vtkTypeMacro(vtkMSNeighbourhoodLabels, vtkTableAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /// Output 0, the catalog of labels.
  vtkTable* GetLabelTable();
  /// Output 1, the example marked with label ids.
  vtkPolyData* GetMarkedExample();

  ///@{
  /// Faces whose normals differ by less than this angle (degrees) share a plane family.
  /// Default 0.01.
  vtkSetClampMacro(AngleTolerance, double, 1e-9, 10.0);
  vtkGetMacro(AngleTolerance, double);
  ///@}

  ///@{
  /// Largest integer component tried when snapping family normals to exact small directions.
  /// Default 12.
  vtkSetClampMacro(MaximumSmallInteger, int, 1, 1000);
  vtkGetMacro(MaximumSmallInteger, int);
  ///@}

protected:
  vtkMSNeighbourhoodLabels();
  ~vtkMSNeighbourhoodLabels() override;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  int FillOutputPortInformation(int port, vtkInformation* info) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

private:
  vtkMSNeighbourhoodLabels(const vtkMSNeighbourhoodLabels&) = delete;
  void operator=(const vtkMSNeighbourhoodLabels&) = delete;

  double AngleTolerance = 0.01;
  int MaximumSmallInteger = 12;
};

#endif
