// SPDX-License-Identifier: BSD-3-Clause
#include "Formats/GltfFile.h"

#include "Core/AtomicFile.h"
#include "Core/Error.h"
#include "Core/Index.h"

#include <tiny_gltf.h> // Debian's libtinygltf holds the implementation

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <unordered_map>

namespace msynth
{
namespace
{
/// sRGB display value -> linear (the sRGB transfer function's inverse).
double Linear(double c)
{
  c = std::min(1.0, std::max(0.0, c));
  return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4);
}

/// Appends @p bytes to the buffer as a view; returns the view's index.
int AddView(tinygltf::Model& model, const void* bytes, std::size_t size, int target)
{
  auto& data = model.buffers[0].data;
  tinygltf::BufferView view;
  view.buffer = 0;
  view.byteOffset = data.size();
  view.byteLength = size;
  view.target = target;
  const auto* begin = static_cast<const unsigned char*>(bytes);
  data.insert(data.end(), begin, begin + size);
  model.bufferViews.push_back(view);
  return static_cast<int>(model.bufferViews.size() - 1);
}

using Vec = std::array<double, 3>;

Vec Sub(const Vec& a, const Vec& b)
{
  return { a[0] - b[0], a[1] - b[1], a[2] - b[2] };
}

Vec Cross(const Vec& a, const Vec& b)
{
  return { a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0] };
}

double Dot(const Vec& a, const Vec& b)
{
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

double Length(const Vec& a)
{
  return std::sqrt(Dot(a, a));
}

/// Corners of one polygon: where it turns by less than this share of its edges' lengths'
/// product it is straight.
constexpr double StraightSine = 1e-9;

/// The part's vertices by point and normal (the normal to a millionth), so polygons of one plane
/// share them and polygons meeting at an edge do not.
class FlatVertices
{
public:
  explicit FlatVertices(GltfPart& part)
    : Part(part)
  {
  }

  std::uint32_t Add(std::int64_t point, const Vec& position, const Vec& normal)
  {
    Key key{ point, std::llround(normal[0] * 1e6), std::llround(normal[1] * 1e6),
      std::llround(normal[2] * 1e6) };
    const auto found = this->Index.find(key);
    if (found != this->Index.end())
      return found->second;
    const std::uint32_t index = this->Push(position, normal);
    this->Index.emplace(key, index);
    return index;
  }

  /// A vertex of its own (a polygon's centre).
  std::uint32_t Push(const Vec& position, const Vec& normal)
  {
    if (this->Part.Positions.size() / 3 >= std::numeric_limits<std::uint32_t>::max())
      throw Error("mesh '" + this->Part.Name + "': more than 2^32 vertices");
    const auto index = static_cast<std::uint32_t>(this->Part.Positions.size() / 3);
    for (int c = 0; c < 3; ++c)
    {
      this->Part.Positions.push_back(static_cast<float>(position[ToIndex(c)]));
      this->Part.Normals.push_back(static_cast<float>(normal[ToIndex(c)]));
    }
    return index;
  }

private:
  struct Key
  {
    std::int64_t Point, X, Y, Z;
    bool operator==(const Key& o) const
    {
      return this->Point == o.Point && this->X == o.X && this->Y == o.Y && this->Z == o.Z;
    }
  };
  struct Hash
  {
    std::size_t operator()(const Key& k) const
    {
      std::uint64_t h = static_cast<std::uint64_t>(k.Point) * 0x9E3779B97F4A7C15ull;
      for (std::int64_t v : { k.X, k.Y, k.Z })
        h = (h ^ static_cast<std::uint64_t>(v)) * 0xBF58476D1CE4E5B9ull;
      return ToIndex(h ^ (h >> 31));
    }
  };
  GltfPart& Part;
  std::unordered_map<Key, std::uint32_t, Hash> Index;
};

/// Ear clipping of a polygon that is not convex, in its plane (normal @p n); @p corners are its
/// part's vertices, @p at their positions. Ears are strictly convex corners with no other corner
/// in or on their triangle; what is left when none is found (a self-touching polygon) is fanned.
void ClipEars(std::vector<std::uint32_t> corners, std::vector<Vec> at, const Vec& n,
  std::vector<std::uint32_t>& triangles)
{
  auto area = [&n](const Vec& a, const Vec& b, const Vec& c)
  { return Dot(Cross(Sub(b, a), Sub(c, b)), n); };
  while (corners.size() > 3)
  {
    const std::size_t m = corners.size();
    bool clipped = false;
    for (std::size_t i = 0; i < m && !clipped; ++i)
    {
      const Vec& a = at[(i + m - 1) % m];
      const Vec& b = at[i];
      const Vec& c = at[(i + 1) % m];
      if (area(a, b, c) <= StraightSine * Length(Sub(b, a)) * Length(Sub(c, b)))
        continue; // reflex or straight
      bool empty = true;
      for (std::size_t j = 0; j < m && empty; ++j)
      {
        if (j == i || j == (i + 1) % m || j == (i + m - 1) % m)
          continue;
        const Vec& p = at[j];
        empty = !(area(a, b, p) >= 0 && area(b, c, p) >= 0 && area(c, a, p) >= 0);
      }
      if (!empty)
        continue;
      triangles.insert(
        triangles.end(), { corners[(i + m - 1) % m], corners[i], corners[(i + 1) % m] });
      corners.erase(corners.begin() + static_cast<std::ptrdiff_t>(i));
      at.erase(at.begin() + static_cast<std::ptrdiff_t>(i));
      clipped = true;
    }
    if (!clipped)
      break;
  }
  for (std::size_t k = 1; k + 1 < corners.size(); ++k)
    if (Length(Cross(Sub(at[k], at[0]), Sub(at[k + 1], at[0]))) > 0)
      triangles.insert(triangles.end(), { corners[0], corners[k], corners[k + 1] });
}

void CheckPart(const std::string& path, const GltfPart& part)
{
  if (part.Positions.size() % 3 != 0)
    throw Error::InFile(path, "mesh '" + part.Name + "': positions are not in threes");
  if (!part.Normals.empty() && part.Normals.size() != part.Positions.size())
    throw Error::InFile(path, "mesh '" + part.Name + "': normals are not one per vertex");
  if (part.Triangles.size() % 3 != 0)
    throw Error::InFile(path, "mesh '" + part.Name + "': indices are not in threes");
  const std::size_t vertices = part.Positions.size() / 3;
  for (std::uint32_t index : part.Triangles)
    if (index >= vertices)
      throw Error::InFile(path,
        "mesh '" + part.Name + "': index " + std::to_string(index) + " beyond its " +
          std::to_string(vertices) + " vertices");
}

/// Adds one part as positions, indices, material, mesh and node.
void AddPart(tinygltf::Model& model, const GltfPart& part)
{
  const std::size_t vertices = part.Positions.size() / 3;
  std::vector<float> turned(part.Positions.size());
  std::vector<double> low(3, std::numeric_limits<double>::max());
  std::vector<double> high(3, std::numeric_limits<double>::lowest());
  for (std::size_t v = 0; v < vertices; ++v)
  {
    const float* p = &part.Positions[3 * v];
    const float q[3] = { p[0], p[2], -p[1] }; // z up -> y up
    for (int a = 0; a < 3; ++a)
    {
      turned[3 * v + ToIndex(a)] = q[a];
      low[ToIndex(a)] = std::min(low[ToIndex(a)], double(q[a]));
      high[ToIndex(a)] = std::max(high[ToIndex(a)], double(q[a]));
    }
  }
  tinygltf::Accessor positions;
  positions.bufferView =
    AddView(model, turned.data(), turned.size() * sizeof(float), TINYGLTF_TARGET_ARRAY_BUFFER);
  positions.componentType = TINYGLTF_COMPONENT_TYPE_FLOAT;
  positions.count = vertices;
  positions.type = TINYGLTF_TYPE_VEC3;
  positions.minValues = low;
  positions.maxValues = high;
  model.accessors.push_back(positions);
  const int positionAccessor = static_cast<int>(model.accessors.size() - 1);

  int normalAccessor = -1;
  if (!part.Normals.empty())
  {
    for (std::size_t v = 0; v < vertices; ++v)
    {
      const float* n = &part.Normals[3 * v];
      turned[3 * v] = n[0]; // z up -> y up, as the positions
      turned[3 * v + 1] = n[2];
      turned[3 * v + 2] = -n[1];
    }
    tinygltf::Accessor normals;
    normals.bufferView =
      AddView(model, turned.data(), turned.size() * sizeof(float), TINYGLTF_TARGET_ARRAY_BUFFER);
    normals.componentType = TINYGLTF_COMPONENT_TYPE_FLOAT;
    normals.count = vertices;
    normals.type = TINYGLTF_TYPE_VEC3;
    model.accessors.push_back(normals);
    normalAccessor = static_cast<int>(model.accessors.size() - 1);
  }

  tinygltf::Accessor indices;
  indices.bufferView = AddView(model, part.Triangles.data(),
    part.Triangles.size() * sizeof(std::uint32_t), TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER);
  indices.componentType = TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT;
  indices.count = part.Triangles.size();
  indices.type = TINYGLTF_TYPE_SCALAR;
  model.accessors.push_back(indices);

  tinygltf::Material material;
  material.name = part.Name;
  material.pbrMetallicRoughness.baseColorFactor = { Linear(part.Color[0]), Linear(part.Color[1]),
    Linear(part.Color[2]), std::min(1.0, std::max(0.0, part.Color[3])) };
  material.pbrMetallicRoughness.metallicFactor = 0.0;
  material.pbrMetallicRoughness.roughnessFactor = 1.0;
  if (part.Color[3] < 1.0)
    material.alphaMode = "BLEND";
  material.doubleSided = part.DoubleSided;
  model.materials.push_back(material);

  tinygltf::Primitive primitive;
  primitive.attributes["POSITION"] = positionAccessor;
  if (normalAccessor >= 0)
    primitive.attributes["NORMAL"] = normalAccessor;
  primitive.indices = static_cast<int>(model.accessors.size() - 1);
  primitive.material = static_cast<int>(model.materials.size() - 1);
  primitive.mode = TINYGLTF_MODE_TRIANGLES;
  tinygltf::Mesh mesh;
  mesh.name = part.Name;
  mesh.primitives.push_back(primitive);
  model.meshes.push_back(mesh);

  tinygltf::Node node;
  node.name = part.Name;
  node.mesh = static_cast<int>(model.meshes.size() - 1);
  model.nodes.push_back(node);
  model.scenes[0].nodes.push_back(static_cast<int>(model.nodes.size() - 1));
}
} // namespace

void AppendFlatPolygons(GltfPart& part, const std::vector<std::array<double, 3>>& points,
  const std::vector<std::vector<std::int32_t>>& polygons)
{
  FlatVertices vertices(part);
  std::vector<Vec> at;
  for (const auto& polygon : polygons)
  {
    const std::size_t n = polygon.size();
    if (n < 3)
      continue;
    at.clear();
    for (std::int32_t i : polygon)
    {
      if (i < 0 || ToIndex(i) >= points.size())
        throw Error("mesh '" + part.Name + "': corner " + std::to_string(i) + " beyond its " +
          std::to_string(points.size()) + " points");
      at.push_back(points[ToIndex(i)]);
    }
    Vec normal{ 0, 0, 0 }; // Newell's: twice the area along the normal
    for (std::size_t k = 0; k < n; ++k)
    {
      const Vec& a = at[k];
      const Vec& b = at[(k + 1) % n];
      normal[0] += (a[1] - b[1]) * (a[2] + b[2]);
      normal[1] += (a[2] - b[2]) * (a[0] + b[0]);
      normal[2] += (a[0] - b[0]) * (a[1] + b[1]);
    }
    const double twiceArea = Length(normal);
    if (!(twiceArea > 0))
      continue;
    for (double& c : normal)
      c /= twiceArea;
    bool convex = true, straight = false;
    for (std::size_t k = 0; k < n; ++k)
    {
      const Vec in = Sub(at[k], at[(k + n - 1) % n]);
      const Vec out = Sub(at[(k + 1) % n], at[k]);
      const double turn = Dot(Cross(in, out), normal);
      const double scale = StraightSine * Length(in) * Length(out);
      if (turn < -scale || (turn <= scale && Dot(in, out) <= 0))
        convex = false; // reflex, or turning back
      else if (turn <= scale)
        straight = true;
    }
    std::vector<std::uint32_t> corners(n);
    for (std::size_t k = 0; k < n; ++k)
      corners[k] = vertices.Add(polygon[k], at[k], normal);
    auto& triangles = part.Triangles;
    if (convex && !straight)
    {
      for (std::size_t k = 1; k + 1 < n; ++k)
        triangles.insert(triangles.end(), { corners[0], corners[k], corners[k + 1] });
    }
    else if (convex)
    {
      Vec centre{ 0, 0, 0 };
      for (const Vec& p : at)
        for (int c = 0; c < 3; ++c)
          centre[ToIndex(c)] += p[ToIndex(c)] / static_cast<double>(n);
      const std::uint32_t middle = vertices.Push(centre, normal);
      for (std::size_t k = 0; k < n; ++k)
        triangles.insert(triangles.end(), { middle, corners[k], corners[(k + 1) % n] });
    }
    else
    {
      ClipEars(corners, at, normal, triangles);
    }
  }
}

void WriteGlbFile(
  const std::string& path, const std::vector<GltfPart>& parts, const std::string& generator)
{
  std::size_t bytes = 0;
  for (const GltfPart& part : parts)
  {
    CheckPart(path, part);
    bytes += part.Positions.size() * sizeof(float) + part.Triangles.size() * sizeof(std::uint32_t);
  }
  // A .glb's lengths are 32-bit: the binary chunk and the JSON must fit in 4 GiB together.
  constexpr std::size_t Limit = (std::size_t(1) << 32) - (std::size_t(1) << 24);
  if (bytes > Limit)
    throw Error::InFile(path,
      "the mesh needs " + std::to_string(bytes >> 20) +
        " MiB, more than a binary glTF file can hold (4 GiB)");

  tinygltf::Model model;
  model.asset.version = "2.0";
  model.asset.generator = generator;
  model.buffers.resize(1);
  model.buffers[0].data.reserve(bytes);
  model.scenes.resize(1);
  model.defaultScene = 0;
  for (const GltfPart& part : parts)
    if (!part.Triangles.empty())
      AddPart(model, part);
  if (model.buffers[0].data.empty())
  {
    // No triangles: the asset alone (glTF allows no empty buffer, and tinygltf writes an empty
    // scene as null, which the validator rejects).
    model.buffers.clear();
    model.scenes.clear();
    model.defaultScene = -1;
  }

  WriteFileAtomically(path,
    [&](std::ostream& out)
    {
      tinygltf::TinyGLTF writer;
      if (!writer.WriteGltfSceneToStream(&model, out, false, true))
        throw Error::InFile(path, "the glTF writer failed");
    });
}
} // namespace msynth
