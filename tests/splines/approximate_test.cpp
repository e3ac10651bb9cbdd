#include "splines/approximate.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "base/errors.hpp"
#include "test_names.hpp"
#include "splines/degree_reduction.hpp"
#include "splines/foot_point.hpp"

namespace {

// Five degree-6 Bezier curves: an S, a hump, a loop-free spiral arc, a wave and a hook.
std::vector<BSpline> degree_six_curves() {
  return {
      BSpline::bezier({V(0, 0, 0), V(1, 2, 0), V(2, 2, 0), V(3, 0, 0), V(4, -2, 0), V(5, -2, 0), V(6, 0, 0)}),
      BSpline::bezier({V(0, 0, 0), V(0.5, 1.5, 0), V(1.5, 2.5, 0), V(3, 3, 0), V(4.5, 2.5, 0), V(5.5, 1.5, 0), V(6, 0, 0)}),
      BSpline::bezier({V(0, 0, 0), V(2, 0, 0), V(3, 1, 0), V(3, 3, 0), V(1, 4, 0), V(-1, 3, 0), V(-1, 1, 0)}),
      BSpline::bezier({V(0, 0, 0), V(1, 1, 0), V(2, -1, 0), V(3, 1, 0), V(4, -1, 0), V(5, 1, 0), V(6, 0, 0)}),
      BSpline::bezier({V(0, 0, 0), V(1, 3, 0), V(3, 4, 0), V(5, 3, 0), V(5, 1, 0), V(3.5, 0.5, 0), V(3, 1.5, 0)}),
  };
}

// The test's own two-sided Hausdorff distance: dense samples of each curve against a dense
// polyline of the other refined by the analytic (Bernstein) form's Newton in exact_distance.
double exact_hausdorff(const BSpline& a, const BSpline& b) {
  const auto curve_of = [](const BSpline& s) -> t::Curve3 {
    return [&s](double u) {
      const auto d = s.derivatives(u, 2);
      return std::array<V, 3>{d[0], d[1], d[2]};
    };
  };
  double h = 0.0;
  for (int i = 0; i <= 200; ++i) {
    h = std::max(h, t::exact_distance(curve_of(b), a.point(i / 200.0), 0, 1, true, 300));
    h = std::max(h, t::exact_distance(curve_of(a), b.point(i / 200.0), 0, 1, true, 300));
  }
  return h;
}
}  // namespace

TEST(DegreeReduction, BadInputIsATypedError) {
  const BSpline b = degree_six_curves()[0];
  EXPECT_THROW((void)reduce_degree(b, 6), InvalidInput);
  EXPECT_THROW((void)reduce_degree_l2(b, 0), InvalidInput);
  EXPECT_THROW((void)reduce_degree(BSpline::periodic(3, {V(0, 0, 0), V(1, 0, 0), V(1, 1, 0), V(0, 1, 0)}), 2), InvalidInput);
}

TEST(DegreeReduction, EckL2ReproducesACurveOfTheLowerDegreeElevated) {
  // A cubic elevated to degree 6 (exact elevation by hand: degree 3 -> 4 -> 5 -> 6) reduces back exactly.
  std::vector<V> c = {V(0, 0, 0), V(1, 2, 0), V(3, 2, 0), V(4, 0, 0)};
  std::vector<V> e = c;
  for (int n = 3; n < 6; ++n) {
    std::vector<V> f(n + 2);
    f[0] = e[0];
    f[n + 1] = e[n];
    for (int i = 1; i <= n; ++i) f[i] = (double(i) / (n + 1)) * e[i - 1] + (1 - double(i) / (n + 1)) * e[i];
    e = f;
  }
  const BSpline r = reduce_degree_l2(BSpline::bezier(e), 3);
  for (int i = 0; i < 4; ++i) EXPECT_LT((r.controls()[i] - c[i]).norm(), 1e-12);
}

TEST(DegreeReduction, EckL2TwiceEqualsOnce) {
  // Nested constrained L2 projections compose: 6 -> 5 -> 4 is the 6 -> 4 projection (docs/splines.md).
  for (const BSpline& b : degree_six_curves()) {
    const BSpline once = reduce_degree_l2(b, 4), twice = reduce_degree_l2(reduce_degree_l2(b, 5), 4);
    for (int i = 0; i <= 4; ++i) EXPECT_LT((once.controls()[i] - twice.controls()[i]).norm(), 1e-10);
  }
}

TEST(DegreeReduction, ActiveCurveBeatsEckOnceAndTwiceOnFiveCurves) {
  for (const BSpline& b : degree_six_curves()) {
    const BSpline eck_once = reduce_degree_l2(b, 4);
    const BSpline eck_twice = reduce_degree_l2(reduce_degree_l2(b, 5), 4);
    const FitResult active = reduce_degree(b, 4);
    const TargetCurve target = target_of(b);
    const double e_active = one_sided_error(active.curve, target).sum;
    const double e_once = one_sided_error(eck_once, target).sum, e_twice = one_sided_error(eck_twice, target).sum;
    const double h_active = exact_hausdorff(active.curve, b), h_once = exact_hausdorff(eck_once, b),
                 h_twice = exact_hausdorff(eck_twice, b);
    EXPECT_LT(e_active, e_once);
    EXPECT_LT(e_active, e_twice);
    EXPECT_LT(h_active, h_once);
    EXPECT_LT(h_active, h_twice);
    EXPECT_EQ(active.curve.controls().front(), b.controls().front());
    EXPECT_EQ(active.curve.controls().back(), b.controls().back());
  }
}

TEST(Approximate, HelixTurnByFourCubicSegmentsFromTheChord) {
  const TargetCurve helix{.evaluate = t::helix(0.2), .t0 = 0, .t1 = 2 * kPi, .closed = false, .samples = 256};
  const V a = helix.evaluate(0)[0], b = helix.evaluate(2 * kPi)[0];
  std::vector<V> chord(7);
  for (int i = 0; i < 7; ++i) chord[i] = a + (b - a) * (i / 6.0);
  const FitResult r = approximate(helix, BSpline::clamped(3, chord, 3), {.fixed = {0, 6}});
  double max_dev = 0.0;
  for (int i = 0; i <= 500; ++i)
    max_dev = std::max(max_dev, t::exact_distance(helix.evaluate, r.curve.point(i / 500.0), 0, 2 * kPi, true));
  ASSERT_TRUE(r.converged);
  ASSERT_GE(r.history.size(), 11u);
  // Converged by step 10: the rms distance is within 1 % of the final one (tolerance 1e-6 stops later).
  EXPECT_LT(r.history[10].rms_distance, 1.01 * r.history.back().rms_distance);
  EXPECT_LT(max_dev, 4e-3);  // measured 3.65e-3 (docs/splines.md)
  EXPECT_NEAR(max_dev, r.history.back().max_distance, 1e-5);  // the library's max agrees with the exact one
}
