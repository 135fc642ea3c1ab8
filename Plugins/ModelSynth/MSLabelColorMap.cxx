// SPDX-License-Identifier: BSD-3-Clause
// The default colour map of arrays named Label, registered when the plugin loads: categorical
// (each label its own colour, the legend listing the labels present), so a label grid or its
// voxel surface shows as distinct parts on Apply instead of a smooth blend of neighbouring labels.
// Only the labels shown are active (ParaView colours the others in the NaN colour and leaves them
// out of the legend); the active set grows at every time step, so the labels a catalog snapshot
// or a later frame adds get their colours too. ParaView computes the active labels when a
// representation is first shown, not when its data changes: a model applied again with a label
// it lacked before (the ground, once the boundaries are set) showed that label in the NaN colour
// and left it out of the legend. So each time a representation coloured by Label gets new data,
// the active labels are computed again from every visible representation that uses the map.
//
// ParaView makes one colour map per array name and takes its defaults from vtkSMSettings at
// ".array_lookup_tables.<array>.PVLookupTable.<property>". The plugin adds them as the
// lowest-priority collection, so a default the user saves for Label (Color Map Editor, "Save
// current colormap as default for Label") still wins.
#include "vtkCallbackCommand.h"
#include "vtkCommand.h"
#include "vtkNew.h"
#include "vtkSMPropertyHelper.h"
#include "vtkSMProxy.h"
#include "vtkSMProxyManager.h"
#include "vtkSMSessionProxyManager.h"
#include "vtkSMSettings.h"
#include "vtkSMTransferFunctionProxy.h"

#include "Core/LabelColor.h" // the palette of render-model.py, shared with mesh.glb

#include <iomanip>
#include <set>
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

/// A representation got new data: when it is coloured by Label through a categorical map, the
/// map's active labels become those of every visible representation that uses it.
void RepresentationUpdated(vtkObject* caller, unsigned long, void*, void*)
{
  auto* representation = vtkSMProxy::SafeDownCast(caller);
  if (!representation || !representation->GetProperty("ColorArrayName") ||
    !representation->GetProperty("LookupTable"))
    return;
  const char* array =
    vtkSMPropertyHelper(representation, "ColorArrayName").GetInputArrayNameToProcess();
  vtkSMProxy* map = vtkSMPropertyHelper(representation, "LookupTable").GetAsProxy();
  if (!array || std::string(array) != "Label" || !map || !map->GetProperty("IndexedLookup") ||
    vtkSMPropertyHelper(map, "IndexedLookup").GetAsInt() != 1)
    return;
  static bool computing = false; // (gathering the data information may update representations)
  if (computing)
    return;
  computing = true;
  vtkSMTransferFunctionProxy::ComputeAvailableAnnotations(map, false);
  computing = false;
}

/// A proxy registered: representations are watched for new data.
void ProxyRegistered(vtkObject*, unsigned long, void*, void* data)
{
  const auto* info = static_cast<vtkSMProxyManager::RegisteredProxyInformation*>(data);
  if (!info || info->Type != vtkSMProxyManager::RegisteredProxyInformation::PROXY || !info->Proxy ||
    !info->GroupName || std::string(info->GroupName) != "representations")
    return;
  vtkNew<vtkCallbackCommand> updated;
  updated->SetCallback(RepresentationUpdated);
  info->Proxy->AddObserver(vtkCommand::UpdateDataEvent, updated);
}

/// Watches the registrations of @p session (once per session proxy manager).
void WatchSession(vtkSMSessionProxyManager* session)
{
  static std::set<vtkSMSessionProxyManager*> watched;
  if (!session || !watched.insert(session).second)
    return;
  vtkNew<vtkCallbackCommand> registered;
  registered->SetCallback(ProxyRegistered);
  session->AddObserver(vtkCommand::RegisterEvent, registered);
}

void SessionChanged(vtkObject*, unsigned long, void*, void*)
{
  if (vtkSMProxyManager::IsInitialized())
    WatchSession(vtkSMProxyManager::GetProxyManager()->GetActiveSessionProxyManager());
}

struct RegisterLabelColorMap
{
  RegisterLabelColorMap()
  {
    vtkSMSettings::GetInstance()->AddCollectionFromString(LabelColorMapSettings(), 0.0);
    if (!vtkSMProxyManager::IsInitialized())
      return;
    vtkNew<vtkCallbackCommand> changed;
    changed->SetCallback(SessionChanged);
    vtkSMProxyManager::GetProxyManager()->AddObserver(
      vtkSMProxyManager::ActiveSessionChanged, changed);
    SessionChanged(nullptr, 0, nullptr, nullptr);
  }
};
const RegisterLabelColorMap registerLabelColorMap;
}
