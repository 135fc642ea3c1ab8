// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/**
 * @file TextLists.h
 * @brief The one parser of the short lists that options and properties hold: pieces between
 * separators, strict integers, label maps "a:b,c:d" (symmetry maps, mirror swaps) and label
 * values "label:number" (soft constraints' target fractions). The command line, the filters and
 * the engine all read them here, so they accept and refuse the same texts.
 */
#include "Core/LabelGrid.h"

#include <map>
#include <string>
#include <vector>

namespace msynth
{

/// The pieces of @p text between @p separator characters, empty ones kept ("" is one empty
/// piece); with @p dropSpaces, spaces are removed from each piece.
std::vector<std::string> SplitText(
  const std::string& text, char separator, bool dropSpaces = false);

/// An integer (an optional '-' and at most 18 decimal digits, nothing else) within
/// [@p low, @p high] into @p value; false otherwise.
bool ParseInteger(const std::string& text, long long low, long long high, long long& value);

/**
 * A label map "a:b,c:d": pairs of integer labels separated by commas, semicolons or spaces;
 * @p both: each pair maps both ways (a swap). An empty text is an empty map.
 * @throw Error "@p what: 'x' is not a pair 'a:b' of labels"
 */
std::map<Label, Label> ParseLabelPairs(const std::string& text, bool both, const std::string& what);

/**
 * Label values "a:x,b:y": an integer label and a finite number each, separated as in
 * ParseLabelPairs.
 * @throw Error "@p what: 'x' is not 'label:@p value'"
 */
std::map<Label, double> ParseLabelValues(
  const std::string& text, const std::string& what, const std::string& value = "number");

/// One entry "NAME:MIN:MAX" of a count list.
struct CountEntry
{
  std::string Name; ///< a label value or a name, as written (spaces around it dropped)
  long long Minimum = 0;
  long long Maximum = 0;
};

/**
 * Label counts "a:min:max,b:min:max" (entries separated by commas or semicolons; a a label
 * value or a name, min and max integers with 0 <= min <= max).
 * @throw Error "@p what: 'x' is not 'label:min:max' ..."
 */
std::vector<CountEntry> ParseCountEntries(const std::string& text, const std::string& what);

} // namespace msynth
