// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/**
 * @file Memory.h
 * @brief Checking an allocation whose size comes from a file or a parameter before making it,
 * so that a large request is refused with a sentence instead of ending in std::bad_alloc or the
 * out-of-memory killer.
 */
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace msynth
{

/**
 * Bytes this process can still expect to allocate: the system's available memory
 * (MemAvailable of /proc/meminfo), capped by the address-space and data limits (RLIMIT_AS,
 * RLIMIT_DATA) less what the process already uses, and by the environment variable
 * MSYNTH_AVAILABLE_MEMORY (bytes) when set. UINT64_MAX when nothing is known.
 */
std::uint64_t AvailableMemory();

/// The process's virtual size in bytes (/proc/self/statm); 0 when unknown.
std::uint64_t VirtualSize();

/// Advises the kernel to back [@p data, @p data + @p bytes) by huge pages (a no-op for small or
/// unsupported ranges); call it before the memory is first touched.
void AdviseHugePages(const void* data, std::size_t bytes);

/**
 * Sizes @p values to @p n zeros backed, where the system allows, by transparent huge pages: the
 * memory is reserved untouched, advised (madvise MADV_HUGEPAGE), then filled. A gigabyte in 4 KB
 * pages costs a quarter of a million page faults; in huge pages, five hundred.
 */
template <typename T>
void ResizeOnHugePages(std::vector<T>& values, std::size_t n)
{
  values.clear();
  values.reserve(n);
  AdviseHugePages(values.data(), n * sizeof(T));
  values.resize(n);
}

/// "1.5 GB", "320 MB", "12 KB": @p bytes for messages.
std::string FormatBytes(std::uint64_t bytes);

/**
 * @throw Error "<what> needs about N, more than the M of memory available" when @p bytes
 * exceeds AvailableMemory().
 */
void CheckMemory(std::uint64_t bytes, const std::string& what);

} // namespace msynth
