#include "curves/optimal/segment_error_tree.hpp"

#include <algorithm>
#include <cmath>

#include "curves/optimal/tolerances.hpp"

namespace sculpt::curves::detail {

namespace {

double distance_to_segment(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  const Eigen::Vector3d d = b - a;
  const double length2 = d.squaredNorm();
  double t = length2 > 0.0 ? (p - a).dot(d) / length2 : 0.0;
  t = std::clamp(t, 0.0, 1.0);
  return (p - (a + t * d)).norm();
}

// Bounds of the distance to the query line over all points of a node: [low, high].
struct Bounds {
  double low, high;
};

}  // namespace

SegmentErrorTree::SegmentErrorTree(const std::vector<Eigen::Vector3d>& points, Norm norm)
    : points_(points), norm_(norm) {
  const int n = static_cast<int>(points.size());
  if (n == 0 || norm == Norm::L2) return;
  nodes_.reserve(2 * (n / kLeafSize + 1) + 1);
  nodes_.push_back({0.0, 0, n, -1, -1});
  std::vector<int> pending{0};  // explicit stack of nodes to split
  while (!pending.empty()) {
    const int k = pending.back();
    pending.pop_back();
    const int begin = nodes_[k].begin, end = nodes_[k].end;
    double radius = 0.0;
    for (int q = begin + 1; q < end - 1; ++q)
      radius = std::max(radius, distance_to_segment(points[q], points[begin], points[end - 1]));
    nodes_[k].radius = radius * (1.0 + kRelativeMargin);
    if (end - begin > kLeafSize) {
      const int mid = begin + (end - begin) / 2;
      const int left = static_cast<int>(nodes_.size());
      nodes_.push_back({0.0, begin, mid, -1, -1});
      nodes_.push_back({0.0, mid, end, -1, -1});
      nodes_[k].left = left;
      nodes_[k].right = left + 1;
      pending.push_back(left);
      pending.push_back(left + 1);
    }
  }
}

namespace {

// Distance bounds of a node's points to the query line (or point, for a degenerate chord).
// u(t) = component of (x(t) - a) orthogonal to the chord, linear along the node's segment.
template <class Node>
Bounds node_bounds(const Node& node, const std::vector<Eigen::Vector3d>& points, const ChordDistance& distance,
                   const Eigen::Vector3d& direction, double inverse_length2) {
  const Eigen::Vector3d& e0 = points[node.begin];
  const Eigen::Vector3d& e1 = points[node.end - 1];
  const Eigen::Vector3d w0 = e0 - distance.origin(), w1 = e1 - distance.origin();
  const Eigen::Vector3d u0 = w0 - direction * (w0.dot(direction) * inverse_length2);
  const Eigen::Vector3d u1 = w1 - direction * (w1.dot(direction) * inverse_length2);
  const Eigen::Vector3d du = u1 - u0;
  const double du2 = du.squaredNorm();
  const double t = du2 > 0.0 ? std::clamp(-u0.dot(du) / du2, 0.0, 1.0) : 0.0;
  const double nearest = (u0 + t * du).norm();
  const double farthest = std::max(u0.norm(), u1.norm());
  // Margin far above the rounding of these few operations relative to the coordinates involved.
  const double margin = kRelativeMargin * (w0.norm() + w1.norm() + node.radius) + kUnderflowMargin;
  return {nearest - node.radius - margin, farthest + node.radius + margin};
}

}  // namespace

WithinTest SegmentErrorTree::test(int i, int j, double eps, int hint) const {
  if (j - i < 2) return {0.0 <= eps, -1};
  const ChordDistance distance(points_[i], points_[j]);
  if (norm_ == Norm::L2) {
    double sum = 0.0;
    for (int k = i + 1; k < j; ++k) {
      const double d = distance(points_[k]);
      sum += d * d;
      if (((k - i) & 15) == 0 && std::sqrt(sum) > eps) return {false, -1};  // partial sums only grow
    }
    return {std::sqrt(sum) <= eps, -1};
  }
  if (hint > i && hint < j && distance(points_[hint]) > eps) return {false, hint};
  const int middle = i + (j - i) / 2;  // often the farthest
  if (distance(points_[middle]) > eps) return {false, middle};
  const Eigen::Vector3d direction = points_[j] - points_[i];
  const double length2 = direction.squaredNorm();
  const double inverse_length2 = length2 > 0.0 ? 1.0 / length2 : 0.0;
  const int lo = i + 1, hi = j - 1;  // interior points, inclusive
  int stack[128];
  int top = 0;
  stack[top++] = 0;
  while (top > 0) {
    const Node& node = nodes_[stack[--top]];
    if (node.end <= lo || node.begin > hi) continue;
    const Bounds bounds = node_bounds(node, points_, distance, direction, inverse_length2);
    if (bounds.high <= eps) continue;  // every point of the node is within
    const bool inside = node.begin >= lo && node.end - 1 <= hi;
    if (inside && bounds.low > eps) return {false, node.begin};  // every point of the node violates
    if (node.left < 0) {
      const int from = std::max(node.begin, lo), to = std::min(node.end - 1, hi);
      for (int k = from; k <= to; ++k)
        if (distance(points_[k]) > eps) return {false, k};
      continue;
    }
    stack[top++] = node.right;
    stack[top++] = node.left;
  }
  return {true, -1};
}

double SegmentErrorTree::error(int i, int j, double limit) const {
  if (norm_ == Norm::L2 || j - i < 2) return segment_error(points_, i, j, norm_);
  const ChordDistance distance(points_[i], points_[j]);
  const Eigen::Vector3d direction = points_[j] - points_[i];
  const double length2 = direction.squaredNorm();
  const double inverse_length2 = length2 > 0.0 ? 1.0 / length2 : 0.0;
  const int lo = i + 1, hi = j - 1;
  // Best-first branch and bound: always open the node with the largest upper bound, stop when
  // that bound cannot beat the largest distance found (or the limit is exceeded).
  thread_local std::vector<std::pair<double, int>> heap;
  heap.clear();
  double best = 0.0;
  heap.push_back({std::numeric_limits<double>::infinity(), 0});
  while (!heap.empty()) {
    std::pop_heap(heap.begin(), heap.end());
    const auto [bound, index] = heap.back();
    heap.pop_back();
    if (bound <= best) break;
    const Node& node = nodes_[index];
    if (node.left < 0) {
      const int from = std::max(node.begin, lo), to = std::min(node.end - 1, hi);
      for (int k = from; k <= to; ++k) best = std::max(best, distance(points_[k]));
      if (best > limit) return best;
      continue;
    }
    for (const int child : {node.left, node.right}) {
      const Node& c = nodes_[child];
      if (c.end <= lo || c.begin > hi) continue;
      const double high = node_bounds(c, points_, distance, direction, inverse_length2).high;
      if (high <= best) continue;
      heap.push_back({high, child});
      std::push_heap(heap.begin(), heap.end());
    }
  }
  return best;
}

}  // namespace sculpt::curves::detail
