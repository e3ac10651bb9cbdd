#pragma once
/// \file feasibility_solver.hpp
/// Internal to optimal_linearization.cpp: is a tolerance eps feasible with m segments? (the two
/// problems of sec. 2, Ihm & Naylor 1990). Feasibility is a shortest-path question in the DAG
/// over the allowed break points ("positions" 0..K-1) whose edges are the chords (a, b) with
/// segment error (Definition 2.3) <= eps. Cone pruning bounds each position's reach (no chord
/// from a beyond reach[a] can be within eps); edges are tested on demand through
/// SegmentErrorTree, or, in stored mode, every candidate edge's error is computed once and
/// probes are lookups. "Exactly m" is decided by a layered bottleneck DP (stored mode), by
/// splitting segments of a min-# path, or by a bitset DP over achievable segment counts.
/// docs/curves.md has the details.

#include <Eigen/Core>
#include <limits>
#include <memory>
#include <optional>
#include <vector>

#include "curves/segment_error.hpp"
#include "curves/optimal/segment_error_tree.hpp"

namespace sculpt::curves::detail {

/// min_count's distance of a position not reached.
inline constexpr int kUnreached = std::numeric_limits<int>::max();
/// A feasible stored-mode probe that needs at least m - kWindow segments ends the search
/// (best_exact_path, kWindow + 1 layers).
inline constexpr int kWindow = 6;

/// Result of FeasibilitySolver::exact_path.
struct ExactPath {
  std::optional<std::vector<int>> path;  ///< positions of a path of exactly m edges within eps, if any
  bool optimal = false;                  ///< the path is the best of all paths of m edges
};

/// Shortest paths over the allowed vertices; positions 0..K-1 index `vertices()`. The state is
/// Impl (feasibility_solver_impl.hpp); its four jobs live in edge_errors.cpp, cone_pruning.cpp,
/// fewest_segments.cpp and exact_paths.cpp.
class FeasibilitySolver {
 public:
  /// `vertices`: sorted point indices, first 0 and last points.size() - 1. `shared_tree` (optional)
  /// is built over the same points and norm; otherwise the solver builds its own when needed.
  FeasibilitySolver(const std::vector<Eigen::Vector3d>& points, Norm norm, std::vector<int> vertices,
                    const SegmentErrorTree* shared_tree = nullptr);
  ~FeasibilitySolver();
  FeasibilitySolver(const FeasibilitySolver&) = delete;
  FeasibilitySolver& operator=(const FeasibilitySolver&) = delete;

  [[nodiscard]] int count() const;
  [[nodiscard]] const std::vector<int>& vertices() const;
  /// Segment error of the chord between positions a < b (a lookup if stored and measured).
  [[nodiscard]] double error(int a, int b);

  /// Number of candidate edges (a, b <= reach[a]).
  [[nodiscard]] long long edge_count() const;
  /// Rough count of point distances needed to evaluate every candidate edge.
  [[nodiscard]] double evaluation_cost() const;

  /// Stored mode: computes every candidate edge's error once (exact if <= limit, else some value
  /// > limit); later tests are lookups. \pre no probe above `limit` follows.
  void store_errors(double limit);
  [[nodiscard]] const std::vector<double>& stored_errors() const;
  /// Stored mode in one pass, for small inputs: each row's reach and its edges' errors under
  /// `limit`; errors certainly below `floor` are left unmeasured (see floor()). False (nothing
  /// stored) once the rows took more than 2e6 point distances plus `budget` per row.
  bool build_rows(double limit, double budget, double floor = 0.0);
  /// Errors below floor() are not measured yet; probes must stay at or above it.
  [[nodiscard]] double floor() const;
  /// Measures every edge left below the floor (floor() becomes 0).
  void materialize();

  /// Edge tests (or lookups) so far.
  [[nodiscard]] long long tests() const;

  /// Bounds every position's reach for tolerances <= eps by cone pruning (drops stored rows).
  void prune_reach(double eps);
  [[nodiscard]] double reach_eps() const;

  /// Fewest segments to the last position at tolerance eps (then min_segments(), min_path()).
  void min_count(double eps);
  [[nodiscard]] int min_segments() const;
  [[nodiscard]] std::vector<int> min_path() const;

  /// A path of exactly m edges with every edge within eps, or none if none exists. In stored
  /// mode, if the fewest edges within eps are at least m - kWindow, the path is the best of all
  /// paths of m edges (.optimal = true).
  [[nodiscard]] ExactPath exact_path(double eps, int m);

  /// Point indices of a position path.
  [[nodiscard]] std::vector<int> indices(const std::vector<int>& path) const;

 private:
  class Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace sculpt::curves::detail
