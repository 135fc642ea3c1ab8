// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/**
 * @file vtkMSLabelCounts.h
 * @brief Label counts (msynth::SynthesisOptions::Counts) for vtkMSDiscreteSynthesis (internal,
 * not wrapped): the `Counts` property's text read into the engine's counts, a tileset's names
 * resolved, and the counts of a result as field data.
 */
#include "Discrete/DiscreteSynthesis.h"

#include <string>
#include <vector>

class vtkFieldData;

namespace msynth
{
struct Tileset;
}

namespace vtkMSLabelCounts
{
/**
 * The counts of @p text ("L:MIN:MAX,..."): L is a label value, or with @p tiles a tile's name
 * (all its orientations or images) or a label's name ("tile k").
 * @throw msynth::Error naming the entry that is not one.
 */
std::vector<msynth::LabelCount> Read(const std::string& text, const msynth::Tileset* tiles);

/// Field arrays `CountNames` (string), `CountMinimum`, `CountMaximum`, `CountAchieved` (one
/// tuple per count); none without counts.
void AddFields(vtkFieldData* fd, const std::vector<msynth::LabelCountResult>& counts);
}
