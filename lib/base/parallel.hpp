#pragma once
/// \file parallel.hpp
/// How the library uses several cores: oneTBB's work-stealing scheduler (docs/bsp.md, "What runs
/// in parallel"), with the thread count set once by SCULPT_THREADS, by `sculpt --threads N` or by a
/// ThreadLimit in C++. Results never depend on the thread count: work is cut into chunks whose
/// bounds depend only on the input size and a grain, each chunk writes only its own output, and
/// outputs are combined in chunk order.

#include <cstddef>
#include <memory>
#include <optional>
#include <string>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_invoke.h>
#include <tbb/partitioner.h>

namespace sculpt {

/// The thread count SCULPT_THREADS asks for: nothing when it is unset or empty.
/// \throw InvalidInput when it is not an integer from 1 to 4096.
std::optional<int> threads_from_environment();

/// Threads a parallel step may use now: the smallest of the live ThreadLimits and SCULPT_THREADS
/// (read once; a malformed value counts as unset), and at most the number of cores.
int thread_count();

/// While it lives, parallel steps use at most `threads` threads (>= 1; 1 runs everything on the
/// calling thread). When limits overlap, the smallest counts (oneTBB's global_control).
/// \throw InvalidInput for threads < 1.
class ThreadLimit {
 public:
  explicit ThreadLimit(int threads);
  ~ThreadLimit();
  ThreadLimit(const ThreadLimit&) = delete;
  ThreadLimit& operator=(const ThreadLimit&) = delete;

 private:
  struct Control;
  std::unique_ptr<Control> control_;
};

namespace detail {
/// Makes SCULPT_THREADS's limit active for the process (once; no effect when it is unset).
void apply_environment_threads();
}  // namespace detail

/// Calls chunk(begin, end) for [0, n) cut into pieces of `grain` indices (the last one shorter),
/// in parallel. The pieces are the same for every thread count, so a caller that keeps one output
/// per piece and joins them in order gets the same result from 1 or 64 threads.
template <typename Chunk>
void parallel_chunks(std::size_t n, std::size_t grain, Chunk&& chunk) {
  if (grain == 0) grain = 1;
  const std::size_t pieces = (n + grain - 1) / grain;
  if (pieces <= 1) {
    if (n > 0) chunk(std::size_t(0), n);
    return;
  }
  detail::apply_environment_threads();
  tbb::parallel_for(
      tbb::blocked_range<std::size_t>(0, pieces, 1),
      [&](const tbb::blocked_range<std::size_t>& r) {
        for (std::size_t p = r.begin(); p != r.end(); ++p) chunk(p * grain, std::min(n, (p + 1) * grain));
      },
      tbb::simple_partitioner());
}

/// Runs f and g, in parallel when a second thread is free.
template <typename F, typename G>
void parallel_invoke(F&& f, G&& g) {
  detail::apply_environment_threads();
  tbb::parallel_invoke(std::forward<F>(f), std::forward<G>(g));
}

}  // namespace sculpt
