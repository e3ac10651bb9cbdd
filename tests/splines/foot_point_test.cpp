#include "splines/foot_point.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

#include "base/errors.hpp"
#include "test_names.hpp"
#include "splines/detail/foot_point_search.hpp"

namespace {

// The library's generic search over an analytic parametrization; its answer is compared with the
// test's own exact distance (a different sampling and Newton loop).
double library_distance(const t::Curve3& c, double a, double b, bool closed, const V& x) {
  const splines::detail::FootPointSearch search([&c](double s) { return c(s); }, a, b, closed, 64);
  return search.global(x).distance;
}
}  // namespace

TEST(FootPoint, CircleDistanceIsRadiusDifference) {
  // A quadratic spline cannot be a circle, so use the degree-1 closed spline through a square
  // instead: its distance is known in closed form (distance to the nearest edge or corner).
  const BSpline square = BSpline(1, {0, 1, 2, 3, 4}, {V(0, 0, 0), V(1, 0, 0), V(1, 1, 0), V(0, 1, 0)}, true);
  EXPECT_NEAR(closest_point(square, V(0.5, -0.3, 0)).distance, 0.3, 1e-14);
  EXPECT_NEAR(closest_point(square, V(0.5, 0.4, 0)).distance, 0.4, 1e-14);
  EXPECT_NEAR(closest_point(square, V(1.3, 1.4, 0)).distance, 0.5, 1e-14);
  EXPECT_NEAR(closest_point(square, V(-3, -4, 0)).distance, 5.0, 1e-14);
}

TEST(FootPoint, EllipseAndHelixByTheGenericSearchMatchExactDistances) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-3, 3);
  const auto e = t::ellipse(2, 1);
  const auto h = t::helix(0.2);
  for (int i = 0; i < 200; ++i) {
    const V x(u(rng), u(rng), 0), y(u(rng) / 2, u(rng) / 2, u(rng) / 3);
    EXPECT_NEAR(library_distance(e, 0, 2 * kPi, true, x), t::exact_distance(e, x, 0, 2 * kPi, false), 1e-10);
    EXPECT_NEAR(library_distance(h, 0, 2 * kPi, false, y), t::exact_distance(h, y, 0, 2 * kPi, true), 1e-10);
  }
}

TEST(FootPoint, OpenCurveEndsAreFootPoints) {
  const BSpline s = BSpline::clamped(3, {V(0, 0, 0), V(1, 1, 0), V(2, -1, 0), V(3, 0, 0)});
  const FootPoint f = closest_point(s, V(-1, -0.5, 0));
  EXPECT_EQ(f.parameter, 0.0);
  EXPECT_NEAR(f.distance, std::hypot(1.0, 0.5), 1e-15);
  const FootPoint g = closest_point(s, V(4, 1, 0));
  EXPECT_EQ(g.parameter, 1.0);
}

TEST(FootPoint, CurveThatComesCloseToItselfGetsTheRightBranch) {
  // A hairpin: two parallel branches 0.02 apart; points just outside each branch must land on it.
  const BSpline s = BSpline::clamped(3, {V(0, 0, 0), V(4, 0, 0), V(5, 0.01, 0), V(4, 0.02, 0), V(0, 0.02, 0)});
  // Dense reference: the curve sampled 200000 times.
  const auto reference = [&](const V& x) {
    double best = INFINITY;
    for (int i = 0; i <= 200000; ++i) best = std::min(best, (s.point(i / 200000.0) - x).norm());
    return best;
  };
  for (const V& x : {V(1, -0.005, 0), V(1, 0.025, 0), V(2.5, 0.011, 0), V(3.7, -0.1, 0)}) {
    const FootPoint f = closest_point(s, x);
    EXPECT_LE(f.distance, reference(x) + 1e-12);
    EXPECT_GE(f.distance, reference(x) - 1e-6);
  }
}

TEST(FootPoint, DistanceSummaryAndSampling) {
  const BSpline line = BSpline::clamped(1, {V(0, 0, 0), V(2, 0, 0)});
  const DistanceSummary d = distance(line, {V(1, 1, 0), V(1, -3, 0), V(3, 0, 0)});
  EXPECT_DOUBLE_EQ(d.max, 3.0);
  EXPECT_NEAR(d.rms, std::sqrt((1.0 + 9.0 + 1.0) / 3.0), 1e-15);
  const auto s = sample(line, 5);
  ASSERT_EQ(s.size(), 5u);
  EXPECT_EQ(s.back(), V(2, 0, 0));
  EXPECT_EQ(sample(BSpline::periodic(1, {V(0, 0, 0), V(1, 0, 0), V(0, 1, 0)}), 3).size(), 3u);
  EXPECT_THROW((void)sample(line, 1), InvalidInput);
  EXPECT_THROW((void)distance(line, {}), InvalidInput);
  EXPECT_THROW((void)closest_point(line, V(std::nan(""), 0, 0)), InvalidInput);
}
