// SPDX-License-Identifier: BSD-3-Clause
// `msynth info FILE.vdb`: the grids of an OpenVDB file (listed by OpenVDB in a child process,
// VDB/IsolatedRead.h, so a damaged file costs one line and bounded memory).
#include "Common.h"
#include "InfoFiles.h"

#include "Core/Error.h"
#include "VDB/VDBFile.h"

#include <iostream>
#include <sstream>

namespace msynth
{
namespace cli
{
namespace
{
std::string Spacing(const std::array<double, 3>& s)
{
  std::ostringstream out;
  out << s[0];
  if (s[1] != s[0] || s[2] != s[0])
    out << " x " << s[1] << " x " << s[2];
  return out.str();
}
} // namespace

int VolumeInfo(const std::string& path)
{
  msynth::vdb::MetadataMap file;
  const std::vector<msynth::vdb::GridSummary> grids = msynth::vdb::ListGrids(path, &file);
  std::cout << "file: " << path << " (OpenVDB, "
            << Counted(static_cast<long long>(grids.size()), "grid") << ")\n";
  for (const char* key : { "generator", "msynth_command", "seed", "ExampleFile", "TilesetFile" })
    if (file.count(key))
      std::cout << key << ": " << msynth::Printable(file[key]) << "\n";
  for (const auto& g : grids)
  {
    std::cout << "grid " << msynth::Printable(g.Name) << ": " << msynth::Printable(g.TypeName)
              << ", " << (g.GridClass.empty() ? "unknown" : msynth::Printable(g.GridClass))
              << " class, " << g.ActiveVoxelCount << " active voxels";
    if (g.ActiveMin[0] <= g.ActiveMax[0])
      std::cout << ", index box (" << g.ActiveMin[0] << ", " << g.ActiveMin[1] << ", "
                << g.ActiveMin[2] << ") - (" << g.ActiveMax[0] << ", " << g.ActiveMax[1] << ", "
                << g.ActiveMax[2] << ")";
    std::cout << ", voxel size " << Spacing(g.VoxelSize) << "\n";
    for (const char* key : { "msynth_label_surfaces", "label_name", "object_type_name" })
      if (g.Metadata.count(key))
        std::cout << "  " << key << ": " << msynth::Printable(g.Metadata.at(key)) << "\n";
  }
  return 0;
}

} // namespace cli
} // namespace msynth
