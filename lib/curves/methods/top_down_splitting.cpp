#include "curves/methods/top_down_splitting.hpp"

#include <algorithm>
#include <cmath>
#include <queue>
#include <tuple>
#include <utility>

namespace sculpt::curves::detail {
namespace {

int farthest_point(const std::vector<Eigen::Vector3d>& points, int i, int j) {
  const ChordDistance distance(points[i], points[j]);
  int best = i + (j - i) / 2;
  double best_distance = -1.0;
  for (int k = i + 1; k < j; ++k)
    if (const double d = distance(points[k]); d > best_distance) {
      best_distance = d;
      best = k;
    }
  return best;
}

// Sec. 4.3.5: the index whose arc length from p_i is nearest to c_kappa.
int center_of_curvature(const CurveMeasures& measures, int i, int j) {
  const double image = measures.image_length(i, j);
  const double target = image > 0.0 ? measures.image_moment(i, j) / image : 0.5 * measures.chord_length(i, j);
  const std::vector<double>& chord = measures.chord_prefix();
  const auto it = std::lower_bound(chord.begin() + i, chord.begin() + j, chord[i] + target);
  int k = static_cast<int>(it - chord.begin());
  if (k > i + 1 && (chord[k] - chord[i]) - target > target - (chord[k - 1] - chord[i])) --k;
  return std::clamp(k, i + 1, j - 1);
}

}  // namespace

Linearization top_down_split(const std::vector<Eigen::Vector3d>& points, const CurveMeasures& measures,
                             const SplitOptions& options) {
  const int last = static_cast<int>(points.size()) - 1;
  const auto split_at = [&](int i, int j) {
    return options.rule == SplitRule::FarthestPoint ? farthest_point(points, i, j)
                                                    : center_of_curvature(measures, i, j);
  };
  Linearization result;
  std::vector<int> indices{0, last};
  if (options.segments > 0) {
    // Worst segment first; among equal errors the longer one (so error-0 pieces still split).
    using Entry = std::tuple<double, int, int, int>;  // error, length, i, j
    std::priority_queue<Entry> queue;
    queue.push({segment_error(points, 0, last, options.norm), last, 0, last});
    int segments = 1;
    while (segments < options.segments) {
      const auto [error, length, i, j] = queue.top();
      queue.pop();
      const int c = split_at(i, j);
      indices.push_back(c);
      queue.push({segment_error(points, i, c, options.norm), c - i, i, c});
      queue.push({segment_error(points, c, j, options.norm), j - c, c, j});
      ++segments;
      ++result.iterations;
    }
  } else {
    std::vector<std::pair<int, int>> stack{{0, last}};
    while (!stack.empty()) {
      const auto [i, j] = stack.back();
      stack.pop_back();
      if (j - i < 2 || segment_error(points, i, j, options.norm) <= options.tolerance) continue;
      const int c = split_at(i, j);
      indices.push_back(c);
      stack.push_back({i, c});
      stack.push_back({c, j});
      ++result.iterations;
    }
  }
  std::sort(indices.begin(), indices.end());
  result.indices = std::move(indices);
  result.error = approximation_error(points, result.indices, options.norm);
  return result;
}

}  // namespace sculpt::curves::detail
