// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/**
 * @file ExactArithmetic.h
 * @brief Exact arithmetic of the plane arrangement (internal): 128-bit integers
 * that refuse to overflow, exact rational points, and integer directions.
 */
#include "Continuous/Neighbourhood.h"
#include "Core/Error.h"

#include <array>
#include <cstdint>
#include <cstdlib>
#include <numeric>

namespace msynth
{
namespace detail
{
using Wide = __int128;

[[noreturn]] inline void Overflow()
{
  throw Error("plane arrangement: exact coordinates exceed 128-bit integers (the output box is "
              "too large for the example's plane directions)");
}

/// Whether @p a fits 64 bits: most exact values do. Their products cannot overflow, and 64-bit
/// division is several times faster than the 128-bit library calls.
inline bool Fits64(Wide a)
{
  return a == static_cast<std::int64_t>(a);
}

inline Wide Mul(Wide a, Wide b)
{
  if (Fits64(a) && Fits64(b))
  {
    return a * b;
  }
  Wide r;
  if (__builtin_mul_overflow(a, b, &r))
  {
    Overflow();
  }
  return r;
}

inline Wide Add(Wide a, Wide b)
{
  Wide r;
  if (__builtin_add_overflow(a, b, &r))
  {
    Overflow();
  }
  return r;
}

inline Wide Abs(Wide a)
{
  return a < 0 ? -a : a;
}

/// a / b and a % b (C++ rounding), in 64 bits when both fit.
inline Wide Quot(Wide a, Wide b)
{
  if (Fits64(a) && Fits64(b) && b != -1)
  {
    return static_cast<std::int64_t>(a) / static_cast<std::int64_t>(b);
  }
  return a / b;
}

inline Wide Rem(Wide a, Wide b)
{
  if (Fits64(a) && Fits64(b) && b != -1)
  {
    return static_cast<std::int64_t>(a) % static_cast<std::int64_t>(b);
  }
  return a % b;
}

inline Wide Gcd(Wide a, Wide b)
{
  a = Abs(a);
  b = Abs(b);
  while (b != 0)
  {
    const Wide t = Rem(a, b);
    a = b;
    b = t;
  }
  return a;
}

/// Floor of a / b for b > 0.
inline Wide FloorDiv(Wide a, Wide b)
{
  const Wide q = Quot(a, b);
  return (q * b != a && a < 0) ? q - 1 : q;
}

inline Wide CeilDiv(Wide a, Wide b)
{
  return -FloorDiv(-a, b);
}

/// An exact rational point Num / Den with Den > 0, reduced.
struct Exact
{
  std::array<Wide, 3> Num{};
  Wide Den = 1;

  void Reduce()
  {
    if (this->Den < 0)
    {
      this->Den = -this->Den;
      for (auto& v : this->Num)
      {
        v = -v;
      }
    }
    Wide g = Gcd(Gcd(Gcd(this->Num[0], this->Num[1]), this->Num[2]), this->Den);
    if (g > 1)
    {
      for (auto& v : this->Num)
      {
        v = Quot(v, g);
      }
      this->Den = Quot(this->Den, g);
    }
  }
};

inline Wide DotNum(const IntVec3& n, const Exact& x)
{
  return Add(Add(Mul(n[0], x.Num[0]), Mul(n[1], x.Num[1])), Mul(n[2], x.Num[2]));
}

inline IntVec3 Primitive(IntVec3 d)
{
  const std::int64_t g = std::gcd(std::gcd(std::abs(d[0]), std::abs(d[1])), std::abs(d[2]));
  if (g > 1)
  {
    for (auto& c : d)
    {
      c /= g;
    }
  }
  // Canonical sign: first non-zero component positive.
  for (auto c : d)
  {
    if (c != 0)
    {
      if (c < 0)
      {
        for (auto& e : d)
        {
          e = -e;
        }
      }
      break;
    }
  }
  return d;
}

inline IntVec3 CrossInt(const IntVec3& a, const IntVec3& b)
{
  return { a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0] };
}

} // namespace detail
} // namespace msynth
