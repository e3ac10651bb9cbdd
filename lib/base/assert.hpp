#pragma once
/// \file assert.hpp
/// SCULPT_ASSERT(condition, message): an internal invariant of the library (tree structure, plane
/// table references, mesh assembly), as distinct from a user's bad input, which throws a typed
/// error (base/errors.hpp). Checked where NDEBUG is not defined: the Sanitize build that runs the
/// whole test suite under ASan + UBSan, and Debug builds; compiled out of Release builds, where
/// the condition is not evaluated. A failure prints the place, the condition and the message,
/// then aborts (a sanitizer or a debugger then shows the stack).

#include <cstdio>
#include <cstdlib>

namespace sculpt::detail {

[[noreturn]] inline void assertion_failed(const char* condition, const char* message, const char* file, int line) {
  std::fprintf(stderr, "%s:%d: internal error: %s (assertion '%s' failed)\n", file, line, message, condition);
  std::abort();
}

}  // namespace sculpt::detail

#ifdef NDEBUG
#define SCULPT_ASSERT(condition, message) static_cast<void>(sizeof((condition) ? 1 : 0))
#else
#define SCULPT_ASSERT(condition, message) \
  ((condition) ? static_cast<void>(0) : ::sculpt::detail::assertion_failed(#condition, message, __FILE__, __LINE__))
#endif
