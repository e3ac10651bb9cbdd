#include "base/memory_limit.hpp"

#include <unistd.h>

#include <charconv>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>  // first: on glibc it defines __GLIBC__ (features.h), which the test below reads
#if defined(__GLIBC__)
#include <malloc.h>
#endif

#include "base/cancel.hpp"
#include "base/errors.hpp"

namespace sculpt {
namespace {

std::atomic<std::uint64_t> watched_limit{0};

/// Hands the heap's free memory back to the system (glibc); the resident set shrinks by it.
void return_free_memory() {
#if defined(__GLIBC__)
  malloc_trim(0);
#endif
}

}  // namespace

std::uint64_t default_memory_limit() {
  const long pages = sysconf(_SC_PHYS_PAGES), page = sysconf(_SC_PAGESIZE);
  if (pages <= 0 || page <= 0) return 0;
  return static_cast<std::uint64_t>(pages) / 10 * 9 * static_cast<std::uint64_t>(page);
}

std::optional<std::uint64_t> resident_bytes() {
  std::FILE* file = std::fopen("/proc/self/statm", "r");
  if (!file) return std::nullopt;
  unsigned long long size = 0, resident = 0;
  const int read = std::fscanf(file, "%llu %llu", &size, &resident);
  std::fclose(file);
  if (read != 2) return std::nullopt;
  return static_cast<std::uint64_t>(resident) * static_cast<std::uint64_t>(sysconf(_SC_PAGESIZE));
}

std::optional<std::uint64_t> parse_memory_size(const std::string& text) {
  if (text == "none") return std::nullopt;
  double number = 0;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), number);
  const std::string unit(end, text.data() + text.size());
  double factor = 0;
  if (unit.empty()) factor = 1;
  if (unit == "K" || unit == "k") factor = 1024.0;
  if (unit == "M" || unit == "m") factor = 1024.0 * 1024;
  if (unit == "G" || unit == "g") factor = 1024.0 * 1024 * 1024;
  if (unit == "T" || unit == "t") factor = 1024.0 * 1024 * 1024 * 1024;
  const double bytes = number * factor;
  if (error != std::errc() || factor == 0 || !std::isfinite(bytes))
    throw InvalidInput("a memory size is a number with K, M, G or T (2G, 500M) or 'none', not '" + text + "'");
  if (bytes < 64.0 * 1024 * 1024)
    throw InvalidInput("a memory limit below 64M leaves sculpt no room, got '" + text + "'");
  if (bytes >= 0x1p63) return std::nullopt;
  return static_cast<std::uint64_t>(bytes);
}

std::string format_memory_size(std::uint64_t bytes) {
  char text[32];
  const double gb = static_cast<double>(bytes) / (1024.0 * 1024 * 1024);
  if (gb >= 1)
    std::snprintf(text, sizeof text, "%.1f GB", gb);
  else
    std::snprintf(text, sizeof text, "%.0f MB", static_cast<double>(bytes) / (1024.0 * 1024));
  return text;
}

MemoryWatch::MemoryWatch(std::uint64_t limit, int period_ms) : enforced_(resident_bytes().has_value()) {
  if (!enforced_) return;
  watched_limit.store(limit, std::memory_order_relaxed);
  thread_ = std::thread([this, limit, period_ms] { run(limit, period_ms); });
}

MemoryWatch::~MemoryWatch() {
  {
    std::lock_guard lock(mutex_);
    stop_ = true;
  }
  wake_.notify_one();
  if (thread_.joinable()) thread_.join();
  watched_limit.store(0, std::memory_order_relaxed);
}

void MemoryWatch::run(std::uint64_t limit, int period_ms) {
  std::unique_lock lock(mutex_);
  while (!wake_.wait_for(lock, std::chrono::milliseconds(period_ms), [this] { return stop_; })) {
    std::optional<std::uint64_t> resident = resident_bytes();
    if (!resident || *resident <= limit || cancel_requested()) continue;
    // Memory freed and kept for reuse counts in the resident set (after a stopped statement, all
    // it held): give it back first, and stop the work only if that is not enough.
    return_free_memory();
    resident = resident_bytes();
    if (resident && *resident > limit) request_cancel_for_memory();
  }
}

std::optional<std::uint64_t> watched_memory_limit() {
  const std::uint64_t limit = watched_limit.load(std::memory_order_relaxed);
  return limit > 0 ? std::optional(limit) : std::nullopt;
}

}  // namespace sculpt
