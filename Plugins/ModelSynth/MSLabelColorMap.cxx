// SPDX-License-Identifier: BSD-3-Clause
// The default colour map of arrays named Label, registered when the plugin loads: categorical
// (each label its own colour, the legend listing the labels present), so a label grid or its
// voxel surface shows as distinct parts on Apply instead of a smooth blend of neighbouring labels.
// Only the labels shown are active (ParaView colours the others in the NaN colour and leaves them
// out of the legend); the active set grows at every time step, so the labels a catalog snapshot
// or a later frame adds get their colours too.
//
// ParaView makes one colour map per array name and takes its defaults from vtkSMSettings at
// ".array_lookup_tables.<array>.PVLookupTable.<property>". The plugin adds them as the
// lowest-priority collection, so a default the user saves for Label (Color Map Editor, "Save
// current colormap as default for Label") still wins.
#include "vtkSMSettings.h"

#include <cmath>
#include <iomanip>
#include <sstream>
#include <string>

namespace
{
// The palette of Utilities/render-model.py (gallery and README pictures): labels 1-12 have these
// colours, so label 1 (walls, buildings) is sand and label 2 (roofs) brick red (label 0 has
// label 12's); labels from 13 each a colour of their own (LabelColor). Tested against that
// script by Testing/ParaView/pvbatch_pipeline.py.
constexpr double Palette[][3] = { { 0.80, 0.70, 0.50 }, { 0.65, 0.20, 0.12 }, { 0.35, 0.50, 0.75 },
  { 0.35, 0.65, 0.35 }, { 0.45, 0.45, 0.45 }, { 0.90, 0.60, 0.20 }, { 0.55, 0.35, 0.70 },
  { 0.20, 0.60, 0.60 }, { 0.85, 0.45, 0.55 }, { 0.60, 0.55, 0.30 }, { 0.30, 0.30, 0.55 },
  { 0.75, 0.75, 0.40 } };
constexpr int PaletteSize = static_cast<int>(sizeof(Palette) / sizeof(Palette[0]));

/// The colour of @p label as render-model.py's label_colour gives it: the palette for labels
/// up to 12, then for label 13 + n the hue 0.07 + n / phi (a golden-ratio turn apart), and
/// saturation and value from the R2 low-discrepancy sequence (steps 1/rho, 1/rho^2), through
/// the HSV to RGB conversion of Python's colorsys.
void LabelColor(int label, double rgb[3])
{
  if (label <= PaletteSize)
  {
    const double* c = Palette[((label - 1) % PaletteSize + PaletteSize) % PaletteSize];
    rgb[0] = c[0];
    rgb[1] = c[1];
    rgb[2] = c[2];
    return;
  }
  const double n = label - PaletteSize - 1;
  const double h = std::fmod(0.07 + n * 0.6180339887498949, 1.0);
  const double s = 0.35 + 0.5 * std::fmod(0.5 + n * 0.7548776662466927, 1.0);
  const double v = 0.55 + 0.4 * std::fmod(0.5 + n * 0.5698402909980532, 1.0);
  const int sector = static_cast<int>(h * 6.0);
  const double f = h * 6.0 - sector;
  const double p = v * (1.0 - s), q = v * (1.0 - s * f), t = v * (1.0 - s * (1.0 - f));
  const double table[6][3] = { { v, t, p }, { q, v, p }, { p, v, t }, { p, q, v }, { t, p, v },
    { v, p, q } };
  for (int i = 0; i < 3; ++i)
    rgb[i] = table[sector % 6][i];
}

// Labels 0..LabelCount-1 are annotated (ParaView colours only annotated values of a categorical
// map); larger labels show in the NaN colour.
constexpr int LabelCount = 1024;

std::string LabelColorMapSettings()
{
  std::ostringstream annotations;
  std::ostringstream colors;
  colors << std::setprecision(6);
  for (int label = 0; label < LabelCount; ++label)
  {
    const char* separator = label ? ", " : "";
    annotations << separator << '"' << label << "\", \"" << label << '"';
    double rgb[3];
    LabelColor(label, rgb);
    colors << separator << rgb[0] << ", " << rgb[1] << ", " << rgb[2];
  }
  std::ostringstream json;
  json
    << "{ \"array_lookup_tables\": { \"Label\": { \"PVLookupTable\": {"
    << " \"IndexedLookup\": 1, \"ShowIndexedColorActiveValues\": 1, \"AnnotationsInitialized\": 1,"
    << " \"AutomaticRescaleRangeMode\": \"Grow and update every timestep\","
    << " \"Annotations\": [" << annotations.str() << "], \"IndexedColors\": [" << colors.str()
    << "] } } } }";
  return json.str();
}

struct RegisterLabelColorMap
{
  RegisterLabelColorMap()
  {
    vtkSMSettings::GetInstance()->AddCollectionFromString(LabelColorMapSettings(), 0.0);
  }
};
const RegisterLabelColorMap registerLabelColorMap;
}
