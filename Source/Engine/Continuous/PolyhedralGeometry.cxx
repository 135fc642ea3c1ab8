// SPDX-License-Identifier: BSD-3-Clause
// The one CGAL translation unit of the engine (CGAL compiles slowly: keep it in one place): point
// classification against closed polyhedra and the self-intersection test of the validation.
#include "Formats/PolyhedralExample.h"

#include "Core/Error.h"

#include "Continuous/BoxGrid.h"
#include "Core/Index.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/self_intersections.h>
#include <CGAL/Polygon_mesh_processing/triangulate_faces.h>
#include <CGAL/Side_of_triangle_mesh.h>
#include <CGAL/Surface_mesh.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <string>
#include <vector>

namespace msynth
{

namespace
{

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Mesh = CGAL::Surface_mesh<Kernel::Point_3>;
using Side = CGAL::Side_of_triangle_mesh<Mesh, Kernel>;

/// The triangulated surface of one object (faces are validated before this is called).
std::unique_ptr<Mesh> ObjectMesh(const PolyhedralExample& example, int object)
{
  auto mesh = std::make_unique<Mesh>();
  std::map<int, Mesh::Vertex_index> vertexOf;
  for (std::size_t f = 0; f < example.Faces.size(); ++f)
  {
    if (example.FaceObject[f] != object)
    {
      continue;
    }
    std::vector<Mesh::Vertex_index> polygon;
    for (int v : example.Faces[f])
    {
      auto it = vertexOf.find(v);
      if (it == vertexOf.end())
      {
        const auto& p = example.Points[v];
        it = vertexOf.emplace(v, mesh->add_vertex(Kernel::Point_3(p[0], p[1], p[2]))).first;
      }
      polygon.push_back(it->second);
    }
    if (mesh->add_face(polygon) == Mesh::null_face())
    {
      throw Error::InFile(example.Source,
        "face " + std::to_string(f + 1) + " of object '" + example.ObjectNames.at(object) +
          "' cannot join the surface (non-manifold)");
    }
  }
  if (!CGAL::Polygon_mesh_processing::triangulate_faces(*mesh))
  {
    throw Error::InFile(example.Source,
      "the faces of object '" + example.ObjectNames.at(object) + "' cannot be triangulated");
  }
  return mesh;
}

} // namespace

bool ObjectSelfIntersects(const PolyhedralExample& example, int object)
{
  const auto mesh = ObjectMesh(example, object);
  return CGAL::Polygon_mesh_processing::does_self_intersect(*mesh);
}

struct SolidClassifier::Internal
{
  bool Planar = false;
  std::string Source;                       ///< the example's file, for messages
  std::vector<std::string> ObjectNames;     ///< as the file names them, for messages
  std::vector<std::array<Point3, 2>> Boxes; ///< per object, to skip far objects quickly
  BoxGrid Grid;                             ///< objects whose box may hold a point
  // 3D
  std::vector<std::unique_ptr<Mesh>> Meshes;
  std::vector<std::unique_ptr<Side>> Sides;
  // 2D: boundary segments per object
  std::vector<std::vector<std::pair<Point3, Point3>>> Segments;
};

SolidClassifier::SolidClassifier(const PolyhedralExample& example)
  : Impl(std::make_unique<Internal>())
{
  this->Impl->Planar = example.Planar;
  this->Impl->Source = example.Source;
  this->Impl->ObjectNames = example.ObjectNames;
  this->Impl->ObjectNames.resize(ToIndex(example.NumberOfObjects()));
  for (std::size_t o = 0; o < this->Impl->ObjectNames.size(); ++o)
  {
    if (this->Impl->ObjectNames[o].empty())
    {
      this->Impl->ObjectNames[o] = "object " + std::to_string(o + 1);
    }
  }
  this->Impl->Boxes.assign(example.NumberOfObjects(),
    { Point3{ HUGE_VAL, HUGE_VAL, HUGE_VAL }, Point3{ -HUGE_VAL, -HUGE_VAL, -HUGE_VAL } });
  for (std::size_t f = 0; f < example.Faces.size(); ++f)
  {
    auto& box = this->Impl->Boxes[example.FaceObject[f]];
    for (int v : example.Faces[f])
    {
      for (int c = 0; c < 3; ++c)
      {
        box[0][c] = std::min(box[0][c], example.Points[v][c]);
        box[1][c] = std::max(box[1][c], example.Points[v][c]);
      }
    }
  }
  this->Impl->Grid = BoxGrid(this->Impl->Boxes, 0.0);
  if (example.Planar)
  {
    this->Impl->Segments.resize(example.NumberOfObjects());
    for (const auto& element : BoundaryOf(example))
    {
      this->Impl->Segments[element.Object].emplace_back(
        example.Points[element.Points[0]], example.Points[element.Points[1]]);
    }
    return;
  }
  for (int o = 0; o < example.NumberOfObjects(); ++o)
  {
    this->Impl->Meshes.push_back(ObjectMesh(example, o));
    this->Impl->Sides.push_back(std::make_unique<Side>(*this->Impl->Meshes.back()));
  }
}

SolidClassifier::~SolidClassifier() = default;

int SolidClassifier::ObjectAt(const Point3& p) const
{
  int found = -1;
  auto far = [this, &p](std::size_t object)
  {
    const auto& box = this->Impl->Boxes[object];
    const int dims = this->Impl->Planar ? 2 : 3;
    for (int c = 0; c < dims; ++c)
    {
      if (p[c] < box[0][c] || p[c] > box[1][c])
      {
        return true;
      }
    }
    return false;
  };
  auto record = [this, &found, &p](int object)
  {
    if (found >= 0)
    {
      const auto& names = this->Impl->ObjectNames;
      throw Error::InFile(this->Impl->Source,
        "objects '" + names[ToIndex(found)] + "' and '" + names[ToIndex(object)] +
          "' overlap near (" + std::to_string(p[0]) + ", " + std::to_string(p[1]) + ", " +
          std::to_string(p[2]) + ")");
    }
    found = object;
  };
  if (this->Impl->Planar)
  {
    for (std::size_t o : this->Impl->Grid.Candidates(p))
    {
      if (far(o))
      {
        continue;
      }
      bool inside = false;
      for (const auto& [a, b] : this->Impl->Segments[o])
      {
        if ((a[1] > p[1]) != (b[1] > p[1]))
        {
          const double x = a[0] + (p[1] - a[1]) * (b[0] - a[0]) / (b[1] - a[1]);
          inside = x > p[0] ? !inside : inside;
        }
      }
      if (inside)
      {
        record(static_cast<int>(o));
      }
    }
    return found;
  }
  const Kernel::Point_3 q(p[0], p[1], p[2]);
  for (std::size_t o : this->Impl->Grid.Candidates(p))
  {
    if (far(o))
    {
      continue;
    }
    const CGAL::Bounded_side side = (*this->Impl->Sides[o])(q);
    if (side == CGAL::ON_BOUNDARY)
    {
      throw Error("a probe point (" + std::to_string(p[0]) + ", " + std::to_string(p[1]) + ", " +
        std::to_string(p[2]) + ") fell on the surface of object " + std::to_string(o) +
        "; features of the example are closer than the probe distance");
    }
    if (side == CGAL::ON_BOUNDED_SIDE)
    {
      record(static_cast<int>(o));
    }
  }
  return found;
}

} // namespace msynth
