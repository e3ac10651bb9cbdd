#include "curves/fast_linearization.hpp"

#include <algorithm>

#include "curves/optimal_linearization.hpp"

namespace sculpt::curves {
namespace {

// {0, last} plus, around every break point b, b itself and b + k * stride within +-window.
std::vector<int> windows(const std::vector<int>& breaks, int last, int window, int stride) {
  std::vector<int> v{0, last};
  for (int b : breaks) {
    v.push_back(b);
    for (int d = stride; d <= window; d += stride) {
      if (b - d > 0) v.push_back(b - d);
      if (b + d < last) v.push_back(b + d);
    }
  }
  std::sort(v.begin(), v.end());
  v.erase(std::unique(v.begin(), v.end()), v.end());
  return v;
}

}  // namespace

Linearization fast_linearization(const std::vector<Eigen::Vector3d>& points, int m, Norm norm,
                                 const FastOptions& options) {
  const int n = static_cast<int>(points.size());
  const int last = n - 1;
  if (n <= options.exact_below) return optimal_min_error(points, m, norm);

  // Stage 1: every stride-th point (at least m + 1 candidates).
  int stride = std::max(1, last / std::max(1, options.candidates_per_segment * m));
  std::vector<int> coarse;
  for (int k = 0; k < last; k += stride) coarse.push_back(k);
  coarse.push_back(last);
  Linearization current = optimal_min_error(points, m, norm, {.vertices = coarse, .start = {}});
  int probes = current.iterations;

  // Stage 2 and 3: refine in windows around the current break points.
  while (true) {
    const bool final_pass = stride == 1;
    const int window = final_pass ? options.final_window : stride;
    stride = final_pass ? 1 : std::max(1, stride / 8);
    const std::vector<int> allowed = windows(current.indices, last, window, stride);
    Linearization next = optimal_min_error(points, m, norm, {.vertices = allowed, .start = current.indices});
    probes += next.iterations;
    current = std::move(next);
    if (final_pass) break;
  }
  current.iterations = probes;
  return current;
}

}  // namespace sculpt::curves
