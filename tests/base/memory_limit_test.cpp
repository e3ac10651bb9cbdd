// The memory budget (base/memory_limit.hpp): its sizes, and the watch that stops work above it.
// The language's message and the session going on are checked on the sculpt executable
// (command_line_test.sh, repl_pty_test.py).
#include <gtest/gtest.h>

#include <unistd.h>

#include <chrono>
#include <cstring>
#include <memory>
#include <thread>

#include "base/cancel.hpp"
#include "base/errors.hpp"
#include "base/memory_limit.hpp"

namespace sculpt {
namespace {

TEST(MemoryLimit, SizesReadWithTheirUnits) {
  EXPECT_EQ(parse_memory_size("2G"), std::uint64_t(2) << 30);
  EXPECT_EQ(parse_memory_size("500M"), std::uint64_t(500) << 20);
  EXPECT_EQ(parse_memory_size("1.5g"), std::uint64_t(3) << 29);
  EXPECT_EQ(parse_memory_size("1T"), std::uint64_t(1) << 40);
  EXPECT_EQ(parse_memory_size("134217728"), std::uint64_t(1) << 27);
  EXPECT_EQ(parse_memory_size("none"), std::nullopt);
  for (const char* bad : {"", "2X", "G", "-1G", "2 G", "1M", "nan"})
    EXPECT_THROW(parse_memory_size(bad), InvalidInput) << bad;
}

TEST(MemoryLimit, SizesPrintInPowersOf1024) {
  EXPECT_EQ(format_memory_size(std::uint64_t(512) << 20), "512 MB");
  EXPECT_EQ(format_memory_size(std::uint64_t(3) << 29), "1.5 GB");
}

TEST(MemoryLimit, DefaultIsNineTenthsOfPhysicalMemory) {
  const double physical = double(sysconf(_SC_PHYS_PAGES)) * double(sysconf(_SC_PAGESIZE));
  EXPECT_NEAR(double(default_memory_limit()), 0.9 * physical, 0.001 * physical);
}

TEST(MemoryLimit, TheWatchStopsWorkAboveTheLimitAndNotBelow) {
  const std::optional<std::uint64_t> before = resident_bytes();
  if (!before) GTEST_SKIP() << "no /proc/self/statm";
  clear_cancel();
  const std::uint64_t limit = *before + (std::uint64_t(128) << 20);
  MemoryWatch watch(limit, 5);
  ASSERT_TRUE(watch.enforced());
  EXPECT_EQ(watched_memory_limit(), limit);
  // 64 MiB touched: below the limit, nothing happens.
  auto touch = [](std::size_t bytes) {
    std::unique_ptr<char[]> block(new char[bytes]);
    std::memset(block.get(), 1, bytes);
    return block;
  };
  auto small = touch(std::size_t(64) << 20);
  std::this_thread::sleep_for(std::chrono::milliseconds(100));
  EXPECT_FALSE(cancel_requested());
  // 256 MiB more: above it; the watch asks the work to stop, saying why.
  auto large = touch(std::size_t(256) << 20);
  // (Up to 10 s: on a loaded machine the watch's thread may wait long for its turn.)
  for (int i = 0; i < 2000 && !cancel_requested(); ++i) std::this_thread::sleep_for(std::chrono::milliseconds(5));
  EXPECT_TRUE(cancel_requested());
  EXPECT_EQ(cancel_reason(), CancelReason::MemoryLimit);
  // Freed (and handed back to the system by the watch): the next work goes on.
  large.reset();
  small.reset();
  clear_cancel();
  EXPECT_EQ(cancel_reason(), CancelReason::User);
  for (int i = 0; i < 2000 && resident_bytes().value_or(0) >= limit; ++i)
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  // A reading the watch took before the memory was freed may still raise one request: let one
  // period pass and clear it; from then on the watch sees only the freed state.
  std::this_thread::sleep_for(std::chrono::milliseconds(50));
  clear_cancel();
  std::this_thread::sleep_for(std::chrono::milliseconds(100));
  EXPECT_FALSE(cancel_requested());
  clear_cancel();
}

}  // namespace
}  // namespace sculpt
