// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class vtkMSLabelGridWriter
 * @brief Writes a label image in the formats users come from, by the file's extension:
 * - `.txt`: the original model-synthesis program's text format (msynth/TextModel.h), as that
 *   program writes its outputs: its header ("... x, y, and z extents"), the values, and the
 *   field-data string `TextModelTrailer` that vtkMSLabelGridReader keeps from a `.txt` example
 *   (its `<Objects>` section: scene and pieces per label), unchanged, so the original program's
 *   Blender and 3ds Max loaders place the example's pieces on a synthesized model;
 * - `.vox`: a MagicaVoxel model (msynth/VoxModel.h): label = palette index 1..255, 0 empty, at
 *   most 256 voxels a side; the palette is the field-data array `PaletteRGBA` that the reader
 *   keeps from a `.vox` example (MagicaVoxel's default palette otherwise).
 *
 * Labels are the point array "Label", else the active scalars (integers). Synthesis filters
 * pass the example's field data on, so reader → synthesis → this writer keeps trailer and
 * palette. A `.vox` model past 256 voxels a side is written as MagicaVoxel's scene: pieces of
 * at most 256 a side, each a model placed by its own transform node (msynth::WriteVoxScene), as
 * voxel tilesets' model.vox is.
 *
 * A continuous model (vtkPolyData: vtkMSArrangementMesh's output, cell arrays `InsideType` and
 * `OutsideType`, or `ObjectType`; also a polyhedral example) is written as `.vox` only, voxelized:
 * each voxel holds the object type at its centre (msynth::VoxelizeModel; 0 empty; 2D models one
 * layer), the grid's lowest corner at the model's lowest corner, palette index T coloured as
 * type T is in every picture (msynth::LabelColor, as model.vtp is drawn). VoxelSize 0 chooses
 * half the smallest plane spacing (field data `SmallestSpacing`), at least the longest extent /
 * 256: one MagicaVoxel model. A finer VoxelSize gives a scene of several models, up to
 * MaximumVoxelsPerAxis a side (MagicaVoxel's world reaches 1000 voxels from its centre) and
 * MaximumVoxels in all. Types beyond 255 cannot be palette indices: an error.
 * The file is written atomically (complete or absent); errors name the file.
 *
 * @sa vtkMSLabelGridReader
 */
#ifndef vtkMSLabelGridWriter_h
#define vtkMSLabelGridWriter_h

#include "ModelSynthIOModule.h" // for export macro
#include "vtkWriter.h"

#include <string> // for ivars

class vtkPolyData;

class MODELSYNTHIO_EXPORT vtkMSLabelGridWriter : public vtkWriter
{
public:
  static vtkMSLabelGridWriter* New();
  vtkTypeMacro(vtkMSLabelGridWriter, vtkWriter);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /// The .txt or .vox file to write. No default.
  vtkSetStdStringFromCharMacro(FileName);
  vtkGetCharFromStdStringMacro(FileName);
  ///@}

  ///@{
  /// A continuous model's voxel edge (model units); 0 (default) chooses it (see above).
  vtkSetClampMacro(VoxelSize, double, 0.0, VTK_DOUBLE_MAX);
  vtkGetMacro(VoxelSize, double);
  ///@}

  ///@{
  /// A continuous model's voxels: at most this many along any axis (default 1000) ...
  vtkSetClampMacro(MaximumVoxelsPerAxis, int, 1, 1 << 20);
  vtkGetMacro(MaximumVoxelsPerAxis, int);
  ///@}

  ///@{
  /// ... and in all (default 10^8); a finer VoxelSize is an error before any work.
  vtkSetClampMacro(MaximumVoxels, double, 1.0, 1e12);
  vtkGetMacro(MaximumVoxels, double);
  ///@}

  /// The voxel edge the last write of a continuous model used (VoxelSize, or the one chosen).
  vtkGetMacro(WrittenVoxelSize, double);

protected:
  vtkMSLabelGridWriter() = default;
  ~vtkMSLabelGridWriter() override = default;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  void WriteData() override;

private:
  vtkMSLabelGridWriter(const vtkMSLabelGridWriter&) = delete;
  void operator=(const vtkMSLabelGridWriter&) = delete;

  void WriteModelVoxels(vtkPolyData* model);

  std::string FileName;
  double VoxelSize = 0;
  int MaximumVoxelsPerAxis = 1000;
  double MaximumVoxels = 1e8;
  double WrittenVoxelSize = 0;
};

#endif
