// SPDX-License-Identifier: BSD-3-Clause
#include "Formats/Image.h"

#include "Core/AtomicFile.h"
#include "Core/Error.h"
#include "Core/Memory.h"

#include <png.h>

#include <cctype>
#include <csetjmp>
#include <cstring>
#include <fstream>

namespace msynth
{
namespace
{
void CheckSize(const std::string& path, std::int64_t width, std::int64_t height)
{
  if (width < 1 || height < 1 || width > 65536 || height > 65536 ||
    width * height > MaximumImagePixels)
    throw Error::InFile(path,
      "is " + std::to_string(width) + " x " + std::to_string(height) +
        " pixels; pictures of 1 to 65536 pixels a side and at most " +
        std::to_string(MaximumImagePixels) + " pixels are read");
  CheckMemory(static_cast<std::uint64_t>(width * height) * 4, "reading '" + path + "'");
}

std::uint32_t Little(const std::vector<std::uint8_t>& b, std::size_t at, int bytes)
{
  std::uint32_t v = 0;
  for (int i = bytes - 1; i >= 0; --i)
    v = (v << 8) | b[at + static_cast<std::size_t>(i)];
  return v;
}

bool EndsWith(const std::string& s, const char* suffix)
{
  const std::size_t n = std::strlen(suffix);
  if (s.size() < n)
    return false;
  for (std::size_t i = 0; i < n; ++i)
    if (std::tolower(static_cast<unsigned char>(s[s.size() - n + i])) != suffix[i])
      return false;
  return true;
}
} // namespace

RgbaImage ReadPng(const std::string& path)
{
  png_image png;
  std::memset(&png, 0, sizeof png);
  png.version = PNG_IMAGE_VERSION;
  if (!png_image_begin_read_from_file(&png, path.c_str()))
  {
    const std::string why = png.message;
    png_image_free(&png);
    std::ifstream probe(path);
    throw Error::InFile(path,
      probe ? "is not a readable PNG image (" + why + ")" : std::string("no such image file"));
  }
  try
  {
    CheckSize(path, png.width, png.height);
  }
  catch (...)
  {
    png_image_free(&png);
    throw;
  }
  RgbaImage image;
  image.Width = static_cast<int>(png.width);
  image.Height = static_cast<int>(png.height);
  png.format = PNG_FORMAT_RGBA;
  image.Pixels.resize(PNG_IMAGE_SIZE(png));
  if (!png_image_finish_read(&png, nullptr, image.Pixels.data(), 0, nullptr))
  {
    const std::string why = png.message;
    png_image_free(&png);
    throw Error::InFile(path, "is truncated or corrupt (" + why + ")");
  }
  return image;
}

RgbaImage ReadBmp(const std::string& path)
{
  std::ifstream in(path, std::ios::binary);
  if (!in)
    throw Error::InFile(path, "no such image file");
  in.seekg(0, std::ios::end);
  const std::streamoff size = in.tellg();
  if (size < 54 || size > (std::streamoff(1) << 30))
    throw Error::InFile(path, "is not a readable BMP image (" + std::to_string(size) + " bytes)");
  in.seekg(0);
  std::vector<std::uint8_t> b(static_cast<std::size_t>(size));
  in.read(reinterpret_cast<char*>(b.data()), size);
  if (!in || b[0] != 'B' || b[1] != 'M')
    throw Error::InFile(path, "is not a readable BMP image (no 'BM' signature)");
  const std::uint32_t offset = Little(b, 10, 4), header = Little(b, 14, 4);
  if (header < 40 || 14 + static_cast<std::uint64_t>(header) > b.size())
    throw Error::InFile(path,
      "is not a BMP image this reader knows (header of " + std::to_string(header) + " bytes)");
  const auto width = static_cast<std::int32_t>(Little(b, 18, 4));
  const auto rawHeight = static_cast<std::int32_t>(Little(b, 22, 4));
  const std::uint32_t planes = Little(b, 26, 2), bits = Little(b, 28, 2),
                      compression = Little(b, 30, 4);
  const bool topDown = rawHeight < 0;
  const std::int64_t height = topDown ? -std::int64_t(rawHeight) : rawHeight;
  if (planes != 1 || (bits != 8 && bits != 24 && bits != 32) ||
    (compression != 0 && compression != 3))
    throw Error::InFile(path,
      "is a BMP image of " + std::to_string(bits) + " bits per pixel, compression " +
        std::to_string(compression) + "; uncompressed 8-, 24- and 32-bit images are read");
  CheckSize(path, width, height);
  const std::uint64_t stride = ((static_cast<std::uint64_t>(width) * bits + 31) / 32) * 4;
  if (offset > b.size() || stride * static_cast<std::uint64_t>(height) > b.size() - offset)
    throw Error::InFile(path,
      "is truncated (its pixels need " +
        std::to_string(stride * static_cast<std::uint64_t>(height)) + " bytes after byte " +
        std::to_string(offset) + ")");
  std::uint32_t colours = bits == 8 ? Little(b, 46, 4) : 0;
  if (bits == 8 && colours == 0)
    colours = 256;
  if (bits == 8 &&
    (colours > 256 || 14 + static_cast<std::uint64_t>(header) + 4 * colours > offset))
    throw Error::InFile(path, "has a colour table that does not fit before its pixels");
  RgbaImage image;
  image.Width = width;
  image.Height = static_cast<int>(height);
  image.Pixels.resize(static_cast<std::size_t>(width) * static_cast<std::size_t>(height) * 4);
  for (std::int64_t row = 0; row < height; ++row)
  {
    const std::uint8_t* src = b.data() + offset + stride * static_cast<std::uint64_t>(row);
    const std::int64_t y =
      topDown ? row : height - 1 - row; // bottom-up unless the height is negative
    std::uint8_t* dst = image.Pixels.data() + static_cast<std::size_t>(y * width * 4);
    for (std::int32_t x = 0; x < width; ++x)
    {
      const std::uint8_t* p = src;
      std::uint8_t alpha = 255;
      if (bits == 8)
      {
        if (src[x] >= colours)
          throw Error::InFile(path,
            "uses colour " + std::to_string(src[x]) + ", beyond its table of " +
              std::to_string(colours));
        p = b.data() + 14 + header + 4 * static_cast<std::size_t>(src[x]);
      }
      else
      {
        p = src + static_cast<std::size_t>(x) * (bits / 8); // blue, green, red (, unused)
      }
      dst[4 * x + 0] = p[2];
      dst[4 * x + 1] = p[1];
      dst[4 * x + 2] = p[0];
      dst[4 * x + 3] = alpha;
    }
  }
  return image;
}

RgbaImage ReadImage(const std::string& path)
{
  return EndsWith(path, ".bmp") ? ReadBmp(path) : ReadPng(path);
}

namespace
{
void WriteToStream(png_structp p, png_bytep data, png_size_t length)
{
  static_cast<std::ostream*>(png_get_io_ptr(p))
    ->write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(length));
}
void FlushStream(png_structp p)
{
  static_cast<std::ostream*>(png_get_io_ptr(p))->flush();
}

/// The libpng calls in a frame of their own, holding no C++ object, for its longjmp on error.
bool Encode(png_structp png, png_infop info, const RgbaImage& image, bool opaque, std::uint8_t* row,
  std::ostream* out, int compression)
{
  if (setjmp(png_jmpbuf(png)))
    return false;
  png_set_write_fn(png, out, WriteToStream, FlushStream);
  png_set_compression_level(png, compression);
  png_set_IHDR(png, info, static_cast<png_uint_32>(image.Width),
    static_cast<png_uint_32>(image.Height), 8, opaque ? PNG_COLOR_TYPE_RGB : PNG_COLOR_TYPE_RGBA,
    PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
  png_write_info(png, info);
  for (int y = 0; y < image.Height; ++y)
  {
    const std::uint8_t* src = image.At(0, y);
    if (opaque)
      for (int x = 0; x < image.Width; ++x)
        std::memcpy(row + 3 * x, src + 4 * x, 3);
    else
      std::memcpy(row, src, 4 * static_cast<std::size_t>(image.Width));
    png_write_row(png, row);
  }
  png_write_end(png, nullptr);
  return true;
}
} // namespace

void WritePng(const std::string& path, const RgbaImage& image, int compression)
{
  bool opaque = true;
  for (std::size_t i = 3; i < image.Pixels.size() && opaque; i += 4)
    opaque = image.Pixels[i] == 255;
  WriteFileAtomically(path,
    [&](std::ostream& out)
    {
      png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, nullptr);
      png_infop info = png ? png_create_info_struct(png) : nullptr;
      std::vector<std::uint8_t> row(static_cast<std::size_t>(image.Width) * 4);
      const bool ok = info && Encode(png, info, image, opaque, row.data(), &out, compression);
      png_destroy_write_struct(&png, info ? &info : nullptr);
      if (!ok)
        throw Error::InFile(path, "could not be written (PNG encoder error)");
    });
}

} // namespace msynth
