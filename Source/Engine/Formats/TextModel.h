// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/**
 * @file TextModel.h
 * @brief The text format of the original model-synthesis program (Merrell's `tiledmodel`
 * samples), read as that program reads it:
 *
 *     <three free-text header lines>
 *     X Y Z
 *     <X * Y * Z integers in the order for z, for x, for y, separated by any white space;
 *      the program writes each slice as X rows of Y values followed by a blank line>
 *     <trailer: free text, kept verbatim and written back unchanged>
 *
 * The original examples end with an `<Objects>` trailer that names the modelling scene and,
 * for labels 1, 2, 3, ... in order, the pieces drawn at a site of that label:
 *
 *     <Objects>
 *     3D Studio Scenes\castle.max     the scene (any text)
 *     somethin'                       entry of label 1: one free-text line
 *     $castle9                        zero or more piece names, each starting with '$'
 *     $snow9
 *     #                               end of the entry
 *     1                               entry of label 2 ...
 *     $rock1
 *     #
 *
 * Blank lines between entries are skipped; the last line may lack a newline. A trailer that
 * is not such a section is kept as it is (no pieces); an `<Objects>` section that does not
 * follow this shape is kept too, with ObjectsProblem saying where it departs from it.
 * Errors name the file and line. Dimensions are checked against a site limit before anything
 * is allocated.
 */
#include "Core/LabelGrid.h"

#include <array>
#include <istream>
#include <map>
#include <ostream>
#include <string>
#include <vector>

namespace msynth
{

/// One entry of an `<Objects>` trailer: its free-text line and its piece names (without '$').
struct TextObjectEntry
{
  std::string Text;
  std::vector<std::string> Pieces;
};

struct TextModel
{
  std::array<std::string, 3> Header;
  LabelGrid Grid;
  /// Everything after the last value, from its first non-blank character, verbatim.
  std::string Trailer;
  /// True when the trailer is an `<Objects>` section read as entries.
  bool HasObjects = false;
  std::string Scene;                    ///< the line after `<Objects>`
  std::vector<TextObjectEntry> Objects; ///< entry i describes label i + 1
  /// Piece names per label (labels with at least one piece), from Objects.
  std::map<Label, std::vector<std::string>> Pieces;
  /// Why an `<Objects>` trailer could not be read as entries ("line N: ..."); empty otherwise.
  std::string ObjectsProblem;
};

/// The header lines the original program writes above a generated model (its Blender and
/// 3ds Max loaders look for the third one).
std::array<std::string, 3> GeneratedTextModelHeader();

/// Parses @p in; @p name is used in error messages. @throw Error "'name', line N: problem".
TextModel ReadTextModel(std::istream& in, const std::string& name, std::int64_t maxSites);
/// Reads the file @p path. @throw Error naming the file.
TextModel ReadTextModelFile(const std::string& path, std::int64_t maxSites);
/// Reads a trailer: fills HasObjects, Scene, Objects, Pieces and ObjectsProblem of @p model
/// from @p trailer (stored as model.Trailer). @p firstLine numbers the trailer's first line.
void SetTextModelTrailer(TextModel& model, const std::string& trailer, std::int64_t firstLine = 1);
/// Writes @p model as the original program writes its outputs: the header, "X Y Z", a blank
/// line, each slice as X rows of Y values ("%2d " each) followed by a blank line, then the
/// trailer unchanged. ReadTextModel reads it back identically.
void WriteTextModel(std::ostream& out, const TextModel& model);

} // namespace msynth
