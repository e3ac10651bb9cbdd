// The memory budget's sizes (base/memory_limit.hpp). Enforcing the limit changes the whole test
// process, so that is checked on the sculpt executable (command_line_test.sh, repl_pty_test.py).
#include <gtest/gtest.h>

#include <unistd.h>

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

}  // namespace
}  // namespace sculpt
