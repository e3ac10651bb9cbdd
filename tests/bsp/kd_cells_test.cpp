// The cell merge's kd subdivision (bsp/local/kd_cells.hpp) checked by brute force: each leaf holds
// exactly the fragments whose boxes meet its closed cell, the cells tile the root box, links and
// the leaf order are consistent; and the subdivision is the same on one thread and on every core
// (its large subtrees are grown side by side and appended).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "base/parallel.hpp"
#include "bsp/local/kd_cells.hpp"

namespace sculpt {
namespace {

using bsp::detail::CellBounds;
using bsp::detail::FragmentBox;
using bsp::detail::KdCells;

// An operand's boxes as a surface's fragments give them: small boxes on a sphere of radius 1000
// around `centre`, some long thin ones across many cells, and one invalid one (unknown: in
// every cell).
std::vector<FragmentBox> boxes(std::mt19937& rng, int n, double centre) {
  std::normal_distribution<double> dir;
  std::uniform_real_distribution<double> size(0, 12);
  std::vector<FragmentBox> out;
  for (int i = 0; i < n; ++i) {
    double d[3] = {dir(rng), dir(rng), dir(rng)};
    const double r = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]) + 1e-12;
    FragmentBox b{};
    for (int k = 0; k < 3; ++k) {
      const double lo = centre + 1000 * d[k] / r;
      b.lo[k] = float(lo);
      b.hi[k] = float(lo + (i % 997 == 0 ? 300 : size(rng)));
    }
    b.valid = i != 5;
    out.push_back(b);
  }
  return out;
}

// The closed cell [lo/2, hi/2] meets the box (an invalid box meets every cell).
bool meets(const CellBounds& c, const FragmentBox& b) {
  if (!b.valid) return true;
  for (int k = 0; k < 3; ++k)
    if (double(b.hi[k]) < 0.5 * double(c.lo[k]) || double(b.lo[k]) > 0.5 * double(c.hi[k])) return false;
  return true;
}

KdCells subdivided(const std::vector<FragmentBox> (&b)[2], std::size_t leaf_size) {
  return bsp::detail::subdivide({std::span<const FragmentBox>(b[0]), std::span<const FragmentBox>(b[1])},
                                {.leaf_size = leaf_size});
}

TEST(KdCells, LeavesHoldExactlyTheBoxesThatMeetThemAndTileTheRoot) {
  std::mt19937 rng(11);
  const std::vector<FragmentBox> b[2] = {boxes(rng, 12000, 0), boxes(rng, 9000, 300)};
  const KdCells cells = subdivided(b, 32);
  ASSERT_GT(cells.leaves.size(), 100u);
  // Links: every child's parent is its node, children split the parent's cell at its wall.
  for (std::size_t i = 0; i < cells.nodes.size(); ++i) {
    const auto& n = cells.nodes[i];
    if (n.axis < 0) continue;
    for (int side = 0; side < 2; ++side) {
      const auto& c = cells.nodes[std::size_t(n.child[side])];
      ASSERT_EQ(c.parent, std::int32_t(i));
      for (int k = 0; k < 3; ++k) {
        EXPECT_EQ(c.bounds.lo[k], k == n.axis && side == 1 ? n.split : n.bounds.lo[k]);
        EXPECT_EQ(c.bounds.hi[k], k == n.axis && side == 0 ? n.split : n.bounds.hi[k]);
      }
    }
  }
  // Leaves in depth-first order, below before above: the order of a walk with an explicit stack.
  std::vector<std::int32_t> walk, stack{0};
  while (!stack.empty()) {
    const std::int32_t id = stack.back();
    stack.pop_back();
    const auto& n = cells.nodes[std::size_t(id)];
    if (n.axis < 0) {
      walk.push_back(id);
      continue;
    }
    stack.push_back(n.child[1]);
    stack.push_back(n.child[0]);
  }
  EXPECT_EQ(walk, cells.leaves);
  // Brute force: a leaf lists (ascending) every box that meets its closed cell, and no other.
  for (const std::int32_t id : cells.leaves) {
    const auto& leaf = cells.nodes[std::size_t(id)];
    for (int op = 0; op < 2; ++op) {
      std::vector<std::uint32_t> expected;
      for (std::uint32_t i = 0; i < b[op].size(); ++i)
        if (meets(leaf.bounds, b[op][i])) expected.push_back(i);
      ASSERT_EQ(leaf.items[std::size_t(op)], expected) << "leaf " << id << " operand " << op;
    }
  }
}

TEST(KdCells, CellsOfOneOperandAreSplitOnlyAboveTheirOwnSize) {
  // Operand 0 on a sphere of radius 1000 around the origin, operand 1 on one around (3000, ...):
  // the boxes apart, so most cells hold one operand only. The invalid box meets every cell.
  std::mt19937 rng(5);
  std::vector<FragmentBox> b[2] = {boxes(rng, 6000, 0), boxes(rng, 300, 3000)};
  b[0][5].valid = b[1][5].valid = true;  // else every cell holds both operands
  auto one_operand_leaves = [&](std::size_t limit) {
    const KdCells cells =
        bsp::detail::subdivide({std::span<const FragmentBox>(b[0]), std::span<const FragmentBox>(b[1])},
                               {.leaf_size = 32, .one_operand_leaf_size = limit});
    std::size_t largest = 0, count = 0;
    for (const std::int32_t id : cells.leaves) {
      const auto& leaf = cells.nodes[std::size_t(id)];
      if (!leaf.items[0].empty() && !leaf.items[1].empty()) continue;
      largest = std::max(largest, leaf.items[0].size() + leaf.items[1].size());
      ++count;
    }
    return std::pair(largest, count);
  };
  const auto [whole, few] = one_operand_leaves(100000);
  EXPECT_GT(whole, 1000u) << "cells of one operand are not split down to leaf_size";
  const auto [limited, many] = one_operand_leaves(256);
  EXPECT_LE(limited, 256u);
  EXPECT_GT(many, few);
}

// A wall at a half-integer strictly inside the cell with every box of one operand strictly
// below it and every box of the other strictly above: the walls are tried upwards from just
// below the lower operand's top (beyond the first that clears it, later ones only come closer
// to the upper operand).
bool apart(const bsp::detail::KdNode& leaf, const std::vector<FragmentBox> (&b)[2]) {
  for (int k = 0; k < 3; ++k)
    for (int below = 0; below < 2; ++below) {
      double top = -1e300, bottom = 1e300;
      bool valid = true;
      for (const std::uint32_t i : leaf.items[std::size_t(below)])
        valid = valid && b[below][i].valid, top = std::max(top, double(b[below][i].hi[k]));
      for (const std::uint32_t i : leaf.items[std::size_t(1 - below)])
        valid = valid && b[1 - below][i].valid, bottom = std::min(bottom, double(b[1 - below][i].lo[k]));
      if (!valid) continue;
      const auto first = std::max(leaf.bounds.lo[k] + 2, 2 * std::int64_t(std::floor(top)) - 3);
      for (std::int64_t s = first | 1; s < leaf.bounds.hi[k] && s <= first + 8; s += 2)
        if (top < 0.5 * double(s) && 0.5 * double(s) < bottom) return true;
    }
  return false;
}

TEST(KdCells, NoLeafHoldsBothOperandsWhereAWallSeparatesThem) {
  // Three small boxes of each operand, apart along x only: one cell of 6 fragments would stay a
  // leaf, but the operands are apart in it, so it is split between them.
  std::vector<FragmentBox> b[2];
  for (int op = 0; op < 2; ++op)
    for (int i = 0; i < 3; ++i) {
      FragmentBox box{};
      box.lo[0] = float(op == 0 ? 0 : 10), box.hi[0] = box.lo[0] + 2;
      box.lo[1] = box.lo[2] = float(i), box.hi[1] = box.hi[2] = float(i + 5);
      box.valid = true;
      b[op].push_back(box);
    }
  KdCells cells = subdivided(b, 32);
  ASSERT_EQ(cells.leaves.size(), 2u);
  for (const std::int32_t id : cells.leaves) {
    const auto& leaf = cells.nodes[std::size_t(id)];
    EXPECT_TRUE(leaf.items[0].empty() != leaf.items[1].empty()) << "leaf " << id;
  }
  // Overlapping on every axis: one leaf with both.
  b[1][0].lo[0] = 1;
  cells = subdivided(b, 32);
  EXPECT_EQ(cells.leaves.size(), 1u);
  // The random surfaces: no leaf that holds both operands has them apart (brute force).
  std::mt19937 rng(17);
  std::vector<FragmentBox> r[2] = {boxes(rng, 3000, 0), boxes(rng, 2000, 300)};
  r[0][5].valid = r[1][5].valid = true;  // else every cell holds both operands' unknown box
  cells = subdivided(r, 32);
  std::size_t both = 0;
  for (const std::int32_t id : cells.leaves) {
    const auto& leaf = cells.nodes[std::size_t(id)];
    if (leaf.items[0].empty() || leaf.items[1].empty()) continue;
    ++both;
    EXPECT_FALSE(apart(leaf, r)) << "leaf " << id;
  }
  EXPECT_GT(both, 10u);
}

TEST(KdCells, CellsOfOneOperandNextToTheOtherAreSplitAboveTheNearLimit) {
  // Two overlapping surfaces: every leaf of one operand whose parent held both has at most
  // near_leaf_size fragments; with a near limit as large as the general one, some have more.
  std::mt19937 rng(23);
  std::vector<FragmentBox> b[2] = {boxes(rng, 20000, 0), boxes(rng, 20000, 300)};
  b[0][5].valid = b[1][5].valid = true;
  auto largest_near = [&](std::size_t near) {
    const KdCells cells =
        bsp::detail::subdivide({std::span<const FragmentBox>(b[0]), std::span<const FragmentBox>(b[1])},
                               {.leaf_size = 32, .one_operand_leaf_size = 4096, .near_leaf_size = near});
    std::size_t largest = 0;
    for (const std::int32_t id : cells.leaves) {
      const auto& leaf = cells.nodes[std::size_t(id)];
      if (!leaf.items[0].empty() && !leaf.items[1].empty()) continue;
      const auto& parent = cells.nodes[std::size_t(leaf.parent)];
      // Brute force: the parent held both operands if boxes of both meet its closed cell.
      bool held[2] = {false, false};
      for (int op = 0; op < 2; ++op)
        for (const FragmentBox& box : b[op]) held[op] = held[op] || meets(parent.bounds, box);
      EXPECT_EQ(leaf.parent_mixed, held[0] && held[1]) << "leaf " << id;
      if (leaf.parent_mixed) largest = std::max(largest, leaf.items[0].size() + leaf.items[1].size());
    }
    return largest;
  };
  EXPECT_LE(largest_near(128), 128u);
  EXPECT_GT(largest_near(4096), 128u);
}

TEST(KdCells, OneThreadAndEveryCoreGiveTheSameSubdivision) {
  std::mt19937 rng(3);
  // Large enough that the first splits leave subtrees of over 8192 fragments (grown side by side).
  const std::vector<FragmentBox> b[2] = {boxes(rng, 40000, 0), boxes(rng, 40000, 300)};
  for (const std::size_t leaf_size : {std::size_t(8), std::size_t(32)}) {
    KdCells one;
    {
      const ThreadLimit limit(1);
      one = subdivided(b, leaf_size);
    }
    const KdCells every = subdivided(b, leaf_size);
    ASSERT_EQ(one.nodes.size(), every.nodes.size());
    EXPECT_EQ(one.leaves, every.leaves);
    for (std::size_t i = 0; i < one.nodes.size(); ++i) {
      const auto &x = one.nodes[i], &y = every.nodes[i];
      ASSERT_EQ(x.axis, y.axis) << i;
      ASSERT_EQ(x.split, y.split) << i;
      ASSERT_EQ(x.child[0], y.child[0]) << i;
      ASSERT_EQ(x.child[1], y.child[1]) << i;
      ASSERT_EQ(x.parent, y.parent) << i;
      ASSERT_EQ(x.items, y.items) << i;
    }
  }
}

}  // namespace
}  // namespace sculpt
