// Ctrl-C in the set operations (base/cancel.hpp): a request made from another thread while a large
// operation runs stops it with Cancelled, and the operands are as they were; a large deferred tree
// whose build was stopped is still whole and builds later; a small one, and in-place work, which has
// taken its operand's storage, are shielded and finish.
#include <gtest/gtest.h>

#include <chrono>
#include <thread>

#include "base/cancel.hpp"
#include "bsp/boundary.hpp"
#include "bsp/classify.hpp"
#include "bsp/primitives.hpp"
#include "bsp/set_operations.hpp"
#include "bsp/transform.hpp"

namespace sculpt {
namespace {

class CancelSetOperations : public ::testing::Test {
 protected:
  void SetUp() override { clear_cancel(); }
  void TearDown() override { clear_cancel(); }
};

// Shape of a solid's tree and storage, to compare before and after.
struct Footprint {
  std::size_t nodes, planes, fragments;
  TreeStats stats;
  double volume;
};
Footprint footprint(const Solid& s) {
  return {s.nodes().size(), std::size_t(s.planes().size()), s.boundary().size(), tree_stats(s), volume(s)};
}
void expect_same(const Footprint& a, const Footprint& b) {
  EXPECT_EQ(a.nodes, b.nodes);
  EXPECT_EQ(a.planes, b.planes);
  EXPECT_EQ(a.fragments, b.fragments);
  EXPECT_EQ(a.stats.nodes, b.stats.nodes);
  EXPECT_EQ(a.stats.height, b.stats.height);
  EXPECT_EQ(a.volume, b.volume);
}

TEST_F(CancelSetOperations, RequestFromAnotherThreadStopsALargeUnion) {
  // Two 400-segment spheres: their union takes seconds (the boundary merge alone); the request
  // comes after 50 ms.
  const Solid a = sphere(1.0, {.segments = 400});
  const Solid b = translate(a, Eigen::Vector3d(0.5, 0, 0));
  const Footprint a_before = footprint(a), b_before = footprint(b);
  std::thread asker([] {
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
    request_cancel();
  });
  bool stopped = false;
  try {
    const Solid u = unite(a, b);
    (void)u.nodes();  // the deferred tree merge too
  } catch (const Cancelled&) {
    stopped = true;
  }
  asker.join();
  clear_cancel();
  EXPECT_TRUE(stopped);
  expect_same(footprint(a), a_before);
  expect_same(footprint(b), b_before);
}

TEST_F(CancelSetOperations, StoppedDeferredTreeIsWholeAndBuildsLater) {
  // 2 x 63,501 nodes: a merge large enough to run on a copy (DeferredMerge::build).
  const Solid a = sphere(1.0, {.segments = 256});
  const Solid b = translate(a, Eigen::Vector3d(0.5, 0.25, 0));
  const Solid u = subtract(a, b);
  ASSERT_TRUE(u.tree_deferred());
  const double boundary_volume = volume(u);  // from the carried boundary: no tree needed
  request_cancel();
  EXPECT_THROW((void)u.nodes(), Cancelled);
  EXPECT_TRUE(u.tree_deferred());  // still the operation's result, not half a tree
  clear_cancel();
  const Solid fresh = subtract(a, b);
  const TreeStats built = tree_stats(u), reference = tree_stats(fresh);
  EXPECT_FALSE(u.tree_deferred());
  EXPECT_EQ(built.nodes, reference.nodes);
  EXPECT_EQ(built.height, reference.height);
  EXPECT_EQ(volume(u), boundary_volume);
  EXPECT_EQ(classify(u, Eigen::Vector3d(-0.9, 0, 0)).location, Location::Inside);
  EXPECT_EQ(classify(u, Eigen::Vector3d(0.9, 0, 0)).location, Location::Outside);
}

TEST_F(CancelSetOperations, SmallDeferredTreeIsBuiltAndTheRequestStays) {
  const Solid a = sphere(1.0, {.segments = 48});
  const Solid u = subtract(a, translate(a, Eigen::Vector3d(0.5, 0.25, 0)));
  ASSERT_TRUE(u.tree_deferred());
  request_cancel();
  EXPECT_NO_THROW((void)u.nodes());  // well under a second: shielded, not copied
  EXPECT_FALSE(u.tree_deferred());
  EXPECT_TRUE(cancel_requested());
}

TEST_F(CancelSetOperations, InPlaceOperationIsShieldedAndTheRequestStays) {
  Solid work = sphere(1.0, {.segments = 128});
  (void)work.nodes();  // a built tree: the in-place merge, not the cell path (which takes nothing)
  const Solid tool = box(Eigen::Vector3d(0.5, -0.1, -0.1), Eigen::Vector3d(1.5, 0.1, 0.1));
  const double expected = volume(subtract(work, tool));
  request_cancel();
  Solid result;
  EXPECT_NO_THROW(result = subtract(std::move(work), tool));  // work's storage was taken: no stop halfway
  EXPECT_TRUE(cancel_requested());
  clear_cancel();
  EXPECT_NEAR(volume(result), expected, 1e-12);
}

// The cell path (bsp/local/cell_merge.hpp) stops between and inside its steps and leaves both
// operands as they were: a workpiece whose tree is deferred is only read.
TEST_F(CancelSetOperations, CellPathStopsAndLeavesTheOperands) {
  Solid work = sphere(1.0, {.segments = 128});
  ASSERT_TRUE(work.tree_deferred());
  const Solid tool = translate(work, Eigen::Vector3d(0.3, 0.2, 0.1));
  const double before = volume(work);
  request_cancel();
  EXPECT_THROW((void)subtract(std::move(work), tool), Cancelled);
  clear_cancel();
  EXPECT_EQ(volume(work), before);  // NOLINT(bugprone-use-after-move): not moved from, by contract
  EXPECT_NEAR(volume(subtract(std::move(work), tool)), volume(subtract(sphere(1.0, {.segments = 128}), tool)), 1e-12);
}

}  // namespace
}  // namespace sculpt
