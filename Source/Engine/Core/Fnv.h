// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/**
 * @file Fnv.h
 * @brief FNV-1a over bytes: the stamps of streamed slabs and the fingerprints MPI ranks compare
 * before they share blocks (not for security).
 */
#include <cstddef>
#include <cstdint>

namespace msynth
{

/// The FNV-1a offset basis: the hash of no bytes.
constexpr std::uint64_t FnvStart = 1469598103934665603ull;

/// @p hash continued over @p size bytes at @p data.
inline std::uint64_t Fnv1a(const void* data, std::size_t size, std::uint64_t hash = FnvStart)
{
  const auto* bytes = static_cast<const unsigned char*>(data);
  for (std::size_t i = 0; i < size; ++i)
    hash = (hash ^ bytes[i]) * 1099511628211ull;
  return hash;
}

} // namespace msynth
