// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/**
 * @file TextModel.h
 * @brief The text format of the original model-synthesis program:
 *
 *     <three free-text header lines>
 *     X Y Z
 *     <Z slices, separated by blank lines; each slice is X rows of Y integers,
 *      so values are read for z, for x, for y>
 *     [<Objects>
 *      <label number>
 *      $<piece name>          (one or more lines starting with '$')
 *      #
 *      ... repeated per label]
 *
 * Errors name the file and line. Dimensions are checked against a site limit before anything
 * is allocated.
 */
#include "msynth/LabelGrid.h"

#include <array>
#include <istream>
#include <map>
#include <ostream>
#include <string>
#include <vector>

namespace msynth
{

struct TextModel
{
  std::array<std::string, 3> Header;
  LabelGrid Grid;
  /// Piece names per label from the optional <Objects> section (without the '$').
  std::map<Label, std::vector<std::string>> Pieces;
};

/// Parses @p in; @p name is used in error messages. @throw Error "'name', line N: problem".
TextModel ReadTextModel(std::istream& in, const std::string& name, std::int64_t maxSites);
/// Reads the file @p path. @throw Error naming the file.
TextModel ReadTextModelFile(const std::string& path, std::int64_t maxSites);
/// Writes @p model in the same format (what ReadTextModel reads back identically).
void WriteTextModel(std::ostream& out, const TextModel& model);

} // namespace msynth
