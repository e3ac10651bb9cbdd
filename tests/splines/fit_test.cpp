#include "splines/fit.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "base/errors.hpp"
#include "splines/analytic.hpp"
#include "splines/foot_point.hpp"

using namespace sculpt;
using namespace sculpt::splines;
using sculpt::splines::testing::exact_distance;

namespace {

std::vector<Eigen::Vector3d> circle_points(int n, double r = 1.0) {
  std::vector<Eigen::Vector3d> p(n);
  for (int i = 0; i < n; ++i) {
    const double a = 2 * std::numbers::pi * i / n;
    p[i] = {r * std::cos(a), r * std::sin(a), 0};
  }
  return p;
}

BSpline regular_net(int n, double r, int degree = 3) {
  return BSpline::periodic(degree, circle_points(n, r));
}

}  // namespace

TEST(FitCurve, UnitCircleWithEightControlsReachesTheOptimum) {
  const auto data = circle_points(1000);
  const FitResult r = fit_curve(data, {.controls = 8, .closed = true, .start = regular_net(8, 0.7)});
  for (const auto& h : r.history) std::printf("%d %.6e %.6e %.6e %.2e %.3f\n", h.iteration, h.objective, h.rms_distance, h.max_distance, h.smoothing, h.step);
  for (const auto& c : r.curve.controls()) std::printf("  %.6f\n", c.norm());
}
