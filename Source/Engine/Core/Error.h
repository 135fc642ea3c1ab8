// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/**
 * @file Error.h
 * @brief The engine's one exception type. Library code never exits the process: it throws
 * msynth::Error with context (file, site, label) and the VTK layer turns it into vtkErrorMacro.
 */
#include <stdexcept>
#include <string>

namespace msynth
{

/// @p text with control characters and bytes that are no valid UTF-8 (from a damaged file, say)
/// shown as '?': messages are one line of valid UTF-8 and never carry terminal escapes.
std::string Printable(const std::string& text);

class Error : public std::runtime_error
{
public:
  /// The message is made Printable.
  explicit Error(const std::string& what);
  /// An error about a file: the message starts with the file's name.
  static Error InFile(const std::string& path, const std::string& problem);
};

} // namespace msynth
