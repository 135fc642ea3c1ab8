// SPDX-License-Identifier: BSD-3-Clause
#include "Formats/TilePictures.h"

#include "Core/Error.h"
#include "Core/Index.h"

#include <algorithm>
#include <cstring>
#include <unordered_map>

namespace msynth
{

namespace
{
/// Orientation k+1 = orientation k turned 90° counter-clockwise (pixel (i, j) of the result is
/// pixel (j, T-1-i) of the source, rows bottom first); 4-7 mirror 0-3 left-right.
TilePicture Oriented(const TilePicture& p, int orientation)
{
  TilePicture out = p;
  const int t = p.Size;
  const auto at = [t](int i, int j) { return 4 * (ToIndex(j) * ToIndex(t) + ToIndex(i)); };
  for (int r = 0; r < orientation % 4; ++r)
  {
    TilePicture turned = out;
    for (int j = 0; j < t; ++j)
      for (int i = 0; i < t; ++i)
        std::copy(out.At(j, t - 1 - i), out.At(j, t - 1 - i) + 4,
          turned.RGBA.begin() + static_cast<std::ptrdiff_t>(at(i, j)));
    out = turned;
  }
  if (orientation >= 4)
  {
    TilePicture mirrored = out;
    for (int j = 0; j < t; ++j)
      for (int i = 0; i < t; ++i)
        std::copy(out.At(t - 1 - i, j), out.At(t - 1 - i, j) + 4,
          mirrored.RGBA.begin() + static_cast<std::ptrdiff_t>(at(i, j)));
    out = mirrored;
  }
  return out;
}

/// The size problem of @p image (tile images are square and all of one size), or "".
std::string SizeProblem(const RgbaImage& image, const Tileset& tiles, int size)
{
  if (image.Width != image.Height)
    return "tile images must be square (this one is " + std::to_string(image.Width) + " x " +
      std::to_string(image.Height) + ").";
  if (tiles.TileSize && image.Width != tiles.TileSize)
    return "is " + std::to_string(image.Width) + " pixels wide; the tileset's <set size> says " +
      std::to_string(tiles.TileSize) + ".";
  if (size && image.Width != size)
    return "is " + std::to_string(image.Width) + " pixels wide; the other tiles are " +
      std::to_string(size) + ".";
  return std::string();
}
} // namespace

std::vector<TilePicture> LoadTilePictures(const std::string& xmlPath, const Tileset& tiles)
{
  std::vector<TilePicture> pictures(ToIndex(tiles.NumberOfLabels()));
  int size = 0;
  for (int b = 0; b < tiles.NumberOfLabels(); ++b)
  {
    const auto& tile = tiles.Tiles[ToIndex(tiles.LabelTile[ToIndex(b)])];
    const int k = tiles.LabelOrientation[ToIndex(b)];
    const std::string path = TileImageFile(xmlPath, tiles, tile, k);
    RgbaImage image;
    try
    {
      image = ReadImage(path);
    }
    catch (const std::exception& e)
    {
      throw Error(std::string(e.what()) + " (tile '" + tile.Name + "')");
    }
    const std::string problem = SizeProblem(image, tiles, size);
    if (!problem.empty())
      throw Error::InFile(path, problem);
    size = image.Width;
    TilePicture p;
    p.Size = size;
    p.RGBA.resize(ToIndex(size) * ToIndex(size) * 4);
    const std::size_t row = 4 * ToIndex(size);
    for (int j = 0; j < size; ++j) // rows bottom first, as VTK stores them
      std::memcpy(p.RGBA.data() + row * ToIndex(j), image.At(0, size - 1 - j), row);
    pictures[ToIndex(b)] = tiles.Unique ? p : Oriented(p, k);
  }
  return pictures;
}

void ComposeTileRow(const std::int32_t* labels, int nx, const std::vector<TilePicture>& tiles,
  int j, std::uint8_t* out)
{
  if (tiles.empty())
    return;
  const int t = tiles.front().Size;
  const std::size_t row = 4 * ToIndex(t);
  if (t == 8)
  {
    // The common tile size, copied inline: a library call per tile row costs more than it.
    for (int x = 0; x < nx; ++x, out += 32)
      std::memcpy(out, tiles[ToIndex(labels[x])].At(0, j), 32);
    return;
  }
  for (int x = 0; x < nx; ++x, out += row)
    std::memcpy(out, tiles[ToIndex(labels[x])].At(0, j), row);
}

void WriteTilePicture(const std::string& path, const std::vector<std::int32_t>& labels, int nx,
  int ny, const std::vector<TilePicture>& tiles)
{
  const int t = tiles.empty() ? 0 : tiles.front().Size;
  if (static_cast<std::int64_t>(labels.size()) != static_cast<std::int64_t>(nx) * ny || t < 1)
    throw Error::InFile(path, "not written: the model and the tiles do not fit");
  for (std::size_t i = 0; i < labels.size(); ++i)
    if (labels[i] < 0 || ToIndex(labels[i]) >= tiles.size())
      throw Error::InFile(path,
        "not written: label " + std::to_string(labels[i]) + " at (" +
          std::to_string(i % ToIndex(nx)) + ", " + std::to_string(i / ToIndex(nx)) +
          ") is not a label of the tileset");
  const std::int64_t height = static_cast<std::int64_t>(ny) * t;
  const std::int64_t width = static_cast<std::int64_t>(nx) * t;
  if (width > (std::int64_t(1) << 30) / 4 || height > (std::int64_t(1) << 30))
    throw Error::InFile(path,
      "not written: a picture of " + std::to_string(width) + " x " + std::to_string(height) +
        " pixels is too large for PNG");
  WritePng(path, static_cast<int>(width), static_cast<int>(height),
    [&](int y)
    {
      // Each thread of the writer composes its rows in a buffer of its own (the pointer is
      // used before that thread asks for another row).
      thread_local std::vector<std::uint8_t> buffer;
      buffer.resize(ToIndex(width) * 4);
      const std::int64_t fromBottom = height - 1 - y;
      ComposeTileRow(labels.data() + ToIndex(fromBottom / t) * ToIndex(nx), nx, tiles,
        static_cast<int>(fromBottom % t), buffer.data());
      return static_cast<const std::uint8_t*>(buffer.data());
    });
}

LabelGrid PinsFromPicture(
  const RgbaImage& picture, const std::string& path, const std::vector<TilePicture>& tiles)
{
  if (tiles.empty())
    throw Error::InFile(path, "cannot be read as a map: the tileset has no tiles");
  const int t = tiles.front().Size;
  if (t < 1 || picture.Width % t != 0 || picture.Height % t != 0 || picture.Width == 0 ||
    picture.Height == 0)
    throw Error::InFile(path,
      "is " + std::to_string(picture.Width) + " x " + std::to_string(picture.Height) +
        " pixels, not a whole number of " + std::to_string(t) + " x " + std::to_string(t) +
        " tiles");
  const std::size_t row = 4 * ToIndex(t);
  // Labels by their picture's bytes (rows bottom first); the lowest label of equal pictures.
  std::unordered_map<std::string, Label> byPicture;
  for (std::size_t b = tiles.size(); b-- > 0;)
    byPicture[std::string(tiles[b].RGBA.begin(), tiles[b].RGBA.end())] = static_cast<Label>(b);
  const int nx = picture.Width / t, ny = picture.Height / t;
  LabelGrid pins(nx, ny, 1, Label(-1));
  std::string cell(row * ToIndex(t), '\0');
  for (int y = 0; y < ny; ++y)
    for (int x = 0; x < nx; ++x)
    {
      bool transparent = true;
      for (int j = 0; j < t; ++j) // cell row j from the bottom: picture row H - 1 - (yT + j)
      {
        const std::uint8_t* src = picture.At(x * t, picture.Height - 1 - (y * t + j));
        std::memcpy(&cell[row * ToIndex(j)], src, row);
        for (std::size_t i = 3; i < row && transparent; i += 4)
          transparent = src[i] == 0;
      }
      if (transparent)
        continue;
      const auto found = byPicture.find(cell);
      if (found == byPicture.end())
        throw Error::InFile(path,
          "the cell of site (" + std::to_string(x) + ", " + std::to_string(y) + ") (pixels " +
            std::to_string(x * t) + ".." + std::to_string(x * t + t - 1) + " across, " +
            std::to_string(picture.Height - (y + 1) * t) + ".." +
            std::to_string(picture.Height - y * t - 1) +
            " down) is neither a tile of the set nor transparent");
      pins.Set(x, y, 0, found->second);
    }
  return pins;
}

} // namespace msynth
