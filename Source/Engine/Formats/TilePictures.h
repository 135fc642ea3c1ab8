// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/**
 * @file TilePictures.h
 * @brief A 2D tileset's label pictures, and the inverse: a drawn map read back into labels.
 *
 * Label b of a tileset is orientation k of a tile (Tileset.h); its picture is the tile's image
 * turned k quarter turns counter-clockwise (and mirrored left-right for k ≥ 4), or its own image
 * in a `unique` set. vtkMSTileImage composes model pictures from them; PinsFromPicture reads a
 * picture drawn with the same tiles (a partial map, `--fixed map.png`) back into pinned sites.
 */
#include "Core/Index.h"
#include "Core/LabelGrid.h"
#include "Formats/Image.h"
#include "Formats/Tileset.h"

#include <cstdint>
#include <string>
#include <vector>

namespace msynth
{

/// A tile picture as RGBA rows, bottom row first (VTK's order).
struct TilePicture
{
  int Size = 0;
  std::vector<unsigned char> RGBA; ///< Size × Size × 4
  const unsigned char* At(int i, int j) const
  {
    return this->RGBA.data() + 4 * (ToIndex(j) * ToIndex(this->Size) + ToIndex(i));
  }
};

/**
 * One picture per label of @p tiles (read from the images beside @p xmlPath, TileImageFile).
 * All images are square and of one size (the set's `size` when given).
 * @throw Error naming the image that is missing, unreadable, not square or of another size.
 */
std::vector<TilePicture> LoadTilePictures(const std::string& xmlPath, const Tileset& tiles);

/**
 * Pixel row @p j (from the bottom of the tiles, 0 ≤ j < T) of a row of sites holding
 * @p labels[0..nx) (each a valid label of @p tiles): nx·T RGBA pixels into @p out. A model's
 * picture, row by row, without holding it (vtkMSTileImage, and picture.png written as it is
 * composed).
 */
void ComposeTileRow(const std::int32_t* labels, int nx, const std::vector<TilePicture>& tiles,
  int j, std::uint8_t* out);

/**
 * Writes the picture of a model of nx × ny sites (@p labels, x fastest, rows from the bottom as
 * VTK stores them) to the PNG @p path, each row composed as the PNG writer asks for it: no
 * picture in memory (a 2000² model of 8-pixel tiles is 1 GB of RGBA).
 * @throw Error naming the first site whose label is not one of @p tiles, or the file.
 */
void WriteTilePicture(const std::string& path, const std::vector<std::int32_t>& labels, int nx,
  int ny, const std::vector<TilePicture>& tiles);

/**
 * Reads a map drawn with a tileset's tiles into pinned sites: @p picture (rows from the top,
 * as read from @p path) is cut into T × T cells, T being the tiles' size; a cell whose pixels
 * are all transparent (alpha 0) is free (-1), any other must equal one label's picture exactly
 * and pins that label. Site (x, y) is the cell whose bottom-left pixel is (xT, H - (y + 1)T)
 * from the top, as vtkMSTileImage lays tiles out. Cells whose picture several labels share pin
 * the lowest of them.
 * @throw Error naming @p path: a size that is not a whole number of tiles, or a cell (with its
 * site and pixel position) that matches no tile.
 */
LabelGrid PinsFromPicture(
  const RgbaImage& picture, const std::string& path, const std::vector<TilePicture>& tiles);

} // namespace msynth
