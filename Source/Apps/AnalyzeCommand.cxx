// SPDX-License-Identifier: BSD-3-Clause
// `msynth analyze EXAMPLE [--out DIR]`: a label grid's labels and transitions as CSV plus the
// example as .vdb; a polyhedral example's catalog of labels and the example marked with them.
// `--infallible`: the search for an infallible refinement E_I of a label grid (D§3.3.8).
#include "Commands.h"
#include "Common.h"
#include "Examples.h"
#include "Synthesize.h"

#include "vtkFieldData.h"
#include "vtkImageData.h"
#include "vtkIntArray.h"
#include "vtkMSLabelArrays.h"
#include "vtkMSLabelGridReader.h"
#include "vtkMSNeighbourhoodLabels.h"
#include "vtkMSOpenVDBWriter.h"
#include "vtkMSTransitionTables.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkXMLImageDataWriter.h"
#include "vtkXMLPolyDataWriter.h"

#include "Core/AtomicFile.h"
#include "Core/Index.h"
#include "Core/OutputFolder.h"
#include "Discrete/InfallibleRefinement.h"

#include <iostream>
#include <memory>

namespace msynth
{
namespace cli
{
namespace
{
struct AnalyzeOptions
{
  std::string Example;
  std::string Out = "msynth-output";
  PolyhedralReading Reading;
  bool Infallible = false;
  std::string WriteInfallible;
  std::vector<std::int64_t> Size;
};

int LabelGridToFolder(const std::string& example, const std::string& dir)
{
  const ExampleTables a = AnalyzeLabelGrid(example);
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

/// The refinement search as one table, and E_I (with f) written when asked.
int InfallibleSearch(const AnalyzeOptions& o)
{
  const ExampleTables a = AnalyzeLabelGrid(o.Example);
  vtkImageData* image = a.Reader->GetOutput();
  const msynth::LabelGrid example =
    vtkMSLabelArrays::ToLabelGrid(image, vtkMSLabelArrays::FindLabelArray(image, nullptr));
  std::array<std::int64_t, 3> size{ { 1, 1, 1 } };
  for (std::size_t i = 0; i < 3; ++i)
    size[i] = o.Size.empty() ? (example.Size(static_cast<int>(i)) > 1 ? 64 : 1) : o.Size[i];
  const msynth::InfallibleRefinement r = msynth::FindInfallibleRefinement(example, size);
  std::cout << "refinements of " << o.Example << " (" << r.Steps.front().Labels << " labels) for "
            << size[0] << " x " << size[1] << " x " << size[2] << " outputs, smallest first:\n"
            << "step | split | labels | Algorithm 3.6 | Eq. 3.13 | why\n";
  int n = 0;
  for (const auto& step : r.Steps)
    std::cout << n++ << " | " << step.Split << " | " << step.Labels << " | "
              << (step.Proved ? "proved" : "not proved") << " | "
              << (step.Equation313.empty() ? "-" : step.Equation313) << " | " << step.Infallibility
              << "\n";
  std::cout << (r.Found ? "infallible: " : "not converted: ") << r.Summary << "\n";
  if (!r.Found)
    return 3;
  std::cout << "f:";
  for (const auto& [from, to] : r.Map)
    if (from != to)
      std::cout << " " << from << "->" << to;
  std::cout << (r.Map.size() == msynth::ToIndex(r.Steps.front().Labels)
      ? " (identity)\n"
      : " (other labels map to themselves)\n");
  if (!o.WriteInfallible.empty())
  {
    vtkNew<vtkImageData> out;
    out->CopyStructure(image);
    vtkSmartPointer<vtkIntArray> labels;
    labels.TakeReference(vtkMSLabelArrays::NewLabelArray(r.Refined, "Label"));
    out->GetPointData()->SetScalars(labels);
    vtkNew<vtkIntArray> map; // f: (label of E_I, label of E) per tuple
    map->SetName("InfallibleLabelMap");
    map->SetNumberOfComponents(2);
    for (const auto& [from, to] : r.Map)
    {
      const int pair[2] = { from, to };
      map->InsertNextTypedTuple(pair);
    }
    out->GetFieldData()->AddArray(map);
    WriteXML<vtkXMLImageDataWriter>(o.WriteInfallible, out.GetPointer());
    std::cout << "wrote " << o.WriteInfallible << " (E_I; f as its field InfallibleLabelMap)\n";
  }
  return 0;
}

/// DIR/labels.csv (the catalog) and DIR/marked-example.vtp.
int PolyhedralToFolder(
  const std::string& path, const PolyhedralReading& reading, const std::string& dir)
{
  auto labels = PolyhedralLabels(path, reading);
  WriteCSV(dir + "/labels.csv", labels->GetLabelTable());
  WriteXML<vtkXMLPolyDataWriter>(dir + "/marked-example.vtp", labels->GetMarkedExample());
  std::cout << "wrote " << dir << "/labels.csv, " << dir << "/marked-example.vtp\n";
  return 0;
}
} // namespace

CLI::Option* AddViaInfallible(CLI::App& synthesize, SynthesizeOptions& o)
{
  return synthesize.add_flag("--via-infallible", o.ViaInfallible,
    "label grids: split the example's labels by their neighbours until synthesis of the whole "
    "model in scan-line order cannot fail, synthesize with the split labels in one attempt and "
    "map the model back (msynth analyze --infallible shows the search); an error when no such "
    "split is found");
}

CommandRunner AddAnalyze(CLI::App& app)
{
  auto o = std::make_shared<AnalyzeOptions>();
  CLI::App* analyze = app.add_subcommand("analyze",
    "write DIR/labels.csv, DIR/transitions.csv and DIR/example.vdb; for a polyhedral example "
    "DIR/labels.csv and DIR/marked-example.vtp (label ids on its features)");
  analyze->add_option("EXAMPLE", o->Example, "a label grid or polyhedral example")->required();
  AddOutOption(*analyze, o->Out);
  AddTypesOption(*analyze, o->Reading);
  analyze->add_flag("--infallible", o->Infallible,
    "search a refinement of a label grid (labels split by their neighbours) with which "
    "synthesis in scan-line order provably never fails and every model stays possible; prints "
    "the search, writes no folder; exit 3 when none is found");
  analyze
    ->add_option("--write-infallible", o->WriteInfallible,
      "with --infallible: write the refined example to FILE (.vti; the split labels to the "
      "example's as the field InfallibleLabelMap; its missing folders are made)")
    ->needs("--infallible");
  analyze
    ->add_option("--size", o->Size,
      "with --infallible: the output size NX NY NZ it is for (only which axes exceed 1 "
      "matters; default: the example's shape)")
    ->expected(3)
    ->check(CLI::Range(std::int64_t(1), std::int64_t(1) << 20))
    ->needs("--infallible");
  return [o]()
  {
    CheckInputFile(o->Example);
    if (o->Infallible)
    {
      if (IsTileset(o->Example) || IsPolyhedral(o->Example) || IsSample(o->Example))
        throw UsageError{ "'" + o->Example +
          "': --infallible needs a label grid (.vti, .txt, .vox)" };
      if (!o->WriteInfallible.empty())
      {
        // Before the search: E_I and its map f are VTK image data; nothing else is replaced.
        const std::string& w = o->WriteInfallible;
        if (w.size() < 5 || w.compare(w.size() - 4, 4, ".vti") != 0)
          throw UsageError{ "--write-infallible '" + o->WriteInfallible +
            "': E_I is written as VTK image data with f as a field; name a .vti file" };
        // Its missing folders are made, as --out's (output/infallible/EI.vti in a fresh checkout).
        if (w.find('/') != std::string::npos && w.rfind('/') > 0)
          msynth::MakeMissingFolders(w.substr(0, w.rfind('/')));
        msynth::CheckReplaceable(o->WriteInfallible);
      }
      return InfallibleSearch(*o);
    }
    if (IsTileset(o->Example))
    {
      throw UsageError{ "'" + o->Example + "' is a tileset: msynth info shows its labels" };
    }
    if (IsPolyhedral(o->Example))
    {
      return IntoFolder(o->Out,
        [&](const std::string& dir) { return PolyhedralToFolder(o->Example, o->Reading, dir); });
    }
    return IntoFolder(
      o->Out, [&](const std::string& dir) { return LabelGridToFolder(o->Example, dir); });
  };
}

} // namespace cli
} // namespace msynth
