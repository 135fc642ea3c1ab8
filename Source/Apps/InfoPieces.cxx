// SPDX-License-Identifier: BSD-3-Clause
// `msynth info FILE.pvti`: a streamed model's pieces (VTK's parallel image data: the whole
// extent, each piece's extent and file, the arrays), read by the engine's small XML reader
// (Formats/Xml.h: bounded nesting, errors naming the file and line); the pieces are not read.
#include "Common.h"
#include "InfoFiles.h"

#include "Core/Error.h"
#include "Formats/Xml.h"

#include <sys/stat.h>

#include <array>
#include <fstream>
#include <iostream>
#include <sstream>

namespace msynth
{
namespace cli
{
namespace
{
using msynth::detail::XmlElement;

std::string Text(const std::string& path)
{
  struct stat info;
  if (::stat(path.c_str(), &info) != 0 || info.st_size > (std::int64_t(1) << 26))
    throw msynth::Error::InFile(
      path, "is missing or larger than 64 MiB (not a .pvti msynth writes)");
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

/// The extent of @p e's attribute @p key: six integers, each pair ordered.
std::array<long long, 6> ExtentOf(const XmlElement& e, const char* key, const std::string& path)
{
  const std::string* value = e.Attribute(key);
  std::array<long long, 6> x{};
  std::istringstream in(value ? *value : "");
  for (auto& v : x)
    if (!(in >> v) || v < -(1LL << 31) || v >= (1LL << 31))
      throw msynth::Error::InFile(path,
        "line " + std::to_string(e.Line) + ": <" + e.Name + "> has no " + key + " of six integers");
  for (std::size_t a = 0; a < 3; ++a)
    if (x[2 * a] > x[2 * a + 1])
      throw msynth::Error::InFile(path,
        "line " + std::to_string(e.Line) + ": <" + e.Name + "> has the empty " + key + " " +
          msynth::Printable(*value));
  return x;
}

std::string Extent(const std::array<long long, 6>& x)
{
  return std::to_string(x[0]) + "-" + std::to_string(x[1]) + " x " + std::to_string(x[2]) + "-" +
    std::to_string(x[3]) + " x " + std::to_string(x[4]) + "-" + std::to_string(x[5]);
}

void PrintArrays(const XmlElement& data, const char* what)
{
  if (data.Children.empty())
    return;
  std::cout << what << ": " << data.Children.size() << "\n";
  for (const auto& a : data.Children)
  {
    const std::string* name = a.Attribute("Name");
    const std::string* type = a.Attribute("type");
    const std::string* components = a.Attribute("NumberOfComponents");
    std::cout << "  " << (name ? msynth::Printable(*name) : "(unnamed)") << ": "
              << (type ? msynth::Printable(*type) : "?")
              << (components ? ", " + msynth::Printable(*components) + " components" : "") << "\n";
  }
}
} // namespace

int PiecesInfo(const std::string& path)
{
  const XmlElement root = msynth::detail::XmlReader(Text(path), path).Parse();
  const std::string* type = root.Attribute("type");
  const XmlElement* image = nullptr;
  for (const auto& c : root.Children)
    if (c.Name == "PImageData")
      image = &c;
  if (root.Name != "VTKFile" || !type || *type != "PImageData" || !image)
    throw msynth::Error::InFile(
      path, "is not VTK's parallel image data (<VTKFile type=\"PImageData\">)");
  const auto whole = ExtentOf(*image, "WholeExtent", path);
  std::cout << "file: " << path << " (parallel image data)\n"
            << "whole extent: " << Extent(whole) << " ("
            << (whole[1] - whole[0] + 1) * (whole[3] - whole[2] + 1) * (whole[5] - whole[4] + 1)
            << " sites)\n";
  for (const char* key : { "Origin", "Spacing" })
    if (const std::string* v = image->Attribute(key))
      std::cout << (key[0] == 'O' ? "origin: " : "spacing: ") << msynth::Printable(*v) << "\n";
  long long pieces = 0, missing = 0;
  for (const auto& c : image->Children)
    pieces += c.Name == "Piece";
  std::cout << "pieces: " << pieces << "\n";
  const std::string folder = path.substr(0, path.find_last_of('/') + 1);
  for (const auto& c : image->Children)
  {
    if (c.Name == "PPointData" || c.Name == "PCellData")
      continue;
    if (c.Name != "Piece")
      continue;
    const auto x = ExtentOf(c, "Extent", path);
    for (std::size_t a = 0; a < 3; ++a)
      if (x[2 * a] < whole[2 * a] || x[2 * a + 1] > whole[2 * a + 1])
        throw msynth::Error::InFile(path,
          "line " + std::to_string(c.Line) + ": a piece's extent " + Extent(x) +
            " is outside the whole extent " + Extent(whole));
    const std::string* source = c.Attribute("Source");
    struct stat info;
    const bool present = source && ::stat((folder + *source).c_str(), &info) == 0;
    missing += !present;
    std::cout << "  " << Extent(x) << ": " << (source ? msynth::Printable(*source) : "(no file)")
              << (present ? "" : " (missing)") << "\n";
  }
  for (const auto& c : image->Children)
    if (c.Name == "PPointData" || c.Name == "PCellData")
      PrintArrays(c, c.Name == "PPointData" ? "point arrays" : "cell arrays");
  if (missing > 0)
    throw msynth::Error::InFile(path,
      Counted(missing, "piece file") + " named in it " + (missing == 1 ? "is" : "are") +
        " missing");
  return 0;
}

} // namespace cli
} // namespace msynth
