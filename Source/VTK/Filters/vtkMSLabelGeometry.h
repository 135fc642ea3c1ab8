// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class vtkMSLabelGeometry
 * @brief Geometry of a label grid (an example or a synthesized model): the model pieces of each
 * label placed at its sites, or, for labels without a piece, the voxel surface.
 *
 * Input: vtkImageData with the integer point array `Label` (else the active scalars).
 *
 * Pieces: PieceDirectory names a folder holding one mesh per label, named after the label value:
 * `<label>.vtp`, `.obj`, `.ply` or `.stl` (e.g. `2.obj` for label 2; extensions in any case), or
 * after the pieces the example names for the label: the `$name` entries of a `.txt` example's
 * `<Objects>` section, carried as the field data `PieceLabels`/`PieceNames` of the reader and of
 * vtkMSDiscreteSynthesis (`round.obj` for `$round`; a label with several such pieces gets all
 * of those found, drawn together). A label's number goes before its piece names. A piece is
 * modelled in the unit cube [-0.5, 0.5]³ around its site and is scaled by the image spacing and
 * moved to the site. Labels without a piece file, or all labels when PieceDirectory is empty, give
 * the voxel surface: each site is a cube, with a face wherever it meets another label or the
 * outside, oriented outward (each label's surface is closed).
 *
 * Tilesets: with TilesetFile (the model of vtkMSDiscreteSynthesis in tileset mode, where label
 * i is orientation k of a tile), a label's piece may also be named after its tile: `<tile>.obj`
 * (etc.) is turned for each orientation as the tile images are: orientation k is k quarter turns
 * counter-clockwise about +z, and orientations 4–7 mirror 0–3 left-right (x → −x, polygons
 * reversed so they stay outward). `<tile> <k>.obj` gives orientation k as it is. Lookup order
 * per label: `<label>.ext`, `<tile> <k>.ext`, `<tile>.ext` (turned).
 *
 * The folder is checked: a missing or empty folder, or one where no file has a piece's name, is
 * an error naming the folder and the names expected; files that match no name (OBJ material
 * libraries and textures aside) are named in one warning, also kept as the one-value string
 * field data `PieceFolderWarning` of the output.
 *
 * Output: vtkPolyData with the cell array `Label`, and `PaletteColor` (RGBA) when the input
 * carries a palette (a `.vox` example, or a model made from one). Sites with EmptyLabel produce
 * nothing.
 *
 * @sa vtkMSDiscreteSynthesis, vtkMSLabelGridReader
 */
#ifndef vtkMSLabelGeometry_h
#define vtkMSLabelGeometry_h

#include "ModelSynthFiltersModule.h" // for export macro
#include "vtkPolyDataAlgorithm.h"

#include <string> // for ivar

class MODELSYNTHFILTERS_EXPORT vtkMSLabelGeometry : public vtkPolyDataAlgorithm
{
public:
  static vtkMSLabelGeometry* New();
  vtkTypeMacro(vtkMSLabelGeometry, vtkPolyDataAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /// The label that produces no geometry. Default 0.
  vtkSetMacro(EmptyLabel, int);
  vtkGetMacro(EmptyLabel, int);
  ///@}

  ///@{
  /// Folder of piece meshes named by label; empty for the voxel surface only. Default "".
  vtkSetStdStringFromCharMacro(PieceDirectory);
  vtkGetCharFromStdStringMacro(PieceDirectory);
  ///@}

  ///@{
  /// The tileset whose model this is (its labels are tile orientations); empty for none.
  vtkSetStdStringFromCharMacro(TilesetFile);
  vtkGetCharFromStdStringMacro(TilesetFile);
  /// The tileset's subset the model was made with (label numbering depends on it).
  vtkSetStdStringFromCharMacro(TilesetSubset);
  vtkGetCharFromStdStringMacro(TilesetSubset);
  ///@}

protected:
  vtkMSLabelGeometry() = default;
  ~vtkMSLabelGeometry() override = default;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

private:
  vtkMSLabelGeometry(const vtkMSLabelGeometry&) = delete;
  void operator=(const vtkMSLabelGeometry&) = delete;

  int EmptyLabel = 0;
  std::string PieceDirectory;
  std::string TilesetFile;
  std::string TilesetSubset;
};

#endif
