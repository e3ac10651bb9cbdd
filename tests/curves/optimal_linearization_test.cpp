// The optimal solvers against DYNAMIC (the paper's algorithm) and against brute force.
#include "curves/optimal/optimal_linearization.hpp"

#include <gtest/gtest.h>

#include <random>

#include "curve_testing.hpp"
#include "curves/appendix_b_curves.hpp"
#include "curves/methods/dynamic_programming.hpp"
#include "curves/methods/fast_linearization.hpp"
#include "support/sanitizer_share.hpp"

using namespace sculpt::curves;
using namespace sculpt::curves::detail;  // the internals under test
using Vec = Eigen::Vector3d;

namespace {

// Points scattered at random: segment errors jump around, gaps in achievable segment counts.
std::vector<Vec> scattered(std::mt19937_64& rng, int n, int dimension) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<Vec> p;
  for (int k = 0; k < n; ++k) p.push_back({u(rng), u(rng), dimension == 3 ? u(rng) : 0.0});
  return p;
}

void expect_valid(const Linearization& la, const std::vector<Vec>& points, int m, Norm norm) {
  ASSERT_EQ(la.segments(), m);
  ASSERT_EQ(la.indices.front(), 0);
  ASSERT_EQ(la.indices.back(), static_cast<int>(points.size()) - 1);
  for (std::size_t k = 0; k + 1 < la.indices.size(); ++k) ASSERT_LT(la.indices[k], la.indices[k + 1]);
  ASSERT_EQ(la.error, approximation_error(points, la.indices, norm));
}

}  // namespace

TEST(OptimalMinError, AgreesWithBruteForceAndDynamicOnSmallRandomCurves) {
  std::mt19937_64 rng(2024);
  int cases = 0;
  for (int trial = 0; trial < 240; ++trial) {
    const int n = 3 + trial % 10;  // 3..12 points
    const int dimension = trial % 2 ? 3 : 2;
    const std::vector<Vec> points =
        trial % 3 == 0 ? scattered(rng, n, dimension) : curve_testing::random_curve(rng, n, dimension).points;
    const Norm norm = trial % 4 == 3 ? Norm::L2 : Norm::LInf;
    for (int m = 1; m < n; ++m) {
      const double brute = curve_testing::brute_force_optimum(points, m, norm);
      const Linearization optimal = optimal_min_error(points, m, norm);
      const Linearization dynamic = dynamic_linearization(points, m, norm);
      expect_valid(optimal, points, m, norm);
      expect_valid(dynamic, points, m, norm);
      ASSERT_EQ(optimal.error, brute) << "trial " << trial << " m " << m;
      ASSERT_EQ(dynamic.error, brute) << "trial " << trial << " m " << m;
      ++cases;
    }
  }
  EXPECT_GT(cases, 1000);
}

TEST(OptimalMinError, AgreesWithDynamicOnLargerRandomCurves) {
  std::mt19937_64 rng(99);
  for (int trial = 0; trial < 40; ++trial) {
    const int n = 30 + 7 * trial % 60;
    const int dimension = trial % 2 ? 3 : 2;
    const std::vector<Vec> points =
        trial % 4 == 0 ? scattered(rng, n, dimension) : curve_testing::random_curve(rng, n, dimension).points;
    for (int m : {1, 2, 3, 5, 8, 13, n / 2, n - 2, n - 1}) {
      if (m < 1 || m > n - 1) continue;
      const Linearization optimal = optimal_min_error(points, m, Norm::LInf);
      expect_valid(optimal, points, m, Norm::LInf);
      ASSERT_EQ(optimal.error, dynamic_linearization(points, m, Norm::LInf).error) << trial << " " << m;
    }
  }
}

TEST(OptimalMinError, AgreesWithDynamicOnTheAppendixBCurves) {
  for (AppendixBCurve which : all_appendix_b_curves()) {
    for (double noise : {0.0, 0.01}) {
      const DigitizedCurve curve = make_appendix_b_curve(which, {.points = 120, .noise = noise, .seed = 5});
      const std::vector<Vec> points = path_points(curve);
      for (int m : {2, 4, 8, 16, 32, 64}) {
        const Linearization optimal = optimal_min_error(points, m, Norm::LInf);
        expect_valid(optimal, points, m, Norm::LInf);
        EXPECT_EQ(optimal.error, dynamic_linearization(points, m, Norm::LInf).error)
            << appendix_b_curve_name(which) << " m=" << m << " noise=" << noise;
      }
    }
  }
}

TEST(OptimalMinError, RestrictedVerticesAreOptimalAmongThem) {
  std::mt19937_64 rng(5);
  for (int trial = 0; trial < 30; ++trial) {
    const auto points = curve_testing::random_curve(rng, 11, 3).points;
    const std::vector<int> allowed{0, 2, 3, 5, 8, 9, 10};
    for (int m = 1; m <= 6; ++m) {
      // Brute force over subsets of the allowed interior vertices.
      double best = 1e300;
      const int interior = static_cast<int>(allowed.size()) - 2;
      for (int mask = 0; mask < (1 << interior); ++mask) {
        if (__builtin_popcount(mask) != m - 1) continue;
        std::vector<int> q{0};
        for (int b = 0; b < interior; ++b)
          if (mask & (1 << b)) q.push_back(allowed[b + 1]);
        q.push_back(10);
        best = std::min(best, approximation_error(points, q, Norm::LInf));
      }
      const Linearization la = optimal_min_error(points, m, Norm::LInf, {.vertices = allowed, .start = {}});
      expect_valid(la, points, m, Norm::LInf);
      for (int index : la.indices) EXPECT_TRUE(std::count(allowed.begin(), allowed.end(), index));
      EXPECT_EQ(la.error, best);
    }
  }
}

TEST(OptimalMinCount, AgreesWithBruteForce) {
  std::mt19937_64 rng(11);
  for (int trial = 0; trial < 150; ++trial) {
    const int n = 3 + trial % 9;
    const std::vector<Vec> points =
        trial % 2 ? scattered(rng, n, 3) : curve_testing::random_curve(rng, n, trial % 3 ? 2 : 3).points;
    const Norm norm = trial % 5 == 4 ? Norm::L2 : Norm::LInf;
    for (double tol : {0.0, 0.05, 0.2, 0.5, 1.0, 3.0}) {
      const Linearization la = optimal_min_count(points, tol, norm);
      EXPECT_LE(la.error, tol);
      EXPECT_EQ(la.error, approximation_error(points, la.indices, norm));
      EXPECT_EQ(la.segments(), curve_testing::brute_force_min_count(points, tol, norm)) << trial << " tol " << tol;
    }
  }
}

TEST(OptimalMinCount, AtTheOptimalErrorOfMNeedsAtMostM) {
  std::mt19937_64 rng(12);
  for (int trial = 0; trial < 40; ++trial) {
    const auto points = trial % 2 ? scattered(rng, 25, 2) : curve_testing::random_curve(rng, 40, 3).points;
    const int n = static_cast<int>(points.size());
    for (int m = 1; m < n; m += 3)
      EXPECT_LE(optimal_min_count(points, optimal_min_error(points, m, Norm::LInf).error, Norm::LInf).segments(), m);
  }
}

TEST(FastLinearization, CoarseToFineStaysWithinFivePercentOfOptimum) {
  // Force the coarse-to-fine path (exact_below = 0) on every test curve (the sanitizer build:
  // every other segment count).
  for (AppendixBCurve which : all_appendix_b_curves()) {
    const DigitizedCurve curve = make_appendix_b_curve(which, {.points = 1000});
    const std::vector<Vec> points = path_points(curve);
    for (int m = 4; m <= 64; m *= 2 * sculpt::checks::kSanitizerStride) {
      const Linearization optimal = optimal_min_error(points, m, Norm::LInf);
      const Linearization fast = fast_linearization(points, m, Norm::LInf, {.exact_below = 0});
      expect_valid(fast, points, m, Norm::LInf);
      EXPECT_GE(fast.error, optimal.error);
      EXPECT_LE(fast.error, 1.05 * optimal.error) << appendix_b_curve_name(which) << " m=" << m;
    }
  }
}

TEST(FastLinearization, GreedyCoversWithManySegmentsStayNearOptimum) {
  // m > 64: only the greedy covers and the layered passes run (no coarse optimum).
  for (AppendixBCurve which : {AppendixBCurve::Cubic, AppendixBCurve::Helix, AppendixBCurve::Rose}) {
    const DigitizedCurve curve = make_appendix_b_curve(which, {.points = 12000});
    const std::vector<Vec> points = path_points(curve);
    const Linearization optimal = optimal_min_error(points, 400, Norm::LInf);
    const Linearization fast = fast_linearization(points, 400, Norm::LInf, {.exact_below = 0});
    expect_valid(fast, points, 400, Norm::LInf);
    EXPECT_GE(fast.error, optimal.error);
    EXPECT_LE(fast.error, 1.05 * optimal.error) << appendix_b_curve_name(which);
  }
}

TEST(FastLinearization, NoisyCurvesKeepTheContract) {
  for (AppendixBCurve which : all_appendix_b_curves()) {
    const DigitizedCurve curve = make_appendix_b_curve(which, {.points = 400, .noise = 0.01, .seed = 2});
    const std::vector<Vec> points = path_points(curve);
    for (int m : {3, 50, 200}) {
      const Linearization fast = fast_linearization(points, m, Norm::LInf, {.exact_below = 0});
      expect_valid(fast, points, m, Norm::LInf);
      EXPECT_GE(fast.error, optimal_min_error(points, m, Norm::LInf).error);
    }
  }
}

TEST(OptimalMinCount, AgreesWithDirectDynamicProgrammingOnLongSegments) {
  // Long segments (> 64 points) exercise the slope filter and the tree; the reference is the
  // plain O(n^2) DP over segment_error().
  std::mt19937_64 rng(21);
  std::vector<std::vector<Vec>> curves;
  for (AppendixBCurve which : all_appendix_b_curves()) {
    curves.push_back(path_points(make_appendix_b_curve(which, {.points = 400})));
    curves.push_back(path_points(make_appendix_b_curve(which, {.points = 400, .noise = 0.003, .seed = 4})));
  }
  curves.push_back(curve_testing::random_curve(rng, 400, 2).points);
  curves.push_back(curve_testing::random_curve(rng, 400, 3).points);
  for (std::size_t c = 0; c < curves.size(); c += sculpt::checks::kSanitizerStride) {  // sanitizers: every other
    const std::vector<Vec>& points = curves[c];
    const int n = static_cast<int>(points.size());
    for (double fraction : {0.002, 0.01, 0.05}) {
      Eigen::Vector3d low = points[0], high = points[0];
      for (const auto& p : points) {
        low = low.cwiseMin(p);
        high = high.cwiseMax(p);
      }
      const double tol = fraction * (high - low).norm();
      std::vector<int> dist(n, 1 << 29);
      dist[0] = 0;
      for (int b = 1; b < n; ++b)
        for (int a = 0; a < b; ++a)
          if (dist[a] + 1 < dist[b] && segment_error(points, a, b) <= tol) dist[b] = dist[a] + 1;
      const Linearization la = optimal_min_count(points, tol, Norm::LInf);
      EXPECT_EQ(la.segments(), dist[n - 1]) << "tol " << tol;
      EXPECT_LE(la.error, tol);
    }
  }
}

TEST(OptimalMinError, StreamingModeAgreesWithDynamic) {
  std::mt19937_64 rng(31);
  std::vector<std::vector<Vec>> curves;
  for (AppendixBCurve which : all_appendix_b_curves())
    curves.push_back(path_points(make_appendix_b_curve(which, {.points = 200, .noise = 0.002, .seed = 8})));
  for (int trial = 0; trial < 6; ++trial) {
    curves.push_back(scattered(rng, 60, trial % 2 ? 3 : 2));
    curves.push_back(curve_testing::random_curve(rng, 150, trial % 2 ? 3 : 2).points);
  }
  for (const auto& points : curves)
    for (int m : {1, 3, 7, 20, 45}) {
      if (m >= static_cast<int>(points.size())) continue;
      const Linearization streamed =
          optimal_min_error(points, m, Norm::LInf, {.vertices = {}, .start = {}, .tree = nullptr, .streaming = true});
      expect_valid(streamed, points, m, Norm::LInf);
      EXPECT_EQ(streamed.error, dynamic_linearization(points, m, Norm::LInf).error) << "m=" << m;
    }
}

// The small-input path (rows built under a cap from an estimate, errors below a floor not
// measured, the layered bottleneck DP that ends the search) on the Appendix-B curves at the
// paper's point counts, where symmetric curves give many chord errors equal up to rounding.
TEST(OptimalMinError, AgreesWithDynamicAtThePapersPointCounts) {
  for (AppendixBCurve which : {AppendixBCurve::Cubic, AppendixBCurve::Helix, AppendixBCurve::Folium, AppendixBCurve::Sextic}) {
    const std::vector<Vec> points = path_points(make_appendix_b_curve(which));
    for (int m : {8, 64}) {
      const Linearization optimal = optimal_min_error(points, m, Norm::LInf);
      expect_valid(optimal, points, m, Norm::LInf);
      EXPECT_EQ(optimal.error, dynamic_linearization(points, m, Norm::LInf).error) << appendix_b_curve_name(which) << " m=" << m;
    }
  }
}

// A densely sampled polygon: the optimum is 0 (up to rounding) once the corners can be break points, far
// below the estimate from evenly spaced break points (whose segments cut corners), so the
// search goes below the floor and must measure the chords it had only bounded.
TEST(OptimalMinError, PolygonWithCornersReachesZero) {
  const Vec corners[] = {{0, 0, 0}, {4, 0, 0}, {4, 3, 0}, {1, 5, 0}, {0, 2, 0}};
  std::vector<Vec> points;
  for (int side = 0; side < 4; ++side)
    for (int t = 0; t < 25; ++t) points.push_back(corners[side] + (corners[side + 1] - corners[side]) * (t / 25.0));
  points.push_back(corners[4]);
  const int n = static_cast<int>(points.size());
  for (int m : {3, 4, 5, 9, 20}) {
    const Linearization optimal = optimal_min_error(points, m, Norm::LInf);
    expect_valid(optimal, points, m, Norm::LInf);
    const double dynamic = dynamic_linearization(points, m, Norm::LInf).error;
    EXPECT_EQ(optimal.error, dynamic) << "m=" << m;
    if (m >= 4) {
      EXPECT_LT(optimal.error, 1e-12) << "m=" << m;  // 0 up to the rounding of the samples
    } else {
      EXPECT_GT(optimal.error, 0.1) << "m=" << m;
    }
    EXPECT_LT(m, n);
  }
}

// Many segments per point (rows of one or two chords) and the L2 norm through the same path.
TEST(OptimalMinError, ShortRowsAndL2AgreeWithDynamic) {
  std::mt19937_64 rng(41);
  for (int trial = 0; trial < 12; ++trial) {
    const std::vector<Vec> points = trial % 3 == 0 ? scattered(rng, 40, trial % 2 ? 3 : 2)
                                                   : curve_testing::random_curve(rng, 60, trial % 2 ? 3 : 2).points;
    const int n = static_cast<int>(points.size());
    for (int m : {n / 3, n / 2, n - 3}) {
      for (Norm norm : {Norm::LInf, Norm::L2}) {
        const Linearization optimal = optimal_min_error(points, m, norm);
        expect_valid(optimal, points, m, norm);
        EXPECT_EQ(optimal.error, dynamic_linearization(points, m, norm).error) << "trial " << trial << " m=" << m;
      }
    }
  }
}
