// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/**
 * @file Memory.h
 * @brief Checking an allocation whose size comes from a file or a parameter before making it,
 * so that a large request is refused with a sentence instead of ending in std::bad_alloc or the
 * out-of-memory killer.
 */
#include <cstdint>
#include <string>

namespace msynth
{

/**
 * Bytes this process can still expect to allocate: the system's available memory
 * (MemAvailable of /proc/meminfo), capped by the address-space and data limits (RLIMIT_AS,
 * RLIMIT_DATA) less what the process already uses. UINT64_MAX when nothing is known.
 */
std::uint64_t AvailableMemory();

/// The process's virtual size in bytes (/proc/self/statm); 0 when unknown.
std::uint64_t VirtualSize();

/// "1.5 GB", "320 MB", "12 KB": @p bytes for messages.
std::string FormatBytes(std::uint64_t bytes);

/**
 * @throw Error "<what> needs about N, more than the M of memory available" when @p bytes
 * exceeds AvailableMemory().
 */
void CheckMemory(std::uint64_t bytes, const std::string& what);

} // namespace msynth
