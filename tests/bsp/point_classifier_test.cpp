#include "bsp/point_classifier.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

#include "base/errors.hpp"
#include "bsp/primitives.hpp"
#include "bsp/set_operations.hpp"
#include "bsp/transform.hpp"

namespace sculpt {
namespace {

// The reference is classify(solid, p): a plain walk with exact integer sides (bsp/classify.cpp).
// Each point is checked one at a time and in batches (whose size is not a multiple of the lanes).
struct Tally {
  int inside = 0, outside = 0, boundary = 0;
};
Tally expect_same_as_classify(const Solid& s, const std::vector<Eigen::Vector3d>& points) {
  const PointClassifier fast(s);
  std::vector<Classification> batch(points.size());
  fast.classify(points, batch);
  Tally t;
  for (std::size_t i = 0; i < points.size(); ++i) {
    const Classification want = classify(s, points[i]);
    const Classification one = fast.classify(points[i]);
    EXPECT_EQ(one.location, want.location) << points[i].transpose();
    EXPECT_EQ(one.path_length, want.path_length) << points[i].transpose();
    EXPECT_EQ(batch[i].location, want.location) << points[i].transpose();
    EXPECT_EQ(batch[i].path_length, want.path_length) << points[i].transpose();
    (want.location == Location::Inside ? t.inside : want.location == Location::Outside ? t.outside : t.boundary)++;
  }
  return t;
}

std::vector<Eigen::Vector3d> lattice(double lo, double hi, double step) {
  std::vector<Eigen::Vector3d> out;
  for (double x = lo; x <= hi; x += step)
    for (double y = lo; y <= hi; y += step)
      for (double z = lo; z <= hi; z += step) out.emplace_back(x, y, z);
  return out;
}

TEST(PointClassifier, AgreesOnALatticeThroughFacesEdgesAndCornersOfTouchingBoxes) {
  // Coplanar faces, a shared face and a shared edge: many lattice points lie on planes, so the
  // floating-point filter must hand them to the exact evaluation.
  const Solid s = (box({0, 0, 0}, {1, 1, 1}) | box({1, 0, 0}, {2, 1, 1}) | box({2, 1, 0}, {3, 2, 1})) -
                  box({0.25, 0.25, 0.25}, {0.75, 0.75, 2});
  const Tally t = expect_same_as_classify(s, lattice(-0.5, 3.5, 0.125));
  EXPECT_GT(t.inside, 100);
  EXPECT_GT(t.outside, 100);
  EXPECT_GT(t.boundary, 100);
}

TEST(PointClassifier, AgreesOnRotatedAndScaledSolidsWithLargePlaneCoefficients) {
  // Rotations give planes with large integer coefficients: the filter's bound is widest there.
  const Solid a = rotate(sphere(1.0, {.segments = 48}), {1, 2, 3}, 37.0);
  const Solid b = rotate(box({0, 0, 0}, {1.5, 1.5, 1.5}), {0, 0, 1}, 45.0);
  const Solid s = a - b;
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> u(-1.6, 1.6);
  std::vector<Eigen::Vector3d> points(20001);
  for (auto& p : points) p = {u(rng), u(rng), u(rng)};
  for (const auto& p : lattice(-1.5, 1.5, 0.25)) points.push_back(p);
  const Tally t = expect_same_as_classify(s, points);
  EXPECT_GT(t.inside, 1000);
  EXPECT_GT(t.outside, 1000);
  // The rotated box's vertical edge through the origin holds lattice points (0, 0, z).
  EXPECT_GT(t.boundary, 0);
}

TEST(PointClassifier, SnapsHalfwayCoordinatesAwayFromZeroLikeTheKernel) {
  // Faces on odd grid coordinates (+-32767 steps) and coordinates exactly halfway between grid
  // points: kernel::snap rounds them away from zero (ties to even would differ at 32766.5).
  const double step = 1.0 / 32768, h = 0.5 * step, f = 1 - step;
  const Solid s = box({-f, -f, -f}, {f, f, f});
  std::vector<Eigen::Vector3d> points;
  for (const double x : {f - h, f + h, -f + h, -f - h, h, -h, 3 * h, -3 * h})
    for (const double y : {0.0, f - h, -f + h}) points.emplace_back(x, y, 0.25);
  const Tally t = expect_same_as_classify(s, points);
  EXPECT_GT(t.boundary, 8);
  EXPECT_EQ(PointClassifier(s).classify({f - h, 0, 0}).location, Location::Boundary);
  EXPECT_EQ(PointClassifier(s).classify({-f + h, 0, 0}).location, Location::Boundary);
}

TEST(PointClassifier, LeafSolids) {
  const std::vector<Eigen::Vector3d> points = {{0, 0, 0}, {1, 2, 3}, {-1000, 1000, 0.5}};
  for (const bool inside : {false, true}) {
    const PointClassifier c(Solid::leaf(inside));
    for (const auto& p : points) {
      EXPECT_EQ(c.classify(p).location, inside ? Location::Inside : Location::Outside);
      EXPECT_EQ(c.classify(p).path_length, 0);
    }
  }
}

TEST(PointClassifier, OutOfRangeAndNonFinitePointsThrowRangeError) {
  const PointClassifier c(box({0, 0, 0}, {1, 1, 1}));
  const double nan = std::numeric_limits<double>::quiet_NaN();
  for (const Eigen::Vector3d& p : {Eigen::Vector3d(2000, 0, 0), Eigen::Vector3d(0, nan, 0),
                                  Eigen::Vector3d(0, 0, -std::numeric_limits<double>::infinity())}) {
    EXPECT_THROW((void)c.classify(p), RangeError);
    std::vector<Eigen::Vector3d> batch(9, Eigen::Vector3d(0.5, 0.5, 0.5));
    batch[3] = p;
    std::vector<Classification> out(batch.size());
    EXPECT_THROW(c.classify(batch, out), RangeError);
  }
  // The range itself is inclusive, as in kernel::snap.
  EXPECT_EQ(c.classify({1024, 0, 0}).location, Location::Outside);
}

}  // namespace
}  // namespace sculpt
