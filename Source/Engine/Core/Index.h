// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/**
 * @file Index.h
 * @brief ToIndex: the one conversion of a signed or unsigned integer to a container index.
 *
 * Sites, labels, planes and blocks are counted with signed integers (they take part in
 * arithmetic with offsets that may be negative); containers are indexed with std::size_t.
 * Every such conversion goes through ToIndex, which checks in debug and sanitizer builds that
 * the value is not negative and compiles to nothing in release builds.
 */
#include <cassert>
#include <cstddef>
#include <type_traits>

namespace msynth
{

/// @p value as a std::size_t index; @p value must not be negative (asserted in debug builds).
template <typename T>
constexpr std::size_t ToIndex(T value) noexcept
{
  // __int128 (the continuous arrangement's exact arithmetic) is not std::is_integral in ISO mode.
  constexpr bool wide = std::is_same_v<T, __int128>;
  static_assert(std::is_integral_v<T> || std::is_enum_v<T> || wide, "ToIndex takes integers only");
  if constexpr (std::is_enum_v<T>)
    return ToIndex(static_cast<std::underlying_type_t<T>>(value));
  else
  {
    if constexpr (std::is_signed_v<T> || wide)
      assert(value >= 0 && "a negative value used as an index");
    return static_cast<std::size_t>(value);
  }
}

} // namespace msynth
