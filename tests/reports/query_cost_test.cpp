#include "reports/query_cost.hpp"

#include <gtest/gtest.h>

#include "base/errors.hpp"
#include "revolution/revolve.hpp"
#include "curves/profiles.hpp"
#include "reports/depth_cost.hpp"
#include "bsp/classify.hpp"

#include <random>

using namespace sculpt;
using namespace sculpt::revolution;
using namespace sculpt::reports;

namespace {
Solid goblet() {
  const auto c = curves::sample_profile(curves::goblet_profile(), {.points = 21, .noise = 0.004, .seed = 1990});
  return revolve(curves::planar_points(c.points), circular_path(32));
}
}  // namespace

TEST(QueryCost, TinyBoxesCostWhatPointsCost) {
  const Solid s = goblet();
  // Same seed, same centres: a box of edge 1e-12 takes the same paths as its centre point.
  const QueryCost p = query_cost(s, {.shape = QueryShape::Point, .samples = 20000, .seed = 4});
  const QueryCost b = query_cost(s, {.shape = QueryShape::Box, .size = 1e-12, .samples = 20000, .seed = 4});
  EXPECT_DOUBLE_EQ(p.mean_nodes, b.mean_nodes);
  EXPECT_DOUBLE_EQ(b.mean_leaves, 1.0);
}

TEST(QueryCost, LargerQueriesVisitMoreNodes) {
  const Solid s = goblet();
  double last = query_cost(s, {.shape = QueryShape::Point, .samples = 5000}).mean_nodes;
  for (double size : {0.1, 0.5, 2.0, 8.0}) {
    const QueryCost seg = query_cost(s, {.shape = QueryShape::Segment, .size = size, .samples = 5000});
    const QueryCost box = query_cost(s, {.shape = QueryShape::Box, .size = size, .samples = 5000});
    EXPECT_GT(seg.mean_nodes, last);
    EXPECT_GT(box.mean_nodes, seg.mean_nodes);  // a cube of edge L contains segments of length L
    EXPECT_LE(box.mean_nodes, tree_stats(s).nodes);
    EXPECT_LT(seg.ci_low, seg.mean_nodes);
    EXPECT_GT(seg.ci_high, seg.mean_nodes);
    last = seg.mean_nodes;
  }
  // A cube larger than the whole sample box meets every cell: the whole tree is visited.
  const QueryCost all = query_cost(s, {.shape = QueryShape::Box, .size = 100, .samples = 10});
  EXPECT_DOUBLE_EQ(all.mean_nodes, tree_stats(s).nodes);
  EXPECT_DOUBLE_EQ(all.std_dev, 0.0);
}

TEST(QueryCost, RejectsBadOptions) {
  const Solid s = goblet();
  EXPECT_THROW(query_cost(s, {.samples = 1}), InvalidInput);
  EXPECT_THROW(query_cost(s, {.confidence = 1.0}), InvalidInput);
  EXPECT_THROW(query_cost(s, {.size = -1}), InvalidInput);
  EXPECT_THROW(query_cost(Solid()), InvalidInput);
}
