#include "curves/methods/dynamic_programming.hpp"
#include "base/cancel.hpp"

#include <limits>
#include <utility>

#include "base/errors.hpp"

namespace sculpt::curves::detail {

Linearization dynamic_linearization(const std::vector<Eigen::Vector3d>& points, int m, Norm norm) {
  const int n = static_cast<int>(points.size());
  if (n > kDynamicMaxPoints)
    throw InvalidInput("DYNAMIC is the O(n^3 log m) reference and accepts at most " +
                       std::to_string(kDynamicMaxPoints) + " points (got " + std::to_string(n) +
                       "); use the optimal method");
  constexpr double kInf = std::numeric_limits<double>::infinity();
  const auto at = [n](int i, int j) { return static_cast<std::size_t>(i) * n + j; };
  int depth = 0;  // largest d with 2^d <= m
  while ((2 << depth) <= m) ++depth;

  // Basis step: E^1_ij by direct evaluation.
  std::vector<double> previous(static_cast<std::size_t>(n) * n, kInf);
  for (int i = 0; i < n; ++i)
    for (int j = i + 1; j < n; ++j) previous[at(i, j)] = segment_error(points, i, j, norm);

  std::vector<std::vector<double>> level_error(depth + 1);  // kept only for the binary digits of m
  std::vector<std::vector<int>> split(depth + 1);            // K^d_ij, d >= 1
  if (m & 1) level_error[0] = previous;
  // Inductive step.
  for (int d = 1; d <= depth; ++d) {
    const int half = 1 << (d - 1), full = 1 << d;
    std::vector<double> current(static_cast<std::size_t>(n) * n, kInf);
    split[d].assign(static_cast<std::size_t>(n) * n, -1);
    for (int i = 0; i + full < n; ++i, check_cancel())  // Ctrl-C (base/cancel.hpp)
      for (int j = i + full; j < n; ++j) {
        double best = kInf;
        int best_k = -1;
        for (int k = i + half; k <= j - half; ++k) {
          const double a = previous[at(i, k)], b = previous[at(k, j)];
          const double value = a > b ? a : b;
          if (value < best) {
            best = value;
            best_k = k;
          }
        }
        current[at(i, j)] = best;
        split[d][at(i, j)] = best_k;
      }
    if (m & full) level_error[d] = current;
    previous = std::move(current);
  }

  // Merge the binary digits of m from the largest power down (sec. 3.3): row 0 only.
  std::vector<int> digits;
  for (int d = depth; d >= 0; --d)
    if (m & (1 << d)) digits.push_back(d);
  std::vector<double> row(n);
  for (int j = 0; j < n; ++j) row[j] = level_error[digits[0]][at(0, j)];
  std::vector<std::vector<int>> merge_split(digits.size());
  for (std::size_t t = 1; t < digits.size(); ++t) {
    const std::vector<double>& table = level_error[digits[t]];
    std::vector<double> next(n, kInf);
    merge_split[t].assign(n, -1);
    for (int j = 0; j < n; ++j)
      for (int k = 1; k < j; ++k) {
        const double a = row[k], b = table[at(k, j)];
        const double value = a > b ? a : b;
        if (value < next[j]) {
          next[j] = value;
          merge_split[t][j] = k;
        }
      }
    row = std::move(next);
  }

  // Construct LA*: blocks (i, j, d) expanded through K^d with an explicit stack.
  std::vector<std::pair<std::pair<int, int>, int>> blocks;  // in right-to-left order
  int j = n - 1;
  for (std::size_t t = digits.size() - 1; t >= 1; --t) {
    const int k = merge_split[t][j];
    blocks.push_back({{k, j}, digits[t]});
    j = k;
  }
  blocks.push_back({{0, j}, digits[0]});
  Linearization result;
  result.indices.push_back(0);
  std::vector<std::pair<std::pair<int, int>, int>> stack(blocks.begin(), blocks.end());  // top = leftmost
  while (!stack.empty()) {
    const auto [range, d] = stack.back();
    stack.pop_back();
    if (d == 0) {
      result.indices.push_back(range.second);
      continue;
    }
    const int k = split[d][at(range.first, range.second)];
    stack.push_back({{k, range.second}, d - 1});
    stack.push_back({{range.first, k}, d - 1});
  }
  result.error = row[n - 1];
  return result;
}

}  // namespace sculpt::curves::detail
