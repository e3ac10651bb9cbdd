// FeasibilitySolver: paths of exactly m segments within eps (Problem 1 of sec. 2): the best such
// path by a layered bottleneck DP (stored mode), or split segments of a min-# path, or a bitset DP.
#include "curves/optimal/feasibility_solver_impl.hpp"

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <optional>
#include <utility>
#include <vector>

namespace sculpt::curves::detail {

ExactPath FeasibilitySolver::Impl::exact_path(double eps, int m) {
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

std::optional<std::vector<int>> FeasibilitySolver::Impl::best_exact_path(double eps, int m) {
  const int count = this->count();
  const int width = m - dist_.back() + 1;
  relax_bottleneck(eps, width);
  best_bottleneck_ = bottleneck_[static_cast<std::size_t>(count) * width - 1];
  if (best_bottleneck_ == std::numeric_limits<double>::infinity()) return std::nullopt;
  return bottleneck_path(eps, width);
}

void FeasibilitySolver::Impl::relax_bottleneck(double eps, int width) {
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

std::vector<int> FeasibilitySolver::Impl::bottleneck_path(double eps, int width) const {
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

std::optional<std::vector<int>> FeasibilitySolver::Impl::split_to(std::vector<int> path, double eps, int m) {
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

std::optional<std::vector<int>> FeasibilitySolver::Impl::bitset_path(double eps, int m) {
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

}  // namespace sculpt::curves::detail
