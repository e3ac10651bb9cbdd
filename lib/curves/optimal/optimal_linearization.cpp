#include "curves/optimal/optimal_linearization.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <optional>
#include <utility>

#include "curves/curve_measures.hpp"
#include "curves/methods/heuristic_subdivision.hpp"
#include "curves/optimal/feasibility_solver.hpp"

namespace sculpt::curves::detail {
namespace {

// Up to this many candidate edges the solver computes all their errors once (stored mode).
// (memory: 8 bytes each), if evaluating them directly costs at most this many point distances.
constexpr long long kStoredEdgeLimit = 4'000'000;
constexpr double kStoredCostLimit = 3e8;
// First reach cap as a fraction of the start's error (INIT is usually within 2x of the optimum,
// and a cap that turns out infeasible costs a second pruning pass).
constexpr double kFirstCap = 1.0;
// Inputs up to this many allowed vertices and this many per segment on average build their
// stored rows in one pass (build_rows: full scans, fast for short chords), if that takes at most
// kSmallBudget point distances (else the general path, whose tree answers long chords).
constexpr int kSmallCount = 20000;
constexpr int kSmallSpan = 64;
// build_rows' first cap: this factor times the estimate of the optimum from the start's errors.
constexpr double kCapMargin = 1.25;
// ... and its floor (errors below are not measured, only known to be below) this fraction of it.
constexpr double kFloorFraction = 0.75;
constexpr double kSmallBudget = 6e7;
// Stored mode: guesses by the 1 / k^2 scaling before the binary search; the first guess as a
// fraction of the start's error (INIT is within 1.0-1.7x of the optimum on the Appendix-B curves).
constexpr int kGuesses = 4;
constexpr double kFirstGuess = 1.0;
// Streaming bisection with no infeasible tolerance known yet: halving, until hi falls below this
// fraction of the start's error; then 0 itself is probed.
constexpr double kZeroProbeFraction = 1e-9;

std::vector<int> all_vertices(int n) {
  std::vector<int> v(n);
  for (int k = 0; k < n; ++k) v[k] = k;
  return v;
}

double path_error(FeasibilitySolver& solver, const std::vector<int>& path) {
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
    return hi < kZeroProbeFraction * first_hi ? 0.0 : 0.5 * hi;
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

// Upper bound: the given start, else for large inputs INIT (alpha = 1/2, Alg. 4.3), else break
// points spread evenly over the allowed vertices (small inputs only need the estimate of the
// optimum below, which is as good from these and costs no tangents). Positions, not indices.
std::vector<int> start_path(const std::vector<Eigen::Vector3d>& points, const FeasibilitySolver& solver, int m,
                            Norm norm, const OptimalOptions& options, bool small_input) {
  std::vector<int> best;
  const std::vector<int>& allowed = solver.vertices();
  if (!options.start.empty()) {
    for (int index : options.start)
      best.push_back(static_cast<int>(std::lower_bound(allowed.begin(), allowed.end(), index) - allowed.begin()));
  } else if (options.vertices.empty() && !small_input) {
    DigitizedCurve open;
    open.points = points;
    best = weighted_subdivision(points, CurveMeasures(open), m, 0.5, norm).indices;
  } else {
    const int count = solver.count();
    for (int s = 0; s <= m; ++s) best.push_back(static_cast<int>((static_cast<long long>(s) * (count - 1)) / m));
  }
  return best;
}

struct Probe {
  double eps;
  int segments;  // fewest segments within eps (0 = no such probe yet)
};

// The search for the optimum of Problem 1 (sec. 2): lo < optimum <= hi, with the best path so far.
struct Search {
  FeasibilitySolver& solver;
  int m;
  std::vector<int> best;  // positions; its error is hi
  double hi = 0.0, first_hi = 0.0;
  double lo = -1.0;  // largest tolerance known infeasible; -1 = none yet
  int probes = 0;
  bool debug = std::getenv("SCULPT_CURVES_DEBUG") != nullptr;
  Probe last{0.0, 0}, feasible{0.0, 0}, infeasible{0.0, 0};

  // Is there a path of exactly m segments within eps? Updates the bounds and the best path.
  bool probe(double eps) {
    ++probes;
    const long long before = solver.tests();
    if (eps < solver.floor()) solver.materialize();
    auto [path, optimal] = solver.exact_path(eps, m);
    last = {eps, solver.min_segments()};
    (path ? feasible : infeasible) = last;
    if (debug)
      std::fprintf(stderr, "probe %d eps %.17g feasible %d optimal %d tests %lld minseg %d\n", probes, eps,
                   path.has_value(), optimal, solver.tests() - before, solver.min_segments());
    if (path) {
      best = std::move(*path);
      hi = path_error(solver, best);  // <= eps: jump to the error actually reached
      if (optimal) lo = std::nextafter(hi, 0.0);  // nothing below hi is feasible: done
    } else {
      lo = std::max(lo, eps);
    }
    return path.has_value();
  }

  // After an infeasible cap needing k > m segments the next cap grows by (k / m)^2 (errors of
  // smooth curves scale with the square of the segment length), at least by 1.25.
  [[nodiscard]] double next_cap(double cap) const {
    const double ratio = static_cast<double>(solver.min_segments()) / m;
    return std::min(hi, cap * std::clamp(1.05 * ratio * ratio, 1.25, 4.0));
  }
};

// Small inputs: rows and errors in one pass (build_rows) under a cap from the start's segment
// errors e_s: on a smooth curve a segment's error grows like its length squared, so segments
// within eps number about sum_s sqrt(e_s / eps), and the optimum for m is near
// (sum_s sqrt(e_s) / m)^2. The cap is a margin above that (never above the start's error);
// a probe at the cap that fails raises it and builds again. False: over the work budget.
bool build_small_rows(Search& search, const std::vector<double>& start_errors) {
  FeasibilitySolver& solver = search.solver;
  const int count = solver.count(), m = search.m;
  double root_sum = 0.0;
  for (double e : start_errors) root_sum += std::sqrt(e);
  const double estimate = (root_sum / m) * (root_sum / m);  // <= hi (power means)
  double cap = std::min(search.hi, kCapMargin * estimate);
  // Work budget per row: smooth curves need about (1.3 n / m)^2 / 2 point distances a row;
  // data without smoothness (rows that never end) gives up early and takes the general path.
  const double span = static_cast<double>(count) / m;
  const double budget = std::min(kSmallBudget / count, 2.5e4 + 16.0 * span * span);
  for (;;) {
    const bool small = solver.build_rows(cap, budget, kFloorFraction * estimate);
    if (search.debug)
      std::fprintf(stderr, "rows under %.6g (start %.6g): %lld candidate edges over %d vertices%s\n", cap, search.hi,
                   solver.edge_count(), count, small ? "" : ", over budget");
    if (!small || cap >= search.hi || search.probe(cap)) return small;
    cap = search.next_cap(cap);
  }
}

// The general path: the reach (and so the work per probe) grows with the tolerance, so caps
// start at kFirstCap times the start's error (a given start is usually near the optimum
// already: no guessing below it then) and grow until feasible; the last cap bounds every later
// probe. Then stores every candidate edge's error if that is affordable.
bool cap_reach(Search& search, const OptimalOptions& options) {
  FeasibilitySolver& solver = search.solver;
  for (double cap = options.start.empty() ? kFirstCap * search.hi : search.hi;;) {
    solver.prune_reach(cap);
    if (search.debug)
      std::fprintf(stderr, "cap %.6g of start %.6g: %lld candidate edges over %d vertices\n", cap, search.hi,
                   solver.edge_count(), solver.count());
    if (!options.streaming && solver.evaluation_cost() <= 1e6) solver.store_errors(cap);  // probe by lookups
    if (cap >= search.hi || cap <= search.lo || search.probe(cap)) break;
    cap = search.next_cap(cap);
  }
  const bool stored = !options.streaming && solver.edge_count() <= kStoredEdgeLimit &&
                      solver.evaluation_cost() <= kStoredCostLimit;
  if (stored && solver.stored_errors().empty()) solver.store_errors(search.hi);
  return stored;
}

// Stored mode, first a few guesses aimed at m - kWindow / 2 segments (a probe needing
// m - kWindow .. m segments ends the search). The segments needed at eps fall like eps^(-1/2) on
// smooth curves (a segment's error grows like its length squared, sec. 4): from a probe at eps
// needing k, the target is near eps (k / target)^2; between a feasible probe and an infeasible
// one, log eps is interpolated linearly in log k. A guess at or above hi probes just below hi
// (infeasible there = hi is optimal).
void guess(Search& search) {
  const double target = std::max(1.0, search.m - kWindow / 2.0);
  const auto next_guess = [&] {
    const Probe &feasible = search.feasible, &infeasible = search.infeasible, &last = search.last;
    if (feasible.segments > 0 && infeasible.segments > feasible.segments && feasible.eps > 0.0 &&
        infeasible.eps > 0.0) {
      const double t = std::clamp((std::log(infeasible.segments) - std::log(target)) /
                                      (std::log(infeasible.segments) - std::log(feasible.segments)),
                                  0.1, 0.9);
      return infeasible.eps * std::pow(feasible.eps / infeasible.eps, t);
    }
    if (last.segments <= 0 || last.segments == kUnreached) return kFirstGuess * search.hi;
    const double scale = last.segments / target;
    return last.eps * scale * scale;
  };
  for (int step = 0; step < kGuesses && search.lo < search.hi; ++step) {
    const double lo = search.lo, hi = search.hi;
    double eps = next_guess();
    if (!(eps < hi)) eps = std::nextafter(hi, 0.0);
    if (!(eps > lo)) eps = lo + 0.5 * (hi - lo);
    if (!(eps > lo && eps < hi)) break;
    search.probe(eps);
    if (search.last.segments == kUnreached) break;
  }
}

// Stored mode: the optimum is one of the stored edge errors in (lo, hi]. After the guesses, a
// binary search over the stored errors left in (lo, hi), by selection (nth_element); each probe
// is a DP over stored values.
void search_stored(Search& search) {
  guess(search);
  FeasibilitySolver& solver = search.solver;
  const double& lo = search.lo;
  const double& hi = search.hi;
  std::vector<double> candidates;
  if (lo < hi && std::nextafter(lo, hi) < hi) {  // else no double lies in between: done
    if (lo < solver.floor()) solver.materialize();
    for (double e : solver.stored_errors())
      if (e < hi && e > lo) candidates.push_back(e);
  }
  while (!candidates.empty()) {
    auto middle_it = candidates.begin() + static_cast<std::ptrdiff_t>(candidates.size() / 2);
    std::nth_element(candidates.begin(), middle_it, candidates.end());
    const double eps = *middle_it;
    if (search.probe(eps)) {
      candidates.erase(
          std::partition(candidates.begin(), candidates.end(), [&](double e) { return e < hi && e > lo; }),
          candidates.end());
    } else {
      candidates.erase(std::partition(candidates.begin(), candidates.end(), [&](double e) { return e > eps; }),
                       candidates.end());
    }
  }
}

// Streaming mode: bisect the tolerance itself; no double between the bounds = done.
void search_streaming(Search& search) {
  FeasibilitySolver& solver = search.solver;
  while (const std::optional<double> eps = middle(search.lo, search.hi, search.first_hi))
    if (search.probe(*eps) && search.hi < 0.6 * solver.reach_eps()) solver.prune_reach(search.hi);
}

}  // namespace

Linearization optimal_min_error(const std::vector<Eigen::Vector3d>& points, int m, Norm norm,
                                const OptimalOptions& options) {
  const int n = static_cast<int>(points.size());
  FeasibilitySolver solver(points, norm, options.vertices.empty() ? all_vertices(n) : options.vertices,
                           options.tree);
  const int count = solver.count();
  const bool small_input = !options.streaming && count <= kSmallCount && count <= static_cast<long long>(kSmallSpan) * m;
  Search search{.solver = solver, .m = m, .best = start_path(points, solver, m, norm, options, small_input)};
  const std::vector<int>& best = search.best;
  std::vector<double> start_errors(best.size() - 1);
  for (std::size_t k = 0; k + 1 < best.size(); ++k) start_errors[k] = solver.error(best[k], best[k + 1]);
  search.hi = search.first_hi = *std::max_element(start_errors.begin(), start_errors.end());
  const bool small = small_input && build_small_rows(search, start_errors);
  if (small || cap_reach(search, options))
    search_stored(search);
  else
    search_streaming(search);
  Linearization result;
  result.indices = solver.indices(search.best);
  result.error = search.hi;
  result.iterations = search.probes;
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

}  // namespace sculpt::curves::detail
