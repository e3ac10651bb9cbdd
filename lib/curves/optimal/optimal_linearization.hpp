#pragma once
/// \file optimal_linearization.hpp
/// Exact solvers for both problems of sec. 2 (Pavlidis & Horowitz), far faster than DYNAMIC.
///
/// Feasibility at a tolerance eps is a shortest-path question in the DAG whose edges are the
/// chords (i, j) with segment error <= eps. Segment errors are not monotone in j, so no greedy
/// "reach as far as possible" works; instead the DAG is relaxed in index order and an edge is
/// tested only when it could improve its end vertex (BFS layers with pruning). Two facts keep
/// the edge set small and the tests cheap:
///  - cone pruning: a line through p_i is within eps of p_k only inside a double cone of
///    half-angle asin(eps / |p_k - p_i|) around p_k - p_i; once two such cones are disjoint no
///    chord from p_i beyond both points can be feasible, which bounds the reach of i;
///  - SegmentErrorTree answers "error(i, j) <= eps" exactly in about O(log n).
/// The min-error problem for exactly m segments: the optimum is one of the segment errors, and
/// feasibility is monotone in eps. Small inputs (<= 64 points per segment on average) store every
/// candidate edge's error, built in one pass under a cap from an estimate of the optimum
/// ((sum_s sqrt(e_s) / m)^2 over evenly spaced break points: errors grow like length squared on
/// smooth curves, sec. 4). A probe needing k <= m segments with m - k <= 6 ends the search: a
/// DAG relaxation with m - k + 1 layers per vertex finds the best path of exactly m edges within
/// eps, which is the optimum. Otherwise guesses by the same scaling, then binary search over
/// the stored errors, or bisection of eps over the doubles when nothing is stored. "Exactly m"
/// is otherwise decided by splitting segments of a min-# path, or a bitset DP over achievable
/// segment counts. docs/curves.md has the details.

#include <Eigen/Core>
#include <vector>

#include "curves/linearization.hpp"
#include "curves/optimal/segment_error_tree.hpp"

namespace sculpt::curves::detail {

struct OptimalOptions {
  /// Allowed break points (sorted indices into points, containing 0 and points.size() - 1);
  /// empty = all. The result is optimal among approximations using only these.
  std::vector<int> vertices = {};
  /// A known feasible approximation with exactly m segments using allowed vertices (its error
  /// bounds the search); empty = the solver builds one.
  std::vector<int> start = {};
  /// A tree built over the same points and norm, to share between calls (optional).
  const SegmentErrorTree* tree = nullptr;
  /// Never store candidate errors: bisect the tolerance with streamed edge tests (the mode used
  /// for large inputs; exposed so that tests can check it on small ones).
  bool streaming = false;
};

/// Exact min-error approximation with exactly m segments (Problem 1).
/// .iterations = feasibility probes. \pre 1 <= m <= allowed vertex count - 1.
[[nodiscard]] Linearization optimal_min_error(const std::vector<Eigen::Vector3d>& points, int m, Norm norm,
                                              const OptimalOptions& options = {});

/// Exact fewest segments with every segment error <= tolerance (the first problem of sec. 2).
/// Always solvable: chords of neighbouring points have error 0.
[[nodiscard]] Linearization optimal_min_count(const std::vector<Eigen::Vector3d>& points, double tolerance,
                                              Norm norm);

}  // namespace sculpt::curves::detail
