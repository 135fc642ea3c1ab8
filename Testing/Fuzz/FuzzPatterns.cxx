// SPDX-License-Identifier: BSD-3-Clause
// Factor-graph pattern synthesis fed small fuzzed exemplars, shapes (as text), zones, fixed sites
// and mirrors; every pattern it returns is checked by the independent pair check, and zones and
// fixed sites are checked here.
#include "FuzzCommon.h"
#include "Patterns/PatternQuality.h"
#include "Patterns/PatternSynthesis.h"

#include <algorithm>
#include <string>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  if (size < 10)
    return 0;
  // Bytes 0-9: exemplar size, output size, method, mirror, zones, fixed, seed; then the
  // exemplar's labels; what is left is the soft factor list, as text.
  const std::int64_t ex = 1 + data[0] % 5, ey = 1 + data[1] % 5, ez = 1 + data[2] % 2;
  const auto cells = static_cast<std::size_t>(ex * ey * ez);
  if (size < 10 + cells)
    return 0;
  msynth::LabelGrid exemplar(ex, ey, ez);
  std::size_t k = 10;
  for (std::int64_t z = 0; z < ez; ++z)
    for (std::int64_t y = 0; y < ey; ++y)
      for (std::int64_t x = 0; x < ex; ++x)
        exemplar.Set(x, y, z, data[k++] % 5);
  const std::string soft(reinterpret_cast<const char*>(data + k), size - k);
  msynth::PatternOptions o;
  o.Size = { { 1 + data[3] % 10, 1 + data[4] % 10, ez > 1 ? 1 + data[5] % 3 : 1 } };
  o.Method = static_cast<msynth::PatternMethod>(data[6] % 3);
  o.Mirror[0] = (data[6] >> 2) & 1;
  if (o.Mirror[0])
    o.MirrorMap = { { 1, 2 }, { 2, 1 } };
  o.Samples = 1 + ((data[6] >> 3) & 1);
  o.BurnIn = (data[6] >> 4) & 3;
  o.MaxMoves = 3000;
  o.MovesPerSample = 50;
  o.Seed = data[9];
  const auto n = static_cast<std::size_t>(o.Size[0] * o.Size[1] * o.Size[2]);
  if (data[7] & 1)
  {
    o.SiteZone.resize(n);
    for (std::size_t i = 0; i < n; ++i)
      o.SiteZone[i] = static_cast<std::int32_t>((i * 7 + data[7]) % 3);
    o.ZoneTiles[1] = { data[7] % 5 };
    o.ZoneExemplars[2] = { 0 };
  }
  if (data[8] & 1)
  {
    o.Fixed.assign(n, -1);
    o.Fixed[data[8] % n] = data[8] % 5;
  }
  msynth_fuzz::Expect(
    [&]
    {
      o.SoftFactors = msynth::ParseStencils(soft);
      const msynth::PatternResult r = msynth::SynthesizePattern({ exemplar }, o);
      for (const msynth::PatternSample& s : r.Samples)
      {
        if (!msynth::CheckPatternPairs({ exemplar }, s.Labels, 1).empty())
          __builtin_trap();
        for (std::size_t i = 0; i < n; ++i)
        {
          const msynth::Label v = s.Labels.Data()[i];
          if (!o.SiteZone.empty() && o.SiteZone[i] == 1 && v != o.ZoneTiles[1][0])
            __builtin_trap();
          if (!o.Fixed.empty() && o.Fixed[i] >= 0 && v != o.Fixed[i] &&
            exemplar.Data().end() !=
              std::find(exemplar.Data().begin(), exemplar.Data().end(), o.Fixed[i]))
            __builtin_trap();
        }
        for (const msynth::Stencil& st : o.SoftFactors)
          (void)msynth::PatternKL({ exemplar }, s.Labels, st);
      }
    });
  return 0;
}
