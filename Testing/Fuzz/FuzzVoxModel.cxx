// SPDX-License-Identifier: BSD-3-Clause
// MagicaVoxel .vox models (msynth/VoxModel.h): the first model, every model of a scene, and the
// summary `msynth info` prints (Formats/VoxSummary.h).
#include "Formats/VoxModel.h"
#include "Formats/VoxSummary.h"
#include "FuzzCommon.h"

#include <vector>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  msynth_fuzz::Expect([&]
    { msynth::ReadVoxModel(std::vector<std::uint8_t>(data, data + size), "fuzz.vox", 1 << 18); });
  msynth_fuzz::Expect([&]
    { msynth::ReadVoxScene(std::vector<std::uint8_t>(data, data + size), "fuzz.vox", 1 << 18); });
  msynth_fuzz::Expect(
    [&] { msynth::SummarizeVox(std::vector<std::uint8_t>(data, data + size), "fuzz.vox"); });
  return 0;
}
