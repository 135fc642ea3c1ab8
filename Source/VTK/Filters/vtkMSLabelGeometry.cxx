// SPDX-License-Identifier: BSD-3-Clause
#include "vtkMSLabelGeometry.h"

#include "vtkMSEngineBridge.h"
#include "vtkMSLabelArrays.h"
#include "vtkMSPolyhedra.h"

#include "vtkCellArray.h"
#include "vtkCellArrayIterator.h"
#include "vtkCellData.h"
#include "vtkIdList.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkIntArray.h"
#include "vtkNew.h"
#include "vtkOBJReader.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSmartPointer.h"
#include "vtkXMLPolyDataReader.h"

#include "Core/Error.h"
#include "Discrete/VoxelSurface.h"
#include "Formats/MeshFormats.h"
#include "Formats/Tileset.h"
#include "Formats/VTKXMLCheck.h"

#include <algorithm>
#include <vector>

#include <map>
#include <set>
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
/// @p piece turned to tile orientation @p orientation: (orientation mod 4) quarter turns
/// counter-clockwise about +z, then, for 4–7, mirrored left-right with its polygons reversed.
vtkSmartPointer<vtkPolyData> Turned(vtkPolyData* piece, int orientation)
{
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  points->SetNumberOfPoints(piece->GetNumberOfPoints());
  for (vtkIdType i = 0; i < piece->GetNumberOfPoints(); ++i)
  {
    double p[3];
    piece->GetPoint(i, p);
    for (int r = 0; r < orientation % 4; ++r)
    {
      const double x = p[0];
      p[0] = -p[1];
      p[1] = x;
    }
    if (orientation >= 4)
    {
      p[0] = -p[0];
    }
    points->SetPoint(i, p);
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
    if (orientation >= 4)
    {
      std::reverse(ids.begin(), ids.end());
    }
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
  const std::string ext = path.substr(path.rfind('.') + 1);
  if (ext == "vtp")
  {
    auto r = vtkSmartPointer<vtkXMLPolyDataReader>::New();
    r->SetFileName(path.c_str());
    reader = r;
  }
  else if (ext == "obj")
  {
    auto r = vtkSmartPointer<vtkOBJReader>::New();
    r->SetFileName(path.c_str());
    reader = r;
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
using Pieces = std::map<msynth::Label, vtkSmartPointer<vtkPolyData>>;

/// The pieces of the labels present in @p grid from folder @p folder: <label>.vtp|obj|ply|stl,
/// and with a tileset <tile> <k>.* or <tile>.* turned to orientation k. False with @p problem.
bool LoadPieces(const msynth::LabelGrid& grid, const std::string& folder,
  const std::string& tilesetFile, const std::string& subset, msynth::Label empty, Pieces& pieces,
  std::string& problem)
{
  struct stat info;
  if (::stat(folder.c_str(), &info) != 0 || !S_ISDIR(info.st_mode))
  {
    problem = "'" + folder + "': no such folder of pieces.";
    return false;
  }
  msynth::Tileset tileset;
  if (!tilesetFile.empty())
  {
    try
    {
      tileset = msynth::ReadTilesetFile(tilesetFile, subset);
    }
    catch (const msynth::Error& e)
    {
      problem = e.what();
      return false;
    }
  }
  const std::set<msynth::Label> present(grid.Data().begin(), grid.Data().end());
  for (msynth::Label b : present)
  {
    if (b == empty)
      continue;
    // Candidate names, each with the orientation to turn it by (0: as it is).
    std::vector<std::pair<std::string, int>> names{ { std::to_string(b), 0 } };
    if (!tilesetFile.empty())
    {
      if (b < 0 || b >= tileset.NumberOfLabels())
      {
        problem = "label " + std::to_string(b) + " is not a label of the tileset '" + tilesetFile +
          "' (" + std::to_string(tileset.NumberOfLabels()) + " labels)";
        return false;
      }
      const auto& tile =
        tileset.Tiles[static_cast<std::size_t>(tileset.LabelTile[static_cast<std::size_t>(b)])];
      const int k = tileset.LabelOrientation[static_cast<std::size_t>(b)];
      names.emplace_back(tile.Name + " " + std::to_string(k), 0);
      names.emplace_back(tile.Name, k);
    }
    bool found = false;
    for (const auto& [name, turn] : names)
    {
      for (const char* ext : { ".vtp", ".obj", ".ply", ".stl" })
      {
        const std::string path = folder + "/" + name + ext;
        if (!found && IsFile(path))
        {
          auto mesh = ReadPiece(path, problem);
          if (!mesh)
            return false;
          pieces[b] = turn ? Turned(mesh, turn) : mesh;
          found = true;
        }
      }
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
  if (!this->PieceDirectory.empty() &&
    !LoadPieces(grid, this->PieceDirectory, this->TilesetFile, this->TilesetSubset,
      this->EmptyLabel, pieces, problem))
  {
    vtkErrorMacro(<< problem);
    return 0;
  }
  Geometry geometry;
  geometry.Points->SetDataTypeToDouble();
  geometry.Labels->SetName("Label");
  AppendVoxelSurface(grid, pieces, this->EmptyLabel, start, spacing, geometry);
  for (const auto& kv : pieces)
  {
    if (kv.second->GetPolys()->GetNumberOfCells() == 0)
    {
      vtkWarningMacro(<< "The piece of label " << kv.first << " has no polygons; skipped.");
      continue;
    }
    AppendPiece(grid, kv.first, kv.second, start, spacing, geometry);
  }
  output->SetPoints(geometry.Points);
  output->SetPolys(geometry.Polys);
  output->GetCellData()->SetScalars(geometry.Labels);
  vtkMSLabelArrays::AddPaletteColors(input->GetFieldData(), output);
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
