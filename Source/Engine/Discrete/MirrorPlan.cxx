// SPDX-License-Identifier: BSD-3-Clause
#include "Discrete/MirrorPlan.h"

#include "Core/Error.h"
#include "Core/Index.h"

#include <string>

namespace msynth
{
namespace detail
{

bool AnyMirror(const SynthesisOptions& options)
{
  return options.Symmetry[0].Enabled || options.Symmetry[1].Enabled || options.Symmetry[2].Enabled;
}

MirrorPlan PlanMirror(const AdjacencyRules& rules, const SynthesisOptions& options)
{
  MirrorPlan plan;
  plan.Full = options.Size;
  plan.HalfOptions = options;
  const int k = rules.NumberOfLabels();
  const auto& values = rules.LabelValues();
  static const char* const axisName = "xyz";
  for (int a = 0; a < 3; ++a)
  {
    const Mirror& mirror = options.Symmetry[ToIndex(a)];
    plan.HalfOptions.Symmetry[ToIndex(a)].Enabled = false;
    if (!mirror.Enabled)
      continue;
    const std::string axis(1, axisName[a]);
    plan.Axes[ToIndex(a)] = true;
    auto& f = plan.F[ToIndex(a)];
    f.resize(ToIndex(k));
    for (int b = 0; b < k; ++b)
      f[ToIndex(b)] = b;
    for (const auto& kv : mirror.Map)
    {
      const int from = rules.IndexOf(kv.first), to = rules.IndexOf(kv.second);
      if (from < 0 || to < 0)
        throw Error("the mirror map along " + axis + " names label " +
          std::to_string(from < 0 ? kv.first : kv.second) +
          ", which does not occur in the example");
      f[ToIndex(from)] = to;
    }
    for (int b = 0; b < k; ++b)
      if (f[ToIndex(f[ToIndex(b)])] != b)
        throw Error("the mirror map along " + axis + " is not its own inverse: label " +
          std::to_string(values[ToIndex(b)]) + " maps to " +
          std::to_string(values[ToIndex(f[ToIndex(b)])]) + ", which does not map back");
    // The rules must be symmetric under f (else a mirrored model breaks them).
    for (int axis2 = 0; axis2 < 3; ++axis2)
      for (int b = 0; b < k; ++b)
        for (int c = 0; c < k; ++c)
        {
          const int fb = f[ToIndex(b)], fc = f[ToIndex(c)];
          const bool mirrored =
            axis2 == a ? rules.Allowed(2 * axis2, fc, fb) : rules.Allowed(2 * axis2, fb, fc);
          if (rules.Allowed(2 * axis2, b, c) != mirrored)
            throw Error("the example is not symmetric under the mirror map along " + axis +
              ": label " + std::to_string(values[ToIndex(b)]) + " before " +
              std::to_string(values[ToIndex(c)]) + " along " + axisName[axis2] +
              (rules.Allowed(2 * axis2, b, c) ? " occurs" : " does not occur") +
              " but its mirror image " + (mirrored ? "does" : "does not"));
        }
    // The half, and the labels allowed on its last layer next to their own mirror image.
    const std::int64_t n = options.Size[a];
    plan.Half[a] = (n + 1) / 2;
    auto& mask = plan.ColumnMask[ToIndex(a)];
    mask.assign(ToIndex(rules.Words()), 0);
    bool any = false;
    for (int b = 0; b < k; ++b)
    {
      const bool ok = (n % 2 == 1) ? f[ToIndex(b)] == b : rules.Allowed(2 * a, b, f[ToIndex(b)]);
      if (ok || n == 1)
      {
        mask[ToIndex(b / 64)] |= std::uint64_t(1) << (b % 64);
        any = true;
      }
    }
    if (!any)
      throw Error("no label can lie on the mirror plane along " + axis +
        (n % 2 == 1 ? " (an odd size puts sites on the plane, and no label is its own mirror image)"
                    : " (no label may be followed by its mirror image)"));
    // Boundary faces: the far face is the mirror image of the near one.
    auto& near = plan.HalfOptions.Boundary[ToIndex(2 * a)];
    auto& far = plan.HalfOptions.Boundary[ToIndex(2 * a + 1)];
    if (near && far && rules.IndexOf(*near) >= 0 && rules.IndexOf(*far) >= 0 &&
      f[ToIndex(rules.IndexOf(*near))] != rules.IndexOf(*far))
      throw Error("with symmetry along " + axis +
        ", the boundary label of the far face must be "
        "the mirror image of the near face's");
    if (!near && far)
      near = values[ToIndex(f[ToIndex(rules.IndexOf(*far) < 0 ? 0 : rules.IndexOf(*far))])];
    far.reset();
  }
  for (int a = 0; a < 3; ++a)
    if (!plan.Axes[ToIndex(a)])
      plan.Half[a] = options.Size[a];
  for (int a = 0; a < 3; ++a)
    for (int c = a + 1; c < 3; ++c)
      if (plan.Axes[ToIndex(a)] && plan.Axes[ToIndex(c)])
        for (int b = 0; b < k; ++b)
          if (plan.Image(plan.Image(b, 1 << a), 1 << c) !=
            plan.Image(plan.Image(b, 1 << c), 1 << a))
            throw Error(std::string("the mirror maps along ") + axisName[a] + " and " +
              axisName[c] + " do not commute (label " + std::to_string(values[ToIndex(b)]) + ")");
  plan.HalfOptions.Size = plan.Half;
  return plan;
}

} // namespace detail
} // namespace msynth
