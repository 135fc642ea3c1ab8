// SPDX-License-Identifier: BSD-3-Clause
#include "Continuous/ContinuousMesh.h"

#include "Continuous/FeatureWidth.h"

#include "Core/Error.h"
#include "Core/ParallelChunks.h"

#include "Continuous/Point3Math.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <numeric>

namespace msynth
{
namespace
{
using Wide = __int128;

Wide DotW(const IntVec3& a, const IntVec3& b)
{
  return static_cast<Wide>(a[0]) * b[0] + static_cast<Wide>(a[1]) * b[1] +
    static_cast<Wide>(a[2]) * b[2];
}

/// (a × b)·n, exactly.
Wide TripleW(const IntVec3& a, const IntVec3& b, const IntVec3& n)
{
  const Wide x = static_cast<Wide>(a[1]) * b[2] - static_cast<Wide>(a[2]) * b[1];
  const Wide y = static_cast<Wide>(a[2]) * b[0] - static_cast<Wide>(a[0]) * b[2];
  const Wide z = static_cast<Wide>(a[0]) * b[1] - static_cast<Wide>(a[1]) * b[0];
  return x * n[0] + y * n[1] + z * n[2];
}

/// Type of @p label toward a direction whose side of each label family is given by @p side.
template <class Side>
int TypeToward(const NeighbourhoodLabel& label, Side&& side)
{
  unsigned mask = 0;
  for (std::size_t j = 0; j < label.Families.size(); ++j)
  {
    if (side(label.Families[j]) > 0)
    {
      mask |= 1u << j;
    }
  }
  const int t = label.Types[mask];
  if (t < 0)
  {
    throw Error("mesh extraction: internal error (a face lies in a cone the label does not have)");
  }
  return t;
}

/**
 * Traces the faces of a labelled arrangement. The links of a vertex within a plane are taken
 * counter-clockwise around the plane's normal: every direction in the plane has a fixed rank in
 * that cyclic order (computed once per plane), so no vertex sorts its links.
 */
class FaceTracer
{
public:
  FaceTracer(const PolyhedralAnalysis& analysis, const PlaneArrangement& arrangement,
    const std::vector<std::int32_t>& labels)
    : Analysis(analysis)
    , Arrangement(arrangement)
    , Labels(labels)
  {
    const PlaneFamilySet& set = arrangement.Families();
    for (int p = 0; p <= set.Size(); ++p)
      this->RankDirections(p < set.Size() ? set.Normal(p) : IntVec3{ 0, 0, 1 });
    const int d = arrangement.NumberOfDirections();
    if (d <= 256)
    {
      this->Sides.resize(static_cast<std::size_t>(d) * static_cast<std::size_t>(d));
      for (int a = 0; a < d; ++a)
        for (int b = 0; b < d; ++b)
          this->Sides[static_cast<std::size_t>(a * d + b)] = this->ComputeSides(a, b);
    }
  }

  /// Bit f set when family f's normal points into the sector between directions @p a and @p b
  /// (n_f · (a + b) > 0).
  std::uint64_t PositiveSides(int a, int b) const
  {
    if (this->Sides.empty())
      return this->ComputeSides(a, b);
    return this->Sides[static_cast<std::size_t>(a * this->Arrangement.NumberOfDirections() + b)];
  }

  /// The plane index of family @p p's normal; Families().Size() is the plane z = 0 (2D).
  const IntVec3& Normal(int p) const { return this->Normals[static_cast<std::size_t>(p)]; }

  /// Links of @p v within plane @p p, counter-clockwise around its normal, from the first link
  /// in the arrangement's order.
  void Around(std::int64_t v, int p, std::vector<PlaneArrangement::Link>& out) const
  {
    const std::vector<int>& rank = this->Ranks[static_cast<std::size_t>(p)];
    const int count = this->Counts[static_cast<std::size_t>(p)];
    out.clear();
    int first = 0;
    for (const auto* l = this->Arrangement.LinksBegin(v); l != this->Arrangement.LinksEnd(v); ++l)
    {
      const int r = rank[static_cast<std::size_t>(l->Direction)];
      if (r < 0)
        continue;
      if (out.empty())
        first = r;
      // Insertion by the angle from the first link (a vertex has a few links in a plane).
      const int key = (r - first + count) % count;
      std::size_t i = out.size();
      out.push_back(*l);
      for (; i > 0 &&
           (rank[static_cast<std::size_t>(out[i - 1].Direction)] - first + count) % count > key;
           --i)
        out[i] = out[i - 1];
      out[i] = *l;
    }
  }

  /**
   * Traces the face left of the edge leaving @p u along @p first (counter-clockwise around plane
   * @p p's normal) into @p loop. False, with the trace cut short, as soon as it meets a vertex
   * numbered below @p u: the face is then emitted from its lowest vertex instead.
   */
  bool Trace(std::int64_t u, const PlaneArrangement::Link& first, int p,
    std::vector<std::int64_t>& loop) const
  {
    loop.assign(1, u);
    PlaneArrangement::Link edge = first;
    for (std::size_t guard = 0;; ++guard)
    {
      if (edge.Vertex < 0 || guard > 1000000)
      {
        throw Error("mesh extraction: a face of the model leaves the output box (the labels are "
                    "not consistent with the arrangement)");
      }
      const std::int64_t v = edge.Vertex;
      if (v == u)
        return true;
      if (v < u)
        return false;
      loop.push_back(v);
      edge = this->Before(v, p, edge.Direction ^ 1);
    }
  }

  /// The link of @p v in plane @p p just before direction @p back counter-clockwise.
  PlaneArrangement::Link Before(std::int64_t v, int p, int back) const
  {
    const std::vector<int>& rank = this->Ranks[static_cast<std::size_t>(p)];
    const int count = this->Counts[static_cast<std::size_t>(p)];
    const int from = rank[static_cast<std::size_t>(back)];
    const PlaneArrangement::Link* best = nullptr;
    int bestKey = -1;
    bool found = false;
    for (const auto* l = this->Arrangement.LinksBegin(v); l != this->Arrangement.LinksEnd(v); ++l)
    {
      const int r = rank[static_cast<std::size_t>(l->Direction)];
      if (r < 0)
        continue;
      found = found || l->Direction == back;
      const int key = (r - from + count) % count;
      if (key > bestKey)
      {
        bestKey = key;
        best = l;
      }
    }
    if (!found || from < 0)
      throw Error("mesh extraction: internal error (an edge has no way back)");
    return *best;
  }

  const NeighbourhoodLabel& LabelOf(std::int64_t v) const
  {
    return this->Analysis.Label(this->Labels[static_cast<std::size_t>(v)]).Label;
  }

  const PolyhedralAnalysis& Analysis;
  const PlaneArrangement& Arrangement;
  const std::vector<std::int32_t>& Labels;

private:
  std::uint64_t ComputeSides(int a, int b) const
  {
    const PlaneFamilySet& set = this->Arrangement.Families();
    const IntVec3& da = this->Arrangement.Direction(a);
    const IntVec3& db = this->Arrangement.Direction(b);
    const IntVec3 w{ da[0] + db[0], da[1] + db[1], da[2] + db[2] };
    std::uint64_t mask = 0;
    for (int f = 0; f < set.Size(); ++f)
      if (set.Side(f, w) > 0)
        mask |= std::uint64_t(1) << f;
    return mask;
  }

  /// Ranks the directions perpendicular to @p n by their angle counter-clockwise around it
  /// from the first of them (-1: not in the plane).
  void RankDirections(const IntVec3& n)
  {
    std::vector<int> in;
    for (int d = 0; d < this->Arrangement.NumberOfDirections(); ++d)
      if (DotW(n, this->Arrangement.Direction(d)) == 0)
        in.push_back(d);
    std::vector<int> rank(static_cast<std::size_t>(this->Arrangement.NumberOfDirections()), -1);
    if (!in.empty())
    {
      const IntVec3 r = this->Arrangement.Direction(in[0]);
      const auto half = [&](const IntVec3& d)
      {
        const Wide t = TripleW(r, d, n);
        return (t > 0 || (t == 0 && DotW(r, d) > 0)) ? 0 : 1;
      };
      std::sort(in.begin(), in.end(),
        [&](int a, int b)
        {
          const IntVec3& da = this->Arrangement.Direction(a);
          const IntVec3& db = this->Arrangement.Direction(b);
          const int ha = half(da), hb = half(db);
          if (ha != hb)
            return ha < hb;
          return TripleW(da, db, n) > 0;
        });
      for (std::size_t i = 0; i < in.size(); ++i)
        rank[static_cast<std::size_t>(in[i])] = static_cast<int>(i);
    }
    this->Normals.push_back(n);
    this->Ranks.push_back(std::move(rank));
    this->Counts.push_back(static_cast<int>(in.size()));
  }

  std::vector<IntVec3> Normals;
  std::vector<std::vector<int>> Ranks;
  std::vector<int> Counts;
  std::vector<std::uint64_t> Sides; ///< PositiveSides of every pair of directions (few directions)
};

/// One label per arrangement vertex, each one of the example's. @throw Error.
void CheckMeshLabels(const PolyhedralAnalysis& analysis, std::int64_t vertices,
  const std::vector<std::int32_t>& labels)
{
  if (static_cast<std::int64_t>(labels.size()) != vertices)
  {
    throw Error("mesh extraction: " + std::to_string(labels.size()) + " labels for " +
      std::to_string(vertices) + " arrangement vertices");
  }
  for (auto a : labels)
  {
    if (a < 0 || a >= analysis.NumberOfLabels())
    {
      throw Error("mesh extraction: label " + std::to_string(a) + " is not one of the example's " +
        std::to_string(analysis.NumberOfLabels()) + " labels");
    }
  }
}

/// The faces found from a range of arrangement vertices, in the order a serial scan finds them:
/// each face's arrangement vertices (already turned for its orientation) and its two types.
struct FoundFaces
{
  std::vector<std::int64_t> Vertices;
  std::vector<std::size_t> Ends;
  std::vector<std::array<int, 2>> Types; ///< inside, outside

  void Add(const std::vector<std::int64_t>& loop, bool reverse, int inside, int outside)
  {
    for (std::size_t i = 0; i < loop.size(); ++i)
      this->Vertices.push_back(loop[reverse ? (loop.size() - i) % loop.size() : i]);
    this->Ends.push_back(this->Vertices.size());
    this->Types.push_back({ inside, outside });
  }
};

/// The faces whose lowest arrangement vertex is @p u (each face once: from its lowest vertex,
/// the traces from its other vertices stop at that one).
void FacesFrom(const FaceTracer& tracer, std::int64_t u, bool planar, FoundFaces& out,
  std::vector<std::int64_t>& loop, std::vector<PlaneArrangement::Link>& around)
{
  const PlaneArrangement& arrangement = tracer.Arrangement;
  const PlaneFamilySet& set = arrangement.Families();
  const NeighbourhoodLabel& label = tracer.LabelOf(u);
  if (label.Families.empty() && (!planar || label.Types[0] == 0))
    return; // inside a cell: no interface (3D) or empty space (2D) starts here
  if (planar)
  {
    tracer.Around(u, set.Size(), around);
    for (std::size_t i = 0; i < around.size(); ++i)
    {
      const std::uint64_t positive = tracer.PositiveSides(
        around[i].Direction, around[(i + 1) % around.size()].Direction);
      const int type = TypeToward(label, [&](int f) { return int((positive >> f) & 1u); });
      if (type != 0 && tracer.Trace(u, around[i], set.Size(), loop))
        out.Add(loop, false, type, 0);
    }
    return;
  }
  for (int p : label.Families)
  {
    tracer.Around(u, p, around);
    if (around.size() < 4)
      throw Error("mesh extraction: internal error (fewer than two lines in a plane)");
    for (std::size_t i = 0; i < around.size(); ++i)
    {
      const std::uint64_t positive =
        tracer.PositiveSides(around[i].Direction, around[(i + 1) % around.size()].Direction);
      const auto side = [&](int sign)
      {
        return TypeToward(
          label, [&](int f) { return f == p ? sign : int((positive >> f) & 1u); });
      };
      const int back = side(-1), front = side(+1);
      if (back == front || !tracer.Trace(u, around[i], p, loop))
        continue;
      // Counter-clockwise around n_p: the normal points to the front side.
      const bool backInside = front == 0 || (back != 0 && back < front);
      if (backInside)
        out.Add(loop, false, back, front);
      else
        out.Add(loop, true, front, back);
    }
  }
}

} // namespace

ContinuousMesh ExtractMesh(const PolyhedralAnalysis& analysis, const PlaneArrangement& arrangement,
  const std::vector<std::int32_t>& labels, unsigned threads)
{
  const std::int64_t n = arrangement.NumberOfVertices();
  CheckMeshLabels(analysis, n, labels);
  const FaceTracer tracer(analysis, arrangement, labels);
  ContinuousMesh mesh;
  mesh.Planar = arrangement.Planar();
  // Faces found in chunks of vertices on threads, then added in the vertices' order: the same
  // mesh for any thread count. A vertex becomes a mesh point the first time a face uses it.
  constexpr std::int64_t chunk = 4096;
  std::vector<FoundFaces> found(static_cast<std::size_t>((n + chunk - 1) / chunk));
  RunChunks(found.size(), threads,
    [&](std::size_t c)
    {
      std::vector<std::int64_t> loop;
      std::vector<PlaneArrangement::Link> around;
      const std::int64_t first = static_cast<std::int64_t>(c) * chunk;
      for (std::int64_t u = first; u < std::min(n, first + chunk); ++u)
        FacesFrom(tracer, u, mesh.Planar, found[c], loop, around);
    });
  std::vector<std::int32_t> pointOf(static_cast<std::size_t>(n), -1);
  for (FoundFaces& faces : found)
  {
    std::size_t begin = 0;
    for (std::size_t f = 0; f < faces.Ends.size(); ++f)
    {
      std::vector<std::int32_t> polygon;
      polygon.reserve(faces.Ends[f] - begin);
      for (std::size_t i = begin; i < faces.Ends[f]; ++i)
      {
        const std::int64_t v = faces.Vertices[i];
        auto& point = pointOf[static_cast<std::size_t>(v)];
        if (point < 0)
        {
          point = static_cast<std::int32_t>(mesh.Points.size());
          mesh.Points.push_back(arrangement.Position(v));
          mesh.PointVertex.push_back(v);
        }
        polygon.push_back(point);
      }
      begin = faces.Ends[f];
      mesh.Polygons.push_back(std::move(polygon));
      mesh.InsideType.push_back(faces.Types[f][0]);
      if (!mesh.Planar)
        mesh.OutsideType.push_back(faces.Types[f][1]);
    }
    faces = FoundFaces(); // its memory back
  }
  return mesh;
}

std::vector<MeshFace> FaceMeasures(const PolyhedralAnalysis& analysis,
  const PlaneArrangement& arrangement, const std::vector<std::int32_t>& labels, unsigned threads)
{
  const std::int64_t n = arrangement.NumberOfVertices();
  CheckMeshLabels(analysis, n, labels);
  const FaceTracer tracer(analysis, arrangement, labels);
  const bool planar = arrangement.Planar();
  const Point3 origin = arrangement.Position(0);
  constexpr std::int64_t chunk = 4096;
  std::vector<std::vector<MeshFace>> found(static_cast<std::size_t>((n + chunk - 1) / chunk));
  RunChunks(found.size(), threads,
    [&](std::size_t c)
    {
      FoundFaces faces;
      std::vector<std::int64_t> loop;
      std::vector<PlaneArrangement::Link> around;
      const std::int64_t first = static_cast<std::int64_t>(c) * chunk;
      for (std::int64_t u = first; u < std::min(n, first + chunk); ++u)
        FacesFrom(tracer, u, planar, faces, loop, around);
      std::size_t begin = 0;
      for (std::size_t f = 0; f < faces.Ends.size(); ++f)
      {
        const auto corner = [&](std::size_t k)
        {
          const Point3& q = arrangement.Position(faces.Vertices[begin + k]);
          return Point3{ q[0] - origin[0], q[1] - origin[1], q[2] - origin[2] };
        };
        double measure = 0; // a fan from the first corner: a·(b × e) / 6, or the area in 2D
        const Point3 a = corner(0);
        for (std::size_t k = 1; k + 1 < faces.Ends[f] - begin; ++k)
        {
          const Point3 b = corner(k), e = corner(k + 1);
          measure += planar
            ? ((b[0] - a[0]) * (e[1] - a[1]) - (b[1] - a[1]) * (e[0] - a[0])) / 2
            : (a[0] * (b[1] * e[2] - b[2] * e[1]) + a[1] * (b[2] * e[0] - b[0] * e[2]) +
                a[2] * (b[0] * e[1] - b[1] * e[0])) /
              6;
        }
        found[c].push_back({ faces.Vertices[begin], faces.Types[f][0],
          planar ? 0 : faces.Types[f][1], measure });
        begin = faces.Ends[f];
      }
    });
  std::vector<MeshFace> out;
  for (const auto& faces : found)
    out.insert(out.end(), faces.begin(), faces.end());
  return out;
}

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
  std::vector<double> volume(static_cast<std::size_t>(model.NumberOfObjects()), 0.0);
  for (std::size_t f = 0; f < model.Faces.size(); ++f)
  {
    const auto& face = model.Faces[f];
    const Point3& a = model.Points[static_cast<std::size_t>(face[0])];
    for (std::size_t i = 1; i + 1 < face.size(); ++i)
    {
      const Point3& b = model.Points[static_cast<std::size_t>(face[i])];
      const Point3& c = model.Points[static_cast<std::size_t>(face[i + 1])];
      const Point3 cr = point3::Cross(point3::Sub(b, a), point3::Sub(c, a));
      volume[static_cast<std::size_t>(model.FaceObject[f])] += planar ? cr[2] : point3::Dot(a, cr);
    }
  }
  for (int o = 0; o < model.NumberOfObjects(); ++o)
  {
    if (!(volume[static_cast<std::size_t>(o)] > 0))
    {
      return "object " + model.ObjectNames[static_cast<std::size_t>(o)] +
        " of the output is not oriented outward";
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
    order.emplace_back(familyMap[static_cast<std::size_t>(l.Families[j])], static_cast<int>(j));
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
      const auto j = static_cast<std::size_t>(order[k].second);
      const bool positive = ((m >> j) & 1u) != 0;
      if (positive != flipped[static_cast<std::size_t>(l.Families[j])])
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
      const Point3& a = mesh.Points[static_cast<std::size_t>(poly[i])];
      const Point3& b = mesh.Points[static_cast<std::size_t>(poly[(i + 1) % poly.size()])];
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

LabelGrid VoxelizeModel(const ContinuousMesh& mesh, const Point3& origin, double voxel,
  const std::array<std::int64_t, 3>& dims)
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
  for (std::int64_t z = 0; z < dims[2]; ++z)
  {
    for (std::int64_t y = 0; y < dims[1]; ++y)
    {
      for (std::int64_t x = 0; x < dims[0]; ++x)
      {
        const Point3 p{ origin[0] + (static_cast<double>(x) + 0.5 + nudge[0]) * voxel,
          origin[1] + (static_cast<double>(y) + 0.5 + nudge[1]) * voxel,
          mesh.Planar ? 0.0 : origin[2] + (static_cast<double>(z) + 0.5 + nudge[2]) * voxel };
        const int object = classifier.ObjectAt(p);
        if (object >= 0)
        {
          grid.Set(x, y, z, model.ObjectTypes[static_cast<std::size_t>(object)]);
        }
      }
    }
  }
  return grid;
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
      if (i < 0 || static_cast<std::size_t>(i) >= points.size())
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
