// round_for_output (issue 14, "Clean output"): meshes with features below what a file's numbers
// can hold come out clean by CGAL's judgement after rounding, nothing moves farther than allowed,
// and a mesh that is clean already is returned as it is.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <random>
#include <string>

#include "mesh/mesh_measures.hpp"
#include "mesh/output_rounding.hpp"
#include "shapes.hpp"
#include "support/cgal_mesh_check.hpp"

namespace sculpt {
namespace {

using Eigen::Vector3d;

Vector3d to_float(const Vector3d& v) {
  Vector3d out;
  for (int k = 0; k < 3; ++k) {
    const volatile float f = static_cast<float>(v[k]);  // see output_rounding.cpp: kept from the vectorizer
    out[k] = f;
  }
  return out;
}

/// Two unit cubes that share the edge x = 1, y = 1 (a solid touching itself along an edge): the
/// edge's ends appear twice, once per cube, at the same coordinates.
PolygonMesh cubes_sharing_an_edge() {
  return test_shapes::merged(test_shapes::unit_cube(), test_shapes::box({1, 1, 0}, {2, 2, 1}));
}

/// The unit cube with the edge y = 0, z = 1 split at x = 0.5 and at the next double above 0.5:
/// both new vertices are on the edge, distinct in doubles and the same point in float32.
PolygonMesh cube_with_close_vertices() {
  PolygonMesh m = test_shapes::unit_cube();
  // unit_cube: vertex i at (i&1, i&2, i&4); the edge from 4 (0,0,1) to 5 (1,0,1) lies in the
  // top face {4, 5, 7, 6} and the front face {0, 1, 5, 4}.
  const double x1 = 0.5, x2 = std::nextafter(0.5, 1.0);
  m.vertices.push_back({x1, 0, 1});  // 8
  m.vertices.push_back({x2, 0, 1});  // 9
  for (auto& f : m.faces) {
    if (f == std::vector<int>{4, 5, 7, 6}) f = {4, 8, 9, 5, 7, 6};
    if (f == std::vector<int>{0, 1, 5, 4}) f = {0, 1, 5, 9, 8, 4};
  }
  return m;
}

TEST(OutputRounding, CleanMeshIsReturnedAsItIs) {
  const PolygonMesh cube = test_shapes::unit_cube();
  OutputRoundingReport r;
  const PolygonMesh out = round_for_output(cube, {}, &r);
  EXPECT_FALSE(r.changed);
  EXPECT_TRUE(r.clean);
  EXPECT_EQ(out.faces, cube.faces);
  EXPECT_EQ(out.vertices, cube.vertices);
}

TEST(OutputRounding, SheetsTouchingAlongAnEdgeAreMovedApart) {
  const PolygonMesh m = cubes_sharing_an_edge();
  ASSERT_FALSE(checks::cgal_check(m.vertices, m.faces).clean());  // duplicate points
  ASSERT_FALSE(output_problem(m).empty());
  OutputRoundingReport r;
  const double max_feature = 1e-6;
  const PolygonMesh out = round_for_output(m, {.max_feature = max_feature}, &r);
  EXPECT_TRUE(r.changed);
  EXPECT_TRUE(r.clean) << r.problem;
  EXPECT_GE(r.separated_vertices, 2);
  EXPECT_LE(r.max_move, max_feature);
  EXPECT_TRUE(checks::CleanForOtherTools(out.vertices, out.faces));
  EXPECT_TRUE(output_problem(out).empty());
  EXPECT_NEAR(mesh_volume(out), 2.0, mesh_surface_area(m) * r.max_move + 1e-15);
}

TEST(OutputRounding, CopiesAreKeptWhenAsked) {
  const PolygonMesh m = cubes_sharing_an_edge();
  OutputRoundingReport r;
  round_for_output(m, {.keep_copies = true}, &r);
  EXPECT_FALSE(r.changed);
}

TEST(OutputRounding, VerticesThatMeetInFloat32AreMerged) {
  const PolygonMesh m = cube_with_close_vertices();
  EXPECT_TRUE(output_problem(m).empty()) << output_problem(m);  // fine in doubles
  ASSERT_FALSE(output_problem(m, {.precision = OutputPrecision::Float32}).empty());  // not in float32
  OutputRoundingReport r;
  const PolygonMesh out = round_for_output(m, {.precision = OutputPrecision::Float32}, &r);
  EXPECT_TRUE(r.clean) << r.problem;
  EXPECT_GE(r.collapsed_edges, 1);
  for (const Vector3d& v : out.vertices) EXPECT_EQ(v, to_float(v));
  EXPECT_TRUE(checks::CleanForOtherTools(out.vertices, out.faces));
  EXPECT_NEAR(mesh_volume(out), 1.0, 1e-12);
}

TEST(OutputRounding, StlTrianglesAreJudgedAsTriangles) {
  // Triangles asked for: the cube comes back as 12 triangles, clean.
  OutputRoundingReport r;
  const PolygonMesh out = round_for_output(test_shapes::unit_cube(), {.triangles = true}, &r);
  EXPECT_TRUE(r.clean);
  EXPECT_EQ(out.faces.size(), 12u);
  for (const auto& f : out.faces) EXPECT_EQ(f.size(), 3u);
  EXPECT_NEAR(mesh_volume(out), 1.0, 1e-15);
}

TEST(OutputRounding, GridRoundingSnapsEveryVertex) {
  const double step = std::ldexp(1.0, -4);
  PolygonMesh m = test_shapes::box({0.01, 0.02, 0.03}, {1.01, 0.52, 0.27});
  OutputRoundingReport r;
  const PolygonMesh out = round_for_output(m, {.precision = OutputPrecision::Grid, .grid_step = step}, &r);
  EXPECT_TRUE(r.clean) << r.problem;
  for (const Vector3d& v : out.vertices)
    for (int k = 0; k < 3; ++k) EXPECT_EQ(v[k], std::round(v[k] / step) * step);
  EXPECT_NEAR(mesh_volume(out), 1.0 * 0.5 * 0.25, 1e-15);
}

TEST(OutputRounding, ASlabThinnerThanFloat32IsReportedNotHidden) {
  // A slab 1e-9 thick at z = 1: float32 cannot hold it (both sides round to 1), and collapsing it
  // would move vertices by its width. The result says so; in particular, local operations must not
  // pass off the slab turned inside out (collapsed, then a corner moved off the crossing) as clean.
  const PolygonMesh slab = test_shapes::box({0, 0, 1}, {1, 1, 1 + 1e-9});
  OutputRoundingReport r;
  round_for_output(slab, {.precision = OutputPrecision::Float32, .max_feature = 1e-12}, &r);
  EXPECT_FALSE(r.clean);
  EXPECT_FALSE(r.problem.empty());
}

TEST(OutputRounding, CrossingsLargerThanAllowedAreReportedNotHidden) {
  // Two cubes overlapping by 0.1 (not a solid's boundary): undoing the crossing would move
  // vertices by 0.1, far beyond the limit. The result says so.
  const PolygonMesh overlapping = test_shapes::merged(test_shapes::box({0, 0, 0}, {1, 1, 1}),
                                                      test_shapes::box({0.9, 0.25, 0.25}, {2, 0.75, 0.75}));
  OutputRoundingReport r;
  round_for_output(overlapping, {.max_feature = 1e-6}, &r);
  EXPECT_FALSE(r.clean);
  EXPECT_FALSE(r.problem.empty());
  EXPECT_LE(r.max_move, 1e-6);
}

TEST(OutputRounding, OpenMeshesAreLeftAlone) {
  PolygonMesh open = test_shapes::unit_cube();
  open.faces.pop_back();
  OutputRoundingReport r;
  const PolygonMesh out = round_for_output(open, {}, &r);
  EXPECT_FALSE(r.clean);
  EXPECT_EQ(out.faces, open.faces);
}

// The first pair of vertices at one point, as a scan in index order with a map finds it (the
// reference), on merged boxes sharing corners, with the vertices renumbered at random.
TEST(OutputRounding, FirstCoincidentVerticesAsAnIndexOrderScan) {
  std::mt19937 rng(5);
  for (int trial = 0; trial < 40; ++trial) {
    PolygonMesh m = test_shapes::merged(test_shapes::merged(test_shapes::box({0, 0, 0}, {1, 1, 1}),
                                                            test_shapes::box({1, 0, 0}, {2, 1, 1})),
                                        test_shapes::box({trial % 3 == 0 ? 0.5 : 1.0, 1, 0}, {2, 2, 1}));
    std::vector<int> perm(m.vertices.size());
    for (size_t i = 0; i < perm.size(); ++i) perm[i] = static_cast<int>(i);
    std::shuffle(perm.begin(), perm.end(), rng);
    PolygonMesh p = m;
    for (size_t i = 0; i < perm.size(); ++i) p.vertices[static_cast<size_t>(perm[i])] = m.vertices[i];
    for (auto& f : p.faces)
      for (int& v : f) v = perm[static_cast<size_t>(v)];
    std::map<std::array<double, 3>, int> seen;
    std::string expected;
    for (size_t v = 0; v < p.vertices.size() && expected.empty(); ++v) {
      const auto [it, inserted] = seen.insert({{p.vertices[v].x(), p.vertices[v].y(), p.vertices[v].z()}, int(v)});
      if (!inserted) expected = "vertices " + std::to_string(it->second) + " and " + std::to_string(v) + " are at the same point";
    }
    ASSERT_FALSE(expected.empty());
    EXPECT_EQ(output_problem(p), expected) << trial;
  }
}


// Exact-vertex marks (OutputRoundingOptions::exact_vertices) hold for the coordinates given: a
// vertex that the rounding to float32 moves loses its mark. Two boxes 1e-9 apart, every vertex
// marked: clean in doubles, but in float32 the second box's face lands inside the first's
// (coplanar overlap), which must still be found, and the result repaired.
TEST(OutputRounding, MarksOfVerticesTheRoundingMovesAreDropped) {
  const PolygonMesh m = test_shapes::merged(test_shapes::box({0, 0, 0}, {1, 1, 1}),
                                            test_shapes::box({1 + 1e-9, 0.25, 0.25}, {2, 0.75, 0.75}));
  const std::vector<char> marks(m.vertices.size(), 1);
  EXPECT_EQ(output_problem(m, {.exact_vertices = marks}), "");
  EXPECT_EQ(output_problem(m), "");
  const std::string unmarked = output_problem(m, {.precision = OutputPrecision::Float32});
  EXPECT_NE(unmarked.find("intersect"), std::string::npos) << unmarked;
  EXPECT_EQ(output_problem(m, {.precision = OutputPrecision::Float32, .exact_vertices = marks}), unmarked);
  OutputRoundingReport report;
  const PolygonMesh out = round_for_output(m, {.precision = OutputPrecision::Float32, .exact_vertices = marks}, &report);
  EXPECT_TRUE(report.changed);
  EXPECT_TRUE(report.clean) << report.problem;
  EXPECT_EQ(output_problem(out, {.precision = OutputPrecision::Float32}), "");
}

}  // namespace
}  // namespace sculpt
