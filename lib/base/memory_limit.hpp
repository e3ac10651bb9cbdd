#pragma once
/// \file memory_limit.hpp
/// The memory budget of executables (issue 35): work that goes over it stops with an error at its
/// statement, the way Ctrl-C stops it (base/cancel.hpp), instead of the system killing the process
/// with the session and its variables (Linux overcommits, so an allocation rarely fails first).
///
/// A MemoryWatch thread reads the process's resident memory every few milliseconds; above the
/// limit it returns freed memory to the system (malloc_trim: the executables keep freed memory for
/// reuse, base/memory_policy.hpp) and, if still above, requests cancellation with the reason
/// CancelReason::MemoryLimit. Long loops check for cancellation often (a fraction of a second
/// apart), so the work overshoots the limit by what it allocates in that time. The resident set
/// is what the system runs out of; address-space limits (RLIMIT_AS) were tried and refused work
/// that fitted, since mapped but untouched memory counts there (a 1000-segment sphere union maps
/// 6.1 GB and touches 2.7 GB).

#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <mutex>
#include <optional>
#include <string>
#include <thread>

namespace sculpt {

/// 90 % of the machine's physical memory (0 if it cannot be read).
std::uint64_t default_memory_limit();

/// The process's resident memory in bytes (nullopt where /proc/self/statm cannot be read).
std::optional<std::uint64_t> resident_bytes();

/// "2G", "500M", "1.5G", "64K" or a number of bytes ("none": no limit, nullopt).
/// \throw InvalidInput for anything else, or a size below 64 MiB (sculpt itself needs that much).
std::optional<std::uint64_t> parse_memory_size(const std::string& text);

/// "2.0 GB", "500 MB": bytes for messages, in powers of 1024.
std::string format_memory_size(std::uint64_t bytes);

/// While it lives, work that takes the process's resident memory above `limit` bytes is cancelled
/// (cancel_reason() == CancelReason::MemoryLimit). One per process.
class MemoryWatch {
 public:
  explicit MemoryWatch(std::uint64_t limit, int period_ms = 10);
  ~MemoryWatch();
  MemoryWatch(const MemoryWatch&) = delete;
  MemoryWatch& operator=(const MemoryWatch&) = delete;

  /// False where resident memory cannot be read (the watch does nothing there).
  [[nodiscard]] bool enforced() const { return enforced_; }

 private:
  void run(std::uint64_t limit, int period_ms);
  std::mutex mutex_;
  std::condition_variable wake_;
  bool stop_ = false;
  bool enforced_ = false;
  std::thread thread_;
};

/// The limit of the live MemoryWatch, for messages (nullopt when none watches).
std::optional<std::uint64_t> watched_memory_limit();

}  // namespace sculpt
