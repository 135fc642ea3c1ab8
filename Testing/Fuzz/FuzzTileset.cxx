// SPDX-License-Identifier: BSD-3-Clause
// Simple-tiled tilesets (msynth/Tileset.h), and a small synthesis with their rules.
#include "Discrete/ConsistencyCheck.h"
#include "Discrete/DiscreteSynthesis.h"
#include "Formats/Tileset.h"
#include "FuzzCommon.h"

#include <sstream>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  msynth_fuzz::Expect(
    [&]
    {
      std::istringstream in(std::string(reinterpret_cast<const char*>(data), size));
      const msynth::Tileset t = msynth::ReadTileset(in, "fuzz.xml");
      if (t.NumberOfLabels() > 64)
        return;
      msynth::SynthesisOptions o;
      o.Size = { { 6, 5, 1 } };
      o.Seed = size;
      const msynth::SynthesisResult r = msynth::Synthesize(t.Rules(), o);
      if (r.Succeeded() && !msynth::CheckConsistency(t.Pairs, r.Model).Consistent)
        __builtin_trap(); // the independent check must accept every model returned
    });
  return 0;
}
