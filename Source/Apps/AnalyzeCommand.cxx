// SPDX-License-Identifier: BSD-3-Clause
// `msynth analyze EXAMPLE [--out DIR]`: a label grid's labels and transitions as CSV plus the
// example as .vdb; a polyhedral example's catalog of labels and the example marked with them.
#include "Commands.h"
#include "Common.h"
#include "Examples.h"

#include "vtkMSLabelGridReader.h"
#include "vtkMSNeighbourhoodLabels.h"
#include "vtkMSOpenVDBWriter.h"
#include "vtkMSTransitionTables.h"
#include "vtkPolyData.h"
#include "vtkXMLPolyDataWriter.h"

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

CommandRunner AddAnalyze(CLI::App& app)
{
  auto o = std::make_shared<AnalyzeOptions>();
  CLI::App* analyze = app.add_subcommand("analyze",
    "write DIR/labels.csv, DIR/transitions.csv and DIR/example.vdb; for a polyhedral example "
    "DIR/labels.csv and DIR/marked-example.vtp (label ids on its features)");
  analyze->add_option("EXAMPLE", o->Example, "a label grid or polyhedral example")->required();
  AddOutOption(*analyze, o->Out);
  AddTypesOption(*analyze, o->Reading);
  return [o]()
  {
    CheckInputFile(o->Example);
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
