// SPDX-License-Identifier: BSD-3-Clause
// Polyhedral examples: OBJ, PLY and STL (the first byte picks the reader), then validated.
#include "Formats/MeshFormats.h"
#include "Formats/PolyhedralExample.h"
#include "FuzzCommon.h"

#include <sstream>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  if (size < 1 || size > 4096)
    return 0;
  msynth_fuzz::Expect(
    [&]
    {
      msynth::PolyhedralExample e;
      const int kind = data[0] % 3;
      if (kind == 0)
      {
        std::istringstream in(std::string(reinterpret_cast<const char*>(data + 1), size - 1));
        e = msynth::ReadOBJExample(in, "fuzz.obj");
      }
      else
        e = kind == 1 ? msynth::ReadPLYExample(msynth_fuzz::AsFile(data + 1, size - 1, ".ply"))
                      : msynth::ReadSTLExample(msynth_fuzz::AsFile(data + 1, size - 1, ".stl"));
      if (e.Points.size() <= 64 && e.Faces.size() <= 64)
        msynth::ValidateExample(e);
    });
  return 0;
}
