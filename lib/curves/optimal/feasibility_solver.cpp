#include "curves/optimal/feasibility_solver.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <memory>
#include <utility>

#include "curves/optimal/chord_scan.hpp"
#include "curves/optimal/tolerances.hpp"

namespace sculpt::curves::detail {
namespace {

// Stored value of an edge whose error exceeds the limit it was measured under.
constexpr double kBeyond = std::numeric_limits<double>::infinity();
// Stored value of an edge whose error is below the floor it was measured under (build_rows).
constexpr double kBelow = -1.0;

// The solver's state and algorithms (FeasibilitySolver forwards to it); positions 0..K-1 index
// `vertex_`. Local to this file, so that its helpers inline into the hot loops.
class Solver {
 public:
  Solver(const std::vector<Eigen::Vector3d>& points, Norm norm, std::vector<int> vertices,
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

  // Rough count of point distances needed to evaluate every candidate edge (directly for
  // short chords, through the tree for long ones).
  [[nodiscard]] double evaluation_cost() const {
    double total = 0;
    for (int a = 0; a + 1 < count(); ++a)
      total += static_cast<double>(reach_[a] - a) *
               (vertex_[reach_[a]] - vertex_[a] <= kDirectSpan ? 0.5 * (vertex_[reach_[a]] - vertex_[a]) : 128.0);
    return total;
  }

  // Computes and keeps the exact error of every candidate edge, or for long chords (evaluated
  // through the tree) a value > limit when the error exceeds limit; later tests are lookups.
  // \pre no probe above `limit` follows.
  void store_errors(double limit) {
    const int count = this->count();
    row_.assign(count, 0);
    std::size_t total = 0;
    for (int a = 0; a + 1 < count; ++a) {
      row_[a] = total;
      total += static_cast<std::size_t>(reach_[a] - a);
    }
    std::vector<double> values(total);
    for (int a = 0; a + 1 < count; ++a)
      for (int b = a + 1; b <= reach_[a]; ++b)
        values[row_[a] + (b - a - 1)] = stored_error(vertex_[a], vertex_[b], limit);
    stored_ = std::move(values);
  }

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
  bool build_rows(double limit, double budget, double floor = 0.0) {
    const int count = this->count();
    std::vector<std::size_t> rows(count, 0);
    std::vector<int> reach(count, count - 1);
    std::vector<double> values;
    values.reserve(static_cast<std::size_t>(count) * 16);
    if (!columns_) columns_.emplace(points_);
    measured_.clear();
    cross2_.clear();
    length2_.clear();
    // squared thresholds with margins far above rounding: beyond limit / certainly below floor
    const Thresholds squared{limit * limit * (1.0 + kRelativeMargin), floor * floor * (1.0 - kRelativeMargin), limit,
                             floor};
    double scanned = 0.0;  // point distances so far (work budget)
    for (int a = 0; a + 1 < count; ++a) {
      rows[a] = values.size();
      const int i = vertex_[a];
      int violator = -1, b = a + 1;
      bool rejected = false;
      for (; b < count; ++b) {
        const int j = vertex_[b];
        // (only after a rejected chord: while chords pass, the row certainly goes on)
        if (rejected && j - i >= 3 && pair_excludes(i, j - 1, i + (j - i) / 2, limit)) break;
        if (j - i == 1) {  // no interior point: error 0
          values.push_back(floor > 0.0 ? kBelow : 0.0);
          rejected = false;
          continue;
        }
        const RowEntry entry = hinted_scan(i, j, squared, violator);
        if (entry.queued) {
          measured_.push_back(values.size());
          cross2_.push_back(entry.cross2);
          length2_.push_back(entry.length2);
        }
        values.push_back(entry.value);
        violator = entry.violator;
        rejected = entry.beyond;
        scanned += entry.work;
        if ((scanned += 1.0) > 2e6 + budget * (a + 1)) return false;
      }
      reach[a] = b - 1;
    }
    // The distances of the measured chords' farthest points, sqrt(cross2) / sqrt(length2)
    // exactly as ChordDistance computes them, in a loop of independent roots and divisions.
    const std::vector<double> distances = chord_distances(cross2_, length2_, kBeyond, kBelow);
    for (std::size_t t = 0; t < measured_.size(); ++t) values[measured_[t]] = distances[t];
    row_ = std::move(rows);
    reach_ = std::move(reach);
    stored_ = std::move(values);
    reach_eps_ = limit;
    floor_ = floor;
    return true;
  }

  // Measures every edge stored as kBelow exactly (floor() becomes 0).
  void materialize() {
    if (floor_ <= 0.0) return;
    for (int a = 0; a + 1 < count(); ++a)
      for (int b = a + 1; b <= reach_[a]; ++b)
        if (double& value = stored_[row_[a] + (b - a - 1)]; value < 0.0)
          value = segment_error(points_, vertex_[a], vertex_[b], norm_);
    floor_ = 0.0;
  }

  // Bounds every position's reach for tolerances <= eps by cone pruning.
  void prune_reach(double eps) {
    const int count = this->count();
    const int last = vertex_.back();
    for (int a = 0; a + 1 < count; ++a) {
      const int reach_index = cone_reach(vertex_[a], last, eps);
      reach_[a] = static_cast<int>(std::upper_bound(vertex_.begin(), vertex_.end(), reach_index) - vertex_.begin()) - 1;
    }
    reach_eps_ = eps;
    stored_.clear();  // rows depend on the reach
    row_.clear();
  }

  // Fills dist_ / pred_: stored mode by relaxation over every position, otherwise by layers.
  void min_count(double eps) {
    const int count = this->count();
    dist_.assign(count, kUnreached);
    pred_.assign(count, -1);
    dist_[0] = 0;
    if (!stored_.empty())
      relax_stored(eps);
    else
      claim_layers(eps);
  }

  [[nodiscard]] std::vector<int> min_path() const {
    std::vector<int> path;
    for (int b = count() - 1; b >= 0; b = pred_[b]) {
      path.push_back(b);
      if (b == 0) break;
    }
    std::reverse(path.begin(), path.end());
    return path;
  }

  // A path of exactly m edges with every edge within eps, or none. In stored mode, if the fewest
  // edges within eps are at least m - kWindow, the path is the best of all paths of m edges
  // (.optimal; best_exact_path).
  ExactPath exact_path(double eps, int m) {
    min_count(eps);
    if (dist_.back() > m) return {std::nullopt, false};
    if (m - dist_.back() <= kWindow && !stored_.empty()) {
      std::optional<std::vector<int>> path = best_exact_path(eps, m);
      if (path && floor_ > 0.0 && best_bottleneck_ < floor_) {  // errors below the floor decide it
        materialize();
        path = best_exact_path(eps, m);
      }
      const bool optimal = path.has_value();
      return {std::move(path), optimal};
    }
    if (std::optional<std::vector<int>> split = split_to(min_path(), eps, m)) return {std::move(split), false};
    return {bitset_path(eps, m), false};
  }

  // Indices of a position path.
  [[nodiscard]] std::vector<int> indices(const std::vector<int>& path) const {
    std::vector<int> result;
    result.reserve(path.size());
    for (int a : path) result.push_back(vertex_[a]);
    return result;
  }

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

  // Stored mode: DAG relaxation in index order, every position; every test is a lookup.
  void relax_stored(double eps) {
    const int count = this->count();
    for (int a = 0; a + 1 < count; ++a) {
      if (dist_[a] == kUnreached) continue;
      const int next = dist_[a] + 1;
      const double* row = stored_.data() + row_[a];
      for (int b = a + 1; b <= reach_[a]; ++b) {
        if (row[b - a - 1] <= eps && dist_[b] > next) {
          dist_[b] = next;
          pred_[b] = a;
        }
      }
    }
    tests_ += edge_count();
  }

  // Breadth-first by layers, which tests each edge at most once, skips the positions already
  // reached in O(1) amortized and leaves positions not reached before the last one at kUnreached.
  // Every position of the current layer, in index order, claims the positions it reaches that no
  // earlier one has (found by `unclaimed`, a disjoint-set forest: the smallest unclaimed position
  // >= x, iterative with path halving).
  void claim_layers(double eps) {
    const int count = this->count();
    std::vector<int>& unclaimed = unclaimed_;
    unclaimed.resize(static_cast<std::size_t>(count) + 1);
    for (int b = 0; b <= count; ++b) unclaimed[b] = b;
    const auto find = [&](int x) {
      while (unclaimed[x] != x) x = unclaimed[x] = unclaimed[unclaimed[x]];
      return x;
    };
    unclaimed[0] = 1;
    std::vector<int> layer{0}, next_layer;
    while (!layer.empty() && dist_[count - 1] == kUnreached) {
      next_layer.clear();
      for (int a : layer) {
        const int next = dist_[a] + 1;
        bool filtered = false;
        for (int b = find(a + 1); b <= reach_[a]; b = find(b + 1)) {
          if (vertex_[b] - vertex_[a] > kSlopeFilterSpan) {  // long chords: O(1) slope filter first
            if (!filtered) {
              build_slope_filter(vertex_[a], vertex_[reach_[a]], eps);
              filtered = true;
            }
            if (slope_rejects(vertex_[a], vertex_[b])) continue;
          }
          if (test(a, b, eps)) {
            dist_[b] = next;
            pred_[b] = a;
            unclaimed[b] = b + 1;
            next_layer.push_back(b);
          }
        }
      }
      std::sort(next_layer.begin(), next_layer.end());
      layer.swap(next_layer);
    }
  }

  // Stored mode, after min_count(eps) found k <= m edges: among the paths of exactly m edges
  // within eps, one whose largest edge error is smallest, or nullopt if there is none. A path
  // through position b with c edges needs c >= dist[b], and c <= dist[b] + m - k (the rest of
  // the path needs at least k - dist[b] edges), so the DAG relaxation by bottleneck keeps
  // m - k + 1 layers per position. Cost: (m - k + 1) lookups per edge.
  std::optional<std::vector<int>> best_exact_path(double eps, int m) {
    const int count = this->count();
    const int width = m - dist_.back() + 1;
    relax_bottleneck(eps, width);
    best_bottleneck_ = bottleneck_[static_cast<std::size_t>(count) * width - 1];
    if (best_bottleneck_ == std::numeric_limits<double>::infinity()) return std::nullopt;
    return bottleneck_path(eps, width);
  }

  // Branch-free relaxation (min of max, no predecessor bookkeeping) of `width` layers per
  // position; bottleneck_path recovers the path by matching values.
  void relax_bottleneck(double eps, int width) {
    const int count = this->count();
    std::vector<double>& bottleneck = bottleneck_;
    bottleneck.assign(static_cast<std::size_t>(count) * width, std::numeric_limits<double>::infinity());
    bottleneck[0] = 0.0;
    for (int a = 0; a + 1 < count; ++a) {
      if (dist_[a] == kUnreached) continue;
      const double* row = stored_.data() + row_[a];
      const double* from = bottleneck.data() + static_cast<std::size_t>(a) * width;
      for (int b = a + 1; b <= reach_[a]; ++b) {
        const double e = row[b - a - 1];
        if (e > eps) continue;
        const int shift = dist_[a] + 1 - dist_[b];  // layer l of a reaches layer l + shift of b
        double* to = bottleneck.data() + static_cast<std::size_t>(b) * width + shift;
        for (int l = 0; l + shift < width; ++l) to[l] = std::min(to[l], std::max(from[l], e));
      }
    }
  }

  // The path to the last position's top layer: each step back takes a predecessor state whose
  // value gives exactly the current one (values are copies of stored errors, so exactly equal).
  std::vector<int> bottleneck_path(double eps, int width) const {
    const int count = this->count();
    const std::vector<double>& bottleneck = bottleneck_;
    std::vector<int> path{count - 1};
    for (int b = count - 1, layer = width - 1; b > 0;) {
      const double value = bottleneck[static_cast<std::size_t>(b) * width + layer];
      int previous = -1, previous_layer = -1;
      for (int a = b - 1; a >= 0 && previous < 0; --a) {
        if (dist_[a] == kUnreached || reach_[a] < b) continue;
        const double e = stored_[row_[a] + (b - a - 1)];
        const int l = layer - (dist_[a] + 1 - dist_[b]);
        if (e > eps || l < 0 || l >= width) continue;
        if (std::max(bottleneck[static_cast<std::size_t>(a) * width + l], e) == value) {
          previous = a;
          previous_layer = l;
        }
      }
      b = previous;  // exists: value was relaxed from some such state
      layer = previous_layer;
      path.push_back(b);
    }
    std::reverse(path.begin(), path.end());
    return path;
  }

  // segment_error(i, j) if it is <= limit, else some value > limit (L-inf: the scan stops at the
  // first point clearly beyond the limit; the margin keeps borderline points exact). The
  // violator is the farthest point scanned when that exceeds the limit, else -1.
  ChordError bounded_error(int i, int j, double limit) const {
    if (norm_ != Norm::LInf || j - i < 2 || !(limit < std::numeric_limits<double>::infinity()))
      return {segment_error(points_, i, j, norm_), -1};
    const Eigen::Vector3d& a = points_[i];
    const Eigen::Vector3d d = points_[j] - a;
    if (d.squaredNorm() == 0.0) return {segment_error(points_, i, j, norm_), -1};
    const double bound = beyond_squared(limit * limit * d.squaredNorm());
    int farthest = i + 1;
    double largest = -1.0;
    for (int k = i + 1; k < j; ++k) {
      const double s = (points_[k] - a).cross(d).squaredNorm();
      if (s > largest) {
        largest = s;
        farthest = k;
        if (s > bound) break;
      }
    }
    const double error = ChordDistance(a, points_[j])(points_[farthest]);  // as segment_error() measures it
    return {error, error > limit ? farthest : -1};
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

  // For build_rows: the stored value of chord (i, j): kBeyond if it exceeds limit (found by a
  // point beyond limit, tried first `hint`), kBelow if it is certainly below floor, else a
  // placeholder queued for measuring (the squared cross product of the farthest point and
  // |p_j - p_i|^2). Degenerate, long and L2 chords are measured at once.
  RowEntry hinted_scan(int i, int j, const Thresholds& t, int hint) {
    const PointColumns& c = *columns_;
    const double dx = c.x[j] - c.x[i], dy = c.y[j] - c.y[i], dz = c.z[j] - c.z[i];
    const double length2 = (dx * dx + dy * dy) + dz * dz;  // = (p_j - p_i).squaredNorm()
    if (norm_ != Norm::LInf || length2 == 0.0 || j - i > kRowTreeSpan) {
      const ChordError measured = hinted_error(i, j, t.limit, hint);
      return {.value = measured.error,
              .beyond = measured.error > t.limit,
              .violator = measured.violator,
              .work = std::min(j - i, kRowTreeSpan)};
    }
    const double bound = t.beyond2 * length2 + kUnderflowMargin;
    if (hint > i && hint < j && cross2_to(c, i, hint, dx, dy, dz) > bound)
      return {.value = kBeyond, .beyond = true, .violator = hint, .work = 0};
    const ChordScan scan = planar_ ? scan_chord_planar(c, i, j, bound) : scan_chord(c, i, j, bound);
    const int work = scan.beyond >= 0 ? scan.beyond - i : j - i;
    if (scan.beyond >= 0) return {.value = kBeyond, .beyond = true, .violator = scan.beyond, .work = work};
    // below floor for certain: sqrt(cross2) / sqrt(length2) < floor
    if (scan.cross2 < t.below2 * length2) return {.value = kBelow, .beyond = false, .violator = -1, .work = work};
    return {.value = 0.0,
            .beyond = false,
            .violator = -1,
            .work = work,
            .queued = true,
            .cross2 = scan.cross2,
            .length2 = length2};
  }

  // bounded_error(i, j, limit), but first against point `hint` (if inside the chord; it stays
  // the violator if it is beyond the limit).
  ChordError hinted_error(int i, int j, double limit, int hint) {
    if (norm_ == Norm::LInf && hint > i && hint < j) {
      const Eigen::Vector3d d = points_[j] - points_[i];
      const double s = (points_[hint] - points_[i]).cross(d).squaredNorm();
      if (s > beyond_squared(limit * limit * d.squaredNorm()) && d.squaredNorm() > 0.0)
        return {ChordDistance(points_[i], points_[j])(points_[hint]), hint};
    }
    if (j - i > kRowTreeSpan) return {tree().error(i, j, limit), -1};
    return bounded_error(i, j, limit);
  }

  // For store_errors: short chords directly; long ones first against kSpreadProbes evenly spread points
  // (rejects most infeasible chords, also where the tree's bounds are weak, e.g. scattered
  // points), then through the tree.
  double stored_error(int i, int j, double limit) {
    if (j - i <= kDirectSpan) return bounded_error(i, j, limit).error;
    if (norm_ == Norm::LInf && limit < std::numeric_limits<double>::infinity()) {
      const ChordDistance distance(points_[i], points_[j]);
      for (int t = 1; t <= kSpreadProbes; ++t) {
        const int k = i + static_cast<int>((static_cast<long long>(j - i) * t) / (kSpreadProbes + 1));
        if (const double d = distance(points_[k]); d > limit) return d;
      }
    }
    return tree().error(i, j, limit);
  }

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

  // The projection plane at p_i: u along the first chord, v across it towards the second (the
  // discrete osculating plane), or within the curve's plane for planar data.
  Plane plane(int i, int last) const {
    const Eigen::Vector3d& origin = points_[i];
    const Eigen::Vector3d first = points_[std::min(i + 1, last)] - origin;
    Eigen::Vector3d u = first.norm() > 0.0 ? Eigen::Vector3d(first.normalized()) : Eigen::Vector3d(1, 0, 0);
    if (planar_) {
      if (u.z() != 0.0) u = Eigen::Vector3d(1, 0, 0);
      return {u, Eigen::Vector3d(-u.y(), u.x(), 0.0)};
    }
    const Eigen::Vector3d second = points_[std::min(i + 2, last)] - origin;
    const Eigen::Vector3d across = second - u * second.dot(u);
    const Eigen::Vector3d v =
        across.norm() > kStraightRatio * second.norm() && across.norm() > 0.0
            ? Eigen::Vector3d(across.normalized())
            : (std::abs(u.x()) < 0.9 ? Eigen::Vector3d(1, 0, 0) : Eigen::Vector3d(0, 1, 0)).cross(u).normalized();
    return {u, v};
  }

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
  int cone_reach(int i, int last, double eps) const {
    const Eigen::Vector3d& origin = points_[i];
    if (i + 1 > last) return last;
    const auto [u, v] = plane(i, last);
    double low = -std::numeric_limits<double>::infinity(), high = std::numeric_limits<double>::infinity();
    for (int k = i + 1; k <= last; k += std::max(1, (k - i) / kConeSamples)) {
      const Eigen::Vector3d w = points_[k] - origin;
      const double x = w.dot(u), y = w.dot(v);
      if (!(x > 2.0 * eps)) continue;  // behind or too near: no constraint (sound)
      const double denominator = x * x - eps * eps;
      const double root = eps * std::sqrt(std::max(0.0, x * x + y * y - eps * eps));
      low = std::max(low, (x * y - root) / denominator);
      high = std::min(high, (x * y + root) / denominator);
      if (low > high + kRelativeMargin * (1.0 + std::abs(low) + std::abs(high))) return k;
    }
    return last;
  }

  // Necessary condition for chord (i, j) within eps, in O(1) per chord: projected to the plane
  // of cone_reach, the chord's slope y_j / x_j must lie in the slope interval of every sampled
  // interior point (the intervals are exact mathematics; the test keeps a safety margin, so it
  // only rejects chords the exact test would reject as well).
  void build_slope_filter(int i, int last, double eps) {
    filter_ = plane(i, last);
    checkpoints_.clear();
    double low = -std::numeric_limits<double>::infinity(), high = std::numeric_limits<double>::infinity();
    const Eigen::Vector3d& origin = points_[i];
    for (int k = i + 1; k <= last; k += std::max(1, (k - i) / kSlopeFilterSamples)) {
      const Eigen::Vector3d w = points_[k] - origin;
      const double x = w.dot(filter_.u), y = w.dot(filter_.v);
      if (!(x > 2.0 * eps)) continue;
      const double denominator = x * x - eps * eps;
      const double root = eps * std::sqrt(std::max(0.0, x * x + y * y - eps * eps));
      low = std::max(low, (x * y - root) / denominator);
      high = std::min(high, (x * y + root) / denominator);
      checkpoints_.push_back({k, low, high});
    }
    checkpoint_at_ = 0;
  }

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

  // Certificate for "exactly m": `path` (positions) with segments split into two within eps until
  // it has m, or nullopt if that fails (within a work budget).
  std::optional<std::vector<int>> split_to(std::vector<int> path, double eps, int m) {
    long long budget = 8LL * count() + 64LL * m;
    std::size_t e = 0;
    while (static_cast<int>(path.size()) - 1 < m) {
      if (e + 1 >= path.size()) return std::nullopt;
      const int a = path[e], b = path[e + 1];
      bool split = false;
      if (b - a >= 2) {
        const int mid = a + (b - a) / 2;
        const int first[3] = {b - 1, a + 1, mid};
        for (int t = 0; t < 3 + (b - a - 1) && !split; ++t) {
          const int c = t < 3 ? first[t] : a + 1 + (t - 3);
          if (c <= a || c >= b) continue;
          if ((budget -= 2) < 0) return std::nullopt;
          if (c <= reach_[a] && c >= 0 && b <= reach_[c] && test(a, c, eps) && test(c, b, eps)) {
            path.insert(path.begin() + static_cast<std::ptrdiff_t>(e) + 1, c);
            split = true;
          }
        }
      }
      if (!split) ++e;  // after a split, try the new first half again
    }
    return path;
  }

  // Exact: S[b] = set of segment counts <= m with which position b is reachable.
  std::optional<std::vector<int>> bitset_path(double eps, int m) {
    const int count = this->count();
    const int words = (m + 1 + 63) / 64;
    std::vector<std::uint64_t> sets(static_cast<std::size_t>(count) * words, 0);
    auto set_of = [&](int a) { return sets.data() + static_cast<std::size_t>(a) * words; };
    const std::uint64_t top_mask = (m + 1) % 64 == 0 ? ~0ULL : ((1ULL << ((m + 1) % 64)) - 1);
    set_of(0)[0] = 1;
    std::vector<std::uint64_t> shifted(words);
    for (int a = 0; a + 1 < count; ++a) {
      const std::uint64_t* from = set_of(a);
      bool any = false;
      std::uint64_t carry = 0;
      for (int w = 0; w < words; ++w) {
        shifted[w] = (from[w] << 1) | carry;
        carry = from[w] >> 63;
        any = any || from[w] != 0;
      }
      shifted[words - 1] &= top_mask;
      if (!any) continue;
      for (int b = a + 1; b <= reach_[a]; ++b) {
        std::uint64_t* to = set_of(b);
        bool adds = false;
        for (int w = 0; w < words && !adds; ++w) adds = (shifted[w] & ~to[w]) != 0;
        if (!adds || !test(a, b, eps)) continue;
        for (int w = 0; w < words; ++w) to[w] |= shifted[w];
      }
    }
    auto has = [&](int a, int length) { return (set_of(a)[length / 64] >> (length % 64)) & 1ULL; };
    if (!has(count - 1, m)) return std::nullopt;
    std::vector<int> path{count - 1};
    for (int b = count - 1, length = m; b > 0; --length) {
      int chosen = -1;
      for (int a = b - 1; a >= 0 && chosen < 0; --a)
        if (reach_[a] >= b && has(a, length - 1) && test(a, b, eps)) chosen = a;
      b = chosen;  // exists: some predecessor set bit length-1 through a feasible edge
      path.push_back(b);
    }
    std::reverse(path.begin(), path.end());
    return path;
  }

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

}  // namespace

class FeasibilitySolver::Impl : public Solver {
  using Solver::Solver;
};

FeasibilitySolver::FeasibilitySolver(const std::vector<Eigen::Vector3d>& points, Norm norm, std::vector<int> vertices,
                                     const SegmentErrorTree* shared_tree)
    : impl_(std::make_unique<Impl>(points, norm, std::move(vertices), shared_tree)) {}
FeasibilitySolver::~FeasibilitySolver() = default;

int FeasibilitySolver::count() const { return impl_->count(); }
const std::vector<int>& FeasibilitySolver::vertices() const { return impl_->vertices(); }
double FeasibilitySolver::error(int a, int b) { return impl_->error(a, b); }
long long FeasibilitySolver::edge_count() const { return impl_->edge_count(); }
double FeasibilitySolver::evaluation_cost() const { return impl_->evaluation_cost(); }
void FeasibilitySolver::store_errors(double limit) { impl_->store_errors(limit); }
const std::vector<double>& FeasibilitySolver::stored_errors() const { return impl_->stored_errors(); }
bool FeasibilitySolver::build_rows(double limit, double budget, double floor) {
  return impl_->build_rows(limit, budget, floor);
}
double FeasibilitySolver::floor() const { return impl_->floor(); }
void FeasibilitySolver::materialize() { impl_->materialize(); }
long long FeasibilitySolver::tests() const { return impl_->tests(); }
void FeasibilitySolver::prune_reach(double eps) { impl_->prune_reach(eps); }
double FeasibilitySolver::reach_eps() const { return impl_->reach_eps(); }
void FeasibilitySolver::min_count(double eps) { impl_->min_count(eps); }
int FeasibilitySolver::min_segments() const { return impl_->min_segments(); }
std::vector<int> FeasibilitySolver::min_path() const { return impl_->min_path(); }
ExactPath FeasibilitySolver::exact_path(double eps, int m) { return impl_->exact_path(eps, m); }
std::vector<int> FeasibilitySolver::indices(const std::vector<int>& path) const { return impl_->indices(path); }

}  // namespace sculpt::curves::detail
