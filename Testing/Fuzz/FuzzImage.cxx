// SPDX-License-Identifier: BSD-3-Clause
// Tile images and samples: PNG (libpng's checks) and BMP (ours); a picture that reads is then
// taken as an image sample (the overlapping model), with a pattern size and symmetry from the
// input's last bytes, so extraction's bounds meet arbitrary pictures too.
#include "Discrete/OverlappingModel.h"
#include "Formats/Image.h"
#include "FuzzCommon.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  const bool bmp = size >= 2 && data[0] == 'B' && data[1] == 'M';
  msynth_fuzz::Expect(
    [&]
    {
      const msynth::RgbaImage image =
        msynth::ReadImage(msynth_fuzz::AsFile(data, size, bmp ? ".bmp" : ".png"));
      if (size < 2)
        return;
      msynth::OverlappingOptions options;
      options.N = 1 + data[size - 1] % 4;
      options.Symmetry = 1 + data[size - 2] % 8;
      options.PeriodicInput = (data[size - 1] & 0x80) != 0;
      options.Ground = (data[size - 2] & 0x80) != 0;
      const msynth::PatternSet set = msynth::ExtractPatterns(image, options, "fuzz");
      (void)set.Rules();
      if (options.Ground)
        (void)set.GroundPatterns(options.PeriodicInput);
    });
  return 0;
}
