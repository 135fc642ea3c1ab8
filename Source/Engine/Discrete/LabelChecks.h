// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/**
 * @file LabelChecks.h
 * @brief The independent checks of a model's pinned sites, label counts and connected network
 * (`msynth check --fixed --count --connected --path`, vtkMSCheckModel's PinsFile, Counts,
 * Connected and Path): the pins compared site by site, the sites counted and the components
 * found by a union-find of their own over the written labels, sharing no code with the solver's
 * pins (PinnedSites.cxx), counts (LabelCounts.h) or repairs (Connectivity.h). Labels are values,
 * or with a tileset a tile's name (all its labels) or a label's name ("tile k").
 */
#include "Core/LabelGrid.h"

#include <array>
#include <string>
#include <vector>

namespace msynth
{
struct Tileset;

/// One count entry "L:MIN:MAX" as the model holds it.
struct CountCheck
{
  std::string Name;
  long long Minimum = 0;
  long long Maximum = 0;
  long long Achieved = 0; ///< sites holding the entry's labels
  bool Kept() const { return this->Achieved >= this->Minimum && this->Achieved <= this->Maximum; }
  /// "count kept: NAME holds N sites (wanted MIN to MAX)", or "count missed: ...".
  std::string Describe() const;
};

/**
 * The counts of @p counts ("L:MIN:MAX,...") in @p model; names resolved in @p names (an empty
 * tileset: values only), named @p source in messages. An entry "region=R:L:MIN:MAX" counts only
 * the sites whose @p regions value (one per site, x fastest: a guide's Region array stretched
 * over the model) is R; its name reads "L in guide region R".
 * @throw Error for an entry that is neither a label value nor a name, or a region entry
 * without @p regions.
 */
std::vector<CountCheck> CheckLabelCounts(const LabelGrid& model, const std::string& counts,
  const Tileset& names, const std::string& source, const std::vector<long long>* regions = nullptr);

/// The pinned sites of a grid of pins as the model holds them.
struct PinsCheck
{
  long long Pinned = 0; ///< sites the pins fix
  long long Missed = 0; ///< of those, sites whose label differs
  std::string First;    ///< the first missed: "(x, y, z) holds A, pinned to B"
  bool Kept() const { return this->Missed == 0; }
  /// "pins kept: N pinned sites hold their labels", or "pins missed: ...".
  std::string Describe() const;
};

/**
 * Whether @p model holds the labels of @p pins: a grid of the model's size, or smaller and
 * placed with its first site at @p origin (x, y, z); FreeSite (-1) is free, and so is 0 with
 * @p emptyFree (`--fixed-empty-free`).
 * @throw Error when @p pins does not fit in the model there.
 */
PinsCheck CheckPinnedLabels(const LabelGrid& model, const LabelGrid& pins,
  const std::array<long long, 3>& origin, bool emptyFree);

/// A connected network "LABELS[:N]" and its path as the model holds them.
struct NetworkCheck
{
  std::string Labels;    ///< LABELS as written
  long long Maximum = 1; ///< N
  long long Components = 0;
  /// LABELS:open, a region of a world: every component must reach the model's border (a
  /// window's border: the world goes on beyond it); Closed counts those that do not.
  bool Open = false;
  long long Closed = 0;
  bool HasPath = false;
  bool PathJoined = true;
  long long PathSites = 0;      ///< sites of the path (listed and those of its labels)
  long long PathComponents = 0; ///< components holding them
  std::string PathLine;         ///< "path joined: ..." or "path not joined: ..."
  bool Kept() const
  {
    return (this->Open ? this->Closed == 0 : this->Components <= this->Maximum) && this->PathJoined;
  }
  /// "connected: LABELS form C components (wanted at most N)", or "not connected: ...".
  std::string Describe() const;
};

/**
 * The components of the network @p spec ("LABELS[:N]", N 1 when left out, or "LABELS:open")
 * in @p model: face
 * neighbours joined through the sides @p names' `connects` give (every side for a label without
 * them); with @p path (items "x,y[,z]" or labels), whether those sites and every site of those
 * labels hold network labels and lie in one component.
 * @throw Error for a label that is neither a value nor a name, a bad N, a path site outside.
 */
NetworkCheck CheckLabelNetwork(const LabelGrid& model, const std::string& spec,
  const std::vector<std::string>& path, const Tileset& names, const std::string& source);

} // namespace msynth
