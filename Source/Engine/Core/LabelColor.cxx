// SPDX-License-Identifier: BSD-3-Clause
#include "Core/LabelColor.h"

#include <cmath>

namespace msynth
{
namespace
{
// Labels 1-12, as render-model.py's COLOURS + MORE (the plugin's colour map, made of these, is
// tested against that script by Testing/ParaView/pvbatch_pipeline.py).
constexpr double Palette[][3] = { { 0.80, 0.70, 0.50 }, { 0.65, 0.20, 0.12 }, { 0.35, 0.50, 0.75 },
  { 0.35, 0.65, 0.35 }, { 0.45, 0.45, 0.45 }, { 0.90, 0.60, 0.20 }, { 0.55, 0.35, 0.70 },
  { 0.20, 0.60, 0.60 }, { 0.85, 0.45, 0.55 }, { 0.60, 0.55, 0.30 }, { 0.30, 0.30, 0.55 },
  { 0.75, 0.75, 0.40 } };
constexpr int PaletteSize = static_cast<int>(sizeof(Palette) / sizeof(Palette[0]));
} // namespace

std::array<double, 3> LabelColor(int label)
{
  if (label <= PaletteSize)
  {
    const double* c = Palette[((label - 1) % PaletteSize + PaletteSize) % PaletteSize];
    return { c[0], c[1], c[2] };
  }
  // Steps 1/phi, 1/rho and 1/rho^2 (rho the plastic number); HSV to RGB as Python's colorsys.
  const double n = label - PaletteSize - 1;
  const double h = std::fmod(0.07 + n * 0.6180339887498949, 1.0);
  const double s = 0.35 + 0.5 * std::fmod(0.5 + n * 0.7548776662466927, 1.0);
  const double v = 0.55 + 0.4 * std::fmod(0.5 + n * 0.5698402909980532, 1.0);
  const int sector = static_cast<int>(h * 6.0);
  const double f = h * 6.0 - sector;
  const double p = v * (1.0 - s), q = v * (1.0 - s * f), t = v * (1.0 - s * (1.0 - f));
  const double table[6][3] = { { v, t, p }, { q, v, p }, { p, v, t }, { p, q, v }, { t, p, v },
    { v, p, q } };
  const double* c = table[sector % 6];
  return { c[0], c[1], c[2] };
}
} // namespace msynth
