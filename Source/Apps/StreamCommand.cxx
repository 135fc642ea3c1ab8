// SPDX-License-Identifier: BSD-3-Clause
// `msynth synthesize EXAMPLE --size ... --block ... --stream [--slab N] [--resume]`: the world
// computed slab by slab in bounded memory (vtkMSDiscreteSynthesis::StreamNextUpdate, the engine's
// SynthesizeStreamed). Finished slabs go to DIR/.msynth-stream as they come, with a list of
// their files and checksums; the finished run publishes DIR/labels.pvti over DIR/labels/, the
// per-slab pictures and volumes and an overview picture together. An interrupted run leaves
// the stream folder once a slab is finished (Ctrl-C names them; before, it removes the folder
// and says there is nothing to resume); --resume checks every listed slab against the world's
// definition and its checksum and goes on from the first missing or damaged one.
#include "Common.h"
#include "Synthesize.h"

#include "vtkFieldData.h"
#include "vtkImageData.h"
#include "vtkMSDiscreteSynthesis.h"
#include "vtkMSLabelGridReader.h"
#include "vtkMSOnDemand.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkSmartPointer.h"
#include "vtkUnsignedCharArray.h"
#include "vtkXMLImageDataWriter.h"

#include "Core/AtomicFile.h"
#include "Core/Error.h"
#include "Core/FileBytes.h"
#include "Core/Fnv.h"
#include "Core/Index.h"
#include "Core/Memory.h"
#include "Core/OutputFolder.h"
#include "Discrete/DiscreteSynthesis.h"

#include <sys/resource.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <sstream>
#include <stdexcept>

namespace msynth
{
namespace cli
{
namespace
{
constexpr const char* StreamFolder = ".msynth-stream";

/// "SIZE:HASH" of a file's bytes (FNV-1a, 64 bits); empty when it cannot be read.
std::string FileStamp(const std::string& path)
{
  std::ifstream in(path, std::ios::binary);
  if (!in)
    return "";
  std::uint64_t hash = msynth::FnvStart, size = 0;
  char buffer[1 << 16];
  while (in.read(buffer, sizeof(buffer)) || in.gcount() > 0)
  {
    hash = msynth::Fnv1a(buffer, msynth::ToIndex(in.gcount()), hash);
    size += static_cast<std::uint64_t>(in.gcount());
  }
  char text[48];
  std::snprintf(text, sizeof(text), "%llu:%016llx", static_cast<unsigned long long>(size),
    static_cast<unsigned long long>(hash));
  return text;
}

/// What defines a stream's world: the example's bytes and every option that changes a label or
/// the slabs.
std::string WorldDefinition(const SynthesizeOptions& o)
{
  std::ostringstream d;
  auto list = [&d](const char* name, const auto& values)
  {
    d << name;
    for (const auto& v : values)
      d << " " << v;
    d << "\n";
  };
  d << "example " << o.Example << " " << FileStamp(o.Example) << "\n";
  list("size", o.Size3);
  list("block", o.Block);
  list("overlap", o.Overlap);
  d << "seed " << o.Seed << "\nattempts " << o.Attempts << "\nbacktracks " << o.Backtracks
    << "\nrepair " << !o.NoRepair << "\nstart " << o.Start << "\norder " << o.Order << "\nchoice "
    << o.Choice << "\nsubset " << o.Subset << "\ntiles " << o.Tiles << "\npattern " << o.Pattern
    << " " << o.Symmetry << " " << o.NoPeriodicInput << " " << o.SampleGround << "\nslab " << o.Slab
    << "\n";
  list("ground", o.Ground);
  list("empty", o.Empty);
  if (!o.Fixed.empty()) // the pins: a resumed stream keeps slabs made with the same ones
    d << "fixed " << o.Fixed << " " << FileStamp(o.Fixed) << " " << o.FixedEmptyFree << "\n";
  return d.str();
}

/// What --stream writes per slab: labels always, pictures and volumes as --outputs asks.
struct StreamOutputs
{
  bool Picture = false, Volume = false;
};

StreamOutputs StreamKinds(const SynthesizeOptions& o)
{
  const bool pictured = IsTileset(o.Example) || IsSample(o.Example);
  const std::string list = !o.Outputs.empty() ? o.Outputs
    : pictured                                ? "labels,picture"
                                              : "labels,vdb";
  StreamOutputs kinds;
  std::istringstream in(list);
  std::string kind;
  while (std::getline(in, kind, ','))
  {
    if (kind == "picture" && pictured)
      kinds.Picture = true;
    else if (kind == "vdb")
      kinds.Volume = true;
    else if (kind != "labels")
      throw std::runtime_error("--stream writes labels, pictures (of a tileset or an image "
                               "sample) and vdb volumes slab by slab, not '" +
        kind + "'");
  }
  return kinds;
}

/// The extent "x0,x1,y0,y1,z0,z1" of the slab file @p path as written (its WholeExtent); empty
/// when it cannot be read.
std::string WrittenExtent(const std::string& path)
{
  std::ifstream in(path, std::ios::binary);
  std::string head(4096, '\0');
  in.read(&head[0], static_cast<std::streamsize>(head.size()));
  head.resize(msynth::ToIndex(in.gcount()));
  const std::string key = "WholeExtent=\"";
  const std::size_t at = head.find(key);
  const std::size_t end = at == std::string::npos ? at : head.find('"', at + key.size());
  if (end == std::string::npos)
    return "";
  std::istringstream numbers(head.substr(at + key.size(), end - at - key.size()));
  std::string extent;
  long long v = 0;
  for (int k = 0; k < 6 && numbers >> v; ++k)
    extent += (k ? "," : "") + std::to_string(v);
  return extent;
}

/// A finished slab as a line of slabs.txt lists it: "J extent=X0,X1,Y0,Y1,Z0,Z1 FILE=STAMP ...".
struct ListedSlab
{
  std::string ExtentText; ///< as listed, "x0,x1,y0,y1,z0,z1"
  std::array<int, 6> Extent{};
  std::string Labels, Picture, Volume;
  std::vector<std::pair<std::string, std::string>> Stamps; ///< each file and its stamp
  /// "failed=OX,OY,OZ,EX,EY,EZ;...": the slab's failed blocks (origin, emptied site)
  std::vector<msynth::BlockFailure> Failures;
  bool FailuresDamaged = false;
};

/// The failed blocks of a slab's field data as listed in slabs.txt ("" when none failed).
std::string FailuresEntry(vtkImageData* slab)
{
  vtkFieldData* fd = slab->GetFieldData();
  vtkDataArray* origins = fd->GetArray("FailedBlockOrigins");
  vtkDataArray* sites = fd->GetArray("FailedBlockSites");
  if (!origins || !sites || origins->GetNumberOfTuples() == 0)
    return "";
  std::string entry = " failed=";
  for (vtkIdType i = 0; i < origins->GetNumberOfTuples(); ++i)
  {
    const double* o = origins->GetTuple3(i);
    const double* e = sites->GetTuple3(i);
    char text[160];
    std::snprintf(text, sizeof(text), "%s%.0f,%.0f,%.0f,%.0f,%.0f,%.0f", i ? ";" : "", o[0], o[1],
      o[2], e[0], e[1], e[2]);
    entry += text;
  }
  return entry;
}

/// Parses the value of a "failed=" entry into @p slab's Failures (FailuresDamaged when it is not
/// a list of six integers each).
void ParseFailures(const std::string& text, ListedSlab& slab)
{
  std::istringstream items(text);
  std::string item;
  while (std::getline(items, item, ';'))
  {
    long long v[6];
    int used = 0;
    if (std::sscanf(item.c_str(), "%lld,%lld,%lld,%lld,%lld,%lld%n", &v[0], &v[1], &v[2], &v[3],
          &v[4], &v[5], &used) != 6 ||
      ToIndex(used) != item.size() || v[0] < 0 || v[1] < 0 || v[2] < 0)
    {
      slab.FailuresDamaged = true;
      return;
    }
    msynth::BlockFailure f;
    f.Origin = { { v[0], v[1], v[2] } };
    f.EmptySite = { { v[3], v[4], v[5] } };
    slab.Failures.push_back(f);
  }
}

ListedSlab ParseSlab(const std::string& line)
{
  std::istringstream fields(line);
  std::string entry;
  fields >> entry; // the index
  ListedSlab slab;
  while (fields >> entry)
  {
    if (entry.rfind("extent=", 0) == 0)
    {
      slab.ExtentText = entry.substr(7);
      std::sscanf(slab.ExtentText.c_str(), "%d,%d,%d,%d,%d,%d", &slab.Extent[0], &slab.Extent[1],
        &slab.Extent[2], &slab.Extent[3], &slab.Extent[4], &slab.Extent[5]);
      continue;
    }
    if (entry.rfind("failed=", 0) == 0)
    {
      ParseFailures(entry.substr(7), slab);
      continue;
    }
    const std::size_t eq = entry.rfind('=');
    const std::string file = entry.substr(0, eq);
    slab.Stamps.emplace_back(file, eq == std::string::npos ? std::string() : entry.substr(eq + 1));
    for (auto [prefix, kind] : { std::make_pair("labels/", &slab.Labels),
           std::make_pair("picture/", &slab.Picture), std::make_pair("vdb/", &slab.Volume) })
      if (file.rfind(prefix, 0) == 0)
        *kind = file;
  }
  return slab;
}

/// Why the listed slab @p line cannot be kept (a file missing or damaged, an extent that is
/// not its file's, other outputs than @p kinds asks for); empty when it can.
std::string SlabProblem(const std::string& folder, const std::string& line, StreamOutputs kinds)
{
  const ListedSlab slab = ParseSlab(line);
  for (const auto& [file, stamp] : slab.Stamps)
    if (stamp.empty() || FileStamp(folder + "/" + file) != stamp)
      return "'" + file + "' is missing or damaged";
  if (slab.Labels.empty() || slab.ExtentText.empty() ||
    WrittenExtent(folder + "/" + slab.Labels) != slab.ExtentText)
    return "its extent is not its labels' extent";
  if (slab.Picture.empty() == kinds.Picture || slab.Volume.empty() == kinds.Volume)
    return "it was written with other --outputs";
  if (slab.FailuresDamaged)
    return "its list of failed blocks is damaged";
  return "";
}

/// Removes the files of @p folder's slab folders that no line of @p kept lists (the temporary
/// files of a slab being written when the run was interrupted, the slabs computed again).
void RemoveUnlisted(const std::string& folder, const std::vector<std::string>& kept)
{
  std::string listed = " ";
  for (const auto& line : kept)
    listed += line + " ";
  for (const std::string sub : { "labels", "picture", "vdb" })
    for (const auto& name : msynth::FolderEntries(folder + "/" + sub))
      if (listed.find(" " + sub + "/" + name + "=") == std::string::npos)
        msynth::RemoveTree(folder + "/" + sub + "/" + name);
}

/**
 * The slabs an interrupted stream in @p folder finished, as lines "J extent=E FILE=STAMP ...",
 * each checked (SlabProblem): the list ends at the first slab that cannot be kept (a note says
 * which and why). @throw std::runtime_error when the folder holds a stream of another world.
 */
std::vector<std::string> KeptSlabs(
  const std::string& folder, const std::string& definition, StreamOutputs kinds)
{
  std::vector<std::string> kept;
  struct stat info;
  if (::stat((folder + "/definition.txt").c_str(), &info) != 0)
  {
    std::cerr << "msynth: note: no interrupted stream to resume in '" << folder
              << "': starting one\n";
    return kept;
  }
  if (msynth::ReadFileBytes(folder + "/definition.txt", 1 << 20,
        "is too large for a stream's definition") != definition)
    throw std::runtime_error("'" + folder +
      "' holds a stream of another world (another example or other options): run with --stream "
      "instead of --resume to start again");
  std::ifstream slabs(folder + "/slabs.txt");
  std::string line;
  while (std::getline(slabs, line))
  {
    std::istringstream in(line);
    int j = -1;
    in >> j;
    if (j != static_cast<int>(kept.size()))
      break;
    const std::string problem = SlabProblem(folder, line, kinds);
    if (!problem.empty())
    {
      std::cerr << "msynth: note: slab " << j << " of the stream cannot be kept ("
                << msynth::Printable(problem) << "): computing it again\n";
      break;
    }
    kept.push_back(line);
  }
  return kept;
}

/// The pieces file over the slabs' .vti files.
void WritePvti(const std::string& path, vtkImageData* first, const std::array<int, 3>& size,
  const std::vector<std::array<int, 6>>& extents)
{
  double origin[3], spacing[3];
  first->GetOrigin(origin);
  first->GetSpacing(spacing);
  WriteFileAtomically(path,
    [&](std::ostream& out)
    {
      out << "<?xml version=\"1.0\"?>\n<VTKFile type=\"PImageData\" version=\"1.0\" "
             "byte_order=\"LittleEndian\" header_type=\"UInt64\">\n  <PImageData WholeExtent=\"0 "
          << size[0] - 1 << " 0 " << size[1] - 1 << " 0 " << size[2] - 1
          << "\" GhostLevel=\"0\" Origin=\"" << origin[0] << " " << origin[1] << " " << origin[2]
          << "\" Spacing=\"" << spacing[0] << " " << spacing[1] << " " << spacing[2]
          << "\" Direction=\"1 0 0 0 1 0 0 0 1\">\n    <PPointData Scalars=\"Label\">\n"
             "      <PDataArray type=\"Int32\" Name=\"Label\"/>\n"
             "      <PDataArray type=\"Int32\" Name=\"LastBlock\"/>\n    </PPointData>\n";
      for (std::size_t j = 0; j < extents.size(); ++j)
      {
        const auto& e = extents[j];
        char name[40];
        std::snprintf(name, sizeof(name), "labels/labels_%05zu.vti", j);
        out << "    <Piece Extent=\"" << e[0] << " " << e[1] << " " << e[2] << " " << e[3] << " "
            << e[4] << " " << e[5] << "\" Source=\"" << name << "\"/>\n";
      }
      out << "  </PImageData>\n</VTKFile>\n";
    });
}

/// The peak resident memory of the process so far, in MB.
double PeakMegabytes()
{
  rusage usage{};
  ::getrusage(RUSAGE_SELF, &usage);
  return static_cast<double>(usage.ru_maxrss) / 1024.0;
}

/// A picture of the whole world at most 2048 pixels a side, each pixel the mean of the
/// scale × scale pixels it stands for (thin lines stay visible as a tint), made from the slabs'
/// pictures @p pictures (of the sites @p extents) read back one at a time.
void WriteOverview(const std::vector<std::string>& pictures,
  const std::vector<std::array<int, 6>>& extents, const std::array<int, 3>& size,
  const std::string& path)
{
  int scale = 1, out[2] = { 0, 0 };
  double tile[2] = { 1, 1 };
  std::vector<std::uint32_t> sums; // RGBA sums and a count per overview pixel
  for (std::size_t j = 0; j < pictures.size(); ++j)
  {
    vtkSmartPointer<vtkAlgorithm> png = vtkMSOnDemand::NewPNGReader(pictures[j]);
    Run(png);
    vtkImageData* slab = vtkImageData::SafeDownCast(png->GetOutputDataObject(0));
    int dims[3];
    slab->GetDimensions(dims);
    const auto& e = extents[j];
    if (j == 0)
    {
      tile[0] = static_cast<double>(dims[0]) / (e[1] - e[0] + 1);
      tile[1] = static_cast<double>(dims[1]) / (e[3] - e[2] + 1);
      const double w = tile[0] * size[0], h = tile[1] * size[1];
      scale = std::max(1, static_cast<int>(std::ceil(std::max(w, h) / 2048.0)));
      if (scale > 2048) // the sums below would overflow
      {
        std::cerr << "msynth: note: no overview picture: the world's picture would be "
                  << static_cast<long long>(w) << " pixels wide\n";
        return;
      }
      out[0] = static_cast<int>(std::ceil(w / scale));
      out[1] = static_cast<int>(std::ceil(h / scale));
      sums.assign(msynth::ToIndex(out[0]) * out[1] * 5, 0);
    }
    const int components = slab->GetNumberOfScalarComponents();
    if (components != 3 && components != 4)
      throw std::runtime_error("'" + pictures[j] + "': not an RGB or RGBA picture");
    const int x0 = static_cast<int>(e[0] * tile[0]), y0 = static_cast<int>(e[2] * tile[1]);
    const auto* from = static_cast<const unsigned char*>(slab->GetScalarPointer());
    for (int y = 0; y < dims[1]; ++y)
      for (int x = 0; x < dims[0]; ++x)
      {
        const int u = (x0 + x) / scale, v = (y0 + y) / scale;
        if (u >= out[0] || v >= out[1])
          continue;
        std::uint32_t* sum = sums.data() + (msynth::ToIndex(v) * out[0] + u) * 5;
        const unsigned char* pixel = from + (msynth::ToIndex(y) * dims[0] + x) * components;
        for (int c = 0; c < 4; ++c)
          sum[c] += c < components ? pixel[c] : 255;
        ++sum[4];
      }
  }
  if (pictures.empty())
    return;
  vtkNew<vtkImageData> overview;
  overview->SetDimensions(out[0], out[1], 1);
  overview->AllocateScalars(VTK_UNSIGNED_CHAR, 4);
  auto* to = static_cast<unsigned char*>(overview->GetScalarPointer());
  for (std::size_t p = 0; p < msynth::ToIndex(out[0]) * out[1]; ++p)
  {
    const std::uint32_t n = std::max<std::uint32_t>(1, sums[p * 5 + 4]);
    for (std::size_t c = 0; c < 4; ++c)
      to[p * 4 + c] = static_cast<unsigned char>((sums[p * 5 + c] + n / 2) / n);
  }
  WritePicturePng(overview, path);
}

/// "slab 3/16, 1.2 M sites/s, 25 s left" on a terminal's stderr.
class StreamProgress
{
public:
  explicit StreamProgress(int first)
    : Start(std::chrono::steady_clock::now())
    , First(first)
    , Shown(::isatty(STDERR_FILENO) != 0)
  {
  }
  ~StreamProgress()
  {
    if (this->Shown && this->Done > 0)
      std::cerr << "\n";
  }
  void Slab(int j, int count, double sites)
  {
    this->Sites += sites;
    this->Done = j + 1 - this->First;
    if (!this->Shown)
      return;
    const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - this->Start).count();
    const double left = seconds / this->Done * (count - j - 1);
    std::fprintf(stderr, "\rstream: slab %d/%d, %.2f M sites/s, %.0f s left   ", j + 1, count,
      this->Sites / std::max(seconds, 1e-9) / 1e6, left);
  }

private:
  std::chrono::steady_clock::time_point Start;
  int First = 0;
  bool Shown = false;
  int Done = 0;
  double Sites = 0;
};

/// --slab, or for pictures slabs of about 2^18 sites (a picture of 8 x 8 pixel tiles then has
/// 16 M pixels); 0: the engine's choice.
int SlabThickness(const SynthesizeOptions& o, const StreamOutputs& kinds)
{
  if (o.Slab > 0 || !kinds.Picture)
    return o.Slab;
  msynth::SynthesisOptions shape;
  for (std::size_t a = 0; a < 3; ++a)
  {
    shape.Size[a] = o.Size3[a];
    shape.BlockSize[a] = o.Block[a];
    shape.Overlap[a] = o.Overlap[a];
  }
  return static_cast<int>(msynth::PlanStream(shape).LayersOf(std::int64_t(1) << 18));
}

std::vector<ListedSlab> ListedSlabs(const std::string& folder)
{
  std::vector<ListedSlab> listed;
  std::ifstream in(folder + "/slabs.txt");
  std::string line;
  while (std::getline(in, line))
    listed.push_back(ParseSlab(line));
  return listed;
}

/// Moves the finished stream from @p folder into the staging folder @p dir with its pieces
/// file, overview picture and statistics, and says what was written.
int PublishStream(const SynthesizeOptions& o, const std::string& dir, const std::string& folder,
  vtkImageData* output, std::size_t resumed, std::chrono::steady_clock::time_point start)
{
  const std::vector<ListedSlab> slabs = ListedSlabs(folder);
  std::vector<std::array<int, 6>> extents;
  std::vector<std::string> pictures;
  bool volumes = false;
  for (const auto& slab : slabs)
  {
    extents.push_back(slab.Extent);
    if (!slab.Picture.empty())
      pictures.push_back(dir + "/" + slab.Picture);
    volumes = volumes || !slab.Volume.empty();
  }
  std::vector<std::string> written{ dir + "/labels.pvti", dir + "/labels/" };
  std::vector<std::string> moved{ "labels" };
  if (pictures.size() == slabs.size() && !pictures.empty())
    moved.push_back("picture");
  if (volumes)
    moved.push_back("vdb");
  for (const auto& sub : moved)
    if (std::rename((folder + "/" + sub).c_str(), (dir + "/" + sub).c_str()) != 0)
      throw std::runtime_error("'" + dir + "/" + sub + "': could not be made");
  WritePvti(dir + "/labels.pvti", output, o.Size3, extents);
  if (moved.size() > 1 && moved[1] == "picture")
  {
    WriteOverview(pictures, extents, o.Size3, dir + "/picture.png");
    written.push_back(dir + "/picture/");
    written.push_back(dir + "/picture.png");
  }
  if (volumes)
    written.push_back(dir + "/vdb/");
  WriteStatistics(output, o, dir,
    { { "Slabs", std::to_string(slabs.size()) }, { "SlabsResumed", std::to_string(resumed) },
      { "PeakMemoryMB", JsonNumber(PeakMegabytes()) } });
  written.push_back(dir + "/statistics.json");
  msynth::RemoveTree(folder);
  vtkFieldData* fd = output->GetFieldData();
  char timing[96];
  std::snprintf(timing, sizeof(timing), "total %.2f s, peak memory %.0f MB",
    std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(),
    PeakMegabytes());
  std::cout << MessageOf(fd) << "\n"
            << o.Size3[0] << " x " << o.Size3[1] << " x " << o.Size3[2] << " sites in "
            << Counted(static_cast<long long>(slabs.size()), "slab") << ", "
            << Counted(CountOf(fd, "Blocks"), "block") << " (" << CountOf(fd, "BlocksFailed")
            << " failed), " << timing << "\nwrote ";
  for (std::size_t i = 0; i < written.size(); ++i)
    std::cout << (i ? ", " : "") << written[i];
  std::cout << "\n";
  return 0;
}
/// What Ctrl-C finds of a stream in @p folder once @p slabs are finished (of @p count, when
/// known): the slabs and --resume. @p listing runs with it: the slab listed as the note changes.
void KeptNote(const std::string& folder, std::size_t slabs, int count,
  const std::function<void()>& listing = nullptr)
{
  SetInterruptNote(Counted(static_cast<long long>(slabs), "finished slab") +
      (count > 0 ? " of " + std::to_string(count) : std::string()) + (slabs == 1 ? " is" : " are") +
      " kept in '" + folder + "': the same command with --resume goes on from " +
      (slabs == 1 ? "it" : "them"),
    "", listing);
}

/// The stream's folder @p folder made ready: the slabs an interrupted run left that --resume
/// keeps (returned), the rest removed, the world's definition and the list written. Until a slab
/// is finished there is nothing to go on from: Ctrl-C removes the folder and says so.
std::vector<std::string> StartStreamFolder(
  const SynthesizeOptions& o, const std::string& folder, StreamOutputs kinds)
{
  const std::string definition = WorldDefinition(o);
  std::vector<std::string> kept;
  if (o.Resume)
    kept = KeptSlabs(folder, definition, kinds);
  if (kept.empty())
  {
    SetInterruptNote(
      "no slab was finished, so there is nothing to --resume: the same command starts again",
      folder);
    msynth::RemoveTree(folder);
  }
  else
  {
    KeptNote(folder, kept.size(), 0);
    RemoveUnlisted(folder, kept);
  }
  for (const char* sub : { "", "/labels", "/picture", "/vdb" })
    ::mkdir((folder + sub).c_str(), 0755);
  WriteFileAtomically(folder + "/definition.txt", [&](std::ostream& out) { out << definition; });
  WriteFileAtomically(folder + "/slabs.txt",
    [&](std::ostream& out)
    {
      for (const auto& line : kept)
        out << line << "\n";
    });
  return kept;
}
} // namespace

void AddStreamOptions(
  CLI::App& s, SynthesizeOptions& o, const std::function<void(CLI::Option*)>& discrete)
{
  discrete(s.add_flag("--stream", o.Stream,
    "compute the world slab by slab in bounded memory: DIR/labels.pvti over DIR/labels/, "
    "per-slab pictures and volumes; needs --block"));
  discrete(s.add_option("--slab", o.Slab,
              "a stream's slab thickness in sites (default: about "
              "2 million sites a slab)")
             ->check(CLI::Range(1, 1 << 30)));
  discrete(s.add_flag("--resume", o.Resume,
    "go on with the stream an interrupted --stream run left in DIR, keeping its finished slabs"));
}

bool StreamsForMemory(const SynthesizeOptions& o)
{
  double sites = 1;
  bool blocks = false;
  for (std::size_t a = 0; a < 3; ++a)
  {
    sites *= o.Size3[a];
    blocks = blocks || (o.Block[a] > 0 && o.Block[a] < o.Size3[a]);
  }
  const bool whole = !o.Guide.empty() || o.Snapshots > 0 || !o.Mirror.empty() ||
    !o.Translate.empty() || o.Rotate || !o.Targets.empty() || !o.Counts.empty() ||
    !o.Connected.empty() || o.Choice == "resemblance" ||
    std::any_of(o.Region.begin(), o.Region.end(), [](int v) { return v != 0; });
  // The model, its last blocks, the output's arrays and the writer's copy: about 24 bytes a
  // site, besides what the outputs (meshes, volumes) take.
  const double bytes = 24 * sites;
  const double available = static_cast<double>(msynth::AvailableMemory());
  if (!blocks || whole || bytes < 0.5 * available)
    return false;
  std::cerr << "msynth: note: a " << o.Size3[0] << " x " << o.Size3[1] << " x " << o.Size3[2]
            << " model would take about " << msynth::FormatBytes(static_cast<std::uint64_t>(bytes))
            << " of the " << msynth::FormatBytes(static_cast<std::uint64_t>(available))
            << " available: it is streamed slab by slab instead (labels.pvti; --stream)\n";
  return true;
}

int SynthesizeStream(const SynthesizeOptions& o, const std::string& dir)
{
  const auto start = std::chrono::steady_clock::now();
  if (!o.Guide.empty() || o.Snapshots > 0)
    throw std::runtime_error("--stream computes the world a slab at a time: it takes no "
                             "--guide or --snapshots (each needs the whole world)");
  if (std::any_of(o.Region.begin(), o.Region.end(), [](int v) { return v != 0; }))
    throw std::runtime_error("--stream computes the whole world: use --region without it for "
                             "one region");
  const StreamOutputs kinds = StreamKinds(o);
  // The stream's own folder beside the staging folder, in the output folder: kept when the run
  // is interrupted, for --resume.
  const std::string folder = dir.substr(0, dir.rfind('/')) + "/" + StreamFolder;
  const std::vector<std::string> kept = StartStreamFolder(o, folder, kinds);
  std::ofstream slabs(folder + "/slabs.txt", std::ios::app);

  vtkNew<vtkMSLabelGridReader> reader;
  vtkNew<vtkMSDiscreteSynthesis> synthesis;
  SetUpDiscrete(o, reader, synthesis);
  StreamProgress progress(static_cast<int>(kept.size()));
  std::size_t finished = 0; // slabs this run wrote
  const int thickness = SlabThickness(o, kinds);
  std::vector<msynth::BlockFailure> keptFailures; // reported again, as a whole run reports them
  for (const auto& line : kept)
  {
    const ListedSlab slab = ParseSlab(line);
    keptFailures.insert(keptFailures.end(), slab.Failures.begin(), slab.Failures.end());
  }
  synthesis->StreamNextUpdate(
    thickness, static_cast<int>(kept.size()),
    [&](vtkImageData* slab, int j, int count)
    {
      char name[3][48];
      std::snprintf(name[0], sizeof(name[0]), "labels/labels_%05d.vti", j);
      std::snprintf(name[1], sizeof(name[1]), "picture/picture_%05d.png", j);
      std::snprintf(name[2], sizeof(name[2]), "vdb/model_%05d.vdb", j);
      WriteXML<vtkXMLImageDataWriter>(folder + "/" + name[0], slab);
      int e[6];
      slab->GetExtent(e);
      std::string line = std::to_string(j) + " extent=" + std::to_string(e[0]);
      for (int k = 1; k < 6; ++k)
        line += "," + std::to_string(e[k]);
      line += std::string(" ") + name[0] + "=" + FileStamp(folder + "/" + name[0]);
      line += FailuresEntry(slab);
      std::vector<std::string> pictures;
      if (kinds.Picture)
        WritePicture(slab, o, folder + "/" + name[1], pictures);
      if (!pictures.empty())
        line += std::string(" ") + name[1] + "=" + FileStamp(folder + "/" + name[1]);
      if (kinds.Volume)
      {
        WriteModelVolume(slab, o, folder + "/" + name[2], "synthesize --stream", nullptr);
        line += std::string(" ") + name[2] + "=" + FileStamp(folder + "/" + name[2]);
      }
      // Listed and said together: Ctrl-C names the slabs slabs.txt lists.
      KeptNote(folder, kept.size() + finished + 1, count,
        [&]()
        {
          slabs << line << "\n" << std::flush;
          if (!slabs)
            throw std::runtime_error("'" + folder + "/slabs.txt': could not be written");
        });
      progress.Slab(j, count, static_cast<double>(slab->GetNumberOfPoints()));
      ++finished;
      return true;
    },
    keptFailures);
  try
  {
    RunDiscrete(synthesis, o);
  }
  catch (const std::exception&)
  {
    SetInterruptNote("");
    if (kept.empty() && finished == 0) // nothing to resume: the output folder stays as it was
      msynth::RemoveTree(folder);
    throw;
  }
  SetInterruptNote("");
  return PublishStream(o, dir, folder, synthesis->GetOutput(), kept.size(), start);
}

} // namespace cli
} // namespace msynth
