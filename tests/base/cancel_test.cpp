// Cancellation (lib/base/cancel.hpp): a request makes the next check throw, polls check every
// kCancelStride ticks, shields hold a request back, and a Cancelled thrown in a parallel task
// reaches the caller.
#include "base/cancel.hpp"

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <cstddef>
#include <thread>
#include <utility>

#include "base/dispose.hpp"
#include "base/parallel.hpp"

namespace sculpt {
namespace {

// Clears the process-wide request before and after each test.
class Cancel : public ::testing::Test {
 protected:
  void SetUp() override { clear_cancel(); }
  void TearDown() override { clear_cancel(); }
};

TEST_F(Cancel, NoRequestNoThrow) {
  EXPECT_FALSE(cancel_requested());
  EXPECT_NO_THROW(check_cancel());
}

TEST_F(Cancel, RequestThrowsUntilCleared) {
  request_cancel();
  EXPECT_TRUE(cancel_requested());
  EXPECT_TRUE(cancel_request_flag()->load());
  EXPECT_THROW(check_cancel(), Cancelled);
  EXPECT_THROW(check_cancel(), Cancelled);  // the request stays until it is withdrawn
  clear_cancel();
  EXPECT_NO_THROW(check_cancel());
}

TEST_F(Cancel, PollChecksEveryStride) {
  request_cancel();
  CancelPoll poll;
  for (std::uint32_t i = 1; i < kCancelStride; ++i) ASSERT_NO_THROW(poll.tick());
  EXPECT_THROW(poll.tick(), Cancelled);
  CancelPoll counted;
  EXPECT_NO_THROW(counted.tick(kCancelStride - 1));
  EXPECT_THROW(counted.tick(1), Cancelled);
}

TEST_F(Cancel, ShieldHoldsTheRequestBack) {
  request_cancel();
  {
    const CancelShield shield;
    EXPECT_NO_THROW(check_cancel());
    {
      const CancelShield nested;
      EXPECT_NO_THROW(check_cancel());
    }
    EXPECT_NO_THROW(check_cancel());
  }
  EXPECT_THROW(check_cancel(), Cancelled);  // still pending once the shield is gone
}

TEST_F(Cancel, MessageSaysInterrupted) { EXPECT_STREQ(Cancelled().what(), "interrupted"); }

TEST_F(Cancel, ThrownInAParallelTaskReachesTheCaller) {
  std::atomic<std::size_t> done{0};
  request_cancel();
  EXPECT_THROW(parallel_chunks(1 << 16, 64,
                               [&](std::size_t begin, std::size_t end) {
                                 CancelPoll poll;
                                 for (std::size_t i = begin; i < end; ++i) poll.tick(kCancelStride);
                                 done += end - begin;
                               }),
               Cancelled);
  EXPECT_LT(done.load(), std::size_t(1) << 16);  // stopped early
  clear_cancel();
  EXPECT_NO_THROW(parallel_invoke([] { check_cancel(); }, [] { check_cancel(); }));
}

// dispose_in_background (base/dispose.hpp): the value is destroyed on another thread, once, and
// the caller does not wait for it.
TEST(DisposeInBackground, DestroysTheValueOnceOnAnotherThread) {
  struct Probe {
    std::atomic<int>* destroyed;
    std::atomic<bool>* other_thread;
    std::thread::id caller;
    Probe(std::atomic<int>* d, std::atomic<bool>* o)
        : destroyed(d), other_thread(o), caller(std::this_thread::get_id()) {}
    Probe(Probe&& p) noexcept
        : destroyed(std::exchange(p.destroyed, nullptr)), other_thread(p.other_thread), caller(p.caller) {}
    ~Probe() {
      if (destroyed == nullptr) return;  // moved from
      other_thread->store(std::this_thread::get_id() != caller);
      destroyed->fetch_add(1);
    }
  };
  std::atomic<int> destroyed{0};
  std::atomic<bool> other_thread{false};
  dispose_in_background(Probe(&destroyed, &other_thread));
  for (int i = 0; i < 500 && destroyed.load() == 0; ++i) std::this_thread::sleep_for(std::chrono::milliseconds(10));
  EXPECT_EQ(destroyed.load(), 1);
  EXPECT_TRUE(other_thread.load());
}

}  // namespace
}  // namespace sculpt
