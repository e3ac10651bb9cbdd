#include "curves/optimal_linearization.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <optional>

#include "curves/segment_error_tree.hpp"

namespace sculpt::curves {
namespace {

constexpr int kUnreached = std::numeric_limits<int>::max();

// Shortest paths over the allowed vertices; positions 0..K-1 index `vertex_`.
class FeasibilitySolver {
 public:
  FeasibilitySolver(const std::vector<Eigen::Vector3d>& points, Norm norm, std::vector<int> vertices)
      : points_(points), tree_(points, norm), vertex_(std::move(vertices)) {
    const int count = static_cast<int>(vertex_.size());
    reach_.assign(count, count - 1);
    hint_.assign(count, -1);
  }

  [[nodiscard]] int count() const { return static_cast<int>(vertex_.size()); }
  [[nodiscard]] const std::vector<int>& vertices() const { return vertex_; }
  [[nodiscard]] double error(int a, int b) const { return tree_.error(vertex_[a], vertex_[b]); }
  [[nodiscard]] long long tests() const { return tests_; }

  /// Bounds every position's reach for tolerances <= eps by cone pruning.
  void prune_reach(double eps) {
    const int count = this->count();
    const int last = vertex_.back();
    for (int a = 0; a + 1 < count; ++a) {
      const int reach_index = cone_reach(vertex_[a], last, eps);
      reach_[a] = static_cast<int>(std::upper_bound(vertex_.begin(), vertex_.end(), reach_index) - vertex_.begin()) - 1;
    }
    reach_eps_ = eps;
  }
  [[nodiscard]] double reach_eps() const { return reach_eps_; }

  /// Fewest segments to every position at tolerance eps (DAG relaxation in index order; an edge
  /// is tested only if it would improve its end). Fills dist_/pred_.
  void min_count(double eps) {
    const int count = this->count();
    dist_.assign(count, kUnreached);
    pred_.assign(count, -1);
    dist_[0] = 0;
    for (int a = 0; a + 1 < count; ++a) {
      if (dist_[a] == kUnreached) continue;
      const int next = dist_[a] + 1;
      for (int b = a + 1; b <= reach_[a]; ++b) {
        if (dist_[b] <= next) continue;
        if (test(a, b, eps)) {
          dist_[b] = next;
          pred_[b] = a;
        }
      }
    }
  }
  [[nodiscard]] int min_segments() const { return dist_.back(); }
  [[nodiscard]] std::vector<int> min_path() const {
    std::vector<int> path;
    for (int b = count() - 1; b >= 0; b = pred_[b]) {
      path.push_back(b);
      if (b == 0) break;
    }
    std::reverse(path.begin(), path.end());
    return path;
  }

  /// A path of exactly m edges with every edge within eps, or nullopt if none exists.
  std::optional<std::vector<int>> exact_path(double eps, int m) {
    min_count(eps);
    if (dist_.back() > m) return std::nullopt;
    std::vector<int> path = min_path();
    if (split_to(path, eps, m)) return path;
    return bitset_path(eps, m);
  }

  /// Indices of a position path.
  [[nodiscard]] std::vector<int> indices(const std::vector<int>& path) const {
    std::vector<int> result;
    result.reserve(path.size());
    for (int a : path) result.push_back(vertex_[a]);
    return result;
  }

 private:
  bool test(int a, int b, double eps) {
    ++tests_;
    int violator = -1;
    const bool ok = tree_.within(vertex_[a], vertex_[b], eps, hint_[b], &violator);
    if (!ok && violator >= 0) hint_[b] = violator;
    return ok;
  }

  // Largest index j such that chord (i, j) may have error <= eps: scan k > i and stop at the
  // first point whose cone is disjoint from the narrowest cone so far (then every chord
  // reaching beyond k has one of the two points farther than eps from its line).
  int cone_reach(int i, int last, double eps) const {
    const Eigen::Vector3d& origin = points_[i];
    Eigen::Vector3d narrow_axis = Eigen::Vector3d::Zero();
    double narrow_half = 10.0;  // no cone yet
    for (int k = i + 1; k <= last; ++k) {
      const Eigen::Vector3d w = points_[k] - origin;
      const double r = w.norm();
      if (!(r > eps * (1.0 + 1e-9))) continue;  // the point constrains nothing
      const double half = std::asin(std::min(1.0, eps / r));
      const Eigen::Vector3d axis = w / r;
      if (narrow_half < 10.0) {
        const double angle = std::atan2(axis.cross(narrow_axis).norm(), std::abs(axis.dot(narrow_axis)));
        if (angle > half + narrow_half + 1e-7) return k;
      }
      if (half < narrow_half) {
        narrow_half = half;
        narrow_axis = axis;
      }
    }
    return last;
  }

  // Certificate for "exactly m": split segments of `path` (positions) into two within eps.
  bool split_to(std::vector<int>& path, double eps, int m) {
    long long budget = 8LL * count() + 64LL * m;
    std::size_t e = 0;
    while (static_cast<int>(path.size()) - 1 < m) {
      if (e + 1 >= path.size()) return false;
      const int a = path[e], b = path[e + 1];
      bool split = false;
      if (b - a >= 2) {
        const int mid = a + (b - a) / 2;
        const int first[3] = {b - 1, a + 1, mid};
        for (int t = 0; t < 3 + (b - a - 1) && !split; ++t) {
          const int c = t < 3 ? first[t] : a + 1 + (t - 3);
          if (c <= a || c >= b) continue;
          if ((budget -= 2) < 0) return false;
          if (c <= reach_[a] && c >= 0 && b <= reach_[c] && test(a, c, eps) && test(c, b, eps)) {
            path.insert(path.begin() + static_cast<std::ptrdiff_t>(e) + 1, c);
            split = true;
          }
        }
      }
      if (!split) ++e;  // after a split, try the new first half again
    }
    return true;
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
  SegmentErrorTree tree_;
  std::vector<int> vertex_;
  std::vector<int> reach_, hint_, dist_, pred_;
  double reach_eps_ = std::numeric_limits<double>::infinity();
  long long tests_ = 0;
};

std::vector<int> all_vertices(int n) {
  std::vector<int> v(n);
  for (int k = 0; k < n; ++k) v[k] = k;
  return v;
}

double path_error(const FeasibilitySolver& solver, const std::vector<int>& path) {
  double e = 0.0;
  for (std::size_t k = 0; k + 1 < path.size(); ++k) e = std::max(e, solver.error(path[k], path[k + 1]));
  return e;
}

// The next tolerance to probe strictly between lo (infeasible, -1 = none known) and hi
// (feasible): halving while lo is unknown (0 itself once hi is tiny), value bisection while the
// bounds are far apart, then bisection of the bit patterns (ordered like non-negative values),
// so the search ends after at most 64 further probes. nullopt: no double lies in between.
std::optional<double> middle(double lo, double hi, double first_hi) {
  if (lo < 0.0) {
    if (hi <= 0.0) return std::nullopt;
    return hi < 1e-9 * first_hi ? 0.0 : 0.5 * hi;
  }
  if (hi > 2.0 * lo) {
    const double mid = lo + 0.5 * (hi - lo);
    if (mid > lo && mid < hi) return mid;
  }
  std::uint64_t l, h;
  std::memcpy(&l, &lo, sizeof l);
  std::memcpy(&h, &hi, sizeof h);
  if (h <= l + 1) return std::nullopt;
  const std::uint64_t bits = l + (h - l) / 2;
  double value;
  std::memcpy(&value, &bits, sizeof value);
  return value;
}

}  // namespace

Linearization optimal_min_error(const std::vector<Eigen::Vector3d>& points, int m, Norm norm,
                                const OptimalOptions& options) {
  const int n = static_cast<int>(points.size());
  FeasibilitySolver solver(points, norm, options.vertices.empty() ? all_vertices(n) : options.vertices);
  const int count = solver.count();
  // Upper bound: the given start, or break points spread evenly over the allowed vertices.
  std::vector<int> best;
  if (!options.start.empty()) {
    const std::vector<int>& allowed = solver.vertices();
    for (int index : options.start)
      best.push_back(static_cast<int>(std::lower_bound(allowed.begin(), allowed.end(), index) - allowed.begin()));
  } else {
    for (int s = 0; s <= m; ++s) best.push_back(static_cast<int>((static_cast<long long>(s) * (count - 1)) / m));
  }
  double hi = path_error(solver, best);
  const double first_hi = hi;
  double lo = -1.0;  // largest tolerance known infeasible; -1 = none yet
  solver.prune_reach(hi);
  int probes = 0;
  while (const std::optional<double> eps = middle(lo, hi, first_hi)) {
    ++probes;
    if (std::optional<std::vector<int>> path = solver.exact_path(*eps, m)) {
      best = std::move(*path);
      hi = path_error(solver, best);  // <= eps: jump to the error actually reached
      if (hi < 0.6 * solver.reach_eps()) solver.prune_reach(hi);
    } else {
      lo = *eps;
    }
  }
  Linearization result;
  result.indices = solver.indices(best);
  result.error = hi;
  result.iterations = probes;
  return result;
}

Linearization optimal_min_count(const std::vector<Eigen::Vector3d>& points, double tolerance, Norm norm) {
  FeasibilitySolver solver(points, norm, all_vertices(static_cast<int>(points.size())));
  solver.prune_reach(tolerance);
  solver.min_count(tolerance);
  const std::vector<int> path = solver.min_path();
  Linearization result;
  result.indices = solver.indices(path);
  result.error = path_error(solver, path);
  return result;
}

}  // namespace sculpt::curves
