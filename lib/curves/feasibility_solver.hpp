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
#include <cstddef>
#include <limits>
#include <optional>
#include <vector>

#include "curves/chord_scan.hpp"
#include "curves/segment_error.hpp"
#include "curves/segment_error_tree.hpp"

namespace sculpt::curves::detail {

/// min_count's distance of a position not reached.
inline constexpr int kUnreached = std::numeric_limits<int>::max();
/// A feasible stored-mode probe that needs at least m - kWindow segments ends the search
/// (best_exact_path, kWindow + 1 layers).
inline constexpr int kWindow = 6;

/// Shortest paths over the allowed vertices; positions 0..K-1 index `vertices()`.
class FeasibilitySolver {
 public:
  /// `vertices`: sorted point indices, first 0 and last points.size() - 1. `shared_tree` (optional)
  /// is built over the same points and norm; otherwise the solver builds its own when needed.
  FeasibilitySolver(const std::vector<Eigen::Vector3d>& points, Norm norm, std::vector<int> vertices,
                    const SegmentErrorTree* shared_tree = nullptr);

  [[nodiscard]] int count() const { return static_cast<int>(vertex_.size()); }
  [[nodiscard]] const std::vector<int>& vertices() const { return vertex_; }
  /// Segment error of the chord between positions a < b (a lookup if stored and measured).
  [[nodiscard]] double error(int a, int b);

  /// Number of candidate edges (a, b <= reach[a]).
  [[nodiscard]] long long edge_count() const;
  /// Rough count of point distances needed to evaluate every candidate edge.
  [[nodiscard]] double evaluation_cost() const;

  /// Stored mode: computes every candidate edge's error once (exact if <= limit, else some value
  /// > limit); later tests are lookups. \pre no probe above `limit` follows.
  void store_errors(double limit);
  [[nodiscard]] const std::vector<double>& stored_errors() const { return stored_; }
  /// Stored mode in one pass, for small inputs: each row's reach and its edges' errors under
  /// `limit`; errors certainly below `floor` are left unmeasured (see floor()). False (nothing
  /// stored) once the rows took more than 2e6 point distances plus `budget` per row.
  bool build_rows(double limit, double budget, double floor = 0.0);
  /// Errors below floor() are not measured yet; probes must stay at or above it.
  [[nodiscard]] double floor() const { return floor_; }
  /// Measures every edge left below the floor (floor() becomes 0).
  void materialize();

  /// Edge tests (or lookups) so far.
  [[nodiscard]] long long tests() const { return tests_; }

  /// Bounds every position's reach for tolerances <= eps by cone pruning (drops stored rows).
  void prune_reach(double eps);
  [[nodiscard]] double reach_eps() const { return reach_eps_; }

  /// Fewest segments to the last position at tolerance eps (then min_segments(), min_path()).
  void min_count(double eps);
  [[nodiscard]] int min_segments() const { return dist_.back(); }
  [[nodiscard]] std::vector<int> min_path() const;

  /// A path of exactly m edges with every edge within eps, or nullopt if none exists. In stored
  /// mode, if the fewest edges within eps are at least m - kWindow, the path is the best of all
  /// paths of m edges (*optimal = true).
  std::optional<std::vector<int>> exact_path(double eps, int m, bool* optimal = nullptr);

  /// Point indices of a position path.
  [[nodiscard]] std::vector<int> indices(const std::vector<int>& path) const;

 private:
  struct Thresholds {  // build_rows' bounds on squared distances
    double beyond2, below2;  // limit^2 (1 + 1e-9), floor^2 (1 - 1e-9)
    double limit, floor;
  };
  struct Checkpoint {  // slope interval after the points up to `index`
    int index;
    double low, high;
  };
  struct Plane {  // orthonormal basis of a projection plane
    Eigen::Vector3d u, v;
  };

  void relax_stored(double eps);
  void claim_layers(double eps);
  std::optional<std::vector<int>> best_exact_path(double eps, int m);
  void relax_bottleneck(double eps, int width);
  [[nodiscard]] std::vector<int> bottleneck_path(double eps, int width) const;
  double bounded_error(int i, int j, double limit, int* farthest_out = nullptr) const;
  bool pair_excludes(int i, int k, int l, double eps) const;
  bool hinted_scan(int i, int j, const Thresholds& t, int& violator, std::vector<double>& values, double& scanned);
  double hinted_error(int i, int j, double limit, int& violator);
  double stored_error(int i, int j, double limit);
  const SegmentErrorTree& tree();
  bool test(int a, int b, double eps);
  [[nodiscard]] Plane plane(int i, int last) const;
  int cone_reach(int i, int last, double eps) const;
  void build_slope_filter(int i, int last, double eps);
  bool slope_rejects(int i, int j);
  bool split_to(std::vector<int>& path, double eps, int m);
  std::optional<std::vector<int>> bitset_path(double eps, int m);

  const std::vector<Eigen::Vector3d>& points_;
  Norm norm_;
  const SegmentErrorTree* shared_tree_;
  bool planar_ = false;
  std::vector<Checkpoint> checkpoints_;  // slope filter of the current row
  std::vector<double> cross2_, length2_;  // build_rows: chords to measure (farthest point, length)
  std::vector<std::size_t> measured_;     // build_rows: their places in the stored errors
  std::optional<PointColumns> columns_;   // build_rows: the points as coordinate columns
  double floor_ = 0.0;                    // stored errors below it are kBelow
  double best_bottleneck_ = 0.0;          // of the last best_exact_path
  std::size_t checkpoint_at_ = 0;
  Plane filter_;  // slope filter's plane
  std::optional<SegmentErrorTree> tree_;
  std::vector<std::size_t> row_;   // stored mode: row start of position a
  std::vector<double> stored_;     // stored mode: error of (a, b) at row_[a] + b - a - 1
  std::vector<int> vertex_;
  std::vector<int> reach_, hint_, dist_, pred_;
  std::vector<int> unclaimed_;  // min_count: disjoint-set forest over positions
  std::vector<double> bottleneck_;  // best_exact_path: per position and layer
  double reach_eps_ = std::numeric_limits<double>::infinity();
  long long tests_ = 0;
};

}  // namespace sculpt::curves::detail
