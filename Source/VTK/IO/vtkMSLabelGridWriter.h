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
 * palette. The file is written atomically (complete or absent); errors name the file.
 *
 * @sa vtkMSLabelGridReader
 */
#ifndef vtkMSLabelGridWriter_h
#define vtkMSLabelGridWriter_h

#include "ModelSynthIOModule.h" // for export macro
#include "vtkWriter.h"

#include <string> // for ivars

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

protected:
  vtkMSLabelGridWriter() = default;
  ~vtkMSLabelGridWriter() override = default;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  void WriteData() override;

private:
  vtkMSLabelGridWriter(const vtkMSLabelGridWriter&) = delete;
  void operator=(const vtkMSLabelGridWriter&) = delete;

  std::string FileName;
};

#endif
