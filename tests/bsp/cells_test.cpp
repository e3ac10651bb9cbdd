#include "bsp/cells.hpp"

#include <gtest/gtest.h>

#include "bsp/boundary.hpp"
#include "bsp/classify.hpp"
#include "bsp/primitives.hpp"
#include "bsp/set_operations.hpp"

namespace sculpt {
namespace {

TEST(LeafCells, VolumesAddUpToTheBoxAndInsideCellsToTheSolid) {
  const Solid s = sphere(1.0, {.segments = 16}) - box({0, 0, 0}, {1, 1, 1});
  const Eigen::AlignedBox3d window(Eigen::Vector3d(-2, -2, -2), Eigen::Vector3d(2, 2, 2));
  const std::vector<LeafCell> cells = leaf_cells(s, window);
  double total = 0, inside = 0;
  const TreeStats st = tree_stats(s);
  for (const LeafCell& c : cells) {
    EXPECT_GT(c.volume, 0);
    EXPECT_GE(c.depth, 1);
    EXPECT_LE(c.depth, st.height);
    total += c.volume;
    if (c.inside) inside += c.volume;
    // The centroid of a cell classifies like the cell (the cell is convex).
    Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
    for (const auto& v : c.vertices) centroid += v;
    centroid /= double(c.vertices.size());
    const Location l = classify(s, centroid).location;
    if (l != Location::Boundary) {
      EXPECT_EQ(l == Location::Inside, c.inside);
    }
  }
  EXPECT_NEAR(total, 64.0, 1e-9);
  EXPECT_NEAR(inside, volume(s), 1e-9);
  EXPECT_LE(int(cells.size()), st.in_leaves + st.out_leaves);
}

TEST(LeafCells, BoxCellsAreExactAndDepthCostIsTheirWeightedSum) {
  const Solid b = box({0, 0, 0}, {1, 1, 1});
  const std::vector<LeafCell> cells = leaf_cells(b, Eigen::AlignedBox3d(Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(2, 1, 1)));
  double inside = 0, total = 0;
  for (const auto& c : cells) {
    total += c.volume;
    if (c.inside) inside += c.volume;
  }
  EXPECT_DOUBLE_EQ(total, 2.0);
  EXPECT_DOUBLE_EQ(inside, 1.0);
}

}  // namespace
}  // namespace sculpt
