#include "base/memory_limit.hpp"

#include <sys/resource.h>
#include <unistd.h>

#include <charconv>
#include <cmath>
#include <cstdio>

#include "base/errors.hpp"

namespace sculpt {
namespace {

constexpr bool kSanitized =
#if defined(__SANITIZE_ADDRESS__)
    true;
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
    true;
#else
    false;
#endif
#else
    false;
#endif

}  // namespace

std::uint64_t default_memory_limit() {
  const long pages = sysconf(_SC_PHYS_PAGES), page = sysconf(_SC_PAGESIZE);
  if (pages <= 0 || page <= 0) return 0;
  return static_cast<std::uint64_t>(pages) / 10 * 9 * static_cast<std::uint64_t>(page);
}

bool set_memory_limit(std::uint64_t bytes) {
  if (kSanitized) return false;
  rlimit limit{};
  if (getrlimit(RLIMIT_AS, &limit) != 0) return false;
  // Never above the hard limit the process was given.
  limit.rlim_cur = limit.rlim_max == RLIM_INFINITY ? bytes : std::min<rlim_t>(bytes, limit.rlim_max);
  return setrlimit(RLIMIT_AS, &limit) == 0;
}

std::optional<std::uint64_t> memory_limit() {
  rlimit limit{};
  if (getrlimit(RLIMIT_AS, &limit) != 0 || limit.rlim_cur == RLIM_INFINITY) return std::nullopt;
  return static_cast<std::uint64_t>(limit.rlim_cur);
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

}  // namespace sculpt
