// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/**
 * @file LabelColor.h
 * @brief The colour of each label, as every picture of the project shows it: the palette of
 * Utilities/render-model.py (label_colour), the ParaView plugin's Label colour map and the
 * materials of mesh.glb.
 */
#include <array>

namespace msynth
{
/**
 * @brief The display (sRGB) colour of @p label, components in [0, 1]: labels 1–12 have the
 * gallery's palette (label 1 sand, 2 brick red, ...; labels 0 and below take them in turn, label
 * 0 has label 12's); label 13 + n the hue 0.07 + n / phi (a golden-ratio turn apart), saturation
 * and value from the R2 low-discrepancy sequence, so no two labels share a colour.
 */
std::array<double, 3> LabelColor(int label);
} // namespace msynth
