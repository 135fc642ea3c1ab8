// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Helpers of the libFuzzer harnesses (Utilities/fuzz.sh builds and runs them).
#include "Core/Error.h"

#include <cstdint>
#include <cstdio>
#include <fstream>
#include <string>
#include <unistd.h>

namespace msynth_fuzz
{
/// The input as a file (for readers that take a path), one per process, with extension @p ext.
inline std::string AsFile(const std::uint8_t* data, std::size_t size, const char* ext)
{
  static const std::string dir = []
  {
    const char* shm = ::access("/dev/shm", W_OK) == 0 ? "/dev/shm" : "/tmp";
    return std::string(shm);
  }();
  const std::string path = dir + "/msynth-fuzz-" + std::to_string(::getpid()) + ext;
  std::ofstream(path, std::ios::binary | std::ios::trunc)
    .write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  return path;
}

/// Runs @p read; msynth::Error is the expected way to refuse an input, anything else escapes
/// (and libFuzzer reports it).
template <typename F>
void Expect(F&& read)
{
  try
  {
    read();
  }
  catch (const msynth::Error&)
  {
  }
}
} // namespace msynth_fuzz
