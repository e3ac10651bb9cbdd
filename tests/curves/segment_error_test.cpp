#include "curves/segment_error.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "curve_testing.hpp"
#include "curves/optimal/segment_error_tree.hpp"

using namespace sculpt::curves;
using namespace sculpt::curves::detail;  // the internals under test
using Vec = Eigen::Vector3d;

TEST(SegmentError, DistanceToInfiniteLineNotToSegment) {
  // The point (3, 1) lies beyond the chord's end: Definition 2.3 measures to the line, so 1.
  const std::vector<Vec> p{{0, 0, 0}, {3, 1, 0}, {1, 0, 0}};
  EXPECT_DOUBLE_EQ(segment_error(p, 0, 2), 1.0);
}

TEST(SegmentError, AnalyticThreeDimensionalDistance) {
  const std::vector<Vec> p{{0, 0, 0}, {1, 2, 2}, {5, 0, 0}, {2, 0, 0}};
  EXPECT_DOUBLE_EQ(segment_error(p, 0, 3), std::sqrt(8.0));  // line is the x axis
  EXPECT_DOUBLE_EQ(segment_error(p, 0, 3, Norm::L2), std::sqrt(8.0));
}

TEST(SegmentError, DegenerateChordMeasuresDistanceToThePoint) {
  const std::vector<Vec> p{{1, 1, 1}, {1, 4, 5}, {1, 1, 2}, {1, 1, 1}};
  EXPECT_DOUBLE_EQ(segment_error(p, 0, 3), 5.0);
  EXPECT_DOUBLE_EQ(segment_error(p, 0, 3, Norm::L2), std::sqrt(26.0));
}

TEST(SegmentError, NeighbouringPointsHaveZeroError) {
  const std::vector<Vec> p{{0, 0, 0}, {1, 5, 0}};
  EXPECT_EQ(segment_error(p, 0, 1), 0.0);
  EXPECT_EQ(segment_error(p, 0, 1, Norm::L2), 0.0);
}

TEST(SegmentError, L2SumsSquares) {
  const std::vector<Vec> p{{0, 0, 0}, {1, 3, 0}, {2, -4, 0}, {3, 0, 0}};
  EXPECT_DOUBLE_EQ(segment_error(p, 0, 3, Norm::L2), 5.0);
  EXPECT_DOUBLE_EQ(segment_error(p, 0, 3, Norm::LInf), 4.0);
}

TEST(SegmentError, ApproximationErrorIsMaxOverSegments) {
  const std::vector<Vec> p{{0, 0, 0}, {1, 1, 0}, {2, 0, 0}, {3, 3, 0}, {4, 0, 0}};
  EXPECT_DOUBLE_EQ(approximation_error(p, {0, 2, 4}), 3.0);
  EXPECT_DOUBLE_EQ(approximation_error(p, {0, 1, 2, 3, 4}), 0.0);
}

TEST(SegmentErrorTree, ExactlyMatchesBruteForceOnRandomCurves) {
  std::mt19937_64 rng(7);
  for (int trial = 0; trial < 20; ++trial) {
    const auto curve = curve_testing::random_curve(rng, 200, trial % 2 ? 3 : 2);
    const SegmentErrorTree tree(curve.points, Norm::LInf);
    std::uniform_int_distribution<int> pick(0, 199);
    for (int q = 0; q < 300; ++q) {
      int i = pick(rng), j = pick(rng);
      if (i == j) continue;
      if (i > j) std::swap(i, j);
      const double exact = segment_error(curve.points, i, j);
      ASSERT_EQ(tree.error(i, j), exact);  // bit-identical
      // Thresholds right at, just below and just above the exact value.
      EXPECT_TRUE(tree.within(i, j, exact));
      if (exact > 0) {
        EXPECT_FALSE(tree.within(i, j, std::nextafter(exact, 0.0)));
      }
      EXPECT_TRUE(tree.within(i, j, std::nextafter(exact, 1e300)));
      const double eps = exact * (0.5 + 0.1 * (q % 10));
      EXPECT_EQ(tree.within(i, j, eps), exact <= eps);
    }
  }
}

TEST(SegmentErrorTree, L2FallsBackToExactSums) {
  std::mt19937_64 rng(3);
  const auto curve = curve_testing::random_curve(rng, 60, 3);
  const SegmentErrorTree tree(curve.points, Norm::L2);
  for (int i = 0; i < 60; i += 7)
    for (int j = i + 1; j < 60; j += 5) {
      const double exact = segment_error(curve.points, i, j, Norm::L2);
      EXPECT_EQ(tree.error(i, j), exact);
      EXPECT_TRUE(tree.within(i, j, exact));
      if (exact > 0) {
        EXPECT_FALSE(tree.within(i, j, std::nextafter(exact, 0.0)));
      }
    }
}
