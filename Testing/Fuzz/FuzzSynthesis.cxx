// SPDX-License-Identifier: BSD-3-Clause
// The discrete solver fed small fuzzed examples and parameters; every model it returns is
// checked against the example by the independent check (Eq. 3.1).
#include "Discrete/AdjacencyRules.h"
#include "Discrete/ConsistencyCheck.h"
#include "Discrete/DiscreteSynthesis.h"
#include "Discrete/ExampleAnalysis.h"
#include "FuzzCommon.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  if (size < 8)
    return 0;
  // Bytes 0-7: example size, output size, block size, order/choice, seed; then the labels.
  const std::int64_t ex = 1 + data[0] % 5, ey = 1 + data[1] % 5, ez = 1 + data[2] % 3;
  if (size < 8 + static_cast<std::size_t>(ex * ey * ez))
    return 0;
  msynth::LabelGrid example(ex, ey, ez);
  std::size_t k = 8;
  for (std::int64_t z = 0; z < ez; ++z)
    for (std::int64_t y = 0; y < ey; ++y)
      for (std::int64_t x = 0; x < ex; ++x)
        example.Set(x, y, z, data[k++] % 6);
  msynth::SynthesisOptions o;
  o.Size = { { 1 + data[3] % 12, 1 + data[4] % 12, 1 + data[5] % 4 } };
  if (data[6] & 1)
    o.BlockSize = { { 1 + (data[6] >> 1) % 6, 1 + (data[6] >> 4) % 6, o.Size[2] } };
  o.Order = static_cast<msynth::SiteOrder>(data[7] % 3);
  o.Choice = (data[7] >> 2) & 1 ? msynth::LabelChoice::Frequency : msynth::LabelChoice::Uniform;
  o.Seed = data[7] >> 3;
  o.Threads = 1 + ((data[7] >> 6) & 1);
  msynth_fuzz::Expect(
    [&]
    {
      const auto rules =
        msynth::AdjacencyRules::FromExample(msynth::ExampleAnalysis::FromExample(example));
      const msynth::SynthesisResult r = msynth::Synthesize(rules, o);
      if (r.Succeeded() && !msynth::CheckConsistency(example, r.Model).Consistent)
        __builtin_trap();
    });
  return 0;
}
