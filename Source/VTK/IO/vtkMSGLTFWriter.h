// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class vtkMSGLTFWriter
 * @brief Writes a mesh as binary glTF 2.0 (`.glb`, for game engines and Blender) with one
 * material per label, colour or object type.
 *
 * Input: vtkPolyData, such as the output of vtkMSLabelGeometry (a model's voxel surface or its
 * pieces). Polygons and triangle strips are triangulated (concave pieces too); vertices and
 * lines are left out. Cells are grouped by the integer cell array LabelArrayName (default
 * `Label`) and, when present, the colour array ColorArrayName (default `PaletteColor`: RGB or
 * RGBA bytes per cell, the palette of a `.vox` example); each group becomes a mesh and node
 * named `label <L>` (with `#rrggbb` when coloured) with its own material: the colour array's
 * colour, else the label's colour in every picture of the project (msynth::LabelColor, the
 * palette of render-model.py and the plugin's Label colour map). Without the label array all
 * cells form one grey mesh. The groups are ordered by label, then colour.
 *
 * A continuous model's mesh (vtkMSArrangementMesh: cell arrays `InsideType` and `OutsideType`,
 * or `ObjectType` in 2D; field data `TypeNames`), and a polyhedral example (`ObjectType`), when
 * it has no label array, is written by object type instead: one mesh, node and material per
 * solid type, named by the type's name (`wall`, `roof`; `type <T>` when unnamed), coloured as
 * the type is in every picture (msynth::LabelColor of the type, as model.vtp is drawn). Each
 * mesh is its type's closed surface (the polygons with InsideType T as they are and those with
 * OutsideType T reversed), flat-shaded with normals that point out of the type; a face between
 * two types is in both meshes, facing out of each. Polygons are triangulated without degenerate
 * triangles (msynth::AppendFlatPolygons). A flat (2D) model's materials are double-sided.
 *
 * glTF is y up: the model's z becomes glTF's y (Blender's importer turns it back). Colours are
 * written linear, as glTF specifies, so viewers show the sRGB colours of the palette. The file
 * is written atomically (complete or absent); every error is one line naming the file.
 *
 * @sa vtkMSLabelGeometry, vtkMSArrangementMesh, msynth::WriteGlbFile (Formats/GltfFile.h)
 */
#ifndef vtkMSGLTFWriter_h
#define vtkMSGLTFWriter_h

#include "ModelSynthIOModule.h" // for export macro
#include "vtkWriter.h"

#include <string> // for ivars

class MODELSYNTHIO_EXPORT vtkMSGLTFWriter : public vtkWriter
{
public:
  static vtkMSGLTFWriter* New();
  vtkTypeMacro(vtkMSGLTFWriter, vtkWriter);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /// The .glb file to write. No default.
  vtkSetStdStringFromCharMacro(FileName);
  vtkGetCharFromStdStringMacro(FileName);
  ///@}

  ///@{
  /// The integer cell array that names each cell's label. Default "Label".
  vtkSetStdStringFromCharMacro(LabelArrayName);
  vtkGetCharFromStdStringMacro(LabelArrayName);
  ///@}

  ///@{
  /// The cell array of colours (3 or 4 components, 0-255), used when present.
  /// Default "PaletteColor".
  vtkSetStdStringFromCharMacro(ColorArrayName);
  vtkGetCharFromStdStringMacro(ColorArrayName);
  ///@}

protected:
  vtkMSGLTFWriter() = default;
  ~vtkMSGLTFWriter() override = default;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  void WriteData() override;

private:
  vtkMSGLTFWriter(const vtkMSGLTFWriter&) = delete;
  void operator=(const vtkMSGLTFWriter&) = delete;

  std::string FileName;
  std::string LabelArrayName = "Label";
  std::string ColorArrayName = "PaletteColor";
};

#endif
