#pragma once
/// \file heuristic_subdivision.hpp
/// The paper's heuristics (sec. 4): LENGTH (Alg. 4.1), IMAGE (Alg. 4.2), INIT (Alg. 4.3) as one
/// weighted subdivision, and ITER (Alg. 4.4), the iterative refinement of an approximation.

#include <Eigen/Core>
#include <vector>

#include "curves/curve_measures.hpp"
#include "curves/linearization.hpp"

namespace sculpt::curves::detail {

/// INIT(alpha): greedy subdivision into exactly m segments of (about) equal weight
/// alpha * L_seg + (1 - alpha) * I_seg. alpha = 1 is LENGTH, alpha = 0 is IMAGE.
/// Differences to the paper's text: segsum = total / m (the paper's ceil() would make segsum 1
/// for any curve shorter than m units); break point i is the largest j with W(0, j) < i segsum
/// (the paper measures W(q_{i-1}, j) < segsum, whose per-step shortfall piles up in the last
/// segment when segments hold few points); break points are clamped so that exactly m
/// non-empty segments result. \pre 1 <= m <= points.size() - 1, 0 <= alpha <= 1.
[[nodiscard]] Linearization weighted_subdivision(const std::vector<Eigen::Vector3d>& points,
                                                 const CurveMeasures& measures, int m, double alpha, Norm norm);

/// ITER (Alg. 4.4) from `start`: sweeps over the segments; a segment whose error exceeds a
/// neighbour's gives that neighbour its shared end point when no resulting segment error
/// exceeds the current maximum. Stops after a sweep without a move, after `max_iterations`
/// sweeps, or after 16 sweeps without a strict decrease of the maximum (plateau cycling).
/// Returns the best approximation seen (never worse than `start`); .iterations = the sweep that
/// reached it (the paper's k), 0 if no sweep improved on `start`.
[[nodiscard]] Linearization iterative_refinement(const std::vector<Eigen::Vector3d>& points, Linearization start,
                                                 Norm norm, int max_iterations);

}  // namespace sculpt::curves::detail
