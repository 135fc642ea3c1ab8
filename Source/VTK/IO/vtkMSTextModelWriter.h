// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class vtkMSTextModelWriter
 * @brief Writes a label image in the text format of the original model-synthesis program
 * (msynth/TextModel.h), as that program writes its outputs, so its Blender and 3ds Max loaders
 * place the example's pieces on a synthesized model.
 *
 * The header is the original program's ("... x, y, and z extents"), the values are the input's
 * label array (point data "Label", else the active scalars; integers), and the trailer is the
 * field-data string `TextModelTrailer` that vtkMSLabelGridReader keeps from a `.txt` example
 * (its `<Objects>` section: scene and pieces per label), unchanged. Synthesis filters pass the
 * example's field data on, so reader → synthesis → this writer keeps the pieces.
 *
 * The file is written atomically (complete or absent); errors name the file.
 */
#ifndef vtkMSTextModelWriter_h
#define vtkMSTextModelWriter_h

#include "ModelSynthIOModule.h" // for export macro
#include "vtkWriter.h"

#include <string> // for ivars

class MODELSYNTHIO_EXPORT vtkMSTextModelWriter : public vtkWriter
{
public:
  static vtkMSTextModelWriter* New();
  vtkTypeMacro(vtkMSTextModelWriter, vtkWriter);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /// The .txt file to write. No default.
  vtkSetStdStringFromCharMacro(FileName);
  vtkGetCharFromStdStringMacro(FileName);
  ///@}

  ///@{
  /// The trailer written when the input has no `TextModelTrailer` field data. Default empty.
  vtkSetStdStringFromCharMacro(Trailer);
  vtkGetCharFromStdStringMacro(Trailer);
  ///@}

protected:
  vtkMSTextModelWriter() = default;
  ~vtkMSTextModelWriter() override = default;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  void WriteData() override;

private:
  vtkMSTextModelWriter(const vtkMSTextModelWriter&) = delete;
  void operator=(const vtkMSTextModelWriter&) = delete;

  std::string FileName;
  std::string Trailer;
};

#endif
