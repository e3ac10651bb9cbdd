#include "revolution/revolve.hpp"
#include "revolution/trees/revolve_plane_tree.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "base/errors.hpp"
#include "bsp/boundary.hpp"
#include "bsp/classify.hpp"
#include "revolution/revolve_boundary.hpp"
#include "bsp/set_operations.hpp"
#include "curves/profiles.hpp"
#include "support/mesh_checks.hpp"

using namespace sculpt;
using namespace sculpt::revolution;
using namespace sculpt::revolution::detail;

namespace {

std::vector<Eigen::Vector2d> sampled(const curves::ProfileDesign& d, int points) {
  return curves::planar_points(curves::sample_profile(d, {.points = points, .noise = 0.004, .seed = 1990}).points);
}

/// Revolves and checks the solid against the polytope of its snapped inputs.
Solid revolve_and_check(const std::vector<Eigen::Vector2d>& profile, const ConvexPath& path) {
  const Solid s = revolve(profile, path);
  const SnappedRevolution snapped = snap_revolution(profile, path);
  const double expected = revolved_volume(snapped.profile, snapped.path);
  EXPECT_NEAR(volume(s), expected, 1e-9 * expected);
  // The snapped inputs are close to the given ones.
  EXPECT_NEAR(revolved_volume(profile, path), expected, 1e-3 * expected);
  const PolygonMesh mesh = to_mesh(s);
  EXPECT_TRUE(checks::EdgesManifoldAndOriented(mesh));
  EXPECT_TRUE(checks::VolumeNear(mesh, expected, 1e-9));
  return s;
}

}  // namespace

TEST(Revolve, VolumeEqualsTheAnalyticPolytopeVolumeAndTheMeshIsClosed) {
  revolve_and_check(sampled(curves::goblet_profile(), 21), circular_path(32));
  revolve_and_check(sampled(curves::human_profile(), 33), ellipse_path(1.0, 0.75, 32));
  revolve_and_check(sampled(curves::ball_profile(1.5, 6.8), 17), circular_path(32));
  revolve_and_check({{0, 0}, {2, 0}, {2, 1}, {1, 1}, {1, 2}, {1.5, 2}, {1.5, 3}, {0, 3.5}}, circular_path(12));
  revolve_and_check({{1, 0}, {1, 2}}, polygon_path({{0, -1}, {1, 1}, {-1, 0.5}}));
}

// Fine paths around thin profiles: edges down to a fraction of the grid step. Ring primitives
// once lost a sliver there (a rounded face plane left its wedge and the solid bent along an
// auxiliary plane); section-6 trees use exact lifted planes and must stay closed.
TEST(Revolve, FineTessellationsOfThinProfilesStayClosed) {
  const std::vector<Eigen::Vector2d> profile = {{0, 0}, {0.8, 0.05}, {0.3, 0.4}, {0.1, 1.0},
                                                {0.6, 1.6}, {0.9, 2.4}, {0, 2.5}};
  for (const double scale : {0.05, 0.002})
    for (const int n : {255, 1024}) {
      SCOPED_TRACE(testing::Message() << "scale " << scale << ", " << n << " edges");
      std::vector<Eigen::Vector2d> p;
      for (const auto& q : profile) p.push_back(q * scale);
      const Solid s = revolve(p, circular_path(n));
      const SnappedRevolution snapped = snap_revolution(p, circular_path(n));
      const PolygonMesh mesh = to_mesh(s);
      EXPECT_TRUE(checks::EdgesManifoldAndOriented(mesh));
      EXPECT_EQ(mesh.faces.size(), std::size_t(6 * n));
      const double expected = revolved_volume(snapped.profile, snapped.path);
      EXPECT_NEAR(volume(s), expected, 1e-9 * expected);
    }
}

TEST(Revolve, BoundaryHasGenusZeroAndLiesOnTheFacesOfTheDirectConstruction) {
  const auto profile = sampled(curves::goblet_profile(), 21);
  const Solid s = revolve(profile, circular_path(32));
  const PolygonMesh mesh = to_mesh(s);
  EXPECT_TRUE(checks::GenusIs(mesh, 0));
  // Exact planes: every face of the extracted boundary lies in the plane of a trapezoid or cap of
  // the polytope built directly (no crack or sliver faces between slabs), and the areas agree.
  const SnappedRevolution snapped = snap_revolution(profile, circular_path(32));
  const PolygonMesh direct = revolve_boundary(snapped.profile, snapped.path);
  auto plane_of = [](const PolygonMesh& m, const std::vector<int>& f) {
    Eigen::Vector3d n = Eigen::Vector3d::Zero(), c = Eigen::Vector3d::Zero();
    for (std::size_t k = 0; k < f.size(); ++k) {
      n += m.vertices[f[k]].cross(m.vertices[f[(k + 1) % f.size()]]);
      c += m.vertices[f[k]] / double(f.size());
    }
    return std::make_pair(Eigen::Vector3d(n.normalized()), 0.5 * n.norm());
  };
  double area = 0, direct_area = 0;
  for (const auto& f : direct.faces) direct_area += plane_of(direct, f).second;
  for (const auto& f : mesh.faces) {
    const auto [n, a] = plane_of(mesh, f);
    area += a;
    bool found = false;
    for (const auto& g : direct.faces) {
      const Eigen::Vector3d m = plane_of(direct, g).first;
      if (n.dot(m) > 1 - 1e-12 && std::abs(m.dot(mesh.vertices[f[0]] - direct.vertices[g[0]])) < 1e-9) {
        found = true;
        break;
      }
    }
    EXPECT_TRUE(found) << "face with normal " << n.transpose() << " at " << mesh.vertices[f[0]].transpose();
  }
  EXPECT_NEAR(area, direct_area, 1e-9 * direct_area);
}

TEST(Revolve, ClassifiesLikeThePlaneTreeAwayFromTheBoundary) {
  const auto profile = sampled(curves::human_profile(), 33);
  const ConvexPath path = ellipse_path(1.0, 0.8, 32);
  const Solid s = revolve(profile, path);
  const SnappedRevolution snapped = snap_revolution(profile, path);
  const PlaneTree reference = revolve_plane_tree(snapped.profile, snapped.path);
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> U(-3.5, 3.5), Z(-0.5, 8);
  int inside = 0;
  for (int i = 0; i < 20000; ++i) {
    const Eigen::Vector3d p(U(rng), U(rng), Z(rng));
    const Classification c = classify(s, p);
    if (c.location == Location::Boundary) continue;
    EXPECT_EQ(c.location == Location::Inside, reference.classify(p) == kIn) << p.transpose();
    inside += c.location == Location::Inside;
  }
  EXPECT_GT(inside, 1000);
}

// Section 6 bounds on the built solid (the builder may only remove nodes, never add).
TEST(Revolve, TreeSizeAndHeightMeetTheSectionSixBounds) {
  // Size counts partitioning nodes and leaves; below 3n per slab once n >= 10 (path_tree_test).
  for (int m : {4, 20, 32})
    for (int n : {16, 32, 64}) {
      const Solid s = revolve(sampled(curves::goblet_profile(), m + 1), circular_path(n));
      const TreeStats st = tree_stats(s);
      EXPECT_LE(st.nodes + st.in_leaves + st.out_leaves, 3 * n * m) << n << " " << m;
      EXPECT_LE(st.height, std::ceil(std::log2(m + 2)) + 3 * std::log2(n) + 4) << n << " " << m;
    }
  // The Figure 11 goblet: at most 3 x 20 x 32 nodes before set operations.
  const TreeStats goblet = tree_stats(revolve(sampled(curves::goblet_profile(), 21), circular_path(32)));
  EXPECT_LE(goblet.nodes + goblet.in_leaves + goblet.out_leaves, 3 * 20 * 32);
}

TEST(Revolve, CarvedCupAndBallSatisfyTheSetIdentities) {
  const ConvexPath path = circular_path(32);
  const Solid outer = revolve(sampled(curves::goblet_profile(), 21), path);
  const Solid cavity = revolve(sampled(curves::goblet_cavity_profile(), 13), path);
  const Solid ball = revolve(sampled(curves::ball_profile(1.5, 6.8), 17), path);
  const Solid cup = outer - cavity;
  const double v_outer = volume(outer), v_cavity_inside = volume(outer & cavity);
  EXPECT_NEAR(volume(cup), v_outer - v_cavity_inside, 1e-9 * v_outer);
  const Solid goblet = cup | ball;
  EXPECT_NEAR(volume(goblet), volume(cup) + volume(ball) - volume(cup & ball), 1e-9 * v_outer);
  EXPECT_GT(volume(cup & ball), 0.0);  // the ball really touches the cup
  EXPECT_TRUE(checks::EdgesManifoldAndOriented(to_mesh(goblet)));
}

TEST(Revolve, ReportsUnrepresentableInput) {
  EXPECT_THROW(revolve({{0, 0}, {1, 1}, {0, 2}, {1, 1.5}}, circular_path(8)), InvalidInput);
  EXPECT_THROW(revolve({{600, 0}, {600, 1}}, circular_path(8, 2.0)), RangeError);  // reaches 1200
  EXPECT_THROW(revolve({{1, 0}, {1, 1e-9}}, circular_path(8)), InvalidInput);     // flat on the grid
  EXPECT_THROW(revolve({{1, 0}, {1, 1}}, circular_path(4000)), GeometryError);    // too fine to stay convex
  EXPECT_THROW(revolve({{1, 0}, {1, 1}}, circular_path(8), {.face_only_below = 1}), InvalidInput);
}

// At another grid (docs/kernel.md, "World range"): a goblet in millimetres, 4 times the size of
// the default one at a grid 4 times coarser, is the default goblet scaled exactly; the reach of
// 1200 that the default grid refuses fits a coarser grid, which the message names.
TEST(Revolve, AtAnotherGridIsTheDefaultScaledExactly) {
  const kernel::Grid grid = kernel::Grid::from_shift(13);
  std::vector<Eigen::Vector2d> profile = sampled(curves::goblet_profile(), 21), big;
  for (const auto& p : profile) big.push_back(4 * p);
  const ConvexPath path = circular_path(32);
  const Solid s = revolve(profile, path), b = revolve(big, path, {.grid = grid});
  EXPECT_EQ(b.grid(), grid);
  EXPECT_EQ(volume(b), 64 * volume(s));
  const SnappedRevolution snapped = snap_revolution(big, path, {.grid = grid});
  EXPECT_NEAR(volume(b), revolved_volume(snapped.profile, snapped.path), 1e-9 * volume(b));
  try {
    (void)revolve({{600, 0}, {600, 1}}, circular_path(8, 2.0));
    FAIL();
  } catch (const RangeError& e) {
    EXPECT_NE(std::string(e.what()).find("a grid of step 2^-14 would fit coordinates up to 2048"), std::string::npos)
        << e.what();
  }
  const RevolveOptions coarser{.grid = kernel::Grid::from_shift(14)};
  const SnappedRevolution far = snap_revolution({{600, 0}, {600, 1}}, circular_path(8, 2.0), coarser);
  const double expected = revolved_volume(far.profile, far.path);
  EXPECT_NEAR(volume(revolve({{600, 0}, {600, 1}}, circular_path(8, 2.0), coarser)), expected, 1e-9 * expected);
}
