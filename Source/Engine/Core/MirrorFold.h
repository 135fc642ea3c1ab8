// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/**
 * @file MirrorFold.h
 * @brief The one unfolding of a mirrored grid (D§3.5.2's reflection symmetry, Y§6's mirrored
 * patterns): a model of @p full sites made of a part of the first ceil(n / 2) sites along each
 * mirrored axis, and its reflections. Discrete synthesis and pattern synthesis both use it;
 * continuous synthesis reflects arrangement vertices instead (Continuous/ContinuousMirror.h).
 */
#include <array>
#include <cstdint>

namespace msynth
{

/**
 * Folds output site @p q of a grid of @p full sites onto site @p p of its part of @p part sites:
 * along each axis whose bit is set in @p axes, a site past the part is reflected,
 * p = full − 1 − q. Returns the axes (bits) along which @p q was reflected.
 */
inline int FoldMirror(const std::array<std::int64_t, 3>& q, const std::array<std::int64_t, 3>& full,
  const std::array<std::int64_t, 3>& part, int axes, std::array<std::int64_t, 3>& p)
{
  int reflected = 0;
  p = q;
  for (std::size_t a = 0; a < 3; ++a)
    if (((axes >> a) & 1) && q[a] >= part[a])
    {
      p[a] = full[a] - 1 - q[a];
      reflected |= 1 << a;
    }
  return reflected;
}

} // namespace msynth
