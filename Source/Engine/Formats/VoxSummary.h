// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/**
 * @file VoxSummary.h
 * @brief What a MagicaVoxel file (.vox) holds, read without building its voxels: its models,
 * their sizes and voxel counts, where its scene places them, and the palette entries its voxels
 * use (for `msynth info`). Every length and count is checked against the bytes that remain, so
 * memory stays within the file's size.
 */
#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace msynth
{

struct VoxModelSummary
{
  std::array<std::int64_t, 3> Size{ { 0, 0, 0 } };
  std::int64_t Voxels = 0;
  /// Where the scene puts the model's centre (translations summed from the root), if it does.
  std::array<std::int64_t, 3> Translation{ { 0, 0, 0 } };
  bool Placed = false;
};

struct VoxSummary
{
  std::int64_t Version = 0;
  std::vector<VoxModelSummary> Models;
  bool HasPalette = false; ///< an RGBA chunk (else MagicaVoxel's default palette)
  std::vector<std::array<std::uint8_t, 4>> Palette; ///< RGBA of indices 0..255 (file's or default)
  std::array<std::int64_t, 256> Uses{};             ///< voxels of each palette index
  std::int64_t SceneNodes = 0;                      ///< nTRN, nGRP and nSHP chunks
};

/// The summary of the .vox held in @p bytes; @p name names it in messages.
/// @throw Error naming @p name and the problem.
VoxSummary SummarizeVox(const std::vector<std::uint8_t>& bytes, const std::string& name);
/// SummarizeVox of the file @p path (at most 256 MiB). @throw Error naming the file.
VoxSummary ReadVoxSummary(const std::string& path);

} // namespace msynth
