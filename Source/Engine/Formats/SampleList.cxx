// SPDX-License-Identifier: BSD-3-Clause
#include "Formats/SampleList.h"

#include "Core/Error.h"
#include "Core/FileBytes.h"
#include "Formats/Xml.h"

#include <cerrno>
#include <cstdlib>
#include <sys/stat.h>

namespace msynth
{
namespace
{
bool IsFile(const std::string& path)
{
  struct stat info;
  return ::stat(path.c_str(), &info) == 0 && S_ISREG(info.st_mode);
}

/// Reads the attributes of one entry, with errors naming the list and the line.
class Attributes
{
public:
  Attributes(const detail::XmlElement& e, const std::string& list)
    : E(e)
    , List(list)
  {
  }

  [[noreturn]] void Fail(
    const std::string& key, const std::string& value, const std::string& what) const
  {
    throw Error("'" + this->List + "', line " + std::to_string(this->E.Line) + ": " + key + "=\"" +
      Printable(value) + "\" is not " + what);
  }

  std::int64_t Integer(
    const std::string& key, std::int64_t fallback, std::int64_t low, std::int64_t high) const
  {
    const std::string* v = this->E.Attribute(key);
    if (!v)
      return fallback;
    errno = 0;
    char* end = nullptr;
    const long long n = std::strtoll(v->c_str(), &end, 10);
    if (v->empty() || *end != '\0' || errno == ERANGE || n < low || n > high)
      this->Fail(
        key, *v, "an integer between " + std::to_string(low) + " and " + std::to_string(high));
    return n;
  }

  bool Boolean(const std::string& key, bool fallback, bool integers = false) const
  {
    const std::string* v = this->E.Attribute(key);
    if (!v)
      return fallback;
    if (*v == "True" || *v == "true" || *v == "1")
      return true;
    if (*v == "False" || *v == "false" || *v == "0")
      return false;
    char* end = nullptr;
    std::strtoll(v->c_str(), &end, 10);
    if (integers && !v->empty() && *end == '\0')
      return true; // an older list's ground pattern index
    this->Fail(key, *v, integers ? "True, False or an integer" : "True or False");
  }

  std::string Text(const std::string& key) const
  {
    const std::string* v = this->E.Attribute(key);
    return v ? *v : std::string();
  }

private:
  const detail::XmlElement& E;
  const std::string& List;
};

/// The first existing file of @p candidates, else the first.
std::string Find(const std::vector<std::string>& candidates)
{
  for (const auto& c : candidates)
    if (IsFile(c))
      return c;
  return candidates.front();
}

SampleEntry ReadEntry(const detail::XmlElement& e, const std::string& list, const std::string& dir)
{
  const Attributes a(e, list);
  constexpr std::int64_t maxSize = 1000000000;
  SampleEntry s;
  s.Element = e.Name;
  s.Line = e.Line;
  s.Name = a.Text("name");
  if (s.Name.empty())
    throw Error(
      "'" + list + "', line " + std::to_string(e.Line) + ": <" + e.Name + "> has no name");
  s.Subset = a.Text("subset");
  s.Periodic = a.Boolean("periodic", false);
  s.Block = { { a.Integer("blockWidth", 0, 0, maxSize), a.Integer("blockLength", 0, 0, maxSize),
    a.Integer("blockHeight", 0, 0, maxSize) } };
  if (e.Name == "overlapping")
  {
    s.Kind = SampleEntry::Overlapping;
    s.N = static_cast<int>(a.Integer("N", 2, 1, 8));
    s.Symmetry = static_cast<int>(a.Integer("symmetry", 8, 1, 8));
    s.PeriodicInput = a.Boolean("periodicInput", true);
    s.Ground = a.Boolean("ground", false, true);
    const std::int64_t size = a.Integer("size", 48, 1, maxSize);
    s.Size = { { a.Integer("width", size, 1, maxSize), a.Integer("height", size, 1, maxSize), 1 } };
    s.File = Find({ dir + "samples/" + s.Name + ".png", dir + "samples/" + s.Name + ".bmp",
      dir + s.Name + ".png", dir + "Samples/" + s.Name + ".png" });
  }
  else if (e.Name == "simpletiled")
  {
    s.Kind = SampleEntry::SimpleTiled;
    const std::int64_t size = a.Integer("size", 24, 1, maxSize);
    s.Size = { { a.Integer("width", size, 1, maxSize), a.Integer("height", size, 1, maxSize), 1 } };
    s.File = Find({ dir + "tilesets/" + s.Name + ".xml", dir + "samples/" + s.Name + "/data.xml",
      dir + s.Name + ".xml", dir + "Tilesets/" + s.Name + ".xml" });
  }
  else
  {
    s.Kind = SampleEntry::TiledModel;
    s.Screenshots = 1;
    const std::int64_t width = a.Integer("width", 0, 0, maxSize);
    const std::int64_t length = a.Integer("length", 0, 0, maxSize);
    const std::int64_t height = a.Integer("height", 0, 0, maxSize);
    // As the original program: without a length the height is the second axis (2D).
    s.Size = length > 0
      ? std::array<std::int64_t, 3>{ { width, length, std::max<std::int64_t>(height, 1) } }
      : std::array<std::int64_t, 3>{ { width, height, 1 } };
    if (s.Size[0] < 1 || s.Size[1] < 1)
      throw Error("'" + list + "', line " + std::to_string(e.Line) +
        ": <tiledmodel> needs a width and a length (or height) of at least 1");
    s.File = Find({ dir + "samples/" + s.Name, dir + "samples/" + s.Name + ".txt", dir + s.Name,
      dir + "Examples/" + s.Name });
  }
  s.Screenshots = static_cast<int>(a.Integer("screenshots", s.Screenshots, 0, 1000));
  return s;
}
} // namespace

std::vector<SampleEntry> ReadSampleList(const std::string& path)
{
  const std::string text = ReadFileBytes(path, std::uint64_t(1) << 24, "is larger than 16 MB");
  const detail::XmlElement root = detail::XmlReader(text, path).Parse();
  if (root.Name != "samples")
    throw Error("'" + path + "', line " + std::to_string(root.Line) +
      ": a sample list's root is <samples>, not <" + root.Name + ">");
  const auto slash = path.rfind('/');
  const std::string dir = slash == std::string::npos ? std::string() : path.substr(0, slash + 1);
  std::vector<SampleEntry> entries;
  for (const auto& e : root.Children)
    if (e.Name == "overlapping" || e.Name == "simpletiled" || e.Name == "tiledmodel")
      entries.push_back(ReadEntry(e, path, dir));
  return entries;
}

} // namespace msynth
