// SPDX-License-Identifier: BSD-3-Clause
// Tile images and samples: PNG (libpng's checks) and BMP (ours).
#include "Formats/Image.h"
#include "FuzzCommon.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  const bool bmp = size >= 2 && data[0] == 'B' && data[1] == 'M';
  msynth_fuzz::Expect(
    [&] { msynth::ReadImage(msynth_fuzz::AsFile(data, size, bmp ? ".bmp" : ".png")); });
  return 0;
}
