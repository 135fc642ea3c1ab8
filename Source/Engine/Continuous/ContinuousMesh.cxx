// SPDX-License-Identifier: BSD-3-Clause
#include "Continuous/ContinuousMesh.h"

#include "Continuous/FeatureWidth.h"

#include "Core/Error.h"

#include "Continuous/Point3Math.h"
#include "Core/Index.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>

namespace msynth
{

std::map<int, std::vector<std::vector<std::int32_t>>> SurfacesByType(const ContinuousMesh& mesh)
{
  std::map<int, std::vector<std::vector<std::int32_t>>> out;
  for (std::size_t f = 0; f < mesh.Polygons.size(); ++f)
  {
    const auto& poly = mesh.Polygons[f];
    if (mesh.InsideType[f] > 0)
    {
      out[mesh.InsideType[f]].push_back(poly);
    }
    if (!mesh.Planar && mesh.OutsideType[f] > 0)
    {
      out[mesh.OutsideType[f]].emplace_back(poly.rbegin(), poly.rend());
    }
  }
  return out;
}

std::map<int, double> TypeVolumes(const ContinuousMesh& mesh)
{
  std::map<int, double> volumes;
  for (const auto& [type, polygons] : SurfacesByType(mesh))
  {
    double sum = 0;
    for (const auto& poly : polygons)
      sum += point3::FanMeasure(mesh.Points, poly, mesh.Planar);
    volumes[type] = sum;
  }
  return volumes;
}

PolyhedralExample MeshToModel(
  const ContinuousMesh& mesh, const std::map<int, std::string>& typeNames)
{
  PolyhedralExample model;
  model.Points = mesh.Points;
  model.Source = "synthesized model";
  model.TypeNames = typeNames;
  std::vector<int> faceType;
  for (auto& [type, polygons] : SurfacesByType(mesh))
  {
    for (auto& poly : polygons)
    {
      model.Faces.emplace_back(poly.begin(), poly.end());
      faceType.push_back(type);
    }
  }
  // Objects: faces of one type joined through shared edges.
  const std::size_t nf = model.Faces.size();
  std::vector<std::size_t> parent(nf);
  std::iota(parent.begin(), parent.end(), 0);
  const auto find = [&parent](std::size_t i)
  {
    while (parent[i] != i)
    {
      i = parent[i] = parent[parent[i]];
    }
    return i;
  };
  std::map<std::tuple<int, int, int>, std::size_t> firstOfEdge; // (type, a, b)
  for (std::size_t f = 0; f < nf; ++f)
  {
    const auto& face = model.Faces[f];
    for (std::size_t i = 0; i < face.size(); ++i)
    {
      const int a = face[i], b = face[(i + 1) % face.size()];
      const auto [it, inserted] =
        firstOfEdge.emplace(std::make_tuple(faceType[f], std::min(a, b), std::max(a, b)), f);
      if (!inserted)
      {
        parent[find(f)] = find(it->second);
      }
    }
  }
  std::map<std::size_t, int> objectOf;
  model.FaceObject.assign(nf, 0);
  for (std::size_t f = 0; f < nf; ++f)
  {
    const auto [it, inserted] = objectOf.emplace(find(f), model.NumberOfObjects());
    if (inserted)
    {
      model.ObjectTypes.push_back(faceType[f]);
      const auto t = typeNames.find(faceType[f]);
      const std::string name =
        t != typeNames.end() ? t->second : "type" + std::to_string(faceType[f]);
      model.ObjectNames.push_back(name + "." + std::to_string(it->second));
    }
    model.FaceObject[f] = it->second;
  }
  model.Planar = mesh.Planar;
  return model;
}

namespace
{
/// The first object of @p model (before validation turns inward objects outward) whose
/// enclosed volume (area in 2D) is not positive, as a problem; empty when all face outward.
std::string OrientationProblem(const PolyhedralExample& model, bool planar)
{
  std::vector<double> volume(ToIndex(model.NumberOfObjects()), 0.0);
  for (std::size_t f = 0; f < model.Faces.size(); ++f)
  {
    const auto& face = model.Faces[f];
    const Point3& a = model.Points[ToIndex(face[0])];
    for (std::size_t i = 1; i + 1 < face.size(); ++i)
    {
      const Point3& b = model.Points[ToIndex(face[i])];
      const Point3& c = model.Points[ToIndex(face[i + 1])];
      const Point3 cr = point3::Cross(point3::Sub(b, a), point3::Sub(c, a));
      volume[ToIndex(model.FaceObject[f])] += planar ? cr[2] : point3::Dot(a, cr);
    }
  }
  for (int o = 0; o < model.NumberOfObjects(); ++o)
  {
    if (!(volume[ToIndex(o)] > 0))
    {
      return "object " + model.ObjectNames[ToIndex(o)] + " of the output is not oriented outward";
    }
  }
  return {};
}

/// Families of the model's analysis @p found → the example's, by their exact normals (up to
/// sign: a family's normal points whichever way the first face seen did), in @p familyMap and
/// @p flipped. Returns the problem when a direction is not the example's, else empty.
std::string MapFamilies(const PolyhedralAnalysis& found, const PolyhedralAnalysis& example,
  std::vector<int>& familyMap, std::vector<bool>& flipped)
{
  for (const auto& n : found.Families().AllNormals())
  {
    const auto& all = example.Families().AllNormals();
    const IntVec3 minus{ -n[0], -n[1], -n[2] };
    auto it = std::find(all.begin(), all.end(), n);
    flipped.push_back(it == all.end());
    if (it == all.end())
    {
      it = std::find(all.begin(), all.end(), minus);
    }
    if (it == all.end())
    {
      // Directions snapped to small integers (a rotated example) may snap to a neighbouring
      // integer direction when re-derived from the output: the example's family within the
      // analysis' angle tolerance is the same plane direction.
      const double tolerance = example.AnalysisOptions().AngleTolerance;
      for (auto k = all.begin(); k != all.end() && it == all.end(); ++k)
      {
        const Point3 a{ double(n[0]), double(n[1]), double(n[2]) };
        const Point3 b{ double((*k)[0]), double((*k)[1]), double((*k)[2]) };
        const double sine = point3::Norm(point3::Cross(a, b)) / (point3::Norm(a) * point3::Norm(b));
        if (sine <= std::sin(tolerance) * 2)
        {
          it = k;
          flipped.back() = point3::Dot(a, b) < 0;
        }
      }
    }
    if (it == all.end())
    {
      return "the output has a face direction (" + std::to_string(n[0]) + ", " +
        std::to_string(n[1]) + ", " + std::to_string(n[2]) + ") that the example does not have";
    }
    familyMap.push_back(static_cast<int>(it - all.begin()));
  }
  return {};
}

/// Label @p l of the model's analysis in the example's terms: the families renumbered by
/// @p familyMap and the cone bits permuted to the example's order (and flipped with the
/// family), canonicalized.
NeighbourhoodLabel MapLabel(
  const NeighbourhoodLabel& l, const std::vector<int>& familyMap, const std::vector<bool>& flipped)
{
  std::vector<std::pair<int, int>> order; // (example family, position in l)
  for (std::size_t j = 0; j < l.Families.size(); ++j)
  {
    order.emplace_back(familyMap[ToIndex(l.Families[j])], static_cast<int>(j));
  }
  std::sort(order.begin(), order.end());
  NeighbourhoodLabel mapped;
  for (const auto& o : order)
  {
    mapped.Families.push_back(o.first);
  }
  mapped.Types.assign(l.Types.size(), -1);
  for (unsigned m = 0; m < l.Types.size(); ++m)
  {
    unsigned target = 0;
    for (std::size_t k = 0; k < order.size(); ++k)
    {
      const auto j = ToIndex(order[k].second);
      const bool positive = ((m >> j) & 1u) != 0;
      if (positive != flipped[ToIndex(l.Families[j])])
      {
        target |= 1u << k;
      }
    }
    mapped.Types[target] = l.Types[m];
  }
  mapped.Canonicalize();
  return mapped;
}
} // namespace

ContinuousModelReport CheckContinuousModel(const PolyhedralAnalysis& example,
  const ContinuousMesh& mesh, const std::map<int, std::string>& typeNames, double smallestSpacing)
{
  ContinuousModelReport report;
  if (mesh.Polygons.empty())
  {
    report.Valid = true; // the empty model satisfies the constraint everywhere
    return report;
  }
  PolyhedralExample model = MeshToModel(mesh, typeNames);
  report.Objects = model.NumberOfObjects();
  // Orientation, before validation (which would turn inward objects outward).
  report.Problem = OrientationProblem(model, mesh.Planar);
  if (!report.Problem.empty())
  {
    return report;
  }
  try
  {
    ValidateExample(model);
  }
  catch (const Error& e)
  {
    report.Problem = std::string("the output is not a valid closed model: ") + e.what();
    return report;
  }
  const PolyhedralAnalysis found = PolyhedralAnalysis::Analyze(model, example.AnalysisOptions());
  std::vector<int> familyMap;
  std::vector<bool> flipped;
  report.Problem = MapFamilies(found, example, familyMap, flipped);
  if (!report.Problem.empty())
  {
    return report;
  }
  report.DistinctLabels = found.NumberOfLabels();
  report.SampledFeatures = static_cast<std::int64_t>(found.Features().size());
  for (int id = 0; id < found.NumberOfLabels(); ++id)
  {
    const NeighbourhoodLabel& l = found.Label(id).Label;
    const NeighbourhoodLabel mapped = MapLabel(l, familyMap, flipped);
    if (example.Find(mapped) < 0)
    {
      Point3 where{};
      for (const auto& f : found.Features())
      {
        if (f.Label == id)
        {
          where = f.A;
          break;
        }
      }
      report.Problem = "the neighbourhood " + found.Label(id).Expression + " at (" +
        std::to_string(where[0]) + ", " + std::to_string(where[1]) + ", " +
        std::to_string(where[2]) + ") is not one of the example's labels";
      return report;
    }
  }
  // Slivers: the narrowest feature, measured on the polygons alone (FeatureWidth.h).
  const double radius = smallestSpacing > 0 ? smallestSpacing : model.Diagonal() / 64;
  const FeatureWidth width = SmallestFeature(mesh, radius);
  report.SmallestFeature = width.Width;
  report.SmallestSpacing = smallestSpacing;
  if (smallestSpacing > 0 && width.Width < MinimumFeatureFraction * smallestSpacing)
  {
    const Point3& w = width.Where;
    report.Problem = "a face, edge or gap is only " + std::to_string(width.Width) + " wide at (" +
      std::to_string(w[0]) + ", " + std::to_string(w[1]) + ", " + std::to_string(w[2]) +
      "): under " + std::to_string(static_cast<int>(MinimumFeatureFraction * 100)) +
      " % of the smallest plane spacing " + std::to_string(smallestSpacing);
    return report;
  }
  report.Valid = true;
  return report;
}

double LevelSetVoxel(
  const ContinuousMesh& mesh, double spacing, double extent, double halfWidth, double budget)
{
  double area = 0; // of the surfaces of every solid type: a face between two types counts twice
  for (std::size_t f = 0; f < mesh.Polygons.size(); ++f)
  {
    const auto& poly = mesh.Polygons[f];
    Point3 n{ 0, 0, 0 };
    for (std::size_t i = 0; i < poly.size(); ++i)
    {
      const Point3& a = mesh.Points[ToIndex(poly[i])];
      const Point3& b = mesh.Points[ToIndex(poly[(i + 1) % poly.size()])];
      n[0] += a[1] * b[2] - a[2] * b[1];
      n[1] += a[2] * b[0] - a[0] * b[2];
      n[2] += a[0] * b[1] - a[1] * b[0];
    }
    const int sides = (mesh.InsideType[f] != 0 ? 1 : 0) +
      (f < mesh.OutsideType.size() && mesh.OutsideType[f] != 0 ? 1 : 0);
    area += sides * 0.5 * std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
  }
  const double voxel = std::max(spacing / 4, extent / 256);
  const double banded = budget > 0 ? std::sqrt(2 * halfWidth * area / budget) : 0;
  return std::max(voxel, banded);
}

namespace
{
/// VoxelizeModel (@p evenly false: each centre, nudged off the lattice) and VoxelizeModelEvenly
/// (@p evenly true: nudged both ways, a centre the two disagree on takes either in a
/// checkerboard, so a slope splits its voxels evenly).
LabelGrid Voxelize(const ContinuousMesh& mesh, const Point3& origin, double voxel,
  const std::array<std::int64_t, 3>& dims, bool evenly)
{
  if (!(voxel > 0) || dims[0] < 1 || dims[1] < 1 || dims[2] < 1 ||
    static_cast<double>(dims[0]) * static_cast<double>(dims[1]) * static_cast<double>(dims[2]) >
      static_cast<double>(LabelGrid::MaxSites))
  {
    throw Error("voxelization: the grid is empty or has too many voxels");
  }
  LabelGrid grid(dims[0], dims[1], dims[2], 0);
  if (mesh.Polygons.empty())
  {
    return grid;
  }
  const PolyhedralExample model = MeshToModel(mesh, {});
  const SolidClassifier classifier(model);
  // Off-lattice nudges (fractions of a voxel) keep centres off the planes of the arrangement.
  const double nudge[3] = { 0.0123456, 0.0234567, mesh.Planar ? 0.0 : 0.0345678 };
  auto typeAt = [&](std::int64_t x, std::int64_t y, std::int64_t z, double sign)
  {
    const Point3 p{ origin[0] + (static_cast<double>(x) + 0.5 + sign * nudge[0]) * voxel,
      origin[1] + (static_cast<double>(y) + 0.5 + sign * nudge[1]) * voxel,
      mesh.Planar ? 0.0 : origin[2] + (static_cast<double>(z) + 0.5 + sign * nudge[2]) * voxel };
    const int object = classifier.ObjectAt(p);
    return object >= 0 ? model.ObjectTypes[ToIndex(object)] : 0;
  };
  for (std::int64_t z = 0; z < dims[2]; ++z)
  {
    for (std::int64_t y = 0; y < dims[1]; ++y)
    {
      for (std::int64_t x = 0; x < dims[0]; ++x)
      {
        const int up = typeAt(x, y, z, 1.0);
        if (!evenly)
        {
          grid.Set(x, y, z, up);
          continue;
        }
        const int down = typeAt(x, y, z, -1.0);
        grid.Set(x, y, z, up == down || (x + y + z) % 2 == 0 ? up : down);
      }
    }
  }
  return grid;
}
} // namespace

LabelGrid VoxelizeModel(const ContinuousMesh& mesh, const Point3& origin, double voxel,
  const std::array<std::int64_t, 3>& dims)
{
  return Voxelize(mesh, origin, voxel, dims, false);
}

LabelGrid VoxelizeModelEvenly(const ContinuousMesh& mesh, const Point3& origin, double voxel,
  const std::array<std::int64_t, 3>& dims)
{
  return Voxelize(mesh, origin, voxel, dims, true);
}

ContinuousMesh MeshFromPolygons(bool planar, std::vector<Point3> points,
  std::vector<std::vector<std::int32_t>> polygons, std::vector<std::int32_t> insideType,
  std::vector<std::int32_t> outsideType)
{
  ContinuousMesh mesh;
  mesh.Planar = planar;
  if (insideType.size() != polygons.size() || (!planar && outsideType.size() != polygons.size()))
  {
    throw Error("a model mesh needs one inside (and, in 3D, one outside) type per polygon");
  }
  for (const auto& poly : polygons)
  {
    if (poly.size() < 3)
    {
      throw Error("a model mesh polygon has fewer than three corners");
    }
    for (auto i : poly)
    {
      if (i < 0 || ToIndex(i) >= points.size())
      {
        throw Error("a model mesh polygon refers to a point that does not exist");
      }
    }
  }
  mesh.Points = std::move(points);
  mesh.PointVertex.assign(mesh.Points.size(), -1);
  mesh.Polygons = std::move(polygons);
  mesh.InsideType = std::move(insideType);
  if (!planar)
  {
    mesh.OutsideType = std::move(outsideType);
  }
  return mesh;
}

} // namespace msynth
