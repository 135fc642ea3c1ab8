// SPDX-License-Identifier: BSD-3-Clause
// The render grids of a label volume (VDB/RenderGrids.h), read back with OpenVDB (in the
// reading child) and checked against what they stand for, recomputed here by brute force.
#include "Core/Error.h"
#include "VDB/RenderGrids.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <random>

namespace vdb = msynth::vdb;

namespace
{
std::string Tmp(const std::string& name)
{
  return std::string(MSYNTH_TEST_TMP) + "/" + name;
}

/// A small label volume off the origin, with holes and labels at its borders.
struct Volume
{
  vdb::GridHeader Header;
  std::vector<std::int32_t> Labels;
  std::int32_t At(std::int64_t x, std::int64_t y, std::int64_t z) const
  {
    const auto& d = this->Header.Dims;
    if (x < 0 || y < 0 || z < 0 || x >= d[0] || y >= d[1] || z >= d[2])
      return 0;
    return this->Labels[static_cast<std::size_t>(x + d[0] * (y + d[1] * z))];
  }
};

Volume MakeVolume()
{
  Volume v;
  v.Header.Name = "Label";
  v.Header.Type = vdb::ValueType::Int32;
  v.Header.IndexMin = { { -2, 5, 1 } };
  v.Header.Dims = { { 7, 6, 5 } };
  v.Header.Origin = { { 1.25, -2.0, 0.5 } };
  v.Header.Spacing = { { 0.5, 0.5, 0.5 } };
  std::mt19937 random(7);
  const std::int32_t values[] = { 0, 0, 1, 2, 5 };
  v.Labels.resize(static_cast<std::size_t>(v.Header.NumberOfVoxels()));
  for (auto& label : v.Labels)
    label = values[random() % 5];
  return v;
}

vdb::LabelRenderView RenderView(const Volume& v)
{
  vdb::LabelRenderView view;
  view.Geometry = v.Header;
  view.Labels = v.Labels.data();
  view.EmptyLabel = 0;
  view.Colors = { { 1, { { 0.1f, 0.2f, 0.3f } } }, { 2, { { 0.4f, 0.5f, 0.6f } } },
    { 5, { { 0.7f, 0.8f, 0.9f } } } };
  view.Names = { { 1, "stone" }, { 2, "stone" }, { 5, "door frame" } };
  return view;
}

/// The exact distance from voxel centre (x, y, z) to the nearest voxel box of the voxels for
/// which @p member holds, by brute force over the grown box (in voxels of side 1).
template <typename Member>
double BruteDistance(
  const Volume& v, std::int64_t x, std::int64_t y, std::int64_t z, const Member& member)
{
  double best = 1e9;
  const auto& d = v.Header.Dims;
  for (std::int64_t k = -4; k < d[2] + 4; ++k)
    for (std::int64_t j = -4; j < d[1] + 4; ++j)
      for (std::int64_t i = -4; i < d[0] + 4; ++i)
        if (member(i, j, k))
        {
          const auto gap = [](std::int64_t a, std::int64_t b)
          { return std::max(0.0, std::abs(double(a - b)) - 0.5); };
          const double dx = gap(x, i), dy = gap(y, j), dz = gap(z, k);
          best = std::min(best, std::sqrt(dx * dx + dy * dy + dz * dz));
        }
  return best;
}

const vdb::DenseGrid& Grid(const vdb::FileContents& file, const std::string& name)
{
  for (const auto& g : file.Grids)
    if (g.Header.Name == name)
      return g;
  throw msynth::Error("no grid " + name);
}

/// Checks the level set @p g of the voxels for which @p solid holds against brute force.
template <typename Solid>
void CheckLevelSet(const Volume& v, const vdb::DenseGrid& g, const Solid& solid)
{
  const double h = v.Header.Spacing[0], band = 3 * h;
  ASSERT_EQ(g.Header.GridClass, "level set");
  EXPECT_DOUBLE_EQ(g.Header.Background, band);
  std::int64_t checked = 0;
  for (std::int64_t z = 0; z < g.Header.Dims[2]; ++z)
    for (std::int64_t y = 0; y < g.Header.Dims[1]; ++y)
      for (std::int64_t x = 0; x < g.Header.Dims[0]; ++x)
      {
        // Volume coordinates of this voxel of the read box.
        const std::int64_t vx = x + g.Header.IndexMin[0] - v.Header.IndexMin[0];
        const std::int64_t vy = y + g.Header.IndexMin[1] - v.Header.IndexMin[1];
        const std::int64_t vz = z + g.Header.IndexMin[2] - v.Header.IndexMin[2];
        const float value =
          g.Floats[static_cast<std::size_t>(x + g.Header.Dims[0] * (y + g.Header.Dims[1] * z))];
        const bool inside = solid(vx, vy, vz);
        ASSERT_EQ(value < 0, inside) << "at " << vx << ", " << vy << ", " << vz;
        const double exact = h *
          BruteDistance(v, vx, vy, vz,
            [&](std::int64_t i, std::int64_t j, std::int64_t k)
            { return solid(i, j, k) != inside; });
        if (exact < band)
          ASSERT_NEAR(std::abs(value), exact, 1e-5) << "at " << vx << ", " << vy << ", " << vz;
        else
          ASSERT_FLOAT_EQ(std::abs(value), static_cast<float>(band));
        ++checked;
      }
  EXPECT_GT(checked, v.Header.NumberOfVoxels());
}
} // namespace

TEST(RenderGrids, DensityColorAndLevelSetsAreWhatTheLabelsSay)
{
  const Volume v = MakeVolume();
  const std::string path = Tmp("render-grids.vdb");
  vdb::WriteFile(
    path, { vdb::DenseGridView{ v.Header, v.Labels.data() } }, {}, { RenderView(v) }, {});

  std::map<std::string, vdb::GridSummary> listed;
  for (const auto& g : vdb::ListGrids(path))
    listed[g.Name] = g;
  ASSERT_EQ(listed.count("density") + listed.count("color") + listed.count("surface") +
      listed.count("surface_stone") + listed.count("surface_door_frame"),
    5u);
  EXPECT_EQ(listed["density"].GridClass, "fog volume");
  EXPECT_EQ(listed["density"].TypeName, "float");
  EXPECT_EQ(listed["color"].TypeName, "vec3s");
  EXPECT_EQ(listed["surface"].GridClass, "level set");
  EXPECT_EQ(listed["surface_door_frame"].GridClass, "level set");
  for (const auto& [name, g] : listed)
    for (std::size_t a = 0; a < 3; ++a)
      EXPECT_DOUBLE_EQ(g.VoxelSize[a], 0.5) << name;
  std::int64_t solid = 0;
  for (auto label : v.Labels)
    solid += label != 0;
  EXPECT_EQ(listed["density"].ActiveVoxelCount, solid);
  EXPECT_EQ(listed["color"].ActiveVoxelCount, solid);
  EXPECT_NE(
    listed["surface"].Metadata["msynth_label_surfaces"].find("2 written"), std::string::npos);

  const vdb::FileContents file = vdb::ReadFile(path);
  const auto& label = Grid(file, "Label");
  const auto& density = Grid(file, "density");
  const auto& color = Grid(file, "color");
  const auto view = RenderView(v);
  for (const auto* g : { &density, &color })
  {
    // The label grid's transform and extent.
    EXPECT_EQ(g->Header.Origin, label.Header.Origin);
    EXPECT_EQ(g->Header.Spacing, label.Header.Spacing);
    EXPECT_EQ(g->Header.IndexMin, label.Header.IndexMin);
    EXPECT_EQ(g->Header.Dims, label.Header.Dims);
  }
  for (std::size_t i = 0; i < v.Labels.size(); ++i)
  {
    const std::int32_t l = v.Labels[i];
    EXPECT_EQ(density.Floats[i], l != 0 ? 1.0f : 0.0f);
    for (std::size_t c = 0; c < 3; ++c)
      EXPECT_EQ(color.Floats[3 * i + c], l != 0 ? view.Colors.at(l)[c] : 0.0f);
  }
  const auto solidAt = [&v](std::int64_t x, std::int64_t y, std::int64_t z)
  { return v.At(x, y, z) != 0; };
  CheckLevelSet(v, Grid(file, "surface"), solidAt);
  CheckLevelSet(v, Grid(file, "surface_stone"),
    [&v](std::int64_t x, std::int64_t y, std::int64_t z)
    {
      const std::int32_t l = v.At(x, y, z);
      return l == 1 || l == 2;
    });
  CheckLevelSet(v, Grid(file, "surface_door_frame"),
    [&v](std::int64_t x, std::int64_t y, std::int64_t z) { return v.At(x, y, z) == 5; });
}

TEST(RenderGrids, LabelSurfacesPastTheBudgetAreSkippedAndSaidSo)
{
  const Volume v = MakeVolume();
  vdb::LabelRenderView view = RenderView(v);
  view.LabelSurfaceBudget = static_cast<double>(v.Header.NumberOfVoxels()) * 2 - 1;
  const std::string path = Tmp("render-grids-budget.vdb");
  vdb::WriteFile(path, {}, {}, { view }, {});
  std::vector<std::string> names;
  std::string note;
  for (const auto& g : vdb::ListGrids(path))
  {
    names.push_back(g.Name);
    if (g.Name == "surface")
      note = g.Metadata.at("msynth_label_surfaces");
  }
  EXPECT_EQ(names, (std::vector<std::string>{ "density", "color", "surface" }));
  EXPECT_NE(note.find("skipped"), std::string::npos) << note;
  // Within the budget, both.
  view.LabelSurfaceBudget = static_cast<double>(v.Header.NumberOfVoxels()) * 2;
  vdb::WriteFile(path, {}, {}, { view }, {});
  EXPECT_EQ(vdb::ListGrids(path).size(), 5u);
}

TEST(RenderGrids, NoLabelsOrANarrowBandIsAnErrorNamingTheFile)
{
  const Volume v = MakeVolume();
  vdb::LabelRenderView view = RenderView(v);
  view.HalfWidth = 0.5;
  const std::string path = Tmp("render-grids-bad.vdb");
  try
  {
    vdb::WriteFile(path, {}, {}, { view }, {});
    FAIL() << "a band of half a voxel was written";
  }
  catch (const msynth::Error& e)
  {
    EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
  }
  view = RenderView(v);
  view.Labels = nullptr;
  EXPECT_THROW(vdb::WriteFile(path, {}, {}, { view }, {}), msynth::Error);
}

TEST(RenderGrids, UndecidedSitesAreEmpty)
{
  // A catalog snapshot's undecided sites (INT_MIN) are empty, as mesh.vtp leaves them out.
  Volume v = MakeVolume();
  std::int64_t solid = 0;
  for (std::size_t i = 0; i < v.Labels.size(); ++i)
  {
    if (i % 3 == 0)
      v.Labels[i] = std::numeric_limits<std::int32_t>::min();
    solid += v.Labels[i] != 0 && v.Labels[i] != std::numeric_limits<std::int32_t>::min();
  }
  const std::string path = Tmp("render-grids-undecided.vdb");
  vdb::WriteFile(path, {}, {}, { RenderView(v) }, {});
  for (const auto& g : vdb::ListGrids(path))
  {
    if (g.Name == "density" || g.Name == "color")
    {
      EXPECT_EQ(g.ActiveVoxelCount, solid) << g.Name;
    }
  }
}
