// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/**
 * @file Index.h
 * @brief The one conversion of a signed count or position (std::int64_t sites, int labels) to a
 * container index: Idx(i) in place of static_cast<std::size_t>(i) throughout the engine, with
 * a check of the sign in debug builds.
 */
#include <cassert>
#include <cstddef>
#include <type_traits>

namespace msynth
{
/// @p i as a std::size_t index (i must not be negative).
template <typename T>
constexpr std::size_t Idx(T i) noexcept
{
  static_assert(std::is_arithmetic_v<T> || std::is_enum_v<T>, "Idx takes a number");
  if constexpr (std::is_signed_v<T>)
    assert(i >= 0);
  return static_cast<std::size_t>(i);
}
} // namespace msynth
