#pragma once
// Timing shared by the benchmark programs: thread CPU time and medians of repeated runs
// (docs/benchmarks.md: medians of several runs; CPU time is the estimate for an idle machine).
#include <algorithm>
#include <chrono>
#include <ctime>
#include <functional>
#include <vector>

namespace sculpt::bench {

/// The calling thread's CPU time in milliseconds.
inline double cpu_ms() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return t.tv_sec * 1e3 + t.tv_nsec * 1e-6;
}

struct Timing {
  double wall = 0, cpu = 0;  ///< milliseconds
};

/// Medians over `runs` of the wall and thread CPU time of f.
inline Timing median_ms(int runs, const std::function<void()>& f) {
  std::vector<double> w, c;
  for (int i = 0; i < runs; ++i) {
    const auto start = std::chrono::steady_clock::now();
    const double cpu = cpu_ms();
    f();
    c.push_back(cpu_ms() - cpu);
    w.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count());
  }
  std::sort(w.begin(), w.end());
  std::sort(c.begin(), c.end());
  return {w[w.size() / 2], c[c.size() / 2]};
}

}  // namespace sculpt::bench
