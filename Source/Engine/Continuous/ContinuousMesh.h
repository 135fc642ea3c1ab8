// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/**
 * @file ContinuousMesh.h
 * @brief Mesh extraction from a labelled plane arrangement (dissertation §4.5.8) and the
 * independent check of a synthesized model (Eq. 4.1).
 *
 * 3D: every face of the arrangement across which the object type changes becomes one convex
 * polygon. Faces are traced around their boundary in the arrangement (the next edge at each
 * vertex is the previous one in counter-clockwise order within the face's plane), so polygons
 * keep every arrangement vertex on their boundary (some are straight-angle corners) and
 * neighbouring polygons share whole edges: the mesh is closed and has no T-junctions.
 * Coplanar neighbours are not merged. The normal points from InsideType to OutsideType; the
 * inside is the non-empty side, or the smaller type between two objects. So the surface of type t
 * is the polygons with InsideType t plus, reversed, those with OutsideType t: closed and
 * consistently oriented per type.
 *
 * 2D: the faces of the line arrangement with a non-empty type, as counter-clockwise polygons
 * (InsideType = the face's type; OutsideType is empty).
 */
#include "Continuous/PlaneArrangement.h"
#include "Continuous/PolyhedralAnalysis.h"
#include "Core/LabelGrid.h"

#include <map>
#include <string>

namespace msynth
{

struct ContinuousMesh
{
  bool Planar = false;
  std::vector<Point3> Points;
  std::vector<std::int64_t> PointVertex; ///< the arrangement vertex of each point
  std::vector<std::vector<std::int32_t>> Polygons;
  std::vector<std::int32_t> InsideType;
  std::vector<std::int32_t> OutsideType; ///< 3D only
};

/**
 * The mesh of @p labels, its faces traced on @p threads threads (0: one per core); the mesh is
 * the same for any thread count. @throw Error when @p labels do not fit the arrangement (a face
 * would leave the box).
 */
ContinuousMesh ExtractMesh(const PolyhedralAnalysis& analysis, const PlaneArrangement& arrangement,
  const std::vector<std::int32_t>& labels, unsigned threads = 0);

/// A polygon of ExtractMesh's mesh, as FaceMeasures gives it.
struct MeshFace
{
  std::int64_t Corner = 0; ///< the arrangement vertex of its first corner
  std::int32_t Inside = 0;
  std::int32_t Outside = 0; ///< 3D only (0 in 2D)
  /// Its term of the divergence theorem: the signed volume of the cone from
  /// arrangement.Position(0) over it (3D), or its signed area (2D).
  double Measure = 0;
};

/**
 * ExtractMesh's polygons, in its order, without building the mesh: what volumes per part need
 * (KeepProportionateParts). The measures are computed on @p threads threads as ExtractMesh would
 * give them; summed in this order they are the same for any thread count.
 */
std::vector<MeshFace> FaceMeasures(const PolyhedralAnalysis& analysis,
  const PlaneArrangement& arrangement, const std::vector<std::int32_t>& labels, unsigned threads);

/**
 * Each object type's closed surface: in 3D the polygons with InsideType t as they are and those
 * with OutsideType t reversed; in 2D the faces of type t. Empty space (type 0) is left out.
 */
std::map<int, std::vector<std::vector<std::int32_t>>> SurfacesByType(const ContinuousMesh& mesh);

/// Each solid object type's volume (area in 2D) enclosed by its surfaces (divergence theorem).
std::map<int, double> TypeVolumes(const ContinuousMesh& mesh);

/**
 * The mesh as a polyhedral model: per object type, its closed surfaces (connected components)
 * as objects, type names from @p typeNames.
 */
PolyhedralExample MeshToModel(
  const ContinuousMesh& mesh, const std::map<int, std::string>& typeNames);

/**
 * The object type at the centre of every voxel of a grid (x fastest; 0 = empty): a label volume
 * of the model, e.g. for OpenVDB export. Voxel (i, j, k) is centred at origin + (i + ½, j + ½,
 * k + ½)·voxel, nudged by a fixed fraction of a voxel off the arrangement's planes. Planar meshes
 * give one layer at z = 0. @throw Error when @p dims hold more than LabelGrid::MaxSites sites.
 */
LabelGrid VoxelizeModel(const ContinuousMesh& mesh, const Point3& origin, double voxel,
  const std::array<std::int64_t, 3>& dims);

/**
 * VoxelizeModel with each voxel sampled twice, its centre nudged by that fraction of a voxel one
 * way and the other: where the two disagree (the centre on a face, or within the nudge of one:
 * sloped planes of an arrangement pass through the centres of voxels aligned with its planes),
 * voxels of even x + y + z take the first and odd ones the second, so such ties fall on either
 * side alike instead of all on one, and the voxels of a type add up to its volume without that
 * bias (the README's houses at half-spacing voxels: roofs 12 % short with one sample). Twice
 * VoxelizeModel's classifications. @throw Error as VoxelizeModel.
 */
LabelGrid VoxelizeModelEvenly(const ContinuousMesh& mesh, const Point3& origin, double voxel,
  const std::array<std::int64_t, 3>& dims);

/**
 * The voxel of a 3D model's level sets, in proportion to the model: a quarter of @p spacing (the
 * smallest plane spacing) or 1/256 of @p extent, whichever is coarser, and coarser still where
 * the narrow bands (2 · @p halfWidth voxels across every solid type's surface, estimated from
 * the surfaces' area) would hold more than @p budget voxels: a level set's cost is its band's
 * voxels, so a large model gets coarser voxels instead of a longer export.
 */
double LevelSetVoxel(
  const ContinuousMesh& mesh, double spacing, double extent, double halfWidth, double budget);

/// Rebuilds a mesh from polygons and their types (e.g. read back from model.vtp).
ContinuousMesh MeshFromPolygons(bool planar, std::vector<Point3> points,
  std::vector<std::vector<std::int32_t>> polygons, std::vector<std::int32_t> insideType,
  std::vector<std::int32_t> outsideType);

struct ContinuousModelReport
{
  bool Valid = false;
  std::string Problem;    ///< empty when valid
  int DistinctLabels = 0; ///< distinct neighbourhoods found on the model
  std::int64_t SampledFeatures = 0;
  int Objects = 0;
  /// The narrowest face, edge or gap (FeatureWidth.h), up to the smallest spacing.
  double SmallestFeature = 0;
  double SmallestSpacing = 0; ///< as given (0: unknown, features not held to the fraction)
};

/**
 * Checks a synthesized mesh without trusting the solver: the mesh must be a valid closed,
 * outward-oriented polyhedral model (the example validation), and the example analysis run on
 * it must find only neighbourhoods that are labels of @p example (vertices, edge pieces, faces).
 * With @p smallestSpacing > 0 (the arrangement's smallest plane spacing), no face, edge or gap
 * may be narrower than MinimumFeatureFraction of it (SmallestFeature, measured on the polygons).
 */
ContinuousModelReport CheckContinuousModel(const PolyhedralAnalysis& example,
  const ContinuousMesh& mesh, const std::map<int, std::string>& typeNames,
  double smallestSpacing = 0);

} // namespace msynth
