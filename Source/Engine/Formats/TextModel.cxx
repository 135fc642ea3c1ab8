// SPDX-License-Identifier: BSD-3-Clause
#include "Formats/TextModel.h"

#include "Core/Error.h"
#include "Core/Index.h"

#include <cerrno>
#include <cstdlib>
#include <fstream>
#include <limits>
#include <sstream>

namespace msynth
{
namespace
{
/// The largest trailer kept (the original examples' are a few kilobytes).
constexpr std::size_t MaximumTrailerBytes = std::size_t(64) << 20;

bool IsSpace(int c)
{
  return c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\f' || c == '\v';
}

/// Reads the file as the original program does: lines for the header, then white-space
/// separated tokens, then the rest verbatim; counts lines for messages.
class Scanner
{
public:
  Scanner(std::istream& in, const std::string& name)
    : Buffer(in.rdbuf())
    , Name(name)
  {
  }
  [[noreturn]] void Fail(const std::string& problem) const
  {
    throw Error("'" + this->Name + "', line " + std::to_string(this->Line) + ": " + problem);
  }
  /// The next line without its end ('\r' of files written on Windows dropped); false at the end.
  bool NextLine(std::string& line)
  {
    line.clear();
    int c = this->Get();
    if (c == EOF)
      return false;
    while (c != EOF && c != '\n')
    {
      if (line.size() < 4096) // a header line is free text: keep a sane amount of it
        line += static_cast<char>(c);
      c = this->Get();
    }
    if (!line.empty() && line.back() == '\r')
      line.pop_back();
    return true;
  }
  /// The next white-space separated token; false at the end of the input.
  bool NextToken(std::string& token)
  {
    this->SkipSpace();
    token.clear();
    int c = this->Peek();
    if (c == EOF)
      return false;
    while (c != EOF && !IsSpace(c))
    {
      if (token.size() < 64)
        token += static_cast<char>(c);
      this->Get();
      c = this->Peek();
    }
    return true;
  }
  void SkipSpace()
  {
    while (IsSpace(this->Peek()))
      this->Get();
  }
  /// Everything that is left, verbatim.
  std::string Rest()
  {
    std::string rest;
    for (int c = this->Get(); c != EOF; c = this->Get())
    {
      if (rest.size() >= MaximumTrailerBytes)
        this->Fail("the text after the last value is larger than 64 MiB");
      rest += static_cast<char>(c);
    }
    return rest;
  }
  std::int64_t CurrentLine() const { return this->Line; }

private:
  int Peek() { return this->Buffer ? this->Buffer->sgetc() : EOF; }
  int Get()
  {
    if (!this->Buffer)
      return EOF;
    const int c = this->Buffer->sbumpc();
    if (c == '\n')
      ++this->Line;
    return c == EOF ? EOF : static_cast<unsigned char>(c);
  }
  std::streambuf* Buffer;
  const std::string& Name;
  std::int64_t Line = 1;
};

/// @p token as a 32-bit integer; fails naming it otherwise.
long long Integer(const std::string& token, const Scanner& scanner)
{
  char* end = nullptr;
  errno = 0;
  const long long v = std::strtoll(token.c_str(), &end, 10);
  if (end == token.c_str() || *end)
    scanner.Fail("'" + token + "' is not an integer"); // (Error shows control bytes as '?')
  if (errno == ERANGE || v < std::numeric_limits<Label>::min() ||
    v > std::numeric_limits<Label>::max())
    scanner.Fail("value out of the 32-bit range");
  return v;
}

std::string Trimmed(const std::string& s)
{
  const auto a = s.find_first_not_of(" \t\r"), b = s.find_last_not_of(" \t\r");
  return a == std::string::npos ? std::string() : s.substr(a, b - a + 1);
}
} // namespace

std::array<std::string, 3> GeneratedTextModelHeader()
{
  return { { "Model generated using ModelSynth (Paul Merrell's model synthesis algorithm).  Do not "
             "insert or delete lines from this file.",
    "", "x, y, and z extents" } };
}

void SetTextModelTrailer(TextModel& model, const std::string& trailer, std::int64_t firstLine)
{
  model.Trailer = trailer;
  model.HasObjects = false;
  model.Scene.clear();
  model.Objects.clear();
  model.Pieces.clear();
  model.ObjectsProblem.clear();

  std::vector<std::string> lines;
  {
    std::istringstream in(trailer);
    std::string line;
    while (std::getline(in, line))
      lines.push_back(line);
  }
  if (lines.empty() || Trimmed(lines[0]) != "<Objects>")
    return; // free text: kept, nothing to read from it
  model.HasObjects = true;
  if (lines.size() > 1)
    model.Scene = Trimmed(lines[1]);
  std::size_t i = 2;
  const auto problem = [&](std::size_t at, const std::string& what)
  {
    model.ObjectsProblem = "line " + std::to_string(firstLine + static_cast<std::int64_t>(at)) +
      ": " + what + "; the <Objects> section is kept as text, without pieces";
    model.Objects.clear();
  };
  while (i < lines.size())
  {
    if (Trimmed(lines[i]).empty())
    {
      ++i;
      continue;
    }
    TextObjectEntry entry;
    entry.Text = Trimmed(lines[i++]);
    const std::size_t label = model.Objects.size() + 1;
    for (; i < lines.size(); ++i)
    {
      const std::string t = Trimmed(lines[i]);
      if (t.empty())
        continue;
      if (t[0] == '#')
        break;
      if (t[0] != '$')
      {
        problem(i,
          "expected a piece name starting with '$' or '#' to end the entry of label " +
            std::to_string(label));
        return;
      }
      // A name runs to the first blank (it may contain '$' itself, as in "$backa$").
      const std::string name = t.substr(1, t.find_first_of(" \t") - 1);
      if (name.empty())
      {
        problem(i, "a '$' without a piece name in the entry of label " + std::to_string(label));
        return;
      }
      entry.Pieces.push_back(name);
    }
    ++i; // past '#' (or the end: a last entry may end with the file)
    if (label > ToIndex(std::numeric_limits<Label>::max()))
    {
      problem(i, "more entries than labels");
      return;
    }
    model.Objects.push_back(std::move(entry));
  }
  for (std::size_t e = 0; e < model.Objects.size(); ++e)
    if (!model.Objects[e].Pieces.empty())
      model.Pieces[static_cast<Label>(e + 1)] = model.Objects[e].Pieces;
}

TextModel ReadTextModel(std::istream& in, const std::string& name, std::int64_t maxSites)
{
  Scanner scanner(in, name);
  TextModel model;
  for (auto& h : model.Header)
  {
    if (!scanner.NextLine(h))
      scanner.Fail("the file ends inside its three header lines");
  }
  std::string token;
  long long dims[3];
  for (int k = 0; k < 3; ++k)
  {
    if (!scanner.NextToken(token))
      scanner.Fail("the file ends before the dimensions 'X Y Z' (found " + std::to_string(k) +
        " of 3 numbers)");
    dims[k] = Integer(token, scanner);
  }
  for (long long d : dims)
    if (d < 1)
      scanner.Fail("dimensions must be at least 1");
  if (dims[0] > maxSites || dims[1] > maxSites / dims[0] ||
    dims[2] > maxSites / (dims[0] * dims[1]))
    scanner.Fail("dimensions " + std::to_string(dims[0]) + " x " + std::to_string(dims[1]) + " x " +
      std::to_string(dims[2]) + " exceed the limit of " + std::to_string(maxSites) + " sites");
  const std::int64_t nx = dims[0], ny = dims[1], nz = dims[2];
  model.Grid = LabelGrid(nx, ny, nz);

  const std::int64_t perSlice = nx * ny;
  for (std::int64_t z = 0; z < nz; ++z)
    for (std::int64_t x = 0; x < nx; ++x)
      for (std::int64_t y = 0; y < ny; ++y)
      {
        if (!scanner.NextToken(token))
          scanner.Fail("the file ends in slice " + std::to_string(z) + " after " +
            std::to_string(x * ny + y) + " of its " + std::to_string(perSlice) +
            " values (expected " + std::to_string(nz) + " slices of " + std::to_string(nx) +
            " rows of " + std::to_string(ny) + " values)");
        model.Grid.Set(x, y, z, static_cast<Label>(Integer(token, scanner)));
      }

  scanner.SkipSpace();
  const std::int64_t trailerLine = scanner.CurrentLine();
  SetTextModelTrailer(model, scanner.Rest(), trailerLine);
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
  out << d[0] << " " << d[1] << " " << d[2] << "\n\n";
  for (std::int64_t z = 0; z < d[2]; ++z)
  {
    for (std::int64_t x = 0; x < d[0]; ++x)
    {
      for (std::int64_t y = 0; y < d[1]; ++y)
      {
        const Label v = model.Grid.At(x, y, z);
        out << (v >= 0 && v < 10 ? " " : "") << v << " ";
      }
      out << "\n";
    }
    out << "\n";
  }
  out << model.Trailer;
}

} // namespace msynth
