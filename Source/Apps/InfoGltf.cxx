// SPDX-License-Identifier: BSD-3-Clause
// `msynth info FILE.glb|.gltf`: meshes, primitives and materials (Formats/GltfSummary.h, which
// checks the container and every accessor used before trusting a count).
#include "Common.h"
#include "InfoFiles.h"

#include "Core/Error.h"
#include "Formats/GltfSummary.h"

#include <cmath>
#include <cstdio>
#include <iostream>

namespace msynth
{
namespace cli
{
namespace
{
/// A linear colour component as the display (sRGB) byte a picture shows.
int DisplayByte(double c)
{
  c = c < 0 ? 0 : (c > 1 ? 1 : c);
  const double s = c <= 0.0031308 ? 12.92 * c : 1.055 * std::pow(c, 1 / 2.4) - 0.055;
  return static_cast<int>(std::lround(s * 255));
}

const char* ModeName(int mode)
{
  static const char* const names[] = { "points", "lines", "line loop", "line strip", "triangles",
    "triangle strip", "triangle fan" };
  return mode >= 0 && mode < 7 ? names[mode] : "unknown mode";
}
} // namespace

int GltfInfo(const std::string& path)
{
  const msynth::GltfSummary s = msynth::ReadGltfSummary(path);
  long long vertices = 0, triangles = 0, primitives = 0;
  for (const auto& mesh : s.Meshes)
    for (const auto& p : mesh.Primitives)
    {
      vertices += p.Vertices;
      triangles += p.Triangles;
      ++primitives;
    }
  std::cout << "file: " << path << " (glTF " << msynth::Printable(s.Version)
            << (s.Binary ? ", binary" : ", JSON") << ")\n";
  if (!s.Generator.empty())
    std::cout << "generator: " << msynth::Printable(s.Generator) << "\n";
  std::cout << "scenes: " << s.Scenes << ", nodes: " << s.Nodes << ", buffers: " << s.BufferBytes
            << " bytes\n"
            << "meshes: " << s.Meshes.size() << " (" << Counted(primitives, "primitive") << ", "
            << Counted(vertices, "vertex", "vertices") << ", " << Counted(triangles, "triangle")
            << ")\n";
  for (const auto& mesh : s.Meshes)
  {
    std::cout << "  " << (mesh.Name.empty() ? "(unnamed)" : msynth::Printable(mesh.Name)) << ":";
    for (const auto& p : mesh.Primitives)
    {
      std::cout << " " << ModeName(p.Mode) << ", " << Counted(p.Vertices, "vertex", "vertices")
                << ", " << Counted(p.Triangles, "triangle");
      if (p.Material >= 0)
        std::cout << ", material " << p.Material;
      std::cout << ";";
    }
    std::cout << "\n";
  }
  std::cout << "materials: " << s.Materials.size() << "\n";
  for (std::size_t m = 0; m < s.Materials.size(); ++m)
  {
    const auto& material = s.Materials[m];
    const auto& c = material.BaseColor;
    char hex[8];
    std::snprintf(
      hex, sizeof(hex), "#%02x%02x%02x", DisplayByte(c[0]), DisplayByte(c[1]), DisplayByte(c[2]));
    std::cout << "  " << m << " "
              << (material.Name.empty() ? "(unnamed)" : msynth::Printable(material.Name))
              << ": base colour " << hex << " (linear " << c[0] << ", " << c[1] << ", " << c[2]
              << ", alpha " << c[3] << ")" << (material.DoubleSided ? ", double-sided" : "")
              << "\n";
  }
  return 0;
}

} // namespace cli
} // namespace msynth
