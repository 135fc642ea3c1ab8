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

#include "Core/LabelColor.h" // the palette of render-model.py, shared with mesh.glb

#include <iomanip>
#include <sstream>
#include <string>

namespace
{
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
    const auto rgb = msynth::LabelColor(label);
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
