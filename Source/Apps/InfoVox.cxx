// SPDX-License-Identifier: BSD-3-Clause
// `msynth info FILE.vox`: a MagicaVoxel file's models, their placement and the palette entries
// their voxels use (Formats/VoxSummary.h; no voxels are built).
#include "Common.h"
#include "InfoFiles.h"

#include "Core/Error.h"
#include "Formats/VoxSummary.h"

#include <cstdio>
#include <iostream>

namespace msynth
{
namespace cli
{

int VoxInfo(const std::string& path)
{
  const msynth::VoxSummary s = msynth::ReadVoxSummary(path);
  long long voxels = 0;
  for (const auto& m : s.Models)
    voxels += m.Voxels;
  std::cout << "file: " << path << " (MagicaVoxel version " << s.Version << ", "
            << Counted(static_cast<long long>(s.Models.size()), "model") << ", "
            << Counted(voxels, "voxel") << ", "
            << (s.SceneNodes > 0 ? Counted(s.SceneNodes, "scene node") : std::string("no scene"))
            << ")\n";
  for (std::size_t i = 0; i < s.Models.size(); ++i)
  {
    const auto& m = s.Models[i];
    std::cout << "  model " << i << ": " << m.Size[0] << " x " << m.Size[1] << " x " << m.Size[2]
              << ", " << Counted(m.Voxels, "voxel");
    if (m.Placed)
      std::cout << ", centre at (" << m.Translation[0] << ", " << m.Translation[1] << ", "
                << m.Translation[2] << ")";
    std::cout << "\n";
  }
  int used = 0;
  for (std::size_t i = 1; i < 256; ++i)
    used += s.Uses[i] > 0;
  std::cout << "palette: " << (s.HasPalette ? "the file's" : "MagicaVoxel's default") << ", "
            << Counted(used, "entry", "entries") << " used\n";
  for (std::size_t i = 1; i < 256; ++i)
  {
    if (s.Uses[i] == 0)
      continue;
    std::cout << "  " << i << ": " << Counted(s.Uses[i], "voxel");
    if (s.HasPalette)
    {
      char hex[10];
      const auto& c = s.Palette[i];
      std::snprintf(hex, sizeof(hex), "#%02x%02x%02x", c[0], c[1], c[2]);
      std::cout << ", " << hex;
    }
    std::cout << "\n";
  }
  return static_cast<int>(s.Models.size());
}

} // namespace cli
} // namespace msynth
