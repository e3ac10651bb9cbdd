// convex_hull against a brute-force reference on small, highly degenerate point sets: the set of
// supporting face planes (every plane through three input points with all points on one side),
// closedness of the triangle surface, and the dimension of flat sets.
#include "kernel/convex_hull.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <random>
#include <set>
#include <tuple>

#include "kernel/plane.hpp"
#include "kernel/predicates.hpp"

namespace sculpt::kernel {
namespace {

using PlaneKey = std::tuple<std::int64_t, std::int64_t, std::int64_t, Int128>;
PlaneKey key(const Plane& p) { return {p.a, p.b, p.c, p.d}; }

bool collinear(const GridPoint& a, const GridPoint& b, const GridPoint& c) {
  const Int128 ux = b.x - a.x, uy = b.y - a.y, uz = b.z - a.z;
  const Int128 vx = c.x - a.x, vy = c.y - a.y, vz = c.z - a.z;
  return uy * vz - uz * vy == 0 && uz * vx - ux * vz == 0 && ux * vy - uy * vx == 0;
}

/// Brute force: the outward planes through three points with every point on or below them.
std::set<PlaneKey> supporting_planes(const std::vector<GridPoint>& pts) {
  std::set<PlaneKey> out;
  const size_t n = pts.size();
  for (size_t i = 0; i < n; ++i)
    for (size_t j = i + 1; j < n; ++j)
      for (size_t k = j + 1; k < n; ++k) {
        if (collinear(pts[i], pts[j], pts[k])) continue;
        const Plane p = plane_through(pts[i], pts[j], pts[k]);
        bool above = false, below = false;
        for (const GridPoint& q : pts) {
          const Sign s = orient(q, p);
          above |= s == Sign::Positive;
          below |= s == Sign::Negative;
        }
        if (!above) out.insert(key(p));
        if (!below) out.insert(key(p.opposite()));
      }
  return out;
}

void expect_hull_matches_brute_force(const std::vector<GridPoint>& pts, const std::string& what) {
  const ConvexHull h = convex_hull(pts);
  ASSERT_EQ(h.dimension, 3) << what;
  std::set<PlaneKey> planes;
  for (const auto& t : h.triangles) planes.insert(key(plane_through(h.vertices[t[0]], h.vertices[t[1]], h.vertices[t[2]])));
  EXPECT_EQ(planes, supporting_planes(pts)) << what;
  // A closed surface: each directed edge once, its reverse once; Euler characteristic 2.
  std::map<std::pair<int, int>, int> edges;
  for (const auto& t : h.triangles)
    for (int k = 0; k < 3; ++k) ++edges[{t[k], t[(k + 1) % 3]}];
  for (const auto& [e, count] : edges) {
    EXPECT_EQ(count, 1) << what;
    EXPECT_EQ(edges.count({e.second, e.first}), 1u) << what;
  }
  EXPECT_EQ(int(h.vertices.size()) - int(edges.size() / 2) + int(h.triangles.size()), 2) << what;
  // The adjacency: the triangle across edge k of t holds that edge reversed.
  ASSERT_EQ(h.neighbours.size(), h.triangles.size()) << what;
  for (std::size_t t = 0; t < h.triangles.size(); ++t)
    for (int k = 0; k < 3; ++k) {
      const int g = h.neighbours[t][std::size_t(k)];
      ASSERT_GE(g, 0) << what;
      ASSERT_LT(std::size_t(g), h.triangles.size()) << what;
      bool reversed = false;
      for (int j = 0; j < 3; ++j)
        reversed |= h.triangles[std::size_t(g)][std::size_t(j)] == h.triangles[t][std::size_t((k + 1) % 3)] &&
                    h.triangles[std::size_t(g)][std::size_t((j + 1) % 3)] == h.triangles[t][std::size_t(k)];
      EXPECT_TRUE(reversed) << what << " triangle " << t << " edge " << k;
    }
  // Every hull vertex is an input point.
  for (const GridPoint& v : h.vertices) EXPECT_NE(std::find(pts.begin(), pts.end(), v), pts.end()) << what;
}

TEST(ConvexHull, RandomPointsOnASmallGridWithManyCoplanarAndRepeatedPoints) {
  std::mt19937 rng(7);
  for (int trial = 0; trial < 60; ++trial) {
    const int side = 2 + trial % 4;  // coordinates in [0, side]: lots of coplanar and repeated points
    std::uniform_int_distribution<int> coord(0, side);
    std::vector<GridPoint> pts;
    const int n = 8 + trial % 25;
    for (int i = 0; i < n; ++i) pts.push_back({coord(rng), coord(rng), coord(rng)});
    if (convex_hull(pts).dimension < 3) continue;
    expect_hull_matches_brute_force(pts, "trial " + std::to_string(trial));
  }
}

TEST(ConvexHull, AllPointsOfACubeGridGiveTheCube) {
  std::vector<GridPoint> pts;
  for (int x = 0; x <= 3; ++x)
    for (int y = 0; y <= 3; ++y)
      for (int z = 0; z <= 3; ++z) pts.push_back({x, y, z});
  const ConvexHull h = convex_hull(pts);
  ASSERT_EQ(h.dimension, 3);
  std::set<PlaneKey> planes;
  for (const auto& t : h.triangles) planes.insert(key(plane_through(h.vertices[t[0]], h.vertices[t[1]], h.vertices[t[2]])));
  EXPECT_EQ(planes.size(), 6u);
  expect_hull_matches_brute_force(pts, "cube grid");
}

TEST(ConvexHull, FlatSetsHaveNoVolume) {
  EXPECT_EQ(convex_hull(std::vector<GridPoint>{}).dimension, 0);
  EXPECT_EQ(convex_hull(std::vector<GridPoint>{{1, 2, 3}, {1, 2, 3}}).dimension, 0);
  EXPECT_EQ(convex_hull(std::vector<GridPoint>{{0, 0, 0}, {1, 1, 1}, {3, 3, 3}, {2, 2, 2}}).dimension, 1);
  const ConvexHull flat = convex_hull(std::vector<GridPoint>{{0, 0, 5}, {4, 0, 5}, {0, 4, 5}, {3, 3, 5}, {1, 1, 5}});
  EXPECT_EQ(flat.dimension, 2);
  EXPECT_TRUE(flat.triangles.empty());
}

TEST(ConvexHull, ExtremeCoordinatesAreExact) {
  // Corners at the ends of the grid range, and a point a single grid unit outside a face.
  const std::int64_t m = kMaxCoord;
  std::vector<GridPoint> pts{{-m, -m, -m}, {m, -m, -m}, {-m, m, -m}, {-m, -m, m}, {m, m, m - 1}};
  expect_hull_matches_brute_force(pts, "extreme");
  pts.push_back({m - 1, m - 1, m - 1});  // just inside or on? decided exactly by the reference too
  expect_hull_matches_brute_force(pts, "extreme plus one");
}

TEST(ConvexHull, PointsOnASphereAreAllCorners) {
  std::mt19937 rng(3);
  std::normal_distribution<double> g;
  std::vector<GridPoint> pts;
  for (int i = 0; i < 400; ++i) {
    double x = g(rng), y = g(rng), z = g(rng);
    const double r = std::sqrt(x * x + y * y + z * z);
    pts.push_back({std::llround(1e6 * x / r), std::llround(1e6 * y / r), std::llround(1e6 * z / r)});
  }
  const ConvexHull h = convex_hull(pts);
  ASSERT_EQ(h.dimension, 3);
  EXPECT_EQ(h.vertices.size(), 400u);  // points on a sphere, in general position
  // Every input point on or below every face (the definition of the hull).
  for (const auto& t : h.triangles) {
    const Plane p = plane_through(h.vertices[t[0]], h.vertices[t[1]], h.vertices[t[2]]);
    for (const GridPoint& q : pts) ASSERT_NE(orient(q, p), Sign::Positive);
  }
}

}  // namespace
}  // namespace sculpt::kernel
