// SPDX-License-Identifier: BSD-3-Clause
#include "vtkMSLabelGeometry.h"

#include "vtkMSEngineBridge.h"
#include "vtkMSLabelArrays.h"
#include "vtkMSOnDemand.h"
#include "vtkMSPolyhedra.h"

#include "vtkAlgorithm.h"
#include "vtkCellArray.h"
#include "vtkCellArrayIterator.h"
#include "vtkCellData.h"
#include "vtkFieldData.h"
#include "vtkIdList.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkIntArray.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSmartPointer.h"
#include "vtkStringArray.h"
#include "vtkXMLPolyDataReader.h"

#include "Core/Error.h"
#include "Core/Index.h"
#include "Discrete/VoxelSurface.h"
#include "Formats/MeshFormats.h"
#include "Formats/Tileset.h"
#include "Formats/VTKXMLCheck.h"
#include "Formats/VoxelTileset.h"

#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <map>
#include <set>
#include <vector>

#include <dirent.h>
#include <sys/stat.h>

vtkStandardNewMacro(vtkMSLabelGeometry);

int vtkMSLabelGeometry::FillInputPortInformation(int, vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkImageData");
  return 1;
}

namespace
{
bool IsFile(const std::string& path)
{
  struct stat info;
  return ::stat(path.c_str(), &info) == 0 && S_ISREG(info.st_mode);
}

/// Reads a piece mesh with the reader its extension calls for; nullptr and @p problem on error.
/// An integer orthogonal map of a piece's points (about the site's centre): q = T p.
using PieceTurn = std::array<std::array<int, 3>, 3>;

/// The turn of a tile's orientation @p orientation: for a voxel tileset (@p voxel) the symmetry
/// of that index in msynth::SymmetryGroup (a source lookup image(q) = tile(M q), so points move
/// by M's transpose); else (orientation mod 4) quarter turns counter-clockwise about +z, then,
/// for 4-7, the left-right mirror.
PieceTurn TurnOf(int orientation, bool voxel, bool full)
{
  PieceTurn t{ { { { 1, 0, 0 } }, { { 0, 1, 0 } }, { { 0, 0, 1 } } } };
  if (voxel)
  {
    const auto& m = msynth::SymmetryGroup(full)[msynth::ToIndex(orientation)].M;
    for (std::size_t i = 0; i < 3; ++i)
      for (std::size_t j = 0; j < 3; ++j)
        t[i][j] = m[j][i];
    return t;
  }
  for (int r = 0; r < orientation % 4; ++r)
    t = { { { { -t[1][0], -t[1][1], -t[1][2] } }, t[0], t[2] } }; // (x, y) -> (-y, x)
  if (orientation >= 4)
    t[0] = { { -t[0][0], -t[0][1], -t[0][2] } };
  return t;
}

/// @p piece moved by @p turn, its polygons reversed when the turn mirrors (keeping them facing
/// out).
vtkSmartPointer<vtkPolyData> Turned(vtkPolyData* piece, const PieceTurn& turn)
{
  const int det = turn[0][0] * (turn[1][1] * turn[2][2] - turn[1][2] * turn[2][1]) -
    turn[0][1] * (turn[1][0] * turn[2][2] - turn[1][2] * turn[2][0]) +
    turn[0][2] * (turn[1][0] * turn[2][1] - turn[1][1] * turn[2][0]);
  const bool mirror = det < 0;
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  points->SetNumberOfPoints(piece->GetNumberOfPoints());
  for (vtkIdType i = 0; i < piece->GetNumberOfPoints(); ++i)
  {
    double p[3], q[3];
    piece->GetPoint(i, p);
    for (std::size_t a = 0; a < 3; ++a)
      q[a] = turn[a][0] * p[0] + turn[a][1] * p[1] + turn[a][2] * p[2];
    points->SetPoint(i, q);
  }
  vtkNew<vtkCellArray> polys;
  auto it = vtk::TakeSmartPointer(piece->GetPolys()->NewIterator());
  std::vector<vtkIdType> ids;
  for (it->GoToFirstCell(); !it->IsDoneWithTraversal(); it->GoToNextCell())
  {
    vtkIdType n;
    const vtkIdType* cell;
    it->GetCurrentCell(n, cell);
    ids.assign(cell, cell + n);
    if (mirror)
      std::reverse(ids.begin(), ids.end());
    polys->InsertNextCell(n, ids.data());
  }
  auto out = vtkSmartPointer<vtkPolyData>::New();
  out->SetPoints(points);
  out->SetPolys(polys);
  return out;
}

vtkSmartPointer<vtkPolyData> ReadPiece(const std::string& path, std::string& problem)
{
  vtkSmartPointer<vtkAlgorithm> reader;
  std::string ext = path.substr(path.rfind('.') + 1);
  for (char& c : ext)
    c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  if (ext == "vtp")
  {
    auto r = vtkSmartPointer<vtkXMLPolyDataReader>::New();
    r->SetFileName(path.c_str());
    reader = r;
  }
  else if (ext == "obj")
  {
    try
    {
      reader = vtkMSOnDemand::NewOBJReader(path);
    }
    catch (const std::exception& e)
    {
      problem = "'" + path + "': could not be read: " + e.what();
      return nullptr;
    }
  }
  else
  {
    // PLY and STL through the engine's checked readers (VTK's crash on damaged files).
    try
    {
      const msynth::PolyhedralExample piece =
        ext == "ply" ? msynth::ReadPLYExample(path) : msynth::ReadSTLExample(path);
      auto mesh = vtkSmartPointer<vtkPolyData>::New();
      vtkMSPolyhedra::FromPolyhedralExample(piece, mesh);
      return mesh;
    }
    catch (const std::exception& e)
    {
      problem = e.what();
      return nullptr;
    }
  }
  if (ext == "vtp")
  {
    try
    {
      msynth::CheckVTKXMLFile(path);
    }
    catch (const std::exception& e)
    {
      const std::string what = e.what(), prefix = "'" + path + "': ";
      problem = prefix + "could not be read: " +
        (what.compare(0, prefix.size(), prefix) == 0 ? what.substr(prefix.size()) : what);
      return nullptr;
    }
  }
  std::string messages;
  if (!vtkMSEngineBridge::Execute(reader, messages))
  {
    problem = "'" + path + "': could not be read: " + messages;
    return nullptr;
  }
  auto* mesh = vtkPolyData::SafeDownCast(reader->GetOutputDataObject(0));
  if (!mesh || mesh->GetNumberOfPoints() == 0 || mesh->GetNumberOfCells() == 0)
  {
    problem = "'" + path + "': holds no geometry";
    return nullptr;
  }
  return mesh;
}
} // namespace

namespace
{
/// The meshes of each label: several when the example names several pieces for it (all drawn).
using Pieces = std::map<msynth::Label, std::vector<vtkSmartPointer<vtkPolyData>>>;

const char* const MeshExtensions[] = { "vtp", "obj", "ply", "stl" };

std::string Lower(std::string text)
{
  for (char& c : text)
    c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return text;
}

bool IsMeshExtension(const std::string& ext)
{
  return std::find(std::begin(MeshExtensions), std::end(MeshExtensions), ext) !=
    std::end(MeshExtensions);
}

/// Files that go with meshes and are not pieces themselves: OBJ material libraries, textures.
bool IsCompanion(const std::string& ext)
{
  for (const char* e : { "mtl", "png", "jpg", "jpeg", "tga", "bmp", "tif", "tiff" })
    if (ext == e)
      return true;
  return false;
}

/// (name without its extension, lower-case extension) of file @p file.
std::pair<std::string, std::string> SplitName(const std::string& file)
{
  const std::size_t dot = file.rfind('.');
  if (dot == std::string::npos || dot == 0)
    return { file, "" };
  return { file.substr(0, dot), Lower(file.substr(dot + 1)) };
}

/// The regular files of @p folder, sorted, hidden ones left out. False with @p problem when
/// it is not a folder.
bool ListFolder(const std::string& folder, std::vector<std::string>& files, std::string& problem)
{
  struct stat info;
  DIR* dir = ::stat(folder.c_str(), &info) == 0 && S_ISDIR(info.st_mode) ? ::opendir(folder.c_str())
                                                                         : nullptr;
  if (!dir)
  {
    problem = "'" + folder + "': no such folder of pieces.";
    return false;
  }
  while (const dirent* entry = ::readdir(dir))
  {
    const std::string name = entry->d_name;
    if (!name.empty() && name[0] != '.' && IsFile(folder + "/" + name))
      files.push_back(name);
  }
  ::closedir(dir);
  std::sort(files.begin(), files.end());
  return true;
}

/// The names a piece may have: a label number, a piece name of the example (the `$name`
/// entries of a `.txt` example's `<Objects>` section), or a tile of the tileset.
struct PieceNaming
{
  std::map<msynth::Label, std::vector<std::string>> ExampleNames;
  std::set<std::string> AllExampleNames;
  const msynth::Tileset* Tiles = nullptr;
  std::string TilesetFile;

  bool Matches(const std::string& stem) const
  {
    char* end = nullptr;
    const long number = std::strtol(stem.c_str(), &end, 10);
    if (!stem.empty() && *end == '\0' && std::to_string(number) == stem)
      return true;
    if (this->AllExampleNames.count(stem))
      return true;
    if (this->Tiles)
      for (const auto& tile : this->Tiles->Tiles)
        for (int k = -1; k < 8; ++k)
          if (stem == (k < 0 ? tile.Name : tile.Name + " " + std::to_string(k)))
            return true;
    return false;
  }

  /// How pieces are named here, for messages.
  std::string Describe() const
  {
    std::string text = "pieces are named <label>.vtp|.obj|.ply|.stl (e.g. 2.obj)";
    if (!this->AllExampleNames.empty())
    {
      text += " or after the example's pieces (";
      int shown = 0;
      for (const auto& kv : this->ExampleNames)
        for (const auto& name : kv.second)
          if (shown++ < 8)
            text += (shown > 1 ? ", " : "") + name + ".obj";
      text += shown > 8 ? ", ...)" : ")";
    }
    if (this->Tiles)
      text += " or after the tileset's tiles (<tile>.obj, '<tile> <k>.obj')";
    return text;
  }
};

/// The example's piece names per label: the field data `PieceLabels`/`PieceNames` of @p input.
PieceNaming NamingOf(vtkDataObject* input, const msynth::Tileset* tiles)
{
  PieceNaming naming;
  naming.Tiles = tiles;
  vtkFieldData* fd = input->GetFieldData();
  auto* labels = vtkIntArray::SafeDownCast(fd->GetAbstractArray("PieceLabels"));
  auto* names = vtkStringArray::SafeDownCast(fd->GetAbstractArray("PieceNames"));
  if (labels && names && labels->GetNumberOfValues() == names->GetNumberOfValues())
    for (vtkIdType i = 0; i < names->GetNumberOfValues(); ++i)
    {
      naming.ExampleNames[labels->GetValue(i)].push_back(names->GetValue(i));
      naming.AllExampleNames.insert(names->GetValue(i));
    }
  return naming;
}

/// The files of @p folder that match no name of @p naming (companions of meshes left out);
/// @p matched counts those that do.
std::vector<std::string> Unmatched(
  const std::vector<std::string>& files, const PieceNaming& naming, int& matched)
{
  std::vector<std::string> unmatched;
  matched = 0;
  for (const auto& file : files)
  {
    const auto [stem, ext] = SplitName(file);
    if (IsMeshExtension(ext) && naming.Matches(stem))
      ++matched;
    else if (!IsCompanion(ext))
      unmatched.push_back(file);
  }
  return unmatched;
}

/// The pieces of the labels present in @p grid from folder @p folder, looked up per label as
/// <label>.ext, else every piece the example names for it (<name>.ext), else with a tileset
/// <tile> <k>.ext or <tile>.ext turned to orientation k. @p warning names the files that match
/// nothing; false with @p problem when the folder is missing, empty or matches nothing.
bool LoadPieces(const msynth::LabelGrid& grid, const std::string& folder, const PieceNaming& naming,
  msynth::Label empty, Pieces& pieces, std::string& warning, std::string& problem)
{
  std::vector<std::string> files;
  if (!ListFolder(folder, files, problem))
    return false;
  if (files.empty())
  {
    problem = "'" + folder + "': the folder of pieces is empty; " + naming.Describe() + ".";
    return false;
  }
  int matched = 0;
  const std::vector<std::string> unmatched = Unmatched(files, naming, matched);
  std::string list;
  for (const auto& file : unmatched)
    list += (list.empty() ? "" : ", ") + file;
  if (matched == 0)
  {
    problem = "'" + folder + "': no file is a piece (" + list + "); " + naming.Describe() + ".";
    return false;
  }
  if (!unmatched.empty())
    warning = "'" + folder + "': " + std::to_string(unmatched.size()) +
      (unmatched.size() == 1 ? " file matches" : " files match") +
      " no label and no piece name and " + (unmatched.size() == 1 ? "is" : "are") +
      " not used: " + list + "; " + naming.Describe() + ".";
  // The file of each name (the first of .vtp, .obj, .ply, .stl; extensions in any case).
  std::map<std::string, std::string> byName;
  for (const char* want : MeshExtensions)
    for (const auto& file : files)
      if (SplitName(file).second == want)
        byName.emplace(SplitName(file).first, file);
  const std::set<msynth::Label> present(grid.Data().begin(), grid.Data().end());
  for (msynth::Label b : present)
  {
    if (b == empty)
      continue;
    // Candidate names, each with the orientation to turn it by (0: as it is); the first group
    // with a file wins: the label number, the example's pieces (all), the tile.
    std::vector<std::vector<std::pair<std::string, int>>> groups{ { { std::to_string(b), 0 } } };
    bool voxel = false, full = false; // a voxel tileset's tiles turn by its symmetry group
    if (naming.ExampleNames.count(b))
    {
      groups.emplace_back();
      for (const auto& name : naming.ExampleNames.at(b))
        groups.back().emplace_back(name, 0);
    }
    if (const msynth::Tileset* tileset = naming.Tiles)
    {
      if (b < 0 || b >= tileset->NumberOfLabels())
      {
        problem = "label " + std::to_string(b) + " is not a label of the tileset '" +
          naming.TilesetFile + "' (" + std::to_string(tileset->NumberOfLabels()) + " labels)";
        return false;
      }
      const auto& tile = tileset->Tiles[msynth::ToIndex(tileset->LabelTile[msynth::ToIndex(b)])];
      const int k = tileset->LabelOrientation[msynth::ToIndex(b)];
      groups.push_back({ { tile.Name + " " + std::to_string(k), 0 } });
      groups.push_back({ { tile.Name, k } });
      voxel = tileset->Voxel;
      full = tileset->FullSymmetry;
    }
    for (const auto& group : groups)
    {
      for (const auto& [name, turn] : group)
      {
        const auto file = byName.find(name);
        if (file == byName.end())
          continue;
        auto mesh = ReadPiece(folder + "/" + file->second, problem);
        if (!mesh)
          return false;
        pieces[b].push_back(turn ? Turned(mesh, TurnOf(turn, voxel, full)) : mesh);
      }
      if (pieces.count(b))
        break;
    }
  }
  return true;
}

/// Where the geometry goes: points, polygons and their labels.
struct Geometry
{
  vtkNew<vtkPoints> Points;
  vtkNew<vtkCellArray> Polys;
  vtkNew<vtkIntArray> Labels;
};

/// The voxel surface of the labels without a piece (labels with one count as empty there).
void AppendVoxelSurface(const msynth::LabelGrid& grid, const Pieces& pieces, msynth::Label empty,
  const std::array<double, 3>& start, const double* spacing, Geometry& out)
{
  msynth::LabelGrid voxels = grid;
  for (auto& v : voxels.Data())
    if (pieces.count(v))
      v = empty;
  const msynth::VoxelSurface surface =
    msynth::ExtractVoxelSurface(voxels, empty, start, { { spacing[0], spacing[1], spacing[2] } });
  for (const auto& p : surface.Points)
    out.Points->InsertNextPoint(p.data());
  for (std::size_t q = 0; q < surface.Quads.size(); ++q)
  {
    const vtkIdType ids[4] = { surface.Quads[q][0], surface.Quads[q][1], surface.Quads[q][2],
      surface.Quads[q][3] };
    out.Polys->InsertNextCell(4, ids);
    out.Labels->InsertNextValue(surface.QuadLabels[q]);
  }
}

/// Piece @p piece of label @p label placed at every site holding it (scaled by the spacing).
void AppendPiece(const msynth::LabelGrid& grid, msynth::Label label, vtkPolyData* piece,
  const std::array<double, 3>& start, const double* spacing, Geometry& out)
{
  vtkCellArray* cells = piece->GetPolys();
  const auto& n = grid.Dimensions();
  vtkNew<vtkIdList> cell;
  for (std::int64_t z = 0; z < n[2]; ++z)
    for (std::int64_t y = 0; y < n[1]; ++y)
      for (std::int64_t x = 0; x < n[0]; ++x)
      {
        if (grid.At(x, y, z) != label)
          continue;
        const vtkIdType base = out.Points->GetNumberOfPoints();
        const double center[3] = { start[0] + double(x) * spacing[0],
          start[1] + double(y) * spacing[1], start[2] + double(z) * spacing[2] };
        for (vtkIdType i = 0; i < piece->GetNumberOfPoints(); ++i)
        {
          double p[3];
          piece->GetPoint(i, p);
          out.Points->InsertNextPoint(center[0] + p[0] * spacing[0], center[1] + p[1] * spacing[1],
            center[2] + p[2] * spacing[2]);
        }
        for (vtkIdType c = 0; c < cells->GetNumberOfCells(); ++c)
        {
          cells->GetCellAtId(c, cell);
          for (vtkIdType i = 0; i < cell->GetNumberOfIds(); ++i)
            cell->SetId(i, cell->GetId(i) + base);
          out.Polys->InsertNextCell(cell);
          out.Labels->InsertNextValue(label);
        }
      }
}
} // namespace

int vtkMSLabelGeometry::RequestData(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  vtkImageData* input = vtkImageData::GetData(inputVector[0], 0);
  vtkPolyData* output = vtkPolyData::GetData(outputVector, 0);
  msynth::LabelGrid grid;
  std::string problem;
  if (!vtkMSLabelArrays::ReadLabels(input, nullptr, grid, problem))
  {
    vtkErrorMacro(<< "Bad input: " << problem);
    return 0;
  }
  const double* spacing = input->GetSpacing();
  const std::array<double, 3> start = vtkMSLabelArrays::FirstSitePosition(input);
  Pieces pieces;
  std::string warning;
  if (!this->PieceDirectory.empty())
  {
    msynth::Tileset tileset;
    if (!this->TilesetFile.empty())
    {
      try
      {
        // A voxel tileset's tiles folder, as the synthesis recorded it (field data).
        auto* folder =
          vtkStringArray::SafeDownCast(input->GetFieldData()->GetAbstractArray("TilesFolder"));
        tileset = msynth::ReadTilesetFile(this->TilesetFile, this->TilesetSubset,
          folder && folder->GetNumberOfValues() == 1 ? folder->GetValue(0) : std::string());
      }
      catch (const msynth::Error& e)
      {
        vtkErrorMacro(<< e.what());
        return 0;
      }
    }
    PieceNaming naming = NamingOf(input, this->TilesetFile.empty() ? nullptr : &tileset);
    naming.TilesetFile = this->TilesetFile;
    if (!LoadPieces(grid, this->PieceDirectory, naming, this->EmptyLabel, pieces, warning, problem))
    {
      vtkErrorMacro(<< problem);
      return 0;
    }
  }
  Geometry geometry;
  geometry.Points->SetDataTypeToDouble();
  geometry.Labels->SetName("Label");
  AppendVoxelSurface(grid, pieces, this->EmptyLabel, start, spacing, geometry);
  for (const auto& kv : pieces)
    for (const auto& piece : kv.second)
    {
      if (piece->GetPolys()->GetNumberOfCells() == 0)
      {
        vtkWarningMacro(<< "A piece of label " << kv.first << " has no polygons; skipped.");
        continue;
      }
      AppendPiece(grid, kv.first, piece, start, spacing, geometry);
    }
  output->SetPoints(geometry.Points);
  output->SetPolys(geometry.Polys);
  output->GetCellData()->SetScalars(geometry.Labels);
  vtkMSLabelArrays::AddPaletteColors(input->GetFieldData(), output);
  if (!warning.empty())
  {
    // Said once here, and kept with the output for those who show no VTK warnings (msynth).
    vtkWarningMacro(<< warning);
    vtkNew<vtkStringArray> kept;
    kept->SetName("PieceFolderWarning");
    kept->InsertNextValue(warning);
    output->GetFieldData()->AddArray(kept);
  }
  return 1;
}

void vtkMSLabelGeometry::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "EmptyLabel: " << this->EmptyLabel << "\n";
  os << indent << "PieceDirectory: " << this->PieceDirectory << "\n";
  os << indent << "TilesetFile: " << this->TilesetFile << "\n";
  os << indent << "TilesetSubset: " << this->TilesetSubset << "\n";
}
