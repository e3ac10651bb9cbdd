// keep_freed_memory() takes effect even when its header is the first one a file includes (it
// once read __GLIBC__ before any header had defined it, and so did nothing there): after it, a
// large block freed at the top of the heap stays with the process instead of being trimmed.
#include "base/memory_policy.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <thread>
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

// Threads share malloc arenas, one for every two cores, so that memory freed by one thread serves
// the others (without the limit, each of these threads would get an arena of its own).
TEST(MemoryPolicy, ThreadsShareArenasOneForEveryTwoCores) {
  if (kOwnAllocator) GTEST_SKIP() << "a sanitizer's allocator replaces glibc's here";
  keep_freed_memory();
  const int limit = std::max(1, static_cast<int>(std::thread::hardware_concurrency() / 2));
  constexpr int kThreads = 6;
  std::atomic<int> holding = 0;
  std::vector<std::thread> threads;
  for (int t = 0; t < kThreads; ++t) {
    threads.emplace_back([&] {
      std::vector<char> block(1 << 16, 1);  // held until every thread holds one: they overlap
      holding += 1;
      while (holding.load() < kThreads) std::this_thread::yield();
    });
  }
  for (std::thread& t : threads) t.join();
  // malloc_info's XML has one <heap nr="..."> per arena.
  char* text = nullptr;
  std::size_t size = 0;
  FILE* out = open_memstream(&text, &size);
  ASSERT_NE(out, nullptr);
  ASSERT_EQ(malloc_info(0, out), 0);
  std::fclose(out);
  const std::string xml(text, size);
  std::free(text);
  int heaps = 0;
  for (std::size_t at = xml.find("<heap nr="); at != std::string::npos; at = xml.find("<heap nr=", at + 1)) ++heaps;
  EXPECT_GE(heaps, 1);
  EXPECT_LE(heaps, limit) << xml.substr(0, 400);
}
#endif

}  // namespace
}  // namespace sculpt
