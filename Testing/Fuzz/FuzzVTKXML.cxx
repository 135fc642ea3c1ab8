// SPDX-License-Identifier: BSD-3-Clause
// The check that stands before VTK's XML readers (msynth/VTKXMLCheck.h).
#include "Formats/VTKXMLCheck.h"
#include "FuzzCommon.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  msynth_fuzz::Expect([&] { msynth::CheckVTKXMLFile(msynth_fuzz::AsFile(data, size, ".vti")); });
  return 0;
}
