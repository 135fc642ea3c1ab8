// SPDX-License-Identifier: BSD-3-Clause
// `msynth info EXAMPLE`: a label grid's labels, counts, transitions (Eq. 3.2) and the
// infallibility verdict (D§3.4); a tileset's labels; a polyhedral example's neighbourhood
// labels and plane families (D§4.3); the files msynth writes (InfoFiles.h, a file per format).
#include "Commands.h"
#include "Common.h"
#include "Examples.h"
#include "InfoFiles.h"

#include "vtkCellData.h"
#include "vtkDataArray.h"
#include "vtkFieldData.h"
#include "vtkImageData.h"
#include "vtkMSLabelGridReader.h"
#include "vtkMSNeighbourhoodLabels.h"
#include "vtkMSTransitionTables.h"
#include "vtkPolyData.h"
#include "vtkSmartPointer.h"
#include "vtkStringArray.h"
#include "vtkTable.h"
#include "vtkVariant.h"

#include "Core/Index.h"
#include "Discrete/OverlappingModel.h"
#include "Formats/Image.h"
#include "Formats/Tileset.h"

#include <sys/stat.h>

#include <cctype>
#include <iostream>
#include <map>
#include <memory>
#include <stdexcept>

namespace msynth
{
namespace cli
{
namespace
{
struct InfoOptions
{
  std::string Example;
  std::string Subset;
  std::string Tiles;
  PolyhedralReading Reading;
  OverlappingOptions Patterns;
  bool NoPeriodicInput = false;
};

/// A voxel tileset: its tiles, their images (labels: tile and symmetry) and the pairs per axis.
int VoxelTilesetInfo(const std::string& path, const msynth::Tileset& t)
{
  std::cout << "tileset: " << path << " (voxel tiles "
            << (t.FullSymmetry ? "with the cube's 48 symmetries" : "with the square's 8 symmetries")
            << ")\n"
            << "tiles folder: " << t.TilesFolder << "\n"
            << "tile size: " << t.VoxelSize[0] << " x " << t.VoxelSize[1] << " x " << t.VoxelSize[2]
            << " voxels\n"
            << "tiles: " << t.Tiles.size() << "\n";
  for (const auto& tile : t.Tiles)
    std::cout << "  " << tile.Name << ": " << Counted(tile.Orientations, "distinct image")
              << " (labels " << tile.FirstLabel << "-" << tile.FirstLabel + tile.Orientations - 1
              << "), weight " << tile.Weight << "\n";
  std::cout << "labels: " << t.NumberOfLabels() << " (tile, symmetry)\n";
  for (int b = 0; b < t.NumberOfLabels(); ++b)
    std::cout << "  label " << b << ": "
              << t.Tiles[msynth::ToIndex(t.LabelTile[msynth::ToIndex(b)])].Name << ", symmetry "
              << t.LabelOrientation[msynth::ToIndex(b)] << "\n";
  const char* names[3] = { "+x", "+y", "+z" };
  for (std::size_t axis = 0; axis < 3; ++axis)
  {
    std::cout << "transitions " << names[axis] << ": " << t.Pairs[axis].size() << "\n";
    for (const auto& p : t.Pairs[axis])
      std::cout << "  " << p.first << "->" << p.second << "\n";
  }
  return 0;
}

int TilesetInfo(const std::string& path, const std::string& subset, const std::string& tiles)
{
  const msynth::Tileset t = msynth::ReadTilesetFile(path, subset, tiles);
  if (t.Voxel)
    return VoxelTilesetInfo(path, t);
  std::cout << "tileset: " << path << (t.Unique ? " (unique)" : "") << "\n"
            << "tiles: " << t.Tiles.size() << "\n"
            << "labels: " << t.NumberOfLabels() << "\n";
  for (int b = 0; b < t.NumberOfLabels(); ++b)
  {
    const auto& tile = t.Tiles[msynth::ToIndex(t.LabelTile[msynth::ToIndex(b)])];
    std::cout << "  label " << b << ": " << t.LabelName(b) << " (symmetry " << tile.Symmetry
              << ", weight " << tile.Weight << ")\n";
  }
  std::cout << "transitions +x: " << t.Pairs[0].size() << "\n"
            << "transitions +y: " << t.Pairs[1].size() << "\n";
  return 0;
}

/// "labels: N", one line per label with its kind and Boolean expression, then the families.
int PolyhedralInfo(const std::string& path, const PolyhedralReading& reading)
{
  auto labels = PolyhedralLabels(path, reading);
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

void PrintTransitions(vtkTable* transitions)
{
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
}

/// An image sample: its colours, the patterns of the given size and symmetry, their pairs.
int SampleInfo(const std::string& example, const OverlappingOptions& options)
{
  const RgbaImage image = ReadImage(example);
  const PatternSet set = ExtractPatterns(image, options, example);
  std::cout << "example: " << example << " (image sample)\n"
            << "size: " << image.Width << " x " << image.Height << " pixels, "
            << Counted(static_cast<long long>(set.Colours.size()), "colour") << "\n"
            << "patterns: " << set.NumberOfPatterns() << " (" << options.N << " x " << options.N
            << " windows, " << Counted(options.Symmetry, "symmetry", "symmetries") << ", "
            << (options.PeriodicInput ? "wrapping" : "not wrapping") << ")\n"
            << "pairs: " << set.Pairs[0].size() << " along x, " << set.Pairs[1].size()
            << " along y\n";
  const AdjacencyRules rules = set.Rules();
  int uniform = 0;
  for (int t = 0; t < set.NumberOfPatterns(); ++t)
    uniform += rules.SelfAdjacent(t, { { 2, 2, 1 } });
  std::cout << "patterns adjacent to themselves (single-pattern starts for blocks): " << uniform
            << "\n";
  return 0;
}

/// A model msynth wrote (mesh.vtp, model.vtp): what it is made of, per label or object type.
/// Its faces join as a model's do (four around an edge where two parts meet), so it is described,
/// not validated as an example would be: `msynth check` does that against its example.
int ModelInfo(const std::string& path, vtkPolyData* model)
{
  vtkFieldData* fd = model->GetFieldData();
  const std::string example =
    vtkStringArray::SafeDownCast(fd->GetAbstractArray("ExampleFile"))->GetValue(0);
  double b[6];
  model->GetBounds(b);
  std::cout << "model: " << path << " (written by msynth from " << example << ")\n"
            << "polygons: " << model->GetNumberOfPolys()
            << ", points: " << model->GetNumberOfPoints() << "\n"
            << "bounds: x " << b[0] << " to " << b[1] << ", y " << b[2] << " to " << b[3] << ", z "
            << b[4] << " to " << b[5] << "\n";
  auto* names = vtkStringArray::SafeDownCast(fd->GetAbstractArray("TypeNames"));
  vtkDataArray* ids = fd->GetArray("TypeIds");
  std::map<long long, std::string> typeName;
  for (vtkIdType i = 0;
       names && ids && i < names->GetNumberOfValues() && i < ids->GetNumberOfTuples(); ++i)
    typeName[static_cast<long long>(ids->GetTuple1(i))] = names->GetValue(i);
  const char* by = model->GetCellData()->GetArray("Label") ? "Label" : "InsideType";
  if (vtkDataArray* cells = model->GetCellData()->GetArray(by))
  {
    std::map<long long, long long> polygons;
    for (vtkIdType c = 0; c < cells->GetNumberOfTuples(); ++c)
      ++polygons[static_cast<long long>(cells->GetTuple1(c))];
    std::cout << (by[0] == 'L' ? "labels: " : "object types: ") << polygons.size() << "\n";
    for (const auto& [value, count] : polygons)
    {
      std::cout << "  " << (by[0] == 'L' ? "label " : "type ") << value;
      if (typeName.count(value))
        std::cout << " (" << typeName[value] << ")";
      std::cout << ": " << Counted(count, "polygon") << "\n";
    }
  }
  if (by[0] == 'L') // a label grid's surface: the labels beside it are what check reads
    std::cout << "check its labels: msynth check " << example << " "
              << path.substr(0, path.find_last_of('/') + 1) << "labels.vti\n";
  else
    std::cout << "check it: msynth check " << example << " " << path << "\n";
  return 0;
}

int LabelGridInfo(const std::string& example)
{
  const ExampleTables a = AnalyzeLabelGrid(example);
  vtkImageData* image = a.Reader->GetOutput();
  vtkTable* labels = a.Tables->GetOutput(1);
  vtkTable* transitions = a.Tables->GetOutput(0);
  int dims[3];
  image->GetDimensions(dims);
  // A model msynth wrote names its example: say it is a model, and how to check it.
  const std::string from = WrittenFrom(example);
  if (from.empty())
    std::cout << "example: " << example << "\n";
  else
    std::cout << "model: " << example << " (written by msynth from " << from
              << "), described as an example would be:\n";
  std::cout << "size: " << dims[0] << " x " << dims[1] << " x " << dims[2] << "\n"
            << "labels: " << labels->GetNumberOfRows() << "\n";
  for (vtkIdType r = 0; r < labels->GetNumberOfRows(); ++r)
  {
    std::cout << "  label " << labels->GetValueByName(r, "Label").ToString() << ": "
              << Counted(labels->GetValueByName(r, "Count").ToLongLong(), "site") << "\n";
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
  PrintTransitions(transitions);
  if (!from.empty())
    std::cout << "check it: msynth check " << from << " " << example << "\n";
  return 0;
}
} // namespace

std::string LowerExtension(const std::string& path)
{
  const std::size_t dot = path.rfind('.');
  if (dot == std::string::npos || path.find('/', dot) != std::string::npos)
    return "";
  std::string ext = path.substr(dot);
  for (auto& c : ext)
    c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return ext;
}

bool IsWrittenFile(const std::string& path)
{
  const std::string ext = LowerExtension(path);
  return ext == ".vdb" || ext == ".glb" || ext == ".gltf" || ext == ".pvti";
}

namespace
{
/// A file msynth wrote, described by its format (after the checks CheckInputFile makes).
int WrittenFileInfo(const std::string& path)
{
  struct stat info;
  if (::stat(path.c_str(), &info) != 0)
    throw std::runtime_error("'" + path + "': no such file");
  if (!S_ISREG(info.st_mode))
    throw std::runtime_error("'" + path + "': " +
      (S_ISDIR(info.st_mode) ? "is a folder, not a file"
                             : "is not a regular file (a pipe, socket or device)"));
  const std::string ext = LowerExtension(path);
  if (ext == ".vdb")
    return VolumeInfo(path);
  if (ext == ".pvti")
    return PiecesInfo(path);
  return GltfInfo(path);
}
} // namespace

CommandRunner AddInfo(CLI::App& app)
{
  auto o = std::make_shared<InfoOptions>();
  CLI::App* info = app.add_subcommand("info",
    "print an example's labels and transition tables; for an image sample (.png, .bmp) its "
    "patterns and their pairs; for a polyhedral example (.obj, .vtp, .ply, .stl) its "
    "neighbourhood labels (continuous model synthesis); for the files msynth writes what they "
    "hold: a .vdb's grids, a .glb or .gltf's meshes and materials, a .vox's models and palette, "
    "a .pvti's pieces");
  info
    ->add_option("EXAMPLE", o->Example,
      "a label grid, tileset or polyhedral example, or a file msynth wrote (.vdb, .glb, "
      ".gltf, .vox, .pvti)")
    ->required();
  AddSubsetOption(*info, o->Subset);
  info->add_option("--tiles", o->Tiles,
    "with a voxel tileset: the folder of its tiles (default: the folder named like the XML)");
  AddTypesOption(*info, o->Reading);
  AddPatternOptions(*info, o->Patterns.N, o->Patterns.Symmetry, o->NoPeriodicInput);
  return [o]()
  {
    if (IsWrittenFile(o->Example))
      return WrittenFileInfo(o->Example);
    CheckInputFile(o->Example);
    // A .vox: its models and palette, then its labels and tables as an example's.
    if (LowerExtension(o->Example) == ".vox")
      VoxInfo(o->Example);
    if (IsSample(o->Example))
    {
      OverlappingOptions patterns = o->Patterns;
      patterns.PeriodicInput = !o->NoPeriodicInput;
      return SampleInfo(o->Example, patterns);
    }
    if (IsTileset(o->Example))
    {
      return TilesetInfo(o->Example, o->Subset, o->Tiles);
    }
    if (const auto model = WrittenModel(o->Example))
      return ModelInfo(o->Example, model);
    if (IsPolyhedral(o->Example))
    {
      return PolyhedralInfo(o->Example, o->Reading);
    }
    return LabelGridInfo(o->Example);
  };
}

} // namespace cli
} // namespace msynth
