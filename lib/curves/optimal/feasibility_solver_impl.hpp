#pragma once
/// \file feasibility_solver_impl.hpp
/// FeasibilitySolver's state (Impl), shared by the files of its four jobs and included only by
/// them: edge_errors.cpp (error storage and evaluation), cone_pruning.cpp (the reach of every
/// position), fewest_segments.cpp (fewest segments within eps, by layers) and exact_paths.cpp
/// (paths of exactly m segments). The calls made in their hot loops (test, slope_rejects,
/// pair_excludes, error) are defined here so that they inline into every file.

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <optional>
#include <utility>
#include <vector>

#include "curves/optimal/chord_scan.hpp"
#include "curves/optimal/feasibility_solver.hpp"
#include "curves/optimal/tolerances.hpp"

namespace sculpt::curves::detail {

/// Stored value of an edge whose error exceeds the limit it was measured under.
inline constexpr double kBeyond = std::numeric_limits<double>::infinity();
/// Stored value of an edge whose error is below the floor it was measured under (build_rows).
inline constexpr double kBelow = -1.0;

/// Positions 0..K-1 index `vertex_`; FeasibilitySolver forwards to the public part.
class FeasibilitySolver::Impl {
 public:
  Impl(const std::vector<Eigen::Vector3d>& points, Norm norm, std::vector<int> vertices,
       const SegmentErrorTree* shared_tree)
      : points_(points), norm_(norm), shared_tree_(shared_tree), vertex_(std::move(vertices)) {
    const int count = static_cast<int>(vertex_.size());
    reach_.assign(count, count - 1);
    hint_.assign(count, -1);
    planar_ = std::all_of(points.begin(), points.end(), [](const Eigen::Vector3d& p) { return p.z() == 0.0; });
  }

  [[nodiscard]] int count() const { return static_cast<int>(vertex_.size()); }
  [[nodiscard]] const std::vector<int>& vertices() const { return vertex_; }
  [[nodiscard]] const std::vector<double>& stored_errors() const { return stored_; }
  [[nodiscard]] double floor() const { return floor_; }
  [[nodiscard]] long long tests() const { return tests_; }
  [[nodiscard]] double reach_eps() const { return reach_eps_; }
  [[nodiscard]] int min_segments() const { return dist_.back(); }

  [[nodiscard]] double error(int a, int b) {
    if (!stored_.empty() && b <= reach_[a] && stored_[row_[a] + (b - a - 1)] >= 0.0)
      return stored_[row_[a] + (b - a - 1)];
    if (vertex_[b] - vertex_[a] <= kDirectErrorSpan) return segment_error(points_, vertex_[a], vertex_[b], norm_);
    return tree().error(vertex_[a], vertex_[b]);
  }
  [[nodiscard]] long long edge_count() const {
    long long total = 0;
    for (int a = 0; a + 1 < count(); ++a) total += reach_[a] - a;
    return total;
  }
  // Indices of a position path.
  [[nodiscard]] std::vector<int> indices(const std::vector<int>& path) const {
    std::vector<int> result;
    result.reserve(path.size());
    for (int a : path) result.push_back(vertex_[a]);
    return result;
  }

  // Error storage and evaluation (edge_errors.cpp).
  // Rough count of point distances needed to evaluate every candidate edge (directly for
  // short chords, through the tree for long ones).
  [[nodiscard]] double evaluation_cost() const;
  // Computes and keeps the exact error of every candidate edge, or for long chords (evaluated
  // through the tree) a value > limit when the error exceeds limit; later tests are lookups.
  // \pre no probe above `limit` follows.
  void store_errors(double limit);
  // Stored mode in one pass, for small inputs: every row's end (reach) and its edges' errors,
  // exact if <= limit, else some value > limit. A row from p_i ends at the first chord with two
  // interior points that no line through p_i passes within limit of (pair_excludes: weaker
  // than cone_reach but sqrt-free, checked while the row grows), so every chord beyond it has
  // error > limit. Each chord is tried first against the previous chord's violator (smooth
  // curves: beyond the feasible chords of a row, one distance rejects each).
  // Errors certainly below `floor` are stored as kBelow (no square roots: most chords of a row);
  // no probe may go below floor() until materialize() has measured them.
  // False (and nothing stored) once the rows so far took more than 2e6 point distances plus
  // `budget` per row.
  bool build_rows(double limit, double budget, double floor = 0.0);
  // Measures every edge stored as kBelow exactly (floor() becomes 0).
  void materialize();

  // Cone pruning (cone_pruning.cpp).
  // Bounds every position's reach for tolerances <= eps by cone pruning.
  void prune_reach(double eps);

  // Fewest segments within eps (fewest_segments.cpp).
  // Fills dist_ / pred_: stored mode by relaxation over every position, otherwise by layers.
  void min_count(double eps);
  [[nodiscard]] std::vector<int> min_path() const;

  // Exactly m segments (exact_paths.cpp).
  // A path of exactly m edges with every edge within eps, or none. In stored mode, if the fewest
  // edges within eps are at least m - kWindow, the path is the best of all paths of m edges
  // (.optimal; best_exact_path).
  ExactPath exact_path(double eps, int m);

 private:
  struct RowEntry {        // one chord of a build_rows row (hinted_scan)
    double value;          // kBeyond, kBelow, the error, or (queued) a placeholder
    bool beyond;           // the error exceeds the limit
    int violator;          // a point beyond the limit, or -1: the hint for the next chord of the row
    int work;              // point distances spent
    bool queued = false;   // to be measured from cross2 and length2 at the end of build_rows
    double cross2 = 0.0, length2 = 0.0;
  };
  struct ChordError {  // bounded_error, hinted_error
    double error;
    int violator;  // a point beyond the limit, or -1
  };
  struct Thresholds {  // build_rows' bounds on squared distances
    double beyond2, below2;  // limit^2 and floor^2 with the relative margin (kRelativeMargin)
    double limit, floor;
  };
  struct Checkpoint {  // slope interval after the points up to `index`
    int index;
    double low, high;
  };
  struct Plane {  // orthonormal basis of a projection plane
    Eigen::Vector3d u, v;
  };

  // Error storage and evaluation (edge_errors.cpp).
  // segment_error(i, j) if it is <= limit, else some value > limit (L-inf: the scan stops at the
  // first point clearly beyond the limit; the margin keeps borderline points exact). The
  // violator is the farthest point scanned when that exceeds the limit, else -1.
  ChordError bounded_error(int i, int j, double limit) const;
  // For build_rows: the stored value of chord (i, j): kBeyond if it exceeds limit (found by a
  // point beyond limit, tried first `hint`), kBelow if it is certainly below floor, else a
  // placeholder queued for measuring (the squared cross product of the farthest point and
  // |p_j - p_i|^2). Degenerate, long and L2 chords are measured at once.
  RowEntry hinted_scan(int i, int j, const Thresholds& t, int hint);
  // bounded_error(i, j, limit), but first against point `hint` (if inside the chord; it stays
  // the violator if it is beyond the limit).
  ChordError hinted_error(int i, int j, double limit, int hint);
  // For store_errors: short chords directly; long ones first against kSpreadProbes evenly spread
  // points (rejects most infeasible chords, also where the tree's bounds are weak, e.g. scattered
  // points), then through the tree.
  double stored_error(int i, int j, double limit);
  const SegmentErrorTree& tree() {
    if (shared_tree_) return *shared_tree_;
    if (!tree_) tree_.emplace(points_, norm_);
    return *tree_;
  }
  bool test(int a, int b, double eps) {
    ++tests_;
    if (!stored_.empty()) return stored_[row_[a] + (b - a - 1)] <= eps;
    const int h = hint_[b];
    if (norm_ == Norm::LInf && h > vertex_[a] && h < vertex_[b]) {
      // Cheap rejection by the last violator of chords ending at b: squared distances with a
      // margin far above rounding, so it never rejects a chord the exact test would accept.
      const Eigen::Vector3d d = points_[vertex_[b]] - points_[vertex_[a]];
      const double cross2 = (points_[h] - points_[vertex_[a]]).cross(d).squaredNorm();
      if (cross2 > beyond_squared(eps * eps * d.squaredNorm())) return false;
    }
    const WithinTest result = tree().test(vertex_[a], vertex_[b], eps, hint_[b]);
    if (!result.within && result.violator >= 0) hint_[b] = result.violator;
    return result.within;
  }

  // Cone pruning (cone_pruning.cpp).
  // The projection plane at p_i: u along the first chord, v across it towards the second (the
  // discrete osculating plane), or within the curve's plane for planar data.
  Plane plane(int i, int last) const;
  // Largest index j such that chord (i, j) may have error <= eps. Projection onto a plane is
  // 1-Lipschitz and maps lines to lines, so if no line in the plane through the projected p_i is
  // within eps of the projected points i+1..k, no chord from p_i beyond k is feasible. In the
  // plane (basis u, v; x along u) the lines y = sigma x within eps of (x, y), x > eps, form the
  // slope interval [xy -+ eps sqrt(x^2 + y^2 - eps^2)] / (x^2 - eps^2); the reach ends where
  // the intersection of these intervals becomes empty (with a safety margin). The plane is the
  // curve's own plane for planar data, else the plane of the first two chords from p_i (the
  // discrete osculating plane, which keeps most of the bending). Points behind or within 2 eps
  // along u add no constraint (still sound). Far from i only every ((k - i) / kConeSamples)-th
  // point is examined, so a scan costs O(kConeSamples log(reach)), not O(reach).
  int cone_reach(int i, int last, double eps) const;
  // Necessary condition for chord (i, j) within eps, in O(1) per chord: projected to the plane
  // of cone_reach, the chord's slope y_j / x_j must lie in the slope interval of every sampled
  // interior point (the intervals are exact mathematics; the test keeps a safety margin, so it
  // only rejects chords the exact test would reject as well).
  void build_slope_filter(int i, int last, double eps);
  bool slope_rejects(int i, int j) {
    // Last checkpoint from a point strictly inside (i, j); b increases, so the index only grows.
    while (checkpoint_at_ + 1 < checkpoints_.size() && checkpoints_[checkpoint_at_ + 1].index < j) ++checkpoint_at_;
    if (checkpoints_.empty() || checkpoints_[checkpoint_at_].index >= j) return false;
    const Checkpoint& c = checkpoints_[checkpoint_at_];
    const Eigen::Vector3d w = points_[j] - points_[i];
    const double x = w.dot(filter_.u), y = w.dot(filter_.v);
    if (!(x > 0.0)) return false;
    const double margin = kRelativeMargin * (std::abs(y) + x * (1.0 + std::abs(c.low) + std::abs(c.high)));
    return y < c.low * x - margin || y > c.high * x + margin;
  }
  // No line through p_i passes within eps of both p_k and p_l: with p = p_k - p_i, q = p_l - p_i,
  // such a line makes angles t_p, t_q with sin t_p <= eps / |p|, sin t_q <= eps / |q|, and the
  // angle g between the lines of p and q is at most t_p + t_q, so |p x q| = |p||q| sin g <=
  // eps (|p| + |q|) (sin(t_p + t_q) <= sin t_p + sin t_q, and both sides >= 1 beyond pi/2).
  // Tested squared with (|p| + |q|)^2 <= 2 (|p|^2 + |q|^2) and a margin far above rounding.
  bool pair_excludes(int i, int k, int l, double eps) const {
    const Eigen::Vector3d p = points_[k] - points_[i], q = points_[l] - points_[i];
    return p.cross(q).squaredNorm() > beyond_squared(2.0 * eps * eps * (p.squaredNorm() + q.squaredNorm()));
  }

  // Fewest segments within eps (fewest_segments.cpp).
  // Stored mode: DAG relaxation in index order, every position; every test is a lookup.
  void relax_stored(double eps);
  // Breadth-first by layers, which tests each edge at most once, skips the positions already
  // reached in O(1) amortized and leaves positions not reached before the last one at kUnreached.
  // Every position of the current layer, in index order, claims the positions it reaches that no
  // earlier one has (found by `unclaimed`, a disjoint-set forest: the smallest unclaimed position
  // >= x, iterative with path halving).
  void claim_layers(double eps);

  // Exactly m segments (exact_paths.cpp).
  // Stored mode, after min_count(eps) found k <= m edges: among the paths of exactly m edges
  // within eps, one whose largest edge error is smallest, or nullopt if there is none. A path
  // through position b with c edges needs c >= dist[b], and c <= dist[b] + m - k (the rest of
  // the path needs at least k - dist[b] edges), so the DAG relaxation by bottleneck keeps
  // m - k + 1 layers per position. Cost: (m - k + 1) lookups per edge.
  std::optional<std::vector<int>> best_exact_path(double eps, int m);
  // Branch-free relaxation (min of max, no predecessor bookkeeping) of `width` layers per
  // position; bottleneck_path recovers the path by matching values.
  void relax_bottleneck(double eps, int width);
  // The path to the last position's top layer: each step back takes a predecessor state whose
  // value gives exactly the current one (values are copies of stored errors, so exactly equal).
  std::vector<int> bottleneck_path(double eps, int width) const;
  // Certificate for "exactly m": `path` (positions) with segments split into two within eps until
  // it has m, or nullopt if that fails (within a work budget).
  std::optional<std::vector<int>> split_to(std::vector<int> path, double eps, int m);
  // Exact: S[b] = set of segment counts <= m with which position b is reachable.
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
