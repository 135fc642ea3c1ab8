// SPDX-License-Identifier: BSD-3-Clause
// The soak: seeded runs over every bundled example, for a given time, each output verified by
// the independent checkers (CheckConsistency recomputes Eq. 3.1 from the example;
// CheckContinuousModel re-analyses the output mesh). Options vary with the run: size, blocks,
// order, choice, threads. A run that fails (no model) is counted and allowed when reported as
// such; an exception other than msynth::Error, or an output a checker rejects, ends the soak
// with exit status 1.
//   msynthSoak SECONDS [FIRST_SEED]
#include "Continuous/ContinuousMesh.h"
#include "Continuous/ContinuousSynthesis.h"
#include "Core/Error.h"
#include "Core/Random.h"
#include "Discrete/AdjacencyRules.h"
#include "Discrete/ConsistencyCheck.h"
#include "Discrete/DiscreteSynthesis.h"
#include "Discrete/ExampleAnalysis.h"
#include "Formats/TextModel.h"
#include "Formats/Tileset.h"
#include "Formats/VoxModel.h"

#include <chrono>
#include <cstdlib>
#include <iostream>
#include <iterator>
#include <map>
#include <string>
#include <vector>

using namespace msynth;

namespace
{
struct Tally
{
  long Runs = 0, Models = 0, Failed = 0, Sites = 0;
};

std::string Data(const std::string& relative)
{
  return std::string(MSYNTH_DATA) + "/" + relative;
}

[[noreturn]] void Die(const std::string& what)
{
  std::cerr << "msynthSoak: " << what << "\n";
  std::exit(1);
}
} // namespace

int main(int argc, char* argv[])
{
  if (argc < 2)
    Die("usage: msynthSoak SECONDS [FIRST_SEED]");
  const double seconds = std::atof(argv[1]);
  std::uint64_t seed = argc > 2 ? std::strtoull(argv[2], nullptr, 10) : 1;

  // The discrete examples, as their readers give them.
  std::map<std::string, LabelGrid> grids;
  grids["Village.txt"] = ReadTextModelFile(Data("Examples/Village.txt"), 1 << 20).Grid;
  grids["Village.vox"] = ReadVoxModelFile(Data("Examples/Village.vox"), 1 << 20).Grid;
  LabelGrid board(4, 4, 1);
  for (std::int64_t y = 0; y < 4; ++y)
    for (std::int64_t x = 0; x < 4; ++x)
      board.Set(x, y, 0, (x + y) % 2);
  grids["Checkerboard"] = board;
  const Tileset lines = ReadTilesetFile(Data("Tilesets/Lines.xml"));
  const Tileset straight = ReadTilesetFile(Data("Tilesets/Lines.xml"), "straight");
  // The continuous examples.
  const char* const polyhedra[] = { "triangle2d.obj", "two-objects2d.obj", "concave2d.obj",
    "cube.obj", "box-building.obj", "l-prism.obj", "house.obj", "tetrahedron.obj",
    "pentagonal-prism.obj", "stairs.obj", "arch.obj", "cottage.obj" };
  std::vector<std::pair<PolyhedralExample, PolyhedralAnalysis>> continuous;
  for (const char* name : polyhedra)
  {
    PolyhedralExample e = ReadOBJExample(Data(std::string("Continuous/") + name));
    ValidateExample(e);
    PolyhedralAnalysis a = PolyhedralAnalysis::Analyze(e);
    continuous.emplace_back(std::move(e), std::move(a));
  }

  std::map<std::string, Tally> tally;
  const auto start = std::chrono::steady_clock::now();
  const auto elapsed = [&]
  { return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(); };
  while (elapsed() < seconds)
  {
    Random rng = Random::Derived(seed, 0x50a4);
    const auto pick = [&](int n)
    { return static_cast<int>(rng.Below(static_cast<std::uint64_t>(n))); };
    const int kind = pick(3);
    try
    {
      if (kind < 2)
      {
        // Discrete: an example grid or a tileset.
        SynthesisOptions o;
        const bool tiles = kind == 1;
        o.Size = { { 4 + pick(30), 4 + pick(30), tiles ? 1 : 1 + pick(6) } };
        if (pick(2))
          o.BlockSize = { { 3 + pick(12), 3 + pick(12), o.Size[2] } };
        o.Order = static_cast<SiteOrder>(pick(3));
        o.Choice = pick(2) ? LabelChoice::Frequency : LabelChoice::Uniform;
        o.Threads = 1 + pick(2);
        o.Seed = seed;
        std::string name;
        SynthesisResult r;
        if (tiles)
        {
          const Tileset& t = pick(2) ? lines : straight;
          name = &t == &lines ? "Lines.xml" : "Lines.xml (straight)";
          r = Synthesize(t.Rules(), o);
          if (r.Succeeded() && !CheckConsistency(t.Pairs, r.Model).Consistent)
            Die(name + " seed " + std::to_string(seed) + ": the check rejects the model");
        }
        else
        {
          auto it = grids.begin();
          std::advance(it, pick(static_cast<int>(grids.size())));
          name = it->first;
          const LabelGrid& example = it->second;
          if (example.Dimensions()[2] == 1)
            o.Size[2] = 1;
          o.Example = &example;
          if (pick(4) == 0)
            o.Choice = LabelChoice::Resemblance;
          r = Synthesize(AdjacencyRules::FromExample(ExampleAnalysis::FromExample(example)), o);
          if (r.Succeeded() && !CheckConsistency(example, r.Model).Consistent)
            Die(name + " seed " + std::to_string(seed) + ": the check rejects the model");
        }
        Tally& t = tally[name];
        ++t.Runs;
        t.Models += r.Succeeded();
        t.Failed += r.Statistics.BlocksFailed > 0;
        t.Sites += o.Size[0] * o.Size[1] * o.Size[2];
      }
      else
      {
        const int which = pick(static_cast<int>(continuous.size()));
        const auto& [example, analysis] = continuous[static_cast<std::size_t>(which)];
        const Point3 size{ { 3.0 + pick(6), 3.0 + pick(6), example.Planar ? 0.0 : 2.0 + pick(4) } };
        const ArrangementParameters p =
          DefaultArrangementParameters(example, analysis, size, 0, {});
        const PlaneArrangement arrangement(analysis.Families(), p);
        ContinuousSynthesisOptions options;
        options.Seed = seed;
        options.BlockSize = pick(2) ? 0 : 2 + pick(4);
        const ContinuousSynthesisResult r = SynthesizeContinuous(analysis, arrangement, options);
        const std::string name = polyhedra[which];
        Tally& t = tally[name];
        ++t.Runs;
        t.Sites += arrangement.NumberOfVertices();
        if (r.Succeeded())
        {
          ++t.Models;
          const std::string labels = CheckArrangementLabels(analysis, arrangement, r.Labels);
          if (!labels.empty())
            Die(name + " seed " + std::to_string(seed) + ": " + labels);
          const ContinuousMesh mesh = ExtractMesh(analysis, arrangement, r.Labels);
          const ContinuousModelReport report =
            CheckContinuousModel(analysis, mesh, example.TypeNames);
          if (!report.Valid)
            Die(name + " seed " + std::to_string(seed) +
              ": the check rejects the model: " + report.Problem);
        }
        t.Failed += r.Statistics.BlocksFailed > 0;
      }
    }
    catch (const Error& e)
    {
      // A refused parameter set (too large an arrangement, no trivial start) is an answer.
      std::string why = e.what();
      const std::size_t colon = why.rfind(": ");
      why = colon == std::string::npos ? why : why.substr(colon + 2);
      ++tally["(refused) " + why.substr(0, 60)].Runs;
    }
    ++seed;
  }
  long runs = 0;
  std::cout << "example                     runs  models  runs-with-failed-blocks\n";
  for (const auto& [name, t] : tally)
  {
    std::cout << name << std::string(name.size() < 26 ? 26 - name.size() : 1, ' ') << t.Runs << "  "
              << t.Models << "  " << t.Failed << "\n";
    runs += t.Runs;
  }
  std::cout << "msynthSoak: " << runs << " runs in " << elapsed() << " s, every model checked\n";
  return 0;
}
