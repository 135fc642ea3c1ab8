// SPDX-License-Identifier: BSD-3-Clause
// The original program's text format (msynth/TextModel.h): read, then written and read back.
#include "Formats/TextModel.h"
#include "FuzzCommon.h"

#include <sstream>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  msynth_fuzz::Expect(
    [&]
    {
      std::istringstream in(std::string(reinterpret_cast<const char*>(data), size));
      const msynth::TextModel m = msynth::ReadTextModel(in, "fuzz.txt", 1 << 16);
      std::ostringstream out;
      msynth::WriteTextModel(out, m);
      std::istringstream again(out.str());
      const msynth::TextModel n = msynth::ReadTextModel(again, "again.txt", 1 << 16);
      if (!(n.Grid == m.Grid) || n.Trailer != m.Trailer)
        __builtin_trap(); // a written model reads back identically
    });
  return 0;
}
