#include "splines/offset.hpp"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <numbers>

#include "base/errors.hpp"
#include "test_names.hpp"
#include "splines/foot_point.hpp"

namespace {
constexpr double kA = 2.0, kB = 1.0;

t::Curve3 ellipse_offset(double d) { return t::ellipse_offset(kA, kB, d); }
using t::interpolant;

// The spline as a test curve (for distances from the exact offset to the result).
t::Curve3 as_curve(const BSpline& s) {
  return [&s](double u) {
    const auto e = s.derivatives(u, 2);
    return std::array<V, 3>{e[0], e[1], e[2]};
  };
}

// The parameter t_c in (0, pi/2) where the raw inner offset at d crosses the x axis (its swallowtail's
// self-intersection), by bisection on the y coordinate; the trimmed offset is t in [t_c, pi - t_c] and its mirror.
double crossing_parameter(double d) {
  const auto y = [d](double s) { return ellipse_offset(d)(s)[0].y(); };
  double lo = 1e-3, hi = kPi / 2;  // y < 0 just after the cusp region, y > 0 at the top
  for (int i = 0; i < 200; ++i) (y(0.5 * (lo + hi)) > 0 ? hi : lo) = 0.5 * (lo + hi);
  return 0.5 * (lo + hi);
}
}  // namespace

TEST(Offset, InputEllipseInterpolantIsExactEnough) {
  const BSpline e = interpolant(t::ellipse(kA, kB), 96);
  double worst = 0;
  for (const V& x : sample(e, 500)) worst = std::max(worst, t::exact_distance(t::ellipse(kA, kB), x, 0, 2 * kPi, false));
  EXPECT_LT(worst, 1e-5);
}

TEST(Offset, EllipseInnerAndOuterOffsetsWithin1e3By32Controls) {
  const BSpline e = interpolant(t::ellipse(kA, kB), 96);
  for (double d : {-0.3, 0.2, 0.5, 1.0}) {
    const OffsetResult r = offset_curve(e, d, {.max_controls = 32});
    EXPECT_LE(r.curve.control_count(), 32) << d;
    EXPECT_TRUE(r.corners.empty()) << d;
    const t::Curve3 exact = ellipse_offset(d);
    double worst = 0;
    for (const V& x : sample(r.curve, 400)) worst = std::max(worst, t::exact_distance(exact, x, 0, 2 * kPi, false, 1000));
    const auto [u0, u1] = r.curve.domain();
    for (int i = 0; i < 200; ++i)
      worst = std::max(worst, t::exact_distance(as_curve(r.curve), exact(2 * kPi * i / 200)[0], u0, u1, false, 1000));
    EXPECT_LE(worst, 1e-3) << "d = " << d;
    EXPECT_GE(r.max_error, 0.5 * worst) << d;  // the reported error is not an underestimate
  }
}

TEST(Offset, InnerOffsetPastTheCurvatureRadiusGetsTwoSharpCorners) {
  // b^2 / a = 0.5 < 0.6: the raw offset has two swallowtails (four cusps), trimmed at the x axis.
  const double d = -0.6;
  const BSpline e = interpolant(t::ellipse(kA, kB), 96);
  const OffsetResult r = offset_curve(e, d, {.max_controls = 40});
  ASSERT_EQ(r.corners.size(), 2u);
  const double tc = crossing_parameter(d);
  const double xc = ellipse_offset(d)(tc)[0].x();
  for (const OffsetCorner& c : r.corners) {
    EXPECT_NEAR(std::abs(c.point.x()), xc, 1e-6);
    EXPECT_NEAR(c.point.y(), 0.0, 1e-6);
    EXPECT_LT((r.curve.point(c.parameter) - c.point).norm(), 1e-9);
    int multiplicity = 0;
    for (double k : r.curve.knots()) multiplicity += k == c.parameter;
    EXPECT_EQ(multiplicity, 3);
    // A real corner: the one-sided tangents differ.
    const V before = r.curve.derivatives(c.parameter - 1e-9, 1)[1].normalized();
    const V after = r.curve.derivatives(c.parameter, 1)[1].normalized();
    EXPECT_LT(before.dot(after), std::cos(10 * kPi / 180));
  }
  EXPECT_GT(r.corners[0].point.x() * r.corners[1].point.x(), -1e300);
  EXPECT_LT(r.corners[0].point.x() * r.corners[1].point.x(), 0.0);  // one on each side
  // Away from the corners the result lies on the trimmed offset (t in [tc, pi - tc] and its mirror).
  const t::Curve3 exact = ellipse_offset(d);
  double worst = 0;
  for (const V& x : sample(r.curve, 400)) {
    if ((x - r.corners[0].point).norm() < 0.05 || (x - r.corners[1].point).norm() < 0.05) continue;
    worst = std::max(worst, std::min(t::exact_distance(exact, x, tc, kPi - tc, true, 1000),
                                     t::exact_distance(exact, x, kPi + tc, 2 * kPi - tc, true, 1000)));
  }
  EXPECT_LE(worst, 1e-3);
}

TEST(Offset, OffsetThatWouldChangeTopologyIsAGeometryError) {
  const BSpline e = interpolant(t::ellipse(kA, kB), 96);
  EXPECT_THROW((void)offset_curve(e, -1.2, {.controls = 16}), GeometryError);  // vanishes
  // A peanut r = 1 + 0.7 cos 2t: neck half-width 0.3, lobes about 0.7 high: at -0.5 two loops would remain.
  const t::Curve3 peanut = [](double s) {
    const double r = 1 + 0.7 * std::cos(2 * s);
    return std::array<V, 3>{V(r * std::cos(s), r * std::sin(s), 0), V::Zero(), V::Zero()};
  };
  const BSpline p = interpolant(peanut, 96);
  EXPECT_NO_THROW((void)offset_curve(p, -0.2, {.controls = 40}));
  EXPECT_THROW((void)offset_curve(p, -0.5, {.controls = 40}), GeometryError);
}

TEST(Offset, BadInputIsATypedError) {
  const BSpline e = interpolant(t::ellipse(kA, kB), 32);
  EXPECT_THROW((void)offset_curve(e, std::nan(""), {}), InvalidInput);
  EXPECT_THROW((void)offset_curve(e, 0.1, {.degree = 0}), InvalidInput);
  EXPECT_THROW((void)offset_curve(BSpline::clamped(3, {V(0, 0, 0), V(1, 0, 1), V(2, 1, 0), V(3, 0, 0)}), 0.1), InvalidInput);
  EXPECT_THROW((void)offset_curve(e, -0.6, {.controls = 5}), InvalidInput);  // two corners need more
}

TEST(Offset, OpenCurveOffsetKeepsItsEndsAndItsDistance) {
  // Every point of an offset without corners is |d| from the curve; the ends are c(a) + d n(a), c(b) + d n(b).
  const BSpline c = BSpline::clamped(3, {V(0, 0, 0), V(1, 1, 0), V(2, -1, 0), V(3, 1, 0), V(4, 0, 0)});
  for (double d : {0.1, -0.1}) {
    const OffsetResult r = offset_curve(c, d, {.max_controls = 32});
    EXPECT_FALSE(r.curve.closed());
    const auto [a, b] = r.curve.domain();
    // The ends: the tangents at the ends of this clamped curve are (1, 1) and (1, -1), so n = (1, -1)/sqrt2 and (-1, -1)/sqrt2.
    EXPECT_LT((r.curve.point(a) - V(d / std::sqrt(2.0), -d / std::sqrt(2.0), 0)).norm(), 1e-9);
    EXPECT_LT((r.curve.point(b) - V(4 - d / std::sqrt(2.0), -d / std::sqrt(2.0), 0)).norm(), 1e-9);
    double worst = 0;
    for (const V& x : sample(r.curve, 300)) worst = std::max(worst, std::abs(t::exact_distance(as_curve(c), x, 0, 1, true) - std::abs(d)));
    EXPECT_LT(worst, 1e-3) << d;
  }
}
