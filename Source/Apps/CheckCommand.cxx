// SPDX-License-Identifier: BSD-3-Clause
// `msynth check EXAMPLE MODEL`: the independent checks, which share no code with the solvers: a
// label grid against the pairs of its example (Eq. 3.1) or tileset, a continuous model against
// the neighbourhoods of its polyhedral example (Eq. 4.1, closed and oriented).
#include "Commands.h"
#include "Common.h"
#include "vtkMSLabelArrays.h"
#include "vtkMSPolyhedra.h"

#include "vtkImageData.h"
#include "vtkMSLabelGridReader.h"
#include "vtkMSPolyhedralExampleReader.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkXMLPolyDataReader.h"

#include "Continuous/ContinuousMesh.h"
#include "Core/Error.h"
#include "Discrete/ConsistencyCheck.h"
#include "Formats/Tileset.h"
#include "Formats/VTKXMLCheck.h"

#include <iostream>
#include <memory>
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
  std::string Types;
};

/// A continuous model (.vtp) against its polyhedral example.
int CheckContinuous(
  const std::string& example, const std::string& modelPath, const std::string& objectTypes)
{
  vtkNew<vtkMSPolyhedralExampleReader> reader;
  reader->SetFileName(example.c_str());
  reader->SetObjectTypes(objectTypes.c_str());
  Run(reader);
  msynth::CheckVTKXMLFile(modelPath);
  vtkNew<vtkXMLPolyDataReader> modelReader;
  modelReader->SetFileName(modelPath.c_str());
  std::string messages;
  if (!vtkMSEngineBridge::Execute(modelReader, messages))
  {
    throw std::runtime_error("'" + modelPath + "': not a readable VTP model: " + messages);
  }
  msynth::PolyhedralExample ex;
  const msynth::PolyhedralAnalysis analysis =
    vtkMSPolyhedra::AnalyzeExample(reader->GetOutput(), 0.01, 12, ex);
  const auto mesh = vtkMSPolyhedra::ToContinuousMesh(modelReader->GetOutput(), modelPath);
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

/// A label grid against the pairs of its example grid or tileset.
int CheckDiscrete(
  const std::string& example, const std::string& modelPath, const std::string& subset)
{
  vtkNew<vtkMSLabelGridReader> e, m;
  m->SetFileName(modelPath.c_str());
  Run(m);
  auto grid = [](vtkImageData* image)
  { return vtkMSLabelArrays::ToLabelGrid(image, image->GetPointData()->GetArray("Label")); };
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
} // namespace

CommandRunner AddCheck(CLI::App& app)
{
  auto o = std::make_shared<CheckOptions>();
  CLI::App* check = app.add_subcommand("check",
    "verify that MODEL satisfies the adjacency constraint of EXAMPLE (a label grid or tileset; "
    "Eq. 3.1) or, for a polyhedral EXAMPLE, that the continuous MODEL.vtp is closed, oriented "
    "and has only the example's neighbourhoods (Eq. 4.1). Exit 0 when it does, 1 listing the "
    "problems when not");
  check->add_option("EXAMPLE", o->Example, "the example the model was synthesized from")
    ->required();
  check->add_option("MODEL", o->Model, "the model (.vti, .txt, .vox; .vtp for continuous)")
    ->required();
  AddSubsetOption(*check, o->Subset);
  AddTypesOption(*check, o->Types);
  return [o]()
  {
    CheckInputFile(o->Example);
    CheckInputFile(o->Model, true);
    if (IsPolyhedral(o->Example))
    {
      return CheckContinuous(o->Example, o->Model, o->Types);
    }
    return CheckDiscrete(o->Example, o->Model, o->Subset);
  };
}

} // namespace cli
} // namespace msynth
