#pragma once
/// \file coverage.hpp
/// The traced polylines in a uniform hash grid, so that a start point on an already traced
/// component is recognised and the component is not traced twice.

#include <Eigen/Core>
#include <cstdint>
#include <unordered_map>
#include <vector>

namespace sculpt::implicit::detail {

class Coverage {
 public:
  Coverage(const Eigen::Vector3d& origin, double cell) : origin_(origin), cell_(cell) {}
  void add_polyline(const std::vector<Eigen::Vector3d>& points, bool closed);
  /// Whether some traced segment passes within `radius` (at most one cell) of p.
  [[nodiscard]] bool covers(const Eigen::Vector3d& p, double radius) const;

 private:
  [[nodiscard]] std::int64_t key(long i, long j, long k) const;
  [[nodiscard]] Eigen::Vector3i cell_of(const Eigen::Vector3d& p) const;
  Eigen::Vector3d origin_;
  double cell_;
  std::vector<std::pair<Eigen::Vector3d, Eigen::Vector3d>> segments_;
  std::unordered_map<std::int64_t, std::vector<int>> grid_;
};

}  // namespace sculpt::implicit::detail
