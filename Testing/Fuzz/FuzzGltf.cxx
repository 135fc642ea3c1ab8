// SPDX-License-Identifier: BSD-3-Clause
// glTF 2.0 as `msynth info` reads it (Formats/GltfSummary.h): a .glb when the input starts with
// glTF's magic, else JSON text; external files refused.
#include "Formats/GltfSummary.h"
#include "FuzzCommon.h"

#include <vector>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  const std::vector<std::uint8_t> bytes(data, data + size);
  const bool binary =
    size >= 4 && data[0] == 'g' && data[1] == 'l' && data[2] == 'T' && data[3] == 'F';
  msynth_fuzz::Expect([&] { msynth::SummarizeGltf(bytes, "fuzz.glb", binary, ""); });
  return 0;
}
