#include "base/parallel.hpp"

#include <algorithm>
#include <cstdlib>

#include <tbb/global_control.h>
#include <tbb/info.h>

#include "base/errors.hpp"

namespace sculpt {

namespace {

constexpr int kMaxThreads = 4096;

std::optional<int> environment_threads_or_unset() {
  try {
    return threads_from_environment();
  } catch (const InvalidInput&) {
    return std::nullopt;  // the executable reports it (repl/main.cpp); the library runs on
  }
}

}  // namespace

std::optional<int> threads_from_environment() {
  const char* text = std::getenv("SCULPT_THREADS");
  if (text == nullptr || *text == '\0') return std::nullopt;
  char* end = nullptr;
  const long value = std::strtol(text, &end, 10);
  if (*end != '\0' || value < 1 || value > kMaxThreads)
    throw InvalidInput("SCULPT_THREADS must be an integer from 1 to " + std::to_string(kMaxThreads) + ", got '" + text +
                       "'");
  return int(value);
}

struct ThreadLimit::Control {
  explicit Control(int threads) : control(tbb::global_control::max_allowed_parallelism, std::size_t(threads)) {}
  tbb::global_control control;
};

ThreadLimit::ThreadLimit(int threads) {
  if (threads < 1) throw InvalidInput("thread count must be at least 1, got " + std::to_string(threads));
  control_ = std::make_unique<Control>(threads);
}

ThreadLimit::~ThreadLimit() = default;

int thread_count() {
  detail::apply_environment_threads();
  const std::size_t limit = tbb::global_control::active_value(tbb::global_control::max_allowed_parallelism);
  return int(std::min<std::size_t>(limit, std::size_t(tbb::info::default_concurrency())));
}

namespace detail {

void apply_environment_threads() {
  // One global_control for the life of the process; TBB keeps the smallest active limit, so a
  // ThreadLimit can lower it further but not raise it above SCULPT_THREADS.
  static const std::unique_ptr<tbb::global_control> limit = [] {
    const std::optional<int> threads = environment_threads_or_unset();
    return threads ? std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism,
                                                           std::size_t(*threads))
                   : nullptr;
  }();
  (void)limit;
}

}  // namespace detail

}  // namespace sculpt
