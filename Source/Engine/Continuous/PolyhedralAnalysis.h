// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/**
 * @file PolyhedralAnalysis.h
 * @brief Example analysis of continuous model synthesis (dissertation §4.5.1–4.5.5, TVCG
 * §4.2–4.3): the plane families of a polyhedral example, and its catalog of neighbourhood
 * labels, each found by probing the example around sample points of every vertex, edge and
 * face.
 *
 * Plane families (§4.5.1): face normals within AngleTolerance of each other (either sign) form
 * one family. Its exact normal is the first face's outward normal snapped to a small integer
 * direction when one lies within the tolerance ((1, 1, 0), (0, 0, 1), …), otherwise to integers
 * of 24 bits; so every later sign test, intersection and coincidence is exact.
 *
 * Sampling: every vertex; every edge, split wherever features of another object touch it, at
 * the midpoint of each piece (and the split points count as vertices); every face, beside each
 * edge piece (so each region of a face that another object's face partly covers is met); the
 * interior of each object type and the exterior. A probe classifies points at a small distance
 * along each cone's interior direction (exact classification with CGAL, in floating-point
 * positions: the probe distance is 1/100 of the face offset, itself min(10⁻³ × diagonal,
 * 5% of the shortest edge)).
 */
#include "Continuous/Neighbourhood.h"
#include "Formats/PolyhedralExample.h"

#include <cstdint>
#include <map>
#include <memory>

namespace msynth
{

/// An exact integer direction within @p angleTolerance (radians) of @p unit: the one with the
/// smallest components up to @p maxSmallInteger if any, else a 24-bit approximation.
IntVec3 SnapDirection(const Point3& unit, double angleTolerance, int maxSmallInteger = 12);

/// Recomputes neighbourhood labels at points of any polyhedral model whose faces lie in the
/// given plane families: the example's analysis uses it, and so can a verification of a
/// synthesized model (the continuous adjacency constraint, Eq. 4.1, checked directly).
class BoxGrid;

class NeighbourhoodProbe
{
public:
  /// @throw Error when a boundary element's normal is in none of the families.
  NeighbourhoodProbe(const PolyhedralExample& model, const PlaneFamilySet& families,
    const std::vector<Point3>& familyUnitNormals, double angleTolerance);
  ~NeighbourhoodProbe();

  /// The canonical label at @p p.
  NeighbourhoodLabel LabelAt(const Point3& p) const;
  /// The canonical label at @p p given the boundary elements through it (ElementsThrough).
  NeighbourhoodLabel LabelAt(const Point3& p, const std::vector<std::size_t>& elements) const;
  /// The boundary elements through @p p (ascending).
  std::vector<std::size_t> ElementsThrough(const Point3& p) const;
  /// The families of the boundary elements through @p p (sorted).
  std::vector<int> FamiliesThrough(const Point3& p) const;
  /// Whether boundary element @p element contains @p p (within Tolerance()).
  bool ElementContains(std::size_t element, const Point3& p) const;

  const std::vector<BoundaryElement>& Boundary() const { return this->Elements; }
  const std::vector<int>& ElementFamily() const { return this->Family; }
  double Tolerance() const { return this->Tol; }
  /// Offset of face samples from edges, and the probe distance used for classification.
  double FaceOffset() const { return this->Offset; }
  double ProbeDistance() const { return this->Offset * 0.01; }

private:
  const PolyhedralExample& Model;
  const PlaneFamilySet& Set;
  std::vector<BoundaryElement> Elements;
  std::vector<int> Family;
  std::vector<std::array<Point3, 2>> Boxes;
  std::unique_ptr<BoxGrid> Grid; ///< the elements whose box may hold a point
  std::unique_ptr<SolidClassifier> Classifier;
  double Tol = 0;
  double Offset = 0;
  std::vector<int> FamiliesOf(const std::vector<std::size_t>& elements) const;
};

class PolyhedralAnalysis
{
public:
  struct Options
  {
    double AngleTolerance = 1e-4; ///< radians; near-parallel faces within it share a family
    int MaxSmallInteger = 12;     ///< largest component tried when snapping normals exactly
  };

  struct LabelInfo
  {
    NeighbourhoodLabel Label;
    FeatureKind Kind = FeatureKind::Volume; ///< by codimension (see FeatureKindName)
    std::int64_t Occurrences = 0;           ///< sampled example features with this label
    std::string Expression;
  };

  /// A sampled piece of the example: a vertex (A = B), an edge piece from A to B (in 2D the
  /// pieces of boundary edges), or a face sample at A beside an edge piece (3D).
  struct Feature
  {
    FeatureKind Kind = FeatureKind::Vertex; ///< codimension of the sampled feature
    Point3 A{};
    Point3 B{};
    int Element = -1; ///< face (boundary element) of a face sample
    int Label = -1;
  };

  /// Analyzes a validated example (see ValidateExample). @throw Error on overlapping objects or
  /// more than PlaneFamilySet::MaxFamiliesPerLabel families at one point.
  static PolyhedralAnalysis Analyze(const PolyhedralExample& example, const Options& options);
  static PolyhedralAnalysis Analyze(const PolyhedralExample& example)
  {
    return Analyze(example, Options());
  }

  bool Planar() const { return this->IsPlanar; }
  const PlaneFamilySet& Families() const { return *this->Set; }
  const std::vector<Point3>& FamilyUnitNormals() const { return this->UnitNormals; }
  /// The example's boundary (faces, or edges in 2D) and the family of each.
  const std::vector<BoundaryElement>& Boundary() const { return this->Elements; }
  const std::vector<int>& ElementFamily() const { return this->Family; }
  /// The label of each boundary element when all its samples agree, else −1.
  const std::vector<int>& ElementLabel() const { return this->ElementLabels; }

  int NumberOfLabels() const { return static_cast<int>(this->Catalog.size()); }
  const std::vector<LabelInfo>& Labels() const { return this->Catalog; }
  const LabelInfo& Label(int id) const { return this->Catalog.at(id); }
  /// The id of @p label, or −1 when the example has no such neighbourhood.
  int Find(const NeighbourhoodLabel& label) const;
  const std::vector<Feature>& Features() const { return this->Samples; }

  /// The labels allowed at a site through planes of @p families (§4.5.2, §4.5.4): those whose
  /// families all pass through it.
  std::vector<int> AllowedLabels(std::vector<int> families) const;

  /// The options the analysis was made with (a model checked against it is analyzed alike).
  const Options& AnalysisOptions() const { return this->Used; }
  /// Volume (area in 2D) of each object type of the example, by the divergence theorem.
  const std::map<int, double>& TypeVolumes() const { return this->Volumes; }
  /// The example's bounding box.
  const Point3& Low() const { return this->BoundsLow; }
  const Point3& High() const { return this->BoundsHigh; }

private:
  bool IsPlanar = false;
  std::shared_ptr<PlaneFamilySet> Set;
  std::vector<Point3> UnitNormals;
  std::vector<BoundaryElement> Elements;
  std::vector<int> Family;
  std::vector<int> ElementLabels;
  std::vector<LabelInfo> Catalog;
  std::map<NeighbourhoodLabel, int> IdOf;
  std::vector<Feature> Samples;
  std::map<int, double> Volumes;
  Point3 BoundsLow{}, BoundsHigh{};
  Options Used;
};

} // namespace msynth
