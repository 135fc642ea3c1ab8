// SPDX-License-Identifier: BSD-3-Clause
#include "Common.h"
#include "Examples.h"

#include "vtkMSOpenVDBWriter.h"
#include "vtkMSPolyhedralExampleReader.h"

#include "vtkAlgorithm.h"
#include "vtkCallbackCommand.h"
#include "vtkCommand.h"
#include "vtkDataArray.h"
#include "vtkFieldData.h"
#include "vtkImageData.h"
#include "vtkPointData.h"
#include "vtkStringArray.h"
#include "vtkTable.h"
#include "vtkUnsignedCharArray.h"
#include "vtkVariant.h"

#include "Core/Error.h"
#include "Core/Index.h"
#include "Core/Memory.h"
#include "Core/OutputFolder.h"
#include "Formats/Image.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <mutex>
#include <sstream>
#include <sys/stat.h>
#include <unistd.h>

namespace msynth
{
namespace cli
{

bool IsTileset(const std::string& path)
{
  return path.size() > 4 && path.compare(path.size() - 4, 4, ".xml") == 0;
}

bool IsSample(const std::string& path)
{
  return msynth::IsImageFile(path);
}

bool IsPolyhedral(const std::string& path)
{
  return vtkMSPolyhedralExampleReader::CanReadFile(path.c_str()) != 0;
}

void CheckInputFile(const std::string& path, bool model)
{
  struct stat info;
  if (::stat(path.c_str(), &info) != 0)
  {
    throw std::runtime_error("'" + path + "': no such file");
  }
  if (S_ISDIR(info.st_mode))
  {
    throw std::runtime_error("'" + path + "': is a folder, not a file");
  }
  if (!S_ISREG(info.st_mode))
  {
    throw std::runtime_error("'" + path + "': is not a regular file (a pipe, socket or device)");
  }
  const std::string::size_type dot = path.rfind('.');
  std::string ext = dot == std::string::npos || path.find('/', dot) != std::string::npos
    ? std::string()
    : path.substr(dot);
  for (auto& c : ext)
  {
    c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  }
  static const char* const known[] = { ".vti", ".txt", ".vox", ".xml", ".png", ".bmp", ".obj",
    ".vtp", ".ply", ".stl" };
  bool ok = model && ext == ".pvti"; // a streamed model's pieces
  for (const char* k : known)
  {
    ok |= ext == k;
  }
  if (!ok)
  {
    throw std::runtime_error("'" + path + "': " +
      (ext.empty() ? std::string("has no extension")
                   : "has the unknown extension '" + msynth::Printable(ext) + "'") +
      (model ? "; models are .vti, .pvti, .txt, .vox or .vtp files"
             : "; examples are label grids (.vti, .txt, .vox), tilesets (.xml), image samples "
               "(.png, .bmp) or polyhedra (.obj, .vtp, .ply, .stl)"));
  }
}

std::string Triple(const int* v)
{
  return std::to_string(v[0]) + " x " + std::to_string(v[1]) + " x " + std::to_string(v[2]);
}

std::string Counted(long long n, const std::string& thing, const std::string& plural)
{
  return std::to_string(n) + " " + (n == 1 ? thing : plural.empty() ? thing + "s" : plural);
}

namespace
{
std::mutex& NoteMutex()
{
  static auto* m = new std::mutex; // never destroyed: the signal thread may read at exit
  return *m;
}
/// What the signal thread says of an interrupted run (InterruptNote, InterruptDone).
struct InterruptWords
{
  std::string Note, Done, Discard;
};
InterruptWords& Words()
{
  static auto* words = new InterruptWords; // never destroyed, as the mutex
  return *words;
}
} // namespace

void SetInterruptNote(
  const std::string& note, const std::string& discard, const std::function<void()>& change)
{
  std::lock_guard<std::mutex> lock(NoteMutex());
  if (change)
    change();
  Words().Note = note;
  Words().Discard = discard;
}

std::string InterruptNote()
{
  std::lock_guard<std::mutex> lock(NoteMutex());
  return Words().Note;
}

std::string InterruptDiscard()
{
  std::lock_guard<std::mutex> lock(NoteMutex());
  return Words().Discard;
}

void SetInterruptDone(const std::string& done)
{
  std::lock_guard<std::mutex> lock(NoteMutex());
  Words().Done = done;
}

std::string InterruptDone()
{
  std::lock_guard<std::mutex> lock(NoteMutex());
  return Words().Done;
}

long long SitesWithinMemory(unsigned bytesPerSite, long long ceiling)
{
  const std::uint64_t sites = msynth::AvailableMemory() / std::max(1u, bytesPerSite);
  return static_cast<long long>(
    std::min<std::uint64_t>(sites, static_cast<std::uint64_t>(ceiling)));
}

void Run(vtkAlgorithm* algorithm)
{
  std::string messages;
  if (!vtkMSEngineBridge::Execute(algorithm, messages))
  {
    throw std::runtime_error(messages);
  }
}

void RunSynthesis(vtkAlgorithm* algorithm)
{
  try
  {
    Run(algorithm);
  }
  catch (const std::runtime_error& e)
  {
    // The filters' messages about a list property start with the property's name.
    std::string text = e.what();
    for (const auto& [property, option] : { std::make_pair("Counts: ", "--count: "),
           std::make_pair("Connected: ", "--connected: "), std::make_pair("Path: ", "--path: ") })
      if (text.compare(0, std::strlen(property), property) == 0)
        text = option + text.substr(std::strlen(property));
    throw std::runtime_error(text);
  }
}

namespace
{
/// @p text with every occurrence of @p from replaced by @p to.
std::string Replaced(std::string text, const std::string& from, const std::string& to)
{
  for (std::size_t at = text.find(from); at != std::string::npos;
       at = text.find(from, at + to.size()))
  {
    text.replace(at, from.size(), to);
  }
  return text;
}
} // namespace

namespace
{
/// "a, b, c and N more": at most eight names of @p names.
std::string Listed(const std::vector<std::string>& names)
{
  constexpr std::size_t shown = 8;
  std::string list;
  for (std::size_t i = 0; i < names.size() && i < shown; ++i)
    list += (i ? ", " : "") + msynth::Printable(names[i]);
  if (names.size() > shown)
    list += " and " + std::to_string(names.size() - shown) + " more";
  return list;
}
} // namespace

std::string ReplacedNote(const std::string& dir, const std::vector<std::string>& replaced,
  const std::vector<std::string>& removed)
{
  if (replaced.empty() && removed.empty())
    return "";
  std::string note = "msynth: note: this run ";
  if (!replaced.empty())
    note += "replaced the earlier outputs in '" + msynth::Printable(dir) + "' (" +
      Listed(replaced) + ")" + (removed.empty() ? "" : " and ");
  if (!removed.empty())
    note += "removed the earlier outputs it did not write again" +
      (replaced.empty() ? " from '" + msynth::Printable(dir) + "'" : std::string()) + " (" +
      Listed(removed) + ")";
  return note;
}

int IntoFolder(const std::string& out, const std::function<int(const std::string&)>& command,
  std::vector<std::string>* replaced)
{
  msynth::OutputFolder folder(out);
  std::ostringstream said;
  struct Console // std::cout into `said` while the command runs
  {
    std::streambuf* Saved;
    ~Console() { std::cout.rdbuf(this->Saved); }
  } console{ std::cout.rdbuf(said.rdbuf()) };
  int status = 1;
  try
  {
    status = command(folder.Stage());
  }
  catch (const std::exception& e)
  {
    throw std::runtime_error(Replaced(e.what(), folder.Stage(), folder.Final()));
  }
  if (status == 0)
  {
    folder.Publish();
  }
  std::cout.rdbuf(console.Saved);
  std::cout << Replaced(said.str(), folder.Stage(), folder.Final()) << std::flush;
  if (replaced)
  {
    replaced->insert(replaced->end(), folder.Replaced().begin(), folder.Replaced().end());
    replaced->insert(replaced->end(), folder.Removed().begin(), folder.Removed().end());
  }
  else if (!folder.Replaced().empty() || !folder.Removed().empty())
    std::cerr << ReplacedNote(folder.Final(), folder.Replaced(), folder.Removed()) << "\n";
  return status;
}

void WriteCSV(const std::string& path, vtkTable* table)
{
  msynth::WriteFileAtomically(path,
    [table](std::ostream& out)
    {
      for (vtkIdType c = 0; c < table->GetNumberOfColumns(); ++c)
      {
        out << (c ? "," : "") << table->GetColumnName(c);
      }
      out << "\n";
      for (vtkIdType r = 0; r < table->GetNumberOfRows(); ++r)
      {
        for (vtkIdType c = 0; c < table->GetNumberOfColumns(); ++c)
        {
          out << (c ? "," : "") << table->GetValue(r, c).ToString();
        }
        out << "\n";
      }
    });
}

std::string Joined(const std::vector<std::string>& items, const char* separator)
{
  std::string out;
  for (const auto& item : items)
    out += (out.empty() ? "" : separator) + item;
  return out;
}

std::string JsonString(const std::string& text)
{
  std::string out = "\"";
  for (const char c : text)
  {
    switch (c)
    {
      case '"':
        out += "\\\"";
        break;
      case '\\':
        out += "\\\\";
        break;
      case '\n':
        out += "\\n";
        break;
      default:
        if (static_cast<unsigned char>(c) < 0x20)
        {
          char buffer[8];
          std::snprintf(buffer, sizeof(buffer), "\\u%04x", c);
          out += buffer;
        }
        else
        {
          out += c;
        }
    }
  }
  return out + "\"";
}

std::string JsonNumber(double value)
{
  std::ostringstream s;
  s << value; // the stream's default: six significant digits
  return s.str();
}

StatisticsJson& StatisticsJson::Raw(const std::string& key, const std::string& json)
{
  this->Members.emplace_back(key, json);
  return *this;
}

StatisticsJson& StatisticsJson::Text(const std::string& key, const std::string& text)
{
  return this->Raw(key, JsonString(text));
}

StatisticsJson& StatisticsJson::Number(const std::string& key, double value)
{
  return this->Raw(key, JsonNumber(value));
}

StatisticsJson& StatisticsJson::Count(const std::string& key, long long value)
{
  return this->Raw(key, std::to_string(value));
}

StatisticsJson& StatisticsJson::Flag(const std::string& key, bool value)
{
  return this->Raw(key, value ? "true" : "false");
}

StatisticsJson& StatisticsJson::Counts(const std::string& key, const std::vector<long long>& values)
{
  std::string json;
  for (const long long v : values)
    json += (json.empty() ? "" : ", ") + std::to_string(v);
  return this->Raw(key, "[" + json + "]");
}

StatisticsJson& StatisticsJson::Solver(vtkFieldData* fd)
{
  for (const auto& f : msynth::StatisticsFields(msynth::SynthesisStatistics()))
  {
    vtkDataArray* array = fd->GetArray(f.Name.c_str());
    const double value = array ? array->GetTuple1(0) : 0.0;
    if (f.Integer)
      this->Count(f.Name, static_cast<long long>(value));
    else
      this->Number(f.Name, value);
  }
  return *this;
}

StatisticsJson& StatisticsJson::Prefixed(
  const std::string& key, vtkFieldData* fd, const std::string& prefix)
{
  std::string json;
  for (int i = 0; i < fd->GetNumberOfArrays(); ++i)
  {
    const std::string name = fd->GetArrayName(i) ? fd->GetArrayName(i) : "";
    if (name.rfind(prefix, 0) == 0)
      json += (json.empty() ? "" : ", ") + JsonString(name.substr(prefix.size())) + ": " +
        JsonNumber(fd->GetArray(i)->GetTuple1(0));
  }
  return this->Raw(key, "{" + json + "}");
}

StatisticsJson& StatisticsJson::LabelCounts(vtkFieldData* fd)
{
  auto* names = vtkStringArray::SafeDownCast(fd->GetAbstractArray("CountNames"));
  vtkDataArray* low = fd->GetArray("CountMinimum");
  vtkDataArray* high = fd->GetArray("CountMaximum");
  vtkDataArray* achieved = fd->GetArray("CountAchieved");
  if (!names || !low || !high || !achieved)
    return *this;
  vtkDataArray* region = fd->GetArray("CountRegion"); // -1: the whole model
  std::string json;
  for (vtkIdType i = 0; i < names->GetNumberOfValues(); ++i)
    json += std::string(i ? ", " : "") + "{\"label\": " + JsonString(names->GetValue(i)) +
      (region && region->GetTuple1(i) >= 0
          ? ", \"region\": " + std::to_string(static_cast<long long>(region->GetTuple1(i)))
          : std::string()) +
      ", \"minimum\": " + std::to_string(static_cast<long long>(low->GetTuple1(i))) +
      ", \"maximum\": " + std::to_string(static_cast<long long>(high->GetTuple1(i))) +
      ", \"achieved\": " + std::to_string(static_cast<long long>(achieved->GetTuple1(i))) + "}";
  return this->Raw("Counts", "[" + json + "]");
}

StatisticsJson& StatisticsJson::Connected(vtkFieldData* fd)
{
  auto* names = vtkStringArray::SafeDownCast(fd->GetAbstractArray("ConnectedLabels"));
  if (!names || names->GetNumberOfValues() < 1)
    return *this;
  std::string json = "\"labels\": " + JsonString(names->GetValue(0));
  for (const char* key : { "Maximum", "Components", "Before", "Repairs", "Redone", "PathSites" })
    if (vtkDataArray* a = fd->GetArray((std::string("Connected") + key).c_str()))
    {
      std::string lower = key;
      lower[0] = static_cast<char>(std::tolower(static_cast<unsigned char>(lower[0])));
      json += ", \"" + lower + "\": " + std::to_string(static_cast<long long>(a->GetTuple1(0)));
    }
  return this->Raw("Connected", "{" + json + "}");
}

void StatisticsJson::Write(const std::string& path) const
{
  msynth::WriteFileAtomically(path,
    [this](std::ostream& out)
    {
      out << "{\n";
      for (std::size_t i = 0; i < this->Members.size(); ++i)
        out << (i ? ",\n" : "") << "  " << JsonString(this->Members[i].first) << ": "
            << this->Members[i].second;
      out << "\n}\n";
    });
}

std::string MessageOf(vtkFieldData* fd, const char* name)
{
  auto* message = vtkStringArray::SafeDownCast(fd->GetAbstractArray(name));
  return message && message->GetNumberOfValues() > 0 ? message->GetValue(0) : std::string();
}

long long CountOf(vtkFieldData* fd, const char* name)
{
  vtkDataArray* array = fd->GetArray(name);
  return array && array->GetNumberOfTuples() > 0 ? static_cast<long long>(array->GetTuple1(0)) : 0;
}

ProgressBar::ProgressBar(vtkAlgorithm* algorithm, const char* stage, double delay)
  : Algorithm(algorithm)
  , Stage(stage)
  , Delay(delay)
  , Start(std::chrono::steady_clock::now())
{
  if (::isatty(STDERR_FILENO) == 0)
  {
    return;
  }
  if (delay <= 0)
  {
    this->OnProgress(0);
  }
  vtkNew<vtkCallbackCommand> callback;
  callback->SetClientData(this);
  callback->SetCallback([](vtkObject*, unsigned long, void* self, void* data)
    { static_cast<ProgressBar*>(self)->OnProgress(*static_cast<double*>(data)); });
  this->Observer = algorithm->AddObserver(vtkCommand::ProgressEvent, callback);
}

ProgressBar::~ProgressBar()
{
  if (this->Observer)
  {
    this->Algorithm->RemoveObserver(this->Observer);
  }
  if (this->Shown)
  {
    std::cerr << "\n";
  }
}

void ProgressBar::OnProgress(double f)
{
  if (!this->Shown && this->Delay > 0 &&
    std::chrono::duration<double>(std::chrono::steady_clock::now() - this->Start).count() <
      this->Delay)
  {
    return;
  }
  f = std::clamp(f, 0.0, 1.0);
  const int width = 40, filled = static_cast<int>(f * width + 0.5);
  const double seconds =
    std::chrono::duration<double>(std::chrono::steady_clock::now() - this->Start).count();
  // The time left once a run has shown its pace (a percent done and two seconds).
  char timing[64] = "";
  if (seconds >= 2.0 && f >= 0.01 && f < 1.0)
    std::snprintf(
      timing, sizeof(timing), ", %.0f s, about %.0f s left   ", seconds, seconds * (1.0 - f) / f);
  else if (seconds >= 2.0)
    std::snprintf(timing, sizeof(timing), ", %.0f s   ", seconds);
  std::cerr << "\r" << this->Stage << " [" << std::string(msynth::ToIndex(filled), '#')
            << std::string(msynth::ToIndex(width - filled), ' ') << "] "
            << static_cast<int>(f * 100 + 0.5) << "%" << timing << std::flush;
  this->Shown = true;
}

void WritePicturePng(vtkImageData* rgba, const std::string& path)
{
  int dims[3];
  rgba->GetDimensions(dims);
  auto* pixels = vtkUnsignedCharArray::SafeDownCast(rgba->GetPointData()->GetScalars());
  if (!pixels || pixels->GetNumberOfComponents() != 4)
    throw std::runtime_error("'" + path + "': the picture is not an RGBA image");
  // VTK's rows are bottom first, the PNG's top first: row y is VTK's row dims[1] - 1 - y.
  msynth::WritePng(path, dims[0], dims[1],
    [&](int y)
    {
      return static_cast<const std::uint8_t*>(
        pixels->GetPointer(4 * static_cast<vtkIdType>(dims[1] - 1 - y) * dims[0]));
    });
}

void WriteCatalogSequence(vtkAlgorithm* source, const std::string& dir, double voxel,
  const char* key, const std::string& value)
{
  vtkNew<vtkMSOpenVDBWriter> catalog;
  catalog->SetInputConnection(source->GetOutputPort());
  catalog->SetFileName((dir + "/catalog.vdb").c_str());
  catalog->SetVoxelSize(voxel);
  catalog->WriteTimeStepsOn();
  catalog->WriteRenderGridsOff(); // the solver's state, for inspection rather than rendering
  catalog->AddMetadata(key, value.c_str());
  vtkNew<vtkMSEngineBridge> errors;
  errors->Watch(catalog);
  if (!catalog->Write() || errors->HasErrors())
  {
    throw std::runtime_error(errors->GetMessages());
  }
}

// ---------------------------------------------------------------------------------------------
// Shared options
// ---------------------------------------------------------------------------------------------

CLI::Option* AddOutOption(CLI::App& command, std::string& out)
{
  return command
    .add_option("--out", out,
      "output folder; its files appear together, or not at all when the run fails or is "
      "interrupted")
    ->check(CLI::Validator(
      [](std::string& text)
      {
        // An empty name would be the current folder, silently: say so instead.
        return text.empty() ? std::string("the folder name is empty (for the current folder, "
                                          "give --out .)")
                            : std::string();
      },
      ""));
}

namespace
{
/// A seed: a decimal whole number within the signed 64-bit range, rewritten in its plain form.
CLI::Validator SeedRange()
{
  return CLI::Validator(
    [](std::string& text)
    {
      // Decimal only, checked here: CLI11 would saturate an out-of-range number and read a
      // leading 0 as octal. Seeds are signed, as the filters' Seed property and statistics.json
      // hold them; the engine uses the same 64 bits as an unsigned number.
      errno = 0;
      char* end = nullptr;
      const long long value = std::strtoll(text.c_str(), &end, 10);
      const bool digits = !text.empty() &&
        (std::isdigit(static_cast<unsigned char>(text[0])) ||
          ((text[0] == '-' || text[0] == '+') && text.size() > 1 &&
            std::isdigit(static_cast<unsigned char>(text[1]))));
      if (!digits || *end != '\0')
      {
        return "'" + msynth::Printable(text) + "' is not a whole number";
      }
      if (errno == ERANGE)
      {
        return "'" + msynth::Printable(text) + "' is outside the seed range " +
          std::to_string(INT64_MIN) + " to " + std::to_string(INT64_MAX) + " (signed 64-bit)";
      }
      text = std::to_string(value);
      return std::string();
    },
    "");
}
} // namespace

void AddSeedOption(CLI::App& command, std::int64_t& seed)
{
  command
    .add_option("--seed", seed,
      "random seed, a whole number from " + std::to_string(INT64_MIN) + " to " +
        std::to_string(INT64_MAX) +
        " (signed 64-bit); the same inputs and seed give the same "
        "result")
    ->transform(SeedRange()); // a transform: it rewrites the text that CLI11 then converts
}

void AddAttemptsOption(CLI::App& command, int& attempts, const std::string& what)
{
  command.add_option("--attempts", attempts, what)->check(CLI::Range(1, 1000000));
}

void AddSnapshotsOption(CLI::App& command, int& snapshots, const std::string& what)
{
  command.add_option("--snapshots", snapshots, what)->check(CLI::Range(0, 9998));
}

std::vector<CLI::Option*> AddTypesOption(CLI::App& command, PolyhedralReading& reading)
{
  return { command.add_option("--types", reading.Types,
             "object types of a polyhedral example: object (or base) name N has type T, as "
             "N=T,..."),
    command
      .add_option("--up", reading.Up,
        "the polyhedral example's up axis: z (default), or y for a file modelled with y up (OBJ "
        "as Blender exports it by default), turned so that y becomes z")
      ->check(CLI::IsMember({ "y", "z" })) };
}

std::vector<CLI::Option*> AddPatternOptions(
  CLI::App& command, int& n, int& symmetry, bool& noPeriodicInput)
{
  const char* group = "Image samples (.png, .bmp)";
  return { command.add_option("--pattern", n, "pattern size N: the labels are N x N windows")
             ->check(CLI::Range(1, 8))
             ->group(group),
    command
      .add_option("--symmetry", symmetry,
        "how many of each window's 8 rotations and reflections are patterns, in "
        "WaveFunctionCollapse's order (identity, mirror, quarter turn, ...)")
      ->check(CLI::Range(1, 8))
      ->group(group),
    command
      .add_flag("--no-periodic-input", noPeriodicInput, "windows do not wrap around the sample")
      ->group(group) };
}

void AddSubsetOption(CLI::App& command, std::string& subset)
{
  command.add_option("--subset", subset, "with a tileset: use the tiles of its subset NAME");
}

CLI::Option* AddOrderOption(
  CLI::App& command, std::string& order, const std::vector<std::string>& allowed)
{
  return command
    .add_option("--order", order,
      "the order sites are assigned in: scanline, random or entropy (fewest choices first)")
    ->check(CLI::IsMember(allowed));
}

CLI::Option* AddChoiceOption(
  CLI::App& command, std::string& choice, const std::vector<std::string>& allowed)
{
  return command
    .add_option("--choice", choice,
      "how a label is drawn: uniform, frequency (weighted by the example) or resemblance "
      "(favour labels whose 3x3x3 surroundings match the example)")
    ->check(CLI::IsMember(allowed));
}

CLI::Validator NonNegativeReal()
{
  return CLI::Validator(
    [](std::string& text)
    {
      char* end = nullptr;
      errno = 0;
      const double v = std::strtod(text.c_str(), &end);
      if (text.empty() || *end != '\0' || errno != 0 || !std::isfinite(v) || v < 0)
      {
        return "'" + msynth::Printable(text) + "' is not a non-negative number";
      }
      return std::string();
    },
    "NUMBER>=0");
}

int IndexIn(const std::string& value, const std::vector<std::string>& names)
{
  for (std::size_t i = 0; i < names.size(); ++i)
  {
    if (names[i] == value)
    {
      return static_cast<int>(i);
    }
  }
  return 0;
}

} // namespace cli
} // namespace msynth
