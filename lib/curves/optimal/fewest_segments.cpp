// FeasibilitySolver: the fewest segments within eps (the first problem of sec. 2), by DAG
// relaxation over stored errors or breadth-first by layers with on-demand edge tests.
#include "base/cancel.hpp"
#include "curves/optimal/feasibility_solver_impl.hpp"

#include <algorithm>
#include <vector>

namespace sculpt::curves::detail {

void FeasibilitySolver::Impl::min_count(double eps) {
  const int count = this->count();
  dist_.assign(count, kUnreached);
  pred_.assign(count, -1);
  dist_[0] = 0;
  if (!stored_.empty())
    relax_stored(eps);
  else
    claim_layers(eps);
}

std::vector<int> FeasibilitySolver::Impl::min_path() const {
  std::vector<int> path;
  for (int b = count() - 1; b >= 0; b = pred_[b]) {
    path.push_back(b);
    if (b == 0) break;
  }
  std::reverse(path.begin(), path.end());
  return path;
}

void FeasibilitySolver::Impl::relax_stored(double eps) {
  const int count = this->count();
  CancelPoll poll;  // Ctrl-C (base/cancel.hpp)
  for (int a = 0; a + 1 < count; ++a) {
    poll.tick();
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

void FeasibilitySolver::Impl::claim_layers(double eps) {
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

}  // namespace sculpt::curves::detail
