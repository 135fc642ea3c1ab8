// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class vtkMSTileImage
 * @brief Composes the picture of a 2D tile model from the tileset's images.
 *
 * Input: vtkImageData of labels (`Label`, else the active scalars), as vtkMSDiscreteSynthesis
 * produces with a TilesetFile; label i is orientation k of a tile (msynth/Tileset.h).
 *
 * Images are found as the format's published tilesets lay them out: a folder named like the
 * XML file beside it (`Castle.xml` + `Castle/<tile>.png`) or, in the older layout, beside
 * `Castle/data.xml`; one image per orientation (`<tile> <k>.png`) when the set is `unique`;
 * `.bmp` where no `.png` exists (msynth::TileImageFile). Otherwise orientation k + 1 is
 * orientation k turned 90° counter-clockwise, and orientations 4-7 mirror 0-3 left-right.
 * All images must be square and of one size T (the set's `size` attribute when it has one).
 *
 * The tileset is TilesetFile, or, when that is empty, the one the input names (the TILESET
 * information of a tileset synthesis upstream, else the input's field data `TilesetFile`); with
 * neither, RequestData reports one error and gives an empty image.
 *
 * Output: vtkImageData of (nx·T) × (ny·T) pixels with the unsigned-char array `RGBA` (four
 * components, the active scalars); site (x, y) covers pixels [xT, xT + T) × [yT, yT + T).
 *
 * @sa vtkMSDiscreteSynthesis
 */
#ifndef vtkMSTileImage_h
#define vtkMSTileImage_h

#include "ModelSynthFiltersModule.h" // for export macro
#include "vtkImageAlgorithm.h"

#include <string> // for ivars

class vtkInformationStringVectorKey;

class MODELSYNTHFILTERS_EXPORT vtkMSTileImage : public vtkImageAlgorithm
{
public:
  static vtkMSTileImage* New();
  vtkTypeMacro(vtkMSTileImage, vtkImageAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /// The tileset (.xml) whose images to use, and its subset ("" for all tiles). Default "":
  /// the input's tileset, as a tileset synthesis announces it (TILESET) or as its output's
  /// field data `TilesetFile` (and `TilesetSubset`) names it, e.g. a saved `labels.vti`.
  vtkSetStdStringFromCharMacro(TilesetFile);
  vtkGetCharFromStdStringMacro(TilesetFile);
  vtkSetStdStringFromCharMacro(TilesetSubset);
  vtkGetCharFromStdStringMacro(TilesetSubset);
  ///@}

  /// Pipeline information a tileset synthesis (vtkMSDiscreteSynthesis with a TilesetFile) puts
  /// on its output: the tileset file and subset, so the picture's size is known before the run.
  static vtkInformationStringVectorKey* TILESET();

protected:
  vtkMSTileImage() = default;
  ~vtkMSTileImage() override = default;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  int RequestInformation(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestUpdateExtent(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

private:
  vtkMSTileImage(const vtkMSTileImage&) = delete;
  void operator=(const vtkMSTileImage&) = delete;

  /// The tileset to use: TilesetFile and TilesetSubset, else the input's (@p inInfo's TILESET,
  /// else the field data of @p input). False when none is known.
  bool FindTileset(
    vtkInformation* inInfo, vtkDataObject* input, std::string& file, std::string& subset) const;

  std::string TilesetFile;
  std::string TilesetSubset;
};

#endif
