// SPDX-License-Identifier: BSD-3-Clause
// `msynth check EXAMPLE MODEL`: the independent checks, which share no code with the solvers: a
// label grid against the pairs of its example (Eq. 3.1) or tileset, a continuous model against
// the neighbourhoods of its polyhedral example (Eq. 4.1, closed and oriented), a picture against
// the windows of its image sample, a voxel model against a voxel tileset; each through
// vtkMSCheckModel (the command: options → readers → the filter → its verdict printed).
#include "Commands.h"
#include "Common.h"
#include "Examples.h"
#include "FrameSeries.h"
#include "Resemblance.h"

#include "vtkDataArray.h"
#include "vtkDataObject.h"
#include "vtkFieldData.h"
#include "vtkImageData.h"
#include "vtkMSCheckModel.h"
#include "vtkMSEngineBridge.h"
#include "vtkMSLabelArrays.h"
#include "vtkMSLabelGridReader.h"
#include "vtkMSPolyhedralExampleReader.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkStringArray.h"
#include "vtkXMLPolyDataReader.h"

#include "Core/Error.h"
#include "Core/FileBytes.h"
#include "Core/Index.h"
#include "Core/Memory.h"
#include "Discrete/OverlappingModel.h"
#include "Formats/Image.h"
#include "Formats/VTKXMLCheck.h"

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <iostream>
#include <memory>
#include <sstream>
#include <sys/stat.h>

namespace msynth
{
namespace cli
{
namespace
{
struct CheckOptions
{
  std::string Example;
  std::string Model;
  std::string Subset;
  std::string Tiles;
  PolyhedralReading Reading;
  OverlappingOptions Patterns;
  bool NoPeriodicInput = false;
  std::string Translate;
  std::vector<std::string> Counts;
  std::string Connected;
  std::string Names; ///< --tileset: names and sides for --count, --connected on a label grid
  std::vector<std::string> Path;
  bool Animation = false; ///< MODEL is the first frame (frame_0001.vti) of an animation
  bool Loop = false;
  std::string Guide; ///< --guide: the guide whose Region array --count region=R:... reads
  std::string Fixed; ///< --fixed: the pins the model must hold
  bool FixedEmptyFree = false;
};

/// The verdict of @p check (vtkMSCheckModel's field data) after it ran.
struct Verdict
{
  vtkFieldData* Fields;
  bool Valid() const { return CountOf(this->Fields, "Valid") == 1; }
  /// Prints each line of the string array @p name, after @p prefix.
  void PrintLines(const char* name, const char* prefix) const
  {
    if (auto* lines = vtkStringArray::SafeDownCast(this->Fields->GetAbstractArray(name)))
      for (vtkIdType i = 0; i < lines->GetNumberOfValues(); ++i)
        std::cout << prefix << lines->GetValue(i) << "\n";
  }
  /// Prints each problem line, after @p prefix.
  void PrintProblems(const char* prefix) const { this->PrintLines("Problems", prefix); }
};

/// A picture against the windows of its image sample: the picture → vtkMSCheckModel
/// (SampleFile; Discrete/OverlappingModel.h's CheckPicture, which shares no code with the
/// patterns' synthesis).
int CheckSamplePicture(const CheckOptions& o)
{
  if (!IsSample(o.Model))
    throw std::runtime_error(
      "'" + o.Model + "': the model of an image sample is its picture (.png)");
  vtkNew<vtkImageData> picture;
  vtkMSLabelArrays::SetPicture(picture, ReadImage(o.Model));
  vtkNew<vtkMSCheckModel> check;
  check->SetInputData(picture);
  check->SetSampleFile(o.Example.c_str());
  check->SetPatternSize(o.Patterns.N);
  check->SetPatternSymmetry(o.Patterns.Symmetry);
  check->SetPeriodicInput(!o.NoPeriodicInput);
  check->SetGround(o.Patterns.Ground);
  check->SetPeriodicOutput(o.Translate.find('x') != std::string::npos ? 1 : 0,
    o.Translate.find('y') != std::string::npos ? 1 : 0);
  Run(check);
  const Verdict verdict{ check->GetOutput()->GetFieldData() };
  if (verdict.Valid())
  {
    int dims[3];
    picture->GetDimensions(dims);
    std::cout << "consistent: every " << o.Patterns.N << " x " << o.Patterns.N << " window of "
              << o.Model << " (" << dims[0] << " x " << dims[1] << ") occurs in " << o.Example
              << "\n";
    return 0;
  }
  std::cout << "inconsistent: " << o.Model << " has windows that are not in " << o.Example << "\n";
  verdict.PrintProblems("  ");
  return 1;
}

/// A continuous model (.vtp) against its polyhedral example: reader → vtkMSCheckModel.
int CheckContinuous(
  const std::string& example, const std::string& modelPath, const PolyhedralReading& reading)
{
  vtkNew<vtkMSPolyhedralExampleReader> reader;
  ConfigureReader(reader, example, reading);
  Run(reader);
  msynth::CheckVTKXMLFile(modelPath);
  vtkNew<vtkXMLPolyDataReader> modelReader;
  modelReader->SetFileName(modelPath.c_str());
  std::string messages;
  if (!vtkMSEngineBridge::Execute(modelReader, messages))
  {
    throw std::runtime_error("'" + modelPath + "': not a readable VTP model: " + messages);
  }
  vtkNew<vtkMSCheckModel> check;
  check->SetInputConnection(modelReader->GetOutputPort());
  check->AddExampleConnection(reader->GetOutputPort());
  try
  {
    Run(check);
  }
  catch (const std::exception& e)
  {
    throw std::runtime_error("'" + modelPath + "': " + e.what());
  }
  const Verdict verdict{ check->GetOutput()->GetFieldData() };
  if (verdict.Valid())
  {
    std::cout << "valid: " << modelPath << " ("
              << Counted(modelReader->GetOutput()->GetNumberOfPolys(), "polygon") << ", "
              << Counted(CountOf(verdict.Fields, "Objects"), "object")
              << ") has only neighbourhoods of " << example << " ("
              << CountOf(verdict.Fields, "DistinctLabels") << " distinct)\n";
    vtkDataArray* width = verdict.Fields->GetArray("SmallestFeature");
    vtkDataArray* fraction = verdict.Fields->GetArray("SmallestFeatureFraction");
    if (width && fraction && fraction->GetTuple1(0) > 0)
      std::cout << "narrowest face, edge or gap: " << width->GetTuple1(0) << " ("
                << fraction->GetTuple1(0) << " of the smallest plane spacing)\n";
    PrintResemblance(verdict.Fields, std::cout);
    return 0;
  }
  std::cout << "invalid: " << modelPath << ": ";
  verdict.PrintProblems("");
  return 1;
}

/// True when @p path is a MarkovJunior voxel tileset (its root element is <tileset>).
bool IsVoxelTileset(const std::string& path)
{
  std::ifstream in(path, std::ios::binary);
  std::string head(4096, '\0');
  in.read(&head[0], static_cast<std::streamsize>(head.size()));
  head.resize(msynth::ToIndex(in.gcount()));
  std::size_t at = 0;
  while ((at = head.find('<', at)) != std::string::npos)
  {
    if (head.compare(at, 2, "<?") != 0 && head.compare(at, 2, "<!") != 0)
      return head.compare(at, 8, "<tileset") == 0 && at + 8 < head.size() &&
        std::strchr(" \t\r\n>/", head[at + 8]);
    ++at;
  }
  return false;
}

/// A voxel model (.vox, all its models placed by its scene) against a voxel tileset: the reader
/// → vtkMSCheckModel (VoxelModel: every tile cell identified by its voxels, every pair against
/// the rules; VoxelTileset.h: CheckVoxelModel).
int CheckVoxels(const std::string& example, const std::string& modelPath, const std::string& tiles)
{
  vtkNew<vtkMSLabelGridReader> reader;
  reader->SetFileName(modelPath.c_str());
  reader->VoxSceneOn();
  reader->GenerateGeometryOff();
  // The scene's span of voxels (its models far apart make it large for a small file): the
  // composed grid, the reader's and the check's copies take about 12 bytes a voxel (measured).
  reader->SetMaximumNumberOfSites(static_cast<vtkIdType>(SitesWithinMemory(16, 1LL << 30)));
  vtkNew<vtkMSCheckModel> check;
  check->SetInputConnection(reader->GetOutputPort());
  check->VoxelModelOn();
  check->SetTilesetFile(example.c_str());
  check->SetTilesFolder(tiles.c_str());
  Run(check);
  const Verdict verdict{ check->GetOutput()->GetFieldData() };
  int d[3];
  reader->GetOutput()->GetDimensions(d);
  const long long models = CountOf(verdict.Fields, "VoxModels");
  if (verdict.Valid())
  {
    std::cout << "consistent: all " << CountOf(verdict.Fields, "Cells") << " tile cells of "
              << modelPath << " (" << d[0] << " x " << d[1] << " x " << d[2] << " voxels, "
              << models << (models == 1 ? " model" : " models") << ") are tiles of " << example
              << " and all " << CountOf(verdict.Fields, "PairsChecked")
              << " adjacent pairs are allowed\n";
    return 0;
  }
  std::cout << "inconsistent: " << Counted(CountOf(verdict.Fields, "Violations"), "problem")
            << " in " << modelPath << " (" << Counted(CountOf(verdict.Fields, "Cells"), "tile cell")
            << ", " << Counted(CountOf(verdict.Fields, "PairsChecked"), "pair") << ")\n";
  verdict.PrintProblems("  ");
  return 1;
}

/// @p check of the model @p m reads against @p example (read by @p e) or its tileset.
void SetUpDiscreteCheck(vtkMSCheckModel* check, vtkMSLabelGridReader* e, vtkMSLabelGridReader* m,
  const std::string& example, const std::string& subset, const std::string& tiles)
{
  e->GenerateGeometryOff(); // the labels are checked, not shown
  m->GenerateGeometryOff();
  check->SetInputConnection(m->GetOutputPort());
  check->SetTilesetSubset(subset.c_str());
  check->SetTilesFolder(tiles.c_str());
  if (IsTileset(example))
    check->SetTilesetFile(example.c_str());
  else
  {
    e->SetFileName(example.c_str());
    check->AddExampleConnection(e->GetOutputPort());
  }
}

/// A label grid against the pairs of its example grid or tileset, its counts and network:
/// readers → vtkMSCheckModel.
int CheckDiscrete(const CheckOptions& o)
{
  if (IsTileset(o.Example) && IsVoxelTileset(o.Example) && o.Model.size() > 4 &&
    o.Model.compare(o.Model.size() - 4, 4, ".vox") == 0)
  {
    if (!o.Counts.empty() || !o.Connected.empty() || !o.Fixed.empty())
      throw std::runtime_error("--count, --connected and --fixed check a model's labels "
                               "(labels.vti), not '" +
        o.Model + "'");
    return CheckVoxels(o.Example, o.Model, o.Tiles);
  }
  vtkNew<vtkMSLabelGridReader> e, m;
  m->SetFileName(o.Model.c_str());
  vtkNew<vtkMSCheckModel> check;
  SetUpDiscreteCheck(check, e, m, o.Example, o.Subset, o.Tiles);
  check->SetCounts(Joined(o.Counts, ",").c_str());
  if (!o.Guide.empty())
  {
    CheckInputFile(o.Guide);
    check->SetCountGuideFile(o.Guide.c_str());
  }
  check->SetConnected(o.Connected.c_str());
  check->SetPath(Joined(o.Path, ";").c_str());
  if (!o.Fixed.empty())
  {
    CheckInputFile(o.Fixed);
    check->SetPinsFile(o.Fixed.c_str());
    check->SetPinsEmptyFree(o.FixedEmptyFree);
  }
  if (!IsTileset(o.Example) && IsTileset(o.Names))
    check->SetConnectedTilesetFile(o.Names.c_str());
  Run(check);
  const Verdict verdict{ check->GetOutput()->GetFieldData() };
  verdict.PrintLines("Findings", "");
  if (CountOf(verdict.Fields, "Violations") == 0)
  {
    std::cout << "consistent: all " << CountOf(verdict.Fields, "PairsChecked")
              << " adjacent pairs of " << o.Model << " occur in " << o.Example << "\n";
    return verdict.Valid() ? 0 : 1;
  }
  std::cout << "inconsistent: " << CountOf(verdict.Fields, "Violations") << " of "
            << CountOf(verdict.Fields, "PairsChecked") << " adjacent pairs never "
            << (CountOf(verdict.Fields, "Violations") == 1 ? "occurs" : "occur") << " in "
            << o.Example << "\n";
  verdict.PrintProblems("  ");
  return 1;
}

/// An animation (MODEL is its first frame, frame_0001.vti, or any NNNN.vti; the frames numbered
/// after it follow while they exist) against the z slices of EXAMPLE, in space and in time: a
/// frame series → vtkMSCheckModel (TimeVarying; Discrete/TimeVarying.h: CheckTimeVarying).
int CheckAnimation(const CheckOptions& o)
{
  const std::string& m = o.Model;
  const std::size_t digits = m.size() >= 8 ? m.size() - 8 : 0;
  const bool numbered = m.size() >= 8 && m.compare(m.size() - 4, 4, ".vti") == 0 &&
    std::all_of(m.begin() + static_cast<std::ptrdiff_t>(digits), m.end() - 4,
      [](char c) { return c >= '0' && c <= '9'; });
  if (!numbered)
    throw UsageError{ "--animation: MODEL is an animation's first frame (frame_0001.vti), not '" +
      o.Model + "'" };
  const std::string prefix = m.substr(0, digits);
  vtkNew<vtkMSFrameSeries> series;
  int frames = 0;
  for (int number = std::stoi(m.substr(digits, 4)); number <= 9999; ++number, ++frames)
  {
    char name[16];
    std::snprintf(name, sizeof(name), "%04d.vti", number);
    struct stat info;
    if (frames > 0 && ::stat((prefix + name).c_str(), &info) != 0)
      break;
    vtkNew<vtkMSLabelGridReader> frame;
    frame->SetFileName((prefix + name).c_str());
    frame->GenerateGeometryOff();
    Run(frame);
    series->AddFrame(frame->GetOutput());
  }
  vtkNew<vtkMSLabelGridReader> example;
  example->SetFileName(o.Example.c_str());
  example->GenerateGeometryOff();
  vtkNew<vtkMSCheckModel> check;
  check->SetInputConnection(series->GetOutputPort());
  check->AddExampleConnection(example->GetOutputPort());
  check->TimeVaryingOn();
  check->ExampleTimeFromZOn();
  check->SetLoop(o.Loop);
  Run(check);
  const Verdict verdict{ check->GetOutput()->GetFieldData() };
  if (verdict.Valid())
  {
    std::cout << "consistent: all " << CountOf(verdict.Fields, "PairsChecked")
              << " pairs of neighbours in space and time of the " << Counted(frames, "frame")
              << " from " << o.Model << (o.Loop ? " (looping)" : "") << " occur in " << o.Example
              << "\n";
    return 0;
  }
  std::cout << "inconsistent: " << CountOf(verdict.Fields, "Violations") << " of "
            << CountOf(verdict.Fields, "PairsChecked")
            << " pairs of neighbours in space and time never "
            << (CountOf(verdict.Fields, "Violations") == 1 ? "occurs" : "occur") << " in "
            << o.Example << "\n";
  verdict.PrintProblems("  ");
  return 1;
}

/// A piece of a streamed model's pieces file.
struct Piece
{
  std::array<int, 6> Extent{};
  std::string Source;
};

/// The six integers of attribute @p name in @p text from @p at on; false when missing.
bool ExtentAttribute(
  const std::string& text, std::size_t at, const char* name, std::array<int, 6>& extent)
{
  const std::size_t found = text.find(std::string(name) + "=\"", at);
  if (found == std::string::npos)
    return false;
  std::istringstream in(text.substr(found + std::strlen(name) + 2, 200));
  for (int& v : extent)
    if (!(in >> v))
      return false;
  return true;
}

/// The whole extent and the pieces of the pieces file @p path (`synthesize --stream`).
std::vector<Piece> ReadPieces(const std::string& path, std::array<int, 6>& whole)
{
  const std::string text = msynth::ReadFileBytes(path, 64 << 20, "is too large for a pieces file");
  if (!ExtentAttribute(text, 0, "WholeExtent", whole))
    throw std::runtime_error("'" + path + "': not a pieces file of image data (no WholeExtent)");
  std::vector<Piece> pieces;
  for (std::size_t at = text.find("<Piece "); at != std::string::npos;
       at = text.find("<Piece ", at + 1))
  {
    Piece piece;
    const std::size_t source = text.find("Source=\"", at);
    const std::size_t end = source == std::string::npos ? source : text.find('"', source + 8);
    if (!ExtentAttribute(text, at, "Extent", piece.Extent) || end == std::string::npos)
      throw std::runtime_error(
        "'" + path + "': piece " + std::to_string(pieces.size()) + " has no Extent or Source");
    piece.Source = text.substr(source + 8, end - source - 8);
    pieces.push_back(piece);
  }
  if (pieces.empty())
    throw std::runtime_error("'" + path + "': no pieces");
  return pieces;
}

/// The axis the pieces follow one another along; @throw std::runtime_error when they do not
/// tile @p whole as slabs sharing their border layers.
int SlabAxis(
  const std::string& path, const std::array<int, 6>& whole, const std::vector<Piece>& pieces)
{
  int axis = 2;
  for (int a = 0; a < 3 && pieces.size() > 1; ++a)
    if (pieces[0].Extent[2 * a + 1] != whole[2 * a + 1])
      axis = a;
  for (std::size_t j = 0; j < pieces.size(); ++j)
  {
    const auto& e = pieces[j].Extent;
    bool ok = e[2 * axis] == (j == 0 ? whole[2 * axis] : pieces[j - 1].Extent[2 * axis + 1]);
    for (int a = 0; a < 3; ++a)
      ok = ok && (a == axis || (e[2 * a] == whole[2 * a] && e[2 * a + 1] == whole[2 * a + 1]));
    if (!ok || (j + 1 == pieces.size() && e[2 * axis + 1] != whole[2 * axis + 1]))
      throw std::runtime_error("'" + path + "': piece " + std::to_string(j) +
        " does not continue the slabs of the whole extent (each shares the previous one's last "
        "layer)");
  }
  return axis;
}

/// Layer @p k along @p axis of the labels @p a of an image of @p dims.
std::vector<int> Layer(vtkDataArray* a, const int dims[3], int axis, int k)
{
  std::vector<int> layer;
  int p[3];
  for (p[2] = 0; p[2] < dims[2]; ++p[2])
    for (p[1] = 0; p[1] < dims[1]; ++p[1])
      for (p[0] = 0; p[0] < dims[0]; ++p[0])
        if (p[axis] == k)
          layer.push_back(static_cast<int>(
            a->GetTuple1(p[0] + static_cast<vtkIdType>(dims[0]) * (p[1] + dims[1] * p[2]))));
  return layer;
}

/// A streamed model (labels.pvti) piece by piece, one in memory at a time: every piece against
/// the example (the pieces share their border layers, so every adjacent pair lies in one), the
/// pieces tiling the whole extent, and each shared layer the same in both pieces.
int CheckPieces(const std::string& example, const std::string& path, const std::string& subset,
  const std::string& tiles)
{
  std::array<int, 6> whole;
  const std::vector<Piece> pieces = ReadPieces(path, whole);
  const int axis = SlabAxis(path, whole, pieces);
  const std::string dir =
    path.find('/') == std::string::npos ? "." : path.substr(0, path.rfind('/'));
  vtkNew<vtkMSLabelGridReader> e, m;
  vtkNew<vtkMSCheckModel> check;
  SetUpDiscreteCheck(check, e, m, example, subset, tiles);
  long long pairs = 0, violations = 0;
  std::vector<int> last;
  for (std::size_t j = 0; j < pieces.size(); ++j)
  {
    const std::string file = dir + "/" + pieces[j].Source;
    CheckInputFile(file, true);
    m->SetFileName(file.c_str());
    Run(check);
    const Verdict verdict{ check->GetOutput()->GetFieldData() };
    pairs += CountOf(verdict.Fields, "PairsChecked");
    violations += CountOf(verdict.Fields, "Violations");
    if (!verdict.Valid())
    {
      std::cout << "inconsistent: piece " << j << " (" << file << ")\n";
      verdict.PrintProblems("  ");
    }
    vtkImageData* labels = m->GetOutput();
    int dims[3];
    labels->GetDimensions(dims);
    const auto& x = pieces[j].Extent;
    vtkDataArray* a = labels->GetPointData()->GetScalars();
    if (!a || dims[0] != x[1] - x[0] + 1 || dims[1] != x[3] - x[2] + 1 ||
      dims[2] != x[5] - x[4] + 1)
      throw std::runtime_error("'" + file + "': not the piece's extent or no labels");
    if (j > 0 && Layer(a, dims, axis, 0) != last)
    {
      std::cout << "inconsistent: piece " << j << " does not share piece " << j - 1
                << "'s last layer\n";
      ++violations;
    }
    last = Layer(a, dims, axis, dims[axis] - 1);
  }
  if (violations > 0)
    return 1;
  std::cout << "consistent: all " << pairs << " adjacent pairs of the "
            << Counted(static_cast<long long>(pieces.size()), "piece") << " of " << path
            << " (seams included) occur in " << example << "\n";
  return 0;
}
} // namespace

CommandRunner AddCheck(CLI::App& app)
{
  auto o = std::make_shared<CheckOptions>();
  CLI::App* check = app.add_subcommand("check",
    "verify that every pair of neighbours in MODEL occurs in EXAMPLE (a label grid or "
    "tileset) or, for a polyhedral EXAMPLE, that the continuous MODEL.vtp is closed, oriented "
    "and has only the example's neighbourhoods, or for an image sample that every "
    "window of the picture MODEL.png is one of the sample's; for a voxel tileset and a MODEL.vox, "
    "that every tile cell is an image of a tile and every adjacent pair allowed. Exit 0 when it "
    "does, 1 listing the "
    "problems when not");
  check->add_option("EXAMPLE", o->Example, "the example the model was synthesized from")
    ->required();
  check
    ->add_option("MODEL", o->Model,
      "the model (.vti, .txt, .vox; labels.pvti of a streamed run, piece by piece; .vtp for "
      "continuous; .png for a sample)")
    ->required();
  AddSubsetOption(*check, o->Subset);
  check->add_option("--tiles", o->Tiles,
    "with a voxel tileset: the folder of its tiles (default: the folder named like the XML)");
  AddTypesOption(*check, o->Reading);
  AddPatternOptions(*check, o->Patterns.N, o->Patterns.Symmetry, o->NoPeriodicInput);
  const char* sample = "Image samples (.png, .bmp)";
  check->add_option("--translate", o->Translate, "the picture repeats along these axes (x, y)")
    ->group(sample);
  check->add_flag("--ground", o->Patterns.Ground, "the bottom row is the sample's ground")
    ->group(sample);
  check
    ->add_option("--count", o->Counts,
      "also check that the sites holding label (or tile) L number MIN to MAX (L:MIN:MAX; "
      "repeatable; region=R:L:MIN:MAX: only the sites of the guide's region R), counted from "
      "the model's labels")
    ->allow_extra_args(false);
  check->add_option("--guide", o->Guide,
    "with --count region=R:...: the guide (.vti) whose point array Region gives the regions");
  check->add_option("--connected", o->Connected,
    "also check that the sites holding any of LABELS (values or tile names, commas between) "
    "form at most N components (LABELS[:N], N 1 when left out), through the tileset's "
    "connecting sides");
  check->add_option("--path", o->Path,
    "with --connected: also check that these sites (x,y[,z]) and every site of these labels "
    "hold network labels and lie in one component");
  auto* fixed = check->add_option("--fixed", o->Fixed,
    "also check that the model holds the pins of this label grid (.vti, .txt, .vox; as "
    "synthesize --fixed: the model's size, or a smaller .vti placed by its extent; -1 free)");
  check
    ->add_flag("--fixed-empty-free", o->FixedEmptyFree,
      "with --fixed: label 0 is free too (as synthesize --fixed-empty-free)")
    ->needs(fixed);
  check->add_option("--tileset", o->Names,
    "with --count or --connected and a label grid as EXAMPLE (a pattern's exemplar): the "
    "tileset whose tile names and connecting sides they use (e.g. Data/Patterns/City.xml)");
  auto* animation = check->add_flag("--animation", o->Animation,
    "MODEL is the first frame of an animation (frame_0001.vti of msynth animate): it and the "
    "frames after it (frame_0002.vti, ...) are checked in space and in time against EXAMPLE, "
    "whose z slices are the example's frames");
  check->add_flag("--loop", o->Loop, "with --animation: the last frame is followed by the first")
    ->needs(animation);
  return [o]()
  {
    CheckOrder("check EXAMPLE MODEL", { o->Example }, o->Model);
    CheckInputFile(o->Example);
    CheckInputFile(o->Model, true);
    if (o->Animation)
    {
      if (!o->Counts.empty() || !o->Connected.empty() || !o->Fixed.empty() ||
        IsPolyhedral(o->Example) || IsSample(o->Example) || IsTileset(o->Example))
        throw UsageError{ "--animation checks the frames of a label grid example's animation "
                          "(no --count, --connected, --fixed, tileset, sample or polyhedral "
                          "example)" };
      return CheckAnimation(*o);
    }
    if (IsPolyhedral(o->Example))
    {
      return CheckContinuous(o->Example, o->Model, o->Reading);
    }
    if ((!o->Counts.empty() || !o->Connected.empty() || !o->Fixed.empty()) &&
      (IsPolyhedral(o->Example) || IsSample(o->Example)))
      throw UsageError{ "--count, --connected and --fixed check the labels of a discrete model "
                        "(a label grid or tileset's labels.vti)" };
    if (IsSample(o->Example))
      return CheckSamplePicture(*o);
    if (o->Model.size() > 5 && o->Model.compare(o->Model.size() - 5, 5, ".pvti") == 0)
    {
      if (!o->Counts.empty() || !o->Connected.empty() || !o->Fixed.empty())
        throw UsageError{ "--count, --connected and --fixed check one labels.vti, not the pieces "
                          "of a streamed model" };
      return CheckPieces(o->Example, o->Model, o->Subset, o->Tiles);
    }
    if (!o->Names.empty())
      CheckInputFile(o->Names);
    if (!o->Path.empty() && o->Connected.empty())
      throw UsageError{ "--path needs --connected LABELS: the labels that carry the path" };
    return CheckDiscrete(*o);
  };
}

} // namespace cli
} // namespace msynth
