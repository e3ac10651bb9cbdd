#include "revolution/trees/path_tree.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <numbers>
#include <random>

#include "base/errors.hpp"

using namespace sculpt;
using namespace sculpt::revolution;
using namespace sculpt::revolution::detail;

namespace {

/// Brute force: inside every edge's left halfplane.
bool inside(const ConvexPath& p, const Eigen::Vector2d& q) {
  for (int i = 0; i < p.edges(); ++i) {
    const auto& a = p.vertices[i];
    const auto& b = p.vertices[(i + 1) % p.edges()];
    if ((b - a).x() * (q - a).y() - (b - a).y() * (q - a).x() < 0) return false;
  }
  return true;
}

/// A random strictly convex polygon: sorted random angles on an ellipse (rotated).
ConvexPath random_convex(int n, std::mt19937_64& rng) {
  std::uniform_real_distribution<double> U(0, 1);
  std::vector<double> t;
  for (int i = 0; i < n; ++i) t.push_back(2 * std::numbers::pi * U(rng));
  std::sort(t.begin(), t.end());
  const double a = 0.5 + U(rng), b = 0.5 + U(rng), phi = U(rng) * 3, cx = U(rng) - 0.5, cy = U(rng) - 0.5;
  std::vector<Eigen::Vector2d> v;
  for (double s : t) {
    const Eigen::Vector2d e(a * std::cos(s), b * std::sin(s));
    v.emplace_back(cx + std::cos(phi) * e.x() - std::sin(phi) * e.y(), cy + std::sin(phi) * e.x() + std::cos(phi) * e.y());
  }
  return polygon_path(v);
}

void check_classification(const ConvexPath& path, const PathTree& tree, std::mt19937_64& rng, int samples) {
  std::uniform_real_distribution<double> U(-2, 2);
  for (int i = 0; i < samples; ++i) {
    const Eigen::Vector2d q(U(rng), U(rng));
    ASSERT_EQ(tree.classify(path, q) == kIn, inside(path, q)) << "n = " << path.edges() << " q = " << q.transpose();
  }
  Eigen::Vector2d centre = Eigen::Vector2d::Zero();
  for (const auto& v : path.vertices) centre += v / path.edges();
  for (const auto& v : path.vertices) {  // near each vertex, just inside and just outside
    ASSERT_EQ(tree.classify(path, centre + 0.999 * (v - centre)), kIn);
    ASSERT_EQ(tree.classify(path, centre + 1.001 * (v - centre)), kOut);
  }
}

}  // namespace

TEST(PathTree, ClassifiesLikeTheConvexPolygon) {
  std::mt19937_64 rng(42);
  for (int n : {3, 4, 5, 6, 7, 8, 13, 16, 31, 32, 33, 64, 100, 257})
    check_classification(circular_path(n), build_path_tree(circular_path(n)), rng, 20000);
  for (int trial = 0; trial < 60; ++trial) {
    const ConvexPath p = random_convex(3 + trial * 3, rng);
    check_classification(p, build_path_tree(p), rng, 5000);
    check_classification(p, build_path_tree(p, {.face_only_below = 2}), rng, 2000);
  }
}

TEST(PathTree, EveryEdgeIsAFaceExactlyOnce) {
  std::mt19937_64 rng(7);
  for (int n : {3, 4, 9, 32, 77, 500}) {
    const ConvexPath p = n % 2 ? random_convex(n, rng) : circular_path(n);
    const PathTree t = build_path_tree(p);
    std::map<int, int> faces;
    for (const auto& node : t.nodes)
      if (node.kind == PathTree::Kind::Face) {
        EXPECT_EQ(node.to, (node.from + 1) % n);
        faces[node.from]++;
      } else {
        EXPECT_NE(node.to, (node.from + 1) % n) << "a chord joining neighbours is a face";
      }
    EXPECT_EQ(static_cast<int>(faces.size()), n);
    for (const auto& [edge, count] : faces) EXPECT_EQ(count, 1) << "edge " << edge;
  }
}

// Section 6: "a nearly balanced tree of size < 3n and height O(log n)". Counting partitioning
// nodes only, the size is about 1.4 n; counting leaves too (I + 1 of them) it is still below 3n from
// n = 10 on (for 7 <= n <= 9 the four quadrant chords make it 3n + 1 or so).
TEST(PathTree, SizeBelowThreeNAndLogarithmicHeight) {
  std::mt19937_64 rng(9);
  for (int n = 3; n <= 2100; n += (n < 100 ? 1 : 97)) {
    for (const ConvexPath& p : {circular_path(n), random_convex(n, rng)}) {
      const PathTree t = build_path_tree(p);
      const int partitioning = static_cast<int>(t.nodes.size());
      EXPECT_LT(partitioning, 1.5 * n + 4) << "n = " << n;
      if (n >= 10) {
        EXPECT_LT(2 * partitioning + 1, 3 * n) << "n = " << n;
      }
      // Each halving of a sub-curve costs at most three levels (median face, two chords).
      EXPECT_LE(t.height(), 3.0 * std::log2(n) + 4) << "n = " << n;
    }
  }
}

TEST(PathTree, FaceOnlyThresholdTradesSizeForHeight) {
  const ConvexPath p = circular_path(256);
  const PathTree faces_only = build_path_tree(p, {.face_only_below = 1000});
  const PathTree balanced = build_path_tree(p, {.face_only_below = 2});
  EXPECT_EQ(faces_only.nodes.size(), 4u + 256u);  // the four quadrant chords, then every face
  EXPECT_LT(balanced.height(), faces_only.height() / 3);
  EXPECT_THROW(build_path_tree(p, {.face_only_below = 1}), InvalidInput);
}
