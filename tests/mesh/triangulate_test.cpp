// Ear clipping of non-convex and collinear polygons: area preserved, every triangle oriented
// like the polygon and of positive area, every corner used (no T-junction left).
#include "mesh/triangulate.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <numbers>
#include <random>
#include <set>

#include "base/errors.hpp"

namespace sculpt {
namespace {

/// Shoelace area of a polygon given in the xy plane (signed, counter-clockwise positive).
double shoelace(const std::vector<Eigen::Vector3d>& v, const std::vector<int>& face) {
  double a = 0;
  for (size_t i = 0; i < face.size(); ++i) {
    const auto &p = v[face[i]], &q = v[face[(i + 1) % face.size()]];
    a += p.x() * q.y() - q.x() * p.y();
  }
  return a / 2;
}

/// Checks a triangulation of a polygon lying in z = 0 (after `to_plane`, identity by default).
void check(const std::vector<Eigen::Vector3d>& v, const std::vector<int>& face, double expected_area,
           const Eigen::Vector3d& normal = Eigen::Vector3d::UnitZ()) {
  for (const EarOrder order : {EarOrder::Fan, EarOrder::Spread}) {
  std::vector<IndexTriangle> tris;
  PolygonTriangulator().append(v, face, tris, order);
  if (order == EarOrder::Fan) {
    EXPECT_EQ(tris, triangulate_polygon(v, face));
  }
  double area = 0;
  std::set<int> used;
  for (const auto& t : tris) {
    const Eigen::Vector3d n = (v[t[1]] - v[t[0]]).cross(v[t[2]] - v[t[0]]);
    EXPECT_GT(n.dot(normal), 0) << "triangle " << t[0] << " " << t[1] << " " << t[2]
                                << " is reversed or has zero area";
    area += 0.5 * n.norm();
    used.insert(t.begin(), t.end());
  }
  EXPECT_NEAR(area, expected_area, 1e-12 * std::max(1.0, expected_area));
  EXPECT_EQ(used, std::set<int>(face.begin(), face.end())) << "a corner is not used (T-junction)";
  EXPECT_EQ(tris.size(), face.size() - 2);
  }
}

std::vector<Eigen::Vector3d> xy(std::initializer_list<std::pair<double, double>> pts) {
  std::vector<Eigen::Vector3d> v;
  for (auto [x, y] : pts) v.emplace_back(x, y, 0);
  return v;
}

std::vector<int> iota_face(size_t n) {
  std::vector<int> f(n);
  for (size_t i = 0; i < n; ++i) f[i] = static_cast<int>(i);
  return f;
}

TEST(Triangulate, LShape) {
  const auto v = xy({{0, 0}, {2, 0}, {2, 1}, {1, 1}, {1, 2}, {0, 2}});
  check(v, iota_face(6), 3);
}

TEST(Triangulate, Comb) {
  // Teeth pointing up: 4 teeth of width 1 with gaps of width 1.
  std::vector<Eigen::Vector3d> v = {{0, 0, 0}, {7, 0, 0}};
  for (int i = 3; i >= 0; --i) {
    v.emplace_back(2 * i + 1, 3, 0);
    v.emplace_back(2 * i, 3, 0);
    if (i > 0) {
      v.emplace_back(2 * i, 1, 0);
      v.emplace_back(2 * i - 1, 1, 0);
    }
  }
  const auto f = iota_face(v.size());
  ASSERT_GT(shoelace(v, f), 0);
  check(v, f, shoelace(v, f));
  EXPECT_DOUBLE_EQ(shoelace(v, f), 7 + 4 * 2);
}

TEST(Triangulate, SquareWithCollinearMidpoints) {
  const auto v = xy({{0, 0}, {1, 0}, {2, 0}, {2, 1}, {2, 2}, {1, 2}, {0, 2}, {0, 1}});
  check(v, iota_face(8), 4);
  // A triangle with many points on one edge: the fan must come from the opposite corner.
  const auto w = xy({{0, 0}, {0.25, 0}, {0.5, 0}, {0.75, 0}, {1, 0}, {0, 1}});
  check(w, iota_face(6), 0.5);
}

TEST(Triangulate, ClockwiseAndTiltedPolygonsKeepTheirOrientation) {
  auto v = xy({{0, 0}, {0, 2}, {1, 1}, {2, 2}, {2, 0}});  // clockwise seen from +z: normal -z
  check(v, iota_face(5), 3, -Eigen::Vector3d::UnitZ());
  // The same shape rotated into a general plane.
  const Eigen::Matrix3d r =
      (Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()) * Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitX()))
          .toRotationMatrix();
  for (auto& p : v) p = r * p + Eigen::Vector3d(5, -3, 2);
  check(v, iota_face(5), 3, r * -Eigen::Vector3d::UnitZ());
}

TEST(Triangulate, RandomStarShapedPolygons) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> radius(0.2, 1.0);
  for (int trial = 0; trial < 200; ++trial) {
    const int n = 3 + trial % 40;
    std::vector<Eigen::Vector3d> v;
    for (int i = 0; i < n; ++i) {
      const double a = 2 * std::numbers::pi * i / n, r = radius(rng);
      v.emplace_back(r * std::cos(a), r * std::sin(a), 0);
    }
    const auto f = iota_face(v.size());
    check(v, f, shoelace(v, f));
  }
}

// Strictly convex polygons (the exact convexity test lets ear clipping skip its containment
// scan): both orders cover the polygon; the fan order keeps its triangles (all through corner 1,
// as the containment scan finds no corner in any ear), the spread order's triangles are mostly
// small (the sum of their box areas stays within a few times the polygon's, where the fan's grows
// with the corner count).
TEST(Triangulate, ConvexPolygonsFanAndSpread) {
  for (const int n : {5, 16, 64, 256}) {
    std::vector<Eigen::Vector3d> v;
    for (int i = 0; i < n; ++i) {
      const double a = 2 * std::numbers::pi * i / n;
      v.emplace_back(std::cos(a), std::sin(a), 0);
    }
    const auto f = iota_face(v.size());
    check(v, f, shoelace(v, f));
    auto box_area = [&](const std::vector<IndexTriangle>& tris) {
      double sum = 0;
      for (const auto& t : tris) {
        Eigen::AlignedBox3d b(v[t[0]]);
        b.extend(v[t[1]]);
        b.extend(v[t[2]]);
        sum += b.sizes().x() * b.sizes().y();
      }
      return sum;
    };
    const auto fan = triangulate_polygon(v, f);
    for (const auto& t : fan) EXPECT_TRUE(t[0] == 1 || t[1] == 1 || t[2] == 1);
    std::vector<IndexTriangle> spread;
    PolygonTriangulator().append(v, f, spread, EarOrder::Spread);
    const double area = shoelace(v, f);
    EXPECT_LT(box_area(spread), 4 * area) << n;
    if (n >= 64) {
      EXPECT_GT(box_area(fan), 8 * area) << n;
    }
  }
  // Not convex although every corner turns left: a pentagram's ring turns twice. Treated as
  // convex, it would be cut into the fan around corner 1, which runs outside the star.
  std::vector<Eigen::Vector3d> star;
  for (int i = 0; i < 5; ++i) {
    const double a = 2 * std::numbers::pi * (2 * i) / 5;
    star.emplace_back(std::cos(a), std::sin(a), 0);
  }
  const std::vector<IndexTriangle> convex_fan = {{4, 0, 1}, {3, 4, 1}, {2, 3, 1}};
  EXPECT_NE(triangulate_polygon(star, iota_face(5)), convex_fan);
}

// Quadrilaterals (a faceted sphere's faces), convex or with one reflex corner, in random planes
// and both orientations: two triangles that cover the face and run its way; a convex one is the
// fan around corner 1 (as every convex polygon's fan above), a dart is cut at its reflex corner.
TEST(Triangulate, QuadrilateralsConvexAndNot) {
  std::mt19937 rng(40);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int trial = 0; trial < 400; ++trial) {
    const bool dart = trial % 2 == 1;
    // In the plane: corners at four increasing angles, or a dart (corner 2 moved to the centroid
    // of the other three: a reflex corner).
    std::vector<Eigen::Vector3d> flat;
    for (int i = 0; i < 4; ++i) {
      const double a = std::numbers::pi / 2 * (i + 0.4 * u(rng)), r = 1 + 0.3 * u(rng);
      flat.emplace_back(r * std::cos(a), r * std::sin(a), 0);
    }
    if (dart) flat[2] = (flat[0] + flat[1] + flat[3]) / 3;
    const std::vector<int> face = trial % 4 < 2 ? std::vector<int>{0, 1, 2, 3} : std::vector<int>{3, 2, 1, 0};
    const std::vector<int> corners = iota_face(4);
    const double area = std::abs(shoelace(flat, corners));
    const Eigen::Matrix3d turn =
        Eigen::AngleAxisd(3 * u(rng), Eigen::Vector3d(u(rng), u(rng), u(rng)).normalized()).toRotationMatrix();
    const Eigen::Vector3d offset(u(rng), u(rng), u(rng));
    std::vector<Eigen::Vector3d> v;
    for (const Eigen::Vector3d& p : flat) v.push_back(turn * p + offset);
    const Eigen::Vector3d normal = turn * Eigen::Vector3d::UnitZ() * (trial % 4 < 2 ? 1.0 : -1.0);
    check(v, face, area, normal);
    const std::vector<IndexTriangle> fan = triangulate_polygon(v, face);
    const int hub = dart ? 2 : face[1];  // the dart's reflex corner is vertex 2 in either order
    for (const auto& t : fan) EXPECT_TRUE(t[0] == hub || t[1] == hub || t[2] == hub) << trial;
  }
}

TEST(Triangulate, DegenerateAndInvalidFaces) {
  const auto line = xy({{0, 0}, {1, 0}, {2, 0}, {3, 0}});
  EXPECT_TRUE(triangulate_polygon(line, iota_face(4)).empty());
  EXPECT_THROW(triangulate_polygon(line, std::vector<int>{0, 1}), InvalidInput);
  EXPECT_THROW(triangulate_polygon(line, std::vector<int>{0, 1, 9}), InvalidInput);
  // A square with a zero-area spike: the spike is dropped, the square kept.
  const auto spike = xy({{0, 0}, {1, 0}, {1, 1}, {1, 2}, {1, 1}, {0, 1}});
  const auto tris = triangulate_polygon(spike, iota_face(6));
  double area = 0;
  for (const auto& t : tris) area += 0.5 * (spike[t[1]] - spike[t[0]]).cross(spike[t[2]] - spike[t[0]]).z();
  EXPECT_NEAR(area, 1, 1e-15);
}

TEST(Triangulate, WholeMesh) {
  PolygonMesh m;
  m.vertices = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  m.faces = {{0, 1, 2, 3}, {0, 3, 2, 1}};
  const PolygonMesh t = triangulate(m);
  EXPECT_EQ(t.faces.size(), 4u);
  EXPECT_EQ(t.vertices, m.vertices);
}

}  // namespace
}  // namespace sculpt
