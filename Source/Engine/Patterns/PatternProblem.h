// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/**
 * @file PatternProblem.h
 * @brief The factor graph of one output (internal to Patterns/): the factors over the output's
 * sites with their validity, each site's allowed tiles (zones, fixed sites, mirror seams) and
 * soft-factor group (style zones), and the evaluation of a factor on a pattern of tile indices.
 *
 * Factor f = s · N + p for shape s and anchor site p (N sites): s = 0, 1, 2 are the hard pairs
 * along x, y, z, s = 3 + k the soft shape k. A factor exists when its scope fits in the grid.
 */
#include "Core/Index.h"
#include "Patterns/FactorGraph.h"
#include "Patterns/PatternSynthesis.h"

#include <array>
#include <cstdint>
#include <unordered_set>
#include <vector>

namespace msynth
{
namespace detail
{

class PatternProblem
{
public:
  /**
   * The factor graph over @p size sites. With @p seams, the last layer along each mirrored axis
   * of @p options allows only tiles that can meet their mirror image there.
   * @throw Error as SynthesizePattern documents.
   */
  PatternProblem(const FactorModel& model, const PatternOptions& options,
    const std::array<std::int64_t, 3>& size, bool seams);

  const FactorModel& Model;
  std::array<std::int64_t, 3> Size;
  std::int64_t N = 0;
  std::array<std::int64_t, 3> Stride{ { 1, 1, 1 } };
  int T = 0;
  int Shapes = 3;                  ///< 3 + soft shapes
  std::vector<std::uint8_t> Valid; ///< per factor
  std::int64_t HardCount = 0;
  std::int64_t SoftCount = 0;

  /// Per soft shape, its offsets as index steps.
  std::vector<std::vector<std::int64_t>> SoftSteps;

  std::vector<std::int32_t> SiteClass;                 ///< per site
  std::vector<std::vector<std::uint8_t>> ClassAllowed; ///< per class, per tile
  std::vector<std::vector<std::int32_t>> ClassTiles;   ///< per class, the allowed tiles
  std::vector<std::int32_t> SiteGroup;                 ///< per site, soft group
  /// Per group, per soft shape, the observed configuration keys.
  std::vector<std::vector<std::unordered_set<std::uint64_t>>> GroupObserved;

  std::array<std::int64_t, 3> Coordinates(std::int64_t p) const
  {
    const std::int64_t x = p % this->Size[0];
    const std::int64_t rest = p / this->Size[0];
    return { { x, rest % this->Size[1], rest / this->Size[1] } };
  }
  bool AllowedAt(std::int64_t p, std::int32_t tile) const
  {
    return this->ClassAllowed[ToIndex(this->SiteClass[ToIndex(p)])][ToIndex(tile)] != 0;
  }

  bool IsHard(std::int64_t f) const { return f < 3 * this->N; }

  /// Whether factor @p f (which must exist) is satisfied by @p tiles.
  bool Satisfied(std::int64_t f, const std::vector<std::int32_t>& tiles) const
  {
    const std::int64_t s = f / this->N;
    const std::int64_t p = f - s * this->N;
    if (s < 3)
      return this->Model.Allowed(
        static_cast<int>(s), tiles[ToIndex(p)], tiles[ToIndex(p + this->Stride[ToIndex(s)])]);
    const auto& steps = this->SoftSteps[ToIndex(s - 3)];
    std::int32_t config[64];
    for (std::size_t k = 0; k < steps.size(); ++k)
      config[k] = tiles[ToIndex(p + steps[k])];
    const auto& observed =
      this->GroupObserved[ToIndex(this->SiteGroup[ToIndex(p)])][ToIndex(s - 3)];
    return observed.count(ConfigurationKey(config, steps.size())) != 0;
  }

  /// Calls @p f(factor) for every existing factor whose scope holds site @p q.
  template <typename F>
  void ForTouching(std::int64_t q, F&& f) const
  {
    const auto c = this->Coordinates(q);
    for (int a = 0; a < 3; ++a)
    {
      const std::int64_t base = a * this->N;
      if (this->Valid[ToIndex(base + q)])
        f(base + q);
      if (c[ToIndex(a)] > 0 && this->Valid[ToIndex(base + q - this->Stride[ToIndex(a)])])
        f(base + q - this->Stride[ToIndex(a)]);
    }
    for (std::size_t k = 0; k < this->SoftSteps.size(); ++k)
    {
      const std::int64_t base = static_cast<std::int64_t>(3 + k) * this->N;
      const Stencil& s = this->Model.SoftShapes[k];
      for (std::size_t o = 0; o < s.Offsets.size(); ++o)
      {
        const auto& off = s.Offsets[o];
        if (c[0] < off[0] || c[1] < off[1] || c[2] < off[2])
          continue;
        const std::int64_t anchor = q - this->SoftSteps[k][o];
        if (this->Valid[ToIndex(base + anchor)])
          f(base + anchor);
      }
    }
  }

  /// Per site, the soft factors anchored there that @p tiles satisfy; returns their total.
  std::int64_t CountSoft(
    const std::vector<std::int32_t>& tiles, std::vector<std::int32_t>* perSite) const;
  /// Hard factors @p tiles violates.
  std::int64_t CountViolatedHard(const std::vector<std::int32_t>& tiles) const;

private:
  void MarkFactors();
  void BuildSiteClasses(const PatternOptions& options, bool seams);
  std::vector<std::vector<int>> BuildSoftGroups(const PatternOptions& options);
};

} // namespace detail
} // namespace msynth
