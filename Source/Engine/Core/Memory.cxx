// SPDX-License-Identifier: BSD-3-Clause
#include "Core/Memory.h"

#include "Core/Error.h"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <limits>
#include <sstream>
#include <sys/mman.h>
#include <sys/resource.h>
#include <unistd.h>

namespace msynth
{
namespace
{
/// A field of /proc/meminfo in bytes ("MemAvailable:   123 kB"); 0 when absent.
std::uint64_t MemInfo(const std::string& key)
{
  std::ifstream in("/proc/meminfo");
  std::string name, unit;
  std::uint64_t value = 0;
  while (in >> name >> value)
  {
    std::getline(in, unit);
    if (name == key + ":")
      return value * 1024;
  }
  return 0;
}

} // namespace

void AdviseHugePages(const void* data, std::size_t bytes)
{
  constexpr std::uintptr_t huge = std::uintptr_t(2) << 20;
  if (bytes < 4 * huge)
    return;
  // The whole huge pages inside the range.
  const auto from = (reinterpret_cast<std::uintptr_t>(data) + huge - 1) & ~(huge - 1);
  const auto to = (reinterpret_cast<std::uintptr_t>(data) + bytes) & ~(huge - 1);
  if (to > from)
    ::madvise(reinterpret_cast<void*>(from), to - from, MADV_HUGEPAGE);
}

std::uint64_t VirtualSize()
{
  std::ifstream in("/proc/self/statm");
  std::uint64_t pages = 0;
  if (!(in >> pages))
    return 0;
  return pages * static_cast<std::uint64_t>(::sysconf(_SC_PAGESIZE));
}

std::uint64_t AvailableMemory()
{
  std::uint64_t available = MemInfo("MemAvailable");
  if (available == 0)
    available = std::numeric_limits<std::uint64_t>::max();
  for (int resource : { RLIMIT_AS, RLIMIT_DATA })
  {
    rlimit limit{};
    if (::getrlimit(resource, &limit) == 0 && limit.rlim_cur != RLIM_INFINITY)
    {
      const std::uint64_t used = VirtualSize();
      const std::uint64_t cap = limit.rlim_cur > used ? limit.rlim_cur - used : 0;
      available = std::min(available, cap);
    }
  }
  if (const char* cap = std::getenv("MSYNTH_AVAILABLE_MEMORY")) // a smaller machine, for tests
  {
    char* end = nullptr;
    const unsigned long long bytes = std::strtoull(cap, &end, 10);
    if (end != cap && *end == '\0')
      available = std::min<std::uint64_t>(available, bytes);
  }
  return available;
}

std::string FormatBytes(std::uint64_t bytes)
{
  static const char* const units[] = { "bytes", "KB", "MB", "GB", "TB", "PB", "EB" };
  double v = static_cast<double>(bytes);
  int u = 0;
  while (v >= 1024.0 && u < 6)
  {
    v /= 1024.0;
    ++u;
  }
  char text[32];
  std::snprintf(text, sizeof text, u == 0 ? "%.0f %s" : "%.1f %s", v, units[u]);
  return text;
}

void CheckMemory(std::uint64_t bytes, const std::string& what)
{
  const std::uint64_t available = AvailableMemory();
  if (bytes > available)
    throw Error(what + " needs about " + FormatBytes(bytes) + ", more than the " +
      FormatBytes(available) + " of memory available");
}

} // namespace msynth
