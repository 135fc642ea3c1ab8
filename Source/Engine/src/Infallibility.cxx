// SPDX-License-Identifier: BSD-3-Clause
#include "msynth/Infallibility.h"

#include <functional>
#include <vector>

namespace msynth
{

InfallibilityReport AnalyzeInfallibility(const AdjacencyRules& rules,
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
        active.push_back(axes[static_cast<std::size_t>(i)]);
    const int n = static_cast<int>(active.size());
    // Corner c (bits over `active`: bit i set = offset -1 along active[i]); c = 0 is p itself.
    std::vector<int> label(static_cast<std::size_t>(1 << n), -1);
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
            ok = rules.Allowed(
              2 * active[static_cast<std::size_t>(i)], label[static_cast<std::size_t>(1 << i)], d);
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
            offset += std::string(i ? " " : "") + ((c >> i) & 1 ? "-" : "0") +
              axisName[active[static_cast<std::size_t>(i)]];
          where += offset + ")=" +
            std::to_string(values[static_cast<std::size_t>(label[static_cast<std::size_t>(c)])]);
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
          if (further < (1 << n) && label[static_cast<std::size_t>(further)] >= 0)
            ok = rules.Allowed(
              2 * active[static_cast<std::size_t>(i)], label[static_cast<std::size_t>(further)], b);
        }
        if (!ok)
          continue;
        label[static_cast<std::size_t>(corner)] = b;
        place(corner - 1);
        label[static_cast<std::size_t>(corner)] = -1;
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
  report.Recommendation = report.Proved
    ? "whole-model synthesis in scan-line order (Algorithm 3.1) cannot fail and can produce every "
      "consistent model; other site orders may still fail"
    : "Algorithm 3.1 may fail on this example; use block synthesis (Algorithm 3.4, --block)";
  return report;
}

} // namespace msynth
