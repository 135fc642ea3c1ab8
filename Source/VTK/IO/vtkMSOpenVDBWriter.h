// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class vtkMSOpenVDBWriter
 * @brief Writes vtkImageData arrays as OpenVDB grids (.vdb) for renderers (Blender, Houdini).
 *
 * Each point-data array becomes a grid of the same name: integer arrays become Int32Grid,
 * float and double arrays FloatGrid, 3-component arrays Vec3SGrid; other arrays are skipped
 * with a warning. Cell-data arrays are written the same way, positioned at the cell centers
 * (with suffix `_cell` when a point array has the same name). The VDB transform maps index
 * (i, j, k) of the image's extent to Origin + (i, j, k) * Spacing, so the grid sits where the
 * image does. A 2D image becomes a one-voxel slab.
 *
 * Voxels equal to the background (EmptyLabel for the label array, 0 for the rest) stay
 * inactive, so label volumes are sparse. WriteFloatLabels adds a float copy of the label grid
 * (`<name>_float`) for tools that only read float grids (Debian's pyopenvdb, for one).
 *
 * Metadata: the file gets `generator` = "ModelSynth <version>", every single-valued array of
 * the input's field data as a string (e.g. `ExampleFile` from the readers, the solvers' `Seed`
 * and run statistics; not `Seconds`, so equal runs give equal files), names by id as
 * `label_names` (from `PieceLabels`/`PieceNames`, the text format's pieces) and
 * `object_type_names` (from `TypeIds`/`TypeNames`), and the pairs given with AddMetadata(). Each
 * grid records `vtk_array` and `vtk_association` (point or cell).
 *
 * The file is written atomically: to a temporary file in the same folder, renamed when
 * complete. A failed write reports an error and leaves no partial file.
 *
 * **Meshes** (vtkPolyData of closed, outward polygon surfaces) become narrow-band level sets
 * (`GRID_CLASS` level set, negative inside; OpenVDB's mesh-to-volume) with a voxel size of
 * VoxelSize (0: the longest extent / 256) and a band of BandWidth voxels on each side:
 * `surface` for the whole model, and for a continuous synthesis model (cell arrays
 * `InsideType`, `OutsideType` from vtkMSArrangementMesh) also `surface_<type>` per object type
 * (the type's name from the field data array `TypeNames` when present). With WriteFog, the fog
 * volume `density` of `surface` too, for volume renderers. Flat (2D) meshes are refused.
 *
 * **Points without polygons** (the vertices of a plane arrangement, e.g. the output of
 * vtkMSContinuousSynthesis with `Label`, `CatalogSize`, `Entropy`) are resampled to a grid of
 * VoxelSize (0: the longest extent / 128), every voxel taking the values of the nearest point,
 * and written as image data is.
 *
 * **Continuous models:** with the model's labelled arrangement on port 1 (the output of
 * vtkMSContinuousSynthesis: SetArrangementConnection) and VoxelSize 0, the voxels follow the
 * planes: max(s / 4, E / 256) for the mesh, s the smallest distance between parallel planes
 * and E the longest extent of the arrangement's box; points that carry their arrangement (the
 * solver's output, e.g. its catalog snapshots) get max(s / 2, E / 128). A flat model (cell
 * array `ObjectType`: a 2D example's) or one without polygons is written as the label grid
 * `ObjectType` (and `ObjectType_float`) of the object type at each voxel's centre over the
 * arrangement's box (`VoxelizeModel`). A grid of more than MaximumVoxels voxels is refused.
 *
 * **Render grids** (WriteRenderGrids, on by default): an image with the integer point array
 * LabelArrayName (a discrete model) also gets what renderers shade, on the label grid's
 * transform (msynth::vdb::LabelRenderView, VDB/RenderGrids.h): `density` (fog volume, 1 at the
 * solid sites, those whose label is not EmptyLabel), `color` (Vec3SGrid, the linear RGB of each
 * solid site's label: the `.vox` example's palette `PaletteRGBA`, else msynth::LabelColor, as
 * mesh.vtp and mesh.glb are coloured), `surface` (level set: the exact signed distance to the
 * solid sites' voxel boundary, negative inside, a band of BandWidth voxels) and `surface_NAME`
 * per named label (a tileset's tiles, a text example's pieces; the keys of the point array
 * NameArrayName when set) while sites × names ≤ LabelSurfaceBudget (`surface`'s metadata
 * `msynth_label_surfaces` says when they are skipped). Only for image inputs: not for points
 * resampled or continuous models voxelized (a continuous model's mesh gets its own `density`
 * and `surface`). msynth turns them off for catalog snapshots (undecided sites).
 *
 * **Sequences:** with WriteTimeSteps and an input that has time steps (e.g. the catalog
 * snapshots of the solver filters), Write() writes one file per step, numbered from 1 with four
 * digits before the extension (`catalog.vdb` → `catalog_0001.vdb`, `catalog_0002.vdb`, …), as
 * Blender and Houdini load sequences. Each file is written atomically.
 *
 * Under MPI (pvbatch --mpi) piece 0 asks for the whole input and writes it; the other pieces
 * ask for nothing and write nothing.
 *
 * @sa vtkMSOpenVDBReader
 */
#ifndef vtkMSOpenVDBWriter_h
#define vtkMSOpenVDBWriter_h

#include "ModelSynthIOModule.h" // for export macro
#include "vtkWriter.h"

#include "vtkSmartPointer.h" // for the resampled image

#include <array>   // for GridDimensions
#include <cstdint> // for GridDimensions
#include <memory>  // for std::unique_ptr
#include <string>  // for ivars

class vtkImageData;
class vtkPolyData;

class MODELSYNTHIO_EXPORT vtkMSOpenVDBWriter : public vtkWriter
{
public:
  static vtkMSOpenVDBWriter* New();
  vtkTypeMacro(vtkMSOpenVDBWriter, vtkWriter);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /// The .vdb file to write. No default.
  vtkSetStdStringFromCharMacro(FileName);
  vtkGetCharFromStdStringMacro(FileName);
  ///@}

  ///@{
  /// The name of the label array, whose background is EmptyLabel. Default "Label".
  vtkSetStdStringFromCharMacro(LabelArrayName);
  vtkGetCharFromStdStringMacro(LabelArrayName);
  ///@}

  ///@{
  /// The empty label: the inactive background of the label grid. Default 0.
  vtkSetMacro(EmptyLabel, int);
  vtkGetMacro(EmptyLabel, int);
  ///@}

  ///@{
  /// Also write the labels as a FloatGrid named `<LabelArrayName>_float`. Default off.
  vtkSetMacro(WriteFloatLabels, bool);
  vtkGetMacro(WriteFloatLabels, bool);
  vtkBooleanMacro(WriteFloatLabels, bool);
  ///@}

  ///@{
  /// Meshes: the voxel size in world units (0: the mesh's longest extent / 256). Default 0.
  vtkSetClampMacro(VoxelSize, double, 0.0, VTK_DOUBLE_MAX);
  vtkGetMacro(VoxelSize, double);
  ///@}

  ///@{
  /// Meshes and voxelized models: the most voxels a grid may have (default 10^9).
  vtkSetClampMacro(MaximumVoxels, double, 1.0, 1e18);
  vtkGetMacro(MaximumVoxels, double);
  ///@}

  ///@{
  /// Port 1, optional: a continuous model's labelled arrangement (see above).
  void SetArrangementConnection(vtkAlgorithmOutput* arrangement)
  {
    this->SetInputConnection(1, arrangement);
  }
  void SetArrangementData(vtkDataObject* arrangement) { this->SetInputData(1, arrangement); }
  ///@}

  ///@{
  /// A continuous model's level sets (VoxelSize 0): coarser voxels where their bands would hold
  /// more than this many voxels (msynth::LevelSetVoxel), so a large model costs about what a
  /// small one does; 0 (the default) for no such limit.
  vtkSetClampMacro(LevelSetBudget, double, 0.0, 1e18);
  vtkGetMacro(LevelSetBudget, double);
  ///@}

  /// The voxel size the last write used (VoxelSize, or the one chosen).
  vtkGetMacro(WrittenVoxelSize, double);

  ///@{
  /// Meshes: the narrow band's half width in voxels. Default 3.
  vtkSetClampMacro(BandWidth, double, 1.0, 1000.0);
  vtkGetMacro(BandWidth, double);
  ///@}

  ///@{
  /// Meshes: also write the fog volume `density`. Default on.
  vtkSetMacro(WriteFog, bool);
  vtkGetMacro(WriteFog, bool);
  vtkBooleanMacro(WriteFog, bool);
  ///@}

  ///@{
  /// Write every time step of the input to its own numbered file (see above). Default off.
  vtkSetMacro(WriteTimeSteps, bool);
  vtkGetMacro(WriteTimeSteps, bool);
  vtkBooleanMacro(WriteTimeSteps, bool);
  ///@}

  ///@{
  /// Label images: also write the render grids `density`, `color`, `surface` and
  /// `surface_NAME` (see above). Default on.
  vtkSetMacro(WriteRenderGrids, bool);
  vtkGetMacro(WriteRenderGrids, bool);
  vtkBooleanMacro(WriteRenderGrids, bool);
  ///@}

  ///@{
  /// Label images: `surface_NAME` grids are written while sites × named labels is at most this
  /// (each is a pass over its label's bounding box). Default 2e7.
  vtkSetClampMacro(LabelSurfaceBudget, double, 0.0, 1e18);
  vtkGetMacro(LabelSurfaceBudget, double);
  ///@}

  ///@{
  /// Label images: the integer point array whose values key the names of `surface_NAME`
  /// ("" (the default): the labels themselves).
  vtkSetStdStringFromCharMacro(NameArrayName);
  vtkGetCharFromStdStringMacro(NameArrayName);
  ///@}

  /// Writes the file, or with WriteTimeSteps the sequence. Returns 1 on success.
  int Write() override;
  /// The file written for step @p index (0-based) of a sequence: `<stem>_<index + 1>.vdb`.
  std::string SequenceFileName(int index) const;

  ///@{
  /// The piece this process writes, and how many there are (set by ParaView under MPI).
  /// Only piece 0 writes the file. Defaults 0 and 1.
  vtkSetMacro(Piece, int);
  vtkGetMacro(Piece, int);
  vtkSetMacro(NumberOfPieces, int);
  vtkGetMacro(NumberOfPieces, int);
  ///@}

  ///@{
  /// File metadata added to every file written (key → string value).
  void AddMetadata(const char* key, const char* value);
  void ClearMetadata();
  ///@}

  /// Input as image data (convenience).
  vtkImageData* GetImageDataInput();

protected:
  vtkMSOpenVDBWriter();
  ~vtkMSOpenVDBWriter() override;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  vtkTypeBool ProcessRequest(vtkInformation* request, vtkInformationVector** inputVector,
    vtkInformationVector* outputVector) override;
  void WriteData() override;
  /// The polydata branch of WriteData.
  void WriteMesh(vtkPolyData* input);
  /// Points without polygons (a plane arrangement): their point arrays sampled on a grid of
  /// VoxelSize (0: the longest extent / 128), each voxel from the nearest point.
  vtkSmartPointer<vtkImageData> ResamplePoints(vtkPolyData* input);
  /// A continuous model without volume (flat, or no polygons) as a label grid `ObjectType`
  /// over the box of @p arrangement.
  vtkSmartPointer<vtkImageData> VoxelizeTypes(vtkPolyData* model, vtkPolyData* arrangement);
  /// VoxelSize; else from the planes of @p arrangement (when it carries them): max(s /
  /// @p perSpacing, E / @p perExtent); else @p extent / @p perExtent (1 when 0).
  double ChooseVoxel(vtkPolyData* arrangement, double perSpacing, double perExtent, double extent);
  /// @throw msynth::Error when a grid over @p bounds (x and y only when @p planar) with voxels
  /// of @p voxel would have more than MaximumVoxels; the grid's dimensions otherwise.
  std::array<std::int64_t, 3> GridDimensions(const double bounds[6], double voxel, bool planar);
  /// Reports a failed write (once, naming the file) and sets the error code.
  void ReportFailure(const std::string& what);

private:
  vtkMSOpenVDBWriter(const vtkMSOpenVDBWriter&) = delete;
  void operator=(const vtkMSOpenVDBWriter&) = delete;

  std::string FileName;
  std::string LabelArrayName = "Label";
  int EmptyLabel = 0;
  bool WriteFloatLabels = false;
  double VoxelSize = 0;
  double MaximumVoxels = 1e9;
  double BandWidth = 3;
  double LevelSetBudget = 0;
  double WrittenVoxelSize = 0;
  bool WriteFog = true;
  bool WriteTimeSteps = false;
  bool WriteRenderGrids = true;
  double LabelSurfaceBudget = 2e7;
  std::string NameArrayName;
  std::string CurrentFileName; ///< the file being written (FileName, or a sequence member)
  bool WritingSequence = false;
  double CurrentTime = 0; ///< the time step being written in a sequence
  int Piece = 0;
  int NumberOfPieces = 1;

  struct Internals;
  std::unique_ptr<Internals> Internal;
};

#endif
