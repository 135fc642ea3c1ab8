// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class vtkMSLabelArrays
 * @brief Label arrays of image data as the engine's label grids, and back.
 *
 * Static functions shared by ModelSynth's VTK classes (not wrapped for Python: their signatures
 * use engine types).
 */
#ifndef vtkMSLabelArrays_h
#define vtkMSLabelArrays_h

#include "Core/BlockSynthesis.h" // for msynth::CatalogSnapshot
#include "Core/LabelGrid.h"      // for msynth::LabelGrid
#include "ModelSynthIOModule.h"  // for export macro

#include <array>
#include <cstdint>
#include <string>
#include <vector>

class vtkDataArray;
class vtkFieldData;
class vtkImageData;
class vtkInformation;
class vtkIntArray;
class vtkPolyData;
class vtkUnsignedCharArray;
namespace msynth
{
struct RgbaImage;
struct Tileset;
struct VoxelSurface;
}

class MODELSYNTHIO_EXPORT vtkMSLabelArrays
{
public:
  /// The one value of a `Label` array at a site a catalog snapshot has not decided yet, in
  /// every filter (VTK_INT_MIN, msynth::CatalogSnapshot::Undecided: no label has it).
  static constexpr int Undecided = msynth::CatalogSnapshot::Undecided;

  /// True when @p array holds integers (any width or signedness).
  static bool IsIntegerArray(vtkDataArray* array);

  /**
   * Checks that @p array can serve as labels of @p image's points: integer type, one
   * component, one value per point, values within the 32-bit range. On failure returns false
   * and sets @p problem to a sentence naming the array and what is wrong.
   */
  static bool CheckLabelArray(vtkImageData* image, vtkDataArray* array, std::string& problem);

  /**
   * The label array of @p image: @p selected (the filter's input array to process) when set,
   * else the point array "Label", else the active point scalars; nullptr when there is none.
   */
  static vtkDataArray* FindLabelArray(vtkImageData* image, vtkDataArray* selected);

  /// Copies a checked label array into an engine grid (x fastest, as VTK stores points).
  static msynth::LabelGrid ToLabelGrid(vtkImageData* image, vtkDataArray* labels);

  /**
   * The labels of the label grid file @p path (.vti, .txt, .vox; -1 where free) as
   * vtkMSLabelGridReader reads it without geometry, and the first corner of its extent (where a
   * smaller grid, such as pins, lies in the world). @throw msynth::Error with the reader's
   * reason, naming the file.
   */
  static msynth::LabelGrid ReadLabelGridFile(const std::string& path, std::array<int, 3>& first);

  /**
   * FindLabelArray, CheckLabelArray and ToLabelGrid in one: @p image's labels (@p selected when
   * set) as a grid. False, with @p problem set to a sentence, when there is no usable array.
   */
  static bool ReadLabels(
    vtkImageData* image, vtkDataArray* selected, msynth::LabelGrid& grid, std::string& problem);

  /// A new vtkIntArray named @p name holding @p grid's labels.
  static vtkIntArray* NewLabelArray(const msynth::LabelGrid& grid, const char* name);

  /**
   * The voxel surface of @p image's labels into @p output (quads with the cell scalars
   * `Label`): sites holding @p empty, or VTK_INT_MIN (a site a catalog snapshot has not yet
   * decided), give none. Piece @p piece of @p pieces holds the faces of its slab of sites along
   * the longest axis; the pieces put together give the whole surface, with no faces at the
   * seams. An empty image gives an empty output. False, with @p problem, when the image has no
   * usable label array. @p merge (one piece only): coplanar faces of a label merged into
   * rectangles (msynth::ExtractMergedVoxelSurface) with single-precision points, for files of
   * large voxel models.
   */
  static bool VoxelSurface(vtkImageData* image, int empty, int piece, int pieces,
    vtkPolyData* output, std::string& problem, bool merge = false);

  /**
   * The Geometry output port (@p geometryInfo) of a filter whose port 0 is the label image
   * @p image: its VoxelSurface for the piece that port asks for, or nothing when @p generate is
   * off. False, with @p problem, when the image has no usable label array.
   */
  static bool FillGeometryPort(vtkImageData* image, bool generate, int empty,
    vtkInformation* geometryInfo, std::string& problem);

  /**
   * The voxels of a model of a voxel tileset (Formats/VoxelTileset.h) as an image: each site of
   * @p model (its `Label` array) becomes its tile image's S x S x SZ voxels filling the site's
   * cell, point array `Label` the palette index (0 empty; undecided sites empty) and field data
   * `PaletteRGBA` the colours, so VoxelSurface gives the coloured voxels (`PaletteColor`).
   */
  static bool TileVoxels(
    const msynth::Tileset& set, vtkImageData* model, vtkImageData* voxels, std::string& problem);

  /**
   * Where TileVoxels puts the voxels of @p model's tiles: the first voxel's centre @p origin and
   * the voxel @p spacing (a site's cell [p - h/2, p + h/2] holds its tile's voxels).
   */
  static void TileVoxelPlacement(const msynth::Tileset& set, vtkImageData* model,
    std::array<double, 3>& origin, std::array<double, 3>& spacing);

  /**
   * The merged voxel surface of @p voxels (palette indices, 0 empty, as msynth::ComposeVoxels
   * makes them) placed by @p origin and @p spacing, into @p output: quads with cell arrays
   * `Label` and `PaletteColor` (@p palette), single-precision points and 32-bit ids, filled
   * directly, without a second copy of the voxels. For the mesh outputs of large voxel models.
   */
  static void MergedVoxelMesh(const msynth::LabelGrid& voxels,
    const std::vector<std::array<std::uint8_t, 4>>& palette, const std::array<double, 3>& origin,
    const std::array<double, 3>& spacing, vtkPolyData* output);

  /**
   * With a palette (field data `PaletteRGBA` of @p fields, as a `.vox` example and the models
   * made from it carry), adds to @p mesh the cell array `PaletteColor`: the RGBA of each cell's
   * `Label`, so the model can be shown in the example's colours (colour by it with Map Scalars
   * off). Labels beyond the palette get transparent black. Nothing without a palette.
   */
  static void AddPaletteColors(vtkFieldData* fields, vtkPolyData* mesh);

  /// The world position of @p image's first site (its origin moved to the extent's start).
  static std::array<double, 3> FirstSitePosition(vtkImageData* image);

  /// The colours of a picture (unsigned char scalars of 1 to 4 components: grey, grey and alpha,
  /// RGB, RGBA, as vtkPNGReader gives them, and no `Label` array), else nullptr.
  static vtkUnsignedCharArray* PictureBytes(vtkImageData* image);
  /**
   * The picture @p image (of the colours @p bytes) as RGBA rows from the top (VTK holds them
   * from the bottom). @throw msynth::Error "@p what must be flat" for an image deeper than 1.
   */
  static msynth::RgbaImage PictureRows(
    vtkImageData* image, vtkUnsignedCharArray* bytes, const std::string& what);
  /// @p picture into @p output: its extent and an `RGBA` array as scalars, rows from the bottom.
  static void SetPicture(vtkImageData* output, const msynth::RgbaImage& picture);
};

#endif
