// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/**
 * @file Image.h
 * @brief RGBA pictures: tile images and image samples read, pictures written.
 *
 * PNG goes through libpng's own checks (chunk CRCs, the compressed stream), so a truncated or
 * corrupted file is an error naming the file, never a crash; BMP (the older published tilesets)
 * is read here with every size checked against the file. Sizes are checked before allocating.
 */
#include "Core/Index.h"
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

namespace msynth
{

struct RgbaImage
{
  int Width = 0;
  int Height = 0;
  std::vector<std::uint8_t> Pixels; ///< Width × Height × 4 bytes, rows from the top

  const std::uint8_t* At(int x, int y) const
  {
    return this->Pixels.data() + 4 * (ToIndex(y) * this->Width + x);
  }
};

/// The largest picture read: 2^26 pixels (256 MB of RGBA), and 65536 pixels per side.
constexpr std::int64_t MaximumImagePixels = std::int64_t(1) << 26;

/// Reads a PNG file. @throw Error naming @p path for anything unreadable.
RgbaImage ReadPng(const std::string& path);
/// Reads an uncompressed BMP (8-bit paletted, 24- or 32-bit). @throw Error naming @p path.
RgbaImage ReadBmp(const std::string& path);
/// ReadPng or ReadBmp by the file's extension (PNG for any other).
RgbaImage ReadImage(const std::string& path);
/// Whether @p path names a picture ReadImage reads by its extension: .png or .bmp, any case.
bool IsImageFile(const std::string& path);
/// Whether @p path is a PNG that msynth wrote (WritePng: its text chunk Software = msynth), read
/// chunk by chunk up to the pixels; false for any other file or one that cannot be read.
bool IsWrittenPng(const std::string& path);

/**
 * Writes @p image as an 8-bit RGBA (RGB when every pixel is opaque) PNG, atomically;
 * @p compression 0-9 as zlib's levels (1: fast, the default for large pictures). Rows are
 * filtered (None, Sub or Up per row) and deflated in strips of about 1 MB on all cores; the
 * strips' streams join into one zlib stream, and the file is the same whatever the number of
 * threads. A text chunk says msynth wrote it (Software = msynth; IsWrittenPng).
 * @throw Error naming @p path on failure.
 */
void WritePng(const std::string& path, const RgbaImage& image, int compression = 1);
/// The same for a picture of @p width × @p height pixels whose row y (from the top) is the
/// @p width × 4 RGBA bytes at @p row(y): no copy of a picture held elsewhere (VTK's rows).
void WritePng(const std::string& path, int width, int height,
  const std::function<const std::uint8_t*(int)>& row, int compression = 1);

} // namespace msynth
