// SPDX-License-Identifier: BSD-3-Clause
#ifndef vtkMSDiscreteSynthesisOptions_h
#define vtkMSDiscreteSynthesisOptions_h
/**
 * @file vtkMSDiscreteSynthesisOptions.h
 * @brief Internal to vtkMSDiscreteSynthesis: the engine's options from the filter's properties
 * and its guide and pinned-sites inputs (errors reported on the filter with vtkErrorMacro).
 */
#include "Discrete/DiscreteSynthesis.h"

class vtkImageData;
class vtkMSDiscreteSynthesis;

namespace vtkMSDiscreteSynthesisOptions
{
/// The engine's options from the filter's sizes and symmetries (shared by RequestInformation,
/// which counts the time steps, and RequestData).
msynth::SynthesisOptions SizeOptions(vtkMSDiscreteSynthesis* self);
/// The engine's options from every property of the filter (and the guide, when connected).
bool BuildOptions(
  vtkMSDiscreteSynthesis* self, vtkImageData* guide, msynth::SynthesisOptions& options);
/// The pinned sites of input port 2 (when connected): its label array, -1 where free.
bool ReadPins(vtkMSDiscreteSynthesis* self, vtkImageData* fixed, msynth::SynthesisOptions& options);
} // namespace vtkMSDiscreteSynthesisOptions

#endif
