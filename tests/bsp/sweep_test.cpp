// sweep / carve / add against analytic swept volumes: a box along straight segments (exact), an
// L-shaped (non-convex) tool along an axis, a ball along a closed square path (a frame-like solid
// bounded by the exact sweep of the ball polytope).
#include "bsp/sweep.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <random>
#include <utility>

#include "base/errors.hpp"
#include "bsp/boundary.hpp"
#include "bsp/hull.hpp"
#include "bsp/primitives.hpp"
#include "bsp/rebuild.hpp"
#include "bsp/set_operations.hpp"
#include "bsp/transform.hpp"
#include "kernel/grid.hpp"
#include "support/mesh_checks.hpp"

namespace sculpt {
namespace {

using checks::EdgesManifoldAndOriented;

TEST(Sweep, ABoxAlongAPolylineHasTheExactSweptVolume) {
  const Solid cube = box({0, 0, 0}, {1, 1, 1});
  // Along x by 3 then along y by 2: two slabs of the Minkowski sum overlapping in the corner cube.
  const std::vector<Eigen::Vector3d> path{{0, 0, 0}, {3, 0, 0}, {3, 2, 0}};
  const Solid s = sweep(cube, path);
  EXPECT_DOUBLE_EQ(volume(s), 4.0 + 3.0 - 1.0);
  EXPECT_TRUE(EdgesManifoldAndOriented(to_mesh(s)));
  // A diagonal segment: 1 + |vx| + |vy| + |vz|.
  const std::vector<Eigen::Vector3d> diagonal{{0, 0, 0}, {0.5, -1.25, 2}};
  EXPECT_DOUBLE_EQ(volume(sweep(cube, diagonal)), 1 + 0.5 + 1.25 + 2);
}

TEST(Sweep, ANonConvexToolIsSweptCellByCell) {
  // An L of two boxes swept along z: a prism over the L, area 3, height 1 + 2.
  const Solid l = box({0, 0, 0}, {2, 1, 1}) | box({0, 1, 0}, {1, 2, 1});
  const std::vector<Eigen::Vector3d> path{{0, 0, 0}, {0, 0, 2}};
  const Solid s = sweep(l, path);
  EXPECT_NEAR(volume(s), 3.0 * 3.0, 1e-9);
  // Swept along x by 1: the L's x-extent grows by 1 in both arms (area 2 * 1 + ... = 5 per unit z).
  const std::vector<Eigen::Vector3d> along_x{{0, 0, 0}, {1, 0, 0}};
  EXPECT_NEAR(volume(sweep(l, along_x)), 5.0, 1e-9);
}

TEST(Sweep, OnePointMovesTheTool) {
  const Solid cube = box({0, 0, 0}, {1, 1, 1});
  const std::vector<Eigen::Vector3d> at{{2, 0, 0}, {2, 0, 0}};
  const Solid s = sweep(cube, at);
  EXPECT_DOUBLE_EQ(volume(s), 1.0);
  EXPECT_DOUBLE_EQ(volume(s & box({2, 0, 0}, {3, 1, 1})), 1.0);
  EXPECT_THROW(sweep(cube, std::vector<Eigen::Vector3d>{}), InvalidInput);
}

TEST(Sweep, CarveAndAddAreTheSetOperationsWithTheSweep) {
  const Solid block = box({-2, -2, -1}, {2, 2, 0});
  const Solid ball = sphere(0.5, {.segments = 16});
  const std::vector<Eigen::Vector3d> path{{-1.5, 0, 0}, {0, 0.5, 0}, {1.5, 0, 0}};
  const Solid swept = sweep(ball, path);
  const Solid carved = carve(block, ball, path);
  EXPECT_NEAR(volume(carved), volume(block) - volume(block & swept), 1e-9);
  EXPECT_LT(volume(carved), volume(block));
  EXPECT_TRUE(EdgesManifoldAndOriented(to_mesh(carved)));
  const Solid added = add(block, ball, path);
  EXPECT_NEAR(volume(added), volume(block) + volume(swept) - volume(block & swept), 1e-9);
  // The ball polytope's sweep lies between the sweep of its inscribed and circumscribed balls:
  // the capsule volume pi r^2 L + 4/3 pi r^3 bounds it from above for r = 0.5 (vertices on the
  // sphere), and the tool itself at each end is inside.
  const double length = (path[1] - path[0]).norm() + (path[2] - path[1]).norm();
  EXPECT_LT(volume(swept), M_PI * 0.25 * length + 4.0 / 3 * M_PI * 0.125 + 1e-9);
  // The ball's vertices (plane intersections) are rounded to the grid for the hulls: each end of
  // the stroke is covered up to that rounding.
  const double bound = surface_area(ball) * std::sqrt(3.0) / 2 * kernel::kGridStep;
  EXPECT_LE(volume(translate(ball, path[0]) - swept), bound);
  EXPECT_LE(volume(translate(ball, path[2]) - swept), bound);
}

/// The old construction of a sweep, kept as the reference: each segment's hull as a solid
/// (bsp/hull.hpp, its own tree), united by unite_all (batch_union.hpp).
Solid sweep_by_hull_solids(const Solid& convex_tool, const std::vector<Eigen::Vector3d>& path) {
  const std::vector<Eigen::Vector3d> vertices = to_mesh(convex_tool).vertices;
  std::vector<Solid> parts;
  for (std::size_t i = 0; i + 1 < path.size(); ++i) {
    std::vector<Eigen::Vector3d> ends;
    for (const Eigen::Vector3d& v : vertices) {
      ends.push_back(convex_tool.grid().to_world(convex_tool.grid().snap(v)) + path[i]);
      ends.push_back(convex_tool.grid().to_world(convex_tool.grid().snap(v)) + path[i + 1]);
    }
    parts.push_back(hull(ends, convex_tool.grid()));
  }
  return unite_all(std::move(parts));
}

TEST(Sweep, EqualsTheUnionOfTheSegmentHullsAsSolids) {
  // Short segments (each hull overlaps several others), a sharp turn, a segment back along the
  // previous one (coplanar faces of opposite and equal orientation), and a box whose faces are
  // shared exactly by consecutive hulls.
  const Solid ball = sphere(0.15, {.segments = 16});
  const Solid cube = box({0, 0, 0}, {0.5, 0.5, 0.5});
  std::vector<Eigen::Vector3d> arc;
  for (int i = 0; i <= 12; ++i) arc.emplace_back(std::cos(0.05 * i), std::sin(0.05 * i), 0.02 * std::sin(3.0 * i));
  const std::vector<Eigen::Vector3d> turns{{0, 0, 0}, {0.5, 0, 0}, {0.5, 0.25, 0}, {0.25, 0.25, 0}, {0.5, 0.25, 0}, {0.5, 0.25, 0.3}};
  for (const Solid* tool : {&ball, &cube})
    for (const std::vector<Eigen::Vector3d>* path : {&std::as_const(arc), &turns}) {
      std::vector<Eigen::Vector3d> on_grid;  // sweep snaps the path; so does the reference
      for (const Eigen::Vector3d& p : *path) on_grid.push_back(tool->grid().to_world(tool->grid().snap(p)));
      const Solid s = sweep(*tool, *path);
      const Solid reference = sweep_by_hull_solids(*tool, on_grid);
      EXPECT_TRUE((s - reference).is_empty());
      EXPECT_TRUE((reference - s).is_empty());
      EXPECT_NEAR(volume(s), volume(reference), 1e-12 * volume(reference));
      EXPECT_TRUE(EdgesManifoldAndOriented(to_mesh(s)));
    }
}

TEST(Sweep, DegeneratePathsAndOtherToolsEqualTheReference) {
  // Paths with repeated points, collinear runs, reversals and segments along the axes and
  // diagonals; tools: a coarse ball, a tetrahedron (its faces' normals meet segments at n.d = 0),
  // and a box (faces parallel to axis segments: stretched faces and coplanar parallelograms).
  const Solid coarse = sphere(0.2, {.segments = 8});
  const std::vector<Eigen::Vector3d> corners{{0, 0, 0}, {0.25, 0, 0}, {0, 0.25, 0}, {0, 0, 0.25}};
  const Solid tetra = hull(corners);
  const Solid cube = box({-0.1, -0.1, -0.1}, {0.1, 0.1, 0.1});
  const std::vector<std::vector<Eigen::Vector3d>> paths{
      {{0, 0, 0}, {0, 0, 0}, {0.3, 0, 0}, {0.3, 0, 0}, {0.6, 0, 0}},  // repeated and collinear along x
      {{0, 0, 0}, {0.5, 0, 0}, {0.1, 0, 0}, {0.4, 0, 0}},             // back and forth on one line
      {{0, 0, 0}, {0, 0.3, 0}, {0, 0.3, 0.3}, {0.3, 0.3, 0.3}},       // along y, z, x
      {{0, 0, 0}, {0.2, 0.2, 0.2}, {0.4, 0.4, 0}, {0.2, 0.2, 0.2}},   // diagonals, then back
      {{0, 0, 0}, {0.05, 0.01, 0}, {0.1, 0.03, 0.01}, {0.15, 0.06, 0.01}, {0.2, 0.1, 0.03}},  // short, turning
  };
  for (const Solid* tool : {&coarse, &tetra, &cube})
    for (std::size_t k = 0; k < paths.size(); ++k) {
      std::vector<Eigen::Vector3d> on_grid;  // the reference gets the snapped path, repeated points dropped
      for (const Eigen::Vector3d& p : paths[k]) {
        const Eigen::Vector3d g = tool->grid().to_world(tool->grid().snap(p));
        if (on_grid.empty() || g != on_grid.back()) on_grid.push_back(g);
      }
      const Solid s = sweep(*tool, paths[k]);
      const Solid reference = sweep_by_hull_solids(*tool, on_grid);
      EXPECT_TRUE((s - reference).is_empty()) << "path " << k;
      EXPECT_TRUE((reference - s).is_empty()) << "path " << k;
      EXPECT_TRUE(EdgesManifoldAndOriented(to_mesh(s))) << "path " << k;
    }
  // A non-convex tool (an L of two boxes), swept cell by cell: the union of its boxes' sweeps.
  const Solid arm = box({0, 0, 0}, {0.4, 0.1, 0.1}), leg = box({0, 0.1, 0}, {0.1, 0.3, 0.1});
  const Solid l = arm | leg;
  for (std::size_t k = 0; k < paths.size(); ++k) {
    const Solid s = sweep(l, paths[k]);
    const Solid reference = sweep(arm, paths[k]) | sweep(leg, paths[k]);
    EXPECT_TRUE((s - reference).is_empty()) << "L, path " << k;
    EXPECT_TRUE((reference - s).is_empty()) << "L, path " << k;
  }
}

TEST(Sweep, RandomToolsAlongRandomPathsEqualTheReference) {
  // Random hulls of 7 points, balls of 4-12 segments and a box, along random paths with repeated
  // points, steps along x and steps back to the point before: the sweep equals the union of the
  // segment hulls built as solids.
  std::mt19937 rng(99);
  std::uniform_real_distribution<double> u(-0.3, 0.3);
  std::uniform_int_distribution<int> pick(0, 3), length(2, 7), segments(4, 12);
  for (int trial = 0; trial < 30; ++trial) {
    Solid tool;
    const int kind = pick(rng);
    if (kind == 0) {
      tool = sphere(0.05 + 0.1 * std::abs(u(rng)), {.segments = segments(rng)});
    } else if (kind == 1) {
      tool = box({0, 0, 0}, {0.1, 0.05, 0.2});
    } else {
      std::vector<Eigen::Vector3d> points;
      for (int i = 0; i < 7; ++i) points.emplace_back(u(rng), u(rng), u(rng));
      tool = hull(points);
    }
    std::vector<Eigen::Vector3d> path;
    Eigen::Vector3d p(u(rng), u(rng), u(rng));
    for (int i = 0, n = length(rng); i < n; ++i) {
      const int step = pick(rng);
      if (step == 0) path.push_back(p);  // the point repeated
      else if (step == 1) p += Eigen::Vector3d(0.05, 0, 0);
      else if (step == 2 && path.size() >= 2) p = path[path.size() - 2];
      else p += Eigen::Vector3d(0.3 * u(rng), 0.3 * u(rng), 0.3 * u(rng));
      path.push_back(p);
    }
    std::vector<Eigen::Vector3d> on_grid;
    for (const Eigen::Vector3d& q : path) {
      const Eigen::Vector3d g = tool.grid().to_world(tool.grid().snap(q));
      if (on_grid.empty() || g != on_grid.back()) on_grid.push_back(g);
    }
    if (on_grid.size() < 2) continue;
    const Solid s = sweep(tool, path);
    const Solid reference = sweep_by_hull_solids(tool, on_grid);
    EXPECT_TRUE((s - reference).is_empty()) << "trial " << trial;
    EXPECT_TRUE((reference - s).is_empty()) << "trial " << trial;
  }
}

TEST(Sweep, ManyStrokesCarveWhatEachSweepCovers) {
  // Ten strokes into a block, each checked against volume(work) - volume(work & sweep) computed
  // from the sweep separately; the result stays a closed, consistently oriented surface.
  Solid work = box({-1, -1, -1}, {1, 1, 0});
  const Solid ball = sphere(0.2, {.segments = 12});
  for (int k = 0; k < 10; ++k) {
    std::vector<Eigen::Vector3d> path;
    for (int i = 0; i <= 8; ++i) {
      const double t = 0.7 * k + 0.15 * i;
      path.emplace_back(0.6 * std::cos(t), 0.6 * std::sin(t), 0.05 * std::sin(2.0 * t));
    }
    const Solid swept = sweep(ball, path);
    const double expected = volume(work) - volume(work & swept);
    work = carve(work, ball, path);
    EXPECT_NEAR(volume(work), expected, 1e-9) << "stroke " << k;
    EXPECT_TRUE((work & swept).is_empty()) << "stroke " << k;
  }
  EXPECT_TRUE(EdgesManifoldAndOriented(to_mesh(work)));
  // A new tree from the boundary: the same solid exactly, with no more nodes than the carved tree
  // (as many when the strokes went by cells: their result's tree is built from its boundary).
  const Solid rebuilt = rebuild_from_boundary(work);
  EXPECT_TRUE((rebuilt - work).is_empty());
  EXPECT_TRUE((work - rebuilt).is_empty());
  EXPECT_LE(tree_stats(rebuilt).nodes, tree_stats(work).nodes);
  EXPECT_TRUE(EdgesManifoldAndOriented(to_mesh(rebuilt)));
  EXPECT_TRUE(rebuild_from_boundary(Solid()).is_empty());
  EXPECT_EQ(rebuild_from_boundary(Solid::leaf(true)).root(), kIn);
}

TEST(Sweep, InPlaceStrokesReuseTheFreedStorage) {
  // Fifteen strokes in place (carving and adding), each the same set as the copying operation
  // and its storage bounded (reclaim_added frees the slots of the nodes a stroke cuts away and
  // gives them to the nodes later strokes keep).
  Solid work = box({-1, -1, -1}, {1, 1, 0});
  const Solid ball = sphere(0.2, {.segments = 8});
  std::size_t most_live = 0;
  for (int k = 0; k < 15; ++k) {
    std::vector<Eigen::Vector3d> path;
    for (int i = 0; i <= 8; ++i) {
      const double t = 0.9 * k + 0.15 * i;
      path.emplace_back(0.6 * std::cos(t), 0.6 * std::sin(t), 0.1 * std::sin(2.0 * t) - (k % 3 == 2 ? 0.3 : 0.0));
    }
    const Solid copied = k % 3 == 2 ? add(work, ball, path) : carve(work, ball, path);
    // In place, carve and add in their two steps: the set operation, then rebuild_region.
    const Solid swept = sweep(ball, path);
    work = k % 3 == 2 ? std::move(work) | swept : std::move(work) - swept;
    const auto live = std::size_t(tree_stats(work).nodes);
    RegionRebuildStats rebuilt;
    work = rebuild_region(std::move(work), swept, {}, &rebuilt);
    most_live = std::max(most_live, live + std::size_t(rebuilt.nodes_after));
    EXPECT_TRUE((work - copied).is_empty()) << "stroke " << k;
    EXPECT_TRUE((copied - work).is_empty()) << "stroke " << k;
    // Freed slots are taken before the storage grows, so it holds little more than the most
    // nodes the tree has had at once (the slots a stroke frees are taken from the next stroke
    // on; a rebuilt subtree's new nodes are made while the old ones are still there).
    EXPECT_LT(double(work.nodes().size()), 1.25 * double(std::max<std::size_t>(most_live, 64))) << "stroke " << k;
    EXPECT_EQ(work.polygons().size(), work.nodes().size()) << "stroke " << k;
  }
  EXPECT_TRUE(EdgesManifoldAndOriented(to_mesh(work)));
}

TEST(SweepMotion, TranslationsGiveThePathSweep) {
  const Solid cube = box({0, 0, 0}, {1, 1, 1});
  const std::vector<Eigen::Vector3d> path{{0, 0, 0}, {3, 0, 0}, {3, 2, 0}};
  std::vector<Eigen::Isometry3d> poses;
  for (const auto& p : path) poses.push_back(Eigen::Isometry3d(Eigen::Translation3d(p)));
  EXPECT_DOUBLE_EQ(volume(sweep(cube, poses)), volume(sweep(cube, path)));
  EXPECT_THROW(sweep(cube, std::vector<Eigen::Isometry3d>{}), InvalidInput);
}

TEST(SweepMotion, ABarTurningAboutItsEndCoversAQuarterDisk) {
  // A bar [0, L] x [-w, w] x [-h, h] turning by 90 degrees about the z axis: the swept region is
  // the quarter disk of radius R = sqrt(L^2 + w^2) and the two strips {0 <= -y <= w, x >= 0} and
  // {0 <= -x <= w, y >= 0} inside that radius (area integral_0^w sqrt(R^2 - y^2) dy each), times 2 h.
  const double L = 4, w = 0.5, h = 0.5, R = std::hypot(L, w);
  const Solid bar = box({0, -w, -h}, {L, w, h});
  const int steps = 64;
  std::vector<Eigen::Isometry3d> poses;
  for (int i = 0; i <= steps; ++i)
    poses.push_back(Eigen::Isometry3d(Eigen::AngleAxisd(M_PI / 2 * i / steps, Eigen::Vector3d::UnitZ())));
  const Solid s = sweep(bar, poses);
  EXPECT_TRUE(EdgesManifoldAndOriented(to_mesh(s)));
  const double strip = 0.5 * (w * L + R * R * std::asin(w / R));
  const double exact = 2 * h * (M_PI * R * R / 4 + 2 * strip);
  // The bound of sweep.hpp: chord error R (1 - cos(d/2)) plus 1/4 |R_i - R_i+1| diam = 1/4 * 2 sin(d/2) * diam,
  // times the area, plus the grid rounding of the rotated vertices.
  const double d = M_PI / 2 / steps, diam = std::sqrt(L * L + 4 * w * w + 4 * h * h);
  const double hausdorff = R * (1 - std::cos(d / 2)) + 0.5 * std::sin(d / 2) * diam + kernel::kGridStep;
  EXPECT_NEAR(volume(s), exact, hausdorff * surface_area(s));
  EXPECT_GT(volume(s), 2 * h * (M_PI * L * L / 4));  // far more than a translation could give
  for (int i : {0, steps / 3, steps}) {
    const Solid at = transform(bar, Eigen::Affine3d(poses[i].matrix()));
    EXPECT_LE(volume(at - s), surface_area(at) * std::sqrt(3.0) * kernel::kGridStep) << i;
  }
}

}  // namespace
}  // namespace sculpt
