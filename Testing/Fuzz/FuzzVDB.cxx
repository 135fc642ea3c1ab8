// SPDX-License-Identifier: BSD-3-Clause
// OpenVDB files (msynth/VDBFile.h): read in a child process, so only our side is fuzzed here;
// a crash of the OpenVDB library is an Error.
#include "FuzzCommon.h"
#include "VDB/VDBFile.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  msynth_fuzz::Expect(
    [&]
    {
      msynth::vdb::ReadOptions options;
      options.MaxVoxels = 1 << 20;
      msynth::vdb::ReadFile(msynth_fuzz::AsFile(data, size, ".vdb"), options);
    });
  return 0;
}
