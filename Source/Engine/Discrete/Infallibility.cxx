// SPDX-License-Identifier: BSD-3-Clause
#include "Discrete/Infallibility.h"

#include "Core/Error.h"
#include "Core/Index.h"

#include <algorithm>
#include <functional>
#include <string>
#include <unordered_set>
#include <vector>

namespace msynth
{

namespace
{
const char* const WholeModelAdvice =
  "whole-model synthesis in scan-line order (Algorithm 3.1) cannot fail and can produce every "
  "consistent model; other site orders may still fail";
const char* const BlockAdvice =
  "Algorithm 3.1 may fail on this example; use block synthesis (Algorithm 3.4, --block)";

/// The 2×2(×2) condition: every consistent placement of a new site's earlier corners.
InfallibilityReport AnalyzeCorners(const AdjacencyRules& rules,
  const std::array<std::int64_t, 3>& outputSize, std::int64_t maxConfigurations)
{
  InfallibilityReport report;
  const int k = rules.NumberOfLabels();
  std::vector<int> axes;
  for (int a = 0; a < 3; ++a)
    if (outputSize[a] > 1)
      axes.push_back(a);
  const auto& values = rules.LabelValues();
  static const char* const axisName = "xyz";

  // Every situation of a new site: the set S of axes along which it has placed neighbours
  // (a site on the low faces of the model has fewer). Corners: offsets in {0, -1}^S but 0.
  const int m = static_cast<int>(axes.size());
  for (int subset = 1; subset < (1 << m) && !report.Exhausted; ++subset)
  {
    std::vector<int> active;
    for (int i = 0; i < m; ++i)
      if (subset & (1 << i))
        active.push_back(axes[ToIndex(i)]);
    const int n = static_cast<int>(active.size());
    // Corner c (bits over `active`: bit i set = offset -1 along active[i]); c = 0 is p itself.
    std::vector<int> label(ToIndex(1 << n), -1);
    bool failed = false;
    // Corners are filled in decreasing bit order so each one's lower neighbours come first.
    std::function<void(int)> place = [&](int corner)
    {
      if (failed || report.Exhausted)
        return;
      if (corner == 0)
      {
        ++report.Configurations;
        if (report.Configurations > maxConfigurations)
        {
          report.Exhausted = true;
          return;
        }
        // Is there a label at p next to its placed neighbours (corner with one bit set)?
        for (int d = 0; d < k; ++d)
        {
          bool ok = true;
          for (int i = 0; i < n && ok; ++i)
            ok = rules.Allowed(2 * active[ToIndex(i)], label[ToIndex(1 << i)], d);
          if (ok)
            return;
        }
        failed = true;
        std::string where;
        for (int c = (1 << n) - 1; c > 0; --c)
        {
          where += where.empty() ? "" : ", ";
          std::string offset = "(";
          for (int i = 0; i < n; ++i)
            offset +=
              std::string(i ? " " : "") + ((c >> i) & 1 ? "-" : "0") + axisName[active[ToIndex(i)]];
          where += offset + ")=" + std::to_string(values[ToIndex(label[ToIndex(c)])]);
        }
        report.Explanation = "no label fits a site whose placed neighbours are " + where;
        return;
      }
      for (int b = 0; b < k && !failed && !report.Exhausted; ++b)
      {
        // Consistent with the corners one step further along each axis (already placed).
        bool ok = true;
        for (int i = 0; i < n && ok; ++i)
        {
          if (corner & (1 << i))
            continue;
          const int further = corner | (1 << i);
          if (further < (1 << n) && label[ToIndex(further)] >= 0)
            ok = rules.Allowed(2 * active[ToIndex(i)], label[ToIndex(further)], b);
        }
        if (!ok)
          continue;
        label[ToIndex(corner)] = b;
        place(corner - 1);
        label[ToIndex(corner)] = -1;
      }
    };
    place((1 << n) - 1);
    if (failed)
      break;
  }
  report.Proved = report.Explanation.empty() && !report.Exhausted;
  if (report.Proved)
    report.Explanation = "every one of " + std::to_string(report.Configurations) +
      " consistent placements of a site's earlier neighbours in its 2x2" + (m == 3 ? "x2" : "") +
      " region leaves a label for it (Algorithm 3.6 cannot fail; Theorem 3.3.6)";
  else if (report.Exhausted)
    report.Explanation =
      "the enumeration stopped after " + std::to_string(maxConfigurations) + " configurations";
  report.Recommendation = report.Proved ? WholeModelAdvice : BlockAdvice;
  return report;
}

/// Window states of Algorithm 3.6 on 2D outputs (see Infallibility.h).
class RegionAnalysis
{
public:
  RegionAnalysis(const AdjacencyRules& rules, const std::array<int, 2>& axes, int rx, int ry)
    : Rules(rules)
    , K(rules.NumberOfLabels())
    , Rx(rx)
    , Ry(ry)
    , Axes(axes)
  {
    this->All = this->K == 64 ? ~std::uint64_t(0) : (std::uint64_t(1) << this->K) - 1;
  }

  InfallibilityReport Run(std::int64_t maxStates)
  {
    InfallibilityReport report;
    report.Region = { { 2, 2, 2 } };
    report.Region[ToIndex(this->Axes[0])] = this->Rx;
    report.Region[ToIndex(this->Axes[1])] = this->Ry;
    const std::string none(ToIndex(this->Rx), Nothing);
    for (int r = 0; r <= this->Rx - 1; ++r)
      for (int u = 0; u <= this->Ry - 1; ++u)
        this->Add(none, none, r, u);
    // Sweep until neither states nor row windows grow: windows found late can open new
    // transitions from states already expanded.
    for (bool grew = true; grew && this->Failure.empty();)
    {
      const std::size_t states = this->States.size(), windows = this->Windows.size();
      for (std::size_t i = 0; i < this->States.size() && this->Failure.empty(); ++i)
      {
        if (static_cast<std::int64_t>(this->States.size()) > maxStates)
        {
          report.Exhausted = true;
          break;
        }
        this->Expand(this->States[i]);
      }
      if (report.Exhausted)
        break;
      grew = this->States.size() != states || this->Windows.size() != windows;
    }
    report.Configurations = static_cast<std::int64_t>(this->States.size());
    const std::string region = std::to_string(this->Rx) + "x" + std::to_string(this->Ry);
    report.Proved = this->Failure.empty() && !report.Exhausted;
    if (report.Proved)
      report.Explanation = "with " + region + " regions, none of the " +
        std::to_string(this->States.size()) +
        " reachable window states of Algorithm 3.6 leaves a site without a label (Algorithm 3.6 "
        "cannot fail; Theorem 3.3.6)";
    else if (report.Exhausted)
      report.Explanation = "with " + region + " regions, the enumeration stopped after " +
        std::to_string(maxStates) + " window states";
    else
      report.Explanation = "with " + region + " regions, " + this->Failure;
    report.Recommendation = report.Proved ? WholeModelAdvice : BlockAdvice;
    return report;
  }

private:
  static constexpr char Nothing = -1;

  // A state: the row below at offsets -1..Rx-2, the current row's last Rx labels, the sites
  // right of p (capped at Rx - 1) and the rows above (capped at Ry - 1).
  struct State
  {
    std::string Below, Recent;
    int Right = 0, Above = 0;
  };

  void Add(const std::string& below, const std::string& recent, int right, int above)
  {
    // A row below shows where its row ends, which is where this row ends too.
    if (below[1] != Nothing)
      for (int j = 1; j <= this->Rx - 2; ++j)
        if ((j <= right) != (below[ToIndex(j + 1)] != Nothing))
          return;
    std::string key = below + recent;
    key.push_back(static_cast<char>(right));
    key.push_back(static_cast<char>(above));
    if (this->Seen.insert(key).second)
      this->States.push_back({ below, recent, right, above });
  }

  void AddWindow(const std::string& w)
  {
    if (this->Windows.insert(w).second)
      this->Prefixes.insert(w.substr(0, ToIndex(this->Rx)));
  }

  /// Labels still possible at p after propagation inside the window (0: Algorithm 3.6 fails).
  std::uint64_t Catalog(const State& s) const
  {
    const int w = this->Rx, h = this->Ry; // columns dx = -1..Rx-2, rows dy = -1..Ry-2
    std::vector<std::uint64_t> dom(ToIndex(w * h), 0);
    std::vector<char> exists(ToIndex(w * h), 0), fixed(dom.size(), 0);
    const bool left = s.Recent.back() != Nothing;
    for (int row = 0; row < h; ++row)
      for (int col = 0; col < w; ++col)
      {
        const auto i = ToIndex(col + w * row);
        const int dx = col - 1, dy = row - 1;
        if (dy == -1)
        {
          const char b = s.Below[ToIndex(col)];
          exists[i] = b != Nothing;
          fixed[i] = 1;
          dom[i] = exists[i] ? std::uint64_t(1) << b : 0;
        }
        else if (dy == 0 && dx == -1)
        {
          exists[i] = left;
          fixed[i] = 1;
          dom[i] = left ? std::uint64_t(1) << s.Recent.back() : 0;
        }
        else
        {
          exists[i] = (dx == -1 ? left : dx <= s.Right) && dy <= s.Above;
          dom[i] = exists[i] ? this->All : 0;
        }
      }
    for (bool changed = true; changed;)
    {
      changed = false;
      for (int row = 0; row < h; ++row)
        for (int col = 0; col < w; ++col)
        {
          const auto i = ToIndex(col + w * row);
          if (!exists[i] || fixed[i])
            continue;
          const int step[4][2] = { { -1, 0 }, { 1, 0 }, { 0, -1 }, { 0, 1 } };
          for (const auto& st : step)
          {
            const int c = col + st[0], r = row + st[1];
            if (c < 0 || r < 0 || c >= w || r >= h)
              continue;
            const auto j = ToIndex(c + w * r);
            if (!exists[j])
              continue;
            // Direction from the neighbour j to i.
            const int axis = this->Axes[st[0] != 0 ? 0 : 1];
            const int d = 2 * axis + ((st[0] + st[1]) < 0 ? 0 : 1);
            std::uint64_t allowed = 0;
            for (std::uint64_t bits = dom[j]; bits; bits &= bits - 1)
              allowed |= this->Rules.Compatible(d, __builtin_ctzll(bits))[0];
            if ((dom[i] & allowed) != dom[i])
            {
              dom[i] &= allowed;
              changed = true;
              if (!dom[i])
                return 0;
            }
          }
        }
    }
    return dom[ToIndex(1 + w * 1)];
  }

  void Expand(const State s)
  {
    const std::uint64_t choices = this->Catalog(s);
    if (!choices)
    {
      this->Failure = "no label fits a site whose row below reads " + this->Show(s.Below) +
        " (from one site left of it) and whose left neighbour is " +
        this->Show(s.Recent.substr(s.Recent.size() - 1));
      return;
    }
    const bool firstRow = s.Below[1] == Nothing;
    const std::string none(ToIndex(this->Rx), Nothing);
    for (std::uint64_t bits = choices; bits; bits &= bits - 1)
    {
      const char e = static_cast<char>(__builtin_ctzll(bits));
      std::string window = s.Recent + e;
      this->AddWindow(window);
      const std::string recent = window.substr(1);
      if (s.Right > 0)
      {
        std::vector<std::string> below;
        if (firstRow)
          below.push_back(none);
        else if (this->Prefixes.count(s.Below))
          for (int c = -1; c < this->K; ++c)
            if (this->Windows.count(s.Below + static_cast<char>(c)))
              below.push_back(s.Below.substr(1) + static_cast<char>(c));
        for (const auto& b : below)
        {
          this->Add(b, recent, s.Right - 1, s.Above);
          if (s.Right == this->Rx - 1)
            this->Add(b, recent, s.Right, s.Above);
        }
        continue;
      }
      // The row ends: its last windows run past the end.
      for (int j = 1; j <= this->Rx; ++j)
      {
        window.push_back(Nothing);
        this->AddWindow(window.substr(window.size() - ToIndex(this->Rx + 1)));
      }
      if (s.Above == 0)
        continue; // the last row
      std::vector<int> above{ s.Above - 1 };
      if (s.Above == this->Ry - 1)
        above.push_back(s.Above);
      for (const auto& w : this->Windows)
        if (w[0] == Nothing && w[1] != Nothing)
          for (int u : above)
            for (int r = 0; r <= this->Rx - 1; ++r)
              this->Add(w.substr(0, ToIndex(this->Rx)), none, r, u);
    }
  }

  std::string Show(const std::string& labels) const
  {
    std::string out;
    for (char b : labels)
      out += (out.empty() ? "" : " ") +
        (b == Nothing ? std::string("-") : std::to_string(this->Rules.LabelValues()[ToIndex(b)]));
    return out;
  }

  const AdjacencyRules& Rules;
  const int K, Rx, Ry;
  const std::array<int, 2> Axes;
  std::uint64_t All = 0;
  std::vector<State> States;
  std::unordered_set<std::string> Seen, Windows, Prefixes;
  std::string Failure;
};
} // namespace

InfallibilityReport AnalyzeRegion2D(const AdjacencyRules& rules, const std::array<int, 2>& axes,
  int rx, int ry, std::int64_t maxStates)
{
  if (rules.NumberOfLabels() > 64)
    throw Error("regions larger than 2x2 are analyzed for at most 64 labels");
  if (rx < 2 || ry < 2 || rx > 6 || ry > 6)
    throw Error("region sizes must be between 2 and 6");
  return RegionAnalysis(rules, axes, rx, ry).Run(maxStates);
}

InfallibilityReport AnalyzeInfallibility(const AdjacencyRules& rules,
  const std::array<std::int64_t, 3>& outputSize, std::int64_t maxConfigurations, int maxRegion)
{
  InfallibilityReport report = AnalyzeCorners(rules, outputSize, maxConfigurations);
  std::array<int, 2> axes{ { -1, -1 } };
  int m = 0;
  for (int a = 0; a < 3; ++a)
    if (outputSize[a] > 1)
    {
      if (m < 2)
        axes[ToIndex(m)] = a;
      ++m;
    }
  if (report.Proved || m != 2 || rules.NumberOfLabels() > 64)
    return report;
  const std::string corners = report.Explanation;
  // Larger regions, smallest first: wider before taller (the scan runs along the first axis).
  for (int area = 5; area <= maxRegion * maxRegion; ++area)
    for (int rx = maxRegion; rx >= 2; --rx)
    {
      const int ry = area / rx;
      if (rx * ry != area || ry < 2 || ry > maxRegion)
        continue;
      InfallibilityReport larger =
        AnalyzeRegion2D(rules, axes, rx, ry, std::min<std::int64_t>(maxConfigurations, 1000000));
      if (larger.Proved)
        return larger;
      report = larger;
    }
  if (report.Region != std::array<int, 3>{ { 2, 2, 2 } })
    report.Explanation = "2x2: " + corners + "; " + report.Explanation;
  return report;
}

} // namespace msynth
