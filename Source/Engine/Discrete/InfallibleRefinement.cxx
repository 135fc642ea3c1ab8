// SPDX-License-Identifier: BSD-3-Clause
#include "Discrete/InfallibleRefinement.h"

#include "Core/Error.h"
#include "Core/Index.h"
#include "Discrete/AdjacencyRules.h"
#include "Discrete/ExampleAnalysis.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <map>
#include <optional>
#include <set>

namespace msynth
{

namespace
{
using Offset3 = std::array<int, 3>;

/// A context: offsets whose labels split a site's label, and its name.
struct Context
{
  std::vector<Offset3> Offsets;
  std::string Name;
  /// When set (one offset only): the key is only whether the neighbour holds this label, so
  /// the split is in two (the dissertation's Eq. 3.12 splits one label so).
  std::optional<Label> Only;
};

std::string OffsetName(const Offset3& o)
{
  std::string s;
  for (int a = 0; a < 3; ++a)
    if (o[ToIndex(a)] != 0)
    {
      const int v = o[ToIndex(a)];
      s += (v < 0 ? "-" : "+") + (std::abs(v) > 1 ? std::to_string(std::abs(v)) : "") +
        std::string(1, static_cast<char>('x' + a));
    }
  return s;
}

Context MakeContext(const std::vector<Offset3>& offsets)
{
  Context c{ offsets, "", std::nullopt };
  for (const auto& o : offsets)
    c.Name += (c.Name.empty() ? "" : " ") + OffsetName(o);
  return c;
}

/// The fixed list of contexts over the example's axes (those longer than one site).
std::vector<Context> Contexts(const LabelGrid& example)
{
  std::vector<int> axes;
  for (int a = 0; a < 3; ++a)
    if (example.Size(a) > 1)
      axes.push_back(a);
  std::vector<Offset3> dirs;
  for (int a : axes)
    for (int s : { -1, 1 })
    {
      Offset3 o{ { 0, 0, 0 } };
      o[ToIndex(a)] = s;
      dirs.push_back(o);
    }
  std::vector<Context> list;
  std::set<Label> values(example.Data().begin(), example.Data().end());
  for (const auto& d : dirs) // one face neighbour holds a given label, or not
    for (Label b : values)
    {
      Context c = MakeContext({ d });
      c.Only = b;
      c.Name += "=" + std::to_string(b);
      list.push_back(c);
    }
  for (const auto& d : dirs) // one face neighbour
    list.push_back(MakeContext({ d }));
  for (std::size_t i = 0; i < dirs.size(); ++i) // two face neighbours
    for (std::size_t j = i + 1; j < dirs.size(); ++j)
      list.push_back(MakeContext({ dirs[i], dirs[j] }));
  if (dirs.size() > 2)
    list.push_back(MakeContext(dirs)); // every face neighbour
  for (const auto& d : dirs)           // two sites along a direction
    list.push_back(MakeContext({ d, { { 2 * d[0], 2 * d[1], 2 * d[2] } } }));
  if (axes.size() > 1) // the whole 3^d box around the site
  {
    std::vector<Offset3> box;
    const int d = static_cast<int>(axes.size());
    for (int code = 0; code < static_cast<int>(std::pow(3, d)); ++code)
    {
      Offset3 o{ { 0, 0, 0 } };
      int c = code;
      for (int a : axes)
      {
        o[ToIndex(a)] = c % 3 - 1;
        c /= 3;
      }
      if (o != Offset3{ { 0, 0, 0 } })
        box.push_back(o);
    }
    Context whole = MakeContext(box);
    whole.Name = "the " + std::string(d == 2 ? "3x3" : "3x3x3") + " box";
    list.push_back(whole);
  }
  return list;
}

/// The context key of each site of @p e whose label is in @p only (all when empty); an offset
/// outside E is `edge`.
std::vector<std::vector<Label>> Keys(
  const LabelGrid& e, const Context& context, const std::vector<Label>& only, Label edge)
{
  const auto& dims = e.Dimensions();
  std::vector<std::vector<Label>> keys(ToIndex(e.NumberOfSites()));
  std::size_t i = 0;
  for (std::int64_t z = 0; z < dims[2]; ++z)
    for (std::int64_t y = 0; y < dims[1]; ++y)
      for (std::int64_t x = 0; x < dims[0]; ++x, ++i)
        if (only.empty() || std::find(only.begin(), only.end(), e.At(x, y, z)) != only.end())
          for (const auto& o : context.Offsets)
          {
            const std::int64_t u = x + o[0], v = y + o[1], w = z + o[2];
            const Label n = e.Contains(u, v, w) ? e.At(u, v, w) : edge;
            keys[i].push_back(context.Only ? Label(n == *context.Only) : n);
          }
  return keys;
}

/// True when site @p i of @p e lies on its outer layer (along an axis longer than one site).
bool OnBorder(const LabelGrid& e, std::size_t i)
{
  std::int64_t rest = static_cast<std::int64_t>(i);
  for (int a = 0; a < 3; ++a)
  {
    const std::int64_t c = rest % e.Size(a);
    rest /= e.Size(a);
    if (e.Size(a) > 1 && (c == 0 || c == e.Size(a) - 1))
      return true;
  }
  return false;
}

/// E split by @p context at sites whose label is in @p only (or every site when it is empty).
/// Variants come from E's inner sites (first seen first). A site on E's border takes the first
/// variant that agrees with its context inside E, else its label's first variant: E's border
/// is where the example was cut, and a variant seen only there would have no neighbour beyond
/// it. Only a label with no inner site makes variants on the border. Fills @p f.
LabelGrid Split(
  const LabelGrid& e, const Context& context, const std::vector<Label>& only, LabelMap& f)
{
  const Label edge = std::numeric_limits<Label>::min();
  const auto keys = Keys(e, context, only, edge);
  const auto& labels = e.Data();
  std::map<Label, std::vector<std::vector<Label>>> variants; // label → keys, first seen first
  const auto find = [&](std::size_t i) -> int
  {
    const auto& known = variants[labels[i]];
    for (std::size_t v = 0; v < known.size(); ++v)
    {
      bool same = true;
      for (std::size_t j = 0; j < known[v].size() && same; ++j)
        same = keys[i][j] == edge || keys[i][j] == known[v][j];
      if (same)
        return static_cast<int>(v);
    }
    return -1;
  };
  for (int pass = 0; pass < 2; ++pass)
    for (std::size_t i = 0; i < keys.size(); ++i)
      if (OnBorder(e, i) == (pass == 1) && find(i) < 0 &&
        (pass == 0 || variants[labels[i]].empty()))
        variants[labels[i]].push_back(keys[i]);
  // The most frequent variant first (it keeps the label's value), then by first occurrence;
  // a site matching several (on the border) takes the first of them.
  std::map<std::pair<Label, std::vector<Label>>, std::int64_t> count;
  for (std::size_t i = 0; i < keys.size(); ++i)
    if (!OnBorder(e, i))
      ++count[{ labels[i], keys[i] }];
  for (auto& [a, known] : variants)
    std::stable_sort(known.begin(), known.end(),
      [&, a = a](const auto& p, const auto& q) {
        return count[{ a, p }] > count[{ a, q }];
      });
  // Values: variant 0 keeps a; the others follow the largest label, label by label.
  Label next = variants.rbegin()->first;
  std::map<Label, std::vector<Label>> value;
  for (const auto& [a, known] : variants)
    for (std::size_t v = 0; v < known.size(); ++v)
    {
      if (v > 0 && next == std::numeric_limits<Label>::max())
        throw Error("no label values are left for a refined example");
      value[a].push_back(v == 0 ? a : ++next);
      f.emplace_back(value[a].back(), a);
    }
  std::sort(f.begin(), f.end());
  LabelGrid refined(e.Size(0), e.Size(1), e.Size(2));
  for (std::size_t i = 0; i < keys.size(); ++i)
    refined.Data()[i] = value[labels[i]][ToIndex(std::max(find(i), 0))];
  return refined;
}

/// Bit sets of label indices, for the enumeration of Eq. 3.13's check.
class Successors
{
public:
  explicit Successors(const ExampleAnalysis& a)
    : K(a.NumberOfLabels())
    , Words((a.NumberOfLabels() + 63) / 64)
  {
    for (int axis = 0; axis < 3; ++axis)
    {
      this->Next[ToIndex(axis)].assign(ToIndex(this->K * this->Words), 0);
      for (const auto& t : a.Transitions(axis))
        this->Next[ToIndex(axis)][ToIndex(t.From * this->Words + t.To / 64)] |= std::uint64_t(1)
          << (t.To % 64);
    }
  }
  /// Labels that may follow @p from along +@p axis, ANDed into @p set.
  void Restrict(int axis, int from, std::vector<std::uint64_t>& set) const
  {
    const auto* row = &this->Next[ToIndex(axis)][ToIndex(from * this->Words)];
    for (int w = 0; w < this->Words; ++w)
      set[ToIndex(w)] &= row[w];
  }
  int K, Words;

private:
  std::array<std::vector<std::uint64_t>, 3> Next;
};

/// Depth-first search over the sites of one output (x fastest) with pair constraints to the
/// placed -x, -y, -z neighbours; @p domain gives each site's allowed labels (all bits set for
/// none). Calls @p found on each complete model (stop when it returns false). Counts nodes.
class Enumeration
{
public:
  Enumeration(const Successors& rules, const std::array<std::int64_t, 3>& dims, std::int64_t& nodes,
    std::int64_t maxNodes)
    : Rules(rules)
    , Dims(dims)
    , Nodes(nodes)
    , MaxNodes(maxNodes)
  {
    this->Model.assign(ToIndex(dims[0] * dims[1] * dims[2]), -1);
  }
  bool OverBudget() const { return this->Nodes > this->MaxNodes; }

  /// False when stopped (by @p found or by the budget).
  template <class Domain, class Found>
  bool Run(const Domain& domain, const Found& found)
  {
    return this->Place(0, domain, found);
  }
  std::vector<int> Model;

private:
  template <class Domain, class Found>
  bool Place(std::size_t i, const Domain& domain, const Found& found)
  {
    if (i == this->Model.size())
      return found(this->Model);
    if (++this->Nodes > this->MaxNodes)
      return false;
    std::vector<std::uint64_t> set = domain(i);
    const std::int64_t x = static_cast<std::int64_t>(i) % this->Dims[0];
    const std::int64_t y = static_cast<std::int64_t>(i) / this->Dims[0] % this->Dims[1];
    const std::int64_t z = static_cast<std::int64_t>(i) / (this->Dims[0] * this->Dims[1]);
    const std::int64_t stride[3] = { 1, this->Dims[0], this->Dims[0] * this->Dims[1] };
    const std::int64_t at[3] = { x, y, z };
    for (int a = 0; a < 3; ++a)
      if (at[a] > 0)
        this->Rules.Restrict(a, this->Model[i - ToIndex(stride[a])], set);
    for (int w = 0; w < this->Rules.Words; ++w)
      for (std::uint64_t bits = set[ToIndex(w)]; bits; bits &= bits - 1)
      {
        this->Model[i] = 64 * w + __builtin_ctzll(bits);
        if (!this->Place(i + 1, domain, found))
          return false;
      }
    this->Model[i] = -1;
    return true;
  }

  const Successors& Rules;
  std::array<std::int64_t, 3> Dims;
  std::int64_t& Nodes;
  std::int64_t MaxNodes;
};

/// Output sizes of the check, fewest sites first.
std::vector<std::array<std::int64_t, 3>> CheckSizes(
  const std::array<std::int64_t, 3>& outputSize, int edge)
{
  std::vector<std::array<std::int64_t, 3>> sizes;
  std::array<std::int64_t, 3> top{ { 1, 1, 1 } };
  for (std::size_t a = 0; a < 3; ++a)
    top[a] = std::min<std::int64_t>(outputSize[a], edge);
  for (std::int64_t z = 1; z <= top[2]; ++z)
    for (std::int64_t y = 1; y <= top[1]; ++y)
      for (std::int64_t x = 1; x <= top[0]; ++x)
        sizes.push_back({ { x, y, z } });
  std::stable_sort(sizes.begin(), sizes.end(),
    [](const auto& a, const auto& b) { return a[0] * a[1] * a[2] < b[0] * b[1] * b[2]; });
  return sizes;
}

std::string SizeText(const std::array<std::int64_t, 3>& s)
{
  return std::to_string(s[0]) + "x" + std::to_string(s[1]) + "x" + std::to_string(s[2]);
}
/// A refinement to try.
struct Candidate
{
  std::string Split;
  LabelGrid Grid;
  LabelMap Map;
  std::size_t Labels;
};

/// Every context applied to each label and to all, without repeats, the smallest first. The
/// list stops (@p cut set) once the sites visited or the sites of the grids kept pass a budget,
/// which bounds time and memory on large examples.
std::vector<Candidate> Candidates(
  const LabelGrid& example, const ExampleAnalysis& analysis, bool& cut)
{
  constexpr std::int64_t MaxVisits = 200000000, MaxKept = 20000000;
  std::int64_t visits = 0, kept = 0;
  cut = false;
  std::vector<Candidate> candidates;
  std::set<std::vector<Label>> seen;
  for (const Context& context : Contexts(example))
  {
    const std::int64_t cost =
      example.NumberOfSites() * static_cast<std::int64_t>(context.Offsets.size() + 1);
    if (visits + cost * (analysis.NumberOfLabels() + 1) > MaxVisits || kept > MaxKept)
    {
      cut = true;
      break;
    }
    visits += cost * (analysis.NumberOfLabels() + 1);
    std::vector<std::vector<Label>> scopes;
    for (Label v : analysis.Labels())
      scopes.push_back({ v });
    scopes.push_back({});
    for (const auto& scope : scopes)
    {
      Candidate c;
      c.Grid = Split(example, context, scope, c.Map);
      c.Labels = c.Map.size();
      if (c.Labels == ToIndex(analysis.NumberOfLabels()) || !seen.insert(c.Grid.Data()).second)
        continue;
      c.Split = (scope.empty() ? std::string("every label") : "label " + std::to_string(scope[0])) +
        " by " + context.Name;
      kept += c.Grid.NumberOfSites();
      candidates.push_back(std::move(c));
    }
  }
  std::stable_sort(candidates.begin(), candidates.end(),
    [](const Candidate& a, const Candidate& b) { return a.Labels < b.Labels; });
  return candidates;
}
} // namespace

LabelGrid MapLabels(const LabelGrid& model, const LabelMap& f)
{
  LabelGrid out = model;
  for (auto& v : out.Data())
  {
    const auto it = std::lower_bound(f.begin(), f.end(), std::make_pair(v, Label(0)),
      [](const auto& a, const auto& b) { return a.first < b.first; });
    if (it == f.end() || it->first != v)
      throw Error("label " + std::to_string(v) + " is not a label of the refined example");
    v = it->second;
  }
  return out;
}

Equation313Check CheckEquation313(const LabelGrid& example, const LabelGrid& refined,
  const LabelMap& f, const std::array<std::int64_t, 3>& outputSize, int frame,
  const RefinementOptions& options)
{
  const ExampleAnalysis ea = ExampleAnalysis::FromExample(example);
  const ExampleAnalysis ia = ExampleAnalysis::FromExample(refined);
  const Successors er(ea), ir(ia);
  // f on indices: the E_I indices whose image is each E index, as bit sets.
  std::vector<std::vector<std::uint64_t>> preimage(
    ToIndex(er.K), std::vector<std::uint64_t>(ToIndex(ir.Words), 0));
  for (const auto& [from, to] : f)
  {
    const int i = ia.IndexOf(from), e = ea.IndexOf(to);
    if (i >= 0 && e >= 0)
      preimage[ToIndex(e)][ToIndex(i / 64)] |= std::uint64_t(1) << (i % 64);
  }
  Equation313Check check;
  std::int64_t nodes = 0;
  std::vector<std::uint64_t> all(ToIndex(er.Words), 0);
  for (int b = 0; b < er.K; ++b)
    all[ToIndex(b / 64)] |= std::uint64_t(1) << (b % 64);
  const auto sizes = CheckSizes(outputSize, options.CheckEdge - 2 * frame);
  for (const auto& inner : sizes)
  {
    std::array<std::int64_t, 3> outer = inner;
    for (std::size_t a = 0; a < 3; ++a)
      outer[a] += outputSize[a] > 1 ? 2 * frame : 0;
    const std::array<std::int64_t, 3> low{ { outer[0] > inner[0] ? frame : 0,
      outer[1] > inner[1] ? frame : 0, outer[2] > inner[2] ? frame : 0 } };
    std::set<std::vector<int>> lifted; // inner models already lifted
    Enumeration models(er, outer, nodes, options.CheckNodes);
    bool ok = true;
    const bool done = models.Run([&](std::size_t) { return all; },
      [&](const std::vector<int>& m)
      {
        std::vector<int> part;
        for (std::int64_t z = 0; z < inner[2]; ++z)
          for (std::int64_t y = 0; y < inner[1]; ++y)
            for (std::int64_t x = 0; x < inner[0]; ++x)
              part.push_back(
                m[ToIndex(x + low[0] + outer[0] * (y + low[1] + outer[1] * (z + low[2])))]);
        if (lifted.count(part))
          return true;
        ++check.Models;
        Enumeration lift(ir, inner, nodes, options.CheckNodes);
        bool any = false;
        lift.Run([&](std::size_t i) { return preimage[ToIndex(part[i])]; },
          [&](const std::vector<int>&)
          {
            any = true;
            return false;
          });
        ok = any || lift.OverBudget();
        lifted.insert(part);
        return any; // stop at a model without a lift, or when the budget ran out
      });
    if (!ok)
    {
      check.Holds = false;
      check.Text = "fails: a " + SizeText(inner) + " model consistent with the example" +
        (frame ? " inside a larger one" : "") + " has no counterpart in the refinement";
      return check;
    }
    if (!done || nodes > options.CheckNodes)
      break;
    check.Largest = inner;
    ++check.Sizes;
  }
  check.Complete = check.Sizes == static_cast<int>(sizes.size());
  check.Text = std::string(frame ? "holds away from the faces" : "holds") +
    " on every output up to " + SizeText(check.Largest) + " (" + std::to_string(check.Sizes) +
    " sizes, " + std::to_string(check.Models) + " models)" +
    (check.Complete ? "" : "; the search budget ended the check there");
  return check;
}

InfallibleRefinement FindInfallibleRefinement(const LabelGrid& example,
  const std::array<std::int64_t, 3>& outputSize, const RefinementOptions& options)
{
  InfallibleRefinement result;
  const ExampleAnalysis analysis = ExampleAnalysis::FromExample(example);
  const auto test = [&](const LabelGrid& grid, RefinementStep& step)
  {
    const AdjacencyRules rules = AdjacencyRules::FromExample(ExampleAnalysis::FromExample(grid));
    step.Labels = rules.NumberOfLabels();
    const InfallibilityReport report = AnalyzeInfallibility(rules, outputSize,
      options.MaxConfigurations, rules.NumberOfLabels() <= 64 ? options.MaxRegion : 2);
    step.Proved = report.Proved;
    step.Infallibility = report.Explanation;
    return report;
  };
  RefinementStep none;
  none.Split = "none (the example itself)";
  result.Report = test(example, none);
  if (none.Proved)
  {
    none.Accepted = true;
    result.Found = true;
    result.Refined = example;
    for (Label v : analysis.Labels())
      result.Map.emplace_back(v, v);
    result.Steps.push_back(none);
    result.Summary = "the example is already proved infallible";
    return result;
  }
  result.Steps.push_back(none);

  bool cut = false;
  std::vector<Candidate> candidates = Candidates(example, analysis, cut);
  int tried = 0;
  for (const Candidate& c : candidates)
  {
    if (tried++ == options.MaxCandidates)
      break;
    RefinementStep step;
    step.Split = c.Split;
    const InfallibilityReport report = test(c.Grid, step);
    if (report.Proved)
    {
      const Equation313Check check =
        CheckEquation313(example, c.Grid, c.Map, outputSize, 1, options);
      step.Equation313 = check.Text;
      // Accepted when checked on outputs of at least 2 sites along every axis of the output.
      bool enough = check.Holds && check.Sizes > 0;
      for (std::size_t a = 0; a < 3; ++a)
        enough = enough && check.Largest[a] >= std::min<std::int64_t>(2, outputSize[a]);
      step.Accepted = enough;
      if (check.Holds && !enough)
        step.Equation313 += " (too small a check to accept)";
      if (step.Accepted) // at the faces too?
      {
        const Equation313Check faces =
          CheckEquation313(example, c.Grid, c.Map, outputSize, 0, options);
        step.Equation313 += "; at the faces it " + faces.Text;
      }
      if (step.Accepted)
      {
        result.Found = true;
        result.Refined = c.Grid;
        result.Map = c.Map;
        result.Report = report;
        result.Check = check;
        result.Steps.push_back(step);
        result.Summary = "refined by splitting " + c.Split + ": " + std::to_string(c.Labels) +
          " labels instead of " + std::to_string(analysis.NumberOfLabels()) +
          ", proved infallible; Eq. 3.13 " + check.Text;
        return result;
      }
    }
    result.Steps.push_back(step);
  }
  result.Summary = "no refinement among the " +
    std::to_string(std::min<std::size_t>(candidates.size(), options.MaxCandidates)) +
    " tried (of " + std::to_string(candidates.size()) +
    ") is both proved infallible and true to Eq. 3.13" +
    (cut ? "; the list of refinements was cut short by its budget (a large example)" : "");
  return result;
}

namespace
{
/// The first option that --via-infallible cannot honour, or empty.
std::string Unsupported(const SynthesisOptions& o)
{
  for (std::size_t a = 0; a < 3; ++a)
    if (o.BlockSize[a] > 0 && o.BlockSize[a] < o.Size[a])
      return "blocks (it runs Algorithm 3.1 on the whole model)";
  if (o.Order != SiteOrder::ScanLine)
    return "a site order other than scan-line (the proof of infallibility is for scan-line order)";
  if (o.Pins || o.Start)
    return "pinned sites or a given start";
  if (!o.Counts.empty() || o.Soft.Active() || o.Guide)
    return "counts, soft targets or a guide";
  for (std::size_t a = 0; a < 3; ++a)
    if (o.Symmetry[a].Enabled || o.Translate[a].Enabled)
      return "symmetry";
  if (o.Rotate.Enabled)
    return "symmetry";
  for (const auto& b : o.Boundary)
    if (b)
      return "boundary labels";
  return {};
}
} // namespace

SynthesisResult SynthesizeViaInfallible(const LabelGrid& example, SynthesisOptions options,
  const RefinementOptions& search, InfallibleRefinement* refinement)
{
  const std::string unsupported = Unsupported(options);
  if (!unsupported.empty())
    throw Error("synthesis via an infallible refinement does not take " + unsupported);
  InfallibleRefinement found = FindInfallibleRefinement(example, options.Size, search);
  if (!found.Found)
    throw Error("no infallible refinement of the example was found: " + found.Summary);
  options.BlocksWhenWholeFails = false;
  options.AttemptsPerBlock = 1;
  options.BacktracksPerAttempt = 0;
  options.BlockSize = { { 0, 0, 0 } };
  options.Example = &found.Refined;
  SynthesisResult result =
    Synthesize(AdjacencyRules::FromExample(ExampleAnalysis::FromExample(found.Refined)), options);
  if (result.Succeeded())
    result.Model = MapLabels(result.Model, found.Map);
  result.Message += std::string(result.Message.empty() ? "" : "; ") + "via an infallible " +
    "refinement (D 3.3.8): " + found.Summary;
  if (refinement)
    *refinement = std::move(found);
  return result;
}

} // namespace msynth
