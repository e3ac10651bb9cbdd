#pragma once
/// \file fast_linearization.hpp
/// Near-optimal min-error approximation for very large inputs: coarse-to-fine optimal search.
///  1. the exact solver restricted to every s-th point (s ~ n / (16 m)) as break point
///     candidates, errors always measured on all points;
///  2. repeatedly, the exact solver restricted to windows of +-s points around the current break
///     points at stride s / 8, until stride 1;
///  3. a last pass at stride 1 in windows of +-8 around the result.
/// Each stage starts from the previous answer, so the error never grows from stage to stage.
/// Inputs with at most `exact_below` points are solved exactly (optimal_min_error).

#include <Eigen/Core>
#include <vector>

#include "curves/linearization.hpp"

namespace sculpt::curves {

struct FastOptions {
  int exact_below = 20000;  ///< n at or below this: exact solver
  int candidates_per_segment = 16;
  int final_window = 8;
};

/// \pre 1 <= m <= points.size() - 1. .iterations = total feasibility probes.
[[nodiscard]] Linearization fast_linearization(const std::vector<Eigen::Vector3d>& points, int m, Norm norm,
                                               const FastOptions& options = {});

}  // namespace sculpt::curves
