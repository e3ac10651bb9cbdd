// Tests of trace() (lib/implicit/trace.hpp) on the curves of Ihm & Naylor's Appendix B, traced
// from their implicit equations and checked against their analytic parametrizations.
#include "implicit/trace.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "implicit/implicit_testing.hpp"

using namespace sculpt;
using namespace sculpt::implicit;
using namespace sculpt::implicit::testing;

namespace {

// Every chord within tol of the curve: the distance from each chord's midpoint to the curve
// (measured on the parametrization), and the largest over the curve.
double max_chord_height(const TracedCurve& c, const std::vector<Parametrization>& curve) {
  double worst = 0.0;
  for (std::size_t k = 0; k < chord_count(c); ++k) {
    const Vec mid = 0.5 * (c.points[k] + c.points[(k + 1) % c.points.size()]);
    double d = std::numeric_limits<double>::infinity();
    for (const Parametrization& p : curve) d = std::min(d, distance_to_curve(p, mid));
    worst = std::max(worst, d);
  }
  return worst;
}

// Total signed turning of the projection onto the xy-plane around the axis (x0, 0).
double winding_angle(const TracedCurve& c, double x0) {
  double total = 0.0;
  for (std::size_t k = 0; k < chord_count(c); ++k) {
    const Vec& a = c.points[k];
    const Vec& b = c.points[(k + 1) % c.points.size()];
    const double da = std::atan2(b.y(), b.x() - x0) - std::atan2(a.y(), a.x() - x0);
    total += std::remainder(da, 2.0 * kPi);
  }
  return total;
}

const Box kFig7Box{.lo = Vec(-2.5, -2.5, -5.0), .hi = Vec(2.5, 2.5, 5.0)};

}  // namespace

class Fig7Quartic : public ::testing::TestWithParam<double> {};

TEST_P(Fig7Quartic, GivesExactlyItsTwoClosedLoops) {
  const double tol = GetParam();
  const CurvePair pair = fig7_quartic();
  const TraceResult r = trace(pair.f, pair.g, {.box = kFig7Box, .tolerance = tol});
  EXPECT_FALSE(r.budget_exhausted);
  EXPECT_TRUE(r.singular_points.empty());
  ASSERT_EQ(r.curves.size(), 2u);
  int upper = 0, lower = 0;
  const double diagonal = (kFig7Box.hi - kFig7Box.lo).norm();
  for (const TracedCurve& c : r.curves) {
    EXPECT_TRUE(c.closed);
    ASSERT_GE(c.points.size(), 8u);
    const double sign = c.points[0].z() > 0 ? 1.0 : -1.0;
    (sign > 0 ? upper : lower)++;
    // Each point on the analytic loop: on the cylinder (to the residual target), and z from the
    // ellipsoid (dz/dy reaches 25 where the loops come closest, hence the looser bound).
    for (const Vec& p : c.points) {
      EXPECT_NEAR(p.head<2>().norm(), std::sqrt(3.94), 1e-12 * diagonal);
      EXPECT_NEAR(p.z(), sign * std::sqrt((324.0 - 36.0 * p.x() * p.x() - 81.0 * p.y() * p.y()) / 9.0), 1e-9);
    }
    EXPECT_NEAR(std::abs(winding_angle(c, 0.0)), 2.0 * kPi, 1e-9);  // once around, no back-tracking
    EXPECT_LE(max_residual(pair, c.points), 1e-12 * diagonal);
    const Parametrization loop = fig7_loop(sign);
    EXPECT_LE(max_chord_height(c, {loop}), tol);
    const double ideal = ideal_point_count(loop, tol);
    EXPECT_LE(static_cast<double>(c.points.size()), 1.3 * ideal) << "ideal " << ideal;
    EXPECT_GE(static_cast<double>(c.points.size()), 0.9 * ideal);  // far fewer would break the chord heights
  }
  EXPECT_EQ(upper, 1);
  EXPECT_EQ(lower, 1);
}

INSTANTIATE_TEST_SUITE_P(Tolerances, Fig7Quartic, ::testing::Values(1e-2, 1e-3, 1e-4));

class SingularCurves : public ::testing::TestWithParam<double> {};

TEST_P(SingularCurves, VivianiCurveIsTracedThroughItsSelfCrossing) {
  const CurvePair pair = viviani();
  const Box box{.lo = Vec(-0.5, -1.5, -2.5), .hi = Vec(2.5, 1.5, 2.5)};
  const double tol = GetParam();
  const TraceResult r = trace(pair.f, pair.g, {.box = box, .tolerance = tol});
  EXPECT_FALSE(r.budget_exhausted);
  ASSERT_EQ(r.singular_points.size(), 1u);
  EXPECT_LE((r.singular_points[0].point - Vec(2, 0, 0)).norm(), 1e-9);  // located, not just seen
  EXPECT_EQ(r.singular_points[0].passes, 2);  // both branches through it, each once
  EXPECT_TRUE(r.singular_points[0].resolved);
  ASSERT_EQ(r.curves.size(), 1u);  // the figure eight, one closed walk through the crossing
  const TracedCurve& c = r.curves[0];
  EXPECT_TRUE(c.closed);
  EXPECT_LE(max_residual(pair, c.points), 1e-12 * (box.hi - box.lo).norm());
  const Parametrization exact = viviani_curve();
  // Length from the quadrature of the parametrization: chords are a little shorter than arcs
  // (by about kappa^2 h^2 / 24 = kappa tol / 3 relative, kappa <= 1.2 here).
  const double length = arc_length(exact);
  EXPECT_NEAR(length, 15.280791156, 1e-8);  // 8 sqrt(2) E(k^2 = 1/2), E the complete elliptic integral
  EXPECT_LE(polyline_length(c), length);
  EXPECT_GE(polyline_length(c), length * (1.0 - 0.5 * tol));
  EXPECT_LE(max_chord_height(c, {exact}), tol);
  EXPECT_LE(static_cast<double>(c.points.size()), 1.3 * ideal_point_count(exact, tol));
}

TEST_P(SingularCurves, Fig8SexticIsTracedThroughItsNode) {
  const CurvePair pair = fig8_sextic();
  const Box box{.lo = Vec(-1.3, -1.5, 1.0), .hi = Vec(0.7, 1.5, 5.0)};
  const double tol = GetParam();
  const TraceResult r = trace(pair.f, pair.g, {.box = box, .tolerance = tol});
  EXPECT_FALSE(r.budget_exhausted);
  ASSERT_EQ(r.singular_points.size(), 1u);
  EXPECT_LE((r.singular_points[0].point - Vec(0, 0, 2)).norm(), 1e-9);
  EXPECT_EQ(r.singular_points[0].passes, 2);
  EXPECT_TRUE(r.singular_points[0].resolved);
  ASSERT_EQ(r.curves.size(), 1u);  // the loop and both tails, one piece
  const TracedCurve& c = r.curves[0];
  EXPECT_FALSE(c.closed);
  EXPECT_NEAR(c.points.front().x(), 0.7, 1e-9);  // open pieces end on the box
  EXPECT_NEAR(c.points.back().x(), 0.7, 1e-9);
  EXPECT_LE(max_residual(pair, c.points), 1e-12 * (box.hi - box.lo).norm());
  const Parametrization exact = fig8_sextic_curve(std::sqrt(1.7));
  const double length = arc_length(exact);
  EXPECT_LE(polyline_length(c), length + 1e-9);
  EXPECT_GE(polyline_length(c), length * (1.0 - tol));
  EXPECT_LE(max_chord_height(c, {exact}), tol);
  // Chords against the ideal count: the target of 1.3, although an open curve loses up to
  // a chord at each box face and each pass through the node (measured: 1.24 at tol 1e-2, 1.11 at
  // 1e-3, 1.04 at 1e-4, see docs/implicit.md).
  EXPECT_LE(static_cast<double>(chord_count(c)), 1.3 * ideal_point_count(exact, tol));
}

INSTANTIATE_TEST_SUITE_P(Tolerances, SingularCurves, ::testing::Values(1e-2, 1e-3, 1e-4));

TEST(Trace, VillarceauCirclesAreTwoLoopsCrossingTwice) {
  // A torus (R = 1, r = 0.5) cut by its bitangent plane through the centre: two circles of
  // radius R centred at (0, +-r, 0), crossing where the plane touches the torus, at
  // +-(R cos^2 a, 0, R cos a sin a) with sin a = r / R. Each circle must come out as one loop.
  const double R = 1.0, r = 0.5, sa = r / R, ca = std::sqrt(1.0 - sa * sa);
  ExpressionBuilder b;
  const Term x = b.x(), y = b.y(), z = b.z();
  const Term rho2 = b.add(b.pow(x, 2), b.pow(y, 2));
  const Expression torus = b.finish(b.sub(b.pow(b.add(b.add(rho2, b.pow(z, 2)), b.constant(R * R - r * r)), 2),
                                          b.mul(b.constant(4 * R * R), rho2)));
  ExpressionBuilder c;
  const Expression plane = c.finish(c.sub(c.mul(c.constant(ca), c.z()), c.mul(c.constant(sa), c.x())));
  const double tol = 1e-3;
  const TraceResult result =
      trace(torus, plane, {.box = {.lo = Vec(-1.7, -1.6, -0.7), .hi = Vec(1.6, 1.7, 0.8)}, .tolerance = tol});
  ASSERT_EQ(result.singular_points.size(), 2u);
  for (const SingularPoint& s : result.singular_points) {
    EXPECT_EQ(s.passes, 2);
    EXPECT_LE((s.point.cwiseAbs() - Vec(R * ca * ca, 0, R * ca * sa)).norm(), 1e-9);
  }
  ASSERT_EQ(result.curves.size(), 2u);
  std::vector<double> centres;
  for (const TracedCurve& curve : result.curves) {
    EXPECT_TRUE(curve.closed);
    // The circle it lies on: the centre with the smaller largest deviation, which must be tiny.
    auto deviation = [&](double cy) {
      double worst = 0.0;
      for (const Vec& p : curve.points) worst = std::max(worst, std::abs((p - Vec(0, cy, 0)).norm() - R));
      return worst;
    };
    const double cy = deviation(r) < deviation(-r) ? r : -r;
    EXPECT_LE(deviation(cy), 1e-9);
    centres.push_back(cy);
    const double length = polyline_length(curve);
    EXPECT_LE(length, 2 * kPi * R);
    EXPECT_GE(length, 2 * kPi * R * (1 - tol));
  }
  EXPECT_NE(centres[0], centres[1]);
}

TEST(Trace, CloseConcentricCirclesAreNotMixed) {
  // Two circles 0.05 apart on the plane z = 0, traced with steps longer than the gap.
  ExpressionBuilder b;
  const Term r2 = b.add(b.pow(b.x(), 2), b.pow(b.y(), 2));
  const Expression g = b.finish(b.mul(b.sub(r2, b.constant(1.0)), b.sub(r2, b.constant(1.05 * 1.05))));
  ExpressionBuilder c;
  const Expression f = c.finish(c.z());
  const TraceResult r = trace(f, g, {.box = {.lo = Vec(-1.3, -1.3, -0.5), .hi = Vec(1.3, 1.3, 0.5)}, .tolerance = 1e-3});
  ASSERT_EQ(r.curves.size(), 2u);
  std::vector<double> radii;
  for (const TracedCurve& curve : r.curves) {
    EXPECT_TRUE(curve.closed);
    const double radius = curve.points[0].head<2>().norm();
    radii.push_back(radius);
    for (const Vec& p : curve.points) EXPECT_NEAR(p.head<2>().norm(), radius, 1e-9);
    EXPECT_NEAR(std::abs(winding_angle(curve, 0.0)), 2.0 * kPi, 1e-9);
  }
  std::sort(radii.begin(), radii.end());
  EXPECT_NEAR(radii[0], 1.0, 1e-9);
  EXPECT_NEAR(radii[1], 1.05, 1e-9);
}

TEST(Trace, RandomPlaneSectionsOfSpheresAreOneCircleEach) {
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (int k = 0; k < 40; ++k) {
    const double radius = 0.05 + 0.8 * u(rng);
    const Vec centre = Vec(u(rng), u(rng), u(rng)) * (2.0 - 2.0 * radius) - Vec::Constant(1.0 - radius);
    const Vec normal = Vec(u(rng) - 0.5, u(rng) - 0.5, u(rng) - 0.5).normalized();
    const double offset = (1.8 * u(rng) - 0.9) * radius, tol = std::pow(10.0, -2.0 - 2.0 * u(rng));
    ExpressionBuilder b;
    const Expression f = b.finish(b.sub(b.add(b.add(b.pow(b.sub(b.x(), b.constant(centre.x())), 2),
                                                    b.pow(b.sub(b.y(), b.constant(centre.y())), 2)),
                                              b.pow(b.sub(b.z(), b.constant(centre.z())), 2)),
                                        b.constant(radius * radius)));
    ExpressionBuilder c;
    const Expression g = c.finish(c.sub(c.add(c.add(c.mul(c.constant(normal.x()), c.x()), c.mul(c.constant(normal.y()), c.y())),
                                              c.mul(c.constant(normal.z()), c.z())),
                                        c.constant(normal.dot(centre) + offset)));
    const TraceResult r = trace(f, g, {.box = {.lo = Vec(-1, -1, -1), .hi = Vec(1, 1, 1)}, .tolerance = tol});
    const double circle_radius = std::sqrt(radius * radius - offset * offset);
    const Vec circle_centre = centre + offset * normal;
    ASSERT_EQ(r.curves.size(), 1u) << "case " << k;
    EXPECT_TRUE(r.curves[0].closed);
    EXPECT_TRUE(r.singular_points.empty());
    for (const Vec& p : r.curves[0].points) EXPECT_NEAR((p - circle_centre).norm(), circle_radius, 1e-9);
    const double length = polyline_length(r.curves[0]);
    EXPECT_LE(length, 2 * kPi * circle_radius);
    EXPECT_GE(length, 2 * kPi * circle_radius - 2 * kPi * tol);  // chord heights <= tol
  }
}

TEST(Trace, NearlyTouchingLoopsStaySeparate) {
  // Fig. 7's configuration with random axes: an ellipsoid cut by a cylinder slightly thinner than
  // its middle axis b gives an upper and a lower loop that come within 2 c sqrt(1 - rho^2/b^2)
  // of each other where the surfaces nearly touch: here from 4.5 tol up (0.045 at tol 1e-2).
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (int k = 0; k < 40; ++k) {
    const double a = 1.5 + 1.5 * u(rng), b = 0.8 + (a - 1.1) * u(rng), c = 0.5 + 2 * u(rng);
    const double rho = b * (1 - std::pow(10.0, -3 + 2 * u(rng))), tol = std::pow(10.0, -2 - 2 * u(rng));
    ExpressionBuilder e;
    const Expression f = e.finish(e.sub(e.add(e.add(e.mul(e.constant(1 / (a * a)), e.pow(e.x(), 2)),
                                                    e.mul(e.constant(1 / (b * b)), e.pow(e.y(), 2))),
                                              e.mul(e.constant(1 / (c * c)), e.pow(e.z(), 2))),
                                        e.constant(1)));
    ExpressionBuilder h;
    const Expression g = h.finish(h.sub(h.add(h.pow(h.x(), 2), h.pow(h.y(), 2)), h.constant(rho * rho)));
    const Box box{.lo = Vec(-a - 0.31, -b - 0.27, -c - 0.33), .hi = Vec(a + 0.29, b + 0.35, c + 0.23)};
    const TraceResult r = trace(f, g, {.box = box, .tolerance = tol});
    ASSERT_EQ(r.curves.size(), 2u) << "case " << k;
    EXPECT_TRUE(r.singular_points.empty());
    int upper = 0;
    for (const TracedCurve& curve : r.curves) {
      EXPECT_TRUE(curve.closed);
      const double sign = curve.points[0].z() > 0 ? 1.0 : -1.0;
      upper += sign > 0;
      for (const Vec& p : curve.points) {
        EXPECT_GT(sign * p.z(), 0.0) << "case " << k << ": a loop jumped to the other";
        EXPECT_NEAR(p.head<2>().norm(), rho, 1e-9);
      }
    }
    EXPECT_EQ(upper, 1);
  }
}

TEST(Trace, SmallComponentIsFoundWithoutSeeds) {
  // A circle of radius 0.02 (sphere cut by a plane through its centre) in a box 100 times larger.
  ExpressionBuilder b;
  const Term dx = b.sub(b.x(), b.constant(0.31)), dy = b.sub(b.y(), b.constant(-0.27)),
             dz = b.sub(b.z(), b.constant(0.13));
  const Expression f = b.finish(b.sub(b.add(b.add(b.pow(dx, 2), b.pow(dy, 2)), b.pow(dz, 2)), b.constant(4e-4)));
  ExpressionBuilder c;
  const Expression g = c.finish(c.sub(c.z(), c.constant(0.13)));
  const TraceResult r = trace(f, g, {.box = {.lo = Vec(-1, -1, -1), .hi = Vec(1, 1, 1)}, .tolerance = 1e-5});
  ASSERT_EQ(r.curves.size(), 1u);
  EXPECT_TRUE(r.curves[0].closed);
  for (const Vec& p : r.curves[0].points) EXPECT_NEAR((p - Vec(0.31, -0.27, 0.13)).norm(), 0.02, 1e-12);
}

TEST(Trace, TouchingSurfacesGiveAnIsolatedPointAndNoCurve) {
  // The unit sphere and its tangent plane z = 1 meet only at (0, 0, 1).
  ExpressionBuilder b;
  const Expression f =
      b.finish(b.sub(b.add(b.add(b.pow(b.x(), 2), b.pow(b.y(), 2)), b.pow(b.z(), 2)), b.constant(1.0)));
  ExpressionBuilder c;
  const Expression g = c.finish(c.sub(c.z(), c.constant(1.0)));
  for (const double tol : {1e-2, 1e-3}) {
    const TraceResult r = trace(f, g, {.box = {.lo = Vec(-1.3, -1.2, -1.1), .hi = Vec(1.2, 1.3, 1.4)}, .tolerance = tol});
    EXPECT_TRUE(r.curves.empty()) << "tol " << tol;
    EXPECT_FALSE(r.budget_exhausted);
    ASSERT_EQ(r.singular_points.size(), 1u);
    EXPECT_EQ(r.singular_points[0].passes, 0);
    EXPECT_LE((r.singular_points[0].point - Vec(0, 0, 1)).norm(), 1e-5);
  }
}

TEST(Trace, BoxWithoutCurveGivesNothing) {
  const CurvePair pair = fig7_quartic();
  const TraceResult r = trace(pair.f, pair.g, {.box = {.lo = Vec(-1, -1, -1), .hi = Vec(1, 1, 1)}, .tolerance = 1e-3});
  EXPECT_TRUE(r.curves.empty());
  EXPECT_FALSE(r.budget_exhausted);
  EXPECT_EQ(r.steps, 0);
}

TEST(Trace, OpenPiecesEndOnTheBox) {
  // The quartic's loops cut by a box that holds only x >= 0.5: four arcs, each ending on x = 0.5.
  const CurvePair pair = fig7_quartic();
  const TraceResult r = trace(pair.f, pair.g, {.box = {.lo = Vec(0.5, -2.5, -5), .hi = Vec(2.5, 2.5, 5)}, .tolerance = 1e-3});
  ASSERT_EQ(r.curves.size(), 2u);
  for (const TracedCurve& c : r.curves) {
    EXPECT_FALSE(c.closed);
    EXPECT_NEAR(c.points.front().x(), 0.5, 1e-9);
    EXPECT_NEAR(c.points.back().x(), 0.5, 1e-9);
    EXPECT_LE(max_chord_height(c, {fig7_loop(c.points[0].z() > 0 ? 1.0 : -1.0)}), 1e-3);
  }
}

TEST(Trace, StepBudgetRunsOutWithoutHanging) {
  const CurvePair pair = fig7_quartic();
  const TraceResult r = trace(pair.f, pair.g, {.box = kFig7Box, .tolerance = 1e-4, .max_steps = 50});
  EXPECT_TRUE(r.budget_exhausted);
  EXPECT_LE(r.steps, 50);
}

TEST(Trace, BadOptionsAreRejected) {
  const CurvePair pair = fig7_quartic();
  EXPECT_THROW((void)trace(pair.f, pair.g, {.box = {.lo = Vec(0, 0, 0), .hi = Vec(1, 0, 1)}, .tolerance = 1e-3}),
               InvalidInput);  // empty box
  EXPECT_THROW((void)trace(pair.f, pair.g, {.box = {.lo = Vec(1, 0, 0), .hi = Vec(0, 1, 1)}, .tolerance = 1e-3}),
               InvalidInput);
  EXPECT_THROW((void)trace(pair.f, pair.g, {.box = kFig7Box, .tolerance = 0.0}), InvalidInput);
  EXPECT_THROW((void)trace(pair.f, pair.g, {.box = kFig7Box, .tolerance = 1e-14}), InvalidInput);
  EXPECT_THROW((void)trace(pair.f, pair.g, {.box = kFig7Box, .tolerance = std::nan("")}), InvalidInput);
  EXPECT_THROW((void)trace(pair.f, pair.g, {.box = kFig7Box, .tolerance = 1e-3, .max_steps = 0}), InvalidInput);
}

TEST(Trace, FunctionNotFiniteInTheBoxIsAnError) {
  // sqrt(x) + y = 0 is not defined for x < 0, and its gradient is infinite at x = 0.
  ExpressionBuilder b;
  const Expression f = b.finish(b.add(b.sqrt(b.x()), b.y()));
  ExpressionBuilder c;
  const Expression g = c.finish(c.z());
  EXPECT_THROW((void)trace(f, g, {.box = {.lo = Vec(-1, -1, -1), .hi = Vec(1, 1, 1)}, .tolerance = 1e-3}),
               NonFiniteValue);
}
