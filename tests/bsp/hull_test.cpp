// hull() as a solid: analytic volumes (boxes, a cube swept along a segment as the hull of its two
// ends: 1 + |vx| + |vy| + |vz|), the hull of a convex solid is itself, classification against the
// hull's own face planes computed independently by brute force on small sets.
#include "bsp/hull.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "bsp/boundary.hpp"
#include "bsp/classify.hpp"
#include "bsp/primitives.hpp"
#include "bsp/set_operations.hpp"
#include "bsp/transform.hpp"
#include "kernel/grid.hpp"
#include "support/mesh_checks.hpp"

namespace sculpt {
namespace {

using checks::EdgesManifoldAndOriented;
using checks::GenusIs;

TEST(Hull, OfABoxsCornersAndInteriorPointsIsTheBox) {
  std::vector<Eigen::Vector3d> pts;
  for (double x : {0.0, 0.5, 2.0})
    for (double y : {0.0, 1.0, 3.0})
      for (double z : {0.0, 0.25, 0.5, 1.0}) pts.emplace_back(x, y, z);
  const Solid h = hull(pts);
  EXPECT_DOUBLE_EQ(volume(h), 6.0);
  const PolygonMesh m = to_mesh(h);
  EXPECT_EQ(m.faces.size(), 6u);  // coplanar triangles merged: one plane per face
  EXPECT_EQ(m.vertices.size(), 8u);
  EXPECT_TRUE(EdgesManifoldAndOriented(m));
}

TEST(Hull, ACubeSweptAlongASegmentHasTheMinkowskiVolume) {
  // The hull of a unit cube and its translate by v is the cube swept along v: 1 + |vx| + |vy| + |vz|.
  const Solid cube = box({0, 0, 0}, {1, 1, 1});
  for (const Eigen::Vector3d& v : {Eigen::Vector3d(2, 0, 0), Eigen::Vector3d(1, 2, 0), Eigen::Vector3d(0.5, -1.25, 3),
                                  Eigen::Vector3d(-3, -0.125, 0.75)}) {
    const std::vector<Solid> ends{cube, translate(cube, v)};
    const Solid swept = hull(ends);
    EXPECT_DOUBLE_EQ(volume(swept), 1 + v.cwiseAbs().sum()) << v.transpose();
    const PolygonMesh m = to_mesh(swept);
    EXPECT_TRUE(EdgesManifoldAndOriented(m));
    EXPECT_TRUE(GenusIs(m, 0));
    // Both ends are inside the hull.
    EXPECT_EQ(volume(ends[0] - swept), 0.0);
    EXPECT_EQ(volume(ends[1] - swept), 0.0);
  }
}

TEST(Hull, OfAConvexSolidIsTheSolid) {
  // A hull's vertices are grid points: its hull is itself, exactly.
  std::mt19937 rng(5);
  std::normal_distribution<double> g;
  std::vector<Eigen::Vector3d> pts;
  for (int i = 0; i < 200; ++i) pts.push_back(Eigen::Vector3d(g(rng), g(rng), g(rng)).normalized());
  const std::vector<Solid> one{hull(pts)};
  const Solid h = hull(one);
  EXPECT_GT(volume(h), 3.5);
  EXPECT_EQ(volume(one[0] - h), 0.0);
  EXPECT_EQ(volume(h - one[0]), 0.0);
  // A sphere primitive's vertices are plane intersections, rounded to the grid first: the hull
  // differs from it by at most area * sqrt(3)/2 grid steps either way.
  const Solid s = sphere(1.0, {.segments = 24});
  const std::vector<Solid> ball{s};
  const Solid hs = hull(ball);
  const double bound = surface_area(s) * std::sqrt(3.0) / 2 * kernel::kGridStep;
  EXPECT_LE(volume(s - hs), bound);
  EXPECT_LE(volume(hs - s), bound);
}

TEST(Hull, PointsClassifyAgainstBruteForcePlanes) {
  std::mt19937 rng(11);
  std::uniform_int_distribution<int> c(-4, 4);
  for (int trial = 0; trial < 20; ++trial) {
    std::vector<Eigen::Vector3d> pts;
    for (int i = 0; i < 12; ++i) pts.emplace_back(c(rng) * 0.25, c(rng) * 0.25, c(rng) * 0.25);
    const Solid h = hull(pts);
    if (volume(h) == 0) continue;
    // Brute force: the supporting planes through three points (every point on one side); q is
    // outside the hull iff it is strictly beyond one of them. Quarter coordinates: exact doubles.
    std::vector<std::pair<Eigen::Vector3d, double>> planes;  // n.q <= offset inside
    for (size_t i = 0; i < pts.size(); ++i)
      for (size_t j = i + 1; j < pts.size(); ++j)
        for (size_t k = j + 1; k < pts.size(); ++k) {
          Eigen::Vector3d n = (pts[j] - pts[i]).cross(pts[k] - pts[i]);
          if (n.isZero()) continue;
          int above = 0, below = 0;
          for (const auto& p : pts) {
            const double s = n.dot(p - pts[i]);
            above += s > 0, below += s < 0;
          }
          if (above && below) continue;
          if (above) n = -n;
          planes.emplace_back(n, n.dot(pts[i]));
        }
    for (int x = -9; x <= 9; ++x)
      for (int y = -9; y <= 9; ++y)
        for (int z = -9; z <= 9; ++z) {
          const Eigen::Vector3d q(x * 0.125, y * 0.125, z * 0.125);
          bool outside = false;
          for (const auto& [n, offset] : planes) outside |= n.dot(q) > offset;
          EXPECT_EQ(classify(h, q).location == Location::Outside, outside) << "trial " << trial << " q " << q.transpose();
        }
  }
}

TEST(Hull, CoplanarPointsGiveTheEmptySolid) {
  const std::vector<Eigen::Vector3d> pts{{0, 0, 1}, {1, 0, 1}, {0, 1, 1}, {1, 1, 1}};
  EXPECT_EQ(volume(hull(pts)), 0.0);
}

}  // namespace
}  // namespace sculpt
