// SPDX-License-Identifier: BSD-3-Clause
#include "Discrete/SymmetryPlan.h"

#include "Core/Error.h"
#include "Core/Index.h"

#include <algorithm>
#include <map>
#include <numeric>
#include <optional>
#include <string>
#include <tuple>

namespace msynth
{
namespace detail
{

ExtendedRelation::ExtendedRelation(
  const AdjacencyRules& rules, const std::vector<std::function<bool(int, int)>>& extra)
{
  const int k = rules.NumberOfLabels();
  this->Allocate(k, NumberOfDirections + 2 * static_cast<int>(extra.size()));
  for (int d = 0; d < NumberOfDirections; ++d)
    for (int b = 0; b < k; ++b)
      for (int c = 0; c < k; ++c)
        if (rules.Allowed(d, b, c))
          this->AllowOne(d, b, c);
  for (std::size_t i = 0; i < extra.size(); ++i)
  {
    const int d = NumberOfDirections + 2 * static_cast<int>(i);
    for (int b = 0; b < k; ++b)
      for (int c = 0; c < k; ++c)
        if (extra[i](b, c))
        {
          this->AllowOne(d, b, c);
          this->AllowOne(d + 1, c, b);
        }
  }
  this->Finish();
}

LabelMap::LabelMap(std::vector<int> f)
  : F(std::move(f))
{
  const std::size_t k = this->F.size();
  this->Cycle.assign(k, -1);
  this->Position.assign(k, 0);
  for (std::size_t b = 0; b < k; ++b)
  {
    if (this->Cycle[b] >= 0)
      continue;
    std::vector<int> cycle;
    for (int c = static_cast<int>(b); this->Cycle[ToIndex(c)] < 0; c = this->F[ToIndex(c)])
    {
      this->Cycle[ToIndex(c)] = static_cast<int>(this->Cycles.size());
      this->Position[ToIndex(c)] = static_cast<int>(cycle.size());
      cycle.push_back(c);
    }
    this->Cycles.push_back(std::move(cycle));
  }
}

int LabelMap::Power(int b, std::int64_t j) const
{
  const auto& cycle = this->Cycles[ToIndex(this->Cycle[ToIndex(b)])];
  const auto len = static_cast<std::int64_t>(cycle.size());
  return cycle[ToIndex((this->Position[ToIndex(b)] + j % len) % len)];
}

std::int64_t SymmetryPlan::Source(const std::array<std::int64_t, 3>& q) const
{
  std::array<std::int64_t, 3> r = q;
  for (int a = 0; a < 3; ++a)
    if (this->Period[a] > 0)
      r[a] = q[a] % this->Period[a];
  if (this->Rotate)
  {
    const std::int64_t xy = this->TurnSource[ToIndex(q[0] + this->Full[0] * q[1])];
    r[0] = xy % this->Domain[0];
    r[1] = xy / this->Domain[0];
  }
  return r[0] + this->Domain[0] * (r[1] + this->Domain[1] * r[2]);
}

int SymmetryPlan::Image(const std::array<std::int64_t, 3>& q, int b) const
{
  for (int a = 0; a < 3; ++a)
    if (this->Period[a] > 0)
      b = this->Shift[a].Power(b, q[a] / this->Period[a]);
  if (this->Rotate)
    b = this->Turn.Power(b, this->TurnPower[ToIndex(q[0] + this->Full[0] * q[1])]);
  return b;
}

bool AnySeamSymmetry(const SynthesisOptions& options)
{
  return options.Rotate.Enabled || options.Translate[0].Enabled || options.Translate[1].Enabled ||
    options.Translate[2].Enabled;
}

namespace
{
using Coord = std::array<std::int64_t, 3>;
const char* const AxisName = "xyz";
const char* const FaceName[6] = { "-x", "+x", "-y", "+y", "-z", "+z" };
} // namespace

namespace
{
/// PlanSymmetry in steps: the maps of the translated axes and of the rotation (checked against
/// the rules and the boundary), then the seams between domain sites as arcs of extra relations
/// (or unary masks where a site meets itself), the guide at every image, and the arcs by source.
class SymmetryPlanner
{
public:
  SymmetryPlanner(const AdjacencyRules& rules, const SynthesisOptions& options)
    : Rules(rules)
    , Options(options)
    , Plan(std::make_unique<SymmetryPlan>())
    , K(rules.NumberOfLabels())
  {
    this->Plan->Full = options.Size;
    this->Plan->Domain = options.Size;
    this->Plan->DomainOptions = options;
    SynthesisOptions& domain = this->Plan->DomainOptions;
    domain.Rotate.Enabled = false;
    for (auto& t : domain.Translate)
      t.Enabled = false;
  }

  std::unique_ptr<SymmetryPlan> Build()
  {
    const bool anyTranslation = this->PlanTranslations();
    if (this->Options.Rotate.Enabled)
    {
      if (anyTranslation)
        throw Error("rotation symmetry cannot be combined with translation symmetry");
      this->PlanRotation();
    }
    this->CheckBoundaries();
    this->Plan->DomainOptions.Size = this->Plan->Domain;
    this->TranslationSeams();
    if (this->Plan->Rotate)
      this->RotationSeams();
    if (this->Options.Guide)
      this->GuideAtImages(*this->Options.Guide);
    this->Plan->Relation = std::make_unique<ExtendedRelation>(this->Rules, this->Relations);
    this->ArcsBySource();
    return std::move(this->Plan);
  }

private:
  std::string Name(int b) const { return std::to_string(this->Rules.LabelValues()[ToIndex(b)]); }

  /// A label map given by values, checked to be one-to-one on the example's labels.
  LabelMap ReadMap(const std::map<Label, Label>& m, const std::string& what) const
  {
    std::vector<int> f(ToIndex(this->K));
    std::iota(f.begin(), f.end(), 0);
    for (const auto& kv : m)
    {
      const int from = this->Rules.IndexOf(kv.first), to = this->Rules.IndexOf(kv.second);
      if (from < 0 || to < 0)
        throw Error("the " + what + " names label " +
          std::to_string(from < 0 ? kv.first : kv.second) +
          ", which does not occur in the example");
      f[ToIndex(from)] = to;
    }
    std::vector<char> hit(ToIndex(this->K), 0);
    for (int b = 0; b < this->K; ++b)
      if (hit[ToIndex(f[ToIndex(b)])]++)
        throw Error("the " + what + " is not one-to-one: two labels map to label " +
          this->Name(f[ToIndex(b)]));
    return LabelMap(std::move(f));
  }

  /// Each seam relation, registered once: (kind, axis or direction, power) → relation index.
  int Relation(int kind, int d, int j, std::function<bool(int, int)> pred)
  {
    const auto key = std::make_tuple(kind, d, j);
    const auto it = this->RelationIndex.find(key);
    if (it != this->RelationIndex.end())
      return it->second;
    this->Relations.push_back(std::move(pred));
    return this->RelationIndex[key] = static_cast<int>(this->Relations.size()) - 1;
  }

  /// The translated axes: their periods and maps, which must preserve the rules and commute.
  bool PlanTranslations()
  {
    bool any = false;
    for (int a = 0; a < 3; ++a)
    {
      const Translation& t = this->Options.Translate[ToIndex(a)];
      if (t.Enabled)
      {
        this->PlanTranslation(a, t);
        any = true;
      }
    }
    const SymmetryPlan& plan = *this->Plan;
    for (int a = 0; a < 3; ++a)
      for (int c = a + 1; c < 3; ++c)
        if (plan.Period[a] > 0 && plan.Period[c] > 0)
          for (int b = 0; b < this->K; ++b)
            if (plan.Shift[a].Apply(plan.Shift[c].Apply(b)) !=
              plan.Shift[c].Apply(plan.Shift[a].Apply(b)))
              throw Error(std::string("the translation maps along ") + AxisName[a] + " and " +
                AxisName[c] + " do not commute (label " + this->Name(b) + ")");
    return any;
  }

  void PlanTranslation(int a, const Translation& t)
  {
    const std::string axis(1, AxisName[a]);
    const std::int64_t n = this->Options.Size[a];
    if (n < 2)
      throw Error("translation symmetry along " + axis +
        " needs an output longer than one site along " + axis);
    const std::int64_t period = t.Period <= 0 ? n : t.Period;
    if (period > n)
      throw Error("the period along " + axis + " (" + std::to_string(period) +
        ") is longer than the output (" + std::to_string(n) + ")");
    LabelMap& f = this->Plan->Shift[ToIndex(a)];
    f = this->ReadMap(t.Map, "translation map along " + axis);
    const AdjacencyRules& rules = this->Rules;
    for (int a2 = 0; a2 < 3; ++a2)
      for (int b = 0; b < this->K; ++b)
        for (int c = 0; c < this->K; ++c)
          if (rules.Allowed(2 * a2, b, c) != rules.Allowed(2 * a2, f.Apply(b), f.Apply(c)))
            throw Error("the translation map along " + axis +
              " does not preserve the example's rules: label " + this->Name(b) + " before " +
              this->Name(c) + " along " + AxisName[a2] +
              (rules.Allowed(2 * a2, b, c) ? " occurs" : " does not occur") + ", but " +
              this->Name(f.Apply(b)) + " before " + this->Name(f.Apply(c)) +
              (rules.Allowed(2 * a2, b, c) ? " does not" : " does"));
    if (this->Options.Boundary[ToIndex(2 * a)] || this->Options.Boundary[ToIndex(2 * a + 1)])
      throw Error("the model repeats along " + axis + ", so its " + axis +
        " faces cannot have boundary labels");
    this->Plan->Period[a] = period;
    this->Plan->Domain[a] = period;
    this->Maps.push_back(&f);
    this->MapNames.push_back("translation map along " + axis);
  }

  /// The quarter turn's map must come back after four turns and carry the rules along x to
  /// those along y.
  void CheckRotationMap(const LabelMap& f) const
  {
    const AdjacencyRules& rules = this->Rules;
    for (int b = 0; b < this->K; ++b)
      if (f.Power(b, 4) != b)
        throw Error("the rotation map turned four times does not bring label " + this->Name(b) +
          " back to itself");
    for (int b = 0; b < this->K; ++b)
      for (int c = 0; c < this->K; ++c)
      {
        const int fb = f.Apply(b), fc = f.Apply(c);
        const char* broken = nullptr;
        if (rules.Allowed(PlusX, b, c) != rules.Allowed(PlusY, fb, fc))
          broken = "along x, turned along y";
        else if (rules.Allowed(PlusY, b, c) != rules.Allowed(PlusX, fc, fb))
          broken = "along y, turned along -x";
        else if (rules.Allowed(PlusZ, b, c) != rules.Allowed(PlusZ, fb, fc))
          broken = "along z, turned along z";
        if (broken)
          throw Error("the example's rules are not preserved by a quarter turn with the rotation "
                      "map: label " +
            this->Name(b) + " before " + this->Name(c) + " (" + broken + ") does not match label " +
            this->Name(fb) + " and " + this->Name(fc) +
            ". The example must look the same turned by 90 degrees");
      }
  }

  void PlanRotation()
  {
    SymmetryPlan& plan = *this->Plan;
    const std::int64_t n = this->Options.Size[0];
    const std::int64_t h = (n + 1) / 2;
    if (this->Options.Size[0] != this->Options.Size[1] || n < 2)
      throw Error("rotation symmetry about the vertical needs an output square in x and y, at "
                  "least 2 x 2 (the size is " +
        std::to_string(this->Options.Size[0]) + " x " + std::to_string(this->Options.Size[1]) +
        ")");
    plan.Rotate = true;
    plan.Turn = this->ReadMap(this->Options.Rotate.Map, "rotation map");
    this->CheckRotationMap(plan.Turn);
    // Side faces: one label on all four, its own turned image.
    std::optional<Label> side;
    for (int face = 0; face < 4; ++face)
    {
      const auto& v = this->Options.Boundary[ToIndex(face)];
      if (!v)
        continue;
      if (side && *side != *v)
        throw Error("with rotation symmetry the four side faces must share one boundary label "
                    "(got " +
          std::to_string(*side) + " and " + std::to_string(*v) + ")");
      side = v;
    }
    SynthesisOptions& domain = plan.DomainOptions;
    domain.Boundary[FaceMinX] = side;
    domain.Boundary[FaceMinY] = side;
    domain.Boundary[FaceMaxX].reset();
    domain.Boundary[FaceMaxY].reset();
    plan.Domain[0] = plan.Domain[1] = h;
    this->Maps.push_back(&plan.Turn);
    this->MapNames.push_back("rotation map");
    // Where each output xy site comes from: the domain site of its orbit with the lowest index.
    plan.TurnSource.assign(ToIndex(n * n), -1);
    plan.TurnPower.assign(ToIndex(n * n), 0);
    for (std::int64_t y = 0; y < n; ++y)
      for (std::int64_t x = 0; x < n; ++x)
      {
        std::int64_t rx = x, ry = y; // R^{-j}(x, y)
        std::int64_t best = -1;
        int power = 0;
        for (int j = 0; j < 4; ++j)
        {
          if (rx < h && ry < h && (best < 0 || rx + h * ry < best))
          {
            best = rx + h * ry;
            power = j;
          }
          const std::int64_t tx = ry, ty = n - 1 - rx; // R^{-1}(x, y) = (y, n - 1 - x)
          rx = tx;
          ry = ty;
        }
        plan.TurnSource[ToIndex(x + n * y)] = best;
        plan.TurnPower[ToIndex(x + n * y)] = static_cast<std::uint8_t>(power);
      }
  }

  /// A boundary label must be its own image under every map.
  void CheckBoundaries() const
  {
    const SynthesisOptions& domain = this->Plan->DomainOptions;
    for (std::size_t i = 0; i < this->Maps.size(); ++i)
      for (int face = 0; face < 6; ++face)
      {
        const auto& v = domain.Boundary[ToIndex(face)];
        if (!v || this->Options.Size[face / 2] == 1)
          continue;
        const int b = this->Rules.IndexOf(*v);
        if (b >= 0 && this->Maps[i]->Apply(b) != b)
          throw Error("the boundary label " + std::to_string(*v) + " of the " + FaceName[face] +
            " face is not its own image under the " + this->MapNames[i] +
            ", so the symmetric copies would not keep it");
      }
  }

  std::int64_t Index(const Coord& p) const
  {
    const Coord& dd = this->Plan->Domain;
    return p[0] + dd[0] * (p[1] + dd[1] * p[2]);
  }

  /// Site @p site keeps only the labels @p allowed accepts (a unary mask).
  void KeepOnly(std::int64_t site, const std::function<bool(int)>& allowed)
  {
    const Coord& dd = this->Plan->Domain;
    const std::int64_t sites = dd[0] * dd[1] * dd[2];
    const int words = this->Rules.Words();
    auto& masks = this->Plan->SiteMasks;
    if (masks.empty())
    {
      masks.assign(ToIndex(sites * words), 0);
      for (std::int64_t s = 0; s < sites; ++s)
        for (int b = 0; b < this->K; ++b)
          masks[ToIndex(s * words + b / 64)] |= std::uint64_t(1) << (b % 64);
    }
    for (int b = 0; b < this->K; ++b)
      if (!allowed(b))
        masks[ToIndex(site * words + b / 64)] &= ~(std::uint64_t(1) << (b % 64));
  }

  /// A seam from @p s to @p t under relation @p rel (a unary mask when they are one site).
  void Link(std::int64_t s, std::int64_t t, int rel)
  {
    if (s == t)
    {
      const auto& pred = this->Relations[ToIndex(rel)];
      this->KeepOnly(s, [&](int b) { return pred(b, b); });
      return;
    }
    this->Arcs.emplace_back(s, t, NumberOfDirections + 2 * rel);
    this->Arcs.emplace_back(t, s, NumberOfDirections + 2 * rel + 1);
  }

  /// The last layer of each translated axis continues into the first, shifted by its map.
  void TranslationSeams()
  {
    const Coord& dd = this->Plan->Domain;
    const AdjacencyRules& rules = this->Rules;
    Coord p;
    for (int a = 0; a < 3; ++a)
    {
      if (this->Plan->Period[a] == 0)
        continue;
      const LabelMap f = this->Plan->Shift[ToIndex(a)];
      const int rel = this->Relation(
        0, a, 1, [&rules, a, f](int b, int c) { return rules.Allowed(2 * a, b, f.Apply(c)); });
      for (p[2] = 0; p[2] < dd[2]; ++p[2])
        for (p[1] = 0; p[1] < dd[1]; ++p[1])
          for (p[0] = 0; p[0] < dd[0]; ++p[0])
            if (p[a] == dd[a] - 1)
            {
              Coord q = p;
              q[a] = 0;
              this->Link(this->Index(p), this->Index(q), rel);
            }
    }
  }

  /// A quadrant's sites meet their turned copies: duplicates, the centre, and the neighbours
  /// across the quadrant's +x and +y sides.
  void RotationSeams()
  {
    const SymmetryPlan& plan = *this->Plan;
    const AdjacencyRules& rules = this->Rules;
    const Coord& dd = plan.Domain;
    const std::int64_t n = this->Options.Size[0];
    const std::int64_t h = (n + 1) / 2;
    const LabelMap f = plan.Turn;
    Coord p;
    for (p[2] = 0; p[2] < dd[2]; ++p[2])
      for (p[1] = 0; p[1] < h; ++p[1])
        for (p[0] = 0; p[0] < h; ++p[0])
        {
          const std::int64_t s = this->Index(p);
          const auto at = ToIndex(p[0] + n * p[1]);
          // A duplicate of a lower-index domain site (odd sizes: the left arm of the centre row).
          const std::int64_t src = plan.TurnSource[at];
          const int j = plan.TurnPower[at];
          if (src != p[0] + h * p[1])
            this->Link(s, src + h * h * p[2],
              this->Relation(2, 0, j, [f, j](int b, int c) { return b == f.Power(c, j); }));
          // The centre of an odd size is its own turned image.
          if (n % 2 == 1 && p[0] == h - 1 && p[1] == h - 1)
            this->KeepOnly(s, [&](int b) { return f.Apply(b) == b; });
          for (int d : { PlusX, PlusY })
          {
            Coord q = p;
            ++q[AxisOf(d)];
            if (q[AxisOf(d)] < h || q[AxisOf(d)] >= n)
              continue; // inside the domain, or outside the output
            const auto qa = ToIndex(q[0] + n * q[1]);
            const int jq = plan.TurnPower[qa];
            const int rel = this->Relation(1, d, jq,
              [&rules, f, d, jq](int b, int c) { return rules.Allowed(d, b, f.Power(c, jq)); });
            this->Link(s, plan.TurnSource[qa] + h * h * p[2], rel);
          }
        }
  }

  /// The guide at every image of a domain site (unary masks).
  void GuideAtImages(const GuideVolume& g)
  {
    const SymmetryPlan& plan = *this->Plan;
    const std::int64_t cells = g.Dims[0] * g.Dims[1] * g.Dims[2];
    bool valid = g.Dims[0] >= 1 && g.Dims[1] >= 1 && g.Dims[2] >= 1;
    std::vector<const std::vector<float>*> weights(ToIndex(this->K), nullptr);
    for (const auto& kv : g.Weights)
    {
      const int b = this->Rules.IndexOf(kv.first);
      valid = valid && b >= 0 && static_cast<std::int64_t>(kv.second.size()) == cells;
      if (b >= 0)
        weights[ToIndex(b)] = &kv.second;
    }
    if (!valid)
      return; // the solver reports what is wrong with the guide
    Coord q;
    for (q[2] = 0; q[2] < plan.Full[2]; ++q[2])
      for (q[1] = 0; q[1] < plan.Full[1]; ++q[1])
        for (q[0] = 0; q[0] < plan.Full[0]; ++q[0])
        {
          const std::int64_t cell = g.CellOf(q, plan.Full);
          this->KeepOnly(plan.Source(q),
            [&](int b)
            {
              const auto* w = weights[ToIndex(plan.Image(q, b))];
              return !w || (*w)[ToIndex(cell)] > 0.0f;
            });
        }
  }

  /// The arcs by source (CSR).
  void ArcsBySource()
  {
    const Coord& dd = this->Plan->Domain;
    const std::int64_t sites = dd[0] * dd[1] * dd[2];
    SiteArcs& out = this->Plan->Arcs;
    out.Dims = dd;
    out.Start.assign(ToIndex(sites + 1), 0);
    for (const auto& arc : this->Arcs)
      ++out.Start[ToIndex(std::get<0>(arc) + 1)];
    for (std::int64_t s = 0; s < sites; ++s)
      out.Start[ToIndex(s + 1)] += out.Start[ToIndex(s)];
    out.Target.resize(this->Arcs.size());
    out.Class.resize(this->Arcs.size());
    std::vector<std::int64_t> fill(out.Start.begin(), out.Start.end() - 1);
    for (const auto& arc : this->Arcs)
    {
      const auto i = ToIndex(fill[ToIndex(std::get<0>(arc))]++);
      out.Target[i] = std::get<1>(arc);
      out.Class[i] = std::get<2>(arc);
    }
  }

  const AdjacencyRules& Rules;
  const SynthesisOptions& Options;
  std::unique_ptr<SymmetryPlan> Plan;
  const int K;
  std::vector<std::function<bool(int, int)>> Relations;
  std::map<std::tuple<int, int, int>, int> RelationIndex;
  std::vector<const LabelMap*> Maps; ///< every map, for the boundary check
  std::vector<std::string> MapNames;
  std::vector<std::tuple<std::int64_t, std::int64_t, int>> Arcs;
};
} // namespace

std::unique_ptr<SymmetryPlan> PlanSymmetry(
  const AdjacencyRules& rules, const SynthesisOptions& options)
{
  return SymmetryPlanner(rules, options).Build();
}

} // namespace detail
} // namespace msynth
