// SPDX-License-Identifier: BSD-3-Clause
#include "Continuous/Neighbourhood.h"

#include "Core/Error.h"

#include <algorithm>
#include <cmath>
#include <set>

namespace msynth
{

namespace
{

WideVec3 Widen(const IntVec3& v)
{
  return { v[0], v[1], v[2] };
}

WideVec3 Cross(const WideVec3& a, const WideVec3& b)
{
  return { a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0] };
}

__int128 Dot(const WideVec3& a, const WideVec3& b)
{
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

int Sign(__int128 v)
{
  return v > 0 ? 1 : (v < 0 ? -1 : 0);
}

bool IsZero(const WideVec3& v)
{
  return v[0] == 0 && v[1] == 0 && v[2] == 0;
}

__int128 Gcd(__int128 a, __int128 b)
{
  a = a < 0 ? -a : a;
  b = b < 0 ? -b : b;
  while (b != 0)
  {
    const __int128 t = a % b;
    a = b;
    b = t;
  }
  return a;
}

/// Divides a ray by the gcd of its components so sums of rays stay far from overflow.
WideVec3 Reduced(const WideVec3& v)
{
  const __int128 g = Gcd(Gcd(v[0], v[1]), v[2]);
  if (g <= 1)
  {
    return v;
  }
  return { v[0] / g, v[1] / g, v[2] / g };
}

WideVec3 Negated(const WideVec3& v)
{
  return { -v[0], -v[1], -v[2] };
}

/// The rays of the spherical arrangement of planes through the origin with @p normals (of the
/// given @p rank), each with its opposite: each cone's closure is spanned by the rays it
/// contains, so the sum of those rays is interior exactly when the cone exists.
std::vector<WideVec3> ArrangementRays(const std::vector<WideVec3>& normals, int rank)
{
  std::vector<WideVec3> rays;
  auto addRay = [&rays](const WideVec3& r)
  {
    const WideVec3 reduced = Reduced(r);
    rays.push_back(reduced);
    rays.push_back(Negated(reduced));
  };
  const int s = static_cast<int>(normals.size());
  if (rank == 1)
  {
    addRay(normals[0]);
  }
  else if (rank == 2)
  {
    const WideVec3 line = Reduced(Cross(normals[0], normals[1]));
    for (const auto& n : normals)
    {
      addRay(Cross(n, line));
    }
  }
  else if (rank == 3)
  {
    for (int a = 0; a < s; ++a)
    {
      for (int b = a + 1; b < s; ++b)
      {
        addRay(Cross(normals[a], normals[b]));
      }
    }
  }
  return rays;
}

} // namespace

// ---------------------------------------------------------------------------------------------
PlaneFamilySet::PlaneFamilySet(std::vector<IntVec3> normals)
  : Normals(std::move(normals))
{
  constexpr std::int64_t limit = std::int64_t(1) << 40;
  for (std::size_t i = 0; i < this->Normals.size(); ++i)
  {
    const auto& n = this->Normals[i];
    if (n[0] == 0 && n[1] == 0 && n[2] == 0)
    {
      throw Error("plane family h" + std::to_string(i + 1) + " has a zero normal");
    }
    for (auto c : n)
    {
      if (c > limit || c < -limit)
      {
        throw Error("plane family h" + std::to_string(i + 1) +
          " has a normal component beyond 2^40; snap normals to smaller integers");
      }
    }
    for (std::size_t j = 0; j < i; ++j)
    {
      if (IsZero(Cross(Widen(n), Widen(this->Normals[j]))))
      {
        throw Error("plane families h" + std::to_string(j + 1) + " and h" + std::to_string(i + 1) +
          " are parallel; they must be one family");
      }
    }
  }
}

int PlaneFamilySet::Side(int family, const IntVec3& d) const
{
  return Sign(Dot(Widen(this->Normals.at(family)), Widen(d)));
}

int PlaneFamilySet::Rank(const std::vector<int>& families) const
{
  if (families.empty())
  {
    return 0;
  }
  if (families.size() == 1)
  {
    return 1;
  }
  // Distinct families are never parallel, so two give rank 2; look for an independent third.
  const WideVec3 axis =
    Cross(Widen(this->Normals.at(families[0])), Widen(this->Normals.at(families[1])));
  for (std::size_t k = 2; k < families.size(); ++k)
  {
    if (Dot(axis, Widen(this->Normals.at(families[k]))) != 0)
    {
      return 3;
    }
  }
  return 2;
}

const std::vector<PlaneFamilySet::Cone>& PlaneFamilySet::Cones(
  const std::vector<int>& families) const
{
  auto found = this->ConeCache.find(families);
  if (found != this->ConeCache.end())
  {
    return found->second;
  }
  const int s = static_cast<int>(families.size());
  if (s > MaxFamiliesPerLabel)
  {
    throw Error(std::to_string(s) + " plane families meet at one point; at most " +
      std::to_string(MaxFamiliesPerLabel) + " are supported");
  }
  std::vector<WideVec3> normals;
  for (int f : families)
  {
    normals.push_back(Widen(this->Normals.at(f)));
  }
  // The rays of the spherical arrangement: each cone's closure is spanned by
  // the rays it contains, so the sum of those rays is interior exactly when the cone exists.
  const std::vector<WideVec3> rays = ArrangementRays(normals, this->Rank(families));
  std::vector<std::vector<int>> raySigns(rays.size(), std::vector<int>(s));
  for (std::size_t r = 0; r < rays.size(); ++r)
  {
    for (int j = 0; j < s; ++j)
    {
      raySigns[r][j] = Sign(Dot(normals[j], rays[r]));
    }
  }
  std::vector<Cone> cones;
  if (s == 0)
  {
    Cone only;
    only.Direction = { 0, 0, 1 };
    only.UnitDirection = { 0, 0, 1 };
    cones.push_back(only);
  }
  for (unsigned mask = 0; s > 0 && mask < (1u << s); ++mask)
  {
    WideVec3 sum{ 0, 0, 0 };
    for (std::size_t r = 0; r < rays.size(); ++r)
    {
      bool inClosure = true;
      for (int j = 0; j < s && inClosure; ++j)
      {
        const int want = (mask >> j) & 1u ? 1 : -1;
        inClosure = raySigns[r][j] == 0 || raySigns[r][j] == want;
      }
      if (inClosure)
      {
        for (int c = 0; c < 3; ++c)
        {
          sum[c] += rays[r][c];
        }
      }
    }
    bool strict = !IsZero(sum);
    for (int j = 0; j < s && strict; ++j)
    {
      strict = Sign(Dot(normals[j], sum)) == ((mask >> j) & 1u ? 1 : -1);
    }
    if (strict)
    {
      Cone cone;
      cone.Mask = mask;
      cone.Direction = sum;
      const double x = static_cast<double>(sum[0]);
      const double y = static_cast<double>(sum[1]);
      const double z = static_cast<double>(sum[2]);
      const double length = std::sqrt(x * x + y * y + z * z);
      cone.UnitDirection = { x / length, y / length, z / length };
      cones.push_back(cone);
    }
  }
  return this->ConeCache.emplace(families, std::move(cones)).first->second;
}

// ---------------------------------------------------------------------------------------------
const char* FeatureKindName(FeatureKind kind, bool planar)
{
  switch (kind)
  {
    case FeatureKind::Volume:
      return planar ? "region" : "volume";
    case FeatureKind::Face:
      return planar ? "edge" : "face";
    case FeatureKind::Edge:
      return planar ? "vertex" : "edge";
    case FeatureKind::Vertex:
      return "vertex";
  }
  return "?";
}

NeighbourhoodLabel NeighbourhoodLabel::Constant(int type)
{
  NeighbourhoodLabel label;
  label.Types = { static_cast<std::int16_t>(type) };
  return label;
}

NeighbourhoodLabel NeighbourhoodLabel::FromFunction(const PlaneFamilySet& set,
  std::vector<int> families, const std::function<int(const PlaneFamilySet::Cone&)>& typeOfCone)
{
  std::sort(families.begin(), families.end());
  families.erase(std::unique(families.begin(), families.end()), families.end());
  NeighbourhoodLabel label;
  label.Types.assign(std::size_t(1) << families.size(), -1);
  for (const auto& cone : set.Cones(families))
  {
    const int type = typeOfCone(cone);
    if (type < 0 || type > 32767)
    {
      throw Error("object type " + std::to_string(type) + " is out of range 0..32767");
    }
    label.Types[cone.Mask] = static_cast<std::int16_t>(type);
  }
  label.Families = std::move(families);
  label.Canonicalize();
  return label;
}

void NeighbourhoodLabel::Canonicalize()
{
  bool dropped = true;
  while (dropped)
  {
    dropped = false;
    const std::size_t s = this->Families.size();
    for (std::size_t j = 0; j < s && !dropped; ++j)
    {
      const unsigned bit = 1u << j;
      bool droppable = true;
      for (unsigned m = 0; m < this->Types.size() && droppable; ++m)
      {
        if (m & bit)
        {
          continue;
        }
        const int a = this->Types[m];
        const int b = this->Types[m | bit];
        droppable = a < 0 || b < 0 || a == b;
      }
      if (!droppable)
      {
        continue;
      }
      std::vector<std::int16_t> merged(this->Types.size() / 2, -1);
      for (unsigned t = 0; t < merged.size(); ++t)
      {
        const unsigned low = t & (bit - 1);
        const unsigned m = ((t & ~(bit - 1)) << 1) | low;
        merged[t] = this->Types[m] >= 0 ? this->Types[m] : this->Types[m | bit];
      }
      this->Types = std::move(merged);
      this->Families.erase(this->Families.begin() + static_cast<std::ptrdiff_t>(j));
      dropped = true;
    }
  }
}

NeighbourhoodLabel NeighbourhoodLabel::Evaluate(const PlaneFamilySet& set, const IntVec3& d) const
{
  NeighbourhoodLabel out;
  std::vector<int> keep; // positions in this->Families still through the new point
  unsigned fixedBits = 0;
  for (std::size_t j = 0; j < this->Families.size(); ++j)
  {
    const int side = set.Side(this->Families[j], d);
    if (side == 0)
    {
      keep.push_back(static_cast<int>(j));
      out.Families.push_back(this->Families[j]);
    }
    else if (side > 0)
    {
      fixedBits |= 1u << j;
    }
  }
  out.Types.assign(std::size_t(1) << keep.size(), -1);
  for (unsigned t = 0; t < out.Types.size(); ++t)
  {
    unsigned m = fixedBits;
    for (std::size_t k = 0; k < keep.size(); ++k)
    {
      if ((t >> k) & 1u)
      {
        m |= 1u << keep[k];
      }
    }
    out.Types[t] = this->Types[m];
  }
  out.Canonicalize();
  return out;
}

FeatureKind NeighbourhoodLabel::Kind(const PlaneFamilySet& set) const
{
  return static_cast<FeatureKind>(set.Rank(this->Families));
}

std::vector<int> NeighbourhoodLabel::TypesPresent() const
{
  std::set<int> present;
  for (auto t : this->Types)
  {
    if (t >= 0)
    {
      present.insert(t);
    }
  }
  return { present.begin(), present.end() };
}

bool NeighbourhoodLabel::operator<(const NeighbourhoodLabel& o) const
{
  if (this->Families != o.Families)
  {
    return this->Families < o.Families;
  }
  return this->Types < o.Types;
}

std::string NeighbourhoodLabel::Expression(bool planar) const
{
  const std::string full = planar ? "ℝ²" : "ℝ³";
  std::vector<int> nonEmpty;
  for (int t : this->TypesPresent())
  {
    if (t > 0)
    {
      nonEmpty.push_back(t);
    }
  }
  if (nonEmpty.empty())
  {
    return "∅";
  }
  std::vector<std::string> names;
  for (int f : this->Families)
  {
    names.push_back("h" + std::to_string(f + 1));
  }
  const int s = static_cast<int>(this->Families.size());
  std::vector<std::string> parts;
  for (int type : nonEmpty)
  {
    std::vector<bool> on(this->Types.size()), dontCare(this->Types.size());
    bool all = true;
    for (std::size_t m = 0; m < this->Types.size(); ++m)
    {
      on[m] = this->Types[m] == type;
      dontCare[m] = this->Types[m] < 0;
      all = all && (on[m] || dontCare[m]);
    }
    const std::string expression = all ? full : MinimizedExpression(s, on, dontCare, names);
    if (nonEmpty.size() == 1 && type == 1)
    {
      return expression;
    }
    const bool compound = expression.find(' ') != std::string::npos;
    parts.push_back(std::to_string(type) + "·" + (compound ? "(" + expression + ")" : expression));
  }
  std::string joined;
  for (const auto& p : parts)
  {
    joined += (joined.empty() ? "" : " + ") + p;
  }
  return joined;
}

bool CompatibleAlong(const PlaneFamilySet& set, const NeighbourhoodLabel& a,
  const NeighbourhoodLabel& b, const IntVec3& d)
{
  const IntVec3 back{ -d[0], -d[1], -d[2] };
  return a.Evaluate(set, d) == b.Evaluate(set, back);
}

// ---------------------------------------------------------------------------------------------
// Quine–McCluskey minimization with don't-cares, then factoring by the most shared literal.
namespace
{

struct Implicant
{
  unsigned Value = 0; ///< fixed bits (only where Free is 0)
  unsigned Free = 0;  ///< bits that may be anything
  bool operator<(const Implicant& o) const
  {
    return this->Free != o.Free ? this->Free < o.Free : this->Value < o.Value;
  }
  bool operator==(const Implicant& o) const
  {
    return this->Free == o.Free && this->Value == o.Value;
  }
  bool Covers(unsigned m) const { return (m & ~this->Free) == this->Value; }
};

/// A literal: variable and polarity (true ⇔ h_j, minterm bit 0).
using Literal = std::pair<int, bool>;
using Term = std::vector<Literal>;

std::string LiteralText(const Literal& l, const std::vector<std::string>& names)
{
  return names[l.first] + (l.second ? "" : "ᶜ");
}

std::vector<std::string> Factor(std::vector<Term> terms, const std::vector<std::string>& names);

std::string Group(const std::vector<std::string>& disjuncts)
{
  std::string s;
  for (const auto& d : disjuncts)
  {
    s += (s.empty() ? "" : " ∪ ") + d;
  }
  return disjuncts.size() > 1 ? "(" + s + ")" : s;
}

/// The top-level disjuncts of a factored sum of products, each already parenthesized where a
/// union would need it.
std::vector<std::string> Factor(std::vector<Term> terms, const std::vector<std::string>& names)
{
  std::map<Literal, int> count;
  for (const auto& t : terms)
  {
    for (const auto& l : t)
    {
      ++count[l];
    }
  }
  Literal best{ -1, true };
  int bestCount = 1;
  for (const auto& [l, c] : count)
  {
    if (c > bestCount || (c == bestCount && c > 1 && l.first > best.first))
    {
      best = l;
      bestCount = c;
    }
  }
  std::vector<std::string> out;
  if (best.first < 0)
  {
    for (const auto& t : terms)
    {
      std::string s;
      for (const auto& l : t)
      {
        s += (s.empty() ? "" : " ∩ ") + LiteralText(l, names);
      }
      out.push_back(t.size() > 1 && terms.size() > 1 ? "(" + s + ")" : s);
    }
  }
  else
  {
    std::vector<Term> with, without;
    for (auto& t : terms)
    {
      auto it = std::find(t.begin(), t.end(), best);
      if (it == t.end())
      {
        without.push_back(t);
      }
      else
      {
        t.erase(it);
        with.push_back(t);
      }
    }
    const std::string product = LiteralText(best, names) + " ∩ " + Group(Factor(with, names));
    out.push_back(without.empty() ? product : "(" + product + ")");
    if (!without.empty())
    {
      for (auto& d : Factor(without, names))
      {
        const bool needsParens = d.find(" ∩ ") != std::string::npos && d.front() != '(';
        out.push_back(needsParens ? "(" + d + ")" : d);
      }
    }
  }
  std::sort(out.begin(), out.end());
  return out;
}

/// The prime implicants of the function whose on- and don't-care minterms are @p current
/// (Quine–McCluskey: merge implicants differing in one bit until none merge).
std::vector<Implicant> PrimeImplicants(std::set<Implicant> current)
{
  std::vector<Implicant> primes;
  while (!current.empty())
  {
    std::set<Implicant> next;
    std::set<Implicant> combined;
    for (auto a = current.begin(); a != current.end(); ++a)
    {
      for (auto b = std::next(a); b != current.end(); ++b)
      {
        if (a->Free != b->Free)
        {
          continue;
        }
        const unsigned diff = a->Value ^ b->Value;
        if (diff != 0 && (diff & (diff - 1)) == 0)
        {
          next.insert({ a->Value & ~diff, a->Free | diff });
          combined.insert(*a);
          combined.insert(*b);
        }
      }
    }
    for (const auto& i : current)
    {
      if (!combined.count(i))
      {
        primes.push_back(i);
      }
    }
    current = std::move(next);
  }
  return primes;
}

/// Primes that cover the on-set @p onMinterms: essential primes first, then greedily the prime
/// covering most of what is left (ties: more free bits, then order), which is exact for the
/// small functions labels give.
std::vector<Implicant> CoverOnSet(
  const std::vector<Implicant>& primes, const std::vector<unsigned>& onMinterms)
{
  std::vector<Implicant> chosen;
  std::set<unsigned> uncovered(onMinterms.begin(), onMinterms.end());
  for (unsigned m : onMinterms)
  {
    int coverCount = 0;
    const Implicant* only = nullptr;
    for (const auto& p : primes)
    {
      if (p.Covers(m))
      {
        ++coverCount;
        only = &p;
      }
    }
    if (coverCount == 1 && std::find(chosen.begin(), chosen.end(), *only) == chosen.end())
    {
      chosen.push_back(*only);
    }
  }
  for (const auto& c : chosen)
  {
    for (auto it = uncovered.begin(); it != uncovered.end();)
    {
      it = c.Covers(*it) ? uncovered.erase(it) : std::next(it);
    }
  }
  while (!uncovered.empty())
  {
    const Implicant* best = nullptr;
    std::size_t bestCover = 0;
    for (const auto& p : primes)
    {
      std::size_t cover = 0;
      for (unsigned m : uncovered)
      {
        cover += p.Covers(m) ? 1 : 0;
      }
      if (cover > bestCover ||
        (cover == bestCover && cover > 0 &&
          __builtin_popcount(p.Free) > __builtin_popcount(best->Free)))
      {
        best = &p;
        bestCover = cover;
      }
    }
    chosen.push_back(*best);
    for (auto it = uncovered.begin(); it != uncovered.end();)
    {
      it = best->Covers(*it) ? uncovered.erase(it) : std::next(it);
    }
  }
  return chosen;
}

} // namespace

std::string MinimizedExpression(int numberOfVariables, const std::vector<bool>& on,
  const std::vector<bool>& dontCare, const std::vector<std::string>& names)
{
  const unsigned size = 1u << numberOfVariables;
  std::set<Implicant> current;
  std::vector<unsigned> onMinterms;
  for (unsigned m = 0; m < size; ++m)
  {
    if (on[m] || dontCare[m])
    {
      current.insert({ m, 0 });
    }
    if (on[m])
    {
      onMinterms.push_back(m);
    }
  }
  if (onMinterms.empty())
  {
    return "∅";
  }
  const std::vector<Implicant> primes = PrimeImplicants(std::move(current));
  // Cover the on-set: essential primes first, then greedily (see CoverOnSet).
  const std::vector<Implicant> chosen = CoverOnSet(primes, onMinterms);
  std::vector<Term> terms;
  for (const auto& c : chosen)
  {
    Term t;
    for (int j = 0; j < numberOfVariables; ++j)
    {
      if (!((c.Free >> j) & 1u))
      {
        t.emplace_back(j, !((c.Value >> j) & 1u));
      }
    }
    terms.push_back(t);
  }
  std::vector<std::string> disjuncts = Factor(terms, names);
  std::string s;
  for (const auto& d : disjuncts)
  {
    s += (s.empty() ? "" : " ∪ ") + d;
  }
  return s;
}

} // namespace msynth
