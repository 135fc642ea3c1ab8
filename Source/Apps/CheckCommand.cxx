// SPDX-License-Identifier: BSD-3-Clause
// `msynth check EXAMPLE MODEL`: the independent checks, which share no code with the solvers: a
// label grid against the pairs of its example (Eq. 3.1) or tileset, a continuous model against
// the neighbourhoods of its polyhedral example (Eq. 4.1, closed and oriented), a picture against
// the windows of its image sample.
#include "Commands.h"
#include "Common.h"
#include "Examples.h"

#include "vtkDataArray.h"
#include "vtkDataObject.h"
#include "vtkFieldData.h"
#include "vtkImageData.h"
#include "vtkMSCheckModel.h"
#include "vtkMSEngineBridge.h"
#include "vtkMSLabelGridReader.h"
#include "vtkMSPolyhedralExampleReader.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkStringArray.h"
#include "vtkXMLImageDataReader.h"
#include "vtkXMLPolyDataReader.h"

#include "Core/Error.h"
#include "Core/FileBytes.h"
#include "Core/Memory.h"
#include "Core/TextLists.h"
#include "Discrete/OverlappingModel.h"
#include "Formats/Image.h"
#include "Formats/Tileset.h"
#include "Formats/VTKXMLCheck.h"
#include "Formats/VoxModel.h"
#include "Formats/VoxelTileset.h"

#include <algorithm>
#include <cstring>
#include <fstream>
#include <iostream>
#include <map>
#include <memory>
#include <set>
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
  std::string Guide; ///< --guide: the guide whose Region array --count region=R:... reads
};

/// The label values @p name gives: a value, or the labels of a tile or label name of @p set.
std::vector<long long> NamedValues(const std::string& name, const msynth::Tileset& set)
{
  std::vector<long long> values;
  long long v = 0;
  if (msynth::ParseInteger(name, -(1LL << 31), (1LL << 31) - 1, v))
    values.push_back(v);
  for (int b = 0; b < set.NumberOfLabels(); ++b)
    if (set.LabelName(b) == name ||
      set.Tiles[static_cast<std::size_t>(set.LabelTile[static_cast<std::size_t>(b)])].Name == name)
      values.push_back(b);
  return values;
}

/**
 * `--path A B ...`: the sites (x,y[,z]) and every site of the labels (values or names of
 * @p set) hold network labels (@p mask >= 0) and share one root of the union-find @p root.
 * Prints one line; false when they do not. @throw std::runtime_error for a site outside the
 * model or an item that is neither a site nor a label.
 */
bool CheckPathJoined(const std::vector<std::string>& path, const msynth::Tileset& set,
  vtkDataArray* labels, const std::vector<int>& mask,
  const std::function<vtkIdType(vtkIdType)>& root, const int dims[3])
{
  std::vector<vtkIdType> sites;
  for (const std::string& item : path)
  {
    const std::vector<std::string> parts = msynth::SplitText(item, ',');
    long long c[3] = { 0, 0, 0 };
    bool isSite = parts.size() == 2 || parts.size() == 3;
    for (std::size_t a = 0; isSite && a < parts.size(); ++a)
      isSite = msynth::ParseInteger(parts[a], -(1LL << 40), 1LL << 40, c[a]);
    if (isSite)
    {
      for (int a = 0; a < 3; ++a)
        if (c[a] < 0 || c[a] >= dims[a])
          throw std::runtime_error("--path: site " + item + " is outside the model (" +
            std::to_string(dims[0]) + " x " + std::to_string(dims[1]) + " x " +
            std::to_string(dims[2]) + " sites)");
      sites.push_back(static_cast<vtkIdType>(c[0] + dims[0] * (c[1] + dims[1] * c[2])));
      continue;
    }
    const std::vector<long long> values = NamedValues(item, set);
    if (values.empty())
      throw std::runtime_error(
        "--path: '" + item + "' is neither a site x,y[,z] nor a label value or name");
    for (vtkIdType i = 0; i < labels->GetNumberOfTuples(); ++i)
      if (std::find(values.begin(), values.end(), static_cast<long long>(labels->GetTuple1(i))) !=
        values.end())
        sites.push_back(i);
  }
  std::set<vtkIdType> roots;
  for (vtkIdType s : sites)
  {
    if (mask[static_cast<std::size_t>(s)] < 0)
    {
      std::cout << "path not joined: site (" << s % dims[0] << ", " << (s / dims[0]) % dims[1]
                << ", " << s / (static_cast<vtkIdType>(dims[0]) * dims[1]) << ") holds label "
                << static_cast<long long>(labels->GetTuple1(s)) << ", not one of the network's\n";
      return false;
    }
    roots.insert(root(s));
  }
  const bool ok = roots.size() <= 1;
  std::cout << (ok ? "path joined: " : "path not joined: ") << sites.size() << " site"
            << (sites.size() == 1 ? "" : "s") << " in " << roots.size() << " component"
            << (roots.size() == 1 ? "" : "s") << " of the network\n";
  return ok;
}

} // namespace

/**
 * `--connected LABELS[:N]`: the sites of @p model holding any of LABELS (values, or with a
 * tileset @p example tile or label names) form at most N components (1 when left out), counted
 * here by a union-find of its own over face neighbours, joined through the sides the tileset's
 * `connects` attributes give (every side for a tile without one). Prints one line.
 */
bool CheckConnected(const std::string& spec, const std::string& example, const std::string& subset,
  const std::string& tiles, vtkImageData* model, const std::vector<std::string>& path)
{
  vtkDataArray* labels = model ? model->GetPointData()->GetArray("Label") : nullptr;
  if (!labels)
    throw std::runtime_error("--connected: the model has no Label array");
  msynth::Tileset set;
  if (IsTileset(example))
    set = msynth::ReadTilesetFile(example, subset, tiles);
  std::string list = spec;
  long long most = 1;
  const std::size_t colon = list.rfind(':');
  if (colon != std::string::npos)
  {
    if (!msynth::ParseInteger(list.substr(colon + 1), 1, 1LL << 40, most))
      throw std::runtime_error(
        "--connected: '" + list.substr(colon + 1) + "' is not a number of components (1 or more)");
    list.resize(colon);
  }
  std::map<long long, int>
    sides; // network label -> the sides it joins through (bits +x -x +y -y +z -z)
  for (const std::string& name : msynth::SplitText(list, ','))
  {
    const std::size_t before = sides.size();
    for (long long v : NamedValues(name, set))
      sides[v] = 63;
    if (sides.size() == before && !name.empty())
      throw std::runtime_error(
        "--connected: '" + name + "' is neither a label value nor a name of " + example);
  }
  for (auto& [label, mask] : sides)
    if (label >= 0 && label < static_cast<long long>(set.LabelSides.size()) &&
      set.LabelSides[static_cast<std::size_t>(label)] >= 0)
      mask = set.LabelSides[static_cast<std::size_t>(label)];
  int dims[3];
  model->GetDimensions(dims);
  const vtkIdType total = labels->GetNumberOfTuples();
  std::vector<vtkIdType> parent(static_cast<std::size_t>(total));
  std::vector<int> mask(static_cast<std::size_t>(total), -1);
  for (vtkIdType i = 0; i < total; ++i)
  {
    parent[static_cast<std::size_t>(i)] = i;
    const auto found = sides.find(static_cast<long long>(labels->GetTuple1(i)));
    if (found != sides.end())
      mask[static_cast<std::size_t>(i)] = found->second;
  }
  auto root = [&](vtkIdType i)
  {
    while (parent[static_cast<std::size_t>(i)] != i)
      i = parent[static_cast<std::size_t>(i)] =
        parent[static_cast<std::size_t>(parent[static_cast<std::size_t>(i)])];
    return i;
  };
  const vtkIdType stride[3] = { 1, dims[0], static_cast<vtkIdType>(dims[0]) * dims[1] };
  for (vtkIdType i = 0; i < total; ++i)
  {
    const int here = mask[static_cast<std::size_t>(i)];
    const vtkIdType at[3] = { i % dims[0], (i / dims[0]) % dims[1], i / stride[2] };
    for (int a = 0; a < 3 && here >= 0; ++a)
    {
      if (at[a] + 1 >= dims[a] || !((here >> (2 * a)) & 1))
        continue;
      const int there = mask[static_cast<std::size_t>(i + stride[a])];
      if (there >= 0 && ((there >> (2 * a + 1)) & 1))
        parent[static_cast<std::size_t>(root(i))] = root(i + stride[a]);
    }
  }
  long long components = 0;
  for (vtkIdType i = 0; i < total; ++i)
    components += mask[static_cast<std::size_t>(i)] >= 0 && root(i) == i ? 1 : 0;
  const bool ok = components <= most;
  std::cout << (ok ? "connected: " : "not connected: ") << list << " form " << components
            << " component" << (components == 1 ? "" : "s") << " (wanted at most " << most << ")\n";
  return (path.empty() || CheckPathJoined(path, set, labels, mask, root, dims)) && ok;
}

namespace
{
/**
 * `--count L:MIN:MAX`: the sites of @p model holding L (a label value, or with a tileset
 * @p example a tile's name, all its orientations, or a label's name "tile k"), counted here
 * from the written labels. Prints one line per count; false when one is outside its range.
 */
/// The guide region of every site of @p model (x fastest) from the `Region` point array of
/// the guide @p path stretched over it: a site at p of n reads the guide point
/// floor((p + 1/2) · D / n) per axis, as `--guide` does.
std::vector<long long> SiteRegions(const std::string& path, vtkImageData* model)
{
  if (path.empty())
    throw std::runtime_error("--count region=R:...: give the guide with --guide GUIDE.vti");
  CheckInputFile(path);
  vtkNew<vtkXMLImageDataReader> reader;
  reader->SetFileName(path.c_str());
  std::string messages;
  if (!vtkMSEngineBridge::Execute(reader, messages))
    throw std::runtime_error("'" + path + "': not a readable guide volume: " + messages);
  vtkImageData* guide = reader->GetOutput();
  vtkDataArray* region = guide->GetPointData()->GetArray("Region");
  if (!region)
    throw std::runtime_error("'" + path + "': the guide has no point array Region");
  int d[3], n[3];
  guide->GetDimensions(d);
  model->GetDimensions(n);
  std::vector<long long> out;
  out.reserve(static_cast<std::size_t>(n[0]) * n[1] * n[2]);
  for (long long z = 0; z < n[2]; ++z)
    for (long long y = 0; y < n[1]; ++y)
      for (long long x = 0; x < n[0]; ++x)
      {
        const long long p[3] = { x, y, z };
        long long cell[3];
        for (int a = 0; a < 3; ++a)
          cell[a] = std::min<long long>(d[a] - 1, (p[a] * 2 * d[a] + d[a]) / (2LL * n[a]));
        out.push_back(static_cast<long long>(
          region->GetTuple1(static_cast<vtkIdType>(cell[0] + d[0] * (cell[1] + d[1] * cell[2])))));
      }
  return out;
}

bool CheckCounts(const std::vector<std::string>& counts, const std::string& example,
  const std::string& subset, const std::string& tiles, vtkImageData* model,
  const std::string& guidePath)
{
  vtkDataArray* labels = model ? model->GetPointData()->GetArray("Label") : nullptr;
  if (!labels)
    throw std::runtime_error("--count: the model has no Label array");
  msynth::Tileset set;
  if (IsTileset(example))
    set = msynth::ReadTilesetFile(example, subset, tiles);
  bool kept = true;
  std::string list;
  for (const std::string& c : counts)
    list += c + ",";
  std::vector<long long> regions; // read once, for the first count of a region
  for (msynth::CountEntry e : msynth::ParseCountEntries(list, "--count"))
  {
    long long region = -1;
    if (e.Name.compare(0, 7, "region=") == 0)
    {
      const std::size_t colon = e.Name.find(':');
      if (colon == std::string::npos ||
        !msynth::ParseInteger(e.Name.substr(7, colon - 7), 0, (1LL << 31) - 1, region))
        throw std::runtime_error("--count: '" + e.Name + "' is not region=R:L (R from 0)");
      e.Name = e.Name.substr(colon + 1);
      if (regions.empty())
        regions = SiteRegions(guidePath, model);
    }
    std::set<long long> values;
    long long v = 0;
    if (msynth::ParseInteger(e.Name, -(1LL << 31), (1LL << 31) - 1, v))
      values.insert(v);
    for (int b = 0; b < set.NumberOfLabels() && values.empty(); ++b)
      if (set.LabelName(b) == e.Name)
        values.insert(b);
    for (int b = 0; b < set.NumberOfLabels(); ++b)
      if (set.Tiles[static_cast<std::size_t>(set.LabelTile[static_cast<std::size_t>(b)])].Name ==
        e.Name)
        values.insert(b);
    if (values.empty())
      throw std::runtime_error(
        "--count: '" + e.Name + "' is neither a label value nor a name of " + example);
    long long n = 0;
    for (vtkIdType i = 0; i < labels->GetNumberOfTuples(); ++i)
      n += values.count(static_cast<long long>(labels->GetTuple1(i))) &&
          (region < 0 || regions[static_cast<std::size_t>(i)] == region)
        ? 1
        : 0;
    const bool ok = n >= e.Minimum && n <= e.Maximum;
    kept = kept && ok;
    std::cout << (ok ? "count kept: " : "count missed: ") << e.Name
              << (region >= 0 ? " in guide region " + std::to_string(region) : std::string())
              << " holds " << n << " sites (wanted " << e.Minimum << " to " << e.Maximum << ")\n";
  }
  return kept;
}

/// A picture against the windows of its image sample (Discrete/OverlappingModel.h's
/// CheckPicture, which shares no code with the patterns' synthesis).
int CheckSamplePicture(const CheckOptions& o)
{
  if (!IsSample(o.Model))
    throw std::runtime_error(
      "'" + o.Model + "': the model of an image sample is its picture (.png)");
  OverlappingOptions options = o.Patterns;
  options.PeriodicInput = !o.NoPeriodicInput;
  const msynth::Periodic periodic{ { o.Translate.find('x') != std::string::npos,
    o.Translate.find('y') != std::string::npos } };
  const RgbaImage picture = ReadImage(o.Model);
  const auto problems = CheckPicture(ReadImage(o.Example), options, picture, periodic, 10);
  if (problems.empty())
  {
    std::cout << "consistent: every " << options.N << " x " << options.N << " window of " << o.Model
              << " (" << picture.Width << " x " << picture.Height << ") occurs in " << o.Example
              << "\n";
    return 0;
  }
  std::cout << "inconsistent: " << o.Model << " has windows that are not in " << o.Example << "\n";
  for (const auto& p : problems)
    std::cout << "  " << p << "\n";
  return 1;
}

/// The verdict of @p check (vtkMSCheckModel's field data) after it ran.
struct Verdict
{
  vtkFieldData* Fields;
  bool Valid() const { return CountOf(this->Fields, "Valid") == 1; }
  /// Prints each problem line, after @p prefix.
  void PrintProblems(const char* prefix) const
  {
    if (auto* lines = vtkStringArray::SafeDownCast(this->Fields->GetAbstractArray("Problems")))
      for (vtkIdType i = 0; i < lines->GetNumberOfValues(); ++i)
        std::cout << prefix << lines->GetValue(i) << "\n";
  }
};

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
    std::cout << "valid: " << modelPath << " (" << modelReader->GetOutput()->GetNumberOfPolys()
              << " polygons, " << CountOf(verdict.Fields, "Objects")
              << " objects) has only neighbourhoods of " << example << " ("
              << CountOf(verdict.Fields, "DistinctLabels") << " distinct)\n";
    vtkDataArray* width = verdict.Fields->GetArray("SmallestFeature");
    vtkDataArray* fraction = verdict.Fields->GetArray("SmallestFeatureFraction");
    if (width && fraction && fraction->GetTuple1(0) > 0)
      std::cout << "narrowest face, edge or gap: " << width->GetTuple1(0) << " ("
                << fraction->GetTuple1(0) << " of the smallest plane spacing)\n";
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
  head.resize(static_cast<std::size_t>(in.gcount()));
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

/// A voxel model (.vox, all its models placed by its scene) against a voxel tileset: every tile
/// cell identified by its voxels, every pair against the rules (VoxelTileset.h: CheckVoxelModel).
int CheckVoxels(const std::string& example, const std::string& modelPath, const std::string& tiles)
{
  const msynth::VoxModel model = msynth::ReadVoxSceneFile(modelPath,
    static_cast<std::int64_t>(std::min<std::uint64_t>(
      std::uint64_t(1) << 30, msynth::AvailableMemory() / (2 * sizeof(msynth::Label)))));
  const msynth::VoxelCheckReport report =
    msynth::CheckVoxelModel(example, tiles, model.Grid, model.Palette);
  const auto& d = model.Grid.Dimensions();
  if (report.Valid)
  {
    std::cout << "consistent: all " << report.Cells << " tile cells of " << modelPath << " ("
              << d[0] << " x " << d[1] << " x " << d[2] << " voxels, " << model.NumberOfModels
              << (model.NumberOfModels == 1 ? " model" : " models") << ") are tiles of " << example
              << " and all " << report.PairsChecked << " adjacent pairs are allowed\n";
    return 0;
  }
  std::cout << "inconsistent: " << report.Problems << " problems in " << modelPath << " ("
            << report.Cells << " tile cells, " << report.PairsChecked << " pairs)\n";
  for (const auto& line : report.First)
    std::cout << "  " << line << "\n";
  return 1;
}

/// @p check of the model @p m reads against @p example (read by @p e) or its tileset.
void SetUpDiscreteCheck(vtkMSCheckModel* check, vtkMSLabelGridReader* e, vtkMSLabelGridReader* m,
  const std::string& example, const std::string& subset, const std::string& tiles)
{
  e->GenerateGeometryOff(); // the labels are checked, not shown
  m->GenerateGeometryOff();
  check->SetInputConnection(m->GetOutputPort());
  if (IsTileset(example))
  {
    check->SetTilesetFile(example.c_str());
    check->SetTilesetSubset(subset.c_str());
    check->SetTilesFolder(tiles.c_str());
  }
  else
  {
    e->SetFileName(example.c_str());
    check->AddExampleConnection(e->GetOutputPort());
  }
}

/// A label grid against the pairs of its example grid or tileset: readers → vtkMSCheckModel.
int CheckDiscrete(const std::string& example, const std::string& modelPath,
  const std::string& subset, const std::string& tiles, const std::vector<std::string>& counts,
  const std::string& connected, const std::string& names, const std::vector<std::string>& path,
  const std::string& guide)
{
  if (IsTileset(example) && IsVoxelTileset(example) && modelPath.size() > 4 &&
    modelPath.compare(modelPath.size() - 4, 4, ".vox") == 0)
  {
    if (!counts.empty() || !connected.empty())
      throw std::runtime_error(
        "--count and --connected check a model's labels (labels.vti), not '" + modelPath + "'");
    return CheckVoxels(example, modelPath, tiles);
  }
  vtkNew<vtkMSLabelGridReader> e, m;
  m->SetFileName(modelPath.c_str());
  vtkNew<vtkMSCheckModel> check;
  SetUpDiscreteCheck(check, e, m, example, subset, tiles);
  Run(check);
  auto* labels = vtkImageData::SafeDownCast(m->GetOutputDataObject(0));
  const std::string& named = IsTileset(example) || names.empty() ? example : names;
  bool kept = counts.empty() || CheckCounts(counts, named, subset, tiles, labels, guide);
  kept =
    (connected.empty() || CheckConnected(connected, named, subset, tiles, labels, path)) && kept;
  const Verdict verdict{ check->GetOutput()->GetFieldData() };
  if (verdict.Valid())
  {
    std::cout << "consistent: all " << CountOf(verdict.Fields, "PairsChecked")
              << " adjacent pairs of " << modelPath << " occur in " << example << "\n";
    return kept ? 0 : 1;
  }
  std::cout << "inconsistent: " << CountOf(verdict.Fields, "Violations") << " of "
            << CountOf(verdict.Fields, "PairsChecked") << " adjacent pairs never occur in "
            << example << "\n";
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
  std::cout << "consistent: all " << pairs << " adjacent pairs of the " << pieces.size()
            << " pieces of " << path << " (seams included) occur in " << example << "\n";
  return 0;
}
} // namespace

CommandRunner AddCheck(CLI::App& app)
{
  auto o = std::make_shared<CheckOptions>();
  CLI::App* check = app.add_subcommand("check",
    "verify that MODEL satisfies the adjacency constraint of EXAMPLE (a label grid or tileset; "
    "Eq. 3.1) or, for a polyhedral EXAMPLE, that the continuous MODEL.vtp is closed, oriented "
    "and has only the example's neighbourhoods (Eq. 4.1), or for an image sample that every "
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
  check->add_option("--tileset", o->Names,
    "with --count or --connected and a label grid as EXAMPLE (a pattern's exemplar): the "
    "tileset whose tile names and connecting sides they use (e.g. Data/Patterns/City.xml)");
  return [o]()
  {
    CheckInputFile(o->Example);
    CheckInputFile(o->Model, true);
    if (IsPolyhedral(o->Example))
    {
      return CheckContinuous(o->Example, o->Model, o->Reading);
    }
    if ((!o->Counts.empty() || !o->Connected.empty()) &&
      (IsPolyhedral(o->Example) || IsSample(o->Example)))
      throw UsageError{ "--count and --connected check the labels of a discrete model (a label "
                        "grid or tileset's labels.vti)" };
    if (IsSample(o->Example))
      return CheckSamplePicture(*o);
    if (o->Model.size() > 5 && o->Model.compare(o->Model.size() - 5, 5, ".pvti") == 0)
    {
      if (!o->Counts.empty() || !o->Connected.empty())
        throw UsageError{ "--count and --connected check one labels.vti, not the pieces of a "
                          "streamed model" };
      return CheckPieces(o->Example, o->Model, o->Subset, o->Tiles);
    }
    if (!o->Names.empty())
      CheckInputFile(o->Names);
    if (!o->Path.empty() && o->Connected.empty())
      throw UsageError{ "--path needs --connected LABELS: the labels that carry the path" };
    return CheckDiscrete(o->Example, o->Model, o->Subset, o->Tiles, o->Counts, o->Connected,
      o->Names, o->Path, o->Guide);
  };
}

} // namespace cli
} // namespace msynth
