#pragma once
/// \file point_classifier.hpp
/// Fast point classification for statistics (Ihm & Naylor 1990, sec. 6: a point descends the tree
/// by the side of each node's plane; the cost is the depth of the leaf reached). The tree is
/// flattened into one array of double-precision planes in world units: no allocation per query.
/// Unlike bsp/classify.hpp it is not exact: a point within about 1e-12 world units of a plane may
/// take either side (it never reports "boundary"), which does not matter for sampling.

#include <cstdint>
#include <span>
#include <vector>

#include <Eigen/Core>

#include "bsp/solid.hpp"

namespace sculpt::reports {

struct PointResult {
  bool inside;
  int depth;  ///< partitioning nodes visited
};

class PointClassifier {
 public:
  explicit PointClassifier(const Solid& solid);

  /// The leaf reached by p (world units): in or out, and its depth. Points on a plane go negative.
  [[nodiscard]] PointResult classify(const Eigen::Vector3d& p) const {
    std::int32_t k = root_;
    int depth = 0;
    while (k >= 0) {  // the side indexes the child: no branch to mispredict
      const FlatNode& n = nodes_[static_cast<std::size_t>(k)];
      k = n.child[n.a * p.x() + n.b * p.y() + n.c * p.z() + n.d > 0.0];
      ++depth;
    }
    return {k == kIn, depth};
  }

  /// Classifies many points: eight walks interleaved, so the processor overlaps their memory
  /// and arithmetic latencies (the walks are independent chains of dependent loads).
  /// \pre out.size() == points.size()
  void classify(std::span<const Eigen::Vector3d> points, std::span<PointResult> out) const;

  /// One flattened node: plane a x + b y + c z + d (world units, normal of unit length).
  struct FlatNode {
    double a, b, c, d;
    std::int32_t child[2];  ///< negative side, positive side (node index, kIn or kOut)
  };
  [[nodiscard]] const std::vector<FlatNode>& nodes() const { return nodes_; }
  [[nodiscard]] std::int32_t root() const { return root_; }

 private:
  std::vector<FlatNode> nodes_;
  std::int32_t root_;
};

}  // namespace sculpt::reports
