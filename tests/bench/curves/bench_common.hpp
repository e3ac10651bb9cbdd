#pragma once
// Small timing helpers shared by the curve benchmark programs.
#include <algorithm>
#include <chrono>
#include <functional>
#include <vector>

namespace sculpt::curves::bench {

/// Median wall time in milliseconds of `runs` calls (at least one).
inline double median_ms(int runs, const std::function<void()>& work) {
  std::vector<double> times;
  for (int r = 0; r < std::max(1, runs); ++r) {
    const auto start = std::chrono::steady_clock::now();
    work();
    times.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count());
  }
  std::sort(times.begin(), times.end());
  return times[times.size() / 2];
}

/// Median of a non-empty list of times.
inline double median(std::vector<double> times) {
  std::sort(times.begin(), times.end());
  return times[times.size() / 2];
}

/// Wall time since construction, in milliseconds.
struct Stopwatch {
  std::chrono::steady_clock::time_point start = std::chrono::steady_clock::now();
  [[nodiscard]] double ms() const {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  }
};

}  // namespace sculpt::curves::bench
