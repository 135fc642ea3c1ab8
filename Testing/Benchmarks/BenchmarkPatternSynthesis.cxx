// SPDX-License-Identifier: BSD-3-Clause
// Factor-graph pattern synthesis (Yeh et al. 2012). BM_PatternCity: an N × N city from the
// bundled city exemplars (Data/Patterns, drawn here as text art) with 2H/2V factors and a
// crossroad fixed every 20 tiles, to the first pattern satisfying the hard factors (§8.2,
// Fig. 13a; the paper: about 5 minutes at 170 × 170). BM_PatternFacadeMH vs BM_PatternFacade:
// single-site Metropolis-Hastings against BLOCKSS on an N × N rectangular facade (§8.2, Fig. 11).
#include "Patterns/PatternSynthesis.h"

#include <benchmark/benchmark.h>

#include <string>
#include <vector>

namespace
{
msynth::LabelGrid Art(const std::vector<std::string>& rows, const std::string& chars)
{
  const auto ny = static_cast<std::int64_t>(rows.size());
  const auto nx = static_cast<std::int64_t>(rows[0].size());
  msynth::LabelGrid g(nx, ny, 1);
  for (std::int64_t y = 0; y < ny; ++y)
    for (std::int64_t x = 0; x < nx; ++x)
      g.Set(x, y, 0,
        static_cast<msynth::Label>(
          chars.find(rows[static_cast<std::size_t>(ny - 1 - y)][static_cast<std::size_t>(x)])));
  return g;
}

// The tiles of Data/Patterns/City.xml and Facade.xml, in label order.
const std::string CityTiles = ".-|+v^abce><1234hBt";
const std::string FacadeTiles = ".-#TW_Dd=~";

std::vector<msynth::LabelGrid> City()
{
  return { Art({ "h.t.|.h..4.t.h", ".h..|.t..|.h..", "----+----e...t", "..h.|..h...h..",
                 "t...|.t...t...", ".h..c---v--2.h", "..t.....|..t..", "---b.h..|.h...",
                 ".h.|..t.>-----", "t..|.h..|.t.h.", "...c---2|..4..", ".h.t.h..|..|.t",
                 "--------^--^--", "h.t.h.t.h..t.h" },
             CityTiles),
    Art({ "BBB|BBB|BBB|", "BBB|BBB|BBB|", "BBB|B.B|BBB|", "---+---+---+", "BBB|BBB|BBB|",
          "B.B|BBB|.t.|", "BBB|BBB|BBB|", "---+---+---+", "BBB|BBB|BBB|", "BBB|.B.|BBB|",
          "BBB|BBB|BBB|", "---+---+---+" },
      CityTiles) };
}

std::vector<msynth::LabelGrid> Facades()
{
  return { Art({ "............", "............", "------------", "#T##T##T##T#", "#W##W##W##W#",
                 "#W##W##W##W#", "#_##_##_##_#", "~~~~~~~~~~~~", "#T##D##T##T#", "#W##d##W##W#",
                 "#W##d##W##W#", "#_##d##_##_#", "============" },
             FacadeTiles),
    Art({ "...............", "-------........", "#T##T##........", "#W##W##........",
          "#W##W##........", "#_##_##........", "~~~~~~~--------", "#T##T##T##T##T#",
          "#W##W##W##W##W#", "#W##W##W##W##W#", "#_##_##_##_##_#", "~~~~~~~~~~~~~~~",
          "#T##D##T##T##D#", "#W##d##W##W##d#", "#W##d##W##W##d#", "#_##d##_##_##d#",
          "===============" },
      FacadeTiles) };
}

void Report(benchmark::State& state, std::int64_t sites, double moves, double failures)
{
  const double n = static_cast<double>(state.iterations());
  state.counters["moves"] = moves / n;
  state.counters["failed_runs"] = failures / n;
  state.SetItemsProcessed(static_cast<std::int64_t>(n) * sites);
}
} // namespace

static void BM_PatternCity(benchmark::State& state)
{
  const auto exemplars = City();
  const std::int64_t n = state.range(0);
  msynth::PatternOptions o;
  o.Size = { { n, n, 1 } };
  o.BurnIn = 0;
  o.Fixed.assign(static_cast<std::size_t>(n * n), -1);
  for (std::int64_t y = 10; y < n; y += 20)
    for (std::int64_t x = 10; x < n; x += 20)
      o.Fixed[static_cast<std::size_t>(x + n * y)] = 3; // a crossroad
  double moves = 0;
  for (auto _ : state)
  {
    o.Seed = static_cast<std::uint64_t>(state.iterations());
    const auto r = msynth::SynthesizePattern(exemplars, o);
    moves += static_cast<double>(r.FirstValidMoves);
    benchmark::DoNotOptimize(r.Samples.data());
  }
  Report(state, n * n, moves, 0);
}
BENCHMARK(BM_PatternCity)->Arg(40)->Arg(80)->Arg(120)->Arg(170)->Unit(benchmark::kMillisecond);

/// One facade of range(0)² tiles by @p method (2H/2V only), at most range(1) moves.
static void FacadeRun(benchmark::State& state, msynth::PatternMethod method)
{
  const auto exemplars = Facades();
  const std::int64_t n = state.range(0);
  msynth::PatternOptions o;
  o.Size = { { n, n, 1 } };
  o.BurnIn = 0;
  o.Method = method;
  o.MaxMoves = state.range(1);
  double moves = 0, failures = 0;
  for (auto _ : state)
  {
    o.Seed = static_cast<std::uint64_t>(state.iterations());
    try
    {
      const auto r = msynth::SynthesizePattern(exemplars, o);
      moves += static_cast<double>(r.FirstValidMoves);
    }
    catch (const std::exception&)
    {
      moves += static_cast<double>(o.MaxMoves);
      failures += 1;
    }
  }
  Report(state, n * n, moves, failures);
}
static void BM_PatternFacade(benchmark::State& state)
{
  FacadeRun(state, msynth::PatternMethod::BlockSS);
}
static void BM_PatternFacadeMH(benchmark::State& state)
{
  FacadeRun(state, msynth::PatternMethod::MetropolisHastings);
}
BENCHMARK(BM_PatternFacade)->Args({ 10, -1 })->Args({ 30, -1 })->Unit(benchmark::kMillisecond);
BENCHMARK(BM_PatternFacadeMH)
  ->Args({ 10, 20000000 })
  ->Args({ 30, 20000000 })
  ->Iterations(3)
  ->Unit(benchmark::kMillisecond);
