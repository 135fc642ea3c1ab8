// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class vtkMSArrangementMesh
 * @brief Mesh extraction of continuous model synthesis (dissertation §4.5.8;
 * msynth::ExtractMesh): the surface of a labelled plane arrangement.
 *
 * Input 0: the polyhedral example. Input 1: the output of vtkMSContinuousSynthesis (the
 * arrangement with point array `Label`, or `ModelLabel` when it has catalog time steps, so the
 * mesh is the finished model at every time).
 *
 * Output, a vtkPolyData of convex polygons (coplanar neighbours are not merged; every
 * arrangement vertex on a polygon's boundary is one of its corners, so the mesh has no
 * T-junctions):
 * - 3D: the faces where the object type changes, with cell arrays `InsideType` and
 *   `OutsideType`; the normal points from inside to outside. The surface of type t is the
 *   polygons with InsideType t and, reversed, those with OutsideType t: closed and oriented.
 * - 2D: the faces of the line arrangement with an object, with cell array `ObjectType`.
 * Point array `ArrangementVertex`; field data `ExampleFile` and `TypeNames` (the object type
 * names by type id, 0 = "empty"), `SmallestSpacing` (the arrangement's, for a later check) and
 * the narrowest face, edge or gap of the synthesized model, `SmallestFeature` and
 * `SmallestFeatureFraction` (of SmallestSpacing; msynth::SmallestFeature).
 *
 * With CheckModel on, the output is verified without trusting the solver (the example
 * analysis is run on it: msynth::CheckContinuousModel); the field data array `ModelCheck`
 * says "valid" or names the problem, which is also an error. It costs more than synthesis.
 *
 * @sa vtkMSPlaneArrangement vtkMSContinuousSynthesis
 */
#ifndef vtkMSArrangementMesh_h
#define vtkMSArrangementMesh_h

#include "ModelSynthFiltersModule.h" // for export macro
#include "vtkPolyDataAlgorithm.h"
#include <string> // for std::string

class MODELSYNTHFILTERS_EXPORT vtkMSArrangementMesh : public vtkPolyDataAlgorithm
{
public:
  static vtkMSArrangementMesh* New();
  vtkTypeMacro(vtkMSArrangementMesh, vtkPolyDataAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /// The labelled arrangement input (port 1).
  void SetArrangementConnection(vtkAlgorithmOutput* output) { this->SetInputConnection(1, output); }

  ///@{
  /// Verify the output against the example (see the class description). Default off.
  vtkSetMacro(CheckModel, bool);
  vtkGetMacro(CheckModel, bool);
  vtkBooleanMacro(CheckModel, bool);
  ///@}

  ///@{
  /// Bounding volumes (TVCG §4.8): with a detail mesh on input port 2 (closed surfaces, authored
  /// inside the example's bounding volume of this object type, a number or name), every part of
  /// that type in the output is replaced by a copy of it mapped onto the part's bounding box.
  /// "TYPE+TYPE": a bounding volume made of pieces of several types (a box cut into prisms).
  /// The field data then has `DetailScales` (per part) and `DetailAnisotropy`. Default "".
  vtkSetStdStringFromCharMacro(DetailType);
  vtkGetCharFromStdStringMacro(DetailType);
  ///@}
  /// The optional detail mesh (port 2).
  void SetDetailConnection(vtkAlgorithmOutput* output) { this->SetInputConnection(2, output); }

protected:
  vtkMSArrangementMesh();
  ~vtkMSArrangementMesh() override;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

private:
  vtkMSArrangementMesh(const vtkMSArrangementMesh&) = delete;
  void operator=(const vtkMSArrangementMesh&) = delete;

  bool CheckModel = false;
  std::string DetailType;
};

#endif
