// SPDX-License-Identifier: BSD-3-Clause
#include "Formats/Image.h"

#include "Core/AtomicFile.h"
#include "Core/Error.h"
#include "Core/Index.h"
#include "Core/Memory.h"
#include "Core/ParallelChunks.h"

#include <png.h>
#include <zlib.h>

#include <algorithm>
#include <functional>
#include <memory>

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
    v = (v << 8) | b[at + ToIndex(i)];
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
  std::vector<std::uint8_t> b(ToIndex(size));
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
  image.Pixels.resize(ToIndex(width) * ToIndex(height) * 4);
  for (std::int64_t row = 0; row < height; ++row)
  {
    const std::uint8_t* src = b.data() + offset + stride * static_cast<std::uint64_t>(row);
    const std::int64_t y =
      topDown ? row : height - 1 - row; // bottom-up unless the height is negative
    std::uint8_t* dst = image.Pixels.data() + ToIndex(y * width * 4);
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
        p = b.data() + 14 + header + 4 * ToIndex(src[x]);
      }
      else
      {
        p = src + ToIndex(x) * (bits / 8); // blue, green, red (, unused)
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

bool IsImageFile(const std::string& path)
{
  return EndsWith(path, ".png") || EndsWith(path, ".bmp");
}

namespace
{
/// The text chunk WritePng puts after the header: keyword, NUL, text.
constexpr char WrittenBy[] = "Software\0msynth";
} // namespace

bool IsWrittenPng(const std::string& path)
{
  std::ifstream in(path, std::ios::binary);
  char signature[8];
  if (!in.read(signature, 8) || std::memcmp(signature, "\x89PNG\r\n\x1a\n", 8) != 0)
    return false;
  // The chunks before the pixels: IHDR, PLTE, tRNS, text (a few, each checked for its length).
  for (int chunk = 0; chunk < 16; ++chunk)
  {
    unsigned char head[8];
    if (!in.read(reinterpret_cast<char*>(head), 8))
      return false;
    const std::uint32_t length = (std::uint32_t(head[0]) << 24) | (std::uint32_t(head[1]) << 16) |
      (std::uint32_t(head[2]) << 8) | head[3];
    const std::string type(reinterpret_cast<const char*>(head) + 4, 4);
    if (type == "IDAT" || type == "IEND" || length > (1u << 20))
      return false;
    std::string data(length, '\0');
    if (!in.read(&data[0], static_cast<std::streamsize>(length)) || !in.ignore(4))
      return false;
    if (type == "tEXt" && data == std::string(WrittenBy, sizeof(WrittenBy) - 1))
      return true;
  }
  return false;
}

namespace
{
/// The PNG filter of one row (None, Sub or Up, whichever leaves the smallest sum of absolute
/// differences, as libpng's heuristic) written to @p out (1 + bytes): filter type, then bytes.
void FilterRow(
  const std::uint8_t* row, const std::uint8_t* above, std::size_t bytes, int bpp, std::uint8_t* out)
{
  std::uint64_t cost[3] = { 0, 0, 0 };
  for (std::size_t i = 0; i < bytes; ++i)
  {
    const auto none = static_cast<std::int8_t>(row[i]);
    const auto sub = static_cast<std::int8_t>(row[i] - (i >= ToIndex(bpp) ? row[i - bpp] : 0));
    const auto up = static_cast<std::int8_t>(row[i] - (above ? above[i] : 0));
    cost[0] += static_cast<std::uint64_t>(none < 0 ? -none : none);
    cost[1] += static_cast<std::uint64_t>(sub < 0 ? -sub : sub);
    cost[2] += static_cast<std::uint64_t>(up < 0 ? -up : up);
  }
  const int type = cost[2] <= cost[1] && cost[2] <= cost[0] ? 2 : (cost[1] <= cost[0] ? 1 : 0);
  out[0] = static_cast<std::uint8_t>(type);
  for (std::size_t i = 0; i < bytes; ++i)
  {
    const std::uint8_t left = i >= ToIndex(bpp) ? row[i - bpp] : 0;
    const std::uint8_t prior = type == 1 ? left : (type == 2 && above ? above[i] : 0);
    out[1 + i] = static_cast<std::uint8_t>(row[i] - prior);
  }
}

/// One strip of rows, filtered and deflated on its own (a raw deflate stream ending in a sync
/// flush, or the final block for the last strip), with the Adler-32 of its filtered bytes.
struct Strip
{
  std::vector<std::uint8_t> Deflated;
  uLong Adler = 1;
  uLong Length = 0;
  bool Failed = false;
};

/**
 * The colours of a picture with at most 256 of them, for an indexed PNG (colour type 3): a
 * quarter of the bytes to filter and deflate. Colours are numbered in order of first
 * appearance (rows from the top), so the file depends on the picture alone.
 */
class Palette
{
public:
  /// Adds @p rgba; false once the picture has more than 256 colours.
  bool Add(std::uint32_t rgba)
  {
    std::size_t at = Slot(rgba);
    while (this->Used[at])
    {
      if (this->Keys[at] == rgba)
        return true;
      at = (at + 1) & (Size - 1);
    }
    if (this->Colours.size() == 256)
      return false;
    this->Used[at] = 1;
    this->Keys[at] = rgba;
    this->Index[at] = static_cast<std::uint8_t>(this->Colours.size());
    this->Colours.push_back(rgba);
    return true;
  }
  /// The index of a colour that was added.
  std::uint8_t IndexOf(std::uint32_t rgba) const
  {
    std::size_t at = Slot(rgba);
    while (this->Keys[at] != rgba)
      at = (at + 1) & (Size - 1);
    return this->Index[at];
  }
  const std::vector<std::uint32_t>& Entries() const { return this->Colours; }

private:
  static constexpr std::size_t Size = 1024; // 4 slots per colour at most: short probes
  static std::size_t Slot(std::uint32_t c) { return (c * 2654435761u) >> 22; }
  std::vector<std::uint32_t> Colours;
  std::uint32_t Keys[Size] = {};
  std::uint8_t Index[Size] = {};
  std::uint8_t Used[Size] = {};
};

std::uint32_t PixelAt(const std::uint8_t* p)
{
  std::uint32_t v;
  std::memcpy(&v, p, 4);
  return v;
}

/// How rows are stored: RGB (opaque), RGBA, or palette indices.
struct PngLayout
{
  bool Opaque = true;
  const Palette* Indexed = nullptr; ///< set: colour type 3
  int BytesPerPixel() const { return this->Indexed ? 1 : (this->Opaque ? 3 : 4); }
};

/// One pass over the pixels: opaque or not, and @p palette while there are few colours.
PngLayout ScanPixels(
  int width, int height, const std::function<const std::uint8_t*(int)>& row, Palette& palette)
{
  PngLayout layout;
  bool few = true;
  for (int y = 0; y < height && (few || layout.Opaque); ++y)
  {
    const std::uint8_t* r = row(y);
    std::uint32_t last = PixelAt(r) + 1;
    for (int x = 0; x < width && (few || layout.Opaque); ++x)
    {
      const std::uint32_t c = PixelAt(r + 4 * x);
      if (c == last)
        continue;
      last = c;
      layout.Opaque = layout.Opaque && r[4 * x + 3] == 255;
      few = few && palette.Add(c);
    }
  }
  if (few)
    layout.Indexed = &palette;
  return layout;
}

void DeflateStrip(int first, int last, bool final, int width, const PngLayout& layout, int level,
  const std::function<const std::uint8_t*(int)>& row, Strip& strip)
{
  const int bpp = layout.BytesPerPixel();
  const bool opaque = layout.Opaque;
  const std::size_t bytes = ToIndex(width) * ToIndex(bpp);
  std::vector<std::uint8_t> packed(bytes), above(bytes), filtered(1 + bytes);
  z_stream z{};
  if (deflateInit2(&z, level, Z_DEFLATED, -15, 8, Z_DEFAULT_STRATEGY) != Z_OK)
  {
    strip.Failed = true;
    return;
  }
  auto pack = [&](int y, std::vector<std::uint8_t>& to)
  {
    const std::uint8_t* src = row(y);
    if (layout.Indexed)
    {
      std::uint32_t previous = PixelAt(src) + 1; // not the first pixel: looked up
      std::uint8_t index = 0;
      for (int x = 0; x < width; ++x)
      {
        const std::uint32_t c = PixelAt(src + 4 * x);
        if (c != previous)
          index = layout.Indexed->IndexOf(previous = c);
        to[ToIndex(x)] = index;
      }
    }
    else if (!opaque)
      std::memcpy(to.data(), src, bytes);
    else
      for (int x = 0; x < width; ++x)
        std::memcpy(to.data() + 3 * x, src + 4 * x, 3);
  };
  if (first > 0)
    pack(first - 1, above);
  std::vector<std::uint8_t> buffer(1 << 16);
  for (int y = first; y < last && !strip.Failed; ++y)
  {
    pack(y, packed);
    FilterRow(packed.data(), y > 0 ? above.data() : nullptr, bytes, bpp, filtered.data());
    strip.Adler = adler32(strip.Adler, filtered.data(), static_cast<uInt>(filtered.size()));
    strip.Length += static_cast<uLong>(filtered.size());
    z.next_in = filtered.data();
    z.avail_in = static_cast<uInt>(filtered.size());
    const int flush = y + 1 < last ? Z_NO_FLUSH : (final ? Z_FINISH : Z_SYNC_FLUSH);
    do
    {
      z.next_out = buffer.data();
      z.avail_out = static_cast<uInt>(buffer.size());
      const int rc = deflate(&z, flush);
      if (rc == Z_STREAM_ERROR)
        strip.Failed = true;
      strip.Deflated.insert(
        strip.Deflated.end(), buffer.data(), buffer.data() + (buffer.size() - z.avail_out));
    } while (z.avail_out == 0 && !strip.Failed);
    std::swap(packed, above);
  }
  deflateEnd(&z);
}

void PutBigEndian(std::ostream& out, std::uint32_t v)
{
  const char b[4] = { static_cast<char>(v >> 24), static_cast<char>(v >> 16),
    static_cast<char>(v >> 8), static_cast<char>(v) };
  out.write(b, 4);
}

void PutChunk(std::ostream& out, const char* type, const std::uint8_t* data, std::size_t length,
  const std::uint8_t* tail = nullptr, std::size_t tailLength = 0)
{
  PutBigEndian(out, static_cast<std::uint32_t>(length + tailLength));
  out.write(type, 4);
  uLong crc = crc32(0, reinterpret_cast<const Bytef*>(type), 4);
  if (length)
  {
    out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(length));
    crc = crc32(crc, data, static_cast<uInt>(length));
  }
  if (tailLength)
  {
    out.write(reinterpret_cast<const char*>(tail), static_cast<std::streamsize>(tailLength));
    crc = crc32(crc, tail, static_cast<uInt>(tailLength));
  }
  PutBigEndian(out, static_cast<std::uint32_t>(crc));
}
} // namespace

void WritePng(const std::string& path, int width, int height,
  const std::function<const std::uint8_t*(int)>& row, int compression)
{
  if (width < 1 || height < 1)
    throw Error::InFile(path,
      "could not be written: a picture of " + std::to_string(width) + " x " +
        std::to_string(height) + " pixels is empty");
  auto palette = std::make_unique<Palette>();
  const PngLayout layout = ScanPixels(width, height, row, *palette);
  // Strips of a fixed height, so the file is the same whatever the number of threads.
  const int rowsPerStrip = std::max(1, (1 << 20) / (4 * width));
  std::vector<Strip> strips(ToIndex((height + rowsPerStrip - 1) / rowsPerStrip));
  // On all cores; an exception in a strip (the rows' callback, memory) reaches the caller.
  RunChunks(strips.size(), 0,
    [&](std::size_t s)
    {
      const int first = static_cast<int>(s) * rowsPerStrip;
      DeflateStrip(first, std::min(height, first + rowsPerStrip), s + 1 == strips.size(), width,
        layout, compression, row, strips[s]);
    });
  uLong adler = 1;
  for (const Strip& s : strips)
  {
    if (s.Failed)
      throw Error::InFile(path, "could not be written (deflate failed)");
    adler = adler32_combine(adler, s.Adler, static_cast<z_off_t>(s.Length));
  }
  WriteFileAtomically(path,
    [&](std::ostream& out)
    {
      static const char signature[8] = { '\x89', 'P', 'N', 'G', '\r', '\n', '\x1a', '\n' };
      out.write(signature, 8);
      std::uint8_t header[13] = { 0 };
      for (int i = 0; i < 4; ++i)
      {
        header[i] = static_cast<std::uint8_t>(static_cast<std::uint32_t>(width) >> (24 - 8 * i));
        header[4 + i] =
          static_cast<std::uint8_t>(static_cast<std::uint32_t>(height) >> (24 - 8 * i));
      }
      header[8] = 8; // bits per channel (or index)
      header[9] = static_cast<std::uint8_t>(layout.Indexed ? 3 : (layout.Opaque ? 2 : 6));
      PutChunk(out, "IHDR", header, 13);
      PutChunk(
        out, "tEXt", reinterpret_cast<const std::uint8_t*>(WrittenBy), sizeof(WrittenBy) - 1);
      if (layout.Indexed)
      {
        // PLTE: the colours' RGB; tRNS: their alpha up to the last not opaque one.
        std::vector<std::uint8_t> rgb, alpha;
        for (const std::uint32_t c : layout.Indexed->Entries())
        {
          std::uint8_t p[4];
          std::memcpy(p, &c, 4);
          rgb.insert(rgb.end(), p, p + 3);
          alpha.push_back(p[3]);
        }
        while (!alpha.empty() && alpha.back() == 255)
          alpha.pop_back();
        PutChunk(out, "PLTE", rgb.data(), rgb.size());
        if (!alpha.empty())
          PutChunk(out, "tRNS", alpha.data(), alpha.size());
      }
      // The zlib stream: header (32K window, fast), the strips' deflate data, Adler-32.
      const std::uint8_t zlibHeader[2] = { 0x78, 0x01 };
      const std::uint8_t check[4] = { static_cast<std::uint8_t>(adler >> 24),
        static_cast<std::uint8_t>(adler >> 16), static_cast<std::uint8_t>(adler >> 8),
        static_cast<std::uint8_t>(adler) };
      PutChunk(out, "IDAT", zlibHeader, 2);
      for (std::size_t s = 0; s < strips.size(); ++s)
        PutChunk(out, "IDAT", strips[s].Deflated.data(), strips[s].Deflated.size(),
          s + 1 == strips.size() ? check : nullptr, s + 1 == strips.size() ? 4 : 0);
      PutChunk(out, "IEND", nullptr, 0);
    });
}

void WritePng(const std::string& path, const RgbaImage& image, int compression)
{
  WritePng(
    path, image.Width, image.Height, [&image](int y) { return image.At(0, y); }, compression);
}

} // namespace msynth
