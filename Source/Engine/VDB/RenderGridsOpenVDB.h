// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/**
 * @file RenderGridsOpenVDB.h
 * @brief Internal to the OpenVDB module (VDBFile.cxx, RenderGrids.cxx): the render grids of a
 * label volume as OpenVDB grids. Includes OpenVDB's headers: include it nowhere else.
 */
#include "VDB/RenderGrids.h"

#include <openvdb/openvdb.h>

namespace msynth
{
namespace vdb
{
namespace detail
{

/// The metadata keys of the dense extent a grid stands for (VDBFile.h).
constexpr const char* IndexMinKey = "msynth_index_min";
constexpr const char* IndexMaxKey = "msynth_index_max";

/**
 * @brief Appends `density`, `color`, `surface` and the `surface_NAME` grids of @p view (see
 * RenderGrids.h) to @p out, each with a copy of @p transform (the label grid's).
 * @throw Error when the view has no labels, or a band narrower than one voxel.
 */
void AppendRenderGrids(
  const LabelRenderView& view, const openvdb::math::Transform& transform, openvdb::GridPtrVec& out);

} // namespace detail
} // namespace vdb
} // namespace msynth
