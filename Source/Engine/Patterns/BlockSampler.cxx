// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file BlockSampler.cxx
 * @brief BLOCKSS (Yeh et al. 2012, Algorithms 1–2) and single-site Metropolis–Hastings (§8.2)
 * on a PatternProblem. See PatternSynthesis.h for the method and its one deviation.
 */
#include "Patterns/BlockSampler.h"

#include "Core/Error.h"
#include "Core/Index.h"
#include "Core/ProgressPoll.h"
#include "Core/Random.h"

#include <algorithm>
#include <chrono>
#include <cmath>

namespace msynth
{
namespace detail
{

namespace
{

using Clock = std::chrono::steady_clock;

double SecondsSince(Clock::time_point start)
{
  return std::chrono::duration<double>(Clock::now() - start).count();
}

/// The factors of the current slice that are unsatisfied, as an indexable set.
class FactorSet
{
public:
  explicit FactorSet(std::size_t factors)
    : Position(factors, -1)
  {
  }
  bool Empty() const { return this->Items.empty(); }
  std::size_t Size() const { return this->Items.size(); }
  std::int64_t At(std::size_t i) const { return this->Items[i]; }
  void Insert(std::int64_t f)
  {
    auto& pos = this->Position[ToIndex(f)];
    if (pos >= 0)
      return;
    pos = static_cast<std::int64_t>(this->Items.size());
    this->Items.push_back(f);
  }
  void Erase(std::int64_t f)
  {
    auto& pos = this->Position[ToIndex(f)];
    if (pos < 0)
      return;
    const std::int64_t last = this->Items.back();
    this->Items[ToIndex(pos)] = last;
    this->Position[ToIndex(last)] = pos;
    this->Items.pop_back();
    pos = -1;
  }
  void Clear()
  {
    for (std::int64_t f : this->Items)
      this->Position[ToIndex(f)] = -1;
    this->Items.clear();
  }

private:
  std::vector<std::int64_t> Items;
  std::vector<std::int64_t> Position;
};

class Sampler
{
public:
  Sampler(const PatternProblem& problem, const PatternOptions& options,
    const std::vector<std::int32_t>& start, PatternResult& result)
    : P(problem)
    , O(options)
    , R(result)
    , Rng(Random::Derived(options.Seed, 0x5a3b1e55))
    , Unsat(ToIndex(problem.Shapes * problem.N))
    , Poll(options.Progress)
  {
    const auto n = ToIndex(problem.N);
    const auto factors = ToIndex(problem.Shapes * problem.N);
    this->InSlice.assign(factors, 0);
    this->Sat.assign(factors, 0);
    this->Stamp.assign(factors, 0);
    this->LastChange.assign(n, 0);
    this->Tiles = start;
    if (this->Tiles.size() != n)
      this->Tiles.resize(n);
    for (std::int64_t p = 0; start.size() != n && p < problem.N; ++p)
    {
      const auto& allowed = problem.ClassTiles[ToIndex(problem.SiteClass[ToIndex(p)])];
      this->Tiles[ToIndex(p)] = allowed[ToIndex(this->Rng.Below(allowed.size()))];
    }
    const std::int64_t moves = options.MovesPerSample >= 0 ? options.MovesPerSample : problem.N;
    this->MovesPerSample = std::max<std::int64_t>(1, moves);
    this->MaxMoves =
      options.MaxMoves > 0 ? options.MaxMoves : std::max<std::int64_t>(10000000, 20000 * problem.N);
    this->PrepareCovering();
  }

  /// Runs Algorithm 1 (or MH) and calls @p take(tiles, lastChange) for each kept sample.
  template <typename Take>
  bool Run(Take&& take, const SampleRepair& repair)
  {
    const auto start = Clock::now();
    const int total = this->O.BurnIn + this->O.Samples;
    for (int n = 0; n < total; ++n)
    {
      const std::int64_t minimum = n == 0 ? 1 : this->MovesPerSample;
      const bool done = this->O.Method == PatternMethod::MetropolisHastings
        ? this->RunMetropolis(minimum, n, total)
        : this->RunBlockSampleSAT(minimum, n, total);
      if (!done)
        return false;
      if (n == 0)
      {
        this->R.FirstValidMoves = this->R.Moves;
        this->R.FirstValidSeconds = SecondsSince(start);
      }
      if (n >= this->O.BurnIn && repair && !this->MendSample(repair, n, total))
        return false;
      if (n >= this->O.BurnIn)
        take(this->Tiles, this->LastChange, SecondsSince(start));
      // After each sample, as the block solvers after each block: told at once, not throttled.
      if (this->O.Progress && !this->O.Progress(double(n + 1) / double(total)))
      {
        this->R.Status = SynthesisStatus::Cancelled;
        return false;
      }
    }
    return true;
  }

private:
  /// Tries at mending one sample before the run fails.
  static constexpr int MendTries = 10;

  /// The sample mended by @p repair; its changed sites take the move count as last change (the
  /// next sample's slice is drawn from the mended pattern). Returns why it could not be mended.
  std::string Mend(const SampleRepair& repair)
  {
    this->Saved = this->Tiles;
    std::string failure = repair(this->Tiles);
    for (std::size_t i = 0; i < this->Tiles.size(); ++i)
      if (this->Tiles[i] != this->Saved[i])
        this->LastChange[i] = this->R.Moves;
    return failure;
  }

  /// Sample @p n mended; one that cannot be moves on from the partly mended pattern by another
  /// sample's moves and is mended again, MendTries times in all. False when cancelled.
  /// @throw Error with the last repair's reason when every try failed.
  bool MendSample(const SampleRepair& repair, int n, int total)
  {
    std::string failure = this->Mend(repair);
    for (int tries = 1; !failure.empty(); ++tries)
    {
      if (tries == MendTries)
        throw Error(failure + " (after " + std::to_string(MendTries) + " tries)");
      const bool moved = this->O.Method == PatternMethod::MetropolisHastings
        ? this->RunMetropolis(this->MovesPerSample, n, total)
        : this->RunBlockSampleSAT(this->MovesPerSample, n, total);
      if (!moved)
        return false;
      failure = this->Mend(repair);
    }
    return true;
  }

  // ---------------------------------------------------------------------------------------
  // Slices (Algorithm 1) and bookkeeping
  // ---------------------------------------------------------------------------------------
  void SampleSlice()
  {
    const double keep = this->O.Epsilon / (1.0 + this->O.Epsilon);
    this->Unsat.Clear();
    const std::int64_t all = this->P.Shapes * this->P.N;
    for (std::int64_t f = 0; f < all; ++f)
    {
      const auto i = ToIndex(f);
      if (!this->P.Valid[i])
        continue;
      const bool sat = this->P.Satisfied(f, this->Tiles);
      this->Sat[i] = sat ? 1 : 0;
      if (this->P.IsHard(f))
        this->InSlice[i] = 1;
      else // u ~ U[0, φ]: binding only when φ = 1 + ε and u > 1
        this->InSlice[i] = sat && this->Rng.Uniform() < keep ? 1 : 0;
      if (this->InSlice[i] && !sat)
        this->Unsat.Insert(f);
    }
  }

  bool Tick(std::int64_t movesThisSample, std::int64_t minimum, int n, int total)
  {
    ++this->R.Moves;
    if (!detail::PollDue(this->R.Moves))
      return true;
    const double within = std::min(1.0,
      static_cast<double>(movesThisSample) /
        static_cast<double>(std::max<std::int64_t>(minimum, 1)));
    if (!this->Poll.Continue((n + 0.5 * within) / total))
    {
      this->R.Status = SynthesisStatus::Cancelled;
      return false;
    }
    return true;
  }

  [[noreturn]] void OutOfMoves(int n)
  {
    const std::int64_t hard = this->P.CountViolatedHard(this->Tiles);
    if (n == 0 || hard > 0)
      throw Error("no pattern satisfying the hard factors was found in " +
        std::to_string(this->MaxMoves) + " moves (" + std::to_string(hard) + " of " +
        std::to_string(this->P.HardCount) +
        " pairs still do not fit); the exemplars' pairs, zones or fixed sites may allow none");
    throw Error("sample " + std::to_string(n + 1) + " found no pattern satisfying its slice in " +
      std::to_string(this->MaxMoves) + " moves");
  }

  // ---------------------------------------------------------------------------------------
  // Blocks
  // ---------------------------------------------------------------------------------------
  struct Placement
  {
    int Shape = 0;
    std::array<std::int64_t, 3> Origin{};
  };

  /// Covering[s][b]: origins of block b, relative to a factor of shape s's anchor, that cover
  /// the factor's scope (empty when b cannot).
  void PrepareCovering()
  {
    const FactorModel& m = this->P.Model;
    for (int s = 0; s < this->P.Shapes; ++s)
    {
      std::vector<std::array<int, 3>> scope;
      if (s < 3)
      {
        scope.push_back({ { 0, 0, 0 } });
        std::array<int, 3> e{ { 0, 0, 0 } };
        e[ToIndex(s)] = 1;
        scope.push_back(e);
      }
      else
        scope = m.SoftShapes[ToIndex(s - 3)].Offsets;
      std::vector<std::vector<std::array<int, 3>>> perBlock(m.BlockShapes.size());
      for (std::size_t b = 0; b < m.BlockShapes.size(); ++b)
      {
        const auto& offsets = m.BlockShapes[b].Offsets;
        for (const auto& ob : offsets)
        {
          const std::array<int, 3> d{ { scope[0][0] - ob[0], scope[0][1] - ob[1],
            scope[0][2] - ob[2] } };
          bool covers = true;
          for (const auto& os : scope)
          {
            const std::array<int, 3> rel{ { os[0] - d[0], os[1] - d[1], os[2] - d[2] } };
            if (!std::binary_search(offsets.begin(), offsets.end(), rel))
            {
              covers = false;
              break;
            }
          }
          if (covers)
            perBlock[b].push_back(d);
        }
      }
      this->Covering.push_back(std::move(perBlock));
    }
  }

  /// A block shape at random, placed with a random cell of it on site @p p.
  Placement RandomPlacement(std::int64_t p)
  {
    const FactorModel& m = this->P.Model;
    Placement pl;
    pl.Shape = static_cast<int>(this->Rng.Below(m.BlockShapes.size()));
    const auto& offsets = m.BlockShapes[ToIndex(pl.Shape)].Offsets;
    const auto& o = offsets[ToIndex(this->Rng.Below(offsets.size()))];
    const auto c = this->P.Coordinates(p);
    for (int a = 0; a < 3; ++a)
      pl.Origin[ToIndex(a)] = c[ToIndex(a)] - o[ToIndex(a)];
    return pl;
  }

  /// A block shape covering factor @p f's scope at random, at a random covering origin.
  Placement CoveringPlacement(std::int64_t f)
  {
    const std::int64_t s = f / this->P.N;
    const std::int64_t p = f - s * this->P.N;
    const auto& perBlock = this->Covering[ToIndex(s)];
    std::size_t choices = 0;
    for (const auto& d : perBlock)
      choices += d.empty() ? 0 : 1;
    if (choices == 0)
      return this->RandomPlacement(p);
    std::size_t pick = ToIndex(this->Rng.Below(choices));
    Placement pl;
    for (std::size_t b = 0; b < perBlock.size(); ++b)
    {
      if (perBlock[b].empty())
        continue;
      if (pick-- == 0)
      {
        pl.Shape = static_cast<int>(b);
        const auto& d = perBlock[b][ToIndex(this->Rng.Below(perBlock[b].size()))];
        const auto c = this->P.Coordinates(p);
        for (int a = 0; a < 3; ++a)
          pl.Origin[ToIndex(a)] = c[ToIndex(a)] + d[ToIndex(a)];
        break;
      }
    }
    return pl;
  }

  /// A block shape at random placed on a random site of soft factor @p f's scope: blocks that
  /// cannot cover the scope (a window column across a row of wall) may still satisfy it.
  Placement OverlappingPlacement(std::int64_t f)
  {
    const std::int64_t k = f / this->P.N - 3;
    const std::int64_t anchor = f % this->P.N;
    const auto& steps = this->P.SoftSteps[ToIndex(k)];
    return this->RandomPlacement(anchor + steps[ToIndex(this->Rng.Below(steps.size()))]);
  }

  /// Collects the sites of @p pl inside the grid (with their cell in the block), the slice
  /// factors touching them and, with @p free (for BestBlock's ties), the other soft factors.
  void Collect(const Placement& pl, bool free = false)
  {
    const auto& offsets = this->P.Model.BlockShapes[ToIndex(pl.Shape)].Offsets;
    this->Sites.clear();
    this->Cells.clear();
    this->Affected.clear();
    this->Free.clear();
    if (++this->CurrentStamp == 0) // wrapped: old stamps could collide
    {
      std::fill(this->Stamp.begin(), this->Stamp.end(), 0u);
      this->CurrentStamp = 1;
    }
    for (std::size_t k = 0; k < offsets.size(); ++k)
    {
      std::int64_t q[3];
      bool inside = true;
      for (int a = 0; a < 3; ++a)
      {
        q[a] = pl.Origin[ToIndex(a)] + offsets[k][ToIndex(a)];
        inside = inside && q[a] >= 0 && q[a] < this->P.Size[ToIndex(a)];
      }
      if (!inside)
        continue;
      const std::int64_t site = q[0] + this->P.Stride[1] * q[1] + this->P.Stride[2] * q[2];
      this->Sites.push_back(site);
      this->Cells.push_back(static_cast<std::int32_t>(k));
      this->P.ForTouching(site,
        [this, free](std::int64_t f)
        {
          auto& stamp = this->Stamp[ToIndex(f)];
          if (stamp == this->CurrentStamp)
            return;
          stamp = this->CurrentStamp;
          if (this->InSlice[ToIndex(f)])
            this->Affected.push_back(f);
          else if (free && !this->P.IsHard(f))
            this->Free.push_back(f);
        });
    }
    this->Saved.resize(this->Sites.size());
    for (std::size_t i = 0; i < this->Sites.size(); ++i)
      this->Saved[i] = this->Tiles[ToIndex(this->Sites[i])];
  }

  /// Writes block configuration @p config of the collected placement (sites whose class forbids
  /// a tile keep theirs); returns the satisfied slice factors among the affected.
  std::int64_t Write(const std::int32_t* config)
  {
    for (std::size_t i = 0; i < this->Sites.size(); ++i)
    {
      const std::int32_t t = config[this->Cells[i]];
      const std::int64_t site = this->Sites[i];
      this->Tiles[ToIndex(site)] = this->P.AllowedAt(site, t) ? t : this->Saved[i];
    }
    std::int64_t c = 0;
    for (std::int64_t f : this->Affected)
      c += this->P.Satisfied(f, this->Tiles) ? 1 : 0;
    return c;
  }

  void Restore()
  {
    for (std::size_t i = 0; i < this->Sites.size(); ++i)
      this->Tiles[ToIndex(this->Sites[i])] = this->Saved[i];
  }

  std::int64_t SatisfiedBefore() const
  {
    std::int64_t c = 0;
    for (std::int64_t f : this->Affected)
      c += this->Sat[ToIndex(f)];
    return c;
  }

  /// Keeps the written block: updates the slice bookkeeping and the sites' last change.
  void Commit()
  {
    for (std::size_t i = 0; i < this->Sites.size(); ++i)
      if (this->Tiles[ToIndex(this->Sites[i])] != this->Saved[i])
        this->LastChange[ToIndex(this->Sites[i])] = this->R.Moves + 1;
    for (std::int64_t f : this->Affected)
    {
      const bool sat = this->P.Satisfied(f, this->Tiles);
      this->Sat[ToIndex(f)] = sat ? 1 : 0;
      if (sat)
        this->Unsat.Erase(f);
      else
        this->Unsat.Insert(f);
    }
  }

  const std::int32_t* BlockConfig(int shape, std::size_t k) const
  {
    const auto& b = this->P.Model.BlockShapes[ToIndex(shape)];
    return this->P.Model.BlockTiles[ToIndex(shape)].data() + k * b.Offsets.size();
  }
  std::size_t BlockCount(int shape) const
  {
    const auto& b = this->P.Model.BlockShapes[ToIndex(shape)];
    return this->P.Model.BlockTiles[ToIndex(shape)].size() / b.Offsets.size();
  }

  /// A random replacement block at @p pl, kept unconditionally (the p_flip move).
  void RandomBlock(const Placement& pl)
  {
    this->Collect(pl);
    this->Write(this->BlockConfig(pl.Shape, this->Rng.Below(this->BlockCount(pl.Shape))));
    this->Commit();
  }

  /// The block of @p pl's shape that satisfies the most slice factors, ties at random.
  void BestBlock(const Placement& pl)
  {
    this->Collect(pl, true);
    const std::size_t count = this->BlockCount(pl.Shape);
    const std::size_t tries =
      this->O.CandidatesPerMove > 0 ? std::min(count, ToIndex(this->O.CandidatesPerMove)) : count;
    std::int64_t best = -1;
    std::size_t bestK = 0;
    std::uint64_t ties = 0;
    const std::int64_t weight = static_cast<std::int64_t>(this->Free.size()) + 1;
    for (std::size_t i = 0; i < tries; ++i)
    {
      const std::size_t k = tries == count ? i : ToIndex(this->Rng.Below(count));
      // The slice's factors first; among ties, the soft factors outside it (see the header),
      // counted only for candidates that can still be best.
      std::int64_t c = this->Write(this->BlockConfig(pl.Shape, k)) * weight;
      if (c + weight > best)
        for (std::int64_t f : this->Free)
          c += this->P.Satisfied(f, this->Tiles) ? 1 : 0;
      this->Restore();
      if (c > best)
      {
        best = c;
        bestK = k;
        ties = 1;
      }
      else if (c == best && this->Rng.Below(++ties) == 0)
        bestK = k;
    }
    this->Write(this->BlockConfig(pl.Shape, bestK));
    this->Commit();
  }

  /// A soft factor whose configuration no exemplar shows, found by a few random draws; -1 if
  /// none was found.
  std::int64_t UnsatisfiedSoftFactor()
  {
    if (this->P.Shapes == 3)
      return -1;
    const auto soft = static_cast<std::uint64_t>((this->P.Shapes - 3) * this->P.N);
    for (int tries = 0; tries < 16; ++tries)
    {
      const std::int64_t f = 3 * this->P.N + static_cast<std::int64_t>(this->Rng.Below(soft));
      if (this->P.Valid[ToIndex(f)] && !this->P.Satisfied(f, this->Tiles))
        return f;
    }
    return -1;
  }

  /// The annealing move: a random block anywhere, kept with min(1, exp(Δc / T)).
  void AnnealingMove()
  {
    ++this->R.AnnealingMoves;
    const Placement pl = this->RandomPlacement(
      static_cast<std::int64_t>(this->Rng.Below(static_cast<std::uint64_t>(this->P.N))));
    this->Collect(pl);
    const std::int64_t before = this->SatisfiedBefore();
    const std::int64_t after =
      this->Write(this->BlockConfig(pl.Shape, this->Rng.Below(this->BlockCount(pl.Shape))));
    const double delta = static_cast<double>(after - before);
    if (delta >= 0 || this->Rng.Uniform() < std::exp(delta / this->O.Temperature))
    {
      ++this->R.AcceptedAnnealingMoves;
      this->Commit();
    }
    else
      this->Restore();
  }

  bool RunBlockSampleSAT(std::int64_t minimum, int n, int total)
  {
    this->SampleSlice();
    for (std::int64_t moves = 0;; ++moves)
    {
      if (moves >= minimum && this->Unsat.Empty())
        return true;
      if (moves >= this->MaxMoves)
        this->OutOfMoves(n);
      if (!this->Tick(moves, minimum, n, total))
        return false;
      if (this->Unsat.Empty() && this->O.SoftWalk && this->Rng.Uniform() < this->O.WalkProbability)
      {
        const std::int64_t f = this->UnsatisfiedSoftFactor();
        if (f >= 0)
        {
          ++this->R.WalkMoves;
          this->BestBlock(this->OverlappingPlacement(f));
          continue;
        }
      }
      if (!this->Unsat.Empty() && this->Rng.Uniform() < this->O.WalkProbability)
      {
        ++this->R.WalkMoves;
        const std::int64_t f = this->Unsat.At(ToIndex(this->Rng.Below(this->Unsat.Size())));
        if (this->Rng.Uniform() < this->O.FlipProbability)
          this->RandomBlock(this->RandomPlacement(f % this->P.N));
        else
          this->BestBlock(this->CoveringPlacement(f));
      }
      else
        this->AnnealingMove();
    }
  }

  // ---------------------------------------------------------------------------------------
  // Single-site Metropolis–Hastings (§8.2)
  // ---------------------------------------------------------------------------------------
  double LogFactor(std::int64_t f) const
  {
    const bool sat = this->P.Satisfied(f, this->Tiles);
    if (this->P.IsHard(f))
      return sat ? 0.0 : std::log(1e-8);
    return sat ? std::log1p(this->O.Epsilon) : 0.0;
  }

  bool RunMetropolis(std::int64_t minimum, int n, int total)
  {
    if (n == 0)
      this->Violated = this->P.CountViolatedHard(this->Tiles);
    for (std::int64_t moves = 0;; ++moves)
    {
      if (moves >= minimum && this->Violated == 0)
        return true;
      if (moves >= this->MaxMoves)
        this->OutOfMoves(n);
      if (!this->Tick(moves, minimum, n, total))
        return false;
      const auto q =
        static_cast<std::int64_t>(this->Rng.Below(static_cast<std::uint64_t>(this->P.N)));
      const auto& allowed = this->P.ClassTiles[ToIndex(this->P.SiteClass[ToIndex(q)])];
      if (allowed.size() < 2)
        continue;
      auto& tile = this->Tiles[ToIndex(q)];
      const std::int32_t old = tile;
      std::int32_t proposal = old;
      while (proposal == old)
        proposal = allowed[ToIndex(this->Rng.Below(allowed.size()))];
      double before = 0, after = 0;
      std::int64_t hardBefore = 0, hardAfter = 0;
      this->P.ForTouching(q,
        [&](std::int64_t f)
        {
          before += this->LogFactor(f);
          if (this->P.IsHard(f) && !this->P.Satisfied(f, this->Tiles))
            ++hardBefore;
        });
      tile = proposal;
      this->P.ForTouching(q,
        [&](std::int64_t f)
        {
          after += this->LogFactor(f);
          if (this->P.IsHard(f) && !this->P.Satisfied(f, this->Tiles))
            ++hardAfter;
        });
      const double delta = after - before;
      if (delta >= 0 || this->Rng.Uniform() < std::exp(delta))
      {
        this->Violated += hardAfter - hardBefore;
        this->LastChange[ToIndex(q)] = this->R.Moves + 1;
      }
      else
        tile = old;
    }
  }

  const PatternProblem& P;
  const PatternOptions& O;
  PatternResult& R;
  Random Rng;
  FactorSet Unsat;
  ProgressPoll Poll;
  std::int64_t MovesPerSample = 1;
  std::int64_t MaxMoves = 0;
  std::int64_t Violated = 0;

  std::vector<std::int32_t> Tiles;
  std::vector<std::int64_t> LastChange;
  std::vector<std::uint8_t> InSlice;
  std::vector<std::uint8_t> Sat;
  std::vector<std::uint32_t> Stamp;
  std::uint32_t CurrentStamp = 0;
  std::vector<std::vector<std::vector<std::array<int, 3>>>> Covering;

  std::vector<std::int64_t> Sites;
  std::vector<std::int32_t> Cells;
  std::vector<std::int32_t> Saved;
  std::vector<std::int64_t> Affected;
  std::vector<std::int64_t> Free; ///< soft factors outside the slice touching the block
};

} // namespace

bool RunSampler(const PatternProblem& problem, const PatternOptions& options,
  const std::vector<std::int32_t>& start, PatternResult& result, const SampleSink& take,
  const SampleRepair& repair)
{
  Sampler sampler(problem, options, start, result);
  return sampler.Run(take, repair);
}

} // namespace detail
} // namespace msynth
