// The set operations computed cell by cell (bsp/local/cell_merge.hpp) against the classic merge
// of whole trees: the same point set (exact classification of many points, volume, area), a
// closed oriented boundary, and a tree built from that boundary that gives the boundary back.
// Degenerate contacts (shared faces, edges, corners, coplanar faces of both orientations,
// identical operands) and deep subdivisions (tiny leaves) are the point.
#include <gtest/gtest.h>

#include <random>

#include "bsp/boundary.hpp"
#include "bsp/classify.hpp"
#include "bsp/from_mesh.hpp"
#include "bsp/local/cell_merge.hpp"
#include "bsp/primitives.hpp"
#include "bsp/set_operations.hpp"
#include "bsp/transform.hpp"
#include "bsp/tree/solid_access.hpp"
#include "support/bench_solids.hpp"
#include "support/mesh_checks.hpp"
#include "support/solid_checks.hpp"

namespace sculpt {
namespace {

using checks::cube;
using checks::vol;
using checks::without_boundary;

constexpr bool kUnion[2][2] = {{false, true}, {true, true}};
constexpr bool kIntersection[2][2] = {{false, false}, {false, true}};
constexpr bool kDifference[2][2] = {{false, false}, {true, false}};
constexpr bool kReversed[2][2] = {{false, true}, {false, false}};  // b - a
const bool (*const kOps[])[2] = {kUnion, kIntersection, kDifference, kReversed};

// The classic result, whatever the threshold: the path by whole trees.
Solid classic(const Solid& a, const Solid& b, const bool op[2][2]) {
  const bsp::detail::ScopedCellMergeThreshold classic(bsp::detail::kClassicMergeOnly);
  return op == kUnion ? (a | b) : op == kIntersection ? (a & b) : op == kDifference ? (a - b) : (b - a);
}

::testing::AssertionResult SameSolid(const Solid& a, const Solid& b, const bool op[2][2], std::size_t leaf_size) {
  const std::optional<Solid> got = bsp::detail::merge_by_cells(a, b, op, {.cells = {.leaf_size = leaf_size}});
  if (!got) return ::testing::AssertionFailure() << "the cell path refused the operands";
  const Solid want = classic(a, b, op);
  // The boundary it carries, before any tree is built.
  const PolygonMesh carried = to_mesh(*got, {.clean = false}), expected = to_mesh(want, {.clean = false});
  if (auto r = checks::EdgesManifoldAndOriented(carried); !r) return r << " (cells)";
  const double vg = vol(carried), ve = vol(expected);
  if (std::fabs(vg - ve) > 1e-9 * std::max(1.0, std::fabs(ve)))
    return ::testing::AssertionFailure() << "volume " << vg << " by cells vs " << ve << " classic";
  const double ag = surface_area(*got), ae = surface_area(want);
  if (std::fabs(ag - ae) > 1e-9 * std::max(1.0, ae))
    return ::testing::AssertionFailure() << "area " << ag << " by cells vs " << ae << " classic";
  // Points: exact classification against the tree built from the carried boundary.
  std::mt19937 rng(7);
  const Eigen::AlignedBox3d box =
      bounding_box(want).isEmpty() ? bounding_box(a).merged(bounding_box(b)) : bounding_box(want);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const Eigen::Vector3d lo = box.min() - 0.1 * box.sizes(), size = 1.2 * box.sizes();
  for (int i = 0; i < 400; ++i) {
    const Eigen::Vector3d p = lo + Eigen::Vector3d(u(rng), u(rng), u(rng)).cwiseProduct(size);
    const Location lg = classify(*got, p).location, le = classify(want, p).location;
    if (lg != le) return ::testing::AssertionFailure() << "point " << p.transpose() << " classified differently";
  }
  // The built tree's own boundary is the carried one.
  const PolygonMesh extracted = to_mesh(without_boundary(*got), {.clean = false});
  if (std::fabs(vol(extracted) - vg) > 1e-9 * std::max(1.0, std::fabs(vg)))
    return ::testing::AssertionFailure() << "the tree built from the boundary has volume " << vol(extracted);
  return ::testing::AssertionSuccess();
}

void check_all_ops(const Solid& a, const Solid& b) {
  for (const std::size_t leaf : {std::size_t(2), std::size_t(8), std::size_t(64)})
    for (int k = 0; k < 4; ++k) EXPECT_TRUE(SameSolid(a, b, kOps[k], leaf)) << "op " << k << ", leaf size " << leaf;
}

TEST(CellMerge, OverlappingCubes) { check_all_ops(cube(0, 0, 0, 2), cube(1, 1, 1, 2)); }

TEST(CellMerge, TouchingAndSharedFaces) {
  const Solid a = cube(0, 0, 0, 1);
  check_all_ops(a, cube(1, 0, 0, 1));                       // a shared face
  check_all_ops(a, cube(1, 1, 0, 1));                       // a shared edge
  check_all_ops(a, cube(1, 1, 1, 1));                       // a shared corner
  check_all_ops(a, box({0, 0, 1}, {1, 2, 2}));              // coplanar faces of both orientations
  check_all_ops(a, box({0.25, 0.25, 0}, {0.75, 0.75, 1}));  // inside, flush top and bottom
}

TEST(CellMerge, IdenticalContainedAndDisjoint) {
  const Solid a = cube(0, 0, 0, 2);
  check_all_ops(a, a);
  check_all_ops(a, cube(0.5, 0.5, 0.5, 1));
  check_all_ops(a, cube(5, 5, 5, 1));
  check_all_ops(cube(0.5, 0.5, 0.5, 1), a);
}

TEST(CellMerge, CurvedSolidsWithManyCells) {
  const Solid s = sphere(1.0, {.segments = 24});
  check_all_ops(s, translate(s, {0.3, 0.2, 0.1}));
  check_all_ops(s, cylinder(0.5, 3.0, {.segments = 16, .center = true}));
  check_all_ops(rotate(cube(-0.6, -0.6, -0.6, 1.2), {1, 1, 0}, 33), s);
}

// Leaves holding one operand's pieces only, 64 or more of them: their trees, read for statuses
// only, take the balancing auxiliary planes (cell_merge.cpp, build_status_trees): the 96-segment
// spheres' caps far from the other sphere, at the default leaf size.
TEST(CellMerge, LargeLeavesOfOneOperandGiveTheirStatusesByBalancedTrees) {
  const Solid s = sphere(1.0, {.segments = 96});
  const Solid moved = translate(s, {0.3, 0.2, 0.1});
  for (int k = 0; k < 4; ++k)
    EXPECT_TRUE(SameSolid(s, moved, kOps[k], bsp::detail::KdOptions{}.leaf_size)) << "op " << k;
}

TEST(CellMerge, AnUnboundedOperand) {
  const Solid a = cube(0, 0, 0, 2);
  check_all_ops(a, complement(cube(1, 1, 1, 2)));
  check_all_ops(complement(cube(1, 1, 1, 2)), a);
}

TEST(CellMerge, ResultsFeedTheNextOperation) {
  // Results of the cell path carry only their boundary; the next operation reads it.
  const Solid s = sphere(1.0, {.segments = 16});
  const std::optional<Solid> u =
      bsp::detail::merge_by_cells(s, translate(s, {0.5, 0, 0}), kUnion, {.cells = {.leaf_size = 8}});
  ASSERT_TRUE(u);
  EXPECT_TRUE(u->tree_deferred());
  const std::optional<Solid> v = bsp::detail::merge_by_cells(*u, cube(0, -0.5, -0.5, 1), kDifference);
  ASSERT_TRUE(v);
  EXPECT_TRUE(u->tree_deferred());  // the operation read its boundary only
  EXPECT_TRUE(v->tree_deferred());
  check_all_ops(*u, cube(0, -0.5, -0.5, 1));  // (the classic merge builds u's tree)
}

TEST(CellMerge, TheSetOperationsTakeThePathAboveTheThreshold) {
  const Solid a = cube(0, 0, 0, 2), b = cube(1, 1, 1, 2);
  const Solid u = [&] {
    const bsp::detail::ScopedCellMergeThreshold always(0);
    return a | b;
  }();
  EXPECT_TRUE(u.tree_deferred());
  EXPECT_NEAR(vol(to_mesh(u, {.clean = false})), 15.0, 1e-12);
  EXPECT_NEAR(surface_area(u), 42.0, 1e-12);
}

// The real-mesh job (issue 33): an import, a general turn, their union and a difference with a
// ball read boundaries only: no whole tree is built on the way, and the result is the classic one.
TEST(CellMerge, ImportTurnUnionAndDifferenceBuildNoTree) {
  const PolygonMesh mesh = to_mesh(sphere(1.0, {.segments = 48}));
  const Solid m = from_mesh(mesh, {.snapped_mesh_is_clean = true});
  EXPECT_TRUE(m.tree_deferred());
  const Solid r = rotate(m, {1, 1, 0}, 33);
  EXPECT_TRUE(r.tree_deferred());
  const Solid u = m | r;  // about 8000 fragments: the cell path
  const Solid d = u - translate(sphere(0.5, {.segments = 32}), {0.7, 0.7, 0.7});
  EXPECT_TRUE(m.tree_deferred());
  EXPECT_TRUE(r.tree_deferred());
  EXPECT_TRUE(u.tree_deferred());
  EXPECT_TRUE(d.tree_deferred());
  const double got = vol(to_mesh(d, {.clean = false}));
  EXPECT_TRUE(d.tree_deferred());  // output reads the boundary alone
  const Solid want =
      classic(classic(m, r, kUnion), translate(sphere(0.5, {.segments = 32}), {0.7, 0.7, 0.7}), kDifference);
  EXPECT_NEAR(got, vol(to_mesh(want, {.clean = false})), 1e-9);
  EXPECT_TRUE(((d - want) | (want - d)).is_empty());
}

// A Menger sponge made by cells (faces with holes, walls everywhere): exact volume, and its mesh
// reads back (the walls leave no seams where nothing changes, and no slivers next to edges).
TEST(CellMerge, ASpongeByCellsReadsBack) {
  const Solid s = [] {
    const bsp::detail::ScopedCellMergeThreshold always(0);
    return checks::menger_sponge(2);
  }();
  const PolygonMesh m = to_mesh(s);
  EXPECT_TRUE(checks::EdgesManifoldAndOriented(m));
  EXPECT_NEAR(vol(m), 400.0, 1e-9);
  const Solid back = from_mesh(m);
  EXPECT_NEAR(volume(back), 400.0, 1e-9);
  EXPECT_TRUE((back - checks::menger_sponge(2)).is_empty());
}

}  // namespace
}  // namespace sculpt
