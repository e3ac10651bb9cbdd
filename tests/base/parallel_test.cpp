// The thread pool's promises (lib/base/parallel.hpp): every index once, chunk bounds that do not
// depend on the thread count, limits that hold, and SCULPT_THREADS read strictly.
#include "base/parallel.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <exception>
#include <mutex>
#include <set>
#include <stdexcept>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include "base/errors.hpp"

namespace sculpt {
namespace {

std::set<std::pair<std::size_t, std::size_t>> chunks_of(std::size_t n, std::size_t grain) {
  std::mutex m;
  std::set<std::pair<std::size_t, std::size_t>> seen;
  parallel_chunks(n, grain, [&](std::size_t begin, std::size_t end) {
    std::lock_guard lock(m);
    seen.emplace(begin, end);
  });
  return seen;
}

// parallel_waves joins in index order whatever the thread count, holds at most one wave of
// outputs, and rethrows the first failing piece's exception after joining the pieces before it.
TEST(ParallelWaves, JoinInIndexOrderAndRethrowTheFirstFailureInOrder) {
  for (const int threads : {1, 2, 8}) {
    ThreadLimit limit(threads);
    for (const std::size_t n : {0u, 1u, 63u, 64u, 1000u, 5000u}) {
      std::vector<std::size_t> joined;
      std::size_t most = 0, held = 0;
      std::mutex m;
      parallel_waves<std::vector<std::size_t>>(
          n, 7,
          [&](std::size_t begin, std::size_t end, std::vector<std::size_t>& out) {
            EXPECT_TRUE(out.empty());
            for (std::size_t i = begin; i < end; ++i) out.push_back(i);
            std::lock_guard lock(m);
            most = std::max(most, held += end - begin);
          },
          [&](std::vector<std::size_t>& out) {
            joined.insert(joined.end(), out.begin(), out.end());
            held -= out.size();
            out.clear();
          });
      ASSERT_EQ(joined.size(), n);
      for (std::size_t i = 0; i < n; ++i) ASSERT_EQ(joined[i], i);
      EXPECT_LE(most, 7 * 4 * std::size_t(thread_count()));  // one wave: 4 pieces per thread
    }
    // Pieces 3 and 5 throw: pieces 0-2 are joined, then 3's error comes out.
    std::vector<std::size_t> joined;
    try {
      parallel_waves<std::vector<std::size_t>>(
          100, 10,
          [&](std::size_t begin, std::size_t end, std::vector<std::size_t>& out) {
            if (begin == 30 || begin == 50) throw std::runtime_error("piece " + std::to_string(begin / 10));
            for (std::size_t i = begin; i < end; ++i) out.push_back(i);
          },
          [&](std::vector<std::size_t>& out) {
            joined.insert(joined.end(), out.begin(), out.end());
            out.clear();
          });
      ADD_FAILURE() << "no exception";
    } catch (const std::runtime_error& e) {
      EXPECT_STREQ(e.what(), "piece 3");
    }
    EXPECT_EQ(joined.size(), 30u);
  }
}

// The second task's exception is handed back, the first's thrown; both tasks run to their end.
TEST(ParallelInvokeHoldingSecond, ReturnsTheSecondsErrorAndThrowsTheFirsts) {
  for (const int threads : {1, 2}) {
    const ThreadLimit limit(threads);
    bool first = false, second = false;
    std::exception_ptr held = parallel_invoke_holding_second([&] { first = true; }, [&] { second = true; });
    EXPECT_TRUE(first && second);
    EXPECT_FALSE(held);
    first = false;
    held = parallel_invoke_holding_second([&] { first = true; }, [] { throw std::runtime_error("second"); });
    EXPECT_TRUE(first);
    ASSERT_TRUE(held);
    EXPECT_THROW(std::rethrow_exception(held), std::runtime_error);
    EXPECT_THROW((void)parallel_invoke_holding_second([] { throw std::logic_error("first"); }, [] {}),
                 std::logic_error);
  }
}

TEST(ParallelChunks, CoverEveryIndexOnceInFixedPieces) {
  for (const std::size_t n : {0u, 1u, 7u, 256u, 1000u, 4097u}) {
    std::vector<int> hits(n, 0);
    parallel_chunks(n, 64, [&](std::size_t begin, std::size_t end) {
      for (std::size_t i = begin; i < end; ++i) ++hits[i];  // each index belongs to one chunk
    });
    for (std::size_t i = 0; i < n; ++i) EXPECT_EQ(hits[i], 1) << n << " " << i;
    // The pieces are [64 k, min(n, 64 (k + 1))), whatever the thread count.
    std::set<std::pair<std::size_t, std::size_t>> expected;
    for (std::size_t b = 0; b < n; b += 64) expected.emplace(b, std::min(n, b + 64));
    EXPECT_EQ(chunks_of(n, 64), expected) << n;
    ThreadLimit one(1);
    EXPECT_EQ(chunks_of(n, 64), expected) << n;
  }
}

TEST(ThreadLimit, LimitsAndRefusesZero) {
  const int all = thread_count();
  EXPECT_GE(all, 1);
  {
    ThreadLimit one(1);
    EXPECT_EQ(thread_count(), 1);
    std::mutex m;
    std::set<std::thread::id> threads;
    parallel_chunks(10000, 1, [&](std::size_t, std::size_t) {
      std::lock_guard lock(m);
      threads.insert(std::this_thread::get_id());
    });
    EXPECT_EQ(threads.size(), 1u);
  }
  EXPECT_EQ(thread_count(), all);
  EXPECT_THROW(ThreadLimit(0), InvalidInput);
}

TEST(ThreadsFromEnvironment, ReadsAPositiveIntegerOrNothing) {
  const char* saved = std::getenv("SCULPT_THREADS");
  const std::string keep = saved ? saved : "";
  unsetenv("SCULPT_THREADS");
  EXPECT_EQ(threads_from_environment(), std::nullopt);
  setenv("SCULPT_THREADS", "3", 1);
  EXPECT_EQ(threads_from_environment(), 3);
  for (const char* bad : {"0", "-2", "two", "3x", "99999"}) {
    setenv("SCULPT_THREADS", bad, 1);
    EXPECT_THROW((void)threads_from_environment(), InvalidInput) << bad;
  }
  if (saved)
    setenv("SCULPT_THREADS", keep.c_str(), 1);
  else
    unsetenv("SCULPT_THREADS");
}

}  // namespace
}  // namespace sculpt
