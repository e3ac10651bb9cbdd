#include "curves/methods/heuristic_subdivision.hpp"

#include <algorithm>

namespace sculpt::curves::detail {

Linearization weighted_subdivision(const std::vector<Eigen::Vector3d>& points, const CurveMeasures& measures, int m,
                                   double alpha, Norm norm) {
  const int last = static_cast<int>(points.size()) - 1;
  // Weight prefix W[k] = alpha * chord(0,k) + (1 - alpha) * image(0,k), nondecreasing.
  std::vector<double> weight(points.size());
  for (int k = 0; k <= last; ++k)
    weight[k] = alpha * measures.chord_length(0, k) + (1.0 - alpha) * measures.image_length(0, k);
  const double segsum = weight[last] / m;
  Linearization result;
  result.indices.reserve(m + 1);
  result.indices.push_back(0);
  int q = 0;
  for (int i = 0; i < m - 1; ++i) {
    // Largest j with W(0, j) < (i + 1) segsum (Alg. 4.3 measured from the start, so that the
    // shortfall of each step does not pile up in the last segment), clamped to leave room.
    const auto it = std::lower_bound(weight.begin() + q, weight.end(), (i + 1) * segsum);
    int j = static_cast<int>(it - weight.begin()) - 1;
    j = std::clamp(j, q + 1, last - (m - 1 - i));
    result.indices.push_back(j);
    q = j;
  }
  result.indices.push_back(last);
  result.error = approximation_error(points, result.indices, norm);
  return result;
}

Linearization iterative_refinement(const std::vector<Eigen::Vector3d>& points, Linearization start, Norm norm,
                                   int max_iterations) {
  std::vector<int> q = start.indices;
  const int m = static_cast<int>(q.size()) - 1;
  Linearization best = start;
  best.iterations = 0;
  if (m < 2) return best;
  std::vector<double> error(m);
  for (int s = 0; s < m; ++s) error[s] = segment_error(points, q[s], q[s + 1], norm);
  int sweeps = 0, stale = 0;
  while (sweeps < max_iterations) {
    const double curmax = *std::max_element(error.begin(), error.end());
    bool moved = false;
    for (int s = 0; s < m; ++s) {
      // Candidate moves: give the left end point to segment s-1, or the right one to s+1,
      // the neighbour with the smaller error first.
      int order[2] = {-1, +1};
      if (s > 0 && s < m - 1 && error[s + 1] < error[s - 1]) std::swap(order[0], order[1]);
      for (int side : order) {
        const int t = s + side;
        if (t < 0 || t >= m || error[s] <= error[t]) continue;
        const int shared = side < 0 ? s : s + 1;  // index into q of the shared end point
        const int moved_to = q[shared] + (side < 0 ? 1 : -1);
        if (moved_to <= q[shared - 1] || moved_to >= q[shared + 1]) continue;
        const int lo = q[shared - 1], hi = q[shared + 1];
        const double left = segment_error(points, lo, moved_to, norm);
        const double right = segment_error(points, moved_to, hi, norm);
        if (left > curmax || right > curmax) continue;
        q[shared] = moved_to;
        error[shared - 1] = left;
        error[shared] = right;
        moved = true;
        break;
      }
    }
    if (!moved) break;
    ++sweeps;
    const double now = *std::max_element(error.begin(), error.end());
    if (now < best.error) {
      best.indices = q;
      best.error = now;
      best.iterations = sweeps;
      stale = 0;
    } else if (++stale >= 16) {
      break;
    }
  }
  return best;
}

}  // namespace sculpt::curves::detail
