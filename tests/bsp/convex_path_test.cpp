#include "bsp/convex_path.hpp"
#include "mesh/predicates.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "base/errors.hpp"

using namespace sculpt;

TEST(PathPolygon, CircleIsTheInscribedRegularPolygonStartingOnPlusX) {
  const ConvexPath p = circular_path(32);
  ASSERT_EQ(p.edges(), 32);
  EXPECT_EQ(p.vertices[0], Eigen::Vector2d(1, 0));
  for (int k = 0; k < 32; ++k) {
    EXPECT_NEAR(p.vertices[k].norm(), 1.0, 1e-15);
    EXPECT_NEAR(std::atan2(p.vertices[k].y(), p.vertices[k].x()),
                std::remainder(2 * std::numbers::pi * k / 32, 2 * std::numbers::pi), 1e-14);
  }
  // Area of the inscribed regular n-gon: n/2 sin(2 pi / n).
  EXPECT_NEAR(p.area(), 16 * std::sin(2 * std::numbers::pi / 32), 1e-14);
  EXPECT_NEAR(circular_path(6, 2.0).area(), 3 * 4 * std::sin(std::numbers::pi / 3), 1e-13);
}

TEST(PathPolygon, EllipseVerticesLieOnTheEllipse) {
  const ConvexPath p = ellipse_path(2.0, 0.5, 32);
  for (const auto& v : p.vertices) EXPECT_NEAR(v.x() * v.x() / 4 + v.y() * v.y() / 0.25, 1.0, 1e-14);
  EXPECT_EQ(p.vertices[0], Eigen::Vector2d(2, 0));
}

TEST(PathPolygon, ClockwiseInputIsReversed) {
  const ConvexPath p = polygon_path({{0, 0}, {0, 1}, {1, 1}, {1, 0}});
  EXPECT_GT(p.area(), 0);
  EXPECT_NEAR(p.area(), 1.0, 0);
}

TEST(PathPolygon, RejectsNonConvexAndDegeneratePolygons) {
  EXPECT_THROW(polygon_path({{0, 0}, {1, 0}}), InvalidInput);
  EXPECT_THROW(polygon_path({{0, 0}, {2, 0}, {1, 0.2}, {2, 2}, {0, 2}}), InvalidInput);      // reflex vertex
  EXPECT_THROW(polygon_path({{0, 0}, {1, 0}, {2, 0}, {1, 1}}), InvalidInput);               // collinear
  EXPECT_THROW(polygon_path({{0, 0}, {1, 0}, {1, 0}, {0, 1}}), InvalidInput);               // repeated
  EXPECT_THROW(polygon_path({{0, 0}, {1, NAN}, {0, 1}}), InvalidInput);
  // A pentagram turns left at every vertex but winds twice.
  std::vector<Eigen::Vector2d> star;
  for (int k = 0; k < 5; ++k) {
    const double t = 2 * std::numbers::pi * 2 * k / 5;
    star.emplace_back(std::cos(t), std::sin(t));
  }
  EXPECT_THROW(polygon_path(star), InvalidInput);
  EXPECT_THROW(circular_path(2), InvalidInput);
  EXPECT_THROW(circular_path(8, 0.0), InvalidInput);
  EXPECT_THROW(ellipse_path(1, -1, 8), InvalidInput);
}

TEST(PathPolygon, OrientationIsExactWhereDoublesFail) {
  // Three points on the line y = x shifted by tiny amounts: the naive determinant rounds.
  const Eigen::Vector2d a(0.5, 0.5), b(12.0, 12.0), c(24.0, 24.0);
  EXPECT_EQ(orient2d(a, b, c), 0);
  const Eigen::Vector2d c_up(24.0, std::nextafter(24.0, 25.0));
  const Eigen::Vector2d c_down(24.0, std::nextafter(24.0, 23.0));
  EXPECT_EQ(orient2d(a, b, c_up), 1);
  EXPECT_EQ(orient2d(a, b, c_down), -1);
  // Classic near-degenerate case (Kettner et al.): p = (0.5 + k u, 0.5 + l u) against a line.
  const double u = std::ldexp(1.0, -53);
  const Eigen::Vector2d q(12, 12), r(24, 24);
  int positive = 0, negative = 0, zero = 0;
  for (int k = 0; k < 16; ++k)
    for (int l = 0; l < 16; ++l) {
      const int s = orient2d({0.5 + k * u, 0.5 + l * u}, q, r);
      // Exact sign: (l - k) decides, as the line is y = x.
      EXPECT_EQ(s, (l > k) - (l < k)) << k << " " << l;
      (s > 0 ? positive : s < 0 ? negative : zero)++;
    }
  EXPECT_EQ(zero, 16);
}
