#pragma once
/// \file segment_error.hpp
/// Segment error of Definition 2.3 (Ihm & Naylor): distances of the points between two chosen
/// indices to the infinite line through the two end points. Every method in this layer measures
/// with ChordDistance, so all of them see bit-identical errors.

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <vector>

namespace sculpt::curves {

/// Error norms of section 2. Both are combined over segments by the maximum (min-max problem).
enum class Norm {
  LInf,  ///< segment error = largest point distance (default, the paper's choice)
  L2,    ///< segment error = sqrt(sum of squared point distances)
};

/// Distance of points to line(a, b). A degenerate chord (a == b) measures distance to a.
class ChordDistance {
 public:
  ChordDistance(const Eigen::Vector3d& a, const Eigen::Vector3d& b)
      : a_(a), d_(b - a), length_(d_.norm()) {}
  [[nodiscard]] double operator()(const Eigen::Vector3d& p) const {
    const Eigen::Vector3d w = p - a_;
    if (length_ == 0.0) return w.norm();
    return w.cross(d_).norm() / length_;
  }
  [[nodiscard]] const Eigen::Vector3d& origin() const { return a_; }
  [[nodiscard]] bool degenerate() const { return length_ == 0.0; }

 private:
  Eigen::Vector3d a_, d_;
  double length_;
};

/// Error of the segment (i, j), i < j, of the point sequence `points` (O(j - i)).
[[nodiscard]] double segment_error(const std::vector<Eigen::Vector3d>& points, int i, int j, Norm norm = Norm::LInf);

/// Error of a linearization: the maximum segment error over consecutive index pairs.
[[nodiscard]] double approximation_error(const std::vector<Eigen::Vector3d>& points, const std::vector<int>& indices,
                                         Norm norm = Norm::LInf);

}  // namespace sculpt::curves
