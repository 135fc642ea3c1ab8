// SPDX-License-Identifier: BSD-3-Clause
// `msynth batch SAMPLES.xml`: every entry of a sample list of the original model-synthesis
// program or of WaveFunctionCollapse (Formats/SampleList.h), synthesized as `msynth synthesize`
// would, each output checked independently of the solver, and a summary table.
#include "Commands.h"
#include "Common.h"
#include "Synthesize.h"

#include "vtkFieldData.h"
#include "vtkImageData.h"
#include "vtkMSCheckModel.h"
#include "vtkMSLabelArrays.h"
#include "vtkMSLabelGridReader.h"
#include "vtkPointData.h"

#include "Core/Error.h"
#include "Core/OutputFolder.h"
#include "Formats/Image.h"
#include "Formats/SampleList.h"
#include "Formats/Tileset.h"

#include <cerrno>
#include <chrono>
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
struct BatchOptions
{
  std::string List;
  std::string Out = "msynth-batch";
  std::int64_t Seed = 0;
  int Threads = 0;
  int Screenshots = -1; ///< -1: as the list says
};

/// One output's line of the summary.
struct Outcome
{
  std::string Result = "ok"; ///< ok, inconsistent, or error
  std::string Problem;
  long long FailedBlocks = 0;
  double Seconds = 0.0;
};

/// The independent check of one output folder through vtkMSCheckModel: pictures against the
/// sample's windows, labels against the tileset's pairs or the example's (Eq. 3.1). Empty when
/// right, else the first problem.
std::string CheckOutput(const SampleEntry& e, const std::string& dir)
{
  vtkNew<vtkMSCheckModel> check;
  check->SetMaximumReported(1);
  vtkNew<vtkImageData> picture;
  vtkNew<vtkMSLabelGridReader> model, example;
  model->GenerateGeometryOff();
  example->GenerateGeometryOff();
  if (e.Kind == SampleEntry::Overlapping)
  {
    vtkMSLabelArrays::SetPicture(picture, ReadImage(dir + "/picture.png"));
    check->SetInputData(picture);
    check->SetSampleFile(e.File.c_str());
    check->SetPatternSize(e.N);
    check->SetPatternSymmetry(e.Symmetry);
    check->SetPeriodicInput(e.PeriodicInput);
    check->SetGround(e.Ground);
    check->SetPeriodicOutput(e.Periodic ? 1 : 0, e.Periodic ? 1 : 0);
  }
  else
  {
    model->SetFileName((dir + "/labels.vti").c_str());
    check->SetInputConnection(model->GetOutputPort());
    if (e.Kind == SampleEntry::SimpleTiled)
    {
      check->SetTilesetFile(e.File.c_str());
      check->SetTilesetSubset(e.Subset.c_str());
    }
    else
    {
      example->SetFileName(e.File.c_str());
      check->AddExampleConnection(example->GetOutputPort());
    }
  }
  Run(check);
  vtkFieldData* verdict = check->GetOutput()->GetFieldData();
  return CountOf(verdict, "Valid") == 1 ? std::string() : MessageOf(verdict, "Problems");
}

/// `"key": value` of statistics.json as a number (0 when absent).
double StatisticOf(const std::string& dir, const std::string& key)
{
  std::ifstream in(dir + "/statistics.json");
  std::stringstream text;
  text << in.rdbuf();
  const std::string all = text.str();
  const auto at = all.find("\"" + key + "\": ");
  return at == std::string::npos ? 0.0 : std::atof(all.c_str() + at + key.size() + 4);
}

/// The options of `msynth synthesize` for entry @p e, output @p k.
SynthesizeOptions OptionsOf(const SampleEntry& e, const BatchOptions& b, int k)
{
  SynthesizeOptions o;
  o.Example = e.File;
  o.Seed = b.Seed + k;
  o.Threads = b.Threads;
  o.Subset = e.Subset;
  for (std::size_t a = 0; a < 3; ++a)
  {
    o.Size3[a] = static_cast<int>(e.Size[a]);
    o.Block[a] = static_cast<int>(e.Block[a]);
  }
  if (o.Block[0] > 0 || o.Block[1] > 0)
    for (std::size_t a = 0; a < 3; ++a)
      if (o.Block[a] == 0)
        o.Block[a] = o.Size3[a]; // an axis without a block size is whole, as the program does
  if (e.Periodic)
    o.Translate = "xy";
  if (e.Kind == SampleEntry::TiledModel)
  {
    o.Order = "scanline";
    return o;
  }
  // WaveFunctionCollapse's choice: the fewest possibilities first, weighted by frequency.
  o.Order = "entropy";
  o.Choice = "frequency";
  o.Pattern = e.N;
  o.Symmetry = e.Symmetry;
  o.NoPeriodicInput = !e.PeriodicInput;
  o.SampleGround = e.Ground;
  return o;
}

/// One output of entry @p e into @p dir; @p replaced gets "dir/" when it replaced an earlier one.
Outcome RunOne(const SampleEntry& e, const BatchOptions& b, int k, const std::string& dir,
  std::vector<std::string>& replaced)
{
  Outcome out;
  const auto start = std::chrono::steady_clock::now();
  try
  {
    CheckInputFile(e.File);
    const SynthesizeOptions o = OptionsOf(e, b, k);
    std::vector<std::string> earlier;
    IntoFolder(
      dir, [&](const std::string& stage) { return SynthesizeDiscrete(o, stage); }, &earlier);
    if (!earlier.empty())
      replaced.push_back(dir.substr(b.Out.size() + 1) + "/");
    out.FailedBlocks = static_cast<long long>(StatisticOf(dir, "BlocksFailed"));
    out.Problem = CheckOutput(e, dir);
    if (!out.Problem.empty())
      out.Result = "inconsistent";
  }
  catch (const std::exception& ex)
  {
    out.Result = "error";
    out.Problem = Printable(ex.what());
  }
  out.Seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return out;
}

std::string FolderName(std::size_t index, const SampleEntry& e)
{
  std::string name =
    std::to_string(index + 1) + "-" + e.Name + (e.Subset.empty() ? "" : "-" + e.Subset);
  for (char& c : name)
    if (c == '/' || c == '\\')
      c = '_';
  return name;
}

int RunBatch(const BatchOptions& b)
{
  CheckInputFile(b.List);
  const std::vector<SampleEntry> entries = ReadSampleList(b.List);
  if (entries.empty())
    throw std::runtime_error("'" + b.List + "': no overlapping, simpletiled or tiledmodel entries");
  std::ostringstream table;
  table << "entry  kind         name                      size          outputs  failed blocks  "
           "seconds  result\n";
  int bad = 0;
  std::vector<std::string> replaced; // the outputs of an earlier batch this one replaced
  for (std::size_t i = 0; i < entries.size(); ++i)
  {
    const SampleEntry& e = entries[i];
    const int shots = b.Screenshots >= 0 ? b.Screenshots : e.Screenshots;
    // Each entry's outputs are published as they finish: an interruption says which are there.
    SetInterruptDone((i == 0 ? "no entry of " + std::to_string(entries.size()) + " is complete"
                             : "entries 1-" + std::to_string(i) + " of " +
                           std::to_string(entries.size()) + " are complete in '" + b.Out + "'") +
      "; entry " + std::to_string(i + 1) + " (" + e.Name +
      ") keeps the outputs it finished, the rest were not written");
    std::cout << "[" << i + 1 << "/" << entries.size() << "] " << e.Element << " " << e.Name
              << (e.Subset.empty() ? "" : " (" + e.Subset + ")")
              << std::endl; // shown before it runs
    // The list's folder; IntoFolder makes the entry's and each output's own, and removes them
    // again when they stay empty (a failed entry leaves nothing behind).
    const std::string entryDir = b.Out + "/" + FolderName(i, e);
    msynth::MakeMissingFolders(b.Out); // --out output/batch in a fresh checkout
    if (::mkdir(b.Out.c_str(), 0777) != 0 && errno != EEXIST)
      throw std::runtime_error("'" + b.Out + "': cannot create folder: " + std::strerror(errno));
    int good = 0;
    long long failedBlocks = 0;
    double seconds = 0.0;
    std::string result = "ok";
    for (int k = 0; k < shots; ++k)
    {
      const Outcome out = RunOne(e, b, k, entryDir + "/" + std::to_string(k + 1), replaced);
      failedBlocks += out.FailedBlocks;
      seconds += out.Seconds;
      good += out.Result == "ok";
      if (out.Result != "ok")
      {
        std::cout << "  " << out.Result << ": " << out.Problem << "\n";
        result = out.Result + ": " + out.Problem;
      }
    }
    bad += good < shots;
    char line[512];
    std::snprintf(line, sizeof(line), "%-6zu %-12s %-25.25s %-13s %3d/%-4d %13lld %8.2f  ", i + 1,
      e.Element.c_str(), (e.Name + (e.Subset.empty() ? "" : " " + e.Subset)).c_str(),
      (std::to_string(e.Size[0]) + "x" + std::to_string(e.Size[1]) + "x" +
        std::to_string(e.Size[2]))
        .c_str(),
      good, shots, failedBlocks, seconds);
    // (a long message ends at a word, marked, not in the middle of one)
    const std::string::size_type cut =
      result.size() <= 200 ? std::string::npos : result.rfind(' ', 200);
    table << line << (cut == std::string::npos ? result : result.substr(0, cut) + " ...") << "\n";
  }
  std::cout << "\n" << table.str();
  const auto n = static_cast<long long>(entries.size());
  std::cout << (bad ? std::to_string(bad) + " of " + Counted(n, "entry", "entries") + " failed"
                   : n == 1 ? std::string("the 1 entry succeeded")
                            : "all " + Counted(n, "entry", "entries") + " succeeded") +
      "; outputs in " + b.Out + "\n";
  if (!replaced.empty())
    std::cerr << ReplacedNote(b.Out, replaced) << "\n";
  return bad ? 1 : 0;
}
} // namespace

CommandRunner AddBatch(CLI::App& app)
{
  auto o = std::make_shared<BatchOptions>();
  CLI::App* batch = app.add_subcommand("batch",
    "run every entry of a sample list (samples.xml) of the original model-synthesis program or "
    "of WaveFunctionCollapse: overlapping (image samples), simpletiled (tilesets) and tiledmodel "
    "(the original program's text models) entries with their attributes, files found beside the "
    "list as each program lays them out. Each output goes to DIR/ENTRY-NAME/K and is checked "
    "independently; a summary table follows. Exit 1 if any entry failed");
  batch->add_option("SAMPLES", o->List, "the sample list (.xml)")->required();
  AddOutOption(*batch, o->Out)
    ->description("output folder: each output appears whole in DIR/ENTRY-NAME/K as it is done, "
                  "so an interrupted batch keeps the entries it finished");
  AddSeedOption(*batch, o->Seed);
  batch->add_option("--threads", o->Threads, "threads for block synthesis (default: one per core)")
    ->check(CLI::Range(0, 1024));
  batch
    ->add_option("--screenshots", o->Screenshots,
      "outputs per entry, instead of each entry's screenshots attribute")
    ->check(CLI::Range(0, 1000));
  return [o]() { return RunBatch(*o); };
}

} // namespace cli
} // namespace msynth
