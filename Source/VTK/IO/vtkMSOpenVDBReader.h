// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class vtkMSOpenVDBReader
 * @brief Reads OpenVDB files (.vdb) into dense vtkImageData, so volumes open in ParaView and
 * tests can round-trip what vtkMSOpenVDBWriter wrote.
 *
 * Int32 grids become vtkIntArray, float grids vtkFloatArray, vec3s grids 3-component
 * vtkFloatArray, all as point data (a voxel is a point). Grids that share a transform are
 * merged onto the union of their extents (the extent the writer stored, or else the active
 * bounding box); voxels outside a grid's own extent take its background value. When some of
 * them are data grids (no grid class: labels, colours), the union is theirs and level sets and
 * fog volumes are read inside it (a label grid's `surface` band reaches past the labels). Grids
 * with a different transform than the first are skipped with a warning (choose one with GridName).
 * File-level string metadata becomes single-valued string arrays in field data.
 *
 * @warning The dense output is refused, with an error, when it would exceed MaximumNumberOfVoxels.
 *
 * @sa vtkMSOpenVDBWriter
 */
#ifndef vtkMSOpenVDBReader_h
#define vtkMSOpenVDBReader_h

#include "ModelSynthIOModule.h" // for export macro
#include "vtkImageAlgorithm.h"

#include <memory> // for std::unique_ptr
#include <string> // for ivars

class MODELSYNTHIO_EXPORT vtkMSOpenVDBReader : public vtkImageAlgorithm
{
public:
  static vtkMSOpenVDBReader* New();
  vtkTypeMacro(vtkMSOpenVDBReader, vtkImageAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /// The .vdb file to read. No default.
  vtkSetStdStringFromCharMacro(FileName);
  vtkGetCharFromStdStringMacro(FileName);
  ///@}

  ///@{
  /// Read only the grid of this name. Default "" (all grids).
  vtkSetStdStringFromCharMacro(GridName);
  vtkGetCharFromStdStringMacro(GridName);
  ///@}

  ///@{
  /// The largest dense output accepted, in voxels. Default 2^28 (268,435,456).
  vtkSetClampMacro(MaximumNumberOfVoxels, vtkIdType, 1, VTK_ID_MAX);
  vtkGetMacro(MaximumNumberOfVoxels, vtkIdType);
  ///@}

  /// True when @p name ends in .vdb.
  static int CanReadFile(const char* name);

protected:
  vtkMSOpenVDBReader();
  ~vtkMSOpenVDBReader() override;

  int RequestInformation(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

private:
  vtkMSOpenVDBReader(const vtkMSOpenVDBReader&) = delete;
  void operator=(const vtkMSOpenVDBReader&) = delete;

  /// Reads the file (or reuses the last read when name, options and mtime are unchanged).
  bool Load();

  std::string FileName;
  std::string GridName;
  vtkIdType MaximumNumberOfVoxels = vtkIdType(1) << 28;

  struct Internals;
  std::unique_ptr<Internals> Internal;
};

#endif
