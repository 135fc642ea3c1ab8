// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/**
 * @file FileBytes.h
 * @brief A whole input file in memory, its size checked against a limit before it is read.
 */
#include <cstdint>
#include <string>

namespace msynth
{

/**
 * The bytes of @p path. @throw Error naming the file when it cannot be opened or read, or with
 * @p tooLarge as the problem when it holds more than @p maxBytes.
 */
std::string ReadFileBytes(
  const std::string& path, std::uint64_t maxBytes, const std::string& tooLarge);

} // namespace msynth
