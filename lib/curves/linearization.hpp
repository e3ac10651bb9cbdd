#pragma once
/// \file linearization.hpp
/// The result type shared by every linearization method.

#include <Eigen/Core>
#include <vector>

#include "curves/digitized_curve.hpp"
#include "curves/segment_error.hpp"

namespace sculpt::curves {

/// A piecewise linear approximation LA (Definition 2.3): strictly increasing indices into
/// path_points(curve), first 0 and last path_points(curve).size() - 1 (for a closed curve that
/// last index denotes the first point again). indices.size() - 1 segments.
struct Linearization {
  std::vector<int> indices;
  double error = 0.0;  ///< max segment error under the norm used
  int iterations = 0;  ///< ITER sweeps, bisection steps etc. where the method iterates, else 0
  [[nodiscard]] int segments() const { return static_cast<int>(indices.size()) - 1; }
};

/// The approximating polygon: path_points(curve)[indices[k]] for every k.
[[nodiscard]] std::vector<Eigen::Vector3d> linearization_points(const DigitizedCurve& curve, const Linearization& la);

/// Recomputes the error of `la` on `curve` (checks the indices; \throw InvalidInput if invalid).
[[nodiscard]] double linearization_error(const DigitizedCurve& curve, const Linearization& la, Norm norm = Norm::LInf);

}  // namespace sculpt::curves
