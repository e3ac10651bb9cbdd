#pragma once
/// \file dynamic_programming.hpp
/// DYNAMIC (Alg. 3.2 with the arbitrary-m extension of sec. 3.3), as the paper wrote it:
/// E^1_ij for all pairs by direct evaluation (O(n^3)), then E^{2^d}_ij = min_k max(E^{2^{d-1}}_ik,
/// E^{2^{d-1}}_kj) for d = 1..floor(log2 m) (O(n^3 log m) time, O(n^2 log m) space), and the
/// binary digits of m merged left to right. Exactly m segments: E^l_ij = inf when j - i < l.
/// This is the slow reference that proves the fast solvers right.

#include <Eigen/Core>
#include <vector>

#include "curves/linearization.hpp"

namespace sculpt::curves::detail {

/// Largest point count accepted by dynamic_linearization (memory O(n^2 log m)).
inline constexpr int kDynamicMaxPoints = 1500;

/// \pre 1 <= m <= points.size() - 1. \throw InvalidInput if points.size() > kDynamicMaxPoints.
[[nodiscard]] Linearization dynamic_linearization(const std::vector<Eigen::Vector3d>& points, int m, Norm norm);

}  // namespace sculpt::curves::detail
