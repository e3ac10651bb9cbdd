#pragma once
/// \file parallel.hpp
/// How the library uses several cores: oneTBB's work-stealing scheduler (docs/bsp.md, "What runs
/// in parallel"), with the thread count set once by SCULPT_THREADS, by `sculpt --threads N` or by a
/// ThreadLimit in C++. Results never depend on the thread count: work is cut into chunks whose
/// bounds depend only on the input size and a grain, each chunk writes only its own output, and
/// outputs are combined in chunk order.

#include <algorithm>
#include <cstddef>
#include <exception>
#include <memory>
#include <optional>
#include <string>
#include <vector>

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

/// parallel_chunks() for work whose outputs are joined in order and should not all be held at
/// once: the pieces run in waves of a few per thread; after each wave, join(out) is called for
/// the wave's outputs in piece order (it takes what it needs and leaves `out` empty, storage kept,
/// for the next wave). So the joined result is that of one pass in order, the same for any thread
/// count, and the scratch holds one wave. chunk(begin, end, out) fills piece [begin, end)'s output;
/// an exception it throws is rethrown when the join reaches that piece (the first in piece
/// order), after the pieces before it were joined.
template <typename Out, typename Chunk, typename Join>
void parallel_waves(std::size_t n, std::size_t grain, Chunk&& chunk, Join&& join) {
  if (grain == 0) grain = 1;
  const std::size_t per_wave = 4 * std::size_t(std::max(thread_count(), 1)), wave = grain * per_wave;
  std::vector<Out> outs(per_wave);
  std::vector<std::exception_ptr> errors(per_wave);
  for (std::size_t start = 0; start < n; start += wave) {
    const std::size_t stop = std::min(n, start + wave);
    parallel_chunks(stop - start, grain, [&](std::size_t begin, std::size_t end) {
      const std::size_t k = begin / grain;
      try {
        chunk(start + begin, start + end, outs[k]);
      } catch (...) {
        errors[k] = std::current_exception();
      }
    });
    for (std::size_t k = 0; k * grain < stop - start; ++k) {
      if (errors[k]) std::rethrow_exception(errors[k]);
      join(outs[k]);
    }
  }
}

/// Runs f and g, in parallel when a second thread is free.
template <typename F, typename G>
void parallel_invoke(F&& f, G&& g) {
  detail::apply_environment_threads();
  tbb::parallel_invoke(std::forward<F>(f), std::forward<G>(g));
}

/// parallel_invoke(f, g) for a g whose outcome counts only when f's does (a search beside the
/// check that decides whether its answer is wanted): an exception from g is returned, not thrown,
/// for the caller to rethrow or drop; one from f is thrown. Cancellation is not lost when g's is
/// dropped: the request stays pending (base/cancel.hpp).
template <typename F, typename G>
[[nodiscard]] std::exception_ptr parallel_invoke_holding_second(F&& f, G&& g) {
  std::exception_ptr held;
  parallel_invoke(std::forward<F>(f), [&] {
    try {
      g();
    } catch (...) {
      held = std::current_exception();
    }
  });
  return held;
}

}  // namespace sculpt
