// SPDX-License-Identifier: BSD-3-Clause
#include "Continuous/PolyhedralAnalysis.h"

#include "Continuous/BoxGrid.h"
#include "Continuous/Point3Math.h"
#include "Core/Error.h"
#include "Core/Index.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <set>

namespace msynth
{

using point3::Add;
using point3::Dot;
using point3::Norm;
using point3::Sub;
using point3::Unit;

namespace
{

/// Distance from @p p to the segment [a, b].
double SegmentDistance(const Point3& p, const Point3& a, const Point3& b)
{
  const Point3 ab = Sub(b, a);
  const double len2 = Dot(ab, ab);
  double t = len2 > 0 ? Dot(Sub(p, a), ab) / len2 : 0.0;
  t = std::clamp(t, 0.0, 1.0);
  return Norm(Sub(p, Add(a, ab, t)));
}

std::int64_t Gcd64(std::int64_t a, std::int64_t b)
{
  a = a < 0 ? -a : a;
  b = b < 0 ? -b : b;
  while (b != 0)
  {
    const std::int64_t t = a % b;
    a = b;
    b = t;
  }
  return a;
}

/// A key that identifies (up to the tolerance) a position, to count each feature once.
std::array<std::int64_t, 3> PositionKey(const Point3& p, double cell)
{
  return { std::llround(p[0] / cell), std::llround(p[1] / cell), std::llround(p[2] / cell) };
}

} // namespace

IntVec3 SnapDirection(const Point3& unit, double angleTolerance, int maxSmallInteger)
{
  const double m = std::max({ std::abs(unit[0]), std::abs(unit[1]), std::abs(unit[2]) });
  if (!(m > 0) || !std::isfinite(m))
  {
    throw Error("cannot snap a zero or non-finite direction");
  }
  const Point3 u = Unit(unit);
  auto within = [&](const IntVec3& v, double tolerance)
  {
    const Point3 w{ double(v[0]), double(v[1]), double(v[2]) };
    const double n = Norm(w);
    if (n == 0)
    {
      return false;
    }
    const double sine = Norm(point3::Cross(w, u)) / n;
    return Dot(w, u) > 0 && sine <= std::sin(tolerance);
  };
  auto reduced = [](IntVec3 v)
  {
    const std::int64_t g = Gcd64(Gcd64(v[0], v[1]), v[2]);
    if (g > 1)
    {
      for (auto& c : v)
      {
        c /= g;
      }
    }
    return v;
  };
  // The smallest integers within the tolerance, unless larger ones (up to the limit) give the
  // direction exactly: a model synthesized on snapped directions, used as an example, keeps its
  // own directions (a neighbour within the tolerance would spread its faces' positions, and the
  // spacing derived from them would collapse into a huge arrangement).
  IntVec3 first{};
  bool found = false;
  for (int n = 1; n <= maxSmallInteger; ++n)
  {
    const IntVec3 v{ std::llround(unit[0] / m * n), std::llround(unit[1] / m * n),
      std::llround(unit[2] / m * n) };
    if (within(v, std::min(1e-9, angleTolerance)))
    {
      return reduced(v);
    }
    if (!found && within(v, angleTolerance))
    {
      first = v;
      found = true;
    }
  }
  if (found)
  {
    return reduced(first);
  }
  for (int n = maxSmallInteger + 1; n <= 4096; ++n)
  {
    const IntVec3 v{ std::llround(unit[0] / m * n), std::llround(unit[1] / m * n),
      std::llround(unit[2] / m * n) };
    if (within(v, std::min(1e-9, angleTolerance)))
    {
      return reduced(v); // exactly a direction of integers up to 4096: no 24-bit approximation
    }
  }
  constexpr double scale = double(1 << 24);
  return reduced({ std::llround(unit[0] / m * scale), std::llround(unit[1] / m * scale),
    std::llround(unit[2] / m * scale) });
}

// ---------------------------------------------------------------------------------------------
NeighbourhoodProbe::NeighbourhoodProbe(const PolyhedralExample& model,
  const PlaneFamilySet& families, const std::vector<Point3>& familyUnitNormals,
  double angleTolerance)
  : Model(model)
  , Set(families)
  , Elements(BoundaryOf(model))
{
  const double diagonal = model.Diagonal();
  this->Tol = std::max(1e-7 * diagonal, 1e-12);
  const double cosine = std::cos(angleTolerance);
  double shortest = diagonal;
  for (std::size_t e = 0; e < this->Elements.size(); ++e)
  {
    const auto& element = this->Elements[e];
    int family = -1;
    for (std::size_t f = 0; f < familyUnitNormals.size() && family < 0; ++f)
    {
      if (std::abs(Dot(element.Normal, familyUnitNormals[f])) >= cosine)
      {
        family = static_cast<int>(f);
      }
    }
    if (family < 0)
    {
      throw Error::InFile(model.Source,
        std::string(model.Planar ? "edge " : "face ") + std::to_string(e + 1) +
          " has a direction in none of the example's plane families");
    }
    this->Family.push_back(family);
    Point3 lo = model.Points[element.Points[0]], hi = lo;
    const std::size_t n = element.Points.size();
    for (std::size_t i = 0; i < n; ++i)
    {
      const Point3& p = model.Points[element.Points[i]];
      for (int c = 0; c < 3; ++c)
      {
        lo[c] = std::min(lo[c], p[c]);
        hi[c] = std::max(hi[c], p[c]);
      }
      const double length = Norm(Sub(model.Points[element.Points[(i + 1) % n]], p));
      if (length > 0)
      {
        shortest = std::min(shortest, length);
      }
    }
    this->Boxes.push_back({ lo, hi });
  }
  this->Offset = std::min(1e-3 * diagonal, 0.05 * shortest);
  this->Classifier = std::make_unique<SolidClassifier>(model);

  this->Grid = std::make_unique<BoxGrid>(this->Boxes, this->Tol);
}

NeighbourhoodProbe::~NeighbourhoodProbe() = default;

bool NeighbourhoodProbe::ElementContains(std::size_t e, const Point3& p) const
{
  const auto& box = this->Boxes[e];
  for (int c = 0; c < 3; ++c)
  {
    if (p[c] < box[0][c] - this->Tol || p[c] > box[1][c] + this->Tol)
    {
      return false;
    }
  }
  const auto& element = this->Elements[e];
  const auto& pts = this->Model.Points;
  if (this->Model.Planar)
  {
    return SegmentDistance(p, pts[element.Points[0]], pts[element.Points[1]]) <= this->Tol;
  }
  const Point3& origin = pts[element.Points[0]];
  if (std::abs(Dot(element.Normal, Sub(p, origin))) > this->Tol)
  {
    return false;
  }
  // Crossing test in the projection that drops the normal's largest component; points within
  // the tolerance of the polygon's boundary count as inside.
  int drop = 0;
  for (int c = 1; c < 3; ++c)
  {
    if (std::abs(element.Normal[c]) > std::abs(element.Normal[drop]))
    {
      drop = c;
    }
  }
  const int i = (drop + 1) % 3, j = (drop + 2) % 3;
  bool inside = false;
  const std::size_t n = element.Points.size();
  for (std::size_t k = 0; k < n; ++k)
  {
    const Point3& a = pts[element.Points[k]];
    const Point3& b = pts[element.Points[(k + 1) % n]];
    if (SegmentDistance(p, a, b) <= this->Tol)
    {
      return true;
    }
    if ((a[j] > p[j]) != (b[j] > p[j]))
    {
      const double x = a[i] + (p[j] - a[j]) * (b[i] - a[i]) / (b[j] - a[j]);
      inside = x > p[i] ? !inside : inside;
    }
  }
  return inside;
}

std::vector<std::size_t> NeighbourhoodProbe::ElementsThrough(const Point3& p) const
{
  std::vector<std::size_t> elements;
  for (std::uint32_t e : this->Grid->Candidates(p))
  {
    if (this->ElementContains(e, p))
    {
      elements.push_back(e);
    }
  }
  return elements;
}

std::vector<int> NeighbourhoodProbe::FamiliesThrough(const Point3& p) const
{
  return this->FamiliesOf(this->ElementsThrough(p));
}

std::vector<int> NeighbourhoodProbe::FamiliesOf(const std::vector<std::size_t>& elements) const
{
  std::vector<int> families;
  for (std::size_t e : elements)
  {
    families.push_back(this->Family[e]);
  }
  std::sort(families.begin(), families.end());
  families.erase(std::unique(families.begin(), families.end()), families.end());
  return families;
}

NeighbourhoodLabel NeighbourhoodProbe::LabelAt(const Point3& p) const
{
  return this->LabelAt(p, this->ElementsThrough(p));
}

NeighbourhoodLabel NeighbourhoodProbe::LabelAt(
  const Point3& p, const std::vector<std::size_t>& elements) const
{
  const double distance = this->ProbeDistance();
  return NeighbourhoodLabel::FromFunction(this->Set, this->FamiliesOf(elements),
    [&](const PlaneFamilySet::Cone& cone)
    {
      const int object = this->Classifier->ObjectAt(Add(p, cone.UnitDirection, distance));
      return object < 0 ? 0 : this->Model.ObjectTypes[object];
    });
}

// ---------------------------------------------------------------------------------------------
namespace
{

/// Parameters t in (0, 1) where segment [a, b] meets segment [c, d] lying in the same plane
/// (coordinates i, j of the projection).
void SegmentBreaks(const Point3& a, const Point3& b, const Point3& c, const Point3& d, int i, int j,
  double tol, std::vector<double>& out)
{
  const double rx = b[i] - a[i], ry = b[j] - a[j];
  const double sx = d[i] - c[i], sy = d[j] - c[j];
  const double length = std::hypot(rx, ry);
  const double slength = std::hypot(sx, sy);
  if (length <= tol || slength <= tol)
  {
    return;
  }
  const double denom = rx * sy - ry * sx;
  const double qx = c[i] - a[i], qy = c[j] - a[j];
  if (std::abs(denom) > 1e-12 * length * slength)
  {
    const double t = (qx * sy - qy * sx) / denom;
    const double u = (qx * ry - qy * rx) / denom;
    const double ut = tol / slength;
    if (u >= -ut && u <= 1 + ut)
    {
      out.push_back(t);
    }
    return;
  }
  // Parallel: when collinear, the other segment's endpoints split this one.
  if (std::abs(qx * ry - qy * rx) / length > tol)
  {
    return;
  }
  out.push_back((qx * rx + qy * ry) / (length * length));
  out.push_back(((d[i] - a[i]) * rx + (d[j] - a[j]) * ry) / (length * length));
}

} // namespace

namespace
{
/// The plane families of the example (§4.5.1): one per direction of its boundary elements, snapped
/// to small integers; their unit normals go to @p units.
std::vector<IntVec3> FindFamilies(const PolyhedralExample& example,
  const PolyhedralAnalysis::Options& options, std::vector<Point3>& units)
{
  std::vector<IntVec3> normals;
  const double cosine = std::cos(options.AngleTolerance);
  for (const auto& element : BoundaryOf(example))
  {
    bool known = false;
    for (const auto& u : units)
    {
      known = known || std::abs(Dot(u, element.Normal)) >= cosine;
    }
    if (!known)
    {
      normals.push_back(
        SnapDirection(element.Normal, options.AngleTolerance, options.MaxSmallInteger));
      const auto& n = normals.back();
      units.push_back(Unit({ double(n[0]), double(n[1]), double(n[2]) }));
    }
  }
  return normals;
}

/**
 * The features of the example sampled for their neighbourhood labels (§4.3): every vertex, every
 * piece of an edge between the points where other objects split it, and the face beside each
 * piece; each label once, with how often it occurs.
 */
class FeatureSampler
{
public:
  FeatureSampler(const PolyhedralExample& example, const NeighbourhoodProbe& probe,
    std::vector<PolyhedralAnalysis::Feature>& samples, const std::vector<BoundaryElement>& elements)
    : Example(example)
    , Probe(probe)
    , Samples(samples)
    , Elements(elements)
    , Tol(probe.Tolerance())
    , Cell(10 * probe.Tolerance())
    , Planar(example.Planar)
    , SeveralObjects(example.NumberOfObjects() > 1)
    , LabelsOfElement(elements.size())
  {
    std::vector<std::array<Point3, 2>> boxes;
    const auto& pts = example.Points;
    for (const auto& element : elements)
    {
      std::array<Point3, 2> box{ pts[element.Points[0]], pts[element.Points[0]] };
      for (int v : element.Points)
      {
        for (int c = 0; c < 3; ++c)
        {
          box[0][c] = std::min(box[0][c], pts[v][c]);
          box[1][c] = std::max(box[1][c], pts[v][c]);
        }
      }
      boxes.push_back(box);
    }
    this->ElementGrid = BoxGrid(boxes, this->Tol);
  }

  /// Samples everything: the volumes, the vertices first (so that a point shared by several
  /// features counts as a vertex), then edges and faces.
  void Run()
  {
    this->AddLabel(NeighbourhoodLabel::Constant(0), 1); // the exterior
    for (int type : this->Example.ObjectTypes)
    {
      this->AddLabel(NeighbourhoodLabel::Constant(type), 1); // each object type's interior
    }
    const auto& pts = this->Example.Points;
    for (const auto& element : this->Elements)
    {
      for (int v : element.Points)
      {
        this->Sample(
          this->Planar ? FeatureKind::Edge : FeatureKind::Vertex, pts[v], pts[v], pts[v], -1);
      }
    }
    for (std::size_t e = 0; e < this->Elements.size(); ++e)
    {
      this->SampleEdgesOf(e);
    }
  }

  const std::vector<NeighbourhoodLabel>& Labels() const { return this->LabelList; }
  const std::vector<std::int64_t>& Counts() const { return this->CountList; }
  const std::vector<std::set<int>>& LabelsOf() const { return this->LabelsOfElement; }

private:
  int AddLabel(const NeighbourhoodLabel& label, std::int64_t count)
  {
    auto it = this->Found.find(label);
    if (it == this->Found.end())
    {
      it = this->Found.emplace(label, static_cast<int>(this->LabelList.size())).first;
      this->LabelList.push_back(label);
      this->CountList.push_back(0);
    }
    this->CountList[ToIndex(it->second)] += count;
    return it->second;
  }

  void Sample(FeatureKind kind, const Point3& at, const Point3& a, const Point3& b, int element)
  {
    if (!this->Seen.insert(PositionKey(at, this->Cell)).second)
    {
      return;
    }
    PolyhedralAnalysis::Feature feature;
    feature.Kind = kind;
    feature.A = a;
    feature.B = b;
    feature.Element = element;
    const auto through = this->Probe.ElementsThrough(at);
    feature.Label = this->AddLabel(this->Probe.LabelAt(at, through), 1);
    this->Samples.push_back(feature);
    if (element >= 0)
    {
      // Every face through the sample has this label there (coplanar faces of other objects
      // included), so a face partly covered by another object is known to have several.
      this->LabelsOfElement[ToIndex(element)].insert(feature.Label);
      for (std::size_t e : through)
      {
        this->LabelsOfElement[e].insert(feature.Label);
      }
    }
  }

  /// Where elements of other objects split the segment (lo, hi), as fractions along it.
  const std::vector<double>& BreaksOf(int lo, int hi, int object)
  {
    auto it = this->Breaks.find({ lo, hi });
    if (it != this->Breaks.end())
    {
      return it->second;
    }
    const auto& pts = this->Example.Points;
    const Point3& a = pts[lo];
    const Point3& b = pts[hi];
    const double length = Norm(Sub(b, a));
    std::vector<double> ts;
    const Point3 segmentLow{ std::min(a[0], b[0]), std::min(a[1], b[1]), std::min(a[2], b[2]) };
    const Point3 segmentHigh{ std::max(a[0], b[0]), std::max(a[1], b[1]), std::max(a[2], b[2]) };
    // Only elements whose box (grown by the tolerance) meets the segment's can split it.
    const std::vector<std::uint32_t> near = this->SeveralObjects
      ? this->ElementGrid.Overlapping(segmentLow, segmentHigh)
      : std::vector<std::uint32_t>();
    for (const std::uint32_t g : near)
    {
      if (this->Elements[g].Object != object)
      {
        this->BreaksBy(g, a, b, ts);
      }
    }
    const double margin = this->Tol / std::max(length, this->Tol);
    std::vector<double> kept;
    std::sort(ts.begin(), ts.end());
    for (double t : ts)
    {
      if (t > margin && t < 1 - margin && (kept.empty() || t - kept.back() > margin))
      {
        kept.push_back(t);
      }
    }
    return this->Breaks.emplace(std::make_pair(lo, hi), kept).first->second;
  }

  /// The points where element @p g splits the segment (a, b), appended to @p ts.
  void BreaksBy(std::uint32_t g, const Point3& a, const Point3& b, std::vector<double>& ts) const
  {
    const auto& pts = this->Example.Points;
    const auto& other = this->Elements[g];
    const std::size_t n = other.Points.size();
    const double tol = this->Tol;
    if (this->Planar)
    {
      SegmentBreaks(a, b, pts[other.Points[0]], pts[other.Points[1]], 0, 1, tol, ts);
      return;
    }
    const Point3& origin = pts[other.Points[0]];
    const double da = Dot(other.Normal, Sub(a, origin));
    const double db = Dot(other.Normal, Sub(b, origin));
    if (std::abs(da) <= tol && std::abs(db) <= tol)
    {
      int drop = 0;
      for (int c = 1; c < 3; ++c)
      {
        drop = std::abs(other.Normal[c]) > std::abs(other.Normal[drop]) ? c : drop;
      }
      for (std::size_t k = 0; k < n; ++k)
      {
        SegmentBreaks(a, b, pts[other.Points[k]], pts[other.Points[(k + 1) % n]], (drop + 1) % 3,
          (drop + 2) % 3, tol, ts);
      }
    }
    else if ((da > tol && db > tol) || (da < -tol && db < -tol))
    {
      return;
    }
    else if (std::abs(da - db) > 0)
    {
      // Keep the crossing only where it lies on the other face.
      const double t = da / (da - db);
      if (this->Probe.ElementContains(g, Add(a, Sub(b, a), t)))
      {
        ts.push_back(t);
      }
    }
  }

  /// The pieces of an edge, as fractions in order from @p from to @p to.
  std::vector<double> Pieces(int from, int to, int object)
  {
    const int lo = std::min(from, to), hi = std::max(from, to);
    std::vector<double> ts = this->BreaksOf(lo, hi, object);
    if (from != lo)
    {
      for (auto& t : ts)
      {
        t = 1 - t;
      }
      std::reverse(ts.begin(), ts.end());
    }
    ts.insert(ts.begin(), 0.0);
    ts.push_back(1.0);
    return ts;
  }

  /// Element @p e's edges (3D: polygon edges; 2D: the segment): split points, pieces, faces.
  void SampleEdgesOf(std::size_t e)
  {
    const auto& pts = this->Example.Points;
    const auto& element = this->Elements[e];
    const std::size_t n = this->Planar ? 1 : element.Points.size();
    for (std::size_t k = 0; k < n; ++k)
    {
      const int from = element.Points[k], to = element.Points[(k + 1) % element.Points.size()];
      const Point3& a = pts[from];
      const Point3 ab = Sub(pts[to], a);
      const auto ts = this->Pieces(from, to, element.Object);
      for (std::size_t s = 1; s + 1 < ts.size(); ++s)
      {
        const Point3 split = Add(a, ab, ts[s]);
        this->Sample(
          this->Planar ? FeatureKind::Edge : FeatureKind::Vertex, split, split, split, -1);
      }
      for (std::size_t s = 0; s + 1 < ts.size(); ++s)
      {
        const Point3 p = Add(a, ab, ts[s]), q = Add(a, ab, ts[s + 1]);
        const Point3 middle = Add(a, ab, 0.5 * (ts[s] + ts[s + 1]));
        if (this->Planar)
        {
          this->Sample(FeatureKind::Face, middle, p, q, static_cast<int>(e));
          continue;
        }
        this->Sample(FeatureKind::Edge, middle, p, q, -1);
        // The face beside this piece.
        const Point3 inward = Unit(point3::Cross(element.Normal, ab));
        const Point3 inside = Add(middle, inward, this->Probe.FaceOffset());
        this->Sample(FeatureKind::Face, inside, inside, inside, static_cast<int>(e));
      }
    }
  }

  const PolyhedralExample& Example;
  const NeighbourhoodProbe& Probe;
  std::vector<PolyhedralAnalysis::Feature>& Samples;
  const std::vector<BoundaryElement>& Elements;
  const double Tol, Cell;
  const bool Planar, SeveralObjects;
  BoxGrid ElementGrid;
  std::map<NeighbourhoodLabel, int> Found;
  std::vector<NeighbourhoodLabel> LabelList;
  std::vector<std::int64_t> CountList;
  std::set<std::array<std::int64_t, 3>> Seen;
  std::vector<std::set<int>> LabelsOfElement;
  std::map<std::pair<int, int>, std::vector<double>> Breaks; ///< by (low, high) point index
};
} // namespace

namespace
{
/// Volume (3D, divergence theorem over the outward faces) or area (2D, shoelace over the
/// counter-clockwise polygons) per object type, and the bounding box.
void MeasureTypes(
  const PolyhedralExample& example, std::map<int, double>& volumes, Point3& low, Point3& high)
{
  for (std::size_t i = 0; i < example.Points.size(); ++i)
  {
    for (std::size_t c = 0; c < 3; ++c)
    {
      low[c] = i == 0 ? example.Points[i][c] : std::min(low[c], example.Points[i][c]);
      high[c] = i == 0 ? example.Points[i][c] : std::max(high[c], example.Points[i][c]);
    }
  }
  for (std::size_t f = 0; f < example.Faces.size(); ++f)
  {
    const int type = example.ObjectTypes.at(ToIndex(example.FaceObject[f]));
    volumes[type] += point3::FanMeasure(example.Points, example.Faces[f], example.Planar);
  }
}
} // namespace

PolyhedralAnalysis PolyhedralAnalysis::Analyze(
  const PolyhedralExample& example, const Options& options)
{
  PolyhedralAnalysis analysis;
  analysis.Used = options;
  analysis.IsPlanar = example.Planar;
  analysis.Set =
    std::make_shared<PlaneFamilySet>(FindFamilies(example, options, analysis.UnitNormals));
  const NeighbourhoodProbe probe(
    example, *analysis.Set, analysis.UnitNormals, options.AngleTolerance);
  analysis.Elements = probe.Boundary();
  analysis.Family = probe.ElementFamily();
  FeatureSampler sampler(example, probe, analysis.Samples, analysis.Elements);
  sampler.Run();
  const auto& labels = sampler.Labels();

  // Ids in a canonical order: by codimension, then families, then types.
  std::vector<int> order(labels.size());
  std::iota(order.begin(), order.end(), 0);
  const PlaneFamilySet& set = *analysis.Set;
  std::sort(order.begin(), order.end(),
    [&](int x, int y)
    {
      const int rx = set.Rank(labels[x].Families), ry = set.Rank(labels[y].Families);
      return rx != ry ? rx < ry : labels[x] < labels[y];
    });
  std::vector<int> idOf(labels.size());
  for (std::size_t i = 0; i < order.size(); ++i)
  {
    idOf[order[i]] = static_cast<int>(i);
    LabelInfo info;
    info.Label = labels[order[i]];
    info.Kind = info.Label.Kind(set);
    info.Occurrences = sampler.Counts()[order[i]];
    info.Expression = info.Label.Expression(example.Planar);
    analysis.IdOf.emplace(info.Label, static_cast<int>(i));
    analysis.Catalog.push_back(std::move(info));
  }
  for (auto& feature : analysis.Samples)
  {
    feature.Label = idOf[feature.Label];
  }
  MeasureTypes(example, analysis.Volumes, analysis.BoundsLow, analysis.BoundsHigh);
  analysis.ElementLabels.assign(analysis.Elements.size(), -1);
  for (std::size_t e = 0; e < analysis.Elements.size(); ++e)
  {
    const auto& of = sampler.LabelsOf()[e];
    if (of.size() == 1)
    {
      analysis.ElementLabels[e] = idOf[*of.begin()];
    }
  }
  return analysis;
}

int PolyhedralAnalysis::Find(const NeighbourhoodLabel& label) const
{
  auto it = this->IdOf.find(label);
  return it == this->IdOf.end() ? -1 : it->second;
}

std::vector<int> PolyhedralAnalysis::AllowedLabels(std::vector<int> families) const
{
  std::sort(families.begin(), families.end());
  std::vector<int> allowed;
  for (int id = 0; id < this->NumberOfLabels(); ++id)
  {
    const auto& f = this->Catalog[id].Label.Families;
    if (std::includes(families.begin(), families.end(), f.begin(), f.end()))
    {
      allowed.push_back(id);
    }
  }
  return allowed;
}

} // namespace msynth
