#pragma once
/// \file memory_policy.hpp
/// How a long-running modeling process should hand memory back to the system: not at every free.
/// glibc's defaults return the top of the heap once 128 KiB are free and map large blocks afresh
/// each time, so a stroke that follows one which freed large temporaries faults all its pages in
/// again (on the benchmark machine, a virtual one, that was up to 20 ms of a 50 ms stroke:
/// docs/benchmarks.md, "Sculpting strokes"). keep_freed_memory() keeps freed memory for reuse:
/// the peak stays resident; use_huge_pages() backs the heap with 2 MiB pages where the system
/// offers them. For executables (the `sculpt` REPL and batch runner, benchmarks that model it);
/// the library itself never changes the process's allocator.

#include <cstdlib>  // first: on glibc it defines __GLIBC__ (features.h), which the test below reads
#if defined(__GLIBC__)
#include <malloc.h>
#endif

#include <algorithm>
#include <cstring>
#include <fstream>
#include <string>
#include <thread>
#if defined(__linux__)
#include <unistd.h>
#endif

namespace sculpt {

/// Keeps freed heap memory for reuse instead of returning it to the system (glibc: trim threshold
/// 1 GiB, top pad 64 MiB, mmap threshold at its largest, 32 MiB), with one malloc arena for every
/// two cores. Each arena keeps what was freed into it, so with an arena per thread the process
/// held the sum of the arenas' peaks: on 2 cores one arena took the armadillo job's peak from 88.6
/// to 82.0 MB at the same time (docs/benchmarks.md, "Session 38"). Call it before starting
/// threads. No effect elsewhere.
inline void keep_freed_memory() {
#if defined(__GLIBC__)
  mallopt(M_TRIM_THRESHOLD, 1 << 30);
  mallopt(M_TOP_PAD, 64 << 20);
  mallopt(M_MMAP_THRESHOLD, 32 << 20);
  mallopt(M_ARENA_MAX, std::max(1, static_cast<int>(std::thread::hardware_concurrency() / 2)));
#endif
}

/// Backs the heap with transparent huge pages where the system offers them: glibc's tunable
/// glibc.malloc.hugetlb=1 (glibc 2.35 and later; the kernel's THP mode "madvise" or "always").
/// A set operation on real meshes first-touches hundreds of MB; on 4 KiB pages each touch is a
/// page fault, and faults were 20-28 % of a job's time on a virtual machine (docs/benchmarks.md,
/// "Session 25"). glibc reads its tunables only at startup, so the executable runs itself again
/// once with the tunable added (same process id, arguments and other environment; at the top of
/// main, before any thread). Nothing happens when SCULPT_HUGE_PAGES=0, when THP is off, under the
/// sanitizers (their own allocator), or when the tunable is already there; if the new start
/// fails, the process goes on as it is.
inline void use_huge_pages([[maybe_unused]] char** argv) {
#if defined(__GLIBC__) && defined(__linux__) && !defined(__SANITIZE_ADDRESS__)
  if (const char* opt = std::getenv("SCULPT_HUGE_PAGES"); opt && std::strcmp(opt, "0") == 0) return;
  const char* tunables = std::getenv("GLIBC_TUNABLES");
  const std::string now = tunables ? tunables : "";
  if (now.find("glibc.malloc.hugetlb") != std::string::npos) return;  // set (by us or the user)
  std::ifstream mode("/sys/kernel/mm/transparent_hugepage/enabled");
  std::string modes;
  if (!std::getline(mode, modes) || modes.find("[never]") != std::string::npos) return;
  const std::string wanted = now.empty() ? "glibc.malloc.hugetlb=1" : now + ":glibc.malloc.hugetlb=1";
  if (setenv("GLIBC_TUNABLES", wanted.c_str(), 1) != 0) return;
  execv("/proc/self/exe", argv);
  // Not restarted: go on with ordinary pages (the tunable stays set for child processes only).
#endif
}

}  // namespace sculpt
