// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Small vector helpers on msynth::Point3 shared by the polyhedral sources (internal header).
#include "Formats/PolyhedralExample.h"

#include <cmath>

namespace msynth
{
namespace point3
{

inline Point3 Sub(const Point3& a, const Point3& b)
{
  return { a[0] - b[0], a[1] - b[1], a[2] - b[2] };
}

/// a + s·b
inline Point3 Add(const Point3& a, const Point3& b, double s)
{
  return { a[0] + s * b[0], a[1] + s * b[1], a[2] + s * b[2] };
}

inline Point3 Cross(const Point3& a, const Point3& b)
{
  return { a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0] };
}

inline double Dot(const Point3& a, const Point3& b)
{
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

inline double Norm(const Point3& a)
{
  return std::sqrt(Dot(a, a));
}

inline Point3 Unit(const Point3& a)
{
  const double n = Norm(a);
  return { a[0] / n, a[1] / n, a[2] / n };
}

} // namespace point3
} // namespace msynth
