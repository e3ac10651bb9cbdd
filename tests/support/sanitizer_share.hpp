#pragma once
/// \file sanitizer_share.hpp
/// The share of a heavy property test's cases that the sanitizer build runs.
///
/// Under ASan + UBSan a case costs 5 to 20 times what it costs in the release build, and CI runs
/// both suites on 2 cores (docs/building.md). The few tests that spend most of the sanitizer suite's
/// time on many like cases (random CSG cases, curve families, dense samples) run every
/// kSanitizerStride-th of them there: every test still runs under the sanitizers, and the release
/// suite runs every case.

namespace sculpt::checks {

#if defined(__SANITIZE_ADDRESS__)
inline constexpr int kSanitizerStride = 2;
#else
inline constexpr int kSanitizerStride = 1;
#endif

}  // namespace sculpt::checks
