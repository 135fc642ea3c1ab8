// SPDX-License-Identifier: BSD-3-Clause
// msynth: ModelSynth's command line.
//
//   msynth info EXAMPLE                  labels, counts and transition tables (Eq. 3.2);
//                                        for EXAMPLE.obj|.vtp|.ply|.stl the neighbourhood
//                                        labels of continuous synthesis
//   msynth analyze EXAMPLE [--out DIR]   the analysis as CSV tables plus the example as .vdb
//   msynth synthesize EXAMPLE --size NX NY NZ [options]   discrete model synthesis
//   msynth check EXAMPLE MODEL.vti       verify the adjacency constraint (Eq. 3.1)
//
// Exit status: 0 on success, 1 when the work fails (bad input, unwritable output), 2 on a
// usage error. Errors are one line on stderr naming the file and the problem.
#include "vtkMSArrangementMesh.h"
#include "vtkMSContinuousSynthesis.h"
#include "vtkMSDiscreteSynthesis.h"
#include "vtkMSEngineBridge.h"
#include "vtkMSLabelGeometry.h"
#include "vtkMSLabelGridReader.h"
#include "vtkMSLabelGridWriter.h"
#include "vtkMSNeighbourhoodLabels.h"
#include "vtkMSOpenVDBWriter.h"
#include "vtkMSPlaneArrangement.h"
#include "vtkMSPolyhedralExampleReader.h"
#include "vtkMSTileImage.h"
#include "vtkMSTransitionTables.h"

#include "vtkAbstractArray.h"
#include "vtkCellArray.h"
#include "vtkCellArrayIterator.h"
#include "vtkCellData.h"
#include "vtkCommand.h"
#include "vtkDataArray.h"
#include "vtkErrorCode.h"
#include "vtkFieldData.h"
#include "vtkIdTypeArray.h"
#include "vtkImageData.h"
#include "vtkIntArray.h"
#include "vtkLogger.h"
#include "vtkNew.h"
#include "vtkOutputWindow.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkSmartPointer.h"
#include "vtkStringArray.h"
#include "vtkTable.h"
#include "vtkUnsignedCharArray.h"
#include "vtkVariant.h"
#include "vtkXMLImageDataReader.h"
#include "vtkXMLImageDataWriter.h"
#include "vtkXMLPolyDataReader.h"
#include "vtkXMLPolyDataWriter.h"

#include "Continuous/ContinuousMesh.h"
#include "Core/AtomicFile.h"
#include "Core/Error.h"
#include "Core/OutputFolder.h"
#include "Discrete/ConsistencyCheck.h"
#include "Discrete/TimeVarying.h"
#include "Formats/Image.h"
#include "Formats/Tileset.h"
#include "Formats/VTKXMLCheck.h"

#include <array>
#include <atomic>
#include <cerrno>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <functional>
#include <iomanip>
#include <iostream>
#include <pthread.h>
#include <sstream>
#include <string>
#include <sys/stat.h>
#include <thread>
#include <unistd.h>
#include <vector>

namespace
{

const char* const Usage = R"(usage:
  msynth info EXAMPLE                 print the example's labels and transition tables;
                                      for a polyhedral EXAMPLE (.obj, .vtp, .ply, .stl) its
                                      neighbourhood labels (continuous model synthesis)
  msynth analyze EXAMPLE [--out DIR]  write DIR/labels.csv, DIR/transitions.csv, DIR/example.vdb;
                                      for a polyhedral EXAMPLE, DIR/labels.csv and
                                      DIR/marked-example.vtp (label ids on its features)
  msynth synthesize EXAMPLE --size NX NY NZ [--seed S] [--block BX BY BZ] [--out DIR]
                                      discrete model synthesis: writes DIR/labels.vti,
                                      DIR/mesh.vtp, DIR/model.vdb and DIR/statistics.json
                                      (and DIR/model.txt or DIR/model.vox in the format of a
                                      .txt or .vox EXAMPLE); the files appear together, or
                                      not at all when the run fails or is interrupted
  msynth synthesize EXAMPLE.obj --size SX SY SZ [--spacing S] [--seed S] [--out DIR]
                                      continuous model synthesis in a box of SX x SY x SZ
                                      example units (SZ ignored for a 2D example): writes
                                      DIR/model.vtp, DIR/arrangement.vtp (labels and catalog
                                      fields), DIR/model.vdb (level sets surface and
                                      surface_TYPE, fog volume density) and DIR/statistics.json
  msynth animate EXAMPLE... --size NX NY NZ --frames N [--loop] [--block BX BY BZ
                [--block-frames BT]] [--seed S] [--out DIR]
                                      time-varying synthesis (dissertation 3.5.4): one EXAMPLE
                                      image whose z slices are the frames, or one file per
                                      frame; writes DIR/frame_0000.vti ... (a series ParaView
                                      opens as time steps), DIR/model_0001.vdb ... and
                                      DIR/statistics.json; --loop joins the last frame to the
                                      first
  msynth check EXAMPLE MODEL.vti      verify that MODEL satisfies the adjacency constraint
                                      of EXAMPLE (exit 0) or list violations (exit 1)
  msynth check EXAMPLE.obj MODEL.vtp  verify a continuous model: closed, oriented, and only
                                      the example's neighbourhoods (Eq. 4.1)
  msynth --help | --version

synthesize options:
  --seed S            random seed (default 0); same inputs and seed give the same model
  --block BX BY BZ    block size of Algorithm 3.4 (default: the whole model, Algorithm 3.1)
  --attempts N        attempts per block (default 10)
  --threads N         threads for block synthesis (default: one per core; same result)
  --order ORDER       scanline (default), random or entropy (minimum entropy first)
  --choice CHOICE     uniform (default), frequency (labels weighted by the example) or
                      resemblance (favour labels whose 3x3x3 surroundings match the example)
  --ground LABEL      fix LABEL along the bottom face (-z, or -y for 2D outputs)
  --empty LABEL       fix LABEL on every other face (usually the empty label 0) but those
                      of translated axes
  --outputs LIST      which files discrete synthesis writes, from labels (labels.vti), mesh
                      (mesh.vtp), vdb (model.vdb), picture (picture.png, tilesets), txt
                      (model.txt) and vox (model.vox); default: labels,picture for a tileset,
                      labels,mesh,vdb for a label grid, plus txt or vox for such an example
                      (statistics.json is always written)
  --pieces DIR        mesh each label with DIR/<label>.obj|.vtp|.ply|.stl (default: voxels);
                      with a tileset also DIR/<tile>.obj, turned for each orientation
  --mirror AXES       make the output mirror-symmetric along AXES (x, y, z or e.g. xy)
  --swap A:B          labels A and B are each other's mirror images (repeatable)
  --translate AXES    make the output repeat along AXES (x, y, z or e.g. xy); with the
                      default period (the output size) it tiles seamlessly
  --period PX PY PZ   periods of the translated axes (0: the output size)
  --shift A:B         label A's image one period on is B (repeatable; default: itself)
  --rotate            make the output look the same turned 90 degrees about the vertical
                      (needs a square output in x and y)
  --turn A:B          label A turned 90 degrees counter-clockwise is B (repeatable)
  --subset NAME       with a tileset: use the tiles of its subset NAME
  --types N=T,...     with an OBJ example: object (or base) name N has object type T
  --target L:F        soft constraint: aim for fraction F of label L (repeatable; needs --block)
  --temperature T     temperature of the soft constraints' Metropolis acceptance (0.01)
  --guide GUIDE.vti   large-scale constraints: image data over the output box whose point
                      arrays Weight_<label> weight each label (0 forbids it there)
  --snapshots N       catalog snapshots per block, also written as the sequence
                      DIR/catalog_0001.vdb ... (Label, CatalogSize, Entropy per site)

continuous (EXAMPLE.obj|.vtp|.ply|.stl) synthesize options:
  --spacing S         smallest plane spacing (default: derived from the example's planes)
  --blocks B          block edge in plane spacings (default 4; 0 = the whole model at once)
  --attempts N, --order scanline|random|entropy (default entropy), --choice uniform|frequency,
  --seed S, --types N=T,... as above; --voxel V sets the .vdb voxel size (default: a quarter
  of the smallest plane spacing, at least 1/256 of the model's extent)
  --snapshots N       also write the catalog at the start, N-1 moments and the end as the
                      sequence DIR/catalog_0001.vdb ... (CatalogSize, Entropy, Label per voxel)

Other options: --verbose shows VTK's own diagnostics as well.

EXAMPLE is a label grid (.vti with an integer array 'Label', the original program's .txt
format, or MagicaVoxel .vox) or a simple-tiled tileset (.xml; synthesize also writes
DIR/picture.png from the tile images).
DIR defaults to ./msynth-output.
)";

struct UsageError
{
  std::string What;
};

/// True when @p path names a simple-tiled tileset (.xml) rather than a label grid.
bool IsTileset(const std::string& path)
{
  return path.size() > 4 && path.compare(path.size() - 4, 4, ".xml") == 0;
}

/// A polyhedral example of continuous model synthesis (.obj, .vtp, .ply, .stl).
bool IsPolyhedral(const std::string& path)
{
  return vtkMSPolyhedralExampleReader::CanReadFile(path.c_str()) != 0;
}

/**
 * An input file given on the command line: it must be a regular file (not a folder, a pipe or
 * a device) of a kind msynth reads. @throw std::runtime_error saying which.
 */
void CheckInputFile(const std::string& path, bool model = false)
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
  static const char* const known[] = { ".vti", ".txt", ".vox", ".xml", ".obj", ".vtp", ".ply",
    ".stl" };
  bool ok = false;
  for (const char* k : known)
  {
    ok |= ext == k;
  }
  if (!ok)
  {
    throw std::runtime_error("'" + path + "': " +
      (ext.empty() ? std::string("has no extension")
                   : "has the unknown extension '" + msynth::Printable(ext) + "'") +
      (model ? "; models are .vti, .txt, .vox or .vtp files"
             : "; examples are label grids (.vti, .txt, .vox), tilesets (.xml) or polyhedra "
               "(.obj, .vtp, .ply, .stl)"));
  }
}

/// Runs @p algorithm, turning its VTK errors into one exception message.
void Run(vtkAlgorithm* algorithm)
{
  std::string messages;
  if (!vtkMSEngineBridge::Execute(algorithm, messages))
  {
    throw std::runtime_error(messages);
  }
}

struct Analysis
{
  vtkSmartPointer<vtkMSLabelGridReader> Reader;
  vtkSmartPointer<vtkMSTransitionTables> Tables;
};

Analysis Analyze(const std::string& example)
{
  Analysis a;
  a.Reader = vtkSmartPointer<vtkMSLabelGridReader>::New();
  a.Reader->SetFileName(example.c_str());
  Run(a.Reader);
  a.Tables = vtkSmartPointer<vtkMSTransitionTables>::New();
  a.Tables->SetInputConnection(a.Reader->GetOutputPort());
  Run(a.Tables);
  return a;
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

int TilesetInfo(const std::string& path, const std::string& subset)
{
  const msynth::Tileset t = msynth::ReadTilesetFile(path, subset);
  std::cout << "tileset: " << path << (t.Unique ? " (unique)" : "") << "\n"
            << "tiles: " << t.Tiles.size() << "\n"
            << "labels: " << t.NumberOfLabels() << "\n";
  for (int b = 0; b < t.NumberOfLabels(); ++b)
  {
    const auto& tile = t.Tiles[static_cast<std::size_t>(t.LabelTile[static_cast<std::size_t>(b)])];
    std::cout << "  label " << b << ": " << t.LabelName(b) << " (symmetry " << tile.Symmetry
              << ", weight " << tile.Weight << ")\n";
  }
  std::cout << "transitions +x: " << t.Pairs[0].size() << "\n"
            << "transitions +y: " << t.Pairs[1].size() << "\n";
  return 0;
}

/// `msynth info EXAMPLE.obj`: "labels: N", then one line per label with its kind and
/// Boolean expression, then the plane families.
/// Reads a polyhedral example and computes its neighbourhood labels (errors as exceptions).
vtkSmartPointer<vtkMSNeighbourhoodLabels> PolyhedralLabels(
  const std::string& path, const std::string& objectTypes)
{
  vtkNew<vtkMSPolyhedralExampleReader> reader;
  reader->SetFileName(path.c_str());
  reader->SetObjectTypes(objectTypes.c_str());
  Run(reader); // so that the reader's own error (naming the file) is the one reported
  auto labels = vtkSmartPointer<vtkMSNeighbourhoodLabels>::New();
  labels->SetInputConnection(reader->GetOutputPort());
  Run(labels);
  return labels;
}

int PolyhedralInfo(const std::string& path, const std::string& objectTypes)
{
  auto labels = PolyhedralLabels(path, objectTypes);
  vtkTable* table = labels->GetLabelTable();
  std::cout << "labels: " << table->GetNumberOfRows() << "\n";
  for (vtkIdType r = 0; r < table->GetNumberOfRows(); ++r)
  {
    std::cout << "  " << table->GetValueByName(r, "Id").ToString() << " "
              << table->GetValueByName(r, "Kind").ToString() << " "
              << table->GetValueByName(r, "Expression").ToString() << "\n";
  }
  auto* normals =
    vtkDataArray::SafeDownCast(table->GetFieldData()->GetAbstractArray("FamilyNormals"));
  std::cout << "plane families: " << normals->GetNumberOfTuples() << "\n";
  for (vtkIdType f = 0; f < normals->GetNumberOfTuples(); ++f)
  {
    double n[3];
    normals->GetTuple(f, n);
    std::cout << "  h" << f + 1 << ": normal (" << static_cast<long long>(n[0]) << ", "
              << static_cast<long long>(n[1]) << ", " << static_cast<long long>(n[2]) << ")\n";
  }
  return 0;
}

int Info(const std::string& example)
{
  Analysis a = Analyze(example);
  vtkImageData* image = a.Reader->GetOutput();
  vtkTable* labels = a.Tables->GetOutput(1);
  vtkTable* transitions = a.Tables->GetOutput(0);
  int dims[3];
  image->GetDimensions(dims);
  std::cout << "example: " << example << "\n"
            << "size: " << dims[0] << " x " << dims[1] << " x " << dims[2] << "\n"
            << "labels: " << labels->GetNumberOfRows() << "\n";
  for (vtkIdType r = 0; r < labels->GetNumberOfRows(); ++r)
  {
    std::cout << "  label " << labels->GetValueByName(r, "Label").ToString() << ": "
              << labels->GetValueByName(r, "Count").ToString() << " sites\n";
  }
  vtkFieldData* fd = transitions->GetFieldData();
  if (auto* verdict =
        vtkStringArray::SafeDownCast(fd->GetAbstractArray("InfallibilityExplanation")))
  {
    const bool proved = fd->GetArray("Infallible")->GetTuple1(0) != 0;
    std::cout << "infallibility: " << (proved ? "proved infallible" : "not proved") << " ("
              << verdict->GetValue(0) << ")\n"
              << "recommendation: "
              << vtkStringArray::SafeDownCast(fd->GetAbstractArray("Recommendation"))->GetValue(0)
              << "\n";
  }
  const char* names[3] = { "+x", "+y", "+z" };
  for (int axis = 0; axis < 3; ++axis)
  {
    std::vector<std::string> pairs;
    for (vtkIdType r = 0; r < transitions->GetNumberOfRows(); ++r)
    {
      if (transitions->GetValueByName(r, "Axis").ToInt() == axis)
      {
        pairs.push_back(transitions->GetValueByName(r, "From").ToString() + "->" +
          transitions->GetValueByName(r, "To").ToString());
      }
    }
    std::cout << "transitions " << names[axis] << ": " << pairs.size() << "\n";
    for (const auto& p : pairs)
    {
      std::cout << "  " << p << "\n";
    }
  }
  return 0;
}

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

/**
 * Runs @p command with a staging folder inside @p out and publishes its files together when it
 * succeeds (msynth::OutputFolder): a failed or interrupted run leaves @p out as it was. What the
 * command prints names the final files, and is printed once they are there.
 */
int IntoFolder(const std::string& out, const std::function<int(const std::string&)>& command)
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
  return status;
}

int AnalyzeToFolder(const std::string& example, const std::string& dir)
{
  Analysis a = Analyze(example);
  WriteCSV(dir + "/labels.csv", a.Tables->GetOutput(1));
  WriteCSV(dir + "/transitions.csv", a.Tables->GetOutput(0));
  vtkNew<vtkMSOpenVDBWriter> writer;
  writer->SetInputConnection(a.Reader->GetOutputPort());
  writer->SetFileName((dir + "/example.vdb").c_str());
  writer->WriteFloatLabelsOn();
  writer->AddMetadata("msynth_command", "analyze");
  vtkNew<vtkMSEngineBridge> errors;
  errors->Watch(writer);
  if (!writer->Write() || errors->HasErrors())
  {
    throw std::runtime_error(errors->GetMessages());
  }
  std::cout << "wrote " << dir << "/labels.csv, " << dir << "/transitions.csv, " << dir
            << "/example.vdb\n";
  return 0;
}

/// @p text as a JSON string literal.
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

/// A solver's statistics read back from its output's field data (vtkMSEngineBridge::AddStatistics).
std::vector<msynth::StatisticsField> StatisticsOf(vtkFieldData* fd)
{
  auto fields = msynth::StatisticsFields(msynth::SynthesisStatistics());
  for (auto& f : fields)
  {
    vtkDataArray* array = fd->GetArray(f.Name.c_str());
    f.Value = array ? array->GetTuple1(0) : 0.0;
  }
  return fields;
}

/// The solver's one-line message from field data `Message`.
std::string MessageOf(vtkFieldData* fd)
{
  auto* message = vtkStringArray::SafeDownCast(fd->GetAbstractArray("Message"));
  return message && message->GetNumberOfValues() > 0 ? message->GetValue(0) : std::string();
}

/// Writes @p data with the VTK XML writer @p WriterT (compressed, appended), atomically.
template <typename WriterT, typename DataT>
void WriteXML(const std::string& path, DataT* data)
{
  const std::string tmp = msynth::TemporaryPathBeside(path);
  vtkNew<WriterT> writer;
  writer->SetInputData(data);
  writer->SetFileName(tmp.c_str());
  writer->SetDataModeToAppended();
  writer->SetCompressorTypeToZLib();
  std::string messages;
  errno = 0;
  if (!vtkMSEngineBridge::Execute(writer, messages) || writer->GetErrorCode() != 0)
  {
    // The system's reason when there is one (no space left on device, file too large).
    const std::string reason = errno ? std::strerror(errno)
      : writer->GetErrorCode()       ? vtkErrorCode::GetStringFromErrorCode(writer->GetErrorCode())
                                     : messages;
    std::remove(tmp.c_str());
    throw std::runtime_error("'" + path + "': could not be written: " + reason);
  }
  msynth::CommitTemporaryFile(tmp, path);
}

/// `msynth analyze EXAMPLE.obj`: DIR/labels.csv (the catalog) and DIR/marked-example.vtp.
int PolyhedralAnalyzeToFolder(
  const std::string& path, const std::string& objectTypes, const std::string& dir)
{
  auto labels = PolyhedralLabels(path, objectTypes);
  WriteCSV(dir + "/labels.csv", labels->GetLabelTable());
  WriteXML<vtkXMLPolyDataWriter>(dir + "/marked-example.vtp", labels->GetMarkedExample());
  std::cout << "wrote " << dir << "/labels.csv, " << dir << "/marked-example.vtp\n";
  return 0;
}

/// A progress bar on stderr when it is a terminal.
class ProgressBar
{
public:
  explicit ProgressBar(vtkAlgorithm* algorithm)
    : Enabled(::isatty(STDERR_FILENO) != 0)
  {
    if (this->Enabled)
    {
      algorithm->AddObserver(vtkCommand::ProgressEvent, this, &ProgressBar::OnProgress);
    }
  }
  ~ProgressBar()
  {
    if (this->Enabled && this->Shown)
    {
      std::cerr << "\n";
    }
  }

private:
  void OnProgress(vtkObject*, unsigned long, void* data)
  {
    const double f = *static_cast<double*>(data);
    const int width = 40, filled = static_cast<int>(f * width + 0.5);
    std::cerr << "\r[" << std::string(static_cast<std::size_t>(filled), '#')
              << std::string(static_cast<std::size_t>(width - filled), ' ') << "] "
              << static_cast<int>(f * 100 + 0.5) << "%" << std::flush;
    this->Shown = true;
  }
  bool Enabled;
  bool Shown = false;
};

struct SynthesizeArguments
{
  std::array<int, 3> Size{ { 0, 0, 0 } };
  std::array<int, 3> Block{ { 0, 0, 0 } };
  long long Seed = 0;
  int Attempts = 10;
  int Threads = 0;
  int Order = vtkMSDiscreteSynthesis::SCAN_LINE;
  int Choice = vtkMSDiscreteSynthesis::UNIFORM;
  bool HasGround = false, HasEmpty = false;
  int Ground = 0, Empty = 0;
  std::string Pieces;
  std::string Outputs; ///< --outputs: comma-separated kinds of file; empty: the defaults
  std::string Guide;
  std::string Subset;
  std::string ObjectTypes;
  std::string Targets;
  double Temperature = 0.01;
  std::array<int, 3> Mirror{ { 0, 0, 0 } };
  std::string Swaps;
  std::array<int, 3> Translate{ { 0, 0, 0 } };
  std::array<int, 3> Period{ { 0, 0, 0 } };
  std::string Shifts;
  bool Rotate = false;
  std::string Turns;
  // Continuous synthesis.
  std::array<double, 3> RealSize{ { 0, 0, 0 } };
  double Spacing = 0;
  double Blocks = 4;
  double Voxel = 0;
  bool OrderGiven = false;
  int Snapshots = 0;
  // Time-varying synthesis.
  int Frames = 0;
  int BlockFrames = 0;
  bool Loop = false;
};

/// Writes @p source's time steps as DIR/catalog_0001.vdb, ... (voxel size @p voxel for points;
/// 0: the writer's default) with file metadata @p key = @p value.
void WriteCatalogSequence(vtkAlgorithm* source, const std::string& dir, double voxel,
  const char* key, const std::string& value)
{
  vtkNew<vtkMSOpenVDBWriter> catalog;
  catalog->SetInputConnection(source->GetOutputPort());
  catalog->SetFileName((dir + "/catalog.vdb").c_str());
  catalog->SetVoxelSize(voxel);
  catalog->WriteTimeStepsOn();
  catalog->AddMetadata(key, value.c_str());
  vtkNew<vtkMSEngineBridge> errors;
  errors->Watch(catalog);
  if (!catalog->Write() || errors->HasErrors())
  {
    throw std::runtime_error(errors->GetMessages());
  }
}

int Synthesize(const std::string& example, const SynthesizeArguments& a, const std::string& dir)
{
  vtkNew<vtkMSLabelGridReader> reader;
  vtkNew<vtkMSDiscreteSynthesis> synthesis;
  const bool tileset = IsTileset(example);
  if (tileset)
  {
    synthesis->SetTilesetFile(example.c_str());
    synthesis->SetTilesetSubset(a.Subset.c_str());
  }
  else
  {
    reader->SetFileName(example.c_str());
    Run(reader);
    synthesis->SetInputConnection(reader->GetOutputPort());
  }
  synthesis->SetOutputSize(a.Size.data());
  synthesis->SetBlockSize(a.Block.data());
  synthesis->SetSeed(a.Seed);
  synthesis->SetAttemptsPerBlock(a.Attempts);
  synthesis->SetNumberOfThreads(a.Threads);
  synthesis->SetSiteOrder(a.Order);
  synthesis->SetLabelChoice(a.Choice);
  // Ground along the bottom: -z in 3D, -y for a 2D (single-layer) output.
  const int bottom = a.Size[2] > 1 ? 4 : 2;
  int use[6] = { 0, 0, 0, 0, 0, 0 }, labels[6] = { 0, 0, 0, 0, 0, 0 };
  for (int f = 0; f < 6; ++f)
  {
    if (f == bottom && a.HasGround)
    {
      use[f] = 1;
      labels[f] = a.Ground;
    }
    else if (f != bottom && a.HasEmpty && !a.Translate[static_cast<std::size_t>(f / 2)])
    { // a translated axis has no faces: the model repeats across them
      use[f] = 1;
      labels[f] = a.Empty;
    }
  }
  synthesis->SetUseBoundary(use);
  synthesis->SetBoundaryLabels(labels);
  synthesis->SetMirror(a.Mirror.data());
  synthesis->SetTargetFractions(a.Targets.c_str());
  synthesis->SetSoftTemperature(a.Temperature);
  synthesis->SetMirrorSwaps(a.Swaps.c_str());
  synthesis->SetTranslate(a.Translate.data());
  synthesis->SetTranslationPeriod(a.Period.data());
  synthesis->SetTranslationMap(a.Shifts.c_str());
  synthesis->SetRotate(a.Rotate);
  synthesis->SetRotationMap(a.Turns.c_str());
  synthesis->SetCatalogSnapshotsPerBlock(a.Snapshots);
  vtkNew<vtkXMLImageDataReader> guide;
  if (!a.Guide.empty())
  {
    struct stat info;
    if (::stat(a.Guide.c_str(), &info) != 0)
    {
      throw std::runtime_error("'" + a.Guide + "': no such guide file");
    }
    msynth::CheckVTKXMLFile(a.Guide); // what VTK's reader trusts, first
    guide->SetFileName(a.Guide.c_str());
    std::string messages;
    if (!vtkMSEngineBridge::Execute(guide, messages))
    {
      throw std::runtime_error("'" + a.Guide + "': not a readable guide volume: " + messages);
    }
    synthesis->SetGuideConnection(guide->GetOutputPort());
  }
  {
    ProgressBar bar(synthesis);
    Run(synthesis);
  }
  vtkImageData* model = synthesis->GetOutput();

  // What to write: --outputs, or what the example calls for.
  const std::string ext = example.size() > 4 ? example.substr(example.size() - 4) : "";
  std::string list = a.Outputs;
  if (list.empty())
  {
    list = tileset ? "labels,picture" : "labels,mesh,vdb";
    if (ext == ".txt")
      list += ",txt";
    if (ext == ".vox")
      list += ",vox";
  }
  const auto wanted = [&list](const char* kind)
  { return ("," + list + ",").find(std::string(",") + kind + ",") != std::string::npos; };
  if (wanted("picture") && !tileset)
  {
    throw std::runtime_error("--outputs picture: pictures are made of a tileset's images; '" +
      example + "' is not a tileset");
  }
  std::vector<std::string> written;
  if (wanted("labels"))
  {
    // The saved model is byte-for-byte reproducible for a seed: timing goes to statistics.json.
    vtkNew<vtkImageData> saved;
    saved->ShallowCopy(model);
    vtkNew<vtkFieldData> fields;
    fields->DeepCopy(model->GetFieldData());
    fields->RemoveArray("Seconds");
    saved->SetFieldData(fields);
    WriteXML<vtkXMLImageDataWriter>(dir + "/labels.vti", saved.GetPointer());
    written.push_back(dir + "/labels.vti");
  }
  for (const char* kind : { "txt", "vox" })
  {
    if (wanted(kind))
    {
      // The original program's text with the example's <Objects> trailer (for its loaders), or
      // MagicaVoxel with the example's palette.
      const std::string path = dir + "/model." + kind;
      vtkNew<vtkMSLabelGridWriter> same;
      same->SetInputData(model);
      same->SetFileName(path.c_str());
      Run(same);
      written.push_back(path);
    }
  }
  if (wanted("mesh"))
  {
    vtkNew<vtkMSLabelGeometry> geometry;
    geometry->SetInputData(model);
    geometry->SetEmptyLabel(a.HasEmpty ? a.Empty : 0);
    geometry->SetPieceDirectory(a.Pieces.c_str());
    if (tileset)
    {
      geometry->SetTilesetFile(example.c_str()); // pieces may be named by tile and turned
      geometry->SetTilesetSubset(a.Subset.c_str());
    }
    Run(geometry);
    WriteXML<vtkXMLPolyDataWriter>(dir + "/mesh.vtp", geometry->GetOutput());
    written.push_back(dir + "/mesh.vtp");
  }
  if (wanted("picture"))
  {
    // The picture, when the tileset's images are there.
    vtkNew<vtkMSTileImage> tiles;
    tiles->SetInputData(model);
    tiles->SetTilesetFile(example.c_str());
    tiles->SetTilesetSubset(a.Subset.c_str());
    std::string messages;
    struct stat folder;
    if (vtkMSEngineBridge::Execute(tiles, messages))
    {
      // Written with libpng at fast compression: a large picture is written in proportion to
      // its synthesis.
      vtkImageData* rgba = tiles->GetOutput();
      int dims[3];
      rgba->GetDimensions(dims);
      msynth::RgbaImage image;
      image.Width = dims[0];
      image.Height = dims[1];
      image.Pixels.resize(
        static_cast<std::size_t>(dims[0]) * static_cast<std::size_t>(dims[1]) * 4);
      auto* pixels = vtkUnsignedCharArray::SafeDownCast(rgba->GetPointData()->GetScalars());
      for (int y = 0; y < dims[1]; ++y) // VTK's rows are bottom first, the PNG's top first
      {
        std::copy(pixels->GetPointer(4 * static_cast<vtkIdType>(y) * dims[0]),
          pixels->GetPointer(4 * static_cast<vtkIdType>(y + 1) * dims[0]),
          image.Pixels.begin() + 4 * static_cast<std::ptrdiff_t>(dims[1] - 1 - y) * dims[0]);
      }
      msynth::WritePng(dir + "/picture.png", image);
      written.push_back(dir + "/picture.png");
    }
    else if (::stat(msynth::TilesetImageFolder(example).c_str(), &folder) != 0)
    {
      std::cerr << "msynth: note: no picture: the tileset has no folder of tile images\n";
    }
    else
    {
      throw std::runtime_error(messages);
    }
  }
  if (wanted("vdb"))
  {
    vtkNew<vtkMSOpenVDBWriter> vdb;
    vdb->SetInputData(model);
    vdb->SetFileName((dir + "/model.vdb").c_str());
    vdb->WriteFloatLabelsOn();
    vdb->AddMetadata("msynth_command", "synthesize");
    vdb->AddMetadata("seed", std::to_string(a.Seed).c_str());
    std::string messages;
    if (!vtkMSEngineBridge::Execute(vdb, messages))
    {
      throw std::runtime_error(messages);
    }
    written.push_back(dir + "/model.vdb");
  }
  if (a.Snapshots > 0)
  {
    // The catalog at every snapshot: DIR/catalog_0001.vdb, ... (Label, CatalogSize, Entropy).
    WriteCatalogSequence(synthesis, dir, 0, "seed", std::to_string(a.Seed));
  }

  // Statistics as JSON.
  vtkFieldData* fd = model->GetFieldData();
  const std::string text = MessageOf(fd);
  msynth::WriteFileAtomically(dir + "/statistics.json",
    [&](std::ostream& out)
    {
      out << "{\n  \"example\": " << JsonString(example) << ",\n  \"size\": [" << a.Size[0] << ", "
          << a.Size[1] << ", " << a.Size[2] << "],\n  \"block\": [" << a.Block[0] << ", "
          << a.Block[1] << ", " << a.Block[2] << "],\n  \"seed\": " << a.Seed << ",\n";
      msynth::WriteStatisticsJSON(out, StatisticsOf(fd));
      out << "  \"Message\": " << JsonString(text) << "\n}\n";
    });
  written.push_back(dir + "/statistics.json");
  if (a.Snapshots > 0)
  {
    written.push_back(dir + "/catalog_0001.vdb ...");
  }
  std::cout << text << "\n"
            << "wrote ";
  for (std::size_t i = 0; i < written.size(); ++i)
  {
    std::cout << (i ? ", " : "") << written[i];
  }
  std::cout << "\n";
  return 0;
}

/// `msynth synthesize EXAMPLE.obj`: plane arrangement → label solver → mesh → files.
int PolyhedralSynthesize(
  const std::string& example, const SynthesizeArguments& a, const std::string& dir)
{
  vtkNew<vtkMSPolyhedralExampleReader> reader;
  reader->SetFileName(example.c_str());
  reader->SetObjectTypes(a.ObjectTypes.c_str());
  Run(reader);
  double exampleBounds[6];
  reader->GetOutput()->GetBounds(exampleBounds);
  const bool flat = exampleBounds[5] - exampleBounds[4] <= 0;
  if (a.RealSize[0] <= 0 || a.RealSize[1] <= 0 || (!flat && a.RealSize[2] <= 0))
  {
    throw std::runtime_error("'" + example + "': --size must be positive along x, y" +
      (flat ? std::string() : std::string(" and z")) + " (example units)");
  }
  vtkNew<vtkMSPlaneArrangement> arrangement;
  arrangement->SetInputConnection(reader->GetOutputPort());
  arrangement->SetOutputSize(a.RealSize[0], a.RealSize[1], a.RealSize[2]);
  arrangement->SetSpacing(a.Spacing);
  vtkNew<vtkMSContinuousSynthesis> synthesis;
  synthesis->SetInputConnection(0, reader->GetOutputPort());
  synthesis->SetArrangementConnection(arrangement->GetOutputPort());
  synthesis->SetSeed(static_cast<int>(a.Seed));
  synthesis->SetBlockSize(a.Blocks);
  synthesis->SetAttempts(a.Attempts);
  synthesis->SetSiteOrder(a.OrderGiven ? a.Order : 2);
  synthesis->SetLabelChoice(a.Choice == vtkMSDiscreteSynthesis::FREQUENCY ? 1 : 0);
  synthesis->SetNumberOfSnapshots(a.Snapshots);
  vtkNew<vtkMSArrangementMesh> mesh;
  mesh->SetInputConnection(0, reader->GetOutputPort());
  mesh->SetArrangementConnection(synthesis->GetOutputPort());
  Run(arrangement);
  {
    ProgressBar bar(synthesis);
    Run(synthesis);
  }
  Run(mesh);
  vtkPolyData* model = mesh->GetOutput();
  vtkPolyData* labelled = synthesis->GetOutput();

  vtkNew<vtkPolyData> saved; // reproducible for a seed: timing goes to statistics.json only
  saved->ShallowCopy(labelled);
  vtkNew<vtkFieldData> fields;
  fields->DeepCopy(labelled->GetFieldData());
  fields->RemoveArray("Seconds");
  saved->SetFieldData(fields);
  WriteXML<vtkXMLPolyDataWriter>(dir + "/arrangement.vtp", saved.GetPointer());
  WriteXML<vtkXMLPolyDataWriter>(dir + "/model.vtp", model);

  // For renderers: a 3D model as level sets per object type and a fog volume; a 2D (or
  // empty) model as a slab of object types.
  const bool planar = model->GetCellData()->GetArray("ObjectType") != nullptr;
  double bounds[6];
  labelled->GetBounds(bounds);
  const auto record = vtkMSEngineBridge::LoadArrangement(labelled->GetFieldData(), example);
  const msynth::PlaneFamilySet families(record.Normals);
  double smallest = 0;
  for (int f = 0; f < families.Size(); ++f)
  {
    const double world = record.Parameters.Spacing(families, f);
    smallest = f == 0 ? world : std::min(smallest, world);
  }
  const int axes = planar ? 2 : 3;
  double extent = 0;
  for (int c = 0; c < axes; ++c)
  {
    extent = std::max(extent, bounds[2 * c + 1] - bounds[2 * c]);
  }
  double voxel = a.Voxel > 0 ? a.Voxel : std::max(smallest / 4, extent / 256);
  if (!(voxel > 0))
  {
    voxel = 1;
  }
  std::array<std::int64_t, 3> dims{ { 1, 1, 1 } };
  for (int c = 0; c < axes; ++c)
  {
    dims[static_cast<std::size_t>(c)] = std::max<std::int64_t>(
      1, static_cast<std::int64_t>(std::ceil((bounds[2 * c + 1] - bounds[2 * c]) / voxel)));
  }
  if (static_cast<double>(dims[0]) * static_cast<double>(dims[1]) * static_cast<double>(dims[2]) >
    1e9)
  {
    throw std::runtime_error("--voxel " + std::to_string(voxel) + " gives more than 10^9 voxels");
  }
  vtkNew<vtkMSOpenVDBWriter> vdb;
  vtkNew<vtkImageData> image;
  if (!planar && model->GetNumberOfPolys() > 0)
  {
    vdb->SetInputData(model);
    vdb->SetVoxelSize(voxel);
  }
  else
  {
    const auto engineMesh = vtkMSEngineBridge::ToContinuousMesh(model, "model");
    const msynth::LabelGrid volume = msynth::VoxelizeModel(
      engineMesh, { bounds[0], bounds[2], planar ? 0.0 : bounds[4] }, voxel, dims);
    image->SetDimensions(
      static_cast<int>(dims[0]), static_cast<int>(dims[1]), static_cast<int>(dims[2]));
    image->SetSpacing(voxel, voxel, voxel);
    image->SetOrigin(
      bounds[0] + voxel / 2, bounds[2] + voxel / 2, planar ? 0.0 : bounds[4] + voxel / 2);
    vtkSmartPointer<vtkIntArray> types;
    types.TakeReference(vtkMSEngineBridge::NewLabelArray(volume, "ObjectType"));
    image->GetPointData()->SetScalars(types);
    vdb->SetInputData(image);
    vdb->SetLabelArrayName("ObjectType");
    vdb->WriteFloatLabelsOn();
  }
  vdb->SetFileName((dir + "/model.vdb").c_str());
  vdb->AddMetadata("msynth_command", "synthesize");
  vdb->AddMetadata("example", example.c_str());
  vdb->AddMetadata("seed", std::to_string(a.Seed).c_str());
  vdb->AddMetadata("block_spacings", std::to_string(a.Blocks).c_str());
  vdb->AddMetadata("plane_spacing", a.Spacing > 0 ? std::to_string(a.Spacing).c_str() : "derived");
  Run(vdb);
  std::string sequence;
  if (a.Snapshots > 0)
  {
    // The catalog at each snapshot, resampled to voxels: DIR/catalog_0001.vdb, ...
    WriteCatalogSequence(synthesis, dir,
      a.Voxel > 0 ? a.Voxel : std::max(smallest / 2, extent / 128), "example", example);
    sequence = ", " + dir + "/catalog_0001.vdb ... catalog_" +
      std::to_string(10000 + a.Snapshots + 1).substr(1) + ".vdb";
  }

  vtkFieldData* fd = labelled->GetFieldData();
  auto number = [fd](const char* name)
  {
    vtkDataArray* array = fd->GetArray(name);
    return array ? array->GetTuple1(0) : 0.0;
  };
  const std::string text = MessageOf(fd);
  msynth::WriteFileAtomically(dir + "/statistics.json",
    [&](std::ostream& out)
    {
      out << "{\n  \"example\": " << JsonString(example) << ",\n  \"size\": [" << a.RealSize[0]
          << ", " << a.RealSize[1] << ", " << a.RealSize[2] << "],\n  \"blocks\": " << a.Blocks
          << ",\n  \"seed\": " << a.Seed << ",\n  \"Vertices\": " << labelled->GetNumberOfPoints()
          << ",\n  \"Polygons\": " << model->GetNumberOfPolys() << ",\n";
      msynth::WriteStatisticsJSON(out, StatisticsOf(fd));
      out << "  \"Message\": " << JsonString(text) << "\n}\n";
    });
  std::cout << labelled->GetNumberOfPoints() << " arrangement vertices, "
            << model->GetNumberOfPolys() << " polygons, "
            << static_cast<long long>(number("BlocksFailed")) << " of "
            << static_cast<long long>(number("Blocks")) << " blocks left unchanged\n"
            << "wrote " << dir << "/model.vtp, " << dir << "/arrangement.vtp, " << dir
            << "/model.vdb, " << dir << "/statistics.json" << sequence << "\n";
  return 0;
}

/// `msynth check EXAMPLE.obj MODEL.vtp`: the independent check of a continuous model.
int PolyhedralCheck(
  const std::string& example, const std::string& modelPath, const std::string& objectTypes)
{
  vtkNew<vtkMSPolyhedralExampleReader> reader;
  reader->SetFileName(example.c_str());
  reader->SetObjectTypes(objectTypes.c_str());
  Run(reader);
  struct stat info;
  if (::stat(modelPath.c_str(), &info) != 0)
  {
    throw std::runtime_error("'" + modelPath + "': no such file");
  }
  msynth::CheckVTKXMLFile(modelPath);
  vtkNew<vtkXMLPolyDataReader> modelReader;
  modelReader->SetFileName(modelPath.c_str());
  std::string messages;
  if (!vtkMSEngineBridge::Execute(modelReader, messages))
  {
    throw std::runtime_error("'" + modelPath + "': not a readable VTP model: " + messages);
  }
  msynth::PolyhedralExample ex;
  msynth::PolyhedralAnalysis analysis;
  try
  {
    double tolerance = 0.01;
    analysis = vtkMSEngineBridge::AnalyzeExample(reader->GetOutput(), tolerance, 12, ex);
  }
  catch (const msynth::Error& e)
  {
    throw std::runtime_error(e.what());
  }
  const auto mesh = vtkMSEngineBridge::ToContinuousMesh(modelReader->GetOutput(), modelPath);
  const auto report = msynth::CheckContinuousModel(analysis, mesh, ex.TypeNames);
  if (report.Valid)
  {
    std::cout << "valid: " << modelPath << " (" << mesh.Polygons.size() << " polygons, "
              << report.Objects << " objects) has only neighbourhoods of " << example << " ("
              << report.DistinctLabels << " distinct)\n";
    return 0;
  }
  std::cout << "invalid: " << modelPath << ": " << report.Problem << "\n";
  return 1;
}

/**
 * `msynth animate EXAMPLE...`: time-varying synthesis (§3.5.4). One example file: its z slices
 * are the frames; several: one frame each, in order. Writes DIR/frame_0000.vti, ... (a series
 * ParaView opens as time steps), DIR/model_0001.vdb, ... and DIR/statistics.json, after checking
 * the model against the example frames.
 */
int Animate(
  const std::vector<std::string>& examples, const SynthesizeArguments& a, const std::string& dir)
{
  msynth::TimeVaryingGrid example;
  for (const auto& path : examples)
  {
    vtkNew<vtkMSLabelGridReader> reader;
    reader->SetFileName(path.c_str());
    Run(reader);
    vtkImageData* image = reader->GetOutput();
    msynth::LabelGrid grid;
    std::string problem;
    if (!vtkMSEngineBridge::ReadLabels(image, nullptr, grid, problem))
    {
      throw std::runtime_error("'" + path + "': " + problem);
    }
    if (examples.size() > 1)
    {
      example.Frames.push_back(std::move(grid));
      continue;
    }
    example = msynth::TimeVaryingGrid::FromSlices(grid);
  }
  msynth::TimeVaryingOptions options;
  options.Size = { { a.Size[0], a.Size[1], a.Size[2], a.Frames } };
  options.BlockSize = { { a.Block[0], a.Block[1], a.Block[2], a.BlockFrames } };
  options.AttemptsPerBlock = a.Attempts;
  options.Seed = a.Seed;
  options.Loop = a.Loop;
  options.Choice = a.Choice == vtkMSDiscreteSynthesis::FREQUENCY ? msynth::LabelChoice::Frequency
                                                                 : msynth::LabelChoice::Uniform;
  if (a.Choice == vtkMSDiscreteSynthesis::RESEMBLANCE)
  {
    throw UsageError{ "animate chooses labels uniformly or by frequency" };
  }
  if (a.Order == vtkMSDiscreteSynthesis::MINIMUM_ENTROPY)
  {
    throw UsageError{ "animate assigns sites in scan-line or random order" };
  }
  options.Order = a.Order == vtkMSDiscreteSynthesis::RANDOM ? msynth::SiteOrder::Random
                                                            : msynth::SiteOrder::ScanLine;
  const auto rules = msynth::TimeVaryingRules::FromExample(example);
  const msynth::TimeVaryingResult result = msynth::SynthesizeTimeVarying(rules, options);
  if (!result.Succeeded())
  {
    throw std::runtime_error(result.Message);
  }
  const msynth::ConsistencyReport report = msynth::CheckTimeVarying(example, result.Model, a.Loop);
  if (!report.Consistent)
  {
    throw std::runtime_error(
      "the synthesized animation breaks the example's rules: " + report.First[0].Describe());
  }
  for (std::size_t t = 0; t < result.Model.Frames.size(); ++t)
  {
    const msynth::LabelGrid& frame = result.Model.Frames[t];
    vtkNew<vtkImageData> image;
    const auto& d = frame.Dimensions();
    image->SetDimensions(static_cast<int>(d[0]), static_cast<int>(d[1]), static_cast<int>(d[2]));
    vtkSmartPointer<vtkIntArray> labels;
    labels.TakeReference(vtkMSEngineBridge::NewLabelArray(frame, "Label"));
    image->GetPointData()->SetScalars(labels);
    char name[32];
    std::snprintf(name, sizeof(name), "/frame_%04zu.vti", t);
    WriteXML<vtkXMLImageDataWriter>(dir + name, image.GetPointer());
    vtkNew<vtkMSOpenVDBWriter> vdb;
    vdb->SetInputData(image);
    std::snprintf(name, sizeof(name), "/model_%04zu.vdb", t + 1);
    vdb->SetFileName((dir + name).c_str());
    vdb->AddMetadata("msynth_command", "animate");
    vdb->AddMetadata("frame", std::to_string(t).c_str());
    std::string messages;
    if (!vtkMSEngineBridge::Execute(vdb, messages))
    {
      throw std::runtime_error(messages);
    }
  }
  const msynth::SynthesisStatistics& st = result.Statistics;
  msynth::WriteFileAtomically(dir + "/statistics.json",
    [&](std::ostream& out)
    {
      out << "{\n  \"examples\": [";
      for (std::size_t i = 0; i < examples.size(); ++i)
        out << (i ? ", " : "") << JsonString(examples[i]);
      out << "],\n  \"exampleFrames\": " << example.Frames.size() << ",\n  \"size\": [" << a.Size[0]
          << ", " << a.Size[1] << ", " << a.Size[2] << "],\n  \"frames\": " << a.Frames
          << ",\n  \"loop\": " << (a.Loop ? "true" : "false") << ",\n  \"seed\": " << a.Seed
          << ",\n";
      msynth::WriteStatisticsJSON(out, msynth::StatisticsFields(st));
      out << "  \"Message\": " << JsonString(result.Message) << "\n}\n";
    });
  std::cout << result.Message << "\n"
            << "consistent: all " << report.PairsChecked
            << " pairs of neighbours in space and time occur in the example\n"
            << "wrote " << dir << "/frame_0000.vti ... frame_" << std::setw(4) << std::setfill('0')
            << (result.Model.Frames.size() - 1) << ".vti, " << dir << "/model_0001.vdb ..., " << dir
            << "/statistics.json\n";
  return 0;
}

int Check(const std::string& example, const std::string& modelPath, const std::string& subset)
{
  vtkNew<vtkMSLabelGridReader> e, m;
  m->SetFileName(modelPath.c_str());
  Run(m);
  auto grid = [](vtkImageData* image)
  { return vtkMSEngineBridge::ToLabelGrid(image, image->GetPointData()->GetArray("Label")); };
  msynth::ConsistencyReport report;
  if (IsTileset(example))
  {
    report = msynth::CheckConsistency(
      msynth::ReadTilesetFile(example, subset).Pairs, grid(m->GetOutput()));
  }
  else
  {
    e->SetFileName(example.c_str());
    Run(e);
    report = msynth::CheckConsistency(grid(e->GetOutput()), grid(m->GetOutput()));
  }
  if (report.Consistent)
  {
    std::cout << "consistent: all " << report.PairsChecked << " adjacent pairs of " << modelPath
              << " occur in " << example << "\n";
    return 0;
  }
  std::cout << "inconsistent: " << report.Violations << " of " << report.PairsChecked
            << " adjacent pairs never occur in " << example << "\n";
  for (const auto& v : report.First)
  {
    std::cout << "  " << v.Describe() << "\n";
  }
  return 1;
}

int Main(const std::vector<std::string>& args)
{
  if (args.empty())
  {
    throw UsageError{ "no command given" };
  }
  const std::string& command = args[0];
  if (command == "--help" || command == "-h" || command == "help")
  {
    std::cout << Usage;
    return 0;
  }
  if (command == "--version")
  {
    std::cout << "msynth " << MSYNTH_VERSION << "\n";
    return 0;
  }
  std::vector<std::string> positional;
  std::string out = "msynth-output";
  SynthesizeArguments synth;
  bool sizeGiven = false;
  std::size_t sizeIndex = 0;
  auto real = [](const std::string& text, const std::string& option)
  {
    char* end = nullptr;
    errno = 0;
    const double v = std::strtod(text.c_str(), &end);
    if (text.empty() || *end != '\0' || errno != 0 || !std::isfinite(v) || v < 0)
    {
      throw UsageError{ option + ": '" + text + "' is not a non-negative number" };
    }
    return v;
  };
  auto integer = [&](std::size_t& i, const std::string& option)
  {
    if (i + 1 >= args.size())
    {
      throw UsageError{ option + " needs a value" };
    }
    const std::string& text = args[++i];
    char* end = nullptr;
    errno = 0;
    const long long v = std::strtoll(text.c_str(), &end, 10);
    if (text.empty() || *end != '\0' || errno != 0)
    {
      throw UsageError{ option + ": '" + text + "' is not an integer" };
    }
    return v;
  };
  auto triple = [&](std::size_t& i, const std::string& option, std::array<int, 3>& v, long long min)
  {
    for (int a = 0; a < 3; ++a)
    {
      const long long x = integer(i, option);
      if (x < min || x > 1000000000)
      {
        throw UsageError{ option + " values must be between " + std::to_string(min) + " and 10^9" };
      }
      v[static_cast<std::size_t>(a)] = static_cast<int>(x);
    }
  };
  for (std::size_t i = 1; i < args.size(); ++i)
  {
    if (args[i] == "--size")
    {
      if (i + 3 >= args.size())
      {
        throw UsageError{ "--size needs three values" };
      }
      sizeIndex = i;
      for (int a = 0; a < 3; ++a)
      {
        synth.RealSize[static_cast<std::size_t>(a)] =
          real(args[i + 1 + static_cast<std::size_t>(a)], "--size");
      }
      i += 3;
      sizeGiven = true;
      continue;
    }
    if (args[i] == "--frames" || args[i] == "--block-frames")
    {
      const std::string option = args[i];
      const long long n = integer(i, option);
      if (n < (option == "--frames" ? 1 : 0) || n > 1000000)
      {
        throw UsageError{ option + " must be between " + (option == "--frames" ? "1" : "0") +
          " and 10^6" };
      }
      (option == "--frames" ? synth.Frames : synth.BlockFrames) = static_cast<int>(n);
      continue;
    }
    if (args[i] == "--loop")
    {
      synth.Loop = true;
      continue;
    }
    if (args[i] == "--snapshots")
    {
      const long long n = integer(i, "--snapshots");
      if (n < 0 || n > 9998)
      {
        throw UsageError{ "--snapshots must be between 0 and 9998" };
      }
      synth.Snapshots = static_cast<int>(n);
      continue;
    }
    if (args[i] == "--spacing" || args[i] == "--blocks" || args[i] == "--voxel")
    {
      if (i + 1 >= args.size())
      {
        throw UsageError{ args[i] + " needs a value" };
      }
      const double v = real(args[i + 1], args[i]);
      (args[i] == "--spacing"     ? synth.Spacing
          : args[i] == "--blocks" ? synth.Blocks
                                  : synth.Voxel) = v;
      ++i;
      continue;
    }
    if (args[i] == "--block")
    {
      triple(i, "--block", synth.Block, 0);
      continue;
    }
    if (args[i] == "--seed")
    {
      synth.Seed = integer(i, "--seed");
      continue;
    }
    if (args[i] == "--threads")
    {
      const long long t = integer(i, "--threads");
      if (t < 0 || t > 1024)
      {
        throw UsageError{ "--threads must be between 0 and 1024" };
      }
      synth.Threads = static_cast<int>(t);
      continue;
    }
    if (args[i] == "--attempts")
    {
      const long long n = integer(i, "--attempts");
      if (n < 1 || n > 1000000)
      {
        throw UsageError{ "--attempts must be between 1 and 10^6" };
      }
      synth.Attempts = static_cast<int>(n);
      continue;
    }
    if (args[i] == "--ground" || args[i] == "--empty")
    {
      const bool ground = args[i] == "--ground";
      const long long label = integer(i, args[i]);
      (ground ? synth.HasGround : synth.HasEmpty) = true;
      (ground ? synth.Ground : synth.Empty) = static_cast<int>(label);
      continue;
    }
    if (args[i] == "--target" || args[i] == "--temperature")
    {
      const std::string option = args[i];
      if (i + 1 >= args.size())
      {
        throw UsageError{ option + " needs a value" };
      }
      const std::string v = args[++i];
      if (option == "--target")
      {
        synth.Targets += (synth.Targets.empty() ? "" : ",") + v;
      }
      else
      {
        char* end = nullptr;
        synth.Temperature = std::strtod(v.c_str(), &end);
        if (end == v.c_str() || *end || !(synth.Temperature > 0.0))
        {
          throw UsageError{ "--temperature: '" + v + "' is not a positive number" };
        }
      }
      continue;
    }
    if (args[i] == "--rotate")
    {
      synth.Rotate = true;
      continue;
    }
    if (args[i] == "--period")
    {
      if (i + 3 >= args.size())
      {
        throw UsageError{ "--period needs three values" };
      }
      for (int a = 0; a < 3; ++a)
      {
        const std::string v = args[++i];
        char* end = nullptr;
        const long p = std::strtol(v.c_str(), &end, 10);
        if (end == v.c_str() || *end || p < 0 || p > (1L << 30))
        {
          throw UsageError{ "--period: '" + v + "' is not a period (0 or a positive integer)" };
        }
        synth.Period[static_cast<std::size_t>(a)] = static_cast<int>(p);
      }
      continue;
    }
    if (args[i] == "--mirror" || args[i] == "--swap" || args[i] == "--translate" ||
      args[i] == "--shift" || args[i] == "--turn")
    {
      const std::string option = args[i];
      if (i + 1 >= args.size())
      {
        throw UsageError{ option + " needs a value" };
      }
      const std::string v = args[++i];
      if (option == "--mirror" || option == "--translate")
      {
        for (const char c : v)
        {
          if (c < 'x' || c > 'z')
          {
            throw UsageError{ option + ": '" + v + "' is not a set of axes x, y, z" };
          }
          (option == "--mirror" ? synth.Mirror
                                : synth.Translate)[static_cast<std::size_t>(c - 'x')] = 1;
        }
      }
      else
      {
        std::string& list =
          option == "--swap" ? synth.Swaps : (option == "--shift" ? synth.Shifts : synth.Turns);
        list += (list.empty() ? "" : ",") + v;
      }
      continue;
    }
    if (args[i] == "--types")
    {
      if (i + 1 >= args.size())
      {
        throw UsageError{ "--types needs NAME=TYPE[,NAME=TYPE...]" };
      }
      synth.ObjectTypes = args[++i];
      continue;
    }
    if (args[i] == "--outputs")
    {
      if (i + 1 >= args.size())
      {
        throw UsageError{ "--outputs needs a value" };
      }
      synth.Outputs = args[++i];
      std::stringstream items(synth.Outputs);
      std::string item;
      while (std::getline(items, item, ','))
      {
        if (item != "labels" && item != "mesh" && item != "vdb" && item != "picture" &&
          item != "txt" && item != "vox")
        {
          throw UsageError{ "--outputs: unknown kind '" + msynth::Printable(item) +
            "' (labels, mesh, vdb, picture, txt, vox)" };
        }
      }
      continue;
    }
    if (args[i] == "--pieces" || args[i] == "--guide" || args[i] == "--subset")
    {
      if (i + 1 >= args.size())
      {
        throw UsageError{ args[i] + " needs a value" };
      }
      (args[i] == "--pieces" ? synth.Pieces : (args[i] == "--guide" ? synth.Guide : synth.Subset)) =
        args[i + 1];
      ++i;
      continue;
    }
    if (args[i] == "--order" || args[i] == "--choice")
    {
      const std::string option = args[i];
      if (i + 1 >= args.size())
      {
        throw UsageError{ option + " needs a value" };
      }
      const std::string v = args[++i];
      if (option == "--order" && (v == "scanline" || v == "random" || v == "entropy"))
      {
        synth.Order = v == "scanline" ? 0 : (v == "random" ? 1 : 2);
        synth.OrderGiven = true;
      }
      else if (option == "--choice" && (v == "uniform" || v == "frequency" || v == "resemblance"))
      {
        synth.Choice = v == "uniform" ? 0 : (v == "frequency" ? 1 : 2);
      }
      else
      {
        throw UsageError{ option + ": unknown value '" + v + "'" };
      }
      continue;
    }
    if (args[i] == "--verbose")
    {
      vtkOutputWindow::GetInstance()->SetDisplayModeToDefault();
      vtkLogger::SetStderrVerbosity(vtkLogger::VERBOSITY_INFO);
    }
    else if (args[i] == "--out")
    {
      if (i + 1 >= args.size())
      {
        throw UsageError{ "--out needs a folder" };
      }
      out = args[++i];
    }
    else if (args[i].rfind("--", 0) == 0)
    {
      throw UsageError{ "unknown option '" + args[i] + "'" };
    }
    else
    {
      positional.push_back(args[i]);
    }
  }
  for (std::size_t i = 0; i < positional.size(); ++i)
  {
    CheckInputFile(positional[i], command == "check" && i == 1);
  }
  if (command == "synthesize")
  {
    if (positional.size() != 1)
    {
      throw UsageError{ "synthesize takes exactly one EXAMPLE" };
    }
    if (!sizeGiven)
    {
      throw UsageError{ "synthesize needs --size NX NY NZ" };
    }
    if (IsPolyhedral(positional[0]))
    {
      return IntoFolder(out,
        [&](const std::string& dir) { return PolyhedralSynthesize(positional[0], synth, dir); });
    }
    triple(sizeIndex, "--size", synth.Size, 1); // a label grid's size is in sites
    return IntoFolder(
      out, [&](const std::string& dir) { return Synthesize(positional[0], synth, dir); });
  }
  if (command == "animate")
  {
    if (positional.empty())
    {
      throw UsageError{ "animate takes one EXAMPLE (z slices as frames) or one file per frame" };
    }
    if (!sizeGiven || synth.Frames < 1)
    {
      throw UsageError{ "animate needs --size NX NY NZ and --frames N" };
    }
    triple(sizeIndex, "--size", synth.Size, 1);
    return IntoFolder(out, [&](const std::string& dir) { return Animate(positional, synth, dir); });
  }
  if (command == "check")
  {
    if (positional.size() != 2)
    {
      throw UsageError{ "check takes EXAMPLE and MODEL.vti" };
    }
    if (IsPolyhedral(positional[0]))
    {
      return PolyhedralCheck(positional[0], positional[1], synth.ObjectTypes);
    }
    return Check(positional[0], positional[1], synth.Subset);
  }
  if (command == "info" || command == "analyze")
  {
    if (positional.size() != 1)
    {
      throw UsageError{ command + " takes exactly one EXAMPLE" };
    }
    if (command == "info" && IsTileset(positional[0]))
    {
      return TilesetInfo(positional[0], synth.Subset);
    }
    if (IsPolyhedral(positional[0]))
    {
      return command == "info"
        ? PolyhedralInfo(positional[0], synth.ObjectTypes)
        : IntoFolder(out,
            [&](const std::string& dir)
            { return PolyhedralAnalyzeToFolder(positional[0], synth.ObjectTypes, dir); });
    }
    return command == "info"
      ? Info(positional[0])
      : IntoFolder(
          out, [&](const std::string& dir) { return AnalyzeToFolder(positional[0], dir); });
  }
  throw UsageError{ "unknown command '" + command + "'" };
}

/// main()'s exit status once it is known (-1 before): a signal arriving after the work is
/// done ends the process with that status, silently, and discards nothing.
std::atomic<int> FinalStatus{ -1 };

/**
 * SIGINT and SIGTERM (and SIGHUP) are taken by one thread: it discards the staging folders of
 * the run, says so in one line and ends the process with 128 + the signal's number, whatever
 * stage the run is in. The signals are blocked in every other thread (they inherit the mask).
 */
void HandleInterruptions()
{
  static sigset_t signals;
  sigemptyset(&signals);
  for (int sig : { SIGINT, SIGTERM, SIGHUP })
  {
    sigaddset(&signals, sig);
  }
  pthread_sigmask(SIG_BLOCK, &signals, nullptr);
  std::thread(
    []()
    {
      int sig = 0;
      while (sigwait(&signals, &sig) != 0)
      {
      }
      if (FinalStatus >= 0)
      {
        std::_Exit(FinalStatus);
      }
      int published = 0;
      if (msynth::OutputFolder::DiscardAll(&published) == 0 && published > 0)
      {
        std::_Exit(0); // the run's outputs are complete: only its last words are lost
      }
      const char* name = sig == SIGINT ? "SIGINT" : sig == SIGTERM ? "SIGTERM" : "SIGHUP";
      std::fprintf(stderr, "\nmsynth: interrupted (%s); no outputs were written\n", name);
      std::fflush(stderr);
      std::_Exit(128 + sig);
    })
    .detach();
}

} // namespace

int main(int argc, char* argv[])
{
  HandleInterruptions();
  // Our errors reach the user as one line each through observers; VTK's own pipeline chatter
  // ("algorithm returned failure") is shown only with --verbose.
  vtkOutputWindow::GetInstance()->SetDisplayModeToNever();
  vtkLogger::SetStderrVerbosity(vtkLogger::VERBOSITY_OFF);
  int status = 1;
  try
  {
    status = Main(std::vector<std::string>(argv + 1, argv + argc));
  }
  catch (const UsageError& e)
  {
    std::cerr << "msynth: " << e.What << "\n" << Usage;
    status = 2;
  }
  catch (const std::exception& e)
  {
    std::cerr << "msynth: error: " << msynth::Printable(e.what()) << "\n";
    status = 1;
  }
  std::cout.flush();
  FinalStatus = status;
  return status;
}
