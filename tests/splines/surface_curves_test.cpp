// Geodesics and splines on surfaces (Pottmann, Leopoldseder & Hofer 2002, sec. 5.1-5.2) against
// analytic references: great circles on the sphere, helices on the cylinder, the torus' outer equator.
#include "splines/surface_curves.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>

#include "base/errors.hpp"
#include "test_names.hpp"

namespace {

/// (min, max) of |c'(t)| over 2000 samples.
std::pair<double, double> speed_range(const BSpline& c) {
  const auto [a, b] = c.domain();
  double lo = 1e300, hi = 0.0;
  for (int k = 0; k <= 2000; ++k) {
    const double s = c.derivatives(a + (b - a) * k / 2000.0, 1)[1].norm();
    lo = std::min(lo, s);
    hi = std::max(hi, s);
  }
  return {lo, hi};
}

/// Arc length by the composite Simpson rule on 20000 intervals (independent of the library's quadrature).
double simpson_length(const BSpline& c) {
  const auto [a, b] = c.domain();
  const int n = 20000;
  double s = 0.0;
  for (int k = 0; k <= n; ++k) {
    const double w = (k == 0 || k == n) ? 1 : (k % 2 ? 4 : 2);
    s += w * c.derivatives(a + (b - a) * k / n, 1)[1].norm();
  }
  return s * (b - a) / n / 3.0;
}

/// max over 4000 samples of | |c(t) - center| - r |.
double sphere_gap(const BSpline& c, const V& center, double r) {
  const auto [a, b] = c.domain();
  double worst = 0.0;
  for (int k = 0; k <= 4000; ++k) worst = std::max(worst, std::abs((c.point(a + (b - a) * k / 4000.0) - center).norm() - r));
  return worst;
}

V on_sphere(const V& center, double r, double theta, double phi) {
  return center + r * V(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta));
}

}  // namespace

TEST(Geodesic, SphereGreatCircleArcHasTheAnalyticLength) {
  const V center(0.3, -0.2, 0.1);
  const double r = 2.0;
  const Surface s = sphere_surface(center, r);
  for (double angle : {0.3, 1.5, 2.6}) {
    const V p = on_sphere(center, r, 0.7, 0.2);
    const V axis = (p - center).cross(V(0.2, 1.0, -0.4)).normalized();
    const V q = center + Eigen::AngleAxisd(angle, axis) * (p - center);
    const GeodesicResult g = geodesic(s, p, q);
    EXPECT_TRUE(g.converged) << angle;
    const double exact = r * angle;
    EXPECT_LT(std::abs(g.length - exact) / exact, 1e-4) << angle;
    EXPECT_LT(std::abs(simpson_length(g.curve) - exact) / exact, 1e-4) << angle;
    EXPECT_LE(sphere_gap(g.curve, center, r), 1e-4) << angle;
    const auto [lo, hi] = speed_range(g.curve);
    EXPECT_LT((hi - lo) / exact, 0.01) << angle;
    // The vertices lie in the great circle's plane.
    const V n = (p - center).cross(q - center).normalized();
    for (const V& v : g.polygon) EXPECT_LT(std::abs((v - center).dot(n)), 1e-9) << angle;
  }
}

TEST(Geodesic, CylinderGeodesicIsTheHelix) {
  const double r = 0.8;
  const Surface s = cylinder_surface(V(0, 0, 0), V(0, 0, 1), r);
  const double phi = 2.5, h = 1.7;  // the short way round: phi < pi
  const V p(r, 0, -0.5), q(r * std::cos(phi), r * std::sin(phi), -0.5 + h);
  const GeodesicResult g = geodesic(s, p, q);
  EXPECT_TRUE(g.converged);
  const double exact = std::hypot(r * phi, h);
  EXPECT_LT(std::abs(g.length - exact) / exact, 1e-4);
  EXPECT_LT(std::abs(simpson_length(g.curve) - exact) / exact, 1e-4);
  const auto [lo, hi] = speed_range(g.curve);
  EXPECT_LT((hi - lo) / exact, 0.01);
  // On the helix: height linear in the angle; on the cylinder.
  for (double t = 0; t <= 1.0; t += 0.01) {
    const V c = g.curve.point(t);
    EXPECT_LE(std::abs(std::hypot(c.x(), c.y()) - r), 1e-4);
    const double angle = std::atan2(c.y(), c.x());
    EXPECT_LT(std::abs(c.z() - (-0.5 + h * angle / phi)), 1e-4) << t;
  }
}

TEST(Geodesic, TorusOuterEquatorArc) {
  const double R = 3.0, r = 1.0, phi = 1.0;  // shorter than the conjugate distance 2 pi sqrt(r (R + r))
  const Surface s = torus_surface(V(0, 0, 0), V(0, 0, 1), R, r);
  const V p(R + r, 0, 0), q((R + r) * std::cos(phi), (R + r) * std::sin(phi), 0);
  const GeodesicResult g = geodesic(s, p, q);
  EXPECT_TRUE(g.converged);
  EXPECT_LT(std::abs(g.length - (R + r) * phi) / ((R + r) * phi), 1e-4);
  for (const V& v : g.polygon) EXPECT_LT(std::abs(v.z()), 1e-9);
}

TEST(Geodesic, ImplicitSphereMatchesTheSphere) {
  const double r = 1.5;
  const Surface s = implicit_surface([r](const V& x) { return x.squaredNorm() - r * r; },
                                     [](const V& x) -> V { return 2.0 * x; });
  const V p = on_sphere(V::Zero(), r, 0.4, 0.0), q = on_sphere(V::Zero(), r, 2.0, 1.3);
  const double exact = r * std::acos(p.normalized().dot(q.normalized()));
  const GeodesicResult g = geodesic(s, p, q);
  EXPECT_LT(std::abs(g.length - exact) / exact, 1e-4);
  EXPECT_LE(sphere_gap(g.curve, V::Zero(), r), 1e-4);
}

TEST(Geodesic, PointsOffTheSurfaceAreMovedToTheirFootPoints) {
  const Surface s = sphere_surface(V::Zero(), 1.0);
  const GeodesicResult g = geodesic(s, V(3, 0, 0), V(0, 0.5, 0));
  EXPECT_LT((g.curve.point(0) - V(1, 0, 0)).norm(), 1e-12);
  EXPECT_LT((g.curve.point(1) - V(0, 1, 0)).norm(), 1e-12);
  EXPECT_LT(std::abs(g.length - kPi / 2) / (kPi / 2), 1e-4);
}

TEST(Geodesic, AntipodalPointsGiveAHalfGreatCircle) {
  // The straight segment passes through the centre: one of the many half great circles.
  const Surface s = sphere_surface(V::Zero(), 1.0);
  const GeodesicResult g = geodesic(s, V(1, 0, 0), V(-1, 0, 0));
  EXPECT_LT(std::abs(g.length - kPi) / kPi, 1e-4);
  EXPECT_LE(sphere_gap(g.curve, V::Zero(), 1.0), 1e-4);
}

TEST(Geodesic, BadInputIsRefused) {
  const Surface s = sphere_surface(V::Zero(), 1.0);
  EXPECT_THROW(geodesic(s, V(1, 0, 0), V(2, 0, 0)), InvalidInput);  // the same foot point
  EXPECT_THROW(geodesic(s, V(1, 0, 0), V(0, 1, 0), {.segments = 1}), InvalidInput);
  EXPECT_THROW(geodesic(s, V(NAN, 0, 0), V(0, 1, 0)), InvalidInput);
  EXPECT_THROW(sphere_surface(V::Zero(), 0.0), InvalidInput);
  EXPECT_THROW(cylinder_surface(V::Zero(), V::Zero(), 1.0), InvalidInput);
  EXPECT_THROW(torus_surface(V::Zero(), V::UnitZ(), 1.0, 2.0), InvalidInput);
}

TEST(SurfaceSpline, SphereSplineInterpolatesStaysCloseAndBendsLessThanTheProjectedSpline) {
  const V center(0.1, 0.2, -0.3);
  const double r = 1.3;
  const Surface s = sphere_surface(center, r);
  const std::vector<V> points{on_sphere(center, r, 0.5, 0.0), on_sphere(center, r, 1.1, 0.6),
                              on_sphere(center, r, 1.4, 1.5), on_sphere(center, r, 0.9, 2.3),
                              on_sphere(center, r, 1.6, 3.1)};
  const SurfaceSplineResult res = surface_spline(s, points, {.distance = 1e-4});
  // The seed's 3 splits suffice here (spans 0.92 to 1.26): the target.
  EXPECT_EQ(res.splits, 3);
  ASSERT_EQ(res.parameters.size(), points.size());
  for (std::size_t j = 0; j < points.size(); ++j)
    EXPECT_LT((res.curve.point(res.parameters[j]) - points[j]).norm(), 1e-12) << j;
  EXPECT_LE(sphere_gap(res.curve, center, r), 1e-4);
  EXPECT_LE(res.max_distance, 1e-4);
  // The start is the natural spline: through the points, c'' = 0 at both ends.
  const auto [a, b] = res.start.domain();
  for (std::size_t j = 0; j < points.size(); ++j)
    EXPECT_LT((res.start.point(res.parameters[j]) - points[j]).norm(), 1e-12) << j;
  EXPECT_LT(res.start.derivatives(a, 2)[2].norm(), 1e-9);
  EXPECT_LT(res.start.derivatives(b, 2)[2].norm(), 1e-9);
  // Bending of the radially projected natural spline by central differences and Simpson's rule.
  auto projected = [&](double t) -> V { return center + r * (res.start.point(t) - center).normalized(); };
  auto ours = [&](double t) -> V { return res.curve.point(t); };
  auto bending = [&, a = a, b = b](auto f) {  // (clang 14 cannot capture structured bindings)
    const int n = 4000;
    const double h = 1e-4;
    double e = 0.0;
    for (int k = 0; k <= n; ++k) {
      const double t = std::clamp(a + (b - a) * k / n, a + h, b - h);
      const double w = (k == 0 || k == n) ? 1 : (k % 2 ? 4 : 2);
      e += w * ((f(t + h) - 2 * f(t) + f(t - h)) / (h * h)).squaredNorm();
    }
    return e * (b - a) / n / 3.0;
  };
  const double e_ours = bending(ours), e_projected = bending(projected);
  EXPECT_LT(e_ours, e_projected);
  EXPECT_NEAR(e_ours, res.bending, 1e-3 * e_ours);
}

TEST(SurfaceSpline, TheSeedsThreeSplitsStayWithinTheSplineSpacesReach) {
  // Spans of about 1.1 on a sphere of radius 1.3 with 3 cubic segments each: a C2 cubic spline is
  // O(h^4) = 5/384 h^4 / r^3 (about 1e-4 here) off the sphere; more splits come closer.
  const double r = 1.3;
  const Surface s = sphere_surface(V::Zero(), r);
  const std::vector<V> points{on_sphere(V::Zero(), r, 0.5, 0.0), on_sphere(V::Zero(), r, 1.1, 0.6),
                              on_sphere(V::Zero(), r, 1.4, 1.5), on_sphere(V::Zero(), r, 0.9, 2.3)};
  const SurfaceSplineResult three = surface_spline(s, points);
  const SurfaceSplineResult six = surface_spline(s, points, {.splits = 6});
  EXPECT_EQ(three.splits, 3);
  EXPECT_TRUE(three.converged);
  EXPECT_LT(three.max_distance, 1e-3);
  EXPECT_LT(six.max_distance, 0.5 * three.max_distance);
  EXPECT_LE(sphere_gap(six.curve, V::Zero(), r), 1e-4);
}

TEST(SurfaceSpline, CylinderSplineThroughHelixPoints) {
  const Surface s = cylinder_surface(V::Zero(), V::UnitZ(), 1.0);
  std::vector<V> points;
  for (int j = 0; j < 5; ++j) points.emplace_back(std::cos(0.9 * j), std::sin(0.9 * j), 0.3 * j);
  const SurfaceSplineResult res = surface_spline(s, points, {.distance = 1e-4});
  for (std::size_t j = 0; j < points.size(); ++j)
    EXPECT_LT((res.curve.point(res.parameters[j]) - points[j]).norm(), 1e-12) << j;
  EXPECT_LE(res.max_distance, 1e-4);
}

TEST(SurfaceSpline, BadInputIsRefused) {
  const Surface s = sphere_surface(V::Zero(), 1.0);
  EXPECT_THROW(surface_spline(s, {V(1, 0, 0)}), InvalidInput);
  EXPECT_THROW(surface_spline(s, {V(1, 0, 0), V(2, 0, 0)}), InvalidInput);
  EXPECT_THROW(surface_spline(s, {V(1, 0, 0), V(0, 1, 0)}, {.splits = 0}), InvalidInput);
}

// A B-spline surface as the constraint (bspline_surface_constraint): the parabolic cylinder
// z = x^2, exactly a quadratic x linear B-spline patch, is developable, so its geodesics unroll to
// straight lines: length^2 = (s(x1) - s(x0))^2 + (y1 - y0)^2 with s the parabola's arc length.
TEST(Geodesic, BSplineParabolicCylinderUnrollsToAStraightLine) {
  std::vector<V> controls;
  for (const V& c : {V(-1, 0, 1), V(0, 0, -1), V(1, 0, 1)})
    for (double y : {-1.0, 1.0}) controls.push_back(V(c.x(), y, c.z()));
  const Surface s = bspline_surface_constraint(BSplineSurface::uniform({2, 1}, 3, 2, controls));
  auto arc = [](double x) { return 0.5 * x * std::sqrt(1 + 4 * x * x) + 0.25 * std::asinh(2 * x); };
  const V p(-0.8, -0.7, 0.64), q(0.6, 0.5, 0.36);
  const GeodesicResult g = geodesic(s, p, q);
  EXPECT_TRUE(g.converged);
  const double exact = std::hypot(arc(0.6) - arc(-0.8), 1.2);
  EXPECT_LT(std::abs(simpson_length(g.curve) - exact) / exact, 1e-4);
  const auto [a, b] = g.curve.domain();
  for (int k = 0; k <= 1000; ++k) {
    const V c = g.curve.point(a + (b - a) * k / 1000.0);
    EXPECT_LT(std::abs(c.z() - c.x() * c.x()), 1e-4) << k;
  }
  const auto [lo, hi] = speed_range(g.curve);
  EXPECT_LT((hi - lo) / exact, 0.01);
}
