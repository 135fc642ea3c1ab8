// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/**
 * @file VDBLayout.h
 * @brief The byte layout of an OpenVDB file checked before the library reads it (no OpenVDB
 * header): OpenVDB allocates every string and metadata value at the length the file states, and
 * reserves room for as many grids as the file claims, before it reads a byte of them (a name
 * field claiming 1.7 GB was allocated and filled). This walk reads the header, the file's
 * metadata, and each grid's descriptor, compression flags, metadata and transform name, and
 * checks every length and count against the bytes left in the file and every grid offset
 * against the file's size.
 */
#include <string>

namespace msynth
{
namespace vdb
{

/// Throws msynth::Error naming @p path when a length, count or offset in its layout is out of
/// range. Files of format versions this walk does not know (before 212) are left to OpenVDB.
void CheckLayout(const std::string& path);

} // namespace vdb
} // namespace msynth
