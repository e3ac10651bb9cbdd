#include "bsp/classify.hpp"

#include <gtest/gtest.h>

#include <random>

#include "bsp/primitives.hpp"
#include "bsp/set_operations.hpp"

namespace sculpt {
namespace {

TEST(Classify, BoxInsideOutsideAndEveryKindOfBoundaryPoint) {
  const Solid b = box({0, 0, 0}, {1, 1, 1});
  EXPECT_EQ(classify(b, {0.5, 0.5, 0.5}).location, Location::Inside);
  EXPECT_EQ(classify(b, {1.5, 0.5, 0.5}).location, Location::Outside);
  EXPECT_EQ(classify(b, {1, 0.5, 0.5}).location, Location::Boundary);  // face
  EXPECT_EQ(classify(b, {1, 1, 0.5}).location, Location::Boundary);    // edge
  EXPECT_EQ(classify(b, {1, 1, 1}).location, Location::Boundary);      // corner
  EXPECT_EQ(classify(b, {1 + 1.0 / 32768, 1, 1}).location, Location::Outside);  // one grid step off
  const Classification c = classify(b, {0.5, 0.5, 0.5});
  EXPECT_GE(c.path_length, 1);
  EXPECT_LE(c.path_length, tree_stats(b).height);
}

TEST(Classify, UnionInteriorFaceIsInsideNotBoundary) {
  const Solid u = box({0, 0, 0}, {1, 1, 1}) | box({1, 0, 0}, {2, 1, 1});
  EXPECT_EQ(classify(u, {1, 0.5, 0.5}).location, Location::Inside);
  EXPECT_EQ(classify(u, {2, 0.5, 0.5}).location, Location::Boundary);
}

// Independent reference: a point is in the sphere polytope iff it is below every face plane;
// compare with a brute-force test on the implicit sphere for points well away from the surface.
TEST(Classify, SphereAgreesWithTheBallAwayFromTheSurfaceAndPathIsShort) {
  const int n = 64;
  const Solid s = sphere(1.0, {.segments = n});
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> d(-1.3, 1.3);
  const double margin = 1.0 - std::cos(3.14159265358979 / n) * std::cos(3.14159265358979 / n) + 0.01;
  int total_path = 0, count = 0;
  for (int i = 0; i < 2000; ++i) {
    const Eigen::Vector3d p(d(rng), d(rng), d(rng));
    const double r = p.norm();
    if (std::fabs(r - 1.0) < margin + 0.02) continue;
    const Classification c = classify(s, p);
    EXPECT_EQ(c.location, r < 1 ? Location::Inside : Location::Outside) << p.transpose();
    total_path += c.path_length;
    ++count;
  }
  // Balanced tree: mean path far below the face count (Ihm & Naylor sec. 6).
  EXPECT_LT(double(total_path) / count, 3.0 * std::log2(double(n * n)));
}

}  // namespace
}  // namespace sculpt
