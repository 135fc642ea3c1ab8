// SPDX-License-Identifier: BSD-3-Clause
#include "Formats/PolyhedralExample.h"

#include "Continuous/Point3Math.h"
#include "Core/Error.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <fstream>
#include <numeric>
#include <sstream>

namespace msynth
{

using point3::Dot;
using point3::Norm;
using point3::Sub;

namespace
{

/// Newell's normal of a polygon (length = twice its area).
Point3 NewellNormal(const std::vector<Point3>& points, const std::vector<int>& face)
{
  Point3 n{ 0, 0, 0 };
  for (std::size_t i = 0; i < face.size(); ++i)
  {
    const Point3& a = points[face[i]];
    const Point3& b = points[face[(i + 1) % face.size()]];
    n[0] += (a[1] - b[1]) * (a[2] + b[2]);
    n[1] += (a[2] - b[2]) * (a[0] + b[0]);
    n[2] += (a[0] - b[0]) * (a[1] + b[1]);
  }
  return n;
}

/// "Cube.001" → "Cube", "roof_2" → "roof", "wall" → "wall".
std::string BaseName(const std::string& name)
{
  std::size_t end = name.size();
  while (end > 0 && std::isdigit(static_cast<unsigned char>(name[end - 1])))
  {
    --end;
  }
  if (end < name.size() && end > 0 && (name[end - 1] == '.' || name[end - 1] == '_'))
  {
    return name.substr(0, end - 1);
  }
  return name;
}

std::string ObjectDescription(const PolyhedralExample& e, int object)
{
  const std::string& name = e.ObjectNames.at(object);
  return "object '" + name + "'";
}

} // namespace

double PolyhedralExample::Diagonal() const
{
  if (this->Points.empty())
  {
    return 0.0;
  }
  Point3 lo = this->Points[0], hi = this->Points[0];
  for (const auto& p : this->Points)
  {
    for (int c = 0; c < 3; ++c)
    {
      lo[c] = std::min(lo[c], p[c]);
      hi[c] = std::max(hi[c], p[c]);
    }
  }
  return Norm(Sub(hi, lo));
}

// ---------------------------------------------------------------------------------------------
PolyhedralExample ReadOBJExample(const std::string& path, const ObjectTypeOptions& options)
{
  std::ifstream in(path, std::ios::binary);
  if (!in)
  {
    throw Error::InFile(path, "cannot be opened");
  }
  return ReadOBJExample(in, path, options);
}

namespace
{
/// The error of an OBJ line: "NAME: line N: PROBLEM".
Error LineError(const std::string& name, long lineNumber, const std::string& problem)
{
  return Error::InFile(name, "line " + std::to_string(lineNumber) + ": " + problem);
}

/// The three coordinates of a "v" line. @throw Error naming the file and line.
Point3 ParseVertex(std::istringstream& words, const std::string& name, long lineNumber)
{
  Point3 p{};
  for (auto& c : p)
  {
    std::string token;
    if (!(words >> token))
    {
      throw LineError(name, lineNumber, "a vertex needs three coordinates");
    }
    char* end = nullptr;
    c = std::strtod(token.c_str(), &end);
    if (end == token.c_str() || *end != '\0' || !std::isfinite(c))
    {
      throw LineError(name, lineNumber, "'" + token + "' is not a finite number");
    }
  }
  return p;
}

/// The type of the object named @p objectName: its own or its base name's in the options,
/// else the type given to its base name before, else the next free one (recorded in
/// @p autoTypes). Not checked for range.
int ObjectTypeOf(const std::string& objectName, const ObjectTypeOptions& options,
  std::map<std::string, int>& autoTypes)
{
  const std::string base = BaseName(objectName);
  if (options.TypeOfName.count(objectName))
  {
    return options.TypeOfName.at(objectName);
  }
  if (options.TypeOfName.count(base))
  {
    return options.TypeOfName.at(base);
  }
  auto t = autoTypes.find(base);
  if (t == autoTypes.end())
  {
    int next = 1;
    for (const auto& [n, v] : options.TypeOfName)
    {
      (void)n;
      next = std::max(next, v + 1);
    }
    for (const auto& [n, v] : autoTypes)
    {
      (void)n;
      next = std::max(next, v + 1);
    }
    t = autoTypes.emplace(base, next).first;
  }
  return t->second;
}

/// The vertex indices of an "f" line (1-based or negative = relative, "i/t/n" forms), as
/// 0-based indices into the @p count vertices read so far. @throw Error naming file and line.
std::vector<int> ParseFace(
  std::istringstream& words, long count, const std::string& name, long lineNumber)
{
  std::vector<int> face;
  std::string token;
  while (words >> token)
  {
    const std::string index = token.substr(0, token.find('/'));
    char* end = nullptr;
    const long value = std::strtol(index.c_str(), &end, 10);
    if (index.empty() || *end != '\0')
    {
      throw LineError(name, lineNumber, "'" + token + "' is not a vertex index");
    }
    const long resolved = value < 0 ? count + value : value - 1;
    if (value == 0 || resolved < 0 || resolved >= count)
    {
      throw LineError(name, lineNumber,
        "vertex index " + index + " is out of range (" + std::to_string(count) +
          " vertices so far)");
    }
    face.push_back(static_cast<int>(resolved));
  }
  if (face.size() < 3)
  {
    throw LineError(name, lineNumber, "a face needs at least three vertices");
  }
  return face;
}
} // namespace

PolyhedralExample ReadOBJExample(
  std::istream& in, const std::string& name, const ObjectTypeOptions& options)
{
  PolyhedralExample example;
  example.Source = name;
  std::map<std::string, int> objectOfName;
  std::map<std::string, int> autoTypes;
  std::string currentName = "object";
  int currentObject = -1;
  std::string line;
  long lineNumber = 0;
  while (std::getline(in, line))
  {
    ++lineNumber;
    if (!line.empty() && line.back() == '\r')
    {
      line.pop_back();
    }
    std::istringstream words(line);
    std::string keyword;
    if (!(words >> keyword) || keyword[0] == '#')
    {
      continue;
    }
    if (keyword == "v")
    {
      example.Points.push_back(ParseVertex(words, name, lineNumber));
    }
    else if (keyword == "o" || keyword == "g")
    {
      std::string rest;
      std::getline(words >> std::ws, rest);
      currentName = rest.empty() ? "object" : rest;
      currentObject = -1;
    }
    else if (keyword == "f")
    {
      if (currentObject < 0)
      {
        auto found = objectOfName.find(currentName);
        if (found == objectOfName.end())
        {
          const int type = ObjectTypeOf(currentName, options, autoTypes);
          if (type < 1 || type > 32767)
          {
            throw LineError(name, lineNumber,
              "object '" + currentName + "' maps to type " + std::to_string(type) +
                "; types are 1..32767 (0 is empty space)");
          }
          example.TypeNames.emplace(type, BaseName(currentName));
          found = objectOfName.emplace(currentName, example.NumberOfObjects()).first;
          example.ObjectTypes.push_back(type);
          example.ObjectNames.push_back(currentName);
        }
        currentObject = found->second;
      }
      example.Faces.push_back(
        ParseFace(words, static_cast<long>(example.Points.size()), name, lineNumber));
      example.FaceObject.push_back(currentObject);
    }
  }
  if (in.bad())
  {
    throw Error::InFile(name, "read error");
  }
  if (example.Faces.empty())
  {
    throw Error::InFile(name, "contains no faces");
  }
  return example;
}

void AssignObjectsByConnectivity(PolyhedralExample& example, const std::vector<int>& faceTypes)
{
  const std::size_t n = example.Faces.size();
  std::vector<std::size_t> parent(n);
  std::iota(parent.begin(), parent.end(), 0);
  auto find = [&parent](std::size_t i)
  {
    while (parent[i] != i)
    {
      i = parent[i] = parent[parent[i]];
    }
    return i;
  };
  std::map<std::pair<int, int>, std::size_t> firstFaceOfEdge;
  for (std::size_t f = 0; f < n; ++f)
  {
    const auto& face = example.Faces[f];
    for (std::size_t i = 0; i < face.size(); ++i)
    {
      const int a = face[i], b = face[(i + 1) % face.size()];
      auto [it, inserted] =
        firstFaceOfEdge.emplace(std::make_pair(std::min(a, b), std::max(a, b)), f);
      if (!inserted && faceTypes[it->second] == faceTypes[f])
      {
        parent[find(f)] = find(it->second);
      }
    }
  }
  std::map<std::size_t, int> objectOfRoot;
  example.FaceObject.assign(n, 0);
  example.ObjectTypes.clear();
  example.ObjectNames.clear();
  for (std::size_t f = 0; f < n; ++f)
  {
    const std::size_t root = find(f);
    auto it = objectOfRoot.find(root);
    if (it == objectOfRoot.end())
    {
      it = objectOfRoot.emplace(root, example.NumberOfObjects()).first;
      example.ObjectTypes.push_back(faceTypes[f]);
      example.ObjectNames.push_back("object " + std::to_string(it->second + 1));
    }
    example.FaceObject[f] = it->second;
  }
}

// ---------------------------------------------------------------------------------------------
namespace
{

/// A face is a simple polygon in its plane (seen along axis @p drop, its normal's largest
/// component): no repeated vertex and no two non-adjacent edges meet. CGAL's face triangulation
/// (for the self-intersection test) needs it: a pinched face corrupts its mesh. @p diagonal is
/// the example's bounding-box diagonal. @throw Error.
void CheckSimplePolygon(const PolyhedralExample& e, const std::vector<int>& face, int drop,
  double diagonal, const std::string& where)
{
  const int u = drop == 0 ? 1 : 0, v = drop == 2 ? 1 : 2;
  std::vector<Point3> points;
  points.reserve(face.size());
  for (int index : face)
  {
    points.push_back({ e.Points[index][u], e.Points[index][v], 0.0 });
  }
  const std::size_t m = face.size();
  for (std::size_t i = 0; i < m; ++i)
  {
    const Point3& a = points[i];
    const Point3& b = points[(i + 1) % m];
    if (Norm(Sub(a, b)) <= 1e-12 * diagonal)
    {
      throw Error::InFile(e.Source, where + " has a repeated vertex");
    }
    for (std::size_t j = i + 2; j < m; ++j)
    {
      if (i == 0 && j == m - 1)
      {
        continue;
      }
      const Point3& c = points[j];
      const Point3& d = points[(j + 1) % m];
      auto orient = [](const Point3& p, const Point3& q, const Point3& r)
      { return (q[0] - p[0]) * (r[1] - p[1]) - (q[1] - p[1]) * (r[0] - p[0]); };
      // p on segment qr, given that the three are collinear.
      auto within = [](const Point3& q, const Point3& r, const Point3& p)
      {
        return std::min(q[0], r[0]) <= p[0] && p[0] <= std::max(q[0], r[0]) &&
          std::min(q[1], r[1]) <= p[1] && p[1] <= std::max(q[1], r[1]);
      };
      const double o1 = orient(a, b, c), o2 = orient(a, b, d), o3 = orient(c, d, a),
                   o4 = orient(c, d, b);
      const bool crossing =
        ((o1 > 0 && o2 < 0) || (o1 < 0 && o2 > 0)) && ((o3 > 0 && o4 < 0) || (o3 < 0 && o4 > 0));
      // Touching or overlapping: an endpoint on the other segment (collinear edges of a plus
      // shape that lie on one line but apart are not).
      const bool touching = (o1 == 0 && within(a, b, c)) || (o2 == 0 && within(a, b, d)) ||
        (o3 == 0 && within(c, d, a)) || (o4 == 0 && within(c, d, b));
      if (crossing || touching)
      {
        throw Error::InFile(e.Source,
          where + " intersects itself (edges " + std::to_string(i + 1) + " and " +
            std::to_string(j + 1) + ")");
      }
    }
  }
}

void Validate2D(PolyhedralExample& e)
{
  const double diagonal = e.Diagonal();
  const double areaTolerance = 1e-12 * diagonal * diagonal;
  for (std::size_t f = 0; f < e.Faces.size(); ++f)
  {
    auto& face = e.Faces[f];
    const std::string where =
      "polygon " + std::to_string(f + 1) + " of " + ObjectDescription(e, e.FaceObject[f]);
    const Point3 n = NewellNormal(e.Points, face);
    if (std::abs(n[2]) <= areaTolerance)
    {
      throw Error::InFile(e.Source, where + " is degenerate (zero area)");
    }
    if (n[2] < 0)
    {
      std::reverse(face.begin(), face.end());
    }
    CheckSimplePolygon(e, face, 2, diagonal, where);
  }
}

/// Face @p f of a 3D example (of bounding-box diagonal @p diagonal): no vertex twice, an area,
/// planar, a simple polygon. @throw Error.
void CheckFace3D(const PolyhedralExample& e, std::size_t f, double diagonal)
{
  const double planarTolerance = 1e-5 * diagonal;
  const double areaTolerance = 1e-12 * diagonal * diagonal;
  const auto& face = e.Faces[f];
  const std::string where =
    "face " + std::to_string(f + 1) + " of " + ObjectDescription(e, e.FaceObject[f]);
  std::vector<int> sorted = face;
  std::sort(sorted.begin(), sorted.end());
  if (std::adjacent_find(sorted.begin(), sorted.end()) != sorted.end())
  {
    throw Error::InFile(e.Source, where + " is degenerate: it uses a vertex twice");
  }
  const Point3 n = NewellNormal(e.Points, face);
  const double length = Norm(n);
  if (length <= areaTolerance)
  {
    throw Error::InFile(e.Source, where + " is degenerate (zero area)");
  }
  const Point3 unit{ n[0] / length, n[1] / length, n[2] / length };
  const Point3& origin = e.Points[face[0]];
  for (int v : face)
  {
    const double off = std::abs(Dot(unit, Sub(e.Points[v], origin)));
    if (off > planarTolerance)
    {
      throw Error::InFile(e.Source,
        where + " is not planar: vertex " + std::to_string(v + 1) + " is " + std::to_string(off) +
          " off its plane");
    }
  }
  int drop = 0;
  for (int c = 1; c < 3; ++c)
  {
    drop = std::abs(unit[c]) > std::abs(unit[drop]) ? c : drop;
  }
  CheckSimplePolygon(e, face, drop, diagonal, where);
}

/// Per undirected edge (lower vertex first), the faces that use it and whether each goes from
/// the lower vertex to the higher.
using EdgeUses = std::map<std::pair<int, int>, std::vector<std::pair<std::size_t, bool>>>;

/// Each undirected edge of an object (@p what) used by exactly two faces, once in each
/// direction. @throw Error naming the edge and faces.
void CheckEdgesOf(const PolyhedralExample& e, const std::string& what, const EdgeUses& uses)
{
  for (const auto& [edge, list] : uses)
  {
    const std::string edgeText =
      "edge (" + std::to_string(edge.first + 1) + ", " + std::to_string(edge.second + 1) + ")";
    if (list.size() == 1)
    {
      throw Error::InFile(e.Source,
        what + " is not closed: " + edgeText + " belongs to face " +
          std::to_string(list[0].first + 1) + " only");
    }
    if (list.size() > 2)
    {
      throw Error::InFile(e.Source,
        what + " is non-manifold: " + edgeText + " is shared by " + std::to_string(list.size()) +
          " faces");
    }
    if (list[0].second == list[1].second)
    {
      throw Error::InFile(e.Source,
        what + " has inconsistent orientation: faces " + std::to_string(list[0].first + 1) +
          " and " + std::to_string(list[1].first + 1) + " traverse " + edgeText +
          " in the same direction");
    }
  }
}

/// Each vertex of an object (@p what): its faces form one fan (connected through the edges at
/// the vertex). Every edge has two uses (CheckEdgesOf). @throw Error naming the vertex.
void CheckVertexFansOf(const PolyhedralExample& e, const std::string& what, const EdgeUses& uses,
  const std::map<int, std::vector<std::size_t>>& facesAtVertex)
{
  std::map<std::size_t, std::size_t> parent;
  auto find = [&parent](std::size_t i)
  {
    while (parent[i] != i)
    {
      i = parent[i] = parent[parent[i]];
    }
    return i;
  };
  std::map<int, std::vector<std::pair<std::size_t, std::size_t>>> linksAtVertex;
  for (const auto& [edge, list] : uses)
  {
    linksAtVertex[edge.first].emplace_back(list[0].first, list[1].first);
    linksAtVertex[edge.second].emplace_back(list[0].first, list[1].first);
  }
  for (const auto& [vertex, faces] : facesAtVertex)
  {
    parent.clear();
    for (auto f : faces)
    {
      parent[f] = f;
    }
    for (const auto& [f1, f2] : linksAtVertex[vertex])
    {
      parent[find(f1)] = find(f2);
    }
    std::size_t roots = 0;
    for (const auto& [f, up] : parent)
    {
      roots += f == up ? 1 : 0;
    }
    if (roots > 1)
    {
      throw Error::InFile(e.Source,
        what + " is non-manifold at vertex " + std::to_string(vertex + 1) +
          " (its faces there form " + std::to_string(roots) + " separate fans)");
    }
  }
}

/// Orientation of object @p o (@p what): the enclosed volume must be positive; an
/// inward-facing object is turned. @throw Error when it encloses no volume.
void OrientObject(PolyhedralExample& e, int o, const std::string& what, double diagonal)
{
  double volume = 0;
  for (std::size_t f = 0; f < e.Faces.size(); ++f)
  {
    if (e.FaceObject[f] == o)
    {
      volume += Dot(e.Points[e.Faces[f][0]], NewellNormal(e.Points, e.Faces[f])) / 6.0;
    }
  }
  if (std::abs(volume) <= 1e-12 * diagonal * diagonal * diagonal)
  {
    throw Error::InFile(e.Source, what + " encloses no volume");
  }
  if (volume < 0)
  {
    for (std::size_t f = 0; f < e.Faces.size(); ++f)
    {
      if (e.FaceObject[f] == o)
      {
        std::reverse(e.Faces[f].begin(), e.Faces[f].end());
      }
    }
  }
}

/// A 3D example: every face valid (CheckFace3D), every object a closed, manifold,
/// consistently oriented, outward-facing (turned if need be), non-self-intersecting solid.
/// @throw Error naming the file and the object.
void Validate3D(PolyhedralExample& e)
{
  const double diagonal = e.Diagonal();
  for (std::size_t f = 0; f < e.Faces.size(); ++f)
  {
    CheckFace3D(e, f, diagonal);
  }
  for (int o = 0; o < e.NumberOfObjects(); ++o)
  {
    const std::string what = ObjectDescription(e, o);
    // Each undirected edge: used by exactly two faces, once in each direction.
    EdgeUses uses;
    std::map<int, std::vector<std::size_t>> facesAtVertex;
    for (std::size_t f = 0; f < e.Faces.size(); ++f)
    {
      if (e.FaceObject[f] != o)
      {
        continue;
      }
      const auto& face = e.Faces[f];
      for (std::size_t i = 0; i < face.size(); ++i)
      {
        const int a = face[i], b = face[(i + 1) % face.size()];
        uses[{ std::min(a, b), std::max(a, b) }].emplace_back(f, a < b);
        facesAtVertex[a].push_back(f);
      }
    }
    CheckEdgesOf(e, what, uses);
    CheckVertexFansOf(e, what, uses, facesAtVertex);
    OrientObject(e, o, what, diagonal);
    if (ObjectSelfIntersects(e, o))
    {
      throw Error::InFile(e.Source, what + " is self-intersecting");
    }
  }
}

} // namespace

void TurnYUpToZUp(PolyhedralExample& example)
{
  for (Point3& p : example.Points)
  {
    p = { p[0], p[2] == 0.0 ? 0.0 : -p[2], p[1] }; // no −0 in a flat example's y
  }
}

void ValidateExample(PolyhedralExample& example)
{
  if (example.Faces.empty())
  {
    throw Error::InFile(example.Source, "contains no faces");
  }
  if (example.FaceObject.size() != example.Faces.size())
  {
    throw Error::InFile(example.Source, "faces and object ids differ in number");
  }
  for (std::size_t f = 0; f < example.Faces.size(); ++f)
  {
    const int o = example.FaceObject[f];
    if (o < 0 || o >= example.NumberOfObjects())
    {
      throw Error::InFile(example.Source, "face " + std::to_string(f + 1) + " has no valid object");
    }
    if (example.Faces[f].size() < 3)
    {
      throw Error::InFile(
        example.Source, "face " + std::to_string(f + 1) + " has fewer than three vertices");
    }
    for (int v : example.Faces[f])
    {
      if (v < 0 || v >= static_cast<int>(example.Points.size()))
      {
        throw Error::InFile(
          example.Source, "face " + std::to_string(f + 1) + " uses a missing vertex");
      }
    }
  }
  if (example.ObjectNames.size() != example.ObjectTypes.size())
  {
    example.ObjectNames.resize(example.ObjectTypes.size());
    for (std::size_t o = 0; o < example.ObjectNames.size(); ++o)
    {
      if (example.ObjectNames[o].empty())
      {
        example.ObjectNames[o] = "object " + std::to_string(o + 1);
      }
    }
  }
  for (int t : example.ObjectTypes)
  {
    if (t < 1 || t > 32767)
    {
      throw Error::InFile(example.Source,
        "object type " + std::to_string(t) + " is out of range 1..32767 (0 is empty space)");
    }
  }
  const double tolerance = 1e-9 * example.Diagonal();
  bool flat = true;
  for (const auto& face : example.Faces)
  {
    for (int v : face)
    {
      flat = flat && std::abs(example.Points[v][2]) <= tolerance;
    }
  }
  example.Planar = flat;
  if (flat)
  {
    Validate2D(example);
  }
  else
  {
    Validate3D(example);
  }
}

std::vector<BoundaryElement> BoundaryOf(const PolyhedralExample& example)
{
  std::vector<BoundaryElement> out;
  if (!example.Planar)
  {
    for (std::size_t f = 0; f < example.Faces.size(); ++f)
    {
      BoundaryElement element;
      element.Object = example.FaceObject[f];
      element.Points = example.Faces[f];
      const Point3 n = NewellNormal(example.Points, example.Faces[f]);
      const double length = Norm(n);
      element.Normal = { n[0] / length, n[1] / length, n[2] / length };
      out.push_back(std::move(element));
    }
    return out;
  }
  // 2D: the directed polygon edges of an object whose reverse the object does not also use.
  for (int o = 0; o < example.NumberOfObjects(); ++o)
  {
    std::map<std::pair<int, int>, int> directed;
    std::vector<std::pair<int, int>> order;
    for (std::size_t f = 0; f < example.Faces.size(); ++f)
    {
      if (example.FaceObject[f] != o)
      {
        continue;
      }
      const auto& face = example.Faces[f];
      for (std::size_t i = 0; i < face.size(); ++i)
      {
        const std::pair<int, int> edge{ face[i], face[(i + 1) % face.size()] };
        if (++directed[edge] > 1)
        {
          throw Error::InFile(example.Source,
            ObjectDescription(example, o) + " has overlapping polygons (edge " +
              std::to_string(edge.first + 1) + "→" + std::to_string(edge.second + 1) +
              " is used twice)");
        }
        order.push_back(edge);
      }
    }
    for (const auto& edge : order)
    {
      if (directed.count({ edge.second, edge.first }))
      {
        continue; // shared by two polygons of the object: interior
      }
      BoundaryElement element;
      element.Object = o;
      element.Points = { edge.first, edge.second };
      const Point3 d = Sub(example.Points[edge.second], example.Points[edge.first]);
      const double length = std::hypot(d[0], d[1]);
      element.Normal = { d[1] / length, -d[0] / length, 0.0 };
      out.push_back(std::move(element));
    }
  }
  return out;
}

} // namespace msynth
