#pragma once
/// \file fast_linearization.hpp
/// Near-optimal min-error approximation for very large inputs (our design, not the paper's).
///  1. greedy covers: at tolerance eps, from each break point the farthest chord end with error
///     <= eps (galloping + binary search on exact SegmentErrorTree tests); eps is bisected in
///     log space for the smallest greedy cover with <= m segments, which is then split to
///     exactly m (worst segment first). Exact if segment errors grew monotonically with the end
///     point, as they nearly do on densely sampled smooth curves; O(m log(n/m) log n) per cover.
///  2. for m <= 64 also: the exact optimum (optimal_min_error) over every s-th point,
///     s ~ n / max(256, 16 m) (FastOptions), refined by layered passes with halving steps; the
///     better wins.
///  3. layered passes at step 1: break point k may move by up to +-2 points; the best joint
///     choice (a min-max path through m - 1 layers of 5 candidates) is found exactly by dynamic
///     programming over O(25 m) chords, measured only if they could improve their end and only
///     up to that bound; repeated while some break point moves to its window's edge.
/// Every stage keeps the best answer so far, so the error never grows. Inputs with at most
/// `exact_below` points are solved exactly (optimal_min_error).

#include <Eigen/Core>
#include <vector>

#include "curves/linearization.hpp"

namespace sculpt::curves::detail {

struct FastOptions {
  int exact_below = 20000;          ///< n at or below this: exact solver
  int bisection_steps = 18;
  int ladder_max_segments = 64;     ///< m up to this: also the coarse optimum with refinement
  int candidates_per_segment = 16;  ///< the coarse optimum's grid: max(min_candidates, this * m) points
  int min_candidates = 256;
  int max_passes_at_step_one = 8;
};

/// \pre 1 <= m <= points.size() - 1. .iterations = layered passes at step 1.
[[nodiscard]] Linearization fast_linearization(const std::vector<Eigen::Vector3d>& points, int m, Norm norm,
                                               const FastOptions& options = {});

}  // namespace sculpt::curves::detail
