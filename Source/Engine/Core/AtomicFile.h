// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/**
 * @file AtomicFile.h
 * @brief Writing a file so that it is complete or absent: the content goes to a temporary file
 * in the same folder, which replaces the target by rename(2) only after a successful write.
 */
#include <functional>
#include <ostream>
#include <string>

namespace msynth
{

/// @throw Error naming @p path when it exists and is not a regular file (a folder, a device
/// such as /dev/null, a FIFO, a socket; a link is followed): renaming a file over it would
/// replace it, so nothing is written there.
void CheckReplaceable(const std::string& path);

/// A temporary file name beside @p path, unique within this process (CheckReplaceable first).
std::string TemporaryPathBeside(const std::string& path);

/**
 * @brief Calls @p write with a stream to a temporary file, then renames it over @p path.
 * @throw Error naming @p path when the folder is not writable or a write fails; any exception
 * from @p write propagates after the temporary file is removed. @p path is untouched on failure.
 */
void WriteFileAtomically(const std::string& path, const std::function<void(std::ostream&)>& write);

/// Renames @p temporary over @p path; removes @p temporary and throws Error on failure (also
/// when @p path is not replaceable).
void CommitTemporaryFile(const std::string& temporary, const std::string& path);

} // namespace msynth
