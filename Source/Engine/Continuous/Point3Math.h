// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Small vector helpers on msynth::Point3 shared by the polyhedral sources (internal header).
#include "Core/Index.h"
#include "Formats/PolyhedralExample.h"

#include <cmath>
#include <vector>

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

/**
 * The measure of polygon @p poly (indices into @p points) by a fan from its first corner: in 2D
 * (@p planar, x and y) its area, unsigned; in 3D the signed volume of the cone from the origin
 * (summed over a closed, outward surface: the enclosed volume).
 */
template <typename Index>
double FanMeasure(const std::vector<Point3>& points, const std::vector<Index>& poly, bool planar)
{
  double sum = 0;
  for (std::size_t k = 1; k + 1 < poly.size(); ++k)
  {
    const Point3& a = points[ToIndex(poly[0])];
    const Point3& b = points[ToIndex(poly[k])];
    const Point3& c = points[ToIndex(poly[k + 1])];
    sum += planar ? ((b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0])) / 2
                  : Dot(a, Cross(b, c)) / 6;
  }
  return planar ? std::abs(sum) : sum;
}

} // namespace point3
} // namespace msynth
