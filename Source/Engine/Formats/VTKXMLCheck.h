// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/**
 * @file VTKXMLCheck.h
 * @brief Checks a VTK XML file (.vti, .vtp) before VTK's reader sees it, for what that reader
 * trusts: array types, the headers of binary and compressed data (block counts and sizes
 * against the bytes present, sizes against the arrays' tuples), and the number of strings in
 * string arrays. VTK's reader crashes on such files (an unknown type in field data, a string
 * array holding more strings than it declares, a compressed header with a zero block size);
 * after this check they are errors naming the file.
 *
 * Encodings: ascii, inline binary (base64) and appended data (raw or base64); header types
 * UInt32 and UInt64; both byte orders; data uncompressed or compressed with zlib, LZ4 or LZMA
 * (decompressed only to count the strings of string arrays).
 */
#include <string>

namespace msynth
{

/// @throw Error "'path': ..." naming the array and the problem.
void CheckVTKXMLFile(const std::string& path);

} // namespace msynth
