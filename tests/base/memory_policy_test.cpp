// keep_freed_memory() takes effect even when its header is the first one a file includes (it
// once read __GLIBC__ before any header had defined it, and so did nothing there): after it, a
// large block freed at the top of the heap stays with the process instead of being trimmed.
#include "base/memory_policy.hpp"

#include <gtest/gtest.h>

#include <vector>
#if defined(__GLIBC__)
#include <malloc.h>
#endif

namespace sculpt {
namespace {

#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
constexpr bool kOwnAllocator = true;  // the sanitizer's allocator replaces glibc's: mallopt and mallinfo2 do not apply
#elif defined(__has_feature)
#if __has_feature(address_sanitizer) || __has_feature(thread_sanitizer) || __has_feature(memory_sanitizer)
constexpr bool kOwnAllocator = true;
#else
constexpr bool kOwnAllocator = false;
#endif
#else
constexpr bool kOwnAllocator = false;
#endif

#if defined(__GLIBC__)
TEST(MemoryPolicy, FreedMemoryStaysWithTheProcess) {
  if (kOwnAllocator) GTEST_SKIP() << "a sanitizer's allocator replaces glibc's here";
  keep_freed_memory();
  const std::size_t before = mallinfo2().arena;
  {
    std::vector<char> block(8 << 20, 1);  // below the raised mmap threshold: from the heap
    ASSERT_GE(mallinfo2().arena, before + (8 << 20));
  }
  // glibc's default trim threshold (128 KiB) would have returned the freed top of the heap.
  EXPECT_GE(mallinfo2().arena, before + (8 << 20));
}
#endif

}  // namespace
}  // namespace sculpt
