// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// A uniform grid over axis-aligned boxes (internal header): which boxes may contain a point,
// in ascending box order, without scanning them all. About one cell per box, at most 128 cells
// along an axis.
#include "Core/Index.h"
#include "Formats/PolyhedralExample.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

namespace msynth
{

class BoxGrid
{
public:
  BoxGrid() = default;

  /// @p boxes as (low, high) corners, each grown by @p pad.
  BoxGrid(const std::vector<std::array<Point3, 2>>& boxes, double pad)
  {
    if (boxes.empty())
    {
      return;
    }
    Point3 lo = boxes[0][0], hi = boxes[0][1];
    for (const auto& b : boxes)
    {
      for (int c = 0; c < 3; ++c)
      {
        lo[c] = std::min(lo[c], b[0][c] - pad);
        hi[c] = std::max(hi[c], b[1][c] + pad);
      }
    }
    const double extent = std::max({ hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2], 1e-300 });
    this->Cell = extent / std::clamp(std::cbrt(static_cast<double>(boxes.size())), 1.0, 128.0);
    this->Low = lo;
    for (int c = 0; c < 3; ++c)
    {
      this->Dims[ToIndex(c)] = std::clamp<std::int64_t>(
        static_cast<std::int64_t>((hi[c] - lo[c]) / this->Cell) + 1, 1, 129);
    }
    this->Cells.assign(ToIndex(this->Dims[0] * this->Dims[1] * this->Dims[2]), {});
    for (std::size_t i = 0; i < boxes.size(); ++i)
    {
      std::array<std::int64_t, 3> a{}, b{};
      for (int c = 0; c < 3; ++c)
      {
        a[ToIndex(c)] = this->Clamp(boxes[i][0][c] - pad, c);
        b[ToIndex(c)] = this->Clamp(boxes[i][1][c] + pad, c);
      }
      for (std::int64_t z = a[2]; z <= b[2]; ++z)
      {
        for (std::int64_t y = a[1]; y <= b[1]; ++y)
        {
          for (std::int64_t x = a[0]; x <= b[0]; ++x)
          {
            this->Cells[this->Index(x, y, z)].push_back(static_cast<std::uint32_t>(i));
          }
        }
      }
    }
  }

  /// Boxes whose cell range holds @p p (a superset of the boxes containing it).
  const std::vector<std::uint32_t>& Candidates(const Point3& p) const
  {
    static const std::vector<std::uint32_t> none;
    if (this->Cells.empty())
    {
      return none;
    }
    std::array<std::int64_t, 3> cell{};
    for (int c = 0; c < 3; ++c)
    {
      const double t = std::floor((p[c] - this->Low[c]) / this->Cell);
      if (!(t >= 0 && t < static_cast<double>(this->Dims[ToIndex(c)])))
      {
        return none; // outside every (grown) box
      }
      cell[ToIndex(c)] = static_cast<std::int64_t>(t);
    }
    return this->Cells[this->Index(cell[0], cell[1], cell[2])];
  }

  /// Boxes whose cell range meets the box [@p lo, @p hi], ascending, each once.
  std::vector<std::uint32_t> Overlapping(const Point3& lo, const Point3& hi) const
  {
    std::vector<std::uint32_t> out;
    if (this->Cells.empty())
    {
      return out;
    }
    std::array<std::int64_t, 3> a{}, b{};
    for (int c = 0; c < 3; ++c)
    {
      a[ToIndex(c)] = this->Clamp(lo[c], c);
      b[ToIndex(c)] = this->Clamp(hi[c], c);
    }
    for (std::int64_t z = a[2]; z <= b[2]; ++z)
    {
      for (std::int64_t y = a[1]; y <= b[1]; ++y)
      {
        for (std::int64_t x = a[0]; x <= b[0]; ++x)
        {
          const auto& cell = this->Cells[this->Index(x, y, z)];
          out.insert(out.end(), cell.begin(), cell.end());
        }
      }
    }
    std::sort(out.begin(), out.end());
    out.erase(std::unique(out.begin(), out.end()), out.end());
    return out;
  }

private:
  std::int64_t Clamp(double x, int c) const
  {
    return std::clamp<std::int64_t>(
      static_cast<std::int64_t>(std::floor((x - this->Low[c]) / this->Cell)), 0,
      this->Dims[ToIndex(c)] - 1);
  }
  std::size_t Index(std::int64_t x, std::int64_t y, std::int64_t z) const
  {
    return ToIndex(x + this->Dims[0] * (y + this->Dims[1] * z));
  }

  Point3 Low{};
  double Cell = 1;
  std::array<std::int64_t, 3> Dims{ { 1, 1, 1 } };
  std::vector<std::vector<std::uint32_t>> Cells;
};

} // namespace msynth
