// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class vtkMSLabelGridReader
 * @brief Reads a discrete example model (a label grid): VTK image data (.vti), the text
 * format of the original model-synthesis program (.txt, see msynth/TextModel.h) or a
 * MagicaVoxel model (.vox: palette index = label, empty = 0; field data `PaletteRGBA` holds
 * the 256 palette colours; see msynth/VoxModel.h).
 *
 * A .vti file must hold an integer array of labels (default name `Label`), as point data (one
 * label per point: a point is a site of the model) or as cell data (one label per voxel; the
 * output then has one point per input cell, at the cell centers). The output is vtkImageData
 * whose point data holds exactly one array, a vtkIntArray named `Label`, and whose field data
 * holds `ExampleFile` (the file name), so the source of a result can be traced.
 *
 * A .txt file gives X Y Z and the labels slice by slice; its optional <Objects> section names
 * the pieces of each label, returned as field data `PieceLabels` (int) and `PieceNames`
 * (string), one entry per piece. Spacing 1, origin 0.
 *
 * Dissertation §3.1: labels are integers; 2D examples have one layer in z.
 *
 * Output port 1 (GetGeometryOutput) is the example's voxel surface, vtkPolyData with the cell
 * scalars `Label` (vtkMSLabelArrays::VoxelSurface), so a viewer shows the model rather than the
 * outline of a label image; sites holding EmptyLabel (0: the empty voxel of .vox and of the text
 * format) give none. Under MPI each piece holds a slab of the sites. GenerateGeometry off leaves
 * it empty.
 *
 * @warning A file claiming more than MaximumNumberOfSites sites is refused before any array is
 * allocated.
 *
 * @sa vtkMSTransitionTables, vtkMSOpenVDBWriter
 */
#ifndef vtkMSLabelGridReader_h
#define vtkMSLabelGridReader_h

#include "ModelSynthIOModule.h" // for export macro
#include "vtkImageAlgorithm.h"
#include "vtkSmartPointer.h" // for ivars

#include <string> // for ivar

class vtkPolyData;
class vtkXMLImageDataReader;

class MODELSYNTHIO_EXPORT vtkMSLabelGridReader : public vtkImageAlgorithm
{
public:
  static vtkMSLabelGridReader* New();
  vtkTypeMacro(vtkMSLabelGridReader, vtkImageAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /// The .vti file to read. No default.
  vtkSetStdStringFromCharMacro(FileName);
  vtkGetCharFromStdStringMacro(FileName);
  ///@}

  ///@{
  /// Name of the integer label array in the file. Default "Label". The output array is
  /// always named "Label".
  vtkSetStdStringFromCharMacro(LabelArrayName);
  vtkGetCharFromStdStringMacro(LabelArrayName);
  ///@}

  ///@{
  /// The largest example accepted, in sites. Default 2^27 (134,217,728).
  vtkSetClampMacro(MaximumNumberOfSites, vtkIdType, 1, VTK_ID_MAX);
  vtkGetMacro(MaximumNumberOfSites, vtkIdType);
  ///@}

  ///@{
  /// Whether a .vox file is read whole: every model placed where its scene puts it (a voxel
  /// tileset's model.vox), rather than its first model. Default off.
  vtkSetMacro(VoxScene, bool);
  vtkGetMacro(VoxScene, bool);
  vtkBooleanMacro(VoxScene, bool);
  ///@}

  ///@{
  /// Whether output port 1 holds the example's voxel surface. Default on.
  vtkSetMacro(GenerateGeometry, bool);
  vtkGetMacro(GenerateGeometry, bool);
  vtkBooleanMacro(GenerateGeometry, bool);
  /// The label that gives no geometry on port 1. Default 0.
  vtkSetMacro(EmptyLabel, int);
  vtkGetMacro(EmptyLabel, int);
  ///@}

  /// Output port 1: the example's voxel surface.
  vtkPolyData* GetGeometryOutput();

  /// True when @p name looks like a file this reader opens (.vti, .txt or .vox).
  static int CanReadFile(const char* name);

protected:
  vtkMSLabelGridReader();
  ~vtkMSLabelGridReader() override;

  int RequestInformation(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int FillOutputPortInformation(int port, vtkInformation* info) override;

private:
  vtkMSLabelGridReader(const vtkMSLabelGridReader&) = delete;
  void operator=(const vtkMSLabelGridReader&) = delete;

  /// Reads the file's header into the internal reader and decides the label association.
  bool ReadHeader();
  /// Reads a text-format example (cached while the file is unchanged).
  bool ReadText();
  void Fail(const std::string& problem);
  /// Reads the labels into @p output; false after an error.
  bool ReadGrid(vtkImageData* output);

  std::string FileName;
  std::string LabelArrayName = "Label";
  vtkIdType MaximumNumberOfSites = vtkIdType(1) << 27;
  bool VoxScene = false;
  bool GenerateGeometry = true;
  int EmptyLabel = 0;

  vtkSmartPointer<vtkXMLImageDataReader> Reader;
  bool LabelsOnCells = false;
  bool IsText = false;

  struct Internals;
  Internals* Internal;
};

#endif
