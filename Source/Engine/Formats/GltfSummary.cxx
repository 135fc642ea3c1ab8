// SPDX-License-Identifier: BSD-3-Clause
#include "Formats/GltfSummary.h"

#include "Core/Error.h"
#include "Core/Index.h"

#include <tiny_gltf.h> // Debian's libtinygltf holds the implementation

#include <sys/stat.h>

#include <fstream>
#include <limits>

namespace msynth
{
namespace
{
// ---------------------------------------------------------------------------------------------
// internal
// ---------------------------------------------------------------------------------------------
constexpr std::uint64_t MaximumFileBytes = std::uint64_t(1) << 31;
constexpr int MaximumNesting = 64;

std::uint32_t U32(const std::vector<std::uint8_t>& b, std::size_t at)
{
  return std::uint32_t(b[at]) | std::uint32_t(b[at + 1]) << 8 | std::uint32_t(b[at + 2]) << 16 |
    std::uint32_t(b[at + 3]) << 24;
}

/// The .glb container's header and chunks, checked against the data's size (tinygltf 2.7's own
/// check lets the binary chunk reach 8 bytes past the end).
void CheckContainer(const std::vector<std::uint8_t>& b, const std::string& name)
{
  const std::uint64_t size = b.size();
  if (size < 20 || U32(b, 0) != 0x46546C67)
    throw Error::InFile(name, "is not a binary glTF file (no 'glTF' header)");
  if (U32(b, 4) != 2)
    throw Error::InFile(
      name, "is binary glTF version " + std::to_string(U32(b, 4)) + "; only version 2 is read");
  const std::uint64_t length = U32(b, 8);
  if (length != size)
    throw Error::InFile(name,
      "is truncated or damaged (its header says " + std::to_string(length) +
        " bytes, the file has " + std::to_string(size) + ")");
  const std::uint64_t json = U32(b, 12);
  if (U32(b, 16) != 0x4E4F534A || json < 2 || 20 + json > size)
    throw Error::InFile(name, "is damaged (its JSON chunk is missing or runs past the end)");
  std::uint64_t at = 20 + json;
  while (at < size)
  {
    if (at + 8 > size || at + 8 + std::uint64_t(U32(b, ToIndex(at))) > size)
      throw Error::InFile(name, "is damaged (a chunk runs past the end of the file)");
    at += 8 + std::uint64_t(U32(b, ToIndex(at)));
  }
}

/// The nesting of @p text's arrays and objects, bounded (a parser's recursion, or the
/// destruction of what it made, must not run out of stack on a hostile file).
void CheckNesting(const char* text, std::size_t size, const std::string& name)
{
  int depth = 0;
  bool quoted = false;
  for (std::size_t i = 0; i < size; ++i)
  {
    const char c = text[i];
    if (quoted)
    {
      if (c == '\\')
        ++i;
      else if (c == '"')
        quoted = false;
    }
    else if (c == '"')
      quoted = true;
    else if ((c == '[' || c == '{') && ++depth > MaximumNesting)
      throw Error::InFile(name,
        "is not a glTF file we read (JSON nested deeper than " + std::to_string(MaximumNesting) +
          " levels)");
    else if (c == ']' || c == '}')
      --depth;
  }
}

bool NoImage(tinygltf::Image*, const int, std::string*, std::string*, int, int,
  const unsigned char*, int, void*)
{
  return true; // images are not decoded: info reports geometry and materials
}

bool Exists(const std::string& path, void* folder)
{
  struct stat info;
  return static_cast<const std::string*>(folder)->size() > 0 && ::stat(path.c_str(), &info) == 0;
}

std::string Expand(const std::string& path, void*)
{
  return path;
}

bool ReadWhole(std::vector<unsigned char>* out, std::string* err, const std::string& path, void*)
{
  struct stat info;
  if (::stat(path.c_str(), &info) != 0 || !S_ISREG(info.st_mode) ||
    std::uint64_t(info.st_size) > MaximumFileBytes)
  {
    *err = "'" + path + "' is missing, not a file or larger than 2 GiB";
    return false;
  }
  std::ifstream in(path, std::ios::binary);
  out->resize(ToIndex(info.st_size));
  in.read(reinterpret_cast<char*>(out->data()), static_cast<std::streamsize>(out->size()));
  if (!in)
    *err = "'" + path + "' could not be read";
  return static_cast<bool>(in);
}

bool NoWrite(std::string*, const std::string&, const std::vector<unsigned char>&, void*)
{
  return false;
}

/// Accessor @p a of @p model: its view inside its buffer and its elements inside its view.
void CheckAccessor(const tinygltf::Model& model, int a, const std::string& name)
{
  const std::string what = "accessor " + std::to_string(a);
  if (a < 0 || a >= static_cast<int>(model.accessors.size()))
    throw Error::InFile(name, "is damaged (a primitive names " + what + ", which is missing)");
  const tinygltf::Accessor& accessor = model.accessors[ToIndex(a)];
  const int components =
    tinygltf::GetNumComponentsInType(static_cast<std::uint32_t>(accessor.type));
  const int bytes =
    tinygltf::GetComponentSizeInBytes(static_cast<std::uint32_t>(accessor.componentType));
  if (components <= 0 || bytes <= 0)
    throw Error::InFile(name, "is damaged (" + what + " has an unknown type)");
  if (accessor.bufferView < 0)
    return; // all zeros (sparse or absent data): nothing to lie outside
  if (accessor.bufferView >= static_cast<int>(model.bufferViews.size()))
    throw Error::InFile(name, "is damaged (" + what + " names a missing buffer view)");
  const tinygltf::BufferView& view = model.bufferViews[ToIndex(accessor.bufferView)];
  if (view.buffer < 0 || view.buffer >= static_cast<int>(model.buffers.size()) ||
    view.byteOffset > model.buffers[ToIndex(view.buffer)].data.size() ||
    view.byteLength > model.buffers[ToIndex(view.buffer)].data.size() - view.byteOffset)
    throw Error::InFile(name, "is damaged (a buffer view of " + what + " lies outside its buffer)");
  const std::uint64_t element = std::uint64_t(components) * std::uint64_t(bytes);
  const std::uint64_t stride = view.byteStride ? view.byteStride : element;
  const std::uint64_t count = accessor.count;
  const std::uint64_t offset = accessor.byteOffset;
  if (count > 0 &&
    (count > (std::uint64_t(1) << 40) || offset + (count - 1) * stride + element > view.byteLength))
    throw Error::InFile(name,
      "is damaged (" + what + "'s " + std::to_string(count) +
        " elements lie outside its buffer view)");
}

GltfSummary Summarize(const tinygltf::Model& model, const std::string& name)
{
  GltfSummary s;
  s.Version = model.asset.version;
  s.Generator = model.asset.generator;
  s.Nodes = static_cast<std::int64_t>(model.nodes.size());
  s.Scenes = static_cast<std::int64_t>(model.scenes.size());
  for (const auto& buffer : model.buffers)
    s.BufferBytes += static_cast<std::int64_t>(buffer.data.size());
  for (const auto& material : model.materials)
  {
    GltfMaterialSummary m;
    m.Name = material.name;
    const auto& c = material.pbrMetallicRoughness.baseColorFactor;
    for (std::size_t k = 0; k < 4 && k < c.size(); ++k)
      m.BaseColor[k] = c[k];
    m.DoubleSided = material.doubleSided;
    s.Materials.push_back(m);
  }
  for (const auto& mesh : model.meshes)
  {
    GltfMeshSummary m;
    m.Name = mesh.name;
    for (const auto& primitive : mesh.primitives)
    {
      GltfPrimitiveSummary p;
      p.Mode = primitive.mode < 0 ? 4 : primitive.mode;
      p.Material = primitive.material;
      if (p.Material >= static_cast<int>(model.materials.size()))
        throw Error::InFile(name, "is damaged (a primitive names a missing material)");
      const auto position = primitive.attributes.find("POSITION");
      for (const auto& attribute : primitive.attributes)
        CheckAccessor(model, attribute.second, name);
      if (position != primitive.attributes.end())
        p.Vertices = static_cast<std::int64_t>(model.accessors[ToIndex(position->second)].count);
      std::int64_t drawn = p.Vertices;
      if (primitive.indices >= 0)
      {
        CheckAccessor(model, primitive.indices, name);
        drawn = static_cast<std::int64_t>(model.accessors[ToIndex(primitive.indices)].count);
      }
      if (p.Mode == 4)
        p.Triangles = drawn / 3;
      else if (p.Mode == 5 || p.Mode == 6)
        p.Triangles = drawn >= 3 ? drawn - 2 : 0;
      m.Primitives.push_back(p);
    }
    s.Meshes.push_back(std::move(m));
  }
  return s;
}
} // namespace

GltfSummary SummarizeGltf(const std::vector<std::uint8_t>& bytes, const std::string& name,
  bool binary, const std::string& folder)
{
  if (bytes.size() > MaximumFileBytes)
    throw Error::InFile(name, "is larger than 2 GiB");
  std::size_t jsonAt = 0, jsonSize = bytes.size();
  if (binary)
  {
    CheckContainer(bytes, name);
    jsonAt = 20;
    jsonSize = U32(bytes, 12);
  }
  CheckNesting(reinterpret_cast<const char*>(bytes.data()) + jsonAt, jsonSize, name);
  tinygltf::TinyGLTF loader;
  loader.SetImageLoader(&NoImage, nullptr);
  std::string base = folder;
  loader.SetFsCallbacks(tinygltf::FsCallbacks{ &Exists, &Expand,
    folder.empty()
      ? static_cast<tinygltf::ReadWholeFileFunction>(
          [](std::vector<unsigned char>*, std::string* err, const std::string& p, void*)
          {
            *err = "external file '" + p + "' is not read here";
            return false;
          })
      : &ReadWhole,
    &NoWrite, &base });
  tinygltf::Model model;
  std::string err, warn;
  bool ok = false;
  try
  {
    ok = binary
      ? loader.LoadBinaryFromMemory(
          &model, &err, &warn, bytes.data(), static_cast<unsigned int>(bytes.size()), folder)
      : loader.LoadASCIIFromString(&model, &err, &warn, reinterpret_cast<const char*>(bytes.data()),
          static_cast<unsigned int>(bytes.size()), folder);
  }
  catch (const std::bad_alloc&)
  {
    throw Error::InFile(name, "is damaged or needs more memory than is available");
  }
  catch (const std::exception& e)
  {
    throw Error::InFile(name, std::string("is not a glTF file we read (") + e.what() + ")");
  }
  if (!ok)
  {
    while (!err.empty() && (err.back() == '\n' || err.back() == ' '))
      err.pop_back();
    for (char& c : err)
      c = c == '\n' ? ';' : c;
    throw Error::InFile(name, "is not a glTF file we read (" + err + ")");
  }
  GltfSummary s = Summarize(model, name);
  s.Binary = binary;
  return s;
}

GltfSummary ReadGltfSummary(const std::string& path)
{
  std::vector<unsigned char> bytes;
  std::string err;
  if (!ReadWhole(&bytes, &err, path, nullptr))
    throw Error::InFile(path, "cannot be read (missing, not a file, or larger than 2 GiB)");
  const bool binary =
    bytes.size() >= 4 && bytes[0] == 'g' && bytes[1] == 'l' && bytes[2] == 'T' && bytes[3] == 'F';
  const std::size_t slash = path.rfind('/');
  const std::string folder = slash == std::string::npos ? "." : path.substr(0, slash);
  return SummarizeGltf(bytes, path, binary, folder);
}

} // namespace msynth
