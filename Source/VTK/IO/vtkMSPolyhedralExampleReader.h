// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class vtkMSPolyhedralExampleReader
 * @brief Reads the example of continuous model synthesis: closed polyhedra of several object
 * types (or polygons in the plane z = 0 for 2D examples), validated.
 *
 * Formats:
 * - OBJ: each `o` or `g` block is one object; objects whose names differ only by a numeric
 *   suffix ("Cube.001") share an object type; types are numbered 1, 2, … by first appearance,
 *   or set with ObjectTypes ("roof=2;wall=1").
 * - VTP: cell arrays `ObjectType` (default 1) and `ObjectId` (default: connected components).
 * - PLY, STL: one object type; each connected component is an object.
 *
 * The output holds the polygons, oriented outward (counter-clockwise in 2D), with cell arrays
 * `ObjectType` and `ObjectId`, and field data `ExampleFile`, `TypeIds`/`TypeNames` and
 * `ObjectNames` (by ObjectId: an OBJ's `o`/`g` names, else "object N" counted from 1).
 *
 * Up axis: ModelSynth takes z as up (the ground, Grounded, overhangs). A file modelled with y
 * up (OBJ as most tools write it, Blender's default export: Forward −Z, Up Y) is read with
 * UpAxis = 1 and turned, (x, y, z) → (x, −z, y) (msynth::TurnYUpToZUp).
 *
 * Validation (msynth::ValidateExample): degenerate or non-planar faces, surfaces that are not
 * closed, non-manifold edges or vertices, inconsistent orientation and self-intersections are
 * errors naming the file, object and face; the request fails.
 *
 * @sa vtkMSNeighbourhoodLabels
 */
#ifndef vtkMSPolyhedralExampleReader_h
#define vtkMSPolyhedralExampleReader_h

#include "ModelSynthIOModule.h" // for export macro
#include "vtkPolyDataAlgorithm.h"

#include <string> // for ivars

class MODELSYNTHIO_EXPORT vtkMSPolyhedralExampleReader : public vtkPolyDataAlgorithm
{
public:
  static vtkMSPolyhedralExampleReader* New();
  vtkTypeMacro(vtkMSPolyhedralExampleReader, vtkPolyDataAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /// The file to read (.obj, .vtp, .ply or .stl).
  vtkSetStdStringFromCharMacro(FileName);
  vtkGetCharFromStdStringMacro(FileName);
  ///@}

  ///@{
  /// OBJ object names mapped to object types, "name=type" separated by ';' or ','. A name
  /// matches an object's full name or its name without numeric suffix. Default: empty.
  vtkSetStdStringFromCharMacro(ObjectTypes);
  vtkGetCharFromStdStringMacro(ObjectTypes);
  ///@}

  ///@{
  /// The file's up axis: 2 (z, default) or 1 (y, turned to z on reading).
  vtkSetClampMacro(UpAxis, int, 1, 2);
  vtkGetMacro(UpAxis, int);
  ///@}

  /// True for the extensions this reader opens.
  static int CanReadFile(const char* name);

protected:
  vtkMSPolyhedralExampleReader();
  ~vtkMSPolyhedralExampleReader() override;

  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

private:
  vtkMSPolyhedralExampleReader(const vtkMSPolyhedralExampleReader&) = delete;
  void operator=(const vtkMSPolyhedralExampleReader&) = delete;

  std::string FileName;
  std::string ObjectTypes;
  int UpAxis = 2;
};

#endif
