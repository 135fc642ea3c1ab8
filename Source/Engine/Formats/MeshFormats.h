// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/**
 * @file MeshFormats.h
 * @brief Polyhedral examples from PLY and STL files, read here rather than by VTK's readers:
 * every count a file declares is checked against the bytes it holds before anything is
 * allocated, every index against the points, so a malformed file is an error naming the file
 * and the problem, never a crash or an allocation the file did not pay for.
 *
 * - PLY (ascii, binary_little_endian, binary_big_endian 1.0): element `vertex` with properties
 *   x, y, z of any scalar type, element `face` with the list `vertex_indices` (or
 *   `vertex_index`); other elements and properties are read and skipped.
 * - STL (binary, or ascii `solid ... facet ... outer loop ... vertex x y z ... endloop`):
 *   equal coordinates are merged into one point, as STL repeats each vertex per triangle.
 *
 * Faces have no object type (type 1); objects are their connected components.
 */
#include "Formats/PolyhedralExample.h"

#include <string>

namespace msynth
{

/// @throw Error naming @p path and the problem.
PolyhedralExample ReadPLYExample(const std::string& path);
/// @throw Error naming @p path and the problem.
PolyhedralExample ReadSTLExample(const std::string& path);

} // namespace msynth
