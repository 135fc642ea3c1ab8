// SPDX-License-Identifier: BSD-3-Clause
// Continuous example analysis against the dissertation's own numbers (§4.5.1–4.5.5).
#include "Continuous/PolyhedralAnalysis.h"
#include "Core/Error.h"
#include "Formats/PolyhedralExample.h"

#include <gtest/gtest.h>

#include <cmath>
#include <sstream>
#include <string>
#include <vector>

using namespace msynth;

namespace
{

std::string Data(const std::string& name)
{
  return std::string(MSYNTH_DATA) + "/Continuous/" + name;
}

PolyhedralAnalysis AnalyzeFile(const std::string& name)
{
  PolyhedralExample example = ReadOBJExample(Data(name));
  ValidateExample(example);
  return PolyhedralAnalysis::Analyze(example);
}

PolyhedralExample FromText(const std::string& text)
{
  std::istringstream in(text);
  PolyhedralExample example = ReadOBJExample(in, "test.obj");
  return example;
}

std::string ValidationError(const std::string& text)
{
  PolyhedralExample example = FromText(text);
  try
  {
    ValidateExample(example);
  }
  catch (const Error& e)
  {
    return e.what();
  }
  return "";
}

int CountByKind(const PolyhedralAnalysis& a, FeatureKind kind)
{
  int n = 0;
  for (const auto& l : a.Labels())
  {
    n += l.Kind == kind ? 1 : 0;
  }
  return n;
}

/// The family whose exact normal is parallel to (x, y, z).
int FamilyAlong(const PolyhedralAnalysis& a, double x, double y, double z)
{
  for (int f = 0; f < a.Families().Size(); ++f)
  {
    const auto& u = a.FamilyUnitNormals()[f];
    const double len = std::sqrt(x * x + y * y + z * z);
    if (std::abs(std::abs(u[0] * x + u[1] * y + u[2] * z) / len - 1) < 1e-9)
    {
      return f;
    }
  }
  return -1;
}

const std::string cubeText = R"(
v 0 0 0
v 1 0 0
v 1 1 0
v 0 1 0
v 0 0 1
v 1 0 1
v 1 1 1
v 0 1 1
f 1 4 3 2
f 5 6 7 8
f 1 2 6 5
f 2 3 7 6
f 3 4 8 7
f 4 1 5 8
)";

} // namespace

TEST(PolyhedralAnalysis, TriangleHasEightLabels)
{
  const auto a = AnalyzeFile("triangle2d.obj");
  EXPECT_TRUE(a.Planar());
  EXPECT_EQ(a.Families().Size(), 3);
  ASSERT_EQ(a.NumberOfLabels(), 8); // Fig. 4.12
  EXPECT_EQ(CountByKind(a, FeatureKind::Volume), 2);
  EXPECT_EQ(CountByKind(a, FeatureKind::Face), 3); // the three edges (codimension 1)
  EXPECT_EQ(CountByKind(a, FeatureKind::Edge), 3); // the three vertices (codimension 2)
  EXPECT_EQ(a.Label(0).Expression, "∅");
  EXPECT_EQ(a.Label(1).Expression, "ℝ²");
  // Fig. 4.15: a site on a horizontal line admits 3 labels.
  const int horizontal = FamilyAlong(a, 0, 1, 0);
  ASSERT_GE(horizontal, 0);
  EXPECT_EQ(a.AllowedLabels({ horizontal }).size(), 3u);
  // Fig. 4.16: where lines parallel to the two other edges cross, 5 labels.
  std::vector<int> others;
  for (int f = 0; f < 3; ++f)
  {
    if (f != horizontal)
    {
      others.push_back(f);
    }
  }
  EXPECT_EQ(a.AllowedLabels(others).size(), 5u);
  // All three families: everything.
  EXPECT_EQ(a.AllowedLabels({ 0, 1, 2 }).size(), 8u);
  // Every vertex label is an intersection (convex corners).
  for (const auto& l : a.Labels())
  {
    if (l.Kind == FeatureKind::Edge)
    {
      EXPECT_NE(l.Expression.find("∩"), std::string::npos) << l.Expression;
      EXPECT_EQ(l.Expression.find("∪"), std::string::npos) << l.Expression;
    }
  }
}

TEST(PolyhedralAnalysis, ConcaveVertexIsAUnion)
{
  const auto a = AnalyzeFile("concave2d.obj");
  int unions = 0;
  for (const auto& l : a.Labels())
  {
    unions += l.Expression.find("∪") != std::string::npos ? 1 : 0;
  }
  EXPECT_EQ(unions, 1); // Fig. 4.13: the reflex vertex (2, 2)
  // Two families (axis-aligned): ∅, ℝ², 4 edges, 5 corners of which one reflex.
  EXPECT_EQ(a.Families().Size(), 2);
  EXPECT_EQ(a.NumberOfLabels(), 2 + 4 + 5);
}

TEST(PolyhedralAnalysis, TwoObjectTypes)
{
  const auto a = AnalyzeFile("two-objects2d.obj");
  int mixed = 0;
  for (const auto& l : a.Labels())
  {
    const auto types = l.Label.TypesPresent();
    if (std::count_if(types.begin(), types.end(), [](int t) { return t > 0; }) == 2)
    {
      ++mixed;
      EXPECT_NE(l.Expression.find("1·"), std::string::npos) << l.Expression;
      EXPECT_NE(l.Expression.find(" + 2·"), std::string::npos) << l.Expression;
    }
  }
  // Where the roof stands on the base: the shared edge and the two roof corners on it.
  EXPECT_EQ(mixed, 3);
  EXPECT_EQ(a.Label(1).Expression, "ℝ²");   // inside the base (type 1)
  EXPECT_EQ(a.Label(2).Expression, "2·ℝ²"); // inside the roof
}

TEST(PolyhedralAnalysis, CubeAndTetrahedron)
{
  const auto cube = AnalyzeFile("cube.obj");
  EXPECT_EQ(cube.Families().Size(), 3);
  EXPECT_EQ(cube.NumberOfLabels(), 28);
  EXPECT_EQ(CountByKind(cube, FeatureKind::Face), 6);
  EXPECT_EQ(CountByKind(cube, FeatureKind::Edge), 12);
  EXPECT_EQ(CountByKind(cube, FeatureKind::Vertex), 8);

  const auto tetra = AnalyzeFile("tetrahedron.obj");
  EXPECT_EQ(tetra.Families().Size(), 4);
  EXPECT_EQ(tetra.NumberOfLabels(), 16); // §4.5.3
  // §4.5.4, Fig. 4.20: a vertex on planes of three families admits 9 labels.
  EXPECT_EQ(tetra.AllowedLabels({ 0, 1, 2 }).size(), 9u);
  // The slanted face snaps exactly to (1, 1, 1).
  const int slanted = FamilyAlong(tetra, 1, 1, 1);
  ASSERT_GE(slanted, 0);
  const auto& n = tetra.Families().Normal(slanted);
  EXPECT_EQ(std::abs(n[0]), 1);
  EXPECT_EQ(n[0], n[1]);
  EXPECT_EQ(n[1], n[2]);
}

TEST(PolyhedralAnalysis, ComplexVertexOfFigure418)
{
  // Five families through one vertex; the neighbourhood (h3 ∩ (h1 ∪ h2)) ∪ (h4 ∩ (h1 ∪ h5)).
  // These normals cut space into 22 cones, and every one of the five planes separates inside
  // from outside somewhere (not so for every choice of five normals: then a family drops out).
  const PlaneFamilySet set(
    { { -3, 1, -1 }, { 1, 3, -1 }, { 0, -2, 1 }, { -1, -1, -3 }, { 1, 2, 2 } });
  EXPECT_EQ(set.Cones({ 0, 1, 2, 3, 4 }).size(), 22u);
  auto in = [](unsigned mask, int family) { return !((mask >> family) & 1u); };
  const auto label = NeighbourhoodLabel::FromFunction(set, { 0, 1, 2, 3, 4 },
    [&](const PlaneFamilySet::Cone& c)
    {
      const unsigned m = c.Mask;
      return ((in(m, 2) && (in(m, 0) || in(m, 1))) || (in(m, 3) && (in(m, 0) || in(m, 4)))) ? 1 : 0;
    });
  EXPECT_EQ(label.Families.size(), 5u);
  EXPECT_EQ(label.Kind(set), FeatureKind::Vertex);
  EXPECT_EQ(label.Expression(false), "(h3 ∩ (h1 ∪ h2)) ∪ (h4 ∩ (h1 ∪ h5))");
  // Equal neighbourhoods compare equal however derived: the same function through an extra,
  // irrelevant family is dropped in the canonical form.
  const PlaneFamilySet more(
    { { -3, 1, -1 }, { 1, 3, -1 }, { 0, -2, 1 }, { -1, -1, -3 }, { 1, 2, 2 }, { 2, 1, -1 } });
  const auto same = NeighbourhoodLabel::FromFunction(more, { 0, 1, 2, 3, 4, 5 },
    [&](const PlaneFamilySet::Cone& c)
    {
      const unsigned m = c.Mask;
      return ((in(m, 2) && (in(m, 0) || in(m, 1))) || (in(m, 3) && (in(m, 0) || in(m, 4)))) ? 1 : 0;
    });
  EXPECT_EQ(same, label);
}

TEST(PolyhedralAnalysis, EvaluationOfFigure421)
{
  // x23 = n2 × n3 points down and lies inside h1 (n1·x23 < 0).
  const PlaneFamilySet set({ { 0, 0, 1 }, { 1, 0, 0 }, { 0, 1, 0 } });
  const IntVec3 down{ 0, 0, -1 }; // = −(n2 × n3)… any direction along both planes h2, h3
  auto in = [](unsigned mask, int family) { return !((mask >> family) & 1u); };
  auto make = [&](auto f)
  {
    return NeighbourhoodLabel::FromFunction(
      set, { 0, 1, 2 }, [&](const PlaneFamilySet::Cone& c) { return f(c.Mask) ? 1 : 0; });
  };
  const auto top = make([&](unsigned m) { return in(m, 0) && (in(m, 1) || in(m, 2)); });
  EXPECT_EQ(top.Expression(false), "h1 ∩ (h2 ∪ h3)");
  // Down (inside h1): h2 ∪ h3.
  const auto evaluated = top.Evaluate(set, down);
  EXPECT_EQ(evaluated.Expression(false), "h2 ∪ h3");
  EXPECT_EQ(evaluated.Families, (std::vector<int>{ 1, 2 }));
  // Up, out of h1: empty.
  EXPECT_EQ(top.Evaluate(set, { 0, 0, 1 }).Expression(false), "∅");
  // The three labels Fig. 4.21 shows beneath it are compatible; others are not.
  const auto a = make([&](unsigned m) { return in(m, 0) || in(m, 1) || in(m, 2); });
  const auto b = make([&](unsigned m) { return in(m, 1) || in(m, 2); });
  const auto c = make([&](unsigned m) { return (!in(m, 0) && in(m, 1)) || in(m, 2); });
  const auto d = make([&](unsigned m) { return in(m, 1) && in(m, 2); });
  for (const auto* below : { &a, &b, &c })
  {
    EXPECT_TRUE(CompatibleAlong(set, top, *below, down)) << below->Expression(false);
  }
  EXPECT_FALSE(CompatibleAlong(set, top, d, down));
  EXPECT_EQ(b.Families, (std::vector<int>{ 1, 2 })); // h1 dropped: no change across it
}

TEST(PolyhedralAnalysis, LPrismHasReflexEdgeUnions)
{
  const auto a = AnalyzeFile("l-prism.obj");
  EXPECT_EQ(a.Families().Size(), 3);
  int unionEdges = 0;
  for (const auto& l : a.Labels())
  {
    if (l.Kind == FeatureKind::Edge && l.Expression.find("∪") != std::string::npos)
    {
      ++unionEdges;
    }
  }
  EXPECT_EQ(unionEdges, 1); // the one reflex edge
  // ∅, ℝ³, 6 faces, 12 + 1 edges (11 convex kinds... counted exactly below), vertices.
  EXPECT_EQ(CountByKind(a, FeatureKind::Face), 6);
}

TEST(PolyhedralAnalysis, RotatedCopyHasTheSameLabels)
{
  for (const char* file : { "cube.obj", "tetrahedron.obj", "l-prism.obj" })
  {
    PolyhedralExample example = ReadOBJExample(Data(file));
    ValidateExample(example);
    const int count = PolyhedralAnalysis::Analyze(example).NumberOfLabels();
    const double ax = 0.3, ay = 0.7, az = 1.1;
    for (auto& p : example.Points)
    {
      double x = p[0], y = p[1], z = p[2];
      double t = std::cos(az) * x - std::sin(az) * y;
      y = std::sin(az) * x + std::cos(az) * y;
      x = t;
      t = std::cos(ay) * x + std::sin(ay) * z;
      z = -std::sin(ay) * x + std::cos(ay) * z;
      x = t;
      t = std::cos(ax) * y - std::sin(ax) * z;
      z = std::sin(ax) * y + std::cos(ax) * z;
      y = t;
      p = { x + 5, y - 2, z + 0.5 };
    }
    ValidateExample(example);
    const auto rotated = PolyhedralAnalysis::Analyze(example);
    EXPECT_EQ(rotated.NumberOfLabels(), count) << file;
  }
}

TEST(PolyhedralAnalysis, MalformedMeshesAreRejected)
{
  auto without = [](const std::string& text, const std::string& line)
  {
    std::string s = text;
    s.erase(s.find(line), line.size());
    return s;
  };
  EXPECT_NE(
    ValidationError(without(cubeText, "f 5 6 7 8\n")).find("not closed"), std::string::npos);
  std::string flipped = cubeText;
  flipped.replace(flipped.find("f 5 6 7 8"), 9, "f 8 7 6 5");
  EXPECT_NE(ValidationError(flipped).find("inconsistent orientation"), std::string::npos);
  EXPECT_NE(ValidationError(cubeText + "f 1 2 3\n").find("non-manifold"), std::string::npos);
  std::string degenerate = cubeText;
  degenerate.replace(degenerate.find("f 5 6 7 8"), 9, "f 5 6 6 8");
  EXPECT_NE(ValidationError(degenerate).find("degenerate"), std::string::npos);
  std::string bent = cubeText;
  bent.replace(bent.find("v 1 1 1"), 7, "v 1 1 1.3");
  EXPECT_NE(ValidationError(bent).find("not planar"), std::string::npos);
  // A cube whose top corner is pushed through the bottom: triangulated so faces stay planar.
  const std::string crossing = R"(
v 0 0 0
v 4 0 0
v 0 4 0
v 0 0 4
v 3 3 -2
f 1 3 2
f 1 2 4
f 1 4 3
f 2 3 5
f 2 5 4
f 3 4 5
)";
  EXPECT_NE(ValidationError(crossing).find("self-intersecting"), std::string::npos);
  // A pyramid whose base is pinched: two of its corners at one point (distinct vertices). The
  // face is planar and uses no vertex twice, but is no simple polygon; CGAL's triangulation of
  // it (in the self-intersection test) overran its mesh (found by FuzzPolyhedral).
  const std::string pinched = R"(
v 4 2 0
v 2 4 0
v 3 2 0
v 2 4 0
v 0 3 0
v 2 2 2
f 5 4 3 2 1
f 1 2 6
f 2 3 6
f 3 4 6
f 4 5 6
f 5 1 6
)";
  EXPECT_NE(ValidationError(pinched).find("intersects itself"), std::string::npos)
    << ValidationError(pinched);
  // The same check on a face seen along x (its normal's largest component): a lopsided bow
  // tie, whose halves do not cancel (no zero area).
  const std::string bowTie = R"(
v 0 0 0
v 0 3 3
v 0 3 0
v 0 0 1
v 1 1 1
f 1 2 3 4
f 1 5 2
f 2 5 3
f 3 5 4
f 4 5 1
)";
  EXPECT_NE(ValidationError(bowTie).find("intersects itself"), std::string::npos)
    << ValidationError(bowTie);
  // Messages name the file.
  EXPECT_EQ(ValidationError(without(cubeText, "f 5 6 7 8\n")).rfind("'test.obj'", 0), 0u);
  // Reader errors name the line.
  EXPECT_THROW(FromText("v 0 0\nf 1 2 3\n"), Error);
  try
  {
    FromText("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n");
    FAIL();
  }
  catch (const Error& e)
  {
    EXPECT_NE(std::string(e.what()).find("line 4"), std::string::npos) << e.what();
  }
  EXPECT_THROW(FromText("v 0 0 0\n"), Error);            // no faces
  EXPECT_THROW(FromText("v 0 0 nan\nf 1 1 1\n"), Error); // not finite
}

TEST(PolyhedralAnalysis, ErrorsNumberFacesFromOneAndNameObjects)
{
  // Faces count from 1 in file order, as the file numbers its vertices: the cube without its
  // second face is open along the edges of that face, each now in one face only.
  std::string open = cubeText;
  open.erase(open.find("f 5 6 7 8\n"), 10);
  EXPECT_NE(ValidationError(open).find("edge (5, 6) belongs to face 2 only"), std::string::npos)
    << ValidationError(open);
  std::string flipped = cubeText;
  flipped.replace(flipped.find("f 5 6 7 8"), 9, "f 8 7 6 5");
  EXPECT_NE(ValidationError(flipped).find("faces 2 and 3 traverse edge (5, 6)"), std::string::npos)
    << ValidationError(flipped);
  std::string degenerate = cubeText;
  degenerate.replace(degenerate.find("f 5 6 7 8"), 9, "f 5 6 6 8");
  EXPECT_NE(ValidationError(degenerate).find("face 2 of object"), std::string::npos)
    << ValidationError(degenerate);
  // Two overlapping objects: the message names the file and both objects as the file does.
  const std::string two = "o roof" + cubeText + R"(o wall
v 0.5 0.5 0.5
v 1.5 0.5 0.5
v 1.5 1.5 0.5
v 0.5 1.5 0.5
v 0.5 0.5 1.5
v 1.5 0.5 1.5
v 1.5 1.5 1.5
v 0.5 1.5 1.5
f 9 12 11 10
f 13 14 15 16
f 9 10 14 13
f 10 11 15 14
f 11 12 16 15
f 12 9 13 16
)";
  PolyhedralExample named = FromText(two);
  ValidateExample(named);
  const Point3 inBoth{ 0.75, 0.75, 0.75 };
  try
  {
    SolidClassifier(named).ObjectAt(inBoth);
    FAIL() << "no overlap found";
  }
  catch (const Error& e)
  {
    EXPECT_EQ(std::string(e.what()).rfind("'test.obj': objects 'roof' and 'wall' overlap", 0), 0u)
      << e.what();
  }
  // Objects without names (a mesh split by connectivity) are numbered from 1.
  AssignObjectsByConnectivity(named, std::vector<int>(named.Faces.size(), 1));
  ValidateExample(named);
  try
  {
    SolidClassifier(named).ObjectAt(inBoth);
    FAIL() << "no overlap found";
  }
  catch (const Error& e)
  {
    EXPECT_NE(
      std::string(e.what()).find("objects 'object 1' and 'object 2' overlap"), std::string::npos)
      << e.what();
  }
}

TEST(PolyhedralAnalysis, InwardObjectIsTurnedOutward)
{
  std::string inward = cubeText;
  // Reverse every face.
  std::istringstream in(cubeText);
  std::string line, out;
  while (std::getline(in, line))
  {
    if (line.rfind("f ", 0) == 0)
    {
      std::istringstream w(line.substr(2));
      std::vector<std::string> idx;
      std::string t;
      while (w >> t)
      {
        idx.push_back(t);
      }
      line = "f";
      for (auto it = idx.rbegin(); it != idx.rend(); ++it)
      {
        line += " " + *it;
      }
    }
    out += line + "\n";
  }
  PolyhedralExample example = FromText(out);
  ValidateExample(example);
  EXPECT_EQ(PolyhedralAnalysis::Analyze(example).NumberOfLabels(), 28);
}

TEST(PolyhedralAnalysis, SnapDirection)
{
  EXPECT_EQ(SnapDirection({ 0, 0, -1 }, 1e-4), (IntVec3{ 0, 0, -1 }));
  const double r = 1 / std::sqrt(2.0);
  EXPECT_EQ(SnapDirection({ r, r + 1e-7, 0 }, 1e-4), (IntVec3{ 1, 1, 0 }));
  // An irrational direction gets 24-bit integers, still within the tolerance.
  const IntVec3 v = SnapDirection({ std::cos(1.2566), std::sin(1.2566), 0 }, 1e-6);
  EXPECT_GT(std::abs(v[1]), 1000);
  EXPECT_NEAR(std::atan2(double(v[1]), double(v[0])), 1.2566, 1e-6);
}

TEST(PolyhedralAnalysis, HouseWithOverhangingRoof)
{
  // Counted by hand: wall 1 + 6 faces (its top under the roof is a two-type face) + 12 edges +
  // 8 vertices; roof 1 + 5 faces (eaves, gables, slopes) + 9 edges + 6 vertices; ∅.
  const auto a = AnalyzeFile("house.obj");
  EXPECT_EQ(a.Families().Size(), 5);
  EXPECT_EQ(a.NumberOfLabels(), 49);
  int mixed = 0;
  for (const auto& l : a.Labels())
  {
    const auto t = l.Label.TypesPresent();
    mixed += std::count(t.begin(), t.end(), 1) && std::count(t.begin(), t.end(), 2) ? 1 : 0;
  }
  EXPECT_EQ(mixed, 9); // the wall's top face, its 4 top edges and 4 top corners, under the roof
  // The wall's top face is covered by the roof; the roof's bottom face is partly exposed
  // (eaves), so it has several labels.
  int several = 0;
  for (int l : a.ElementLabel())
  {
    several += l < 0 ? 1 : 0;
  }
  EXPECT_EQ(several, 1);
}
