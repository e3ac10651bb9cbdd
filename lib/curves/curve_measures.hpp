#pragma once
/// \file curve_measures.hpp
/// Tangents (sec. 4.2) and the two measures the heuristics subdivide by: chord length
/// (sec. 4.1) and spherical-image length (sec. 4.2), as prefix sums for O(1) range queries.

#include <Eigen/Core>
#include <vector>

#include "curves/digitized_curve.hpp"

namespace sculpt::curves {

enum class TangentMethod {
  FivePoint,          ///< the paper's 5-point formula with Bessel end conditions (sec. 4.2)
  CentralDifference,  ///< (p[i+1] - p[i-1]) normalized, one-sided at open ends
};

/// Unit tangents, one per point of path_points(curve) (closed curves wrap around; the repeated
/// last point gets the first point's tangent). Zero-length differences (repeated points)
/// are skipped so that no tangent is NaN; a curve with all points equal gets (1, 0, 0).
[[nodiscard]] std::vector<Eigen::Vector3d> tangents(const DigitizedCurve& curve,
                                                    TangentMethod method = TangentMethod::FivePoint);

/// Prefix sums over path_points(curve): chord[k] = sum_{i<k} |p[i+1]-p[i]|,
/// image[k] = sum_{i<k} |t[i+1]-t[i]|, plus the moment sum_{i<k} chord[i] |t[i+1]-t[i]|
/// for the center of curvature (sec. 4.3.5).
class CurveMeasures {
 public:
  explicit CurveMeasures(const DigitizedCurve& curve, TangentMethod method = TangentMethod::FivePoint);
  /// Chord length L_seg(i, j) of the sub-range i..j (i <= j), O(1).
  [[nodiscard]] double chord_length(int i, int j) const { return chord_[j] - chord_[i]; }
  /// Spherical-image length I_seg(i, j), O(1).
  [[nodiscard]] double image_length(int i, int j) const { return image_[j] - image_[i]; }
  /// sum_{i<=k<j} (chord(0,k) - chord(0,i)) * |t[k+1]-t[k]|, O(1): numerator of c_kappa.
  [[nodiscard]] double image_moment(int i, int j) const {
    return (moment_[j] - moment_[i]) - chord_[i] * (image_[j] - image_[i]);
  }
  [[nodiscard]] int size() const { return static_cast<int>(chord_.size()); }
  [[nodiscard]] const std::vector<double>& chord_prefix() const { return chord_; }
  [[nodiscard]] const std::vector<double>& image_prefix() const { return image_; }

 private:
  std::vector<double> chord_, image_, moment_;
};

}  // namespace sculpt::curves
