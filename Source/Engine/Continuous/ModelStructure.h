// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/**
 * @file ModelStructure.h
 * @brief What a person sees in a 3D polyhedral model, measured on its polygons alone (no plane
 * arrangement, no labels, no solver), and how far a synthesized model is from its example by it.
 *
 * Volume shares can match while the structure does not (a town of small houses and road
 * fragments has its example's shares). So the model is cut into parts: the connected pieces of
 * each object type, on a voxel grid classified by vertical rays through the polygons. Each
 * part has a footprint (the area of its x-y bounding box), a height (its z extent) and a span
 * (its bounding box's longer x-y side); a part fronts a type when its footprint grown by the
 * reach meets a voxel of that type at any height (houses along streets, roofs on walls).
 *
 * Compared with the example, a type resembles it when its median footprint is within 0.5–2× of
 * the example's, and so are its parts per ground area where the example has several parts of it
 * (one object's box says nothing of how far apart copies stand); a network type (its largest
 * example part spans at least half the example's width and covers under half of its box: the
 * streets of a town, not the one house of a house example) when nearly all of its volume is in
 * parts at least half that long (its size and count are the model's, not compared); and fronting
 * holds when a pair the example has for most of its parts holds for most of the model's (at least
 * 0.8 of the example's share).
 */
#include "Formats/PolyhedralExample.h"

#include <array>
#include <cstdint>
#include <map>
#include <string>
#include <vector>

namespace msynth
{

/// A model's object type at voxel centres over its bounding box (x fastest; 0 = empty).
struct TypeVoxels
{
  Point3 Origin{};
  double Voxel = 0;
  std::array<std::int64_t, 3> Dims{};
  std::vector<std::int32_t> Types;
  std::int64_t Index(std::int64_t x, std::int64_t y, std::int64_t z) const
  {
    return x + this->Dims[0] * (y + this->Dims[1] * z);
  }
};

/**
 * @p model's types on voxels of edge @p voxel (coarsened until the box holds at most 2^23),
 * from vertical rays through its non-vertical polygons: a centre is inside a type while more of
 * its faces were entered than left below it (centres and rays nudged off the lattice).
 */
TypeVoxels ClassifyTypes(const PolyhedralExample& model, double voxel);

/// One connected part of one object type.
struct StructurePart
{
  double Footprint = 0; ///< x-y bounding box area
  double Height = 0;    ///< z extent
  double Span = 0;      ///< the bounding box's longer x-y side
  double Volume = 0;
  double Ground = 0;       ///< the area it covers seen from above
  std::vector<int> Fronts; ///< the other types within the reach of its footprint (ascending)
};

struct TypeStructure
{
  int Type = 0;
  std::vector<StructurePart> Parts; ///< largest volume first
  double PartsPer100 = 0;           ///< parts per 100 square units of ground
  double MedianFootprint = 0;
  double MedianHeight = 0;
  double Volume = 0;
  /// The share of its parts that front type t, for every other type t some part fronts.
  std::map<int, double> Fronting;
};

struct ModelStructure
{
  double Voxel = 0;                 ///< the voxel edge the parts were found on
  double Reach = 0;                 ///< how far a footprint is grown to find what it fronts
  double GroundArea = 0;            ///< the x-y area of the model's box
  std::vector<TypeStructure> Types; ///< solid types present, ascending
  const TypeStructure* Find(int type) const;
};

/**
 * The parts of @p model (a 3D polyhedral model: an example, or a synthesized mesh as
 * MeshToModel gives it) on voxels of edge @p voxel (coarsened until the box holds at most
 * 2^23 voxels), their fronting within @p reach. The box is the model's bounding box.
 * @throw Error for a planar model or a non-positive voxel or reach.
 */
ModelStructure MeasureStructure(const PolyhedralExample& model, double voxel, double reach);

/// One line of a comparison: a measure of the model against the example's, and whether it is
/// within bounds.
struct ResemblanceItem
{
  std::string Measure; ///< e.g. "wall: parts per 100 square units"
  double Example = 0;
  double Model = 0;
  std::string Bounds; ///< what passes, in words ("0.5-2x the example")
  bool Passes = false;
};

/**
 * The model's structure against the example's, type by type (names from @p typeNames):
 * parts per ground area (types with three parts or more in the example) and median footprint
 * (0.5–2×), or for a network type its share of volume in network-length parts (≥ 0.9); fronting
 * the example has for at least 0.5 of a type's parts (at least 0.8 of its share). Types the
 * model lacks fail; types the example lacks are not compared.
 */
std::vector<ResemblanceItem> CompareStructure(const ModelStructure& example,
  const ModelStructure& model, const std::map<int, std::string>& typeNames);

/// The default voxel and reach for a model whose smallest plane spacing is @p spacing (0:
/// unknown) and whose example's x-y extent is @p extent: half and twice the spacing (a fortieth
/// and a fifteenth of the extent when the spacing is unknown).
double StructureVoxel(double spacing, double extent);
double StructureReach(double spacing, double extent);

} // namespace msynth
