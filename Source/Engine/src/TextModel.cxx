// SPDX-License-Identifier: BSD-3-Clause
#include "msynth/TextModel.h"

#include "msynth/Error.h"

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <limits>
#include <sstream>

namespace msynth
{
namespace
{
class LineReader
{
public:
  LineReader(std::istream& in, const std::string& name)
    : In(in)
    , Name(name)
  {
  }
  bool Next(std::string& line)
  {
    if (!std::getline(this->In, line))
      return false;
    ++this->Number;
    if (!line.empty() && line.back() == '\r')
      line.pop_back(); // files written on Windows
    return true;
  }
  /// The next line that is not blank; false at the end of the input.
  bool NextNonBlank(std::string& line)
  {
    while (this->Next(line))
      if (line.find_first_not_of(" \t") != std::string::npos)
        return true;
    return false;
  }
  [[noreturn]] void Fail(const std::string& problem) const
  {
    throw Error("'" + this->Name + "', line " + std::to_string(this->Number) + ": " + problem);
  }
  std::int64_t Line() const { return this->Number; }

private:
  std::istream& In;
  const std::string& Name;
  std::int64_t Number = 0;
};

/// Whitespace-separated integers of @p line; fails on anything else or out-of-range values.
std::vector<long long> Integers(const std::string& line, const LineReader& reader)
{
  std::vector<long long> values;
  const char* p = line.c_str();
  while (*p)
  {
    while (*p == ' ' || *p == '\t')
      ++p;
    if (!*p)
      break;
    char* end = nullptr;
    errno = 0;
    const long long v = std::strtoll(p, &end, 10);
    if (end == p || (*end && *end != ' ' && *end != '\t'))
    {
      std::string token(p, static_cast<std::size_t>(std::strcspn(p, " \t")));
      reader.Fail("'" + token + "' is not an integer");
    }
    if (errno == ERANGE || v < std::numeric_limits<Label>::min() ||
      v > std::numeric_limits<Label>::max())
      reader.Fail("value out of the 32-bit range");
    values.push_back(v);
    p = end;
  }
  return values;
}
} // namespace

TextModel ReadTextModel(std::istream& in, const std::string& name, std::int64_t maxSites)
{
  LineReader reader(in, name);
  TextModel model;
  std::string line;
  for (auto& h : model.Header)
  {
    if (!reader.Next(line))
      reader.Fail("the file ends inside its three header lines");
    h = line;
  }
  if (!reader.NextNonBlank(line))
    reader.Fail("the file ends before the dimensions line 'X Y Z'");
  const std::vector<long long> dims = Integers(line, reader);
  if (dims.size() != 3)
    reader.Fail(
      "expected the dimensions 'X Y Z', found " + std::to_string(dims.size()) + " numbers");
  for (long long d : dims)
    if (d < 1)
      reader.Fail("dimensions must be at least 1");
  if (dims[0] > maxSites || dims[1] > maxSites / dims[0] ||
    dims[2] > maxSites / (dims[0] * dims[1]))
    reader.Fail("dimensions " + std::to_string(dims[0]) + " x " + std::to_string(dims[1]) + " x " +
      std::to_string(dims[2]) + " exceed the limit of " + std::to_string(maxSites) + " sites");
  const std::int64_t nx = dims[0], ny = dims[1], nz = dims[2];
  model.Grid = LabelGrid(nx, ny, nz);

  for (std::int64_t z = 0; z < nz; ++z)
  {
    for (std::int64_t x = 0; x < nx; ++x)
    {
      // Rows of a slice are consecutive; blank lines may only separate slices.
      const bool ok = x == 0 ? reader.NextNonBlank(line) : reader.Next(line);
      if (!ok)
        reader.Fail("the file ends in slice " + std::to_string(z) + " (expected " +
          std::to_string(nz) + " slices of " + std::to_string(nx) + " rows)");
      const std::vector<long long> row = Integers(line, reader);
      if (static_cast<std::int64_t>(row.size()) != ny)
        reader.Fail("row " + std::to_string(x) + " of slice " + std::to_string(z) + " has " +
          std::to_string(row.size()) + " values, expected Y = " + std::to_string(ny));
      for (std::int64_t y = 0; y < ny; ++y)
        model.Grid.Set(x, y, z, static_cast<Label>(row[static_cast<std::size_t>(y)]));
    }
  }

  // Optional <Objects> section.
  if (!reader.NextNonBlank(line))
    return model;
  const auto trimmed = [](const std::string& s)
  {
    const auto a = s.find_first_not_of(" \t"), b = s.find_last_not_of(" \t");
    return a == std::string::npos ? std::string() : s.substr(a, b - a + 1);
  };
  if (trimmed(line) != "<Objects>")
    reader.Fail("unexpected content after the last slice (expected '<Objects>' or the end)");
  while (reader.NextNonBlank(line))
  {
    const std::vector<long long> label = Integers(line, reader);
    if (label.size() != 1)
      reader.Fail("expected a label number to start an object entry");
    auto& names = model.Pieces[static_cast<Label>(label[0])];
    bool closed = false;
    while (reader.Next(line))
    {
      const std::string t = trimmed(line);
      if (t == "#")
      {
        closed = true;
        break;
      }
      if (t.empty())
        continue;
      if (t[0] != '$')
        reader.Fail("expected a piece name starting with '$' or '#' to end label " +
          std::to_string(label[0]));
      names.push_back(t.substr(1));
    }
    if (!closed)
      reader.Fail("the object entry of label " + std::to_string(label[0]) + " has no closing '#'");
  }
  return model;
}

TextModel ReadTextModelFile(const std::string& path, std::int64_t maxSites)
{
  std::ifstream in(path, std::ios::binary);
  if (!in)
    throw Error::InFile(path, "cannot be opened for reading (missing or unreadable)");
  return ReadTextModel(in, path, maxSites);
}

void WriteTextModel(std::ostream& out, const TextModel& model)
{
  for (const auto& h : model.Header)
    out << h << "\n";
  const auto& d = model.Grid.Dimensions();
  out << d[0] << " " << d[1] << " " << d[2] << "\n";
  for (std::int64_t z = 0; z < d[2]; ++z)
  {
    out << "\n";
    for (std::int64_t x = 0; x < d[0]; ++x)
    {
      for (std::int64_t y = 0; y < d[1]; ++y)
        out << (y ? " " : "") << model.Grid.At(x, y, z);
      out << "\n";
    }
  }
  if (!model.Pieces.empty())
  {
    out << "\n<Objects>\n";
    for (const auto& kv : model.Pieces)
    {
      out << kv.first << "\n";
      for (const auto& n : kv.second)
        out << "$" << n << "\n";
      out << "#\n";
    }
  }
}

} // namespace msynth
