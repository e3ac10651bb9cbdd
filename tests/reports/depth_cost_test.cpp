#include "reports/depth_cost.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <map>

#include "base/errors.hpp"
#include "bsp/boundary.hpp"
#include "bsp/cells.hpp"
#include "bsp/primitives.hpp"
#include "revolution/revolve.hpp"
#include "bsp/set_operations.hpp"
#include "curves/profiles.hpp"
#include "reports/cell_clipper.hpp"
#include "reports/query_cost.hpp"

using namespace sculpt;
using namespace sculpt::revolution;
using namespace sculpt::reports;

namespace {

Solid goblet_outer() {
  const auto c = curves::sample_profile(curves::goblet_profile(), {.points = 21, .noise = 0.004, .seed = 1990});
  return revolve(curves::planar_points(c.points), circular_path(32));
}

Solid goblet_after_set_operations() {
  auto profile = [](const curves::ProfileDesign& d, int points) {
    return curves::planar_points(curves::sample_profile(d, {.points = points, .noise = 0.004, .seed = 1990}).points);
  };
  const ConvexPath path = circular_path(32);
  return (goblet_outer() - revolve(profile(curves::goblet_cavity_profile(), 13), path)) |
         revolve(profile(curves::ball_profile(1.5, 6.8), 17), path);
}

}  // namespace

// A cylinder over a diamond, worked by hand: the tree is z = 0 (below: out), z = 1 (above: out), then
// the four face planes NE, NW, SW, SE (section 6: every quadrant sub-curve is a single edge). In the
// bounding box [-1, 1]^2 x [0, 1] (V = 4) the four corners (volume 1/2 each) are out-cells at depths
// 3, 4, 5, 6 and the diamond (volume 2) is the in-cell at depth 6:
// expected depth = 0.125 (3 + 4 + 5 + 6) + 0.5 * 6 = 5.25, entropy = 4 * 0.125 * 3 + 0.5 * 1 = 2.
TEST(DepthCost, DiamondCylinderByHand) {
  const Solid s = revolve({{1, 0}, {1, 1}}, polygon_path({{1, 0}, {0, 1}, {-1, 0}, {0, -1}}));
  const DepthCost c = depth_cost(s);
  EXPECT_NEAR(c.sample_volume, 4.0, 1e-12);
  EXPECT_EQ(c.cells_in_box, 5);
  EXPECT_NEAR(c.expected_depth, 5.25, 1e-12);
  EXPECT_NEAR(c.entropy_bound, 2.0, 1e-12);
  EXPECT_NEAR(c.ratio, 2.625, 1e-12);
  EXPECT_NEAR(c.in_volume, 2.0, 1e-12);
  EXPECT_EQ(c.nodes, 6);
  EXPECT_EQ(c.height, 6);
  ASSERT_EQ(c.histogram.size(), 4u);
  EXPECT_EQ(c.histogram.back().depth, 6);
  EXPECT_EQ(c.histogram.back().in_cells, 1);
  EXPECT_NEAR(c.histogram.back().out_probability, 0.125, 1e-12);
}

TEST(DepthCost, CellVolumesSumToTheSampleSpaceAndMatchAnIndependentClipper) {
  for (const Solid& s : {goblet_outer(), goblet_after_set_operations(), sphere(1.0, {.segments = 24})}) {
    const DepthCost c = depth_cost(s);
    EXPECT_NEAR(c.cell_volume_sum, c.sample_volume, 1e-9 * c.sample_volume);
    EXPECT_NEAR(c.in_volume, volume(s), 1e-9 * volume(s));
    // The volume inside agrees with the boundary's (divergence theorem), an independent computation.
    // Same cells, volumes and depths from the floating-point clipper, which shares nothing with
    // bsp/cells.hpp but the tree.
    std::map<std::pair<int, bool>, double> exact, clipped;
    for (const LeafCell& cell : leaf_cells(s, c.sample_box)) exact[{cell.depth, cell.inside}] += cell.volume;
    double expected = 0;
    for (const auto& cell : clipped_cells(s, c.sample_box)) {
      clipped[{cell.depth, cell.inside}] += cell.volume;
      expected += cell.volume / c.sample_volume * cell.depth;
    }
    for (const auto& [key, v] : clipped) EXPECT_NEAR(exact[key], v, 1e-8 * c.sample_volume) << key.first;
    EXPECT_NEAR(c.expected_depth, expected, 1e-8);
    // Shannon: no binary tree beats the entropy of its leaf distribution.
    EXPECT_GE(c.expected_depth, c.entropy_bound);
  }
}

TEST(DepthCost, PointSamplingAgreesWithTheExactExpectedDepth) {
  for (const Solid& s : {goblet_outer(), goblet_after_set_operations()}) {
    const DepthCost c = depth_cost(s);
    for (std::uint64_t seed : {1u, 2u, 3u}) {
      // 99.9% interval so that the three fixed seeds do not fail by chance (about 1 in 300).
      const QueryCost q = query_cost(s, {.shape = QueryShape::Point, .samples = 200000, .seed = seed, .confidence = 0.999});
      EXPECT_LE(q.ci_low, c.expected_depth) << "seed " << seed;
      EXPECT_GE(q.ci_high, c.expected_depth) << "seed " << seed;
      EXPECT_LT(q.ci_high - q.ci_low, 0.1);
    }
  }
}

TEST(DepthCost, GivenSampleBoxAndErrors) {
  const Solid s = goblet_outer();
  const Eigen::AlignedBox3d big(Eigen::Vector3d(-10, -10, -5), Eigen::Vector3d(10, 10, 15));
  const DepthCost c = depth_cost(s, {.sample_box = big});
  EXPECT_NEAR(c.sample_volume, 20 * 20 * 20, 1e-9);
  EXPECT_NEAR(c.cell_volume_sum, c.sample_volume, 1e-9 * c.sample_volume);
  EXPECT_NEAR(c.in_volume, volume(s), 1e-9 * volume(s));
  // More empty space around the solid: big out-cells near the root, a cheaper average point.
  EXPECT_LT(c.expected_depth, depth_cost(s).expected_depth);
  EXPECT_THROW(depth_cost(Solid()), InvalidInput);
  EXPECT_THROW(depth_cost(s, {.sample_box = Eigen::AlignedBox3d(Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1, 1, 0))}),
               InvalidInput);
  EXPECT_NO_THROW(depth_cost(Solid(), {.sample_box = big}));
}
