// Tensor-product B-spline surfaces: evaluation against closed forms (bilinear patch, plane,
// paraboloid as an exact biquadratic), periodicity, curvature, and foot points against brute force.
#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <cmath>
#include <limits>
#include <random>

#include "base/errors.hpp"
#include "splines/bspline_surface.hpp"
#include "splines/fit_surface.hpp"
#include "surface_shapes.hpp"
#include "test_names.hpp"

namespace {


// A wavy cubic surface with non-uniform knots in u (open) and v (open).
BSplineSurface wavy() {
  const int nu = 7, nv = 6;
  std::vector<V> P;
  for (int i = 0; i < nu; ++i)
    for (int j = 0; j < nv; ++j) P.emplace_back(i, j, std::sin(1.7 * i) * std::cos(1.1 * j) + 0.3 * ((i + j) % 2));
  return BSplineSurface({3, 3}, {std::vector<double>{0, 0, 0, 0, 0.2, 0.5, 0.6, 1, 1, 1, 1}, std::vector<double>{0, 0, 0, 0, 0.3, 0.7, 1, 1, 1, 1}},
                        nu, nv, P, {false, false});
}

// A surface closed in both directions: control points on a torus (R = 3, r = 1), 8 x 6, cubic.
BSplineSurface torus_like() {
  const int nu = 8, nv = 6;
  std::vector<V> P;
  for (int i = 0; i < nu; ++i)
    for (int j = 0; j < nv; ++j) {
      const double a = 2 * kPi * i / nu, b = 2 * kPi * j / nv;
      P.emplace_back((3 + std::cos(b)) * std::cos(a), (3 + std::cos(b)) * std::sin(a), std::sin(b));
    }
  return BSplineSurface::uniform({3, 3}, nu, nv, P, {true, true});
}

TEST(BSplineSurface, BilinearPatchOfDegreeOneIsTheBilinearInterpolant) {
  const V c00(0, 0, 0), c10(2, 0, 1), c01(0, 3, -1), c11(2.5, 3.5, 4);
  const BSplineSurface s = BSplineSurface::uniform({1, 1}, 2, 2, {c00, c01, c10, c11});
  std::mt19937 rng(1);
  std::uniform_real_distribution<double> U(0, 1);
  for (int k = 0; k < 50; ++k) {
    const double u = U(rng), v = U(rng);
    const V expected = (1 - u) * (1 - v) * c00 + u * (1 - v) * c10 + (1 - u) * v * c01 + u * v * c11;
    EXPECT_LT((s.point(u, v) - expected).norm(), 1e-14);
    const SurfaceJet j = s.jet(u, v, 2);
    EXPECT_LT((j.du - ((1 - v) * (c10 - c00) + v * (c11 - c01))).norm(), 1e-13);
    EXPECT_LT((j.dv - ((1 - u) * (c01 - c00) + u * (c11 - c10))).norm(), 1e-13);
    EXPECT_LT((j.duv - (c11 - c10 - c01 + c00)).norm(), 1e-13);
    EXPECT_LT(j.duu.norm() + j.dvv.norm(), 1e-13);
  }
}

TEST(BSplineSurface, BilinearStartPatchOfDegreeThreeIsExactlyBilinear) {
  const std::array<V, 4> c = {V(0, 0, 0), V(2, 0, 1), V(0, 3, -1), V(2.5, 3.5, 4)};
  const BSplineSurface s = bilinear_patch(c, {8, 7});
  for (double u : {0.0, 0.13, 0.5, 0.77, 1.0})
    for (double v : {0.0, 0.31, 0.62, 1.0}) {
      const V expected = (1 - u) * (1 - v) * c[0] + u * (1 - v) * c[1] + (1 - u) * v * c[2] + u * v * c[3];
      EXPECT_LT((s.point(u, v) - expected).norm(), 1e-13) << u << " " << v;
    }
}

TEST(BSplineSurface, ControlsOnAPlaneGiveAPlane) {
  // Any control grid on the plane x + 2y - z = 1 with any knots: every point and derivative stays in it.
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> U(-2, 2);
  std::vector<V> P;
  for (int k = 0; k < 6 * 5; ++k) {
    const double x = U(rng), y = U(rng);
    P.emplace_back(x, y, x + 2 * y - 1);
  }
  const BSplineSurface s({3, 2}, {std::vector<double>{0, 0, 0, 0, 0.1, 0.8, 1, 1, 1, 1}, std::vector<double>{0, 1, 2.5, 3, 4, 5}}, 6, 5, P,
                         {false, true});
  const V n = V(1, 2, -1).normalized();
  for (double u : {0.0, 0.05, 0.4, 0.9, 1.0})
    for (double v : {0.0, 1.2, 3.7, 4.99}) {
      const SurfaceJet j = s.jet(u, v, 2);
      EXPECT_NEAR(j.point.x() + 2 * j.point.y() - j.point.z(), 1.0, 1e-12);
      for (const V& d : {j.du, j.dv, j.duu, j.duv, j.dvv}) EXPECT_NEAR(d.dot(n), 0.0, 1e-10 * (1 + d.norm()));
      const PrincipalCurvatures k = s.curvatures(u, v);
      if (k.normal.norm() > 0) {
        EXPECT_NEAR(k.k1, 0.0, 1e-9);
        EXPECT_NEAR(k.k2, 0.0, 1e-9);
      }
    }
}

TEST(BSplineSurface, ParaboloidIsExactAndCurvedTwiceAtTheApex) {
  const BSplineSurface s = paraboloid();
  for (double u : {0.0, 0.2, 0.5, 0.9, 1.0})
    for (double v : {0.0, 0.35, 0.5, 1.0}) {
      const double x = 2 * u - 1, y = 2 * v - 1;
      const SurfaceJet j = s.jet(u, v, 2);
      EXPECT_LT((j.point - V(x, y, x * x + y * y)).norm(), 1e-14);
      EXPECT_LT((j.du - V(2, 0, 4 * x)).norm(), 1e-13);
      EXPECT_LT((j.dv - V(0, 2, 4 * y)).norm(), 1e-13);
      EXPECT_LT((j.duu - V(0, 0, 8)).norm(), 1e-12);
      EXPECT_LT(j.duv.norm(), 1e-12);
      EXPECT_LT((j.dvv - V(0, 0, 8)).norm(), 1e-12);
      // Gaussian and mean curvature of z = f(x, y) in closed form.
      const double w = 1 + 4 * x * x + 4 * y * y;
      const PrincipalCurvatures k = s.curvatures(u, v);
      EXPECT_NEAR(k.k1 * k.k2, 4 / (w * w), 1e-12);
      EXPECT_NEAR(0.5 * (k.k1 + k.k2), (2 * (1 + 4 * y * y) + 2 * (1 + 4 * x * x)) / (2 * std::pow(w, 1.5)), 1e-12);
    }
  const PrincipalCurvatures apex = s.curvatures(0.5, 0.5);
  EXPECT_NEAR(apex.k1, 2.0, 1e-12);
  EXPECT_NEAR(apex.k2, 2.0, 1e-12);
  EXPECT_LT((apex.normal - V(0, 0, 1)).norm(), 1e-14);
  EXPECT_LT((s.normal(0.5, 0.5) - V(0, 0, 1)).norm(), 1e-14);
}

TEST(BSplineSurface, PrincipalDirectionsOfTheSaddle) {
  // z = x^2 - y^2 (biquadratic as above): at the apex k = +-2 along x and y.
  const double x[3] = {-1, 0, 1}, sq[3] = {1, -1, 1};
  std::vector<V> P;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) P.emplace_back(x[i], x[j], sq[i] - sq[j]);
  const PrincipalCurvatures k = BSplineSurface::uniform({2, 2}, 3, 3, P).curvatures(0.5, 0.5);
  EXPECT_NEAR(k.k1, 2.0, 1e-12);
  EXPECT_NEAR(k.k2, -2.0, 1e-12);
  EXPECT_NEAR(std::abs(k.d1.x()), 1.0, 1e-12);
  EXPECT_NEAR(std::abs(k.d2.y()), 1.0, 1e-12);
}

TEST(BSplineSurface, DerivativesAgreeWithFiniteDifferences) {
  // A cross-check only (the closed forms above are the reference).
  for (const BSplineSurface& s : {wavy(), torus_like()}) {
    for (double u : {0.11, 0.47, 0.83})
      for (double v : {0.09, 0.52, 0.91}) {
        const double h = 1e-6;
        const SurfaceJet j = s.jet(u, v, 2), ju = s.jet(u + h, v, 1), jv = s.jet(u, v + h, 1);
        const SurfaceJet ju0 = s.jet(u - h, v, 1), jv0 = s.jet(u, v - h, 1);
        const double scale = 1 + j.du.norm() + j.dv.norm();
        EXPECT_LT((j.du - (ju.point - ju0.point) / (2 * h)).norm(), 1e-6 * scale);
        EXPECT_LT((j.dv - (jv.point - jv0.point) / (2 * h)).norm(), 1e-6 * scale);
        EXPECT_LT((j.duu - (ju.du - ju0.du) / (2 * h)).norm(), 1e-4 * scale);
        EXPECT_LT((j.duv - (jv.du - jv0.du) / (2 * h)).norm(), 1e-4 * scale);
        EXPECT_LT((j.dvv - (jv.dv - jv0.dv) / (2 * h)).norm(), 1e-4 * scale);
      }
  }
}

TEST(BSplineSurface, ClosedDirectionsArePeriodicAndSmoothAcrossTheSeam) {
  const BSplineSurface s = torus_like();
  for (double u : {0.0, 0.3, 0.999})
    for (double v : {0.0, 0.45}) {
      EXPECT_LT((s.point(u + 1, v) - s.point(u, v)).norm(), 1e-13);
      EXPECT_LT((s.point(u, v - 2) - s.point(u, v)).norm(), 1e-13);
    }
  // C2 at the seam: the one-sided limits agree.
  const double e = 1e-9;
  const SurfaceJet a = s.jet(1 - e, 0.3, 2), b = s.jet(0.0, 0.3, 2);
  EXPECT_LT((a.point - b.point).norm(), 1e-7);
  EXPECT_LT((a.du - b.du).norm(), 1e-6);
  EXPECT_LT((a.duu - b.duu).norm(), 1e-4);
  // Turning the control grid by one row (a rotation by 2 pi / 8 about z) turns the surface:
  // S(u + 1/8, v) = R S(u, v) on uniform break points.
  const Eigen::Matrix3d R = Eigen::AngleAxisd(2 * kPi / 8, V::UnitZ()).toRotationMatrix();
  for (double u : {0.0, 0.21, 0.9})
    for (double v : {0.1, 0.77}) EXPECT_LT((s.point(u + 0.125, v) - R * s.point(u, v)).norm(), 1e-13);
}

TEST(BSplineSurface, BadInputIsRefused) {
  EXPECT_THROW(BSplineSurface::uniform({3, 3}, 3, 4, std::vector<V>(12, V::Zero())), InvalidInput);  // 3 < degree + 1
  EXPECT_THROW(BSplineSurface::uniform({3, 3}, 4, 4, std::vector<V>(15, V::Zero())), InvalidInput);
  EXPECT_THROW(BSplineSurface::uniform({0, 3}, 4, 4, std::vector<V>(16, V::Zero())), InvalidInput);
  EXPECT_THROW(BSplineSurface::uniform({8, 3}, 9, 4, std::vector<V>(36, V::Zero())), InvalidInput);
  std::vector<V> P(16, V::Zero());
  P[5].x() = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(BSplineSurface::uniform({3, 3}, 4, 4, P), InvalidInput);
  const BSplineSurface s = paraboloid();
  EXPECT_THROW((void)s.point(std::numeric_limits<double>::infinity(), 0), InvalidInput);
  EXPECT_THROW((void)closest_point(s, V(0, std::numeric_limits<double>::quiet_NaN(), 0)), InvalidInput);
  EXPECT_THROW((void)distance(s, {}), InvalidInput);
}

// Brute force: the nearest of n x n samples, refined by a dense local grid around it. Returns an
// upper bound of the true distance (a surface point's distance).
double brute_force_distance(const BSplineSurface& s, const V& x, int n) {
  double best = std::numeric_limits<double>::infinity();
  const auto [a0, a1] = s.domain(0);
  const auto [b0, b1] = s.domain(1);
  for (int i = 0; i <= n; ++i)
    for (int j = 0; j <= n; ++j)
      best = std::min(best, (s.point(a0 + (a1 - a0) * i / n, b0 + (b1 - b0) * j / n) - x).norm());
  return best;
}

TEST(BSplineSurface, FootPointsAreNoFartherThanDenseSamples) {
  std::mt19937 rng(7);
  for (const BSplineSurface& s : {wavy(), torus_like(), paraboloid()}) {
    Eigen::Vector3d lo = s.controls()[0], hi = lo;
    for (const V& c : s.controls()) {
      lo = lo.cwiseMin(c);
      hi = hi.cwiseMax(c);
    }
    std::uniform_real_distribution<double> X(lo.x() - 1, hi.x() + 1), Y(lo.y() - 1, hi.y() + 1), Z(lo.z() - 1, hi.z() + 1);
    for (int k = 0; k < 25; ++k) {
      const V x(X(rng), Y(rng), Z(rng));
      const SurfaceFootPoint f = closest_point(s, x);
      // The foot point is a point of the surface at its parameters, at the reported distance...
      EXPECT_LT((s.point(f.u, f.v) - f.point).norm(), 1e-14 * (1 + f.point.norm()));
      EXPECT_NEAR((f.point - x).norm(), f.distance, 1e-14 * (1 + f.distance));
      // ... and no dense sample (300 x 300) is closer.
      const double bf = brute_force_distance(s, x, 300);
      EXPECT_LE(f.distance, bf + 1e-12) << "point " << x.transpose();
    }
  }
}

TEST(BSplineSurface, FootPointOfAPointOnTheSurfaceIsItself) {
  const BSplineSurface s = wavy();
  for (double u : {0.0, 0.25, 0.55, 1.0})
    for (double v : {0.0, 0.33, 0.8}) {
      const SurfaceFootPoint f = closest_point(s, s.point(u, v));
      EXPECT_LT(f.distance, 1e-12);
    }
  // Off the paraboloid along its normal at (x, y) = (0.3, -0.2): the foot point is that point
  // as long as the offset stays below the smaller curvature radius.
  const BSplineSurface p = paraboloid();
  const double u = 0.65, v = 0.4;
  const V base = p.point(u, v), n = p.normal(u, v);
  for (double d : {-0.2, 0.01, 0.1}) {
    const SurfaceFootPoint f = closest_point(p, base - d * n);
    EXPECT_NEAR(f.u, u, 1e-9);
    EXPECT_NEAR(f.v, v, 1e-9);
    EXPECT_NEAR(f.distance, std::abs(d), 1e-12);
  }
}

}  // namespace
