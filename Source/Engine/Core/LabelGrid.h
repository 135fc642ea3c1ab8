// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/**
 * @file LabelGrid.h
 * @brief A discrete model (dissertation §3.1): a 3D array of integer labels, one per site.
 *
 * Sites are indexed (x, y, z) with x fastest, the same order as vtkImageData points, so a grid
 * converts to and from image data without reordering. A 2D model has nz = 1.
 */
#include "Core/Index.h"
#include <algorithm>
#include <array>
#include <cstdint>
#include <vector>

namespace msynth
{

using Label = std::int32_t;

/// The index of @p value in @p values (ascending, each value once: a label's index), or -1.
inline int IndexOfLabel(const std::vector<Label>& values, Label value)
{
  const auto it = std::lower_bound(values.begin(), values.end(), value);
  return it != values.end() && *it == value ? static_cast<int>(it - values.begin()) : -1;
}

/// The three axes, and the six axis-aligned unit directions of the adjacency constraint.
enum Axis : int
{
  AxisX = 0,
  AxisY = 1,
  AxisZ = 2
};

class LabelGrid
{
public:
  /// The largest number of sites a grid may hold (2^31): bounds allocations driven by files.
  static constexpr std::int64_t MaxSites = std::int64_t(1) << 31;

  LabelGrid() = default;
  /// A grid of nx × ny × nz sites, every one set to @p fill.
  /// @throw Error when a dimension is < 1 or the site count exceeds MaxSites.
  LabelGrid(std::int64_t nx, std::int64_t ny, std::int64_t nz, Label fill = 0);
  /// A grid taking ownership of @p labels (x fastest). @throw Error when the size mismatches.
  LabelGrid(std::array<std::int64_t, 3> dims, std::vector<Label> labels);

  const std::array<std::int64_t, 3>& Dimensions() const { return this->Dims; }
  std::int64_t Size(int axis) const { return this->Dims[axis]; }
  std::int64_t NumberOfSites() const { return static_cast<std::int64_t>(this->Labels.size()); }
  bool Is2D() const { return this->Dims[2] == 1; }

  std::int64_t Index(std::int64_t x, std::int64_t y, std::int64_t z) const
  {
    return x + this->Dims[0] * (y + this->Dims[1] * z);
  }
  bool Contains(std::int64_t x, std::int64_t y, std::int64_t z) const
  {
    return x >= 0 && y >= 0 && z >= 0 && x < this->Dims[0] && y < this->Dims[1] &&
      z < this->Dims[2];
  }
  Label At(std::int64_t x, std::int64_t y, std::int64_t z) const
  {
    return this->Labels[ToIndex(this->Index(x, y, z))];
  }
  void Set(std::int64_t x, std::int64_t y, std::int64_t z, Label b)
  {
    this->Labels[ToIndex(this->Index(x, y, z))] = b;
  }

  const std::vector<Label>& Data() const { return this->Labels; }
  std::vector<Label>& Data() { return this->Labels; }

  bool operator==(const LabelGrid& other) const
  {
    return this->Dims == other.Dims && this->Labels == other.Labels;
  }
  bool operator!=(const LabelGrid& other) const { return !(*this == other); }

  /// Checks dimensions before allocating: @throw Error naming the problem.
  static void CheckDimensions(std::int64_t nx, std::int64_t ny, std::int64_t nz);

private:
  std::array<std::int64_t, 3> Dims{ { 0, 0, 0 } };
  std::vector<Label> Labels;
};

} // namespace msynth
