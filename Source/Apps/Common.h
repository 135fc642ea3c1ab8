// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/**
 * @file Common.h
 * @brief What every msynth command shares: checking input files, running VTK algorithms with
 * their errors as one message, staged output folders, writing VTK XML, CSV and JSON files,
 * statistics.json from field data, the progress bar, and the options several commands
 * take (registered with CLI11 the same way everywhere).
 */
#include "vtkErrorCode.h"
#include "vtkMSEngineBridge.h"
#include "vtkMSFieldData.h"
#include "vtkNew.h"

#include "Core/AtomicFile.h"
#include "Core/BlockSynthesis.h"

#include <CLI/CLI.hpp>

#include <cerrno>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <functional>
#include <stdexcept>
#include <string>
#include <vector>

class vtkAlgorithm;
class vtkFieldData;
class vtkImageData;
class vtkTable;

namespace msynth
{
namespace cli
{

/// A usage problem found after parsing (an option that does not fit the example): exit 2 with
/// "msynth COMMAND: What; see msynth COMMAND --help".
struct UsageError
{
  std::string What;
};

/// True when @p path names a simple-tiled tileset (.xml) rather than a label grid.
bool IsTileset(const std::string& path);
/// True when @p path names an image sample (.png, .bmp) of the overlapping model.
bool IsSample(const std::string& path);
/// A polyhedral example of continuous model synthesis (.obj, .vtp, .ply, .stl).
bool IsPolyhedral(const std::string& path);

/**
 * An input file given on the command line: it must be a regular file (not a folder, a pipe or
 * a device) of a kind msynth reads. @throw std::runtime_error saying which.
 */
void CheckInputFile(const std::string& path, bool model = false);

/**
 * The most sites a command that takes about @p bytesPerSite bytes a site (measured: its reader,
 * its filters and their copies together) may read from a file: the memory available divided by
 * that, at most @p ceiling. A file declaring more is refused by its reader before anything is
 * allocated (vtkMSLabelGridReader::MaximumNumberOfSites).
 */
long long SitesWithinMemory(unsigned bytesPerSite, long long ceiling);

/// Runs @p algorithm, turning its VTK errors into one exception message.
void Run(vtkAlgorithm* algorithm);
/// Runs a synthesis filter as Run does, its messages about its list properties (Counts,
/// Connected, Path) naming the command's options instead (--count, --connected, --path).
void RunSynthesis(vtkAlgorithm* algorithm);

/**
 * Runs @p command with a staging folder inside @p out and publishes its files together when it
 * succeeds (msynth::OutputFolder): a failed or interrupted run leaves @p out as it was. What the
 * command prints names the final files, and is printed once they are there, then a note naming
 * the files of an earlier run it replaced or removed (ReplacedNote). With @p replaced, those
 * names go there instead of the note (a batch says it once for all its entries).
 */
int IntoFolder(const std::string& out, const std::function<int(const std::string&)>& command,
  std::vector<std::string>* replaced = nullptr);
/// "msynth: note: this run replaced the earlier outputs in 'DIR' (a, b, ... and N more) and
/// removed those it did not write again (c)" for the @p replaced and @p removed names of @p dir;
/// "" when there are none.
std::string ReplacedNote(const std::string& dir, const std::vector<std::string>& replaced,
  const std::vector<std::string>& removed = {});

/// What an interrupted run says after "no outputs were written" (empty: nothing): a streamed
/// run names what it keeps and how to go on. Set while the run goes; read by the signal thread.
/// @p discard: a folder the signal thread removes before it says so (a stream's folder before
/// its first slab is finished: nothing in it to resume). @p change, when given, runs first under
/// the same lock: what the note describes changes with it (a slab listed), never apart.
void SetInterruptNote(const std::string& note, const std::string& discard = "",
  const std::function<void()>& change = nullptr);
std::string InterruptNote();
std::string InterruptDiscard();
/// What an interrupted run has written, said instead of "no outputs were written" (empty: that):
/// a batch's finished entries. Set while the run goes; read by the signal thread.
void SetInterruptDone(const std::string& done);
std::string InterruptDone();

/// @p table as CSV (a header of column names), written atomically.
void WriteCSV(const std::string& path, vtkTable* table);
/// @p items joined by @p separator (a filter's list property from repeated options).
std::string Joined(const std::vector<std::string>& items, const char* separator = ",");
/// @p text as a JSON string literal.
std::string JsonString(const std::string& text);
/// @p value as JSON writes it ("%g" with six significant digits: 0.25, 1e-07).
std::string JsonNumber(double value);

/**
 * DIR/statistics.json of every command: its members in the order added, each a key and its
 * value as JSON text, written as "{\n  \"key\": value,\n  ...\n}\n" (Write, atomically).
 */
class StatisticsJson
{
public:
  /// @p json is the value's JSON text (an array, an object).
  StatisticsJson& Raw(const std::string& key, const std::string& json);
  StatisticsJson& Text(const std::string& key, const std::string& text);
  StatisticsJson& Number(const std::string& key, double value);
  StatisticsJson& Count(const std::string& key, long long value);
  StatisticsJson& Flag(const std::string& key, bool value);
  StatisticsJson& Counts(const std::string& key, const std::vector<long long>& values);
  /// A solver's statistics from its output's field data under their one naming
  /// (vtkMSFieldData::AddStatistics: Blocks, ..., Seconds).
  StatisticsJson& Solver(vtkFieldData* fd);
  /// An object of the one-value arrays of @p fd whose names start with @p prefix (the prefix
  /// dropped from the keys).
  StatisticsJson& Prefixed(const std::string& key, vtkFieldData* fd, const std::string& prefix);
  /// "Counts": [{"label", "minimum", "maximum", "achieved"}, ...] from field data `CountNames`,
  /// `CountMinimum`, `CountMaximum`, `CountAchieved` (vtkMSDiscreteSynthesis); nothing without.
  StatisticsJson& LabelCounts(vtkFieldData* fd);
  /// "Connected": {"labels", "maximum", "components", "before", "repairs", "redone"} from field
  /// data `Connected*` (vtkMSDiscreteSynthesis); nothing without.
  StatisticsJson& Connected(vtkFieldData* fd);
  /// The file @p path, written atomically.
  void Write(const std::string& path) const;

private:
  std::vector<std::pair<std::string, std::string>> Members;
};

/// "NX x NY x NZ" of the three values at @p v.
std::string Triple(const int* v);

/// "1 block", "2 blocks": @p n and @p thing, made plural (@p plural, or @p thing + "s") unless
/// @p n is 1.
std::string Counted(long long n, const std::string& thing, const std::string& plural = "");

/// The solver's one-line message from field data `Message`.
std::string MessageOf(vtkFieldData* fd, const char* name = "Message");
/// The one-value count @p name of field data (0 when it is not there).
long long CountOf(vtkFieldData* fd, const char* name);

/// A progress bar on stderr while @p algorithm runs, when stderr is a terminal.
class ProgressBar
{
public:
  /// Shows "STAGE [####    ] 45%" on a terminal from @p algorithm's progress, from the start
  /// (so a stage without progress events still says what runs); with @p delay > 0, only once
  /// the stage has run that many seconds (quick writes stay quiet).
  explicit ProgressBar(
    vtkAlgorithm* algorithm, const char* stage = "synthesis", double delay = 0.0);
  ~ProgressBar();
  ProgressBar(const ProgressBar&) = delete;
  ProgressBar& operator=(const ProgressBar&) = delete;

private:
  void OnProgress(double fraction);
  vtkAlgorithm* Algorithm;
  std::string Stage;
  double Delay;
  std::chrono::steady_clock::time_point Start;
  unsigned long Observer = 0;
  bool Shown = false;
};

/// Writes @p data with the VTK XML writer @p WriterT (compressed, appended), atomically, and
/// reproducibly: without its timing (vtkMSFieldData::WithoutTiming). @p int32Ids writes point
/// ids and offsets as 32-bit integers (half the bytes to compress, for meshes of under 2^31
/// points). @p fast compresses with LZ4 instead of zlib and stores the appended bytes raw instead
/// of base64: for meshes of millions of faces, about ten times faster to write and to read, for a
/// file about twice as large.
template <typename WriterT, typename DataT>
void WriteXML(const std::string& path, DataT* data, bool int32Ids = false, bool fast = false)
{
  const std::string tmp = msynth::TemporaryPathBeside(path);
  vtkNew<WriterT> writer;
  writer->SetInputData(vtkMSFieldData::WithoutTiming(data));
  writer->SetFileName(tmp.c_str());
  writer->SetDataModeToAppended();
  if (fast)
  {
    writer->SetCompressorTypeToLZ4();
    writer->EncodeAppendedDataOff();
  }
  else
    writer->SetCompressorTypeToZLib();
  if (int32Ids)
    writer->SetIdTypeToInt32();
  std::string messages;
  errno = 0;
  // The bar names the file: writing a large model can take longer than making it.
  const std::string name = path.substr(path.find_last_of('/') + 1);
  ProgressBar bar(writer, name.c_str(), 0.5);
  const bool ran = vtkMSEngineBridge::Execute(writer, messages);
  const int saved = errno; // the system's reason, read before anything else can change it
  if (!ran || writer->GetErrorCode() != 0)
  {
    const std::string reason = saved != 0 ? std::strerror(saved)
      : writer->GetErrorCode() ? vtkErrorCode::GetStringFromErrorCode(writer->GetErrorCode())
                               : messages;
    std::remove(tmp.c_str());
    throw std::runtime_error("'" + path + "': could not be written: " + reason);
  }
  msynth::CommitTemporaryFile(tmp, path);
}

/// The RGBA image @p rgba (VTK rows bottom first) as a PNG, top row first (msynth::WritePng).
void WritePicturePng(vtkImageData* rgba, const std::string& path);

/// Writes @p source's time steps as DIR/catalog_0001.vdb, ... (voxel size @p voxel for points;
/// 0: the writer's default) with file metadata @p key = @p value.
void WriteCatalogSequence(vtkAlgorithm* source, const std::string& dir, double voxel,
  const char* key, const std::string& value);

// ---------------------------------------------------------------------------------------------
// Options several commands take, registered the same way everywhere.
// ---------------------------------------------------------------------------------------------

/// `--out DIR` (default @p out's value: ./msynth-output, ./msynth-batch for batch); an empty
/// name is a usage error.
CLI::Option* AddOutOption(CLI::App& command, std::string& out);
/// `--seed S`: a decimal whole number in the signed 64-bit range; anything else, a usage error.
void AddSeedOption(CLI::App& command, std::int64_t& seed);
/// `--attempts N` with @p what (attempts per block, or per block of the arrangement).
void AddAttemptsOption(CLI::App& command, int& attempts, const std::string& what);
/// `--snapshots N` with @p what.
void AddSnapshotsOption(CLI::App& command, int& snapshots, const std::string& what);
struct PolyhedralReading;
/// `--types NAME=TYPE,...` (object types of a polyhedral example) and `--up y|z`; returns the two
/// options.
std::vector<CLI::Option*> AddTypesOption(CLI::App& command, PolyhedralReading& reading);
/// `--pattern N`, `--symmetry S` and `--no-periodic-input` of image samples, in their own group;
/// returns the three options.
std::vector<CLI::Option*> AddPatternOptions(
  CLI::App& command, int& n, int& symmetry, bool& noPeriodicInput);
/// `--subset NAME` (a tileset's subset).
void AddSubsetOption(CLI::App& command, std::string& subset);
/// `--order` from @p allowed (scanline, random, entropy).
CLI::Option* AddOrderOption(
  CLI::App& command, std::string& order, const std::vector<std::string>& allowed);
/// `--choice` from @p allowed (uniform, frequency, resemblance).
CLI::Option* AddChoiceOption(
  CLI::App& command, std::string& choice, const std::vector<std::string>& allowed);

/// A finite number at least 0 ("'x' is not a non-negative number" otherwise).
CLI::Validator NonNegativeReal();

/// The index of @p value in @p names (the order of the filters' enums).
int IndexIn(const std::string& value, const std::vector<std::string>& names);

} // namespace cli
} // namespace msynth
