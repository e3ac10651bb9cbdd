#include "curves/segment_error_tree.hpp"

#include <algorithm>
#include <cmath>

namespace sculpt::curves {
namespace {

// Safety margin for sphere bounds: far above the rounding error of ChordDistance, far below
// any distance that matters. Borderline nodes are opened and decided point by point.
double slack(double distance_scale, double radius) { return 1e-9 * (distance_scale + radius) + 1e-300; }

}  // namespace

SegmentErrorTree::SegmentErrorTree(const std::vector<Eigen::Vector3d>& points, Norm norm)
    : points_(points), norm_(norm) {
  const int n = static_cast<int>(points.size());
  if (n == 0 || norm == Norm::L2) return;
  nodes_.reserve(2 * (n / kLeafSize + 1) + 1);
  nodes_.push_back({Eigen::Vector3d::Zero(), 0.0, 0, n, -1, -1});
  std::vector<int> pending{0};  // explicit stack of nodes to split
  while (!pending.empty()) {
    const int k = pending.back();
    pending.pop_back();
    const int begin = nodes_[k].begin, end = nodes_[k].end;
    Eigen::Vector3d low = points[begin], high = points[begin];
    for (int q = begin + 1; q < end; ++q) {
      low = low.cwiseMin(points[q]);
      high = high.cwiseMax(points[q]);
    }
    const Eigen::Vector3d center = 0.5 * (low + high);
    double radius = 0.0;
    for (int q = begin; q < end; ++q) radius = std::max(radius, (points[q] - center).norm());
    nodes_[k].center = center;
    nodes_[k].radius = radius * (1.0 + 1e-12);
    if (end - begin > kLeafSize) {
      const int mid = begin + (end - begin) / 2;
      const int left = static_cast<int>(nodes_.size());
      nodes_.push_back({Eigen::Vector3d::Zero(), 0.0, begin, mid, -1, -1});
      nodes_.push_back({Eigen::Vector3d::Zero(), 0.0, mid, end, -1, -1});
      nodes_[k].left = left;
      nodes_[k].right = left + 1;
      pending.push_back(left);
      pending.push_back(left + 1);
    }
  }
}

bool SegmentErrorTree::within(int i, int j, double eps, int hint, int* violator) const {
  if (violator) *violator = -1;
  if (j - i < 2) return 0.0 <= eps;
  const ChordDistance distance(points_[i], points_[j]);
  if (norm_ == Norm::L2) {
    double sum = 0.0;
    for (int k = i + 1; k < j; ++k) {
      const double d = distance(points_[k]);
      sum += d * d;
      if (((k - i) & 15) == 0 && std::sqrt(sum) > eps) return false;  // partial sums only grow
    }
    return std::sqrt(sum) <= eps;
  }
  if (hint > i && hint < j && distance(points_[hint]) > eps) {
    if (violator) *violator = hint;
    return false;
  }
  const int lo = i + 1, hi = j - 1;  // interior points, inclusive
  int stack[128];
  int top = 0;
  stack[top++] = 0;
  while (top > 0) {
    const Node& node = nodes_[stack[--top]];
    if (node.end <= lo || node.begin > hi) continue;
    const double d = distance(node.center);
    const double margin = slack((node.center - distance.origin()).norm(), node.radius);
    if (d + node.radius + margin <= eps) continue;  // every point of the node is within
    const bool inside = node.begin >= lo && node.end - 1 <= hi;
    if (inside && d - node.radius - margin > eps) {  // every point of the node violates
      if (violator) *violator = node.begin;
      return false;
    }
    if (node.left < 0) {
      const int from = std::max(node.begin, lo), to = std::min(node.end - 1, hi);
      for (int k = from; k <= to; ++k)
        if (distance(points_[k]) > eps) {
          if (violator) *violator = k;
          return false;
        }
      continue;
    }
    // Open the child nearer to violating last, so it is examined first.
    const double dl = distance(nodes_[node.left].center), dr = distance(nodes_[node.right].center);
    if (dl > dr) {
      stack[top++] = node.right;
      stack[top++] = node.left;
    } else {
      stack[top++] = node.left;
      stack[top++] = node.right;
    }
  }
  return true;
}

double SegmentErrorTree::error(int i, int j) const {
  if (norm_ == Norm::L2 || j - i < 2) return segment_error(points_, i, j, norm_);
  const ChordDistance distance(points_[i], points_[j]);
  const int lo = i + 1, hi = j - 1;
  double best = 0.0;
  int stack[128];
  int top = 0;
  stack[top++] = 0;
  while (top > 0) {
    const Node& node = nodes_[stack[--top]];
    if (node.end <= lo || node.begin > hi) continue;
    const double d = distance(node.center);
    const double margin = slack((node.center - distance.origin()).norm(), node.radius);
    if (d + node.radius + margin <= best) continue;
    if (node.left < 0) {
      const int from = std::max(node.begin, lo), to = std::min(node.end - 1, hi);
      for (int k = from; k <= to; ++k) best = std::max(best, distance(points_[k]));
      continue;
    }
    const double dl = distance(nodes_[node.left].center), dr = distance(nodes_[node.right].center);
    if (dl > dr) {
      stack[top++] = node.right;
      stack[top++] = node.left;
    } else {
      stack[top++] = node.left;
      stack[top++] = node.right;
    }
  }
  return best;
}

}  // namespace sculpt::curves
