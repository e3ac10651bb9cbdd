#pragma once
/// \file cancel.hpp
/// Stopping long work when the user asks (Ctrl-C): a process-wide request flag, set by
/// request_cancel() (async-signal-safe: a SIGINT handler may call it), and check_cancel(), which
/// long loops call (every kCancelStride iterations through CancelPoll) and which throws Cancelled
/// once a request is pending. A loop in a oneTBB task may throw it too: oneTBB cancels the task
/// group and rethrows the first exception on the thread that started the parallel step.
///
/// Work that cannot be abandoned halfway without losing a value it was given (an in-place set
/// operation that has taken its operand's storage) runs under a CancelShield: while one lives, no
/// check throws, and the request stays pending for the first check after it ends. The flag is
/// process-wide: whoever runs the work (the REPL, the batch driver, a test) clears it with
/// clear_cancel() before the next piece of work.

#include <atomic>
#include <cstdint>
#include <stdexcept>

namespace sculpt {

/// The work was stopped because cancellation was requested (request_cancel). Values the stopped
/// operation was given are unchanged; what it was making is discarded.
class Cancelled : public std::runtime_error {
 public:
  Cancelled() : std::runtime_error("interrupted") {}
};

/// Why work was stopped: the user asked (Ctrl-C), or it went over the memory budget
/// (base/memory_limit.hpp's MemoryWatch).
enum class CancelReason { User, MemoryLimit };

namespace detail {
inline std::atomic<bool> cancel_flag{false};
inline std::atomic<CancelReason> cancel_reason{CancelReason::User};
inline std::atomic<int> cancel_shields{0};
static_assert(std::atomic<bool>::is_always_lock_free, "request_cancel() is called from signal handlers");
static_assert(std::atomic<CancelReason>::is_always_lock_free);
/// Throws Cancelled unless a CancelShield lives (the flag was seen raised).
void throw_cancelled();
}  // namespace detail

/// Asks every running check_cancel() to throw. Async-signal-safe (one lock-free atomic store).
inline void request_cancel() noexcept { detail::cancel_flag.store(true, std::memory_order_relaxed); }
/// Asks as request_cancel() does, for going over the memory budget (the reason is kept until
/// clear_cancel(); a user's request made meanwhile stays a user's).
inline void request_cancel_for_memory() noexcept {
  if (!detail::cancel_flag.load(std::memory_order_relaxed)) {
    detail::cancel_reason.store(CancelReason::MemoryLimit, std::memory_order_relaxed);
    detail::cancel_flag.store(true, std::memory_order_relaxed);
  }
}
/// Withdraws the request (before the next statement, the next test, ...).
inline void clear_cancel() noexcept {
  detail::cancel_flag.store(false, std::memory_order_relaxed);
  detail::cancel_reason.store(CancelReason::User, std::memory_order_relaxed);
}
/// Why the pending request was made.
inline CancelReason cancel_reason() noexcept { return detail::cancel_reason.load(std::memory_order_relaxed); }
/// True while a request is pending.
inline bool cancel_requested() noexcept { return detail::cancel_flag.load(std::memory_order_relaxed); }
/// The request flag itself, for code that polls a flag of its own kind (the language's
/// InterpreterOptions::interrupt).
inline const std::atomic<bool>* cancel_request_flag() noexcept { return &detail::cancel_flag; }

/// Throws Cancelled if a request is pending (and no CancelShield lives). One relaxed atomic load
/// when nothing is pending: cheap, but call it through CancelPoll in tight loops.
/// \throw Cancelled
inline void check_cancel() {
  if (detail::cancel_flag.load(std::memory_order_relaxed)) [[unlikely]]
    detail::throw_cancelled();
}

/// Iterations between two checks of a CancelPoll.
inline constexpr std::uint32_t kCancelStride = 1024;

/// A loop's cancellation point: tick() checks every kCancelStride calls (a counter increment
/// otherwise). One per loop and thread (not shared between tasks).
class CancelPoll {
 public:
  /// \throw Cancelled (check_cancel) on every kCancelStride-th call while a request is pending.
  void tick() {
    if (++count_ % kCancelStride == 0) check_cancel();
  }
  /// Counts `n` iterations at once (a loop whose steps differ much in cost).
  void tick(std::uint32_t n) {
    const std::uint32_t before = count_;
    count_ += n;
    if (count_ / kCancelStride != before / kCancelStride) check_cancel();
  }

 private:
  std::uint32_t count_ = 0;
};

/// While it lives, check_cancel() does not throw (the request stays pending). For work that would
/// lose a value if it stopped halfway; process-wide, like the flag.
class CancelShield {
 public:
  CancelShield() noexcept { detail::cancel_shields.fetch_add(1, std::memory_order_relaxed); }
  ~CancelShield() { detail::cancel_shields.fetch_sub(1, std::memory_order_relaxed); }
  CancelShield(const CancelShield&) = delete;
  CancelShield& operator=(const CancelShield&) = delete;
};

}  // namespace sculpt
