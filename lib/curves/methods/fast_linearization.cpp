#include "curves/methods/fast_linearization.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <numeric>

#include "curves/optimal/optimal_linearization.hpp"
#include "curves/optimal/segment_error_tree.hpp"

namespace sculpt::curves::detail {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

struct LayeredPass {
  std::vector<int> breaks;  // the new break points
  double error;             // their error
  bool moved_to_edge;       // some break point chose the outermost candidate of its window
};

// One refinement pass: break point k (1..m-1) chooses among q[k] + j * step, |j| <= half.
// Exact min-max path through the layers.
LayeredPass layered_pass(const SegmentErrorTree& tree, const std::vector<int>& q, int step, int half) {
  const int m = static_cast<int>(q.size()) - 1;
  const int last = q.back();
  std::vector<std::vector<int>> layers(m + 1);
  layers[0] = {0};
  layers[m] = {last};
  for (int k = 1; k < m; ++k)
    for (int j = -half; j <= half; ++j) {
      const int v = q[k] + j * step;
      if (v > 0 && v < last) layers[k].push_back(v);
    }
  std::vector<std::vector<double>> best(m + 1);
  std::vector<std::vector<int>> from(m + 1);
  best[0] = {0.0};
  from[0] = {-1};
  std::vector<int> order;
  for (int k = 0; k < m; ++k) {
    const std::vector<int>& left = layers[k];
    const std::vector<int>& right = layers[k + 1];
    order.resize(left.size());
    std::iota(order.begin(), order.end(), 0);
    std::sort(order.begin(), order.end(), [&](int a, int b) { return best[k][a] < best[k][b]; });
    best[k + 1].assign(right.size(), kInf);
    from[k + 1].assign(right.size(), -1);
    for (std::size_t r = 0; r < right.size(); ++r) {
      double& target = best[k + 1][r];
      for (int l : order) {
        if (best[k][l] >= target) break;  // sorted: no later u can improve
        if (left[l] >= right[r]) continue;
        const double e = tree.error(left[l], right[r], target);  // exact when < target
        const double value = std::max(best[k][l], e);
        if (value < target) {
          target = value;
          from[k + 1][r] = l;
        }
      }
    }
  }
  std::vector<int> result(m + 1);
  int at = 0;
  for (int k = m; k >= 0; --k) {
    result[k] = layers[k][at];
    at = from[k][at];
  }
  bool moved_to_edge = false;
  for (int k = 1; k < m; ++k) moved_to_edge = moved_to_edge || std::abs(result[k] - q[k]) == half * step;
  return {std::move(result), best[m][0], moved_to_edge};
}


// Greedy cover at tolerance eps: from each break point, the farthest end found by galloping and
// binary search on "error <= eps" (exact for errors monotone in the end point, which sampled
// smooth curves nearly are; always a valid cover since every accepted chord is tested).
// Returns the break points, or an empty vector if more than `limit` segments are needed.
std::vector<int> greedy_cover(const SegmentErrorTree& tree, int last, double eps, int limit, int guess) {
  std::vector<int> q{0};
  int a = 0;
  while (a < last) {
    if (static_cast<int>(q.size()) > limit) return {};
    int good = a + 1, bad = -1;  // chord (a, good) is within eps; (a, bad) is not
    int probe = std::min(last, a + std::max(1, guess));
    while (true) {
      if (tree.within(a, probe, eps)) {
        good = probe;
        if (probe == last) break;
        probe = std::min(last, a + 2 * (probe - a));
      } else {
        bad = probe;
        break;
      }
    }
    if (bad > 0)
      while (bad - good > 1) {
        const int mid = good + (bad - good) / 2;
        (tree.within(a, mid, eps) ? good : bad) = mid;
      }
    guess = good - a;
    q.push_back(good);
    a = good;
  }
  return q;
}

}  // namespace

Linearization fast_linearization(const std::vector<Eigen::Vector3d>& points, int m, Norm norm,
                                 const FastOptions& options) {
  const int n = static_cast<int>(points.size());
  const int last = n - 1;
  if (n <= options.exact_below) return optimal_min_error(points, m, norm);
  const bool debug = std::getenv("SCULPT_CURVES_DEBUG") != nullptr;
  auto clock = std::chrono::steady_clock::now();
  const auto lap = [&](const char* what, double error) {
    if (!debug) return;
    const auto now = std::chrono::steady_clock::now();
    std::fprintf(stderr, "fast: %s %.1f ms, error %.9g\n", what,
                 std::chrono::duration<double, std::milli>(now - clock).count(), error);
    clock = now;
  };
  const SegmentErrorTree tree(points, norm);
  lap("tree", 0.0);

  // Stage 1: the smallest tolerance (bisected in log space) whose greedy cover needs <= m
  // segments, starting from break points spread evenly.
  std::vector<int> q(m + 1);
  for (int k = 0; k <= m; ++k) q[k] = static_cast<int>((static_cast<long long>(k) * last) / m);
  double error = approximation_error(points, q, norm);
  double lo = 0.0, hi = error;
  for (int iteration = 0; iteration < options.bisection_steps && hi > 0.0; ++iteration) {
    const double eps = lo > 0.0 ? std::sqrt(lo * hi) : 0.125 * hi;
    std::vector<int> cover = greedy_cover(tree, last, eps, m, std::max(1, last / m));
    if (cover.empty()) {
      lo = eps;
      continue;
    }
    // Exactly m: split the worst segments at their middle (a max-heap of segment errors).
    if (static_cast<int>(cover.size()) - 1 < m) {
      std::vector<std::pair<double, std::pair<int, int>>> heap;
      for (std::size_t k = 0; k + 1 < cover.size(); ++k)
        heap.push_back({cover[k + 1] - cover[k] >= 2 ? tree.error(cover[k], cover[k + 1]) : -1.0, {cover[k], cover[k + 1]}});
      std::make_heap(heap.begin(), heap.end());
      for (int segments = static_cast<int>(cover.size()) - 1; segments < m; ++segments) {
        std::pop_heap(heap.begin(), heap.end());
        const auto [a, b] = heap.back().second;
        heap.pop_back();
        const int mid = a + (b - a) / 2;  // b - a >= 2: some segment is splittable while segments < last
        cover.push_back(mid);
        for (const auto& [x, y] : {std::pair{a, mid}, std::pair{mid, b}}) {
          heap.push_back({y - x >= 2 ? tree.error(x, y) : -1.0, {x, y}});
          std::push_heap(heap.begin(), heap.end());
        }
      }
      std::sort(cover.begin(), cover.end());
    }
    const double cover_error = approximation_error(points, cover, norm);
    hi = eps;
    if (cover_error < error) {
      error = cover_error;
      q = std::move(cover);
    }
  }
  lap("greedy", error);

  // For few segments (cheap, and where greedy covers are weakest): the exact optimum over every
  // stride-th point, refined with halving steps; keep whichever is better.
  if (m <= options.ladder_max_segments) {
    const int stride = std::max(1, last / std::max(options.min_candidates, options.candidates_per_segment * m));
    std::vector<int> coarse;
    for (int k = 0; k < last; k += stride) coarse.push_back(k);
    coarse.push_back(last);
    const Linearization start = optimal_min_error(points, m, norm, {.vertices = coarse, .start = {}, .tree = &tree});
    std::vector<int> r = start.indices;
    double r_error = start.error;
    for (int step = std::max(1, stride / 2); step > 1; step /= 2)
      for (int pass = 0; pass < 2; ++pass) {
        LayeredPass next = layered_pass(tree, r, step, 2);
        if (next.error <= r_error) {
          r = std::move(next.breaks);
          r_error = next.error;
        }
        if (!next.moved_to_edge) break;
      }
    if (r_error < error) {
      q = std::move(r);
      error = r_error;
    }
    lap("coarse ladder", error);
  }

  // Stage 2: layered refinement at step 1.
  int passes = 0;
  for (int pass = 0; pass < options.max_passes_at_step_one; ++pass) {
    LayeredPass next = layered_pass(tree, q, 1, 2);
    ++passes;
    if (next.error <= error) {  // the old q is a candidate, so this always holds
      q = std::move(next.breaks);
      error = next.error;
    }
    if (!next.moved_to_edge) break;
  }
  lap("passes", error);
  Linearization result;
  result.indices = std::move(q);
  result.error = approximation_error(points, result.indices, norm) ;
  result.iterations = passes;
  return result;
}

}  // namespace sculpt::curves::detail
