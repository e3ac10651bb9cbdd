#pragma once
/// \file dispose.hpp
/// Destroying a large value on another thread. Freeing millions of small blocks takes glibc about
/// a second per few gigabytes; work stopped by Ctrl-C (cancel.hpp) should answer at once, so the
/// structures it built are handed to a detached thread instead of being freed while the
/// exception unwinds.
///
///   catch (const Cancelled&) { dispose_in_background(std::move(big)); throw; }

#include <memory>
#include <thread>
#include <utility>

namespace sculpt {

/// Destroys `value` (a unique_ptr, a container, ...) on a detached thread. The value must not
/// refer to anything the caller's stack owns in its destructor. If no thread can be started, it
/// is destroyed here.
template <class T>
void dispose_in_background(T&& value) noexcept {
  auto owned = std::make_unique<std::decay_t<T>>(std::forward<T>(value));
  try {
    std::thread([v = std::move(owned)]() mutable { v.reset(); }).detach();
  } catch (...) {  // std::system_error: no thread; the lambda (and the value) were not taken
  }
}

}  // namespace sculpt
