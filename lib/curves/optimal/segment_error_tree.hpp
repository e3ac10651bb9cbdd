#pragma once
/// \file segment_error_tree.hpp
/// Fast exact segment-error queries for the optimal solvers: a binary tree of capsules over the
/// point sequence. A node covering points [b, e) stores the largest distance r of its points to
/// the segment p_b p_{e-1}. Distance to a line is 1-Lipschitz and convex along a segment, so the
/// node's points lie within [min over the segment - r, max(d(p_b), d(p_{e-1})) + r]; for sampled
/// smooth curves r is the tiny sagitta, so only nodes straddling the threshold are opened.
/// Leaves are measured with ChordDistance, so every answer equals the brute-force
/// segment_error() bit for bit (internal bounds carry a safety slack, they never decide a
/// borderline point). Under Norm::L2 the queries fall back to exact brute-force sums.

#include <Eigen/Core>
#include <limits>
#include <vector>

#include "curves/segment_error.hpp"

namespace sculpt::curves::detail {

/// Result of SegmentErrorTree::test.
struct WithinTest {
  bool within;   ///< segment_error(points, i, j, norm) <= eps
  int violator;  ///< if not within: an index whose distance exceeds eps (L-inf), else -1
};

class SegmentErrorTree {
 public:
  SegmentErrorTree(const std::vector<Eigen::Vector3d>& points, Norm norm);

  /// Is segment_error(points, i, j, norm) <= eps, and if not, which point shows it? `hint` is an
  /// index to try first (e.g. the violator found for a neighbouring chord).
  [[nodiscard]] WithinTest test(int i, int j, double eps, int hint = -1) const;
  /// test(i, j, eps, hint).within.
  [[nodiscard]] bool within(int i, int j, double eps, int hint = -1) const { return test(i, j, eps, hint).within; }

  /// segment_error(points, i, j, norm), exactly, if it is <= limit; otherwise some value > limit
  /// (the search stops at the first point beyond the limit).
  [[nodiscard]] double error(int i, int j, double limit = std::numeric_limits<double>::infinity()) const;

  [[nodiscard]] const std::vector<Eigen::Vector3d>& points() const { return points_; }
  [[nodiscard]] Norm norm() const { return norm_; }
  [[nodiscard]] int size() const { return static_cast<int>(points_.size()); }

 private:
  struct Node {
    double radius;      // max distance of the node's points to segment p_begin p_{end-1}
    int begin, end;     // point range [begin, end)
    int left, right;    // child nodes, -1 for a leaf
  };
  static constexpr int kLeafSize = 8;
  const std::vector<Eigen::Vector3d>& points_;
  Norm norm_;
  std::vector<Node> nodes_;  // nodes_[0] is the root
};

}  // namespace sculpt::curves::detail
