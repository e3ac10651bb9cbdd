// FeasibilitySolver: cone pruning, the bound on every position's reach, and the O(1) slope filter
// of the streaming min-# pass (see optimal_linearization.hpp).
#include "curves/optimal/feasibility_solver_impl.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace sculpt::curves::detail {

void FeasibilitySolver::Impl::prune_reach(double eps) {
  const int count = this->count();
  const int last = vertex_.back();
  for (int a = 0; a + 1 < count; ++a) {
    const int reach_index = cone_reach(vertex_[a], last, eps);
    reach_[a] = static_cast<int>(std::upper_bound(vertex_.begin(), vertex_.end(), reach_index) - vertex_.begin()) - 1;
  }
  reach_eps_ = eps;
  stored_.clear();  // rows depend on the reach
  row_.clear();
}

FeasibilitySolver::Impl::Plane FeasibilitySolver::Impl::plane(int i, int last) const {
  const Eigen::Vector3d& origin = points_[i];
  const Eigen::Vector3d first = points_[std::min(i + 1, last)] - origin;
  Eigen::Vector3d u = first.norm() > 0.0 ? Eigen::Vector3d(first.normalized()) : Eigen::Vector3d(1, 0, 0);
  if (planar_) {
    if (u.z() != 0.0) u = Eigen::Vector3d(1, 0, 0);
    return {u, Eigen::Vector3d(-u.y(), u.x(), 0.0)};
  }
  const Eigen::Vector3d second = points_[std::min(i + 2, last)] - origin;
  const Eigen::Vector3d across = second - u * second.dot(u);
  const Eigen::Vector3d v =
      across.norm() > kStraightRatio * second.norm() && across.norm() > 0.0
          ? Eigen::Vector3d(across.normalized())
          : (std::abs(u.x()) < 0.9 ? Eigen::Vector3d(1, 0, 0) : Eigen::Vector3d(0, 1, 0)).cross(u).normalized();
  return {u, v};
}

int FeasibilitySolver::Impl::cone_reach(int i, int last, double eps) const {
  const Eigen::Vector3d& origin = points_[i];
  if (i + 1 > last) return last;
  const auto [u, v] = plane(i, last);
  double low = -std::numeric_limits<double>::infinity(), high = std::numeric_limits<double>::infinity();
  for (int k = i + 1; k <= last; k += std::max(1, (k - i) / kConeSamples)) {
    const Eigen::Vector3d w = points_[k] - origin;
    const double x = w.dot(u), y = w.dot(v);
    if (!(x > 2.0 * eps)) continue;  // behind or too near: no constraint (sound)
    const double denominator = x * x - eps * eps;
    const double root = eps * std::sqrt(std::max(0.0, x * x + y * y - eps * eps));
    low = std::max(low, (x * y - root) / denominator);
    high = std::min(high, (x * y + root) / denominator);
    if (low > high + kRelativeMargin * (1.0 + std::abs(low) + std::abs(high))) return k;
  }
  return last;
}

void FeasibilitySolver::Impl::build_slope_filter(int i, int last, double eps) {
  filter_ = plane(i, last);
  checkpoints_.clear();
  double low = -std::numeric_limits<double>::infinity(), high = std::numeric_limits<double>::infinity();
  const Eigen::Vector3d& origin = points_[i];
  for (int k = i + 1; k <= last; k += std::max(1, (k - i) / kSlopeFilterSamples)) {
    const Eigen::Vector3d w = points_[k] - origin;
    const double x = w.dot(filter_.u), y = w.dot(filter_.v);
    if (!(x > 2.0 * eps)) continue;
    const double denominator = x * x - eps * eps;
    const double root = eps * std::sqrt(std::max(0.0, x * x + y * y - eps * eps));
    low = std::max(low, (x * y - root) / denominator);
    high = std::min(high, (x * y + root) / denominator);
    checkpoints_.push_back({k, low, high});
  }
  checkpoint_at_ = 0;
}

}  // namespace sculpt::curves::detail
