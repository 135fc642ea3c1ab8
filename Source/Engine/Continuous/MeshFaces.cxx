// SPDX-License-Identifier: BSD-3-Clause
// Mesh extraction (ContinuousMesh.h): the faces of a labelled arrangement across which the object
// type changes, traced on threads and added in the vertices' order (ExtractMesh, FaceMeasures).
#include "Continuous/ContinuousMesh.h"

#include "Core/Error.h"
#include "Core/Index.h"
#include "Core/ParallelChunks.h"

#include <algorithm>
#include <array>

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
      this->Sides.resize(ToIndex(d) * ToIndex(d));
      for (int a = 0; a < d; ++a)
        for (int b = 0; b < d; ++b)
          this->Sides[ToIndex(a * d + b)] = this->ComputeSides(a, b);
    }
  }

  /// Bit f set when family f's normal points into the sector between directions @p a and @p b
  /// (n_f · (a + b) > 0).
  std::uint64_t PositiveSides(int a, int b) const
  {
    if (this->Sides.empty())
      return this->ComputeSides(a, b);
    return this->Sides[ToIndex(a * this->Arrangement.NumberOfDirections() + b)];
  }

  /// The plane index of family @p p's normal; Families().Size() is the plane z = 0 (2D).
  const IntVec3& Normal(int p) const { return this->Normals[ToIndex(p)]; }

  /// Links of @p v within plane @p p, counter-clockwise around its normal, from the first link
  /// in the arrangement's order.
  void Around(std::int64_t v, int p, std::vector<PlaneArrangement::Link>& out) const
  {
    const std::vector<int>& rank = this->Ranks[ToIndex(p)];
    const int count = this->Counts[ToIndex(p)];
    out.clear();
    int first = 0;
    for (const auto* l = this->Arrangement.LinksBegin(v); l != this->Arrangement.LinksEnd(v); ++l)
    {
      const int r = rank[ToIndex(l->Direction)];
      if (r < 0)
        continue;
      if (out.empty())
        first = r;
      // Insertion by the angle from the first link (a vertex has a few links in a plane).
      const int key = (r - first + count) % count;
      std::size_t i = out.size();
      out.push_back(*l);
      for (; i > 0 && (rank[ToIndex(out[i - 1].Direction)] - first + count) % count > key; --i)
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
    const std::vector<int>& rank = this->Ranks[ToIndex(p)];
    const int count = this->Counts[ToIndex(p)];
    const int from = rank[ToIndex(back)];
    const PlaneArrangement::Link* best = nullptr;
    int bestKey = -1;
    bool found = false;
    for (const auto* l = this->Arrangement.LinksBegin(v); l != this->Arrangement.LinksEnd(v); ++l)
    {
      const int r = rank[ToIndex(l->Direction)];
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
    return this->Analysis.Label(this->Labels[ToIndex(v)]).Label;
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
    std::vector<int> rank(ToIndex(this->Arrangement.NumberOfDirections()), -1);
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
        rank[ToIndex(in[i])] = static_cast<int>(i);
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
      const std::uint64_t positive =
        tracer.PositiveSides(around[i].Direction, around[(i + 1) % around.size()].Direction);
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
      const auto side = [&](int sign) {
        return TypeToward(label, [&](int f) { return f == p ? sign : int((positive >> f) & 1u); });
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
  std::vector<FoundFaces> found(ToIndex((n + chunk - 1) / chunk));
  RunChunks(found.size(), threads,
    [&](std::size_t c)
    {
      std::vector<std::int64_t> loop;
      std::vector<PlaneArrangement::Link> around;
      const std::int64_t first = static_cast<std::int64_t>(c) * chunk;
      for (std::int64_t u = first; u < std::min(n, first + chunk); ++u)
        FacesFrom(tracer, u, mesh.Planar, found[c], loop, around);
    });
  std::vector<std::int32_t> pointOf(ToIndex(n), -1);
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
        auto& point = pointOf[ToIndex(v)];
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
  std::vector<std::vector<MeshFace>> found(ToIndex((n + chunk - 1) / chunk));
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
        found[c].push_back(
          { faces.Vertices[begin], faces.Types[f][0], planar ? 0 : faces.Types[f][1], measure });
        begin = faces.Ends[f];
      }
    });
  std::vector<MeshFace> out;
  for (const auto& faces : found)
    out.insert(out.end(), faces.begin(), faces.end());
  return out;
}

} // namespace msynth
