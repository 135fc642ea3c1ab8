// SPDX-License-Identifier: BSD-3-Clause
// `msynth pattern EXEMPLAR... --size NX NY [NZ]`: factor-graph pattern synthesis (Yeh et al.
// 2012) through vtkMSPatternSynthesis, writing DIR/labels.vti (the last sample; with --samples
// also labels_0001.vti ...), DIR/picture.png with --tileset, and DIR/statistics.json with the KL
// divergence per factor shape and the log probability of each sample. Every sample is checked
// against the exemplars' pairs and measured by vtkMSCheckModel before anything is written.
// `msynth quality EXEMPLAR... MODEL --factors 4H,4V`: the KL divergence of any model, by the same
// filter.
#include "Commands.h"
#include "Common.h"
#include "Examples.h"

#include "vtkDataArray.h"
#include "vtkFieldData.h"
#include "vtkImageData.h"
#include "vtkMSCheckModel.h"
#include "vtkMSLabelArrays.h"
#include "vtkMSLabelGridReader.h"
#include "vtkMSPatternSynthesis.h"
#include "vtkMSTileImage.h"
#include "vtkStringArray.h"
#include "vtkXMLImageDataWriter.h"

#include "Discrete/SeamMeasure.h"
#include "Patterns/FactorGraph.h"

#include <array>
#include <cstdio>
#include <iostream>
#include <memory>
#include <optional>
#include <sstream>

namespace msynth
{
namespace cli
{
namespace
{
const std::vector<std::string> Methods{ "blockss", "mh", "csp" };
const std::vector<std::string> Starts{ "random", "solver" };

struct PatternCommandOptions
{
  std::vector<std::string> Exemplars;
  std::vector<int> Size;
  std::string Factors = "2H,2V";
  std::string Measure;
  double Epsilon = 0.1;
  std::string Blocks = "B6";
  std::string Zones;
  std::vector<std::string> ZoneTiles;
  std::vector<std::string> ZoneExemplars;
  std::string Fixed;
  std::string Mirror;
  std::vector<std::string> Swaps;
  std::string Tileset;
  std::string Connected;
  std::vector<std::string> Path;
  int Samples = 1;
  int BurnIn = 5;
  std::string Method = "blockss";
  std::string Start = "random";
  double Temperature = 0.25;
  double PWalk = 0.6;
  double PFlip = 0.1;
  std::int64_t MovesPerSample = -1;
  std::int64_t MaxMoves = -1;
  std::int64_t Seed = 0;
  std::string Out = "msynth-output";
};

vtkSmartPointer<vtkMSLabelGridReader> OpenGrid(const std::string& path, const char* array = "Label")
{
  auto reader = vtkSmartPointer<vtkMSLabelGridReader>::New();
  reader->SetFileName(path.c_str());
  reader->SetLabelArrayName(array);
  reader->GenerateGeometryOff();
  Run(reader);
  return reader;
}

/// A zoning: its `Zone` array, else its labels.
vtkSmartPointer<vtkMSLabelGridReader> OpenZones(const std::string& path)
{
  try
  {
    return OpenGrid(path, "Zone");
  }
  catch (const std::exception&)
  {
    return OpenGrid(path);
  }
}

void Configure(vtkMSPatternSynthesis* s, const PatternCommandOptions& o)
{
  s->SetOutputSize(o.Size[0], o.Size[1], o.Size.size() > 2 ? o.Size[2] : 1);
  s->SetSoftFactors(msynth::SoftShapes(o.Factors).c_str());
  s->SetEpsilon(o.Epsilon);
  if (o.Blocks.size() == 2 && (o.Blocks[0] == 'B' || o.Blocks[0] == 'b') &&
    std::isdigit(static_cast<unsigned char>(o.Blocks[1])))
    s->SetBlockScheme(o.Blocks[1] - '0');
  else
    s->SetBlockShapes(o.Blocks.c_str());
  s->SetZoneTiles(Joined(o.ZoneTiles, ";").c_str());
  s->SetZoneExemplars(Joined(o.ZoneExemplars, ";").c_str());
  s->SetMirror(o.Mirror.find('x') != std::string::npos, o.Mirror.find('y') != std::string::npos,
    o.Mirror.find('z') != std::string::npos);
  s->SetMirrorSwaps(Joined(o.Swaps, ",").c_str());
  s->SetConnected(o.Connected.c_str());
  s->SetPath(Joined(o.Path, ";").c_str());
  s->SetConnectedTilesetFile(o.Tileset.c_str());
  s->SetSamples(o.Samples);
  s->SetBurnIn(o.BurnIn);
  s->SetMethod(IndexIn(o.Method, Methods));
  s->SetStart(IndexIn(o.Start, Starts));
  s->SetTemperature(o.Temperature);
  s->SetWalkProbability(o.PWalk);
  s->SetFlipProbability(o.PFlip);
  s->SetMovesPerSample(static_cast<vtkIdType>(o.MovesPerSample));
  s->SetMaxMoves(static_cast<vtkIdType>(o.MaxMoves));
  s->SetSeed(static_cast<vtkIdType>(o.Seed));
}

double FieldValue(vtkFieldData* fd, const std::string& name)
{
  vtkDataArray* a = fd->GetArray(name.c_str());
  return a && a->GetNumberOfTuples() > 0 ? a->GetTuple1(0) : 0.0;
}

/// Connects the command's inputs to @p synthesis and @p check: each EXEMPLAR (read, kept in
/// @p readers), or at most one tileset (its path in @p tileset: its rules are hard pairs too),
/// the zoning and the fixed sites. @throw UsageError for a second tileset; reading errors.
void ConnectInputs(vtkMSPatternSynthesis* synthesis, vtkMSCheckModel* check,
  const PatternCommandOptions& o, std::vector<vtkSmartPointer<vtkMSLabelGridReader>>& readers,
  std::string& tileset)
{
  for (const auto& path : o.Exemplars)
  {
    if (IsTileset(path))
    {
      if (!tileset.empty())
        throw UsageError{ "give at most one tileset" };
      tileset = path;
      synthesis->SetTilesetFile(path.c_str());
      check->SetTilesetFile(path.c_str());
      continue;
    }
    readers.push_back(OpenGrid(path));
    synthesis->AddInputConnection(0, readers.back()->GetOutputPort());
    check->AddExampleConnection(readers.back()->GetOutputPort());
  }
  if (!o.Zones.empty())
  {
    readers.push_back(OpenZones(o.Zones));
    synthesis->SetZonesConnection(readers.back()->GetOutputPort());
  }
  if (!o.Fixed.empty())
  {
    readers.push_back(OpenGrid(o.Fixed));
    int d[3];
    readers.back()->GetOutput()->GetDimensions(d);
    const int n[3] = { o.Size[0], o.Size[1], o.Size.size() > 2 ? o.Size[2] : 1 };
    if (d[0] != n[0] || d[1] != n[1] || d[2] != n[2])
    {
      std::string size;
      for (int v : o.Size)
        size += " " + std::to_string(v);
      throw std::runtime_error("--fixed '" + o.Fixed + "': the grid has " + Triple(d) +
        " sites, the output " + Triple(n) + ": expected a grid of the output's size (--size" +
        size + ")");
    }
    synthesis->SetFixedConnection(readers.back()->GetOutputPort());
  }
}

/// What statistics.json says of the samples as a whole.
struct SampleMeans
{
  double LogProbability = 0.0; ///< mean over the samples
  std::vector<double> KL;      ///< mean per measured shape
  double FirstValidSeconds = 0.0;
  double Seconds = 0.0;
};

/// DIR/statistics.json: the run's options, the means, the run's counts from the field data
/// @p fd of the last sample, and @p samplesJson (one object per sample).
void WritePatternStatistics(const std::string& dir, const PatternCommandOptions& o,
  vtkFieldData* fd, const std::vector<msynth::Stencil>& measured, const SampleMeans& means,
  const std::string& samplesJson)
{
  StatisticsJson json;
  std::string exemplars;
  for (std::size_t i = 0; i < o.Exemplars.size(); ++i)
    exemplars += (i ? ", " : "") + JsonString(o.Exemplars[i]);
  json.Raw("exemplars", "[" + exemplars + "]")
    .Counts("size", { o.Size[0], o.Size[1], o.Size.size() > 2 ? o.Size[2] : 1 })
    .Text("method", o.Method)
    .Text("factors", o.Factors)
    .Number("epsilon", o.Epsilon)
    .Count("seed", o.Seed)
    .Count("burnIn", o.BurnIn)
    .Number("LogProbability", means.LogProbability);
  for (std::size_t i = 0; i < measured.size(); ++i)
    json.Number("KL_" + measured[i].Name, means.KL[i]);
  for (const char* name : { "Moves", "WalkMoves", "AnnealingMoves", "AcceptedAnnealingMoves",
         "FirstValidMoves", "HardFactors", "SoftFactors", "Tiles", "ReplacementBlocks" })
    json.Count(name, CountOf(fd, name));
  json.Connected(fd)
    .Number("FirstValidSeconds", means.FirstValidSeconds)
    .Number("Seconds", means.Seconds)
    .Raw("samples", "[\n" + samplesJson + "\n  ]")
    .Write(dir + "/statistics.json");
}

int Pattern(const PatternCommandOptions& o, const std::string& dir)
{
  vtkNew<vtkMSPatternSynthesis> synthesis;
  // Every sample checked against the exemplars' pairs (and the tileset's rules), independently
  // of the sampler, and measured: the KL divergence per shape.
  vtkNew<vtkMSCheckModel> check;
  std::vector<vtkSmartPointer<vtkMSLabelGridReader>> readers;
  std::string tileset; // an EXEMPLAR that is a tileset: its rules are hard pairs too
  ConnectInputs(synthesis, check, o, readers, tileset);
  Configure(synthesis, o);
  check->SetInputConnection(synthesis->GetOutputPort());
  check->SetShapes(o.Measure.c_str()); // "": the soft shapes the synthesis records
  check->SetMaximumReported(1);
  // The network counted again by the check's own union-find (Discrete/LabelChecks.h).
  check->SetConnected(o.Connected.c_str());
  check->SetPath(Joined(o.Path, ";").c_str());
  check->SetConnectedTilesetFile((o.Tileset.empty() ? tileset : o.Tileset).c_str());
  {
    ProgressBar bar(synthesis);
    synthesis->UpdateInformation();
    RunSynthesis(synthesis); // all samples at once; the steps below come from the filter's cache
  }
  const std::vector<msynth::Stencil> measured = msynth::ParseStencils(o.Measure.empty()
      ? MessageOf(synthesis->GetOutput()->GetFieldData(), "SoftShapes")
      : o.Measure);
  std::ostringstream samples;
  std::vector<double> kl(measured.size(), 0.0);
  double logp = 0.0, seconds = 0.0, firstValid = 0.0;
  vtkSmartPointer<vtkImageData> last;
  for (int k = 0; k < o.Samples; ++k)
  {
    check->UpdateTimeStep(k);
    Run(check);
    vtkFieldData* verdict = check->GetOutput()->GetFieldData();
    if (CountOf(verdict, "Violations") != 0)
    {
      auto* lines = vtkStringArray::SafeDownCast(verdict->GetAbstractArray("Problems"));
      throw std::runtime_error("sample " + std::to_string(k + 1) +
        " breaks the exemplars' pairs: " + (lines ? lines->GetValue(0) : std::string()));
    }
    if (auto* lines = vtkStringArray::SafeDownCast(verdict->GetAbstractArray("Findings")))
      std::cout << lines->GetValue(0) << "\n"; // the network, as counted by the check
    if (CountOf(verdict, "Valid") != 1)
      throw std::runtime_error("sample " + std::to_string(k + 1) + " has more components of " +
        o.Connected + " than asked" + (o.Path.empty() ? "" : ", or does not join the path"));
    auto image = vtkSmartPointer<vtkImageData>::New();
    image->DeepCopy(synthesis->GetOutput());
    vtkFieldData* fd = image->GetFieldData();
    samples << (k ? ",\n" : "") << "    {\"sample\": " << k + 1
            << ", \"LogProbability\": " << JsonNumber(FieldValue(fd, "LogProbability"));
    for (std::size_t i = 0; i < measured.size(); ++i)
    {
      const double v = FieldValue(verdict, "KL_" + measured[i].Name);
      kl[i] += v / o.Samples;
      samples << ", \"KL_" << measured[i].Name << "\": " << JsonNumber(v);
    }
    logp += FieldValue(fd, "LogProbability") / o.Samples;
    samples << ", \"Moves\": " << CountOf(fd, "SampleMoves")
            << ", \"Seconds\": " << JsonNumber(FieldValue(fd, "SampleSeconds")) << "}";
    seconds = FieldValue(fd, "Seconds");
    firstValid = FieldValue(fd, "FirstValidSeconds");
    if (o.Samples > 1)
    {
      char name[32];
      std::snprintf(name, sizeof(name), "/labels_%04d.vti", k + 1);
      WriteXML<vtkXMLImageDataWriter>(dir + name, image.GetPointer());
    }
    last = image;
  }
  WriteXML<vtkXMLImageDataWriter>(dir + "/labels.vti", last.GetPointer());
  std::string picture;
  const std::string& drawing = o.Tileset.empty() ? tileset : o.Tileset;
  if (!drawing.empty())
  {
    vtkNew<vtkMSTileImage> tiles;
    tiles->SetTilesetFile(drawing.c_str());
    tiles->SetInputData(last);
    Run(tiles);
    picture = dir + "/picture.png";
    WritePicturePng(tiles->GetOutput(), picture);
  }
  vtkFieldData* fd = last->GetFieldData();
  WritePatternStatistics(dir, o, fd, measured, { logp, kl, firstValid, seconds }, samples.str());
  std::cout << Counted(o.Samples, "sample") << " of " << o.Size[0] << " x " << o.Size[1]
            << (o.Size.size() > 2 ? " x " + std::to_string(o.Size[2]) : std::string()) << " by "
            << (o.Method == "blockss" ? std::string("BLOCKSS") : o.Method) << " in "
            << JsonNumber(seconds) << " s (first valid after " << JsonNumber(firstValid)
            << " s); every pair occurs in an exemplar"
            << (tileset.empty() ? "" : " or the tileset's rules") << "\n";
  for (std::size_t i = 0; i < measured.size(); ++i)
    std::cout << "KL " << measured[i].Name << ": " << JsonNumber(kl[i]) << "\n";
  std::cout << "wrote " << dir << "/labels.vti" << (o.Samples > 1 ? ", labels_0001.vti ..." : "")
            << (picture.empty() ? "" : ", " + picture) << ", " << dir << "/statistics.json\n";
  return 0;
}

struct QualityOptions
{
  std::vector<std::string> Files;
  std::string Factors = "4H,4V";
  double Epsilon = 0.1;
  std::vector<int> Seams;                 ///< the block size MODEL was synthesized in (--seams)
  std::vector<int> Overlap{ -1, -1, -1 }; ///< its blocks' overlap
  std::string Whole;                      ///< a whole run of the same size to compare with
  int Window = 2;
};

/// The labels of the label grid file @p path.
msynth::LabelGrid GridOf(const std::string& path)
{
  auto reader = OpenGrid(path);
  vtkImageData* image = reader->GetOutput();
  return vtkMSLabelArrays::ToLabelGrid(image, vtkMSLabelArrays::FindLabelArray(image, nullptr));
}

/// `msynth quality MODEL --seams BX BY BZ [--whole WHOLE]`: SeamMeasure.h's figures.
int QualitySeams(const QualityOptions& o)
{
  const std::string& path = o.Files.back();
  const msynth::LabelGrid model = GridOf(path);
  std::array<std::int64_t, 3> block{}, overlap{};
  for (std::size_t a = 0; a < 3; ++a)
  {
    block[a] = o.Seams[a];
    overlap[a] = o.Overlap[a];
  }
  const auto planes = msynth::BlockBorderPlanes(model.Dimensions(), block, overlap);
  std::optional<msynth::LabelGrid> whole;
  if (!o.Whole.empty())
    whole = GridOf(o.Whole);
  const msynth::SeamMeasure s =
    msynth::MeasureSeams(model, planes, o.Window, whole ? &*whole : nullptr);
  std::cout << path << ": " << model.Size(0) << " x " << model.Size(1) << " x " << model.Size(2)
            << " in " << o.Seams[0] << " x " << o.Seams[1] << " x " << o.Seams[2] << " blocks\n";
  for (std::size_t a = 0; a < 3; ++a)
  {
    std::cout << "block borders along " << static_cast<char>('x' + a) << ":";
    for (std::int64_t p : planes[a])
      std::cout << " " << p;
    std::cout << (planes[a].empty() ? " none\n" : "\n");
  }
  std::cout << "seam windows: " << s.Window << " sites a side, " << s.BorderWindows
            << " touching a border, " << s.InteriorWindows << " inside\n"
            << "seam distance (border windows against interior ones, total variation): "
            << JsonNumber(s.BorderVsInterior) << "\n"
            << "seam top share (most frequent window, border / interior): "
            << JsonNumber(s.BorderTop) << " / " << JsonNumber(s.InteriorTop) << "\n";
  if (s.HasWhole)
    std::cout << "whole run at the same places (its own variation): "
              << JsonNumber(s.WholeBorderVsInterior) << ", top share at the borders "
              << JsonNumber(s.WholeBorderTop) << "\n"
              << "against all of the whole run's windows: border " << JsonNumber(s.BorderVsWhole)
              << ", interior " << JsonNumber(s.InteriorVsWhole) << "\n"
              << "seam excess (seam distance minus the whole run's): " << JsonNumber(s.Excess())
              << "\n";
  return 0;
}

/// EXEMPLAR... MODEL: readers → vtkMSCheckModel (the pairs, KL per shape, log probability).
int Quality(const QualityOptions& o)
{
  if (!o.Seams.empty())
    return QualitySeams(o);
  std::vector<vtkSmartPointer<vtkMSLabelGridReader>> readers;
  vtkNew<vtkMSCheckModel> check;
  for (std::size_t i = 0; i + 1 < o.Files.size(); ++i)
  {
    readers.push_back(OpenGrid(o.Files[i]));
    check->AddExampleConnection(readers.back()->GetOutputPort());
  }
  const std::string& path = o.Files.back();
  auto model = OpenGrid(path);
  check->SetInputConnection(model->GetOutputPort());
  check->SetShapes(o.Factors.c_str());
  check->SetEpsilon(o.Epsilon);
  check->SetMaximumReported(5);
  Run(check);
  vtkFieldData* fd = check->GetOutput()->GetFieldData();
  int dims[3];
  model->GetOutput()->GetDimensions(dims);
  std::cout << path << ": " << dims[0] << " x " << dims[1] << " x " << dims[2] << "\n";
  const std::vector<msynth::Stencil> shapes = msynth::ParseStencils(o.Factors);
  double mean = 0.0;
  for (const msynth::Stencil& s : shapes)
  {
    const double kl = FieldValue(fd, "KL_" + s.Name);
    mean += kl / static_cast<double>(shapes.size());
    std::cout << "KL " << s.Name << ": " << JsonNumber(kl) << "\n";
  }
  if (shapes.size() > 1)
    std::cout << "KL mean: " << JsonNumber(mean) << "\n";
  std::cout << "log probability: " << JsonNumber(FieldValue(fd, "PatternLogProbability")) << "\n";
  if (CountOf(fd, "Valid") == 1)
  {
    std::cout << "every pair of neighbours occurs in an exemplar\n";
    return 0;
  }
  if (auto* lines = vtkStringArray::SafeDownCast(fd->GetAbstractArray("Problems")))
    for (vtkIdType i = 0; i < lines->GetNumberOfValues(); ++i)
      std::cout << "seam: " << lines->GetValue(i) << "\n";
  return 1;
}
} // namespace

CommandRunner AddPattern(CLI::App& app)
{
  auto o = std::make_shared<PatternCommandOptions>();
  CLI::App* p = app.add_subcommand("pattern",
    "pattern synthesis from EXEMPLAR label grids: samples whose small neighbourhoods occur about "
    "as often as in the exemplars (a factor graph, sampled block by block); writes "
    "DIR/labels.vti (the last sample; with --samples also labels_0001.vti ...), DIR/picture.png "
    "with --tileset, and DIR/statistics.json (KL per factor shape, log probability)");
  p->add_option("EXEMPLAR", o->Exemplars,
     "exemplar label grids (.vti, .txt, .vox) of one tile set; a tileset (.xml) among them adds "
     "its neighbor rules as hard pairs and draws DIR/picture.png")
    ->required();
  p->add_option("--size", o->Size, "output size NX NY [NZ] in tiles")
    ->expected(2, 3)
    ->required()
    ->check(CLI::Range(1, 1000000000));
  p->add_option("--factors", o->Factors,
    "factor shapes: 2H, 2V (and 2D) are the hard pairs, always on; others are soft: NH, NV, ND, "
    "AxB, AxBxC, or offsets like 0:0+1:0+1:1");
  p->add_option("--measure", o->Measure,
    "shapes whose KL divergence statistics.json reports (default: the soft factors)");
  p->add_option("--epsilon", o->Epsilon, "a soft factor is 1 + E where an exemplar shows it")
    ->check(NonNegativeReal());
  p->add_option(
    "--blocks", o->Blocks, "replacement blocks: scheme B1 ... B6, or shapes as --factors");
  p->add_option("--zones", o->Zones, "zone ids per site (a label grid, stretched over the output)");
  p->add_option("--zone-tiles", o->ZoneTiles, "zone Z allows only labels L1, L2, ... (Z:L1,L2)")
    ->allow_extra_args(false);
  p->add_option("--zone-exemplars", o->ZoneExemplars,
     "zone Z takes its soft factors from exemplars E1, E2, ... numbered from 1 (Z:E1,E2)")
    ->allow_extra_args(false);
  p->add_option("--fixed", o->Fixed,
    "a label grid of the output's size: sites holding an exemplar label are fixed to it");
  p->add_option("--mirror", o->Mirror, "synthesize half and mirror it along AXES (x, y, z)")
    ->check(CLI::IsMember({ "x", "y", "z", "xy", "xz", "yz", "xyz" }));
  p->add_option("--swap", o->Swaps, "labels A and B are each other's mirror images (A:B)")
    ->allow_extra_args(false);
  p->add_option("--tileset", o->Tileset,
    "the tileset (.xml) whose images draw DIR/picture.png (and whose tile names and connecting "
    "sides --connected uses)");
  p->add_option("--connected", o->Connected,
    "the sites holding any of LABELS (values, or tile names of the tileset; commas between) form "
    "at most N components (LABELS[:N], N 1 when left out), joined through the tiles' connects "
    "sides: each sample's surplus components are joined or removed by re-solving boxes");
  p->add_option("--path", o->Path,
    "with --connected: one component joins these sites (x,y[,z]) and every site of these "
    "labels (values or tile names), in every sample");
  p->add_option("--samples", o->Samples, "samples to keep after the burn-in")
    ->check(CLI::Range(1, 100000));
  p->add_option("--burn-in", o->BurnIn, "samples discarded first")->check(CLI::Range(0, 100000));
  p->add_option("--method", o->Method,
     "blockss, mh (single-site Metropolis-Hastings) or csp "
     "(the discrete solver on the hard pairs)")
    ->check(CLI::IsMember(Methods));
  p->add_option("--start", o->Start,
     "where BLOCKSS starts: random tiles (the paper) or a pattern "
     "of the constraint solver")
    ->check(CLI::IsMember(Starts));
  p->add_option("--temperature", o->Temperature, "T of the annealing moves")
    ->check(CLI::Range(1e-6, 1e6));
  p->add_option("--p-walk", o->PWalk, "probability of a WalkSAT move")->check(CLI::Range(0.0, 1.0));
  p->add_option("--p-flip", o->PFlip, "probability that a WalkSAT move is a random block")
    ->check(CLI::Range(0.0, 1.0));
  p->add_option("--moves-per-sample", o->MovesPerSample,
     "moves before a sample may end (-1: one per site; 0: none, a sample ends as soon as "
     "every factor of its slice holds)")
    ->check(CLI::Range(std::int64_t(-1), std::int64_t(1) << 50));
  p->add_option("--max-moves", o->MaxMoves,
     "moves allowed for a sample before the run fails "
     "(-1: 20,000 per site, at least 10^7)")
    ->check(CLI::Range(std::int64_t(-1), std::int64_t(1) << 50));
  AddSeedOption(*p, o->Seed);
  AddOutOption(*p, o->Out);
  return [o]()
  {
    for (const auto& path : o->Exemplars)
      CheckInputFile(path);
    for (const std::string* path : { &o->Zones, &o->Fixed, &o->Tileset })
      if (!path->empty())
        CheckInputFile(*path);
    if (!o->Path.empty() && o->Connected.empty())
      throw UsageError{ "--path needs --connected LABELS: the labels that carry the path" };
    try
    {
      msynth::SoftShapes(o->Factors);
      msynth::ParseStencils(o->Measure);
    }
    catch (const std::exception& e)
    {
      throw UsageError{ e.what() };
    }
    return IntoFolder(o->Out, [&](const std::string& dir) { return Pattern(*o, dir); });
  };
}

CommandRunner AddQuality(CLI::App& app)
{
  auto o = std::make_shared<QualityOptions>();
  CLI::App* q = app.add_subcommand("quality",
    "how much MODEL looks like the EXEMPLARs: the KL divergence of its "
    "configurations of each factor shape, its log probability, and whether every pair of "
    "neighbours occurs in an exemplar (exit 1 if not)");
  q->add_option("FILES", o->Files,
     "EXEMPLAR... MODEL: label grids (.vti, .txt, .vox); with --seams MODEL alone")
    ->required()
    ->expected(1, -1);
  q->add_option("--factors", o->Factors, "factor shapes to measure (as msynth pattern --factors)");
  q->add_option("--epsilon", o->Epsilon, "epsilon of the log probability")
    ->check(NonNegativeReal());
  q->add_option("--seams", o->Seams,
     "BX BY BZ: MODEL was synthesized in blocks of this size; measure whether their borders "
     "show: the frequencies of the windows touching a block border against the interior's "
     "(total variation distance) and, with --whole, the whole run's at the same places")
    ->expected(3)
    ->check(CLI::Range(0, 1000000000));
  q->add_option("--overlap", o->Overlap, "with --seams: the blocks' overlap (default -1: half)")
    ->expected(3)
    ->check(CLI::Range(-1, 1000000000));
  q->add_option("--whole", o->Whole, "with --seams: a whole run of MODEL's size to compare with");
  q->add_option("--window", o->Window, "with --seams: window edge in sites (default 2)")
    ->check(CLI::Range(1, 64));
  return [o]()
  {
    if (o->Files.size() > 1)
      CheckOrder(
        "quality EXEMPLAR... MODEL", { o->Files.begin(), o->Files.end() - 1 }, o->Files.back());
    for (const auto& path : o->Files)
      CheckInputFile(path);
    if (!o->Whole.empty())
      CheckInputFile(o->Whole);
    if (o->Seams.empty() && o->Files.size() < 2)
      throw UsageError{ "quality needs EXEMPLAR... MODEL (or MODEL --seams BX BY BZ)" };
    if (!o->Seams.empty() && o->Files.size() != 1)
      throw UsageError{ "quality --seams measures one MODEL, not " +
        std::to_string(o->Files.size()) + " files (a whole run goes with --whole)" };
    try
    {
      msynth::ParseStencils(o->Factors);
    }
    catch (const std::exception& e)
    {
      throw UsageError{ e.what() };
    }
    return Quality(*o);
  };
}

} // namespace cli
} // namespace msynth
