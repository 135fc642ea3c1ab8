// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/**
 * @file InfallibleRefinement.h
 * @brief Converting a fallible example to an infallible one (dissertation §3.3.8, Eqs. 3.12–3.14).
 *
 * For a fallible example E the dissertation suggests finding an infallible example E_I and a
 * label function f with f(E_I) = E such that Eq. 3.13 holds:
 *   {M | M consistent with E} = {f(M) | M consistent with E_I};
 * Algorithm 3.1 then runs on E_I without failing and f maps its model back. It gives no general
 * procedure; this is a measured search, not a method that always succeeds.
 *
 * The search refines E by splitting labels by their context: a site's new label is its label
 * together with the labels at a few offsets around it (an offset outside E counts as "edge").
 * Candidates are every context in a fixed list (one face neighbour, two, all of them, two sites
 * along a direction, the whole 3^d box) applied to one label at a time or to every label; they
 * are tried in order of their label count (smallest first, ties in list order, identical
 * refinements once). Each is tested by the infallibility analysis (Algorithm 3.6,
 * Infallibility.h); a proved one is then checked against Eq. 3.13.
 *
 * f(E_I) = E holds by construction, and so does the inclusion ⊇ of Eq. 3.13 (every pair of E_I
 * maps to a pair of E). The other inclusion (every model consistent with E lifts to one
 * consistent with E_I) can fail, since a context split turns pair constraints into larger ones;
 * CheckEquation313 tests it exhaustively on small outputs: it enumerates every model consistent
 * with E on each output size up to an edge and searches a lift for each.
 *
 * Numbering: the variants of label a are ordered by first occurrence (x fastest); the first
 * keeps the value a, the others take new values above the largest label of E (label a's extra
 * variants before label a + 1's). Everything is deterministic.
 */
#include "Core/LabelGrid.h"
#include "Discrete/DiscreteSynthesis.h"
#include "Discrete/Infallibility.h"

#include <array>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace msynth
{

/// f of Eqs. 3.12–3.14: pairs (label of E_I, label of E), sorted by the first.
using LabelMap = std::vector<std::pair<Label, Label>>;

struct RefinementOptions
{
  int MaxCandidates = 200;                ///< refinements tested (after the example itself)
  std::int64_t MaxConfigurations = 20000; ///< per infallibility analysis (and region size)
  int MaxRegion = 3;                      ///< region sizes of the analysis (Infallibility.h)
  std::int64_t CheckNodes = 2000000;      ///< search nodes of one Eq. 3.13 check
  int CheckEdge = 5; ///< outputs of up to this many sites per axis (with the frame)
};

/// The outcome of checking Eq. 3.13 on small outputs.
struct Equation313Check
{
  bool Holds = true;     ///< no model of E without a lift was found
  bool Complete = false; ///< every output size up to the edge was checked
  std::array<std::int64_t, 3> Largest{ { 0, 0, 0 } }; ///< the last size checked completely
  int Sizes = 0;                                      ///< output sizes checked completely
  std::int64_t Models = 0;                            ///< models of E enumerated (and lifted)
  std::string Text;                                   ///< one line: what was checked, or why not
};

/// One refinement tried.
struct RefinementStep
{
  std::string Split; ///< "none", "label 0 by -x", "every label by -x +y", ...
  int Labels = 0;    ///< k of the refined example
  bool Proved = false;
  std::string Infallibility; ///< the analysis' explanation
  std::string Equation313;   ///< the check's line; empty when not checked
  bool Accepted = false;
};

struct InfallibleRefinement
{
  bool Found = false;
  LabelGrid Refined; ///< E_I (E itself when E is already proved infallible)
  LabelMap Map;      ///< f; the identity when E is proved
  InfallibilityReport Report;
  Equation313Check Check;
  std::vector<RefinementStep> Steps;
  std::string Summary; ///< one line
};

/**
 * Searches a refinement of @p example that the infallibility analysis proves infallible for
 * outputs shaped like @p outputSize (2D or 3D) and that passes CheckEquation313.
 * @throw Error when the example is empty.
 */
InfallibleRefinement FindInfallibleRefinement(const LabelGrid& example,
  const std::array<std::int64_t, 3>& outputSize, const RefinementOptions& options = {});

/**
 * Eq. 3.13 on small outputs: along each axis where @p outputSize is larger than 1, outputs of
 * 1..options.CheckEdge − 2 @p frame sites (at most the output's size there), smallest first,
 * within options.CheckNodes search nodes. With @p frame 1, the models checked are the inner
 * parts of the models consistent with E one site larger on each side: Eq. 3.13 away from the
 * output's faces. (At the faces it often fails: a structure cut off by the face, "2 0 0" in a
 * one-row output of the Fig. 3.5 example, is consistent with E but not with any refinement
 * that ties 2 to what follows it. The search accepts a refinement on the framed check.)
 */
Equation313Check CheckEquation313(const LabelGrid& example, const LabelGrid& refined,
  const LabelMap& f, const std::array<std::int64_t, 3>& outputSize, int frame,
  const RefinementOptions& options = {});

/// f(@p model). @throw Error naming a label that f does not map.
LabelGrid MapLabels(const LabelGrid& model, const LabelMap& f);

/**
 * D§3.3.8: finds E_I (FindInfallibleRefinement for @p options.Size), runs Algorithm 3.1 on it
 * (the whole model, scan-line order, one attempt, no backtracking, no fallback to blocks: a
 * proved example cannot fail) and maps the model back with f. The message names the split.
 * Fills @p refinement when given.
 * @throw Error when no refinement is found, or for options that speak of E's labels or of blocks
 * (blocks, another site order, pins, counts, soft targets, a guide, symmetry, boundary labels,
 * a given start).
 */
SynthesisResult SynthesizeViaInfallible(const LabelGrid& example, SynthesisOptions options,
  const RefinementOptions& search = {}, InfallibleRefinement* refinement = nullptr);

} // namespace msynth
