#include "splines/bspline.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "base/errors.hpp"

using namespace sculpt;
using namespace sculpt::splines;
using V = Eigen::Vector3d;

namespace {

// Analytic quadratic Bezier: (1-t)^2 P0 + 2t(1-t) P1 + t^2 P2, derivatives by hand.
V quad(double t, const V& a, const V& b, const V& c) { return (1 - t) * (1 - t) * a + 2 * t * (1 - t) * b + t * t * c; }

std::vector<V> net(int n, int dimension) {
  std::vector<V> p(n);
  for (int i = 0; i < n; ++i) p[i] = V(std::cos(1.3 * i) + 0.1 * i, std::sin(0.7 * i * i), dimension == 3 ? 0.3 * i : 0.0);
  return p;
}

}  // namespace

TEST(BSpline, QuadraticBezierMatchesTheBernsteinForm) {
  const V a(0, 0, 0), b(1, 2, 0), c(3, 0, 0);
  const BSpline s = BSpline::bezier({a, b, c});
  EXPECT_TRUE(s.is_bezier());
  EXPECT_EQ(s.dimension(), 2);
  for (double t : {0.0, 0.1, 0.5, 0.77, 1.0}) {
    const auto d = s.derivatives(t, 3);
    EXPECT_LT((d[0] - quad(t, a, b, c)).norm(), 1e-14);
    EXPECT_LT((d[1] - (2 * (1 - t) * (b - a) + 2 * t * (c - b))).norm(), 1e-13);
    EXPECT_LT((d[2] - 2 * (c - 2 * b + a)).norm(), 1e-13);
    EXPECT_LT(d[3].norm(), 1e-12);
  }
}

TEST(BSpline, CurvatureOfAQuadraticBezierAtItsApex) {
  // y = x^2 on [-1, 1]: controls (-1,1), (0,-1), (1,1); curvature at the apex is 2, turning left.
  const BSpline s = BSpline::bezier({V(-1, 1, 0), V(0, -1, 0), V(1, 1, 0)});
  EXPECT_NEAR(s.curvature(0.5), 2.0, 1e-12);
  const BSpline mirrored = BSpline::bezier({V(1, 1, 0), V(0, -1, 0), V(-1, 1, 0)});
  EXPECT_NEAR(mirrored.curvature(0.5), -2.0, 1e-12);
}

TEST(BSpline, BasisFunctionsSumToOneAndDerivativesToZero) {
  for (bool closed : {false, true})
    for (int p : {1, 2, 3, 5}) {
      const auto pts = net(9, 3);
      const BSpline s = closed ? BSpline::periodic(p, pts) : BSpline::clamped(p, pts);
      const auto [a, b] = s.domain();
      for (int i = 0; i <= 50; ++i) {
        const Basis basis = s.basis(a + (b - a) * i / 50.0, 2);
        EXPECT_NEAR(basis.value.row(0).sum(), 1.0, 1e-14);
        EXPECT_NEAR(basis.value.row(1).sum(), 0.0, 1e-11);
        EXPECT_NEAR(basis.value.row(2).sum(), 0.0, 1e-9);
        EXPECT_GE(basis.value.row(0).minCoeff(), -1e-15);
      }
    }
}

TEST(BSpline, DerivativesAgreeWithFiniteDifferencesOfTheEvaluator) {  // a cross-check only
  const BSpline s = BSpline::clamped(4, net(10, 3));
  const double h = 1e-6;
  for (double t : {0.13, 0.4, 0.61, 0.9}) {
    const auto d = s.derivatives(t, 2);
    const V fd1 = (s.point(t + h) - s.point(t - h)) / (2 * h);
    const V fd2 = (s.derivatives(t + h, 1)[1] - s.derivatives(t - h, 1)[1]) / (2 * h);
    EXPECT_LT((d[1] - fd1).norm(), 1e-6 * (1 + d[1].norm()));
    EXPECT_LT((d[2] - fd2).norm(), 1e-5 * (1 + d[2].norm()));
  }
}

TEST(BSpline, ClampedCurveInterpolatesItsEndControls) {
  const auto pts = net(7, 2);
  const BSpline s = BSpline::clamped(3, pts);
  EXPECT_LT((s.point(0) - pts.front()).norm(), 1e-15);
  EXPECT_LT((s.point(1) - pts.back()).norm(), 1e-15);
  EXPECT_LT((s.point(-5) - pts.front()).norm(), 1e-15);  // open curves clamp the parameter
}

TEST(BSpline, UniformCubicPeriodicCurveIsTheKnownCombinationAtBreaks) {
  // At a break of a uniform cubic B-spline the point is (P_{i} + 4 P_{i+1} + P_{i+2}) / 6.
  const auto pts = net(6, 2);
  const BSpline s = BSpline::periodic(3, pts);
  for (int i = 0; i < 6; ++i) {
    const V expected = (pts[i] + 4 * pts[(i + 1) % 6] + pts[(i + 2) % 6]) / 6;
    EXPECT_LT((s.point(i) - expected).norm(), 1e-14) << i;
  }
  EXPECT_LT((s.point(0.3) - s.point(6.3)).norm(), 1e-14);  // periodic
  EXPECT_LT((s.point(-0.2) - s.point(5.8)).norm(), 1e-14);
}

TEST(BSpline, KnotInsertionLeavesTheCurveUnchanged) {
  for (bool closed : {false, true})
    for (int p : {1, 2, 3, 4}) {
      const auto pts = net(8, 3);
      const BSpline s = closed ? BSpline::periodic(p, pts) : BSpline::clamped(p, pts);
      const auto [a, b] = s.domain();
      for (double f : {0.05, 0.51, 0.93}) {
        const BSpline r = s.insert_knot(a + f * (b - a));
        EXPECT_EQ(r.control_count(), s.control_count() + 1);
        EXPECT_EQ(r.closed(), closed);
        for (int i = 0; i <= 97; ++i) {
          const double t = a + (b - a) * i / 97.0;
          EXPECT_LT((r.point(t) - s.point(t)).norm(), 1e-12) << "closed " << closed << " p " << p << " t " << t;
        }
      }
    }
}

TEST(BSpline, RepeatedKnotInsertionMakesACornerThroughAControlPoint) {
  const BSpline s = BSpline::periodic(3, net(7, 2));
  BSpline r = s.insert_knot(2.5).insert_knot(2.5).insert_knot(2.5);
  bool through = false;
  for (const auto& c : r.controls()) through = through || (c - s.point(2.5)).norm() < 1e-12;
  EXPECT_TRUE(through);
  EXPECT_THROW((void)r.insert_knot(2.5), InvalidInput);  // multiplicity 4 > degree 3
}

TEST(BSpline, KnotInsertionAtABreakOfAClosedCurve) {
  const BSpline s = BSpline::periodic(3, net(6, 2));
  const BSpline r = s.insert_knot(0.0);
  for (int i = 0; i <= 60; ++i) EXPECT_LT((r.point(i / 10.0) - s.point(i / 10.0)).norm(), 1e-12);
}

TEST(BSpline, BadInputIsATypedError) {
  const auto pts = net(5, 2);
  EXPECT_THROW(BSpline::clamped(0, pts), InvalidInput);
  EXPECT_THROW(BSpline::clamped(5, pts), InvalidInput);  // needs 6 control points
  EXPECT_THROW(BSpline(3, {0, 0, 0, 0, 1, 1, 1}, pts, false), InvalidInput);  // 9 knots needed
  EXPECT_THROW(BSpline(2, {0, 0, 0, 0.6, 0.5, 1, 1, 1}, pts, false), InvalidInput);  // decreasing
  EXPECT_THROW(BSpline(2, {0, 0, 0, 0.5, 0.5, 0.5, 1, 1, 1}, net(6, 2), false), InvalidInput);  // multiplicity 3 > 2
  EXPECT_THROW(BSpline(2, {0, 1, 2, 2, 2, 4}, pts, true), InvalidInput);  // closed: multiplicity 3 > 2
  EXPECT_THROW(BSpline(2, {0, 0, 0, 0, 0, 0}, pts, true), InvalidInput);  // empty period
  auto bad = pts;
  bad[2].x() = std::nan("");
  EXPECT_THROW(BSpline::periodic(3, bad), InvalidInput);
  EXPECT_THROW(BSpline::periodic(3, pts, 4), InvalidInput);
  EXPECT_THROW((void)BSpline::clamped(2, pts).point(std::nan("")), InvalidInput);
  EXPECT_THROW((void)BSpline::clamped(2, pts).insert_knot(1.0), InvalidInput);  // not strictly inside
  EXPECT_THROW(BSpline::bezier({V(0, 0, 0)}), InvalidInput);
}

TEST(BSpline, DimensionIsDetectedFromZ) {
  EXPECT_EQ(BSpline::clamped(2, net(4, 2)).dimension(), 2);
  EXPECT_EQ(BSpline::clamped(2, net(4, 3)).dimension(), 3);
  EXPECT_EQ(BSpline::clamped(2, net(4, 2), 3).dimension(), 3);
  EXPECT_THROW(BSpline::clamped(2, net(4, 3), 2), InvalidInput);
}
