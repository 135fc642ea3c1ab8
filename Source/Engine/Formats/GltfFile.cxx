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

void CheckPart(const std::string& path, const GltfPart& part)
{
  if (part.Positions.size() % 3 != 0)
    throw Error::InFile(path, "mesh '" + part.Name + "': positions are not in threes");
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
  model.materials.push_back(material);

  tinygltf::Primitive primitive;
  primitive.attributes["POSITION"] = static_cast<int>(model.accessors.size() - 2);
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
