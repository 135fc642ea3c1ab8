// SPDX-License-Identifier: BSD-3-Clause
// `msynth synthesize EXAMPLE.obj --size SX SY SZ`: continuous model synthesis (D ch. 4): plane
// arrangement (vtkMSPlaneArrangement) → label solver (vtkMSContinuousSynthesis) → mesh
// (vtkMSArrangementMesh) → model.vtp, arrangement.vtp, model.vdb, mesh.glb, model.vox and
// statistics.json.
#include "Common.h"
#include "Examples.h"
#include "Resemblance.h"
#include "Synthesize.h"

#include "vtkDataArray.h"
#include "vtkFieldData.h"
#include "vtkMSArrangementMesh.h"
#include "vtkMSContinuousSynthesis.h"
#include "vtkMSGLTFWriter.h"
#include "vtkMSLabelGridWriter.h"
#include "vtkMSOpenVDBWriter.h"
#include "vtkMSPlaneArrangement.h"
#include "vtkMSPolyhedralExampleReader.h"
#include "vtkPolyData.h"
#include "vtkXMLImageDataReader.h"
#include "vtkXMLPolyDataWriter.h"

#include <chrono>
#include <cmath>
#include <functional>
#include <iostream>
#include <set>
#include <sstream>

namespace msynth
{
namespace cli
{
namespace
{
/// Which of arrangement.vtp (labels), model.vtp (mesh), model.vdb (vdb), mesh.glb (glb) and
/// model.vox (vox) to write: --outputs, else all but vox (mesh.glb costs a fraction of model.vtp's
/// time: 0.14 s of the town's 80 s run; the voxels are a lossy copy only MagicaVoxel users
/// want). @throw std::runtime_error naming a kind polyhedral examples do not write.
std::set<std::string> ContinuousOutputs(const SynthesizeOptions& o)
{
  std::set<std::string> kinds;
  std::stringstream items(o.Outputs.empty() ? "labels,mesh,vdb,glb" : o.Outputs);
  for (std::string item; std::getline(items, item, ',');)
  {
    if (item != "labels" && item != "mesh" && item != "vdb" && item != "glb" && item != "vox")
      throw std::runtime_error("--outputs: polyhedral examples write labels (arrangement.vtp), "
                               "mesh (model.vtp), vdb (model.vdb), glb (mesh.glb) and vox "
                               "(model.vox), not '" +
        item + "'");
    kinds.insert(item);
  }
  return kinds;
}

/// model.vdb's level sets: at most this many voxels in their bands by default (about a second
/// of export on two cores).
constexpr double LevelSetBudget = 1e6;

/// One number of field data @p name, 0 when absent.
double NumberOf(vtkFieldData* fd, const char* name)
{
  vtkDataArray* a = fd ? fd->GetArray(name) : nullptr;
  return a && a->GetNumberOfTuples() > 0 ? a->GetTuple1(0) : 0.0;
}

/// model.vdb: a 3D model as level sets per object type and a fog volume; a 2D (or empty) model
/// as a slab of object types (the writer chooses the voxels from the planes of @p labelled,
/// unless --voxel gives them).
double WriteModelVDB(
  vtkPolyData* model, vtkPolyData* labelled, const SynthesizeOptions& o, const std::string& dir)
{
  vtkNew<vtkMSOpenVDBWriter> vdb;
  vdb->SetInputData(model);
  vdb->SetArrangementData(labelled);
  vdb->SetVoxelSize(o.Voxel);
  vdb->SetLevelSetBudget(LevelSetBudget);
  vdb->SetFileName((dir + "/model.vdb").c_str());
  vdb->AddMetadata("msynth_command", "synthesize");
  vdb->AddMetadata("example", o.Example.c_str());
  vdb->AddMetadata("seed", std::to_string(o.Seed).c_str());
  vdb->AddMetadata(
    "block_spacings", std::to_string(NumberOf(labelled->GetFieldData(), "BlockSize")).c_str());
  vdb->AddMetadata("plane_spacing", o.Spacing > 0 ? std::to_string(o.Spacing).c_str() : "derived");
  {
    ProgressBar bar(vdb, "model.vdb");
    Run(vdb);
  }
  return vdb->GetWrittenVoxelSize();
}

/// mesh.glb (a mesh and material per object type, named by the example: vtkMSGLTFWriter) and
/// model.vox (the model voxelized for MagicaVoxel, palette index = object type:
/// vtkMSLabelGridWriter) as @p outputs ask, each timed by @p lap and added to @p written.
/// Returns model.vox's voxel, 0 without it.
double WriteExports(vtkPolyData* model, const SynthesizeOptions& o,
  const std::set<std::string>& outputs, const std::string& dir,
  const std::function<void(const char*)>& lap, std::string& written)
{
  if (outputs.count("glb"))
  {
    vtkNew<vtkMSGLTFWriter> glb;
    glb->SetInputData(model);
    glb->SetFileName((dir + "/mesh.glb").c_str());
    Run(glb);
    lap("mesh.glb");
    written += dir + "/mesh.glb, ";
  }
  if (!outputs.count("vox"))
    return 0;
  vtkNew<vtkMSLabelGridWriter> vox;
  vox->SetInputData(model);
  vox->SetVoxelSize(o.Voxel);
  vox->SetFileName((dir + "/model.vox").c_str());
  Run(vox);
  lap("model.vox");
  written += dir + "/model.vox, ";
  return vox->GetWrittenVoxelSize();
}

void WriteStatistics(vtkPolyData* labelled, vtkPolyData* model, const SynthesizeOptions& o,
  const std::string& dir, const std::vector<std::pair<std::string, double>>& stages, double voxel,
  double voxVoxel)
{
  vtkFieldData* fd = labelled->GetFieldData();
  vtkDataArray* match = fd->GetArray("MatchError");
  std::string seconds;
  for (const auto& [stage, value] : stages)
    seconds += (seconds.empty() ? "" : ", ") + JsonString(stage) + ": " + JsonNumber(value);
  StatisticsJson()
    .Text("example", o.Example)
    .Raw("size",
      "[" + JsonNumber(o.Size[0]) + ", " + JsonNumber(o.Size[1]) + ", " + JsonNumber(o.Size[2]) +
        "]")
    .Number("blockSize", NumberOf(fd, "BlockSize"))
    .Text("SiteOrder", MessageOf(fd, "SiteOrder"))
    .Count("seed", o.Seed)
    // The figure and name of the console's summary and of the solver's message.
    .Count("ArrangementVertices", labelled->GetNumberOfPoints())
    .Count("Polygons", model->GetNumberOfPolys())
    .Solver(fd)
    .Flag("Grounded", o.Grounded)
    .Flag("ExampleSizes", !o.NoSizes)
    .Count("Components", CountOf(fd, "Components"))
    .Count("GroundedComponents", CountOf(fd, "GroundedComponents"))
    .Count("FloatingPartsRemoved", CountOf(fd, "FloatingPartsRemoved"))
    .Count("PartsBeyondSeedsRemoved", CountOf(fd, "PartsBeyondSeedsRemoved"))
    .Count("NarrowPartsRemoved", CountOf(fd, "NarrowPartsRemoved"))
    // Proportions: parts emptied to keep the types' shares, and the types still outside 25 %.
    .Count("ProportionPartsRemoved", CountOf(fd, "ProportionPartsRemoved"))
    .Number("ProportionVolumeRemoved", NumberOf(fd, "ProportionVolumeRemoved"))
    .Count("ProportionBlocksRedrawn", CountOf(fd, "ProportionBlocksRedrawn"))
    .Text("ProportionsOutside", MessageOf(fd, "ProportionsOutside"))
    .Count("ModelCandidates", o.Models)
    .Count("ModelChosen", CountOf(fd, "ModelChosen"))
    .Number("MatchError", match ? match->GetTuple1(0) : 0.0)
    // The narrowest face, edge or gap (up to the smallest plane spacing), and as a fraction of it.
    .Number("SmallestFeature", NumberOf(model->GetFieldData(), "SmallestFeature"))
    .Number("SmallestFeatureFraction", NumberOf(model->GetFieldData(), "SmallestFeatureFraction"))
    // Shares of the solid per object type: by volume of the model written, and by vertex
    // occupancy (what the proportions steer).
    .Prefixed("TypeShares", model->GetFieldData(), "VolumeShare_")
    .Prefixed("VertexShares", fd, "TypeShare_")
    // Parts of each type, their sizes and what they front, against the example's.
    .Raw("Resemblance", ResemblanceJson(model->GetFieldData()))
    .Raw("StageSeconds", "{" + seconds + "}")
    .Number("VoxelSize", voxel)
    .Number("VoxVoxelSize", voxVoxel)
    .Text("Message", MessageOf(fd))
    .Write(dir + "/statistics.json");
}

/// The label solver's settings from the command line's options.
void ConfigureSolver(vtkMSContinuousSynthesis* synthesis, const SynthesizeOptions& o)
{
  synthesis->SetSeed(static_cast<vtkIdType>(o.Seed));
  synthesis->SetBlockSize(o.Blocks);
  synthesis->SetAttempts(o.Attempts);
  synthesis->SetNumberOfThreads(o.Threads);
  synthesis->SetSiteOrder(o.Order.empty()
      ? vtkMSContinuousSynthesis::AUTOMATIC_ORDER
      : (o.Order == "scanline" ? 0 : (o.Order == "random" ? 1 : 2)));
  synthesis->SetLabelChoice(o.Choice == "frequency" ? 1 : 0);
  synthesis->SetNumberOfSnapshots(o.Snapshots);
  synthesis->SetGrounded(o.Grounded);
  synthesis->SetKeepProportions(!o.NoProportions);
  synthesis->SetExampleSizes(!o.NoSizes);
  synthesis->SetBlockCandidates(o.Candidates);
  synthesis->SetModelCandidates(o.Models);
  synthesis->SetMirror(o.Mirror.find('x') != std::string::npos,
    o.Mirror.find('y') != std::string::npos, o.Mirror.find('z') != std::string::npos);
  synthesis->SetThickness(Joined(o.Thickness).c_str());
  synthesis->SetOverhang(Joined(o.Overhang).c_str());
  synthesis->SetConnected(Joined(o.Connected).c_str());
  synthesis->SetTargetFractions(Joined(o.Targets).c_str());
}

/// --detail TYPE=FILE: the detail mesh read (in the example's up axis) and substituted for the
/// objects of TYPE by @p mesh. Nothing without the option. @throw std::runtime_error.
void ConnectDetail(vtkMSArrangementMesh* mesh, vtkMSPolyhedralExampleReader* detail,
  vtkMSPolyhedralExampleReader* reader, const std::string& detailOption)
{
  if (detailOption.empty())
  {
    return;
  }
  const auto equals = detailOption.find('=');
  if (equals == std::string::npos || equals == 0 || equals + 1 == detailOption.size())
    throw std::runtime_error("--detail '" + detailOption + "' is not TYPE=FILE");
  detail->SetFileName(detailOption.substr(equals + 1).c_str());
  detail->SetUpAxis(reader->GetUpAxis()); // modelled in the same tool as the example
  Run(detail);
  mesh->SetDetailType(detailOption.substr(0, equals).c_str());
  mesh->SetDetailConnection(detail->GetOutputPort());
}

/// Notes on the terminal what the arrangement had to give up (as the filter warns), once.
void NoteArrangementCompromises(vtkMSPlaneArrangement* arrangement)
{
  vtkFieldData* fd = arrangement->GetOutput()->GetFieldData();
  const long long without = CountOf(fd, "NonTrihedralLabelsWithoutSites");
  if (without > 0)
    std::cerr << "msynth: note: over-constrained plane spacing: " << without << " of "
              << CountOf(fd, "NonTrihedralLabels")
              << " vertices where four or more planes meet cannot appear in the output\n";
  vtkDataArray* change = fd->GetArray("DirectionChangeDegrees");
  if (change && CountOf(fd, "MaximumSmallInteger") > 12)
    std::cerr << "msynth: note: plane directions snapped to fit exact arithmetic; faces turn by "
                 "up to "
              << change->GetTuple1(0) << " degrees\n";
  else if (vtkDataArray* tolerance = fd->GetArray("AngleTolerance");
           change && tolerance && tolerance->GetTuple1(0) > arrangement->GetAngleTolerance())
    std::cerr << "msynth: note: four or more planes meet at a corner of the example, so plane "
                 "directions were snapped to small integers; faces turn by up to "
              << change->GetTuple1(0) << " degrees\n";
}

/// The run's one-line summary, and a note when proportion steering emptied most of the model.
void PrintSummary(vtkPolyData* labelled, vtkPolyData* model)
{
  vtkFieldData* fd = labelled->GetFieldData();
  std::cout << labelled->GetNumberOfPoints() << " arrangement vertices, "
            << model->GetNumberOfPolys() << " polygons, " << CountOf(fd, "BlocksFailed") << " of "
            << Counted(CountOf(fd, "Blocks"), "block") << " left unchanged, "
            << Counted(CountOf(fd, "Components"), "solid part") << " ("
            << CountOf(fd, "GroundedComponents") << " on the ground)\n";
  // Proportion steering can empty most of the first model: say so where the user looks.
  vtkDataArray* emptied = fd->GetArray("ProportionVolumeRemoved");
  if (emptied && emptied->GetTuple1(0) > 0.5)
    std::cout << "note: " << Counted(CountOf(fd, "ProportionPartsRemoved"), "part") << " ("
              << static_cast<int>(std::lround(100 * emptied->GetTuple1(0)))
              << " % of the solid) were emptied to keep the example's proportions; more "
                 "constraints (--thickness, --overhang) or --no-proportions keep more\n";
  if (ResemblanceFailed(model->GetFieldData()) >= 0)
    std::cout << "structure against the example: " << ResemblanceSummary(model->GetFieldData())
              << "\n";
}
} // namespace

int SynthesizeContinuous(const SynthesizeOptions& o, const std::string& dir)
{
  // Seconds per stage, for statistics.json (a user sees where a run's time goes).
  std::vector<std::pair<std::string, double>> stages;
  auto clock = std::chrono::steady_clock::now();
  auto lap = [&](const char* stage)
  {
    const auto now = std::chrono::steady_clock::now();
    stages.emplace_back(stage, std::chrono::duration<double>(now - clock).count());
    clock = now;
  };
  const std::set<std::string> outputs = ContinuousOutputs(o);
  vtkNew<vtkMSPolyhedralExampleReader> reader;
  ConfigureReader(reader, o.Example, o.Reading);
  Run(reader);
  double exampleBounds[6];
  reader->GetOutput()->GetBounds(exampleBounds);
  const bool flat = exampleBounds[5] - exampleBounds[4] <= 0;
  if (o.Size[0] <= 0 || o.Size[1] <= 0 || (!flat && o.Size[2] <= 0))
  {
    throw std::runtime_error("'" + o.Example + "': --size must be positive along x, y" +
      (flat ? std::string() : std::string(" and z")) + " (example units)");
  }
  vtkNew<vtkMSPlaneArrangement> arrangement;
  arrangement->SetInputConnection(reader->GetOutputPort());
  arrangement->SetOutputSize(o.Size[0], o.Size[1], o.Size[2]);
  arrangement->SetSpacing(o.Spacing);
  vtkNew<vtkMSContinuousSynthesis> synthesis;
  synthesis->SetInputConnection(0, reader->GetOutputPort());
  synthesis->SetArrangementConnection(arrangement->GetOutputPort());
  ConfigureSolver(synthesis, o);
  // A mistyped constraint is reported before the arrangement is built (minutes at city sizes).
  const std::string problem = synthesis->CheckConstraints(
    reader->GetOutput(), arrangement->GetAngleTolerance(), arrangement->GetMaximumSmallInteger());
  if (!problem.empty())
    throw std::runtime_error(problem);
  vtkNew<vtkXMLImageDataReader> guide;
  if (!o.Guide.empty())
    ConnectGuide(synthesis, 2, guide, o.Guide);
  vtkNew<vtkMSArrangementMesh> mesh;
  mesh->SetInputConnection(0, reader->GetOutputPort());
  mesh->SetArrangementConnection(synthesis->GetOutputPort());
  vtkNew<vtkMSPolyhedralExampleReader> detail;
  ConnectDetail(mesh, detail, reader, o.Detail);
  Run(arrangement);
  lap("example and arrangement");
  NoteArrangementCompromises(arrangement);
  {
    ProgressBar bar(synthesis);
    Run(synthesis);
  }
  lap("synthesis");
  {
    ProgressBar bar(mesh, "mesh");
    Run(mesh);
  }
  lap("mesh");
  vtkPolyData* model = mesh->GetOutput();
  vtkPolyData* labelled = synthesis->GetOutput();

  std::string written; // "DIR/model.vtp, ..." as they are written
  if (outputs.count("mesh"))
  {
    WriteXML<vtkXMLPolyDataWriter>(dir + "/model.vtp", model);
    written += dir + "/model.vtp, ";
  }
  if (outputs.count("labels"))
  {
    // Past a quarter of a million vertices zlib took most of the writing (the town at 100 x 100
    // x 10, 2.5 M vertices: 10 s, 92 MB); LZ4 with raw bytes 2.5 s, 174 MB, as for large voxel
    // meshes.
    const bool large = labelled->GetNumberOfPoints() >= (vtkIdType(1) << 18);
    WriteXML<vtkXMLPolyDataWriter>(dir + "/arrangement.vtp", labelled, false, large);
    written += dir + "/arrangement.vtp, ";
  }
  lap("vtp files");
  double voxel = 0;
  if (outputs.count("vdb"))
  {
    voxel = WriteModelVDB(model, labelled, o, dir);
    lap("model.vdb");
    written += dir + "/model.vdb, ";
  }
  const double voxVoxel = WriteExports(model, o, outputs, dir, lap, written);
  std::string sequence;
  if (o.Snapshots > 0)
  {
    // The catalog at each snapshot, resampled to voxels: DIR/catalog_0001.vdb, ...
    WriteCatalogSequence(synthesis, dir, o.Voxel, "example", o.Example);
    sequence = ", " + dir + "/catalog_0001.vdb ... catalog_" +
      std::to_string(10000 + o.Snapshots + 1).substr(1) + ".vdb";
  }
  if (o.Snapshots > 0)
    lap("catalog sequence");
  WriteStatistics(labelled, model, o, dir, stages, voxel, voxVoxel);
  PrintSummary(labelled, model);
  std::cout << "wrote " << written << dir << "/statistics.json" << sequence << "\n";
  return 0;
}

} // namespace cli
} // namespace msynth
