// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/**
 * @file PolyhedralExample.h
 * @brief The example of continuous model synthesis: closed polyhedra of several object types
 * (dissertation §4.2), or polygons in the plane for the 2D algorithm (Figs. 4.10–4.16).
 *
 * - 3D: each object is a closed, manifold, consistently oriented polygon surface (one or more
 *   shells); faces are planar polygons, counter-clockwise seen from outside.
 * - 2D (all z = 0): each object is the union of its polygons; its boundary is the edges that
 *   only one of its polygons uses.
 *
 * ValidateExample() checks these and throws Error naming the file, object and face; faces and
 * vertices are numbered from 1 in file order, as OBJ numbers its vertices. CGAL's
 * polygon-mesh processing finds self-intersections (PolyhedralGeometry.cxx, the one CGAL
 * translation unit).
 */
#include <array>
#include <iosfwd>
#include <map>
#include <memory>
#include <string>
#include <vector>

namespace msynth
{

using Point3 = std::array<double, 3>;

struct PolyhedralExample
{
  std::vector<Point3> Points;
  std::vector<std::vector<int>> Faces; ///< point indices, counter-clockwise seen from outside
  std::vector<int> FaceObject;         ///< object index of each face
  std::vector<int> ObjectTypes;        ///< object type (≥ 1) of each object
  std::vector<std::string> ObjectNames;
  std::map<int, std::string> TypeNames; ///< optional readable names of object types
  bool Planar = false;                  ///< 2D example (every point has z = 0)
  std::string Source;                   ///< file name, for messages

  int NumberOfObjects() const { return static_cast<int>(this->ObjectTypes.size()); }
  /// Length of the bounding box diagonal (scale for tolerances).
  double Diagonal() const;
};

/// How object names map to object types when reading OBJ files.
struct ObjectTypeOptions
{
  /// Explicit name → type entries (an object's full name or its base name, see below).
  std::map<std::string, int> TypeOfName;
  /// Without an entry, objects whose base names are equal share a type, numbered 1, 2, … by
  /// first appearance. The base name drops a numeric suffix ("Cube.001", "roof_2" → "Cube",
  /// "roof").
};

/// Reads a Wavefront OBJ file: `v`, `f` (with v/vt/vn forms, negative indices), `o` and `g`
/// start objects; other statements are ignored. @throw Error naming the file and line.
PolyhedralExample ReadOBJExample(const std::string& path, const ObjectTypeOptions& options = {});
PolyhedralExample ReadOBJExample(
  std::istream& in, const std::string& name, const ObjectTypeOptions& options = {});

/// Splits faces without object ids into objects: connected components (faces sharing an edge)
/// per object type. @p faceTypes gives each face's type.
void AssignObjectsByConnectivity(PolyhedralExample& example, const std::vector<int>& faceTypes);

/// Turns an example modelled with y up (as most tools write OBJ, Blender's default export among
/// them: Forward −Z, Up Y) to ModelSynth's z up: (x, y, z) → (x, −z, y), a rotation, so faces
/// keep their orientation. Run it before ValidateExample, which decides 2D or 3D.
void TurnYUpToZUp(PolyhedralExample& example);

/// Decides 2D or 3D (all z = 0 and every face flat in z), checks the example and orients it:
/// degenerate or non-planar faces, open or non-manifold surfaces, inconsistent orientation and
/// self-intersections are errors; an object whose faces all point inward is turned outward, and
/// 2D polygons are made counter-clockwise. @throw Error naming the file, object and face.
void ValidateExample(PolyhedralExample& example);

/// The oriented boundary of an example: faces in 3D, edges in 2D (codimension 1).
struct BoundaryElement
{
  int Object = 0;
  std::vector<int> Points; ///< a polygon (3D) or a segment (2D)
  Point3 Normal{};         ///< unit outward normal
};
std::vector<BoundaryElement> BoundaryOf(const PolyhedralExample& example);

/// Which object contains a point (exactly, for points off the boundary): CGAL's side-of-mesh
/// test per object in 3D, a crossing test in 2D.
class SolidClassifier
{
public:
  explicit SolidClassifier(const PolyhedralExample& example);
  ~SolidClassifier();
  SolidClassifier(const SolidClassifier&) = delete;
  SolidClassifier& operator=(const SolidClassifier&) = delete;
  /// The index of the object whose interior contains @p p, −1 for none. @throw Error naming the
  /// example's file and both objects (by name, or numbered from 1) when two contain it.
  int ObjectAt(const Point3& p) const;

private:
  struct Internal;
  std::unique_ptr<Internal> Impl;
};

/// Whether the surface of one 3D object intersects itself (CGAL PMP::does_self_intersect after
/// triangulating its faces). Used by ValidateExample.
bool ObjectSelfIntersects(const PolyhedralExample& example, int object);

} // namespace msynth
