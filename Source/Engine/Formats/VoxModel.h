// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/**
 * @file VoxModel.h
 * @brief MagicaVoxel .vox files as label grids: the palette index of a voxel is its label and
 * empty space is label 0. The first model of the file is read (files may hold several).
 *
 * Format: "VOX " and a version, then a MAIN chunk whose children are SIZE (x, y, z), XYZI
 * (count, then x, y, z, index bytes per voxel), optionally PACK, RGBA (the palette) and scene
 * chunks, which are skipped. Every chunk length and count is checked against the bytes that
 * remain, so a corrupt file is an error, never an over-read or a huge allocation.
 */
#include "Core/LabelGrid.h"

#include <array>
#include <cstdint>
#include <ostream>
#include <string>
#include <vector>

namespace msynth
{

struct VoxModel
{
  LabelGrid Grid; ///< labels 0..255, 0 = empty
  /// RGBA of palette indices 0..255 (the file's palette, or MagicaVoxel's default if absent).
  std::vector<std::array<std::uint8_t, 4>> Palette;
  int NumberOfModels = 1; ///< how many models the file holds (only the first is read)
};

/// Parses a .vox file held in memory; @p name is used in messages. A model of more than
/// @p maxSites sites is refused before it is allocated. @throw Error.
VoxModel ReadVoxModel(
  const std::vector<std::uint8_t>& bytes, const std::string& name, std::int64_t maxSites);
/// Reads the file @p path (at most 256 MiB). @throw Error naming the file and the problem.
VoxModel ReadVoxModelFile(const std::string& path, std::int64_t maxSites);

/**
 * Writes @p model as MagicaVoxel writes a one-model file (version 150: MAIN with SIZE, XYZI and,
 * when the palette has 256 entries, RGBA; label 0 is empty). MagicaVoxel models are at most 256
 * voxels a side and hold palette indices 1..255. @throw Error naming @p name otherwise.
 */
void WriteVoxModel(std::ostream& out, const VoxModel& model, const std::string& name);
/// WriteVoxModel into @p path, atomically. @throw Error naming the file.
void WriteVoxModelFile(const std::string& path, const VoxModel& model);

/**
 * Writes @p model of any size (up to 256 x 2048 voxels a side) as MagicaVoxel's scene: pieces of
 * at most 256 voxels a side, each a model placed by its own transform node (nTRN `_t`, the
 * piece's centre: its lowest corner plus half its size, rounded down) under one group node.
 */
void WriteVoxScene(std::ostream& out, const VoxModel& model, const std::string& name);
void WriteVoxSceneFile(const std::string& path, const VoxModel& model);
/**
 * Every model of a file placed as its scene places it (translations summed along the node path
 * from the root; a file without a scene: every model at the origin), composed into one grid from
 * the lowest corner of the models; later models overwrite earlier ones. Rotated models are an
 * error. @throw Error naming the file and the problem; a composed model of more than
 * @p maxSites sites, or of more than 2^24 sites that its models' boxes fill less than 1/64 of
 * (models far apart), is refused before allocation.
 */
VoxModel ReadVoxScene(
  const std::vector<std::uint8_t>& bytes, const std::string& name, std::int64_t maxSites);
VoxModel ReadVoxSceneFile(const std::string& path, std::int64_t maxSites);

} // namespace msynth
