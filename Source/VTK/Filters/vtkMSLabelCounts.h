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
 * (all its orientations or images) or a label's name ("tile k"); "region=R:L:MIN:MAX" counts
 * only the sites of the guide's region R (LabelCount::Region).
 * @throw msynth::Error naming the entry that is not one.
 */
std::vector<msynth::LabelCount> Read(const std::string& text, const msynth::Tileset* tiles);

/**
 * The connected network of @p text ("LABELS[:N]": labels or, with @p tiles, tile or label names,
 * separated by commas; N the most components, 1 when left out); inactive for "". A tileset's
 * `connects` sides become the labels' Sides. @p path ("A;B;...") lists the path: each item a
 * site "x,y[,z]" or a label (value or name: every site holding it).
 * @throw msynth::Error naming the entry that is not a label or site.
 */
msynth::ConnectedNetwork ReadConnected(
  const std::string& text, const msynth::Tileset* tiles, const std::string& path = "");

/// Field arrays `ConnectedLabels` (string), `ConnectedMaximum`, `ConnectedComponents`,
/// `ConnectedBefore`, `ConnectedRepairs`, `ConnectedRedone` (one tuple); none without a network.
void AddConnectedFields(vtkFieldData* fd, const msynth::ConnectedResult& connected);

/// Field arrays `CountNames` (string), `CountMinimum`, `CountMaximum`, `CountAchieved`,
/// `CountRegion` (-1: the whole model; one tuple per count); none without counts.
void AddFields(vtkFieldData* fd, const std::vector<msynth::LabelCountResult>& counts);
}
