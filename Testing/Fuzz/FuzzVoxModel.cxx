// SPDX-License-Identifier: BSD-3-Clause
// MagicaVoxel .vox models (msynth/VoxModel.h): the first model, and every model of a scene.
#include "Formats/VoxModel.h"
#include "FuzzCommon.h"

#include <vector>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  msynth_fuzz::Expect([&]
    { msynth::ReadVoxModel(std::vector<std::uint8_t>(data, data + size), "fuzz.vox", 1 << 18); });
  msynth_fuzz::Expect([&]
    { msynth::ReadVoxScene(std::vector<std::uint8_t>(data, data + size), "fuzz.vox", 1 << 18); });
  return 0;
}
