#pragma once
/// \file memory_policy.hpp
/// How a long-running modeling process should hand memory back to the system: not at every free.
/// glibc's defaults return the top of the heap once 128 KiB are free and map large blocks afresh
/// each time, so a stroke that follows one which freed large temporaries faults all its pages in
/// again (on the benchmark machine, a virtual one, that was up to 20 ms of a 50 ms stroke:
/// docs/benchmarks.md, "Sculpting strokes"). keep_freed_memory() keeps freed memory for reuse:
/// the peak stays resident. For executables (the `sculpt` REPL and batch runner, benchmarks that
/// model it); the library itself never changes the process's allocator.

#include <cstdlib>  // first: on glibc it defines __GLIBC__ (features.h), which the test below reads
#if defined(__GLIBC__)
#include <malloc.h>
#endif

namespace sculpt {

/// Keeps freed heap memory for reuse instead of returning it to the system (glibc: trim threshold
/// 1 GiB, top pad 64 MiB, mmap threshold at its largest, 32 MiB). No effect elsewhere.
inline void keep_freed_memory() {
#if defined(__GLIBC__)
  mallopt(M_TRIM_THRESHOLD, 1 << 30);
  mallopt(M_TOP_PAD, 64 << 20);
  mallopt(M_MMAP_THRESHOLD, 32 << 20);
#endif
}

}  // namespace sculpt
