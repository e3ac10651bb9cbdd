// Active surface fitting (fit_surface.hpp): convergence on known surfaces, corners and boundary
// constraints, the start patch, and bad input.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

#include "base/errors.hpp"
#include "splines/fit_surface.hpp"
#include "test_names.hpp"

namespace {

// n x n points of z = f(x, y) over [-1, 1]^2 (the grid includes the four corners).
template <class F>
std::vector<V> height_field(int n, F f) {
  std::vector<V> p;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      const double x = -1 + 2.0 * i / (n - 1), y = -1 + 2.0 * j / (n - 1);
      p.emplace_back(x, y, f(x, y));
    }
  return p;
}

// Exact distance of x to the graph of z = x^2 - y^2 over [-1, 1]^2 is not needed: the saddle is a
// biquadratic, so an 8 x 8 bicubic represents it exactly and the optimum of the fit is 0.
std::vector<V> saddle_points(int n) { return height_field(n, [](double x, double y) { return 0.5 * (x * x - y * y); }); }

// A spherical cap of radius 2 over [-1, 1]^2 (not polynomial).
std::vector<V> sphere_points(int n) {
  return height_field(n, [](double x, double y) { return std::sqrt(4 - x * x - y * y); });
}

TEST(FitSurface, CornerPointsOfAGridAreItsCorners) {
  const auto c = corner_points(saddle_points(11));
  // Order S(0,0), S(1,0), S(0,1), S(1,1) up to the orientation of the principal axes: the four
  // corners of [-1, 1]^2 each once, with S(0,0) and S(1,1) opposite.
  for (const V& p : c) EXPECT_NEAR(std::abs(p.x()) + std::abs(p.y()), 2.0, 1e-15);
  EXPECT_NEAR((c[0] - c[3]).head<2>().norm(), std::sqrt(8.0), 1e-15);
  EXPECT_NEAR((c[1] - c[2]).head<2>().norm(), std::sqrt(8.0), 1e-15);
}

TEST(FitSurface, SaddleConvergesAndKeepsItsCornersExactly) {
  const auto data = saddle_points(30);
  const FitSurfaceResult r = fit_surface(data, {.iterations = 30});
  ASSERT_GE(r.history.size(), 2u);
  // SDM halves steps that would grow the objective: the history never rises.
  for (std::size_t k = 1; k < r.history.size(); ++k) EXPECT_LE(r.history[k].objective, r.history[k - 1].objective) << k;
  // The bilinear start is a plane at distance up to 0.5; the saddle is exactly representable.
  EXPECT_GT(r.history[0].max_distance, 0.2);
  EXPECT_LT(r.history.back().max_distance, 1e-4);
  // Independent check of the final error by exact foot points.
  EXPECT_LT(distance(r.surface, data).max, 1e-4);
  // The corners are the data's corners, bit for bit.
  const auto c = corner_points(data);
  const BSplineSurface& s = r.surface;
  EXPECT_EQ(s.point(0, 0), c[0]);
  EXPECT_EQ(s.point(1, 0), c[1]);
  EXPECT_EQ(s.point(0, 1), c[2]);
  EXPECT_EQ(s.point(1, 1), c[3]);
}

TEST(FitSurface, SphereCapWithinSevenSteps) {
  const auto data = sphere_points(40);
  const FitSurfaceResult r = fit_surface(data, {.iterations = 7});
  EXPECT_LE(r.iterations, 7);
  // OpenCascade's GeomAPI_PointsToBSplineSurface with 8 x 8 poles on the same 40 x 40 grid is at
  // max 1.41e-5 (tests/bench/splines/peers.sh, measured by the same exact foot points).
  EXPECT_LT(r.history.back().max_distance, 1.4e-5);
  EXPECT_LT(r.history.back().max_distance, 1e-3 * r.history[0].max_distance);
  // The history's figures (warm-started foot points) agree with a fresh global search.
  const DistanceSummary d = distance(r.surface, data);
  EXPECT_NEAR(r.history.back().max_distance, d.max, 1e-12);
  EXPECT_NEAR(r.history.back().rms_distance, d.rms, 1e-12);
}

TEST(FitSurface, SquaredDistanceModelBeatsPointDistanceAtTheSameStepCount) {
  const auto data = sphere_points(30);
  const FitSurfaceResult sdm = fit_surface(data, {.method = Method::SDM, .iterations = 5, .tolerance = 0});
  const FitSurfaceResult pdm = fit_surface(data, {.method = Method::PDM, .iterations = 5, .tolerance = 0});
  EXPECT_LT(sdm.history.back().rms_distance, pdm.history.back().rms_distance);
}

TEST(FitSurface, ScatteredNoisyPointsRecoverTheSurface) {
  // 3000 random points of the saddle z = (x^2 - y^2) / 2 with vertical noise sigma = 1e-3: the fit's
  // rms distance is at the noise level and the true surface (inner 90 %) lies within 1e-3 of it.
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> U(-1, 1);
  std::normal_distribution<double> noise(0, 1e-3);
  std::vector<V> data;
  for (int k = 0; k < 3000; ++k) {
    const double x = U(rng), y = U(rng);
    data.emplace_back(x, y, 0.5 * (x * x - y * y) + noise(rng));
  }
  const FitSurfaceResult r = fit_surface(data, {.iterations = 10});
  EXPECT_LT(r.history.back().rms_distance, 1.2e-3);
  EXPECT_GT(r.history.back().rms_distance, 0.5e-3);  // not fitting the noise away
  double worst = 0;
  for (int i = 0; i <= 10; ++i)
    for (int j = 0; j <= 10; ++j) {
      const double x = -0.9 + 0.18 * i, y = -0.9 + 0.18 * j;
      worst = std::max(worst, closest_point(r.surface, V(x, y, 0.5 * (x * x - y * y))).distance);
    }
  EXPECT_LT(worst, 1e-3);
}

TEST(FitSurface, FixedBoundaryKeepsEveryBoundaryControl) {
  const auto data = sphere_points(20);
  const FitSurfaceResult r = fit_surface(data, {.controls = {6, 5}, .iterations = 3, .fix_boundary = true});
  const BSplineSurface start = bilinear_patch(corner_points(data), {6, 5});
  for (int i = 0; i < 6; ++i)
    for (int j = 0; j < 5; ++j) {
      const bool boundary = i == 0 || i == 5 || j == 0 || j == 4;
      if (boundary)
        EXPECT_EQ(r.surface.control(i, j), start.control(i, j));
      else
        EXPECT_NE(r.surface.control(i, j), start.control(i, j));
    }
}

TEST(FitSurface, ClosedSurfaceFromAStartSurface) {
  // Points on a torus (R = 3, r = 1); start: the same periodic grid on a torus of tube radius 1.5.
  std::vector<V> data;
  for (int i = 0; i < 60; ++i)
    for (int j = 0; j < 30; ++j) {
      const double a = 2 * kPi * (i + 0.5 * (j % 2)) / 60, b = 2 * kPi * j / 30;
      data.emplace_back((3 + std::cos(b)) * std::cos(a), (3 + std::cos(b)) * std::sin(a), std::sin(b));
    }
  std::vector<V> P;
  for (int i = 0; i < 10; ++i)
    for (int j = 0; j < 8; ++j) {
      const double a = 2 * kPi * i / 10, b = 2 * kPi * j / 8;
      P.emplace_back((3 + 1.5 * std::cos(b)) * std::cos(a), (3 + 1.5 * std::cos(b)) * std::sin(a), 1.5 * std::sin(b));
    }
  const BSplineSurface start = BSplineSurface::uniform({3, 3}, 10, 8, P, {true, true});
  const FitSurfaceResult r = fit_surface(data, {.iterations = 15, .start = start});
  EXPECT_GT(r.history[0].rms_distance, 0.3);
  // A 10 x 8 periodic bicubic is not a torus; it gets within a few thousandths.
  EXPECT_LT(r.history.back().max_distance, 1e-2);
}

TEST(FitSurface, BadInputIsRefused) {
  const auto data = saddle_points(5);  // 25 points
  EXPECT_THROW((void)fit_surface(data, {.controls = {6, 6}}), InvalidInput);
  EXPECT_THROW((void)fit_surface(data, {.controls = {3, 3}}), InvalidInput);  // cubic needs 4
  EXPECT_THROW((void)fit_surface(data, {.controls = {4, 4}, .fixed = {16}}), InvalidInput);
  auto bad = data;
  bad[3].y() = std::numeric_limits<double>::infinity();
  EXPECT_THROW((void)fit_surface(bad, {.controls = {4, 4}}), InvalidInput);
  EXPECT_THROW((void)corner_points({V::Zero(), V::Zero(), V::Zero()}), InvalidInput);
  // Coincident points do not crash (the fit stays at the degenerate start).
  EXPECT_NO_THROW((void)fit_surface(std::vector<V>(30, V(1, 2, 3)), {.controls = {4, 4}, .iterations = 2}));
}

}  // namespace
