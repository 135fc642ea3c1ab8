// SPDX-License-Identifier: BSD-3-Clause
// The parts of a polyhedral model and their comparison with the example's (ModelStructure.h).
#include "Continuous/ModelStructure.h"

#include "Core/Error.h"
#include "Core/Index.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <deque>

namespace msynth
{

const TypeStructure* ModelStructure::Find(int type) const
{
  for (const auto& t : this->Types)
    if (t.Type == type)
      return &t;
  return nullptr;
}

namespace
{
/// A face crossing a column: at height Z, entering (+1) or leaving (-1) Type going up.
struct Crossing
{
  std::int64_t Column = 0;
  double Z = 0;
  int Type = 0;
  int Delta = 0;
  bool operator<(const Crossing& o) const
  {
    return this->Column < o.Column || (this->Column == o.Column && this->Z < o.Z);
  }
};

// Off-lattice fractions of a voxel keep ray and voxel centres off the model's planes.
constexpr double NudgeX = 0.0123456;
constexpr double NudgeY = 0.0234567;
constexpr double NudgeZ = 0.0345678;

bool InsidePolygon2D(
  const std::vector<Point3>& points, const std::vector<int>& face, double x, double y)
{
  bool inside = false;
  for (std::size_t i = 0, j = face.size() - 1; i < face.size(); j = i++)
  {
    const Point3& a = points[ToIndex(face[i])];
    const Point3& b = points[ToIndex(face[j])];
    if ((a[1] > y) != (b[1] > y) && x < (b[0] - a[0]) * (y - a[1]) / (b[1] - a[1]) + a[0])
      inside = !inside;
  }
  return inside;
}

/// Every non-vertical face's crossings with the vertical rays through the column centres.
std::vector<Crossing> Crossings(const PolyhedralExample& model, const TypeVoxels& g)
{
  std::vector<Crossing> crossings;
  for (std::size_t f = 0; f < model.Faces.size(); ++f)
  {
    const auto& face = model.Faces[f];
    if (face.size() < 3)
      continue;
    // Newell's normal (outward: faces are counter-clockwise seen from outside).
    Point3 n{ 0, 0, 0 };
    Point3 lo{ HUGE_VAL, HUGE_VAL, 0 }, hi{ -HUGE_VAL, -HUGE_VAL, 0 };
    for (std::size_t i = 0; i < face.size(); ++i)
    {
      const Point3& a = model.Points[ToIndex(face[i])];
      const Point3& b = model.Points[ToIndex(face[(i + 1) % face.size()])];
      n[0] += (a[1] - b[1]) * (a[2] + b[2]);
      n[1] += (a[2] - b[2]) * (a[0] + b[0]);
      n[2] += (a[0] - b[0]) * (a[1] + b[1]);
      for (int k = 0; k < 2; ++k)
      {
        lo[k] = std::min(lo[k], a[k]);
        hi[k] = std::max(hi[k], a[k]);
      }
    }
    const double length = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    if (!(length > 0) || std::abs(n[2]) < 1e-9 * length)
      continue; // vertical: no ray crosses it
    const Point3& p0 = model.Points[ToIndex(face[0])];
    const double d = n[0] * p0[0] + n[1] * p0[1] + n[2] * p0[2];
    const int type = model.ObjectTypes[ToIndex(model.FaceObject[f])];
    auto column = [&](double v, int k)
    {
      const double nudge = k == 0 ? NudgeX : NudgeY;
      return static_cast<std::int64_t>(std::floor((v - g.Origin[ToIndex(k)]) / g.Voxel - nudge));
    };
    for (std::int64_t y = std::max<std::int64_t>(0, column(lo[1], 1));
         y <= std::min(g.Dims[1] - 1, column(hi[1], 1)); ++y)
    {
      const double cy = g.Origin[1] + (static_cast<double>(y) + 0.5 + NudgeY) * g.Voxel;
      for (std::int64_t x = std::max<std::int64_t>(0, column(lo[0], 0));
           x <= std::min(g.Dims[0] - 1, column(hi[0], 0)); ++x)
      {
        const double cx = g.Origin[0] + (static_cast<double>(x) + 0.5 + NudgeX) * g.Voxel;
        if (InsidePolygon2D(model.Points, face, cx, cy))
          crossings.push_back(
            { x + g.Dims[0] * y, (d - n[0] * cx - n[1] * cy) / n[2], type, n[2] > 0 ? -1 : 1 });
      }
    }
  }
  std::sort(crossings.begin(), crossings.end());
  return crossings;
}

} // namespace

TypeVoxels ClassifyTypes(const PolyhedralExample& model, double voxel)
{
  Point3 lo{ HUGE_VAL, HUGE_VAL, HUGE_VAL }, hi{ -HUGE_VAL, -HUGE_VAL, -HUGE_VAL };
  for (const auto& p : model.Points)
    for (int k = 0; k < 3; ++k)
    {
      lo[ToIndex(k)] = std::min(lo[ToIndex(k)], p[ToIndex(k)]);
      hi[ToIndex(k)] = std::max(hi[ToIndex(k)], p[ToIndex(k)]);
    }
  TypeVoxels g;
  g.Origin = lo;
  g.Voxel = voxel;
  for (;; g.Voxel *= 1.25)
  {
    double sites = 1;
    for (int k = 0; k < 3; ++k)
    {
      g.Dims[ToIndex(k)] = std::max<std::int64_t>(
        1, static_cast<std::int64_t>(std::ceil((hi[ToIndex(k)] - lo[ToIndex(k)]) / g.Voxel)));
      sites *= static_cast<double>(g.Dims[ToIndex(k)]);
    }
    if (sites <= static_cast<double>(1 << 23))
      break;
  }
  g.Types.assign(ToIndex(g.Dims[0] * g.Dims[1] * g.Dims[2]), 0);
  const std::vector<Crossing> crossings = Crossings(model, g);
  std::map<int, int> inside;
  for (std::size_t i = 0; i < crossings.size();)
  {
    const std::int64_t column = crossings[i].Column;
    inside.clear();
    std::int64_t z = 0;
    for (; i < crossings.size() && crossings[i].Column == column; ++i)
    {
      const Crossing& c = crossings[i];
      // Voxels whose centres lie below this crossing take the types entered so far.
      const double top = (c.Z - g.Origin[2]) / g.Voxel - 0.5 - NudgeZ;
      const std::int64_t below = std::min(g.Dims[2], static_cast<std::int64_t>(std::ceil(top)));
      int type = 0;
      for (const auto& [t, count] : inside)
        if (count > 0)
        {
          type = t;
          break;
        }
      for (; z < below; ++z)
        g.Types[ToIndex(column + g.Dims[0] * g.Dims[1] * z)] = type;
      inside[c.Type] += c.Delta;
    }
  }
  return g;
}

namespace
{
double Median(std::vector<double> v)
{
  if (v.empty())
    return 0;
  std::sort(v.begin(), v.end());
  const std::size_t m = v.size() / 2;
  return v.size() % 2 ? v[m] : 0.5 * (v[m - 1] + v[m]);
}

/// Per type, the number of columns up to (x, y) holding that type at some height (2D prefix
/// sums with a zero row and column in front).
std::map<int, std::vector<std::int64_t>> Presence(const TypeVoxels& g)
{
  const std::int64_t nx = g.Dims[0], ny = g.Dims[1];
  std::map<int, std::vector<std::int64_t>> sums;
  for (std::int64_t z = 0; z < g.Dims[2]; ++z)
    for (std::int64_t y = 0; y < ny; ++y)
      for (std::int64_t x = 0; x < nx; ++x)
      {
        const int t = g.Types[ToIndex(g.Index(x, y, z))];
        if (t == 0)
          continue;
        auto& s = sums[t];
        if (s.empty())
          s.assign(ToIndex((nx + 1) * (ny + 1)), 0);
        s[ToIndex((x + 1) + (nx + 1) * (y + 1))] = 1;
      }
  for (auto& [t, s] : sums)
    for (std::int64_t y = 1; y <= ny; ++y)
      for (std::int64_t x = 1; x <= nx; ++x)
        s[ToIndex(x + (nx + 1) * y)] += s[ToIndex(x - 1 + (nx + 1) * y)] +
          s[ToIndex(x + (nx + 1) * (y - 1))] - s[ToIndex(x - 1 + (nx + 1) * (y - 1))];
  return sums;
}

/// The parts of every type: 6-connected voxels of one type, found breadth first.
void FindParts(const TypeVoxels& g, double reach, ModelStructure& out)
{
  const auto presence = Presence(g);
  const std::int64_t grow = static_cast<std::int64_t>(std::ceil(reach / g.Voxel - 1e-9));
  const std::int64_t nx = g.Dims[0], ny = g.Dims[1], nz = g.Dims[2];
  std::vector<char> seen(g.Types.size(), 0);
  std::map<int, TypeStructure> types;
  std::deque<std::int64_t> queue;
  std::vector<std::int64_t> columns; // of the part being found
  const double v = g.Voxel;
  for (std::int64_t start = 0; start < static_cast<std::int64_t>(g.Types.size()); ++start)
  {
    const int t = g.Types[ToIndex(start)];
    if (t == 0 || seen[ToIndex(start)])
      continue;
    std::array<std::int64_t, 6> box{ nx, ny, nz, -1, -1, -1 };
    std::int64_t voxels = 0;
    columns.clear();
    queue.assign(1, start);
    seen[ToIndex(start)] = 1;
    while (!queue.empty())
    {
      const std::int64_t i = queue.front();
      queue.pop_front();
      ++voxels;
      columns.push_back(i % (nx * ny));
      const std::array<std::int64_t, 3> at{ i % nx, (i / nx) % ny, i / (nx * ny) };
      for (int k = 0; k < 3; ++k)
      {
        box[ToIndex(k)] = std::min(box[ToIndex(k)], at[ToIndex(k)]);
        box[ToIndex(k + 3)] = std::max(box[ToIndex(k + 3)], at[ToIndex(k)]);
      }
      const std::int64_t step[3] = { 1, nx, nx * ny };
      for (int k = 0; k < 3; ++k)
        for (int s : { -1, 1 })
        {
          const std::int64_t c = at[ToIndex(k)] + s;
          const std::int64_t j = i + s * step[k];
          if (c >= 0 && c < g.Dims[ToIndex(k)] && !seen[ToIndex(j)] && g.Types[ToIndex(j)] == t)
          {
            seen[ToIndex(j)] = 1;
            queue.push_back(j);
          }
        }
    }
    StructurePart part;
    const double sx = static_cast<double>(box[3] - box[0] + 1) * v;
    const double sy = static_cast<double>(box[4] - box[1] + 1) * v;
    part.Footprint = sx * sy;
    part.Span = std::max(sx, sy);
    part.Height = static_cast<double>(box[5] - box[2] + 1) * v;
    part.Volume = static_cast<double>(voxels) * v * v * v;
    std::sort(columns.begin(), columns.end());
    part.Ground =
      static_cast<double>(std::unique(columns.begin(), columns.end()) - columns.begin()) * v * v;
    const std::int64_t x0 = std::max<std::int64_t>(0, box[0] - grow);
    const std::int64_t y0 = std::max<std::int64_t>(0, box[1] - grow);
    const std::int64_t x1 = std::min(nx, box[3] + grow + 1);
    const std::int64_t y1 = std::min(ny, box[4] + grow + 1);
    for (const auto& entry : presence)
    {
      const int other = entry.first;
      const auto& s = entry.second;
      const auto at = [&](std::int64_t x, std::int64_t y) { return s[ToIndex(x + (nx + 1) * y)]; };
      if (other != t && at(x1, y1) - at(x0, y1) - at(x1, y0) + at(x0, y0) > 0)
        part.Fronts.push_back(other);
    }
    types[t].Parts.push_back(std::move(part));
  }
  for (auto& [t, ts] : types)
  {
    ts.Type = t;
    std::stable_sort(ts.Parts.begin(), ts.Parts.end(),
      [](const StructurePart& a, const StructurePart& b) { return a.Volume > b.Volume; });
    std::vector<double> footprints, heights;
    for (const auto& p : ts.Parts)
    {
      footprints.push_back(p.Footprint);
      heights.push_back(p.Height);
      ts.Volume += p.Volume;
      for (int other : p.Fronts)
        ts.Fronting[other] += 1.0 / static_cast<double>(ts.Parts.size());
    }
    ts.MedianFootprint = Median(footprints);
    ts.MedianHeight = Median(heights);
    ts.PartsPer100 =
      out.GroundArea > 0 ? 100.0 * static_cast<double>(ts.Parts.size()) / out.GroundArea : 0.0;
    out.Types.push_back(std::move(ts));
  }
}
} // namespace

ModelStructure MeasureStructure(const PolyhedralExample& model, double voxel, double reach)
{
  if (model.Planar)
    throw Error("the structure of a model is measured in 3D; '" + model.Source + "' is planar");
  if (!(voxel > 0) || !(reach >= 0) || !std::isfinite(voxel) || !std::isfinite(reach))
    throw Error("the structure of a model needs a positive voxel and reach");
  ModelStructure out;
  out.Reach = reach;
  if (model.Points.empty())
  {
    out.Voxel = voxel;
    return out;
  }
  const TypeVoxels g = ClassifyTypes(model, voxel);
  out.Voxel = g.Voxel;
  out.GroundArea = static_cast<double>(g.Dims[0] * g.Dims[1]) * g.Voxel * g.Voxel;
  FindParts(g, reach, out);
  return out;
}

namespace
{
std::string Named(int type, const std::map<int, std::string>& names)
{
  const auto it = names.find(type);
  return it != names.end() && !it->second.empty() ? it->second : "type " + std::to_string(type);
}

bool Within(double model, double example, double factor)
{
  return example > 0 ? model >= example / factor && model <= example * factor : model == 0;
}
} // namespace

std::vector<ResemblanceItem> CompareStructure(const ModelStructure& example,
  const ModelStructure& model, const std::map<int, std::string>& typeNames)
{
  std::vector<ResemblanceItem> items;
  double width = 0; // the example's longest part span decides network types
  for (const auto& e : example.Types)
    if (!e.Parts.empty())
      width = std::max(width, e.Parts.front().Span);
  for (const auto& e : example.Types)
  {
    const std::string name = Named(e.Type, typeNames);
    const TypeStructure* m = model.Find(e.Type);
    const TypeStructure none;
    const TypeStructure& mt = m ? *m : none;
    double longest = 0;
    bool sparse = false; // a part covering under half its box on the ground: a network's shape
    for (const auto& p : e.Parts)
      if (p.Span > longest)
      {
        longest = p.Span;
        sparse = p.Ground < 0.5 * p.Footprint;
      }
    if (e.Parts.size() <= 2 && sparse && longest >= 0.5 * width && width > 0)
    {
      // A network: as large as the model lets it be, so its size and count say nothing, and it
      // fronts nearly everything; what counts is how much of it is in network-sized parts.
      double networked = 0;
      for (const auto& p : mt.Parts)
        networked += p.Span >= 0.5 * longest ? p.Volume : 0.0;
      const double share = mt.Volume > 0 ? networked / mt.Volume : 0.0;
      items.push_back({ name + ": volume share in networks (parts spanning half the example's)",
        1.0, share, ">= 0.9", share >= 0.9 });
      continue;
    }
    if (e.Parts.size() >= 3)
      items.push_back({ name + ": parts per 100 square units of ground", e.PartsPer100,
        mt.PartsPer100, "0.5-2x", Within(mt.PartsPer100, e.PartsPer100, 2) });
    items.push_back({ name + ": median footprint (square units)", e.MedianFootprint,
      mt.MedianFootprint, "0.5-2x", Within(mt.MedianFootprint, e.MedianFootprint, 2) });
    for (const auto& [other, share] : e.Fronting)
    {
      if (share < 0.5)
        continue;
      const auto it = mt.Fronting.find(other);
      const double got = it != mt.Fronting.end() ? it->second : 0.0;
      items.push_back({ name + ": share of parts fronting " + Named(other, typeNames), share, got,
        ">= 0.8x", got >= 0.8 * share - 1e-12 });
    }
  }
  return items;
}

double StructureVoxel(double spacing, double extent)
{
  return spacing > 0 ? 0.5 * spacing : extent / 40.0;
}

double StructureReach(double spacing, double extent)
{
  return spacing > 0 ? 2.0 * spacing : extent / 15.0;
}

} // namespace msynth
